"""Slider-to-picture latency in a real browser (JupyterLab + ipympl in headless Chromium).

For each notebook: open it in JupyterLab, Run All, take the first slider of the first interactive
panel and press a key on it ~20 times (PageUp/PageDown alternating in blocks, i.e. 5 slider steps
per press). The time of one move is measured inside the page, from the keydown event's timestamp
to the first animation frame in which the panel's ipympl canvas pixels differ from before the
press (getImageData, checked on every requestAnimationFrame). Between moves we wait until the
kernel is idle and the canvas has been still for 300 ms, so moves do not overlap.

The row "(minimal panel)" is a plain ipywidgets slider moving one Line2D on an ipympl canvas with
draw_idle (the browser tests' self-check notebook): the floor set by the browser -> kernel ->
ipympl PNG round trip; chapter panels add their own computation (and gm_core's blitting).

    .venv/bin/python benchmarks/browser_latency.py                    # the first two interactive chapters
    .venv/bin/python benchmarks/browser_latency.py book/01-*.ipynb --moves 30

Needs /usr/bin/chromium (Debian package); never run `playwright install`.
"""
from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "browser"))
import browserlab  # noqa: E402
import labview  # noqa: E402

_ARM_JS = r"""
(sel) => {
  const area = document.querySelector(sel);
  const canvases = [...area.querySelectorAll('.jupyter-matplotlib canvas, .jupyter-matplotlib-canvas-div canvas')];
  const grab = () => canvases.map(c => {
    if (!c.width || !c.height) return new Uint32Array(0);
    return new Uint32Array(c.getContext('2d').getImageData(0, 0, c.width, c.height).data.buffer);
  });
  const same = (a, b) => {
    for (let k = 0; k < a.length; k++) {
      const x = a[k], y = b[k];
      if (x.length !== y.length) return false;
      for (let i = 0; i < x.length; i++) if (x[i] !== y[i]) return false;
    }
    return true;
  };
  const state = {t0: null, latency: null, frames: 0};
  window.__gmLatency = state;
  const before = grab();
  const onKey = (e) => {
    document.removeEventListener('keydown', onKey, true);
    state.t0 = e.timeStamp;
    const tick = () => {
      if (window.__gmLatency !== state) return;  // disarmed
      state.frames++;
      if (!same(before, grab())) { state.latency = performance.now() - state.t0; return; }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  };
  document.addEventListener('keydown', onKey, true);
  return true;
}
"""


def measure(lab, relpath, moves=20, per_move_timeout=15.0):
    with browserlab.NotebookPage(lab, relpath) as nbp:
        nbp.open()
        nbp.run_all()
        nbp.check_no_errors()
        sel = nbp.find_panel(0)
        handle = nbp.page.locator(f"{sel} .widget-slider .noUi-handle").first
        label = nbp.page.locator(f"{sel} .widget-slider .widget-label").first
        name = label.inner_text().strip() if label.count() else ""
        above = nbp.page.locator(f"{sel} .gm-control-label").first   # a label laid out above its slider
        if not name and above.count():
            name = above.inner_text().strip()
        name = name or "?"
        handle.scroll_into_view_if_needed()
        info = nbp.slider_value(sel, 0)
        lo, hi, v = info["min"], info["max"], info["value"]
        up, down = "PageUp", "PageDown"
        first = up if v <= (lo + hi) / 2 else down
        second = down if first == up else up
        block = max(1, moves // 4)
        keys = ([first] * block + [second] * block) * (moves // (2 * block) + 1)
        keys = keys[:moves]
        handle.focus()
        nbp.wait_still(sel, still=0.3)
        lat, misses = [], 0
        for key in keys:
            nbp.page.evaluate(_ARM_JS, sel)
            v_before = nbp.slider_value(sel, 0)["value"]
            handle.press(key)
            if nbp.slider_value(sel, 0)["value"] == v_before:
                nbp.page.evaluate("window.__gmLatency = null")
                continue  # at the end of the range: no move, nothing to time
            try:
                nbp.page.wait_for_function("window.__gmLatency && window.__gmLatency.latency !== null",
                                           timeout=per_move_timeout * 1000, polling=50)
                lat.append(nbp.page.evaluate("window.__gmLatency.latency"))
            except Exception:
                misses += 1
            nbp.page.evaluate("window.__gmLatency = null")
            nbp.wait_still(sel, still=0.3)
        nbp.check_no_errors()
        return {"notebook": relpath, "slider": name, "lat": lat, "misses": misses}


def pct(xs, q):
    xs = sorted(xs)
    if not xs:
        return float("nan")
    k = (len(xs) - 1) * q
    i = int(k)
    j = min(i + 1, len(xs) - 1)
    return xs[i] + (xs[j] - xs[i]) * (k - i)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("notebooks", nargs="*", help="notebooks (default: the first two interactive chapters)")
    ap.add_argument("--moves", type=int, default=20)
    ap.add_argument("--no-baseline", action="store_true", help="skip the minimal-panel row")
    args = ap.parse_args(argv)
    if not browserlab.chromium_available():
        print(browserlab.CHROMIUM_MISSING)
        return 2
    from playwright.sync_api import sync_playwright

    if args.notebooks:
        nbs = [Path(p).resolve().relative_to(ROOT).as_posix() for p in args.notebooks]
    else:
        found = browserlab.interactive_notebooks()
        chapters = [p for p in found if not p.name.startswith("00")] or found
        nbs = [p.relative_to(ROOT).as_posix() for p in chapters[:2]]
    if not args.no_baseline:
        nbs = [browserlab.SELFCHECK_PATH] + nbs
    rows = []
    with tempfile.TemporaryDirectory(prefix="gm-latency-") as tmp:
        server = browserlab.LabServer(Path(tmp), extra_notebooks={browserlab.SELFCHECK_PATH: browserlab.selfcheck_notebook()})
        with server, sync_playwright() as pw:
            context = browserlab.launch_chromium(pw, Path(tmp) / "profile", viewport=labview.STUDENT_WINDOW)
            lab = browserlab.LabBrowser(context, server)
            try:
                for nb in nbs:
                    r = measure(lab, nb, moves=args.moves)
                    if nb == browserlab.SELFCHECK_PATH:
                        r["notebook"] = "(minimal panel)"
                    rows.append(r)
                    print(f"  measured {r['notebook']}: {len(r['lat'])} moves", file=sys.stderr)
            finally:
                lab.close()
                context.close()
    print(f"\nslider key press -> canvas pixels changed, headless Chromium + JupyterLab ({args.moves} moves each)\n")
    hdr = f"{'notebook':<38} {'slider':<14} {'n':>3} {'median ms':>10} {'p95 ms':>8} {'max ms':>8} {'missed':>6}"
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        lat = r["lat"]
        med = statistics.median(lat) if lat else float("nan")
        print(f"{r['notebook']:<38} {r['slider'][:14]:<14} {len(lat):>3} {med:>10.0f} {pct(lat, 0.95):>8.0f} "
              f"{(max(lat) if lat else float('nan')):>8.0f} {r['misses']:>6}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

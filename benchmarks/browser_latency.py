"""Slider-to-picture latency in a real browser (JupyterLab + ipympl in headless Chromium), per panel.

For each notebook: open it in JupyterLab (1366 x 768, file browser open, as a student's laptop),
Run All, and find every live panel: an output holding an ipympl canvas and an enabled slider
(tests/browser/student.py's panel finder, numbered #0, #1, ... in page order). For each panel,
take its first slider that changes the picture (up to three are tried) and press a key on it
``--moves`` times (PageUp/PageDown, i.e. 5 slider steps per press, direction reversed every
quarter of the moves and at either end of the range). The time of one move is measured inside
the page, from the keydown event's timestamp to the first animation frame in which the panel's
ipympl canvas pixels differ from before the press (getImageData, checked on every
requestAnimationFrame). Between moves we wait until the kernel is idle and the canvas has been
still for 0.3 s (1 s if its last picture was a difference image, not a whole one), so moves do
not overlap. A notebook without a live panel gets a row saying so; a notebook that fails gets a
row with the error, and the run goes on.

The row "(minimal panel)" is a plain ipywidgets slider moving one Line2D on an ipympl canvas with
draw_idle (the browser tests' self-check notebook): the floor set by the browser -> kernel ->
ipympl PNG round trip. It is measured in the same run, before every notebook and once more at the
end (``--floor-moves`` moves each time), and its row pools all those moves, so that a machine whose
load drifts during the run weighs on the floor as it does on the panels (``--floor-once``: only
once, first, with ``--moves`` moves). "<=min" says whether a panel's median is at or
below it (issue 36, item 8). "pics" is the median number of pictures the canvas showed per move
(a blitting panel shows a difference image and, 0.25 s later, a whole key frame); "canvas" the
ipympl canvas size in pixels. Times depend on the machine's load: the heading prints it.

    .venv/bin/python benchmarks/browser_latency.py                      # every notebook of book/
    .venv/bin/python benchmarks/browser_latency.py 00 08 --moves 30     # book/00-*, book/08-*
    .venv/bin/python benchmarks/browser_latency.py book/11-many-links.ipynb --panels 0,2
    .venv/bin/python benchmarks/browser_latency.py 03 --json /tmp/lat.json   # raw numbers too

Needs /usr/bin/chromium (Debian package) and the playwright PyPI package; never run
`playwright install`. Reuses tests/browser/ (browserlab: the server on a temporary copy of the
course and the page; student: the panel finder and the picture watch). A benchmark, not a test.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "browser"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import browserlab  # noqa: E402
import labview  # noqa: E402
import latency_report as lr  # noqa: E402
import student  # noqa: E402

# Arm the measurement of one move: remember the area's canvas pixels, and on the next keydown
# look at them on every animation frame until they differ. ipympl paints a canvas only when a
# new picture has loaded (student.py's picture watch counts them), so while the count of the
# panel's pictures is unchanged the pixels are not read: reading a large canvas on every frame
# would take the page's time from the very drawing being timed (and more for larger canvases).
_ARM_JS = r"""
(sel) => {
  const area = document.querySelector(sel);
  const canvases = [...area.querySelectorAll('.jupyter-matplotlib canvas, .jupyter-matplotlib-canvas-div canvas')];
  const ids = [...area.querySelectorAll('[data-gm-pictures]')].map(v => v.getAttribute('data-gm-pictures'));
  const watched = ids.length > 0 && window.__gmPictures && ids.every(id => window.__gmPictures[id]);
  const shown = () => watched ? ids.reduce((n, id) => n + window.__gmPictures[id].shown, 0) : null;
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
  const state = {t0: null, latency: null, frames: 0, grabs: 0, watched};
  window.__gmLatency = state;
  const before = grab(), shown0 = shown();
  const onKey = (e) => {
    document.removeEventListener('keydown', onKey, true);
    state.t0 = e.timeStamp;
    const tick = () => {
      if (window.__gmLatency !== state) return;  // disarmed
      state.frames++;
      if (!watched || shown() !== shown0) {
        state.grabs++;
        if (!same(before, grab())) { state.latency = performance.now() - state.t0; return; }
      }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  };
  document.addEventListener('keydown', onKey, true);
  return true;
}
"""

# One panel's sliders (label, enabled, range, value) and figures (canvas size), in page order.
_PANEL_FACTS_JS = r"""
(sel) => {
  const area = document.querySelector(sel);
  if (!area) return {sliders: [], canvases: []};
  const num = (x) => { const v = Number(Array.isArray(x) ? x[0] : x); return Number.isFinite(v) ? v : null; };
  const sliders = [...area.querySelectorAll('.widget-slider')].map(s => {
    const t = s.querySelector('.noUi-target'), h = s.querySelector('.noUi-handle');
    // textContent, not innerText: a cell JupyterLab has not laid out (off screen) has no innerText
    const text = (e) => (e && e.textContent || '').trim();
    const lab = s.querySelector('.widget-label');
    const above = s.parentElement && s.parentElement.querySelector(':scope > .gm-control-label-box .gm-control-label');
    const tip = lab && lab.getAttribute('title');   // a label shown above the slider is its tooltip too
    const label = text(lab) || text(above) || (tip && tip !== 'null' ? tip : '');
    const disabled = !t || !h || t.hasAttribute('disabled') || t.classList.contains('noUi-state-disabled') || !!h.closest('[disabled]');
    const r = t && t.noUiSlider ? t.noUiSlider.options.range : {};
    return {label, disabled, min: num(r.min), max: num(r.max),
            value: t && t.noUiSlider ? num(t.noUiSlider.get()) : null};
  });
  const canvases = [...area.querySelectorAll('.jupyter-matplotlib')].map(f => {
    const c = f.querySelector('canvas');
    return c ? [c.width, c.height] : [0, 0];
  });
  return {sliders, canvases};
}
"""

STILL = 0.3            # s the canvas must stay unchanged (kernel idle) between moves ...
STILL_ON_A_DIFFERENCE = 1.0   # ... and when its last picture was a difference image


def _state(nbp, k):
    return nbp.page.evaluate(student._STATE_JS, [k])[str(k)]


def quiet(nbp, k, timeout=20.0):
    """Wait until panel ``k``'s canvas has not changed for STILL s (STILL_ON_A_DIFFERENCE if its
    last picture was a difference: a blitting panel's whole key frame is on its way) and the
    kernel is idle. Reads student.py's cheap per-panel state (a pixel hash reused while no new
    picture arrived, the number of pictures shown). Raises browserlab.CanvasBusy."""
    last = _state(nbp, k)
    since = time.monotonic()
    deadline = since + timeout
    while time.monotonic() < deadline:
        nbp.page.wait_for_timeout(50)
        now = _state(nbp, k)
        if now != last:
            last, since = now, time.monotonic()
            continue
        need = STILL if (now or {}).get("whole") is not False else STILL_ON_A_DIFFERENCE
        if time.monotonic() - since >= need and nbp.read_status().get("kernel") == "idle":
            return now
    raise browserlab.CanvasBusy(f"panel #{k}: the canvas kept changing (or the kernel stayed busy) for {timeout:.0f} s")


def discover(nbp, stable=1.0, timeout=20.0) -> list[dict]:
    """The notebook's live panels (student.py's finder tags each output area data-gm-drag=k), once
    their number has not changed for ``stable`` s (widget views appear after Run All ends), with
    the pictures of their canvases watched."""
    panel_id = nbp.read_status()["panelId"]
    last, since = None, time.monotonic()
    deadline = since + timeout
    while True:
        panels = nbp.page.evaluate(student._PANELS_JS, panel_id)
        if last is None or len(panels) != len(last):
            last, since = panels, time.monotonic()
        elif time.monotonic() - since >= stable or time.monotonic() > deadline:
            break
        nbp.page.wait_for_timeout(250)
    if panels:
        missing = nbp.page.evaluate(student._WATCH_PICTURES_JS)
        if missing:
            print(f"  {nbp.relpath}: pictures not watched ({missing}); 'pics' stays empty", file=sys.stderr)
    return panels


class _Stuck(Exception):
    """The key press did not move the slider (at the end of its range)."""


def one_move(nbp, sel, k, handle, index, key, timeout):
    """Press ``key`` on the slider; (latency in ms or None if the canvas did not change within
    ``timeout`` s, pictures shown). Waits for the panel to be quiet again afterwards."""
    page = nbp.page
    shown0 = (_state(nbp, k) or {}).get("shown")
    page.evaluate(_ARM_JS, sel)
    v0 = nbp.slider_value(sel, index).get("value")
    handle.press(key)
    if nbp.slider_value(sel, index).get("value") == v0:
        page.evaluate("window.__gmLatency = null")
        raise _Stuck
    lat = None
    try:
        page.wait_for_function("window.__gmLatency && window.__gmLatency.latency !== null",
                               timeout=timeout * 1000, polling=50)
        lat = page.evaluate("window.__gmLatency.latency")
    except Exception as e:  # playwright's TimeoutError: the picture never changed
        if "Timeout" not in type(e).__name__:
            raise
    page.evaluate("window.__gmLatency = null")
    shown1 = (quiet(nbp, k) or {}).get("shown")
    pics = shown1 - shown0 if isinstance(shown0, int) and isinstance(shown1, int) else None
    return lat, pics


def measure_panel(nbp, panel, moves, timeout=15.0, probe_timeout=8.0) -> lr.Row:
    k = panel["index"]
    sel = f'[data-gm-drag="{k}"]'
    facts = nbp.page.evaluate(_PANEL_FACTS_JS, sel)
    canvas = ",".join(f"{w}x{h}" for w, h in facts["canvases"])
    row = lr.Row(nbp.relpath, panel=k, cell=panel.get("cell"), canvas=canvas)
    order = lr.slider_order(facts["sliders"])
    if not order:
        row.note = "no enabled slider with a range"
        return row
    try:
        quiet(nbp, k, timeout=30.0)
    except browserlab.CanvasBusy as e:
        row.note = str(e)
        return row

    def key(direction):
        return "PageUp" if direction > 0 else "PageDown"

    try:
        chosen, tried = None, []
        for index in order:  # the first slider that changes the picture is measured
            s = facts["sliders"][index]
            handle = nbp.page.locator(f"{sel} .widget-slider").nth(index).locator(".noUi-handle").first
            handle.scroll_into_view_if_needed()
            direction = 1 if s["value"] is None or s["value"] <= (s["min"] + s["max"]) / 2 else -1
            tried.append(s["label"] or f"slider {index}")
            lat = None
            for _turn in range(2):  # this move is the warm-up: not counted
                try:
                    lat, _ = one_move(nbp, sel, k, handle, index, key(direction), probe_timeout)
                    break
                except _Stuck:
                    direction = -direction
            if lat is not None:
                chosen = index
                break
        if chosen is None:
            row.note = "no slider changed the picture: tried " + ", ".join(tried)
            return row
        row.slider = facts["sliders"][chosen]["label"] or f"slider {chosen}"
        block = max(1, moves // 4)
        for m in range(moves):
            if m and m % block == 0:
                direction = -direction
            for _turn in range(2):  # at an end of the range: turn round
                try:
                    lat, pics = one_move(nbp, sel, k, handle, chosen, key(direction), timeout)
                    break
                except _Stuck:
                    direction = -direction
            else:
                row.note = "the slider stopped moving"
                break
            if lat is None:
                row.misses += 1
            else:
                row.lat.append(round(lat, 1))
            if pics is not None:
                row.pictures.append(pics)
    except browserlab.CanvasBusy as e:
        row.note = str(e)
    if row.misses:
        row.note = (row.note + "; " if row.note else "") + f"{row.misses} move(s) not drawn within {timeout:.0f} s"
    return row


def measure_notebook(lab, relpath, rows, wanted=None, moves=20, timeout=15.0, name=None):
    """Append a row per measured panel of ``relpath`` to ``rows`` (rows of panels measured before
    a failure are kept); a notebook without a live panel gets one row saying so."""
    first = len(rows)
    with browserlab.NotebookPage(lab, relpath) as nbp:
        nbp.open()
        nbp.run_all()
        nbp.check_no_errors()
        student.wait_for_pictures(nbp)
        found = discover(nbp)
        panels = lr.live_panels(found, wanted)
        if not found:
            rows.append(lr.Row(name or relpath, note="no live panel (no output with an ipympl canvas and a slider)"))
            return
        if not panels:
            rows.append(lr.Row(name or relpath, note=f"none of the panels asked for (it has #0-#{len(found) - 1})"))
            return
        for p in panels:
            t0 = time.monotonic()
            row = measure_panel(nbp, p, moves, timeout=timeout)
            row.notebook = name or relpath
            rows.append(row)
            s = row.stats
            print(f"  {row.notebook} panel #{row.panel}: {s['n']} moves, median {s['median']:.0f} ms, "
                  f"p95 {s['p95']:.0f} ms ({time.monotonic() - t0:.0f} s){'  ' + row.note if row.note else ''}",
                  file=sys.stderr)
        st = nbp.read_status()
        problems = st.get("errors", []) + st.get("tracebacks", []) + st.get("widgetErrors", [])
        if problems:
            for r in rows[first:]:
                r.note = (r.note + "; " if r.note else "") + "error output after the moves: " + problems[0][:120]


def _load() -> str:
    try:
        a, b, c = os.getloadavg()
        cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
        return f"load average {a:.2f} {b:.2f} {c:.2f} on {cpus} CPU(s)"
    except OSError:
        return "load average unknown"


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n\n".join(__doc__.split("\n\n")[1:]))
    ap.add_argument("notebooks", nargs="*",
                    help="notebooks: paths, globs or a book notebook's number (00, 11); default: every book/*.ipynb")
    ap.add_argument("--panels", type=lr.parse_panels, default=None, metavar="LIST",
                    help="only these panels of each notebook, counted from 0 in page order, e.g. 0,2-3")
    ap.add_argument("--moves", "--drags", dest="moves", type=int, default=20, metavar="N",
                    help="slider moves timed per panel (default 20)")
    ap.add_argument("--timeout", type=float, default=15.0, help="seconds a move may take before it counts as missed")
    ap.add_argument("--no-baseline", action="store_true", help="skip the minimal-panel row")
    ap.add_argument("--floor-once", action="store_true", help="measure the minimal panel once, first, not between notebooks")
    ap.add_argument("--floor-moves", type=int, default=6, metavar="N",
                    help="moves of the minimal panel before each notebook and at the end (default 6)")
    ap.add_argument("--json", type=Path, help="also write every latency to this file")
    args = ap.parse_args(argv)
    if args.moves < 1:
        ap.error("--moves must be at least 1")
    try:
        nbs = lr.resolve_notebooks(args.notebooks, ROOT)
    except ValueError as e:
        ap.error(str(e))
    if not browserlab.chromium_available():
        print(browserlab.CHROMIUM_MISSING)
        return 2
    from playwright.sync_api import sync_playwright

    interactive = {p.relative_to(ROOT).as_posix() for p in browserlab.interactive_notebooks(ROOT)}
    load_before = _load()
    t_start = time.monotonic()
    rows: list[lr.Row] = []
    floor: lr.Row | None = None
    with tempfile.TemporaryDirectory(prefix="gm-latency-") as tmp:
        server = browserlab.LabServer(Path(tmp), extra_notebooks={browserlab.SELFCHECK_PATH: browserlab.selfcheck_notebook()})
        with server, sync_playwright() as pw:
            context = browserlab.launch_chromium(pw, Path(tmp) / "profile", viewport=labview.STUDENT_WINDOW)
            lab = browserlab.LabBrowser(context, server)
            try:
                base = (browserlab.SELFCHECK_PATH, {0}, lr.FLOOR_NAME)
                todo = [(nb, args.panels, None) for nb in nbs]
                if args.no_baseline:
                    pass
                elif args.floor_once:
                    todo = [base] + todo
                else:               # the floor before every notebook and at the end, pooled
                    todo = [x for t in todo for x in (base, t)] + [base]
                for relpath, wanted, name in todo:
                    if relpath.startswith("book/") and relpath not in interactive:
                        rows.append(lr.Row(relpath, note="no live panel (no %matplotlib widget)"))
                        continue
                    n0 = len(rows)
                    moves = args.moves if name != lr.FLOOR_NAME or args.floor_once else args.floor_moves
                    try:
                        measure_notebook(lab, relpath, rows, wanted, moves, args.timeout, name)
                    except Exception as e:  # one notebook's failure is a row, not the end of the run
                        first = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
                        rows.append(lr.Row(name or relpath, note=f"failed: {first[:160]}"))
                        print(f"  {relpath}: FAILED\n{e}", file=sys.stderr)
                    if name == lr.FLOOR_NAME:
                        new = next((r for r in rows[n0:] if r.stats["n"]), rows[n0] if len(rows) > n0 else None)
                        del rows[n0:]
                        floor = lr.pool(floor, new)
            finally:
                lab.close()
                context.close()
    minutes = (time.monotonic() - t_start) / 60
    header = (f"headless Chromium + JupyterLab at {labview.STUDENT_WINDOW[0]}x{labview.STUDENT_WINDOW[1]}; "
              f"{load_before} at the start, {_load()} at the end ({minutes:.1f} min)")
    print()
    print(lr.format_table(rows, floor, moves=args.moves, header=header))
    if args.json:
        args.json.write_text(lr.to_json(rows, floor, {"moves": args.moves, "header": header}), encoding="utf-8")
        print(f"\nraw latencies: {args.json}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

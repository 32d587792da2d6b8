"""A picture of every figure of the course, with an index page, to review the course at a glance.

    python tools/screenshots.py                 # real browser if /usr/bin/chromium exists, else headless
    python tools/screenshots.py --headless      # matplotlib PNGs only (no browser)
    python tools/screenshots.py --only book/04  # notebooks whose path contains the text
    make screenshots

Writes ``build/screenshots/`` (git-ignored) with ``index.html`` (and the same captions as ``index.txt``):

* **browser** (Chromium + playwright, as tests/browser): JupyterLab on a scratch copy of the
  course, a 1366 x 768 window with the file browser open (what a student on a laptop sees); for
  every notebook that draws, Run All, then one PNG per output holding a figure (ipympl canvas,
  inline image or animation), cut exactly as the output area shows it, plus a window shot; the
  layout problems of tests/browser/labview.py and the control problems of tests/browser/student.py
  (short slider tracks, cut labels, panels taller than one screen) are listed beside the pictures,
  and each panel's caption gives its height with its controls and its shortest track; then the first
  slider of every panel is dragged slowly and quickly (tests/browser/student.py) and both final
  canvases are shown (after a quick drag the picture must be the slow drag's, with no ghost).
* **headless** (always available): every figure of every notebook and every panel's initial state
  drawn with Agg at its own size and dpi (animations: their last rendered frame), with the
  breaches of the figure standard (tests/figstd.py) listed beside each picture.
"""
from __future__ import annotations

import argparse
import html
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT), str(ROOT / "tests"), str(ROOT / "tests" / "browser")]
os.environ.setdefault("GM_COURSE_TESTING", "1")  # short animations, as under the tests
OUT = ROOT / "build" / "screenshots"


def _slug(text: str) -> str:
    return "".join(c if c.isalnum() or c in "-_." else "_" for c in text).strip("_")


# -- headless -------------------------------------------------------------------------------

def headless(out: Path, only: str | None) -> list[dict]:
    import matplotlib

    matplotlib.use("Agg")
    import figstd
    import matplotlib.pyplot as plt
    import nbfigures

    from gm_core.widgets.base import all_panels

    entries = []
    d = out / "headless"
    d.mkdir(parents=True, exist_ok=True)
    for nb in nbfigures.course_notebooks():
        rel = nb.relative_to(ROOT).as_posix()
        if only and only not in rel:
            continue
        tight = nbfigures.shows_inline(nb)
        shots = []

        def visit(where, obj, kind, rel=rel, shots=shots, tight=tight):
            fig = obj._fig if kind == "animation" else obj
            name = f"{_slug(rel)}-{len(shots):02d}-{_slug(where.split(' ', 1)[-1])}.png"
            fig.savefig(d / name, dpi=fig.dpi, bbox_inches="tight" if tight else None)
            shots.append({"png": f"headless/{name}", "caption": f"{where} ({kind})",
                          "problems": figstd.check_figure(fig, "", tight=tight)})

        t0 = time.monotonic()
        res = nbfigures.run_notebook(nb, visit=visit)
        print(f"headless {rel}: {len(shots)} pictures, {len(res.breaches)} breaches "
              f"({time.monotonic() - t0:.1f} s)", flush=True)
        if shots or res.errors:
            entries.append({"title": rel, "shots": shots, "notes": res.errors + res.breaches})
    if not only or "panel" in only:
        shots = []
        for name, cls in sorted(all_panels().items()):
            fig = cls().fig
            png = f"headless/panel-{name}.png"
            fig.savefig(out / png, dpi=fig.dpi)
            shots.append({"png": png, "caption": f"{name} (initial state)",
                          "problems": figstd.check_figure(fig, "")})
            plt.close("all")
        entries.append({"title": "every registered panel (gm_core.widgets.base.all_panels())",
                        "shots": shots, "notes": []})
    return entries


# -- browser --------------------------------------------------------------------------------

_MARK_FIGURES_JS = r"""
(id) => {
  const root = document.getElementById(id);
  const cells = [...root.querySelectorAll('.jp-Cell')];
  let n = 0; const inNum = new Map();
  for (const c of cells) if (c.classList.contains('jp-CodeCell')) inNum.set(c, ++n);
  const out = [];
  let k = 0;
  for (const o of root.querySelectorAll('.jp-OutputArea-output')) {
    if (!o.querySelector('canvas, img')) continue;
    o.setAttribute('data-gm-shot', String(k));
    // a panel (a canvas with controls): its height with the controls, its shortest slider track
    const ctl = o.querySelector('.widget-slider, .widget-dropdown, .widget-toggle-buttons, .widget-checkbox');
    const parts = [...o.querySelectorAll('.jupyter-widgets, canvas')].map(e => e.getBoundingClientRect())
                    .filter(r => r.width > 0 && r.height > 0);
    const tracks = [...o.querySelectorAll('.widget-slider .noUi-target, .widget-slider .slider-container')]
      .map(t => t.getBoundingClientRect().width).filter(w => w > 0);
    out.push({index: k, cell: 'In[' + (inNum.get(o.closest('.jp-Cell')) || '?') + ']',
              kind: o.querySelector('img[id^="_anim_img"]') ? 'animation'
                    : o.querySelector('.jupyter-matplotlib canvas') ? 'interactive figure' : 'image',
              height: ctl && parts.length ? Math.round(Math.max(...parts.map(r => r.bottom)) - Math.min(...parts.map(r => r.top))) : null,
              track: tracks.length ? Math.round(Math.min(...tracks)) : null});
    k++;
  }
  return out;
}
"""


def _window_shot(nbp, rel: str, d: Path) -> dict | None:
    """The 1366 x 768 window as the student sees it, scrolled to the first figure."""
    st = nbp.read_status()
    if not nbp.page.evaluate(_MARK_FIGURES_JS, st["panelId"]):
        return None
    nbp.page.locator('[data-gm-shot="0"]').scroll_into_view_if_needed()
    name = f"{_slug(rel)}-window.png"
    nbp.page.screenshot(path=str(d / name))
    return {"png": f"browser/{name}", "caption": f"{rel}: the 1366 x 768 window", "problems": []}


def _played_animations(nbp, rel: str, d: Path, notes: list[str]) -> list[dict]:
    """Press ▶ on every animation, shoot it 1 s after its frame first changes and pause it again (tests/browser/student.py
    checks that the frame changes; here a person sees which frame it reached)."""
    import student

    page, shots = nbp.page, []
    for a in page.evaluate(student._ANIMS_JS, nbp.read_status()["panelId"])["anims"]:
        root = page.locator(f'[data-gm-anim="{a["index"]}"]')
        root.scroll_into_view_if_needed()
        try:
            root.locator("button.gm-anim-play").click(timeout=10_000)
            img = root.locator("img").first
            for _ in range(40):   # a busy page may show the next frame late: up to 10 s
                page.wait_for_timeout(250)
                if img.get_attribute("data-frame") != a["frame"]:
                    break
            page.wait_for_timeout(1000)
            name = f"{_slug(rel)}-anim{a['index']:02d}-played.png"
            frame = root.locator("img").first.get_attribute("data-frame")
            root.screenshot(path=str(d / name))
            root.locator("button.gm-anim-play").click(timeout=10_000)
        except Exception as e:  # noqa: BLE001 - a failed press is a finding, not a crash
            notes.append(f"animation #{a['index']}: could not press ▶: {e}"[:300])
            continue
        shots.append({"png": f"browser/{name}", "caption": f"{rel} animation #{a['index']} playing after ▶ "
                      f"(frame {frame} of {a['frames']}; it starts at frame {a['frame']})",
                      # the picture is the evidence (its counter reads k / n): the img's data-frame
                      # attribute was seen stale while the player showed frame 3 of 6
                      "problems": []})
    return shots


def browser(out: Path, only: str | None) -> list[dict]:
    import browserlab
    import labview
    import student
    from playwright.sync_api import sync_playwright

    notebooks = [p for p in labview.figure_notebooks() if not only or only in p.relative_to(ROOT).as_posix()]
    d = out / "browser"
    d.mkdir(parents=True, exist_ok=True)
    entries = []
    work = Path(tempfile.mkdtemp(prefix="gm-screenshots-"))
    server = browserlab.LabServer(work)
    pw = context = lab = None
    try:
        server.start()
        pw = sync_playwright().start()
        context = browserlab.launch_chromium(pw, work / "profile", viewport=labview.STUDENT_WINDOW)
        lab = browserlab.LabBrowser(context, server)
        for nb in notebooks:
            rel = nb.relative_to(ROOT).as_posix()
            t0 = time.monotonic()
            shots, notes = [], []
            try:
                with browserlab.NotebookPage(lab, rel) as nbp:
                    nbp.open()
                    nbp.run_all()
                    nbp.page.wait_for_timeout(2500)  # canvases drawn, images decoded
                    problems, counts = labview.layout_problems(nbp)
                    problems += student.control_problems(nbp)  # short tracks, cut labels, tall panels
                    notes += problems
                    st = nbp.check_no_errors()
                    if shots_window := _window_shot(nbp, rel, d):
                        shots.append(shots_window)
                    # a taller window for the pictures (same width, so the same layout): an output
                    # taller than 768 px is then captured whole, without JupyterLab's bars over it
                    width, _ = labview.STUDENT_WINDOW
                    nbp.page.set_viewport_size({"width": width, "height": 2400})
                    nbp.page.wait_for_timeout(500)
                    for fig in nbp.page.evaluate(_MARK_FIGURES_JS, st["panelId"]):
                        name = f"{_slug(rel)}-{fig['index']:02d}-{_slug(fig['cell'])}.png"
                        loc = nbp.page.locator(f'[data-gm-shot="{fig["index"]}"]')
                        loc.scroll_into_view_if_needed()
                        loc.screenshot(path=str(d / name), timeout=30_000)
                        mine = [p for p in problems if p.startswith(fig["cell"] + " ") or p.startswith(fig["cell"] + ":")]
                        size = (f"; with its controls {fig['height']} px tall" if fig.get("height") else "") + (
                            f", shortest slider track {fig['track']} px" if fig.get("track") else "")
                        shots.append({"png": f"browser/{name}", "caption": f"{rel} {fig['cell']} ({fig['kind']}){size}",
                                      "problems": mine})
                    nbp.page.set_viewport_size(dict(zip(("width", "height"), labview.STUDENT_WINDOW)))
                    if len(shots) == 1:  # a window shot but no figure
                        shots.clear()
                    # every animation after ▶ (its frames must move: compare with its first frame)
                    shots += _played_animations(nbp, rel, d, notes)
                    # what a hurried student is left with: every panel's canvas after a quick
                    # drag of its first slider (beside the slow drag's, which it must equal)
                    drag_dir = d / f"{_slug(rel)}-drag"
                    drag_dir.mkdir(exist_ok=True)
                    drag_problems, drags = student.drag_check(nbp, shots_dir=drag_dir)
                    notes += drag_problems
                    for row in drags["panels"]:
                        for tag in ("quick", "slow"):
                            png = f"browser/{drag_dir.name}/panel{row['panel']:02d}-{tag}.png"
                            shots.append({"png": png, "caption": f"{rel} panel #{row['panel']} (cell {row['cell']}) "
                                          f"after a {tag} drag to {row['value']!r}"
                                          + (f"; differs from the slow drag in {row['differing']:.2%} of pixels"
                                             if tag == "quick" else ""),
                                          "problems": [p for p in drag_problems if p.startswith(f"panel #{row['panel']} ")]
                                          if tag == "quick" else []})
            except AssertionError as e:  # a notebook that fails is reported, the others still shot
                notes.append(f"FAILED: {e}"[:2000])
            print(f"browser {rel}: {len(shots)} pictures, {len(notes)} problems "
                  f"({time.monotonic() - t0:.1f} s)", flush=True)
            entries.append({"title": rel, "shots": shots, "notes": notes})
    finally:
        for close in (lambda: lab and lab.close(), lambda: context and context.close(),
                      lambda: pw and pw.stop(), server.stop):
            try:
                close()
            except Exception as e:  # noqa: BLE001 - keep releasing the rest
                print(f"clean-up: {e}", file=sys.stderr)
        shutil.rmtree(work, ignore_errors=True)
    return entries


# -- index ----------------------------------------------------------------------------------

def write_index(out: Path, sections: list[tuple[str, list[dict]]]):
    e = html.escape
    parts = ["<!doctype html><meta charset='utf-8'><title>Course figures</title><style>",
             "body{font-family:sans-serif;margin:1em 2em} figure{display:inline-block;vertical-align:top;"
             "margin:0 1em 1.5em 0;max-width:48%} figure img{max-width:100%;border:1px solid #ccc}"
             "figcaption{font-size:13px} .bad{color:#a00;font-size:12px;white-space:pre-wrap} "
             "h2{border-top:1px solid #999;padding-top:.5em}</style>",
             f"<h1>Every figure of the course</h1><p>{time.strftime('%Y-%m-%d %H:%M')} &middot; "
             "red lines: breaches of the figure standard (CONTRIBUTING.md) or layout problems.</p>"]
    for label, entries in sections:
        parts.append(f"<h1>{e(label)}</h1>")
        for ent in entries:
            parts.append(f"<h2 id='{e(_slug(label + ent['title']))}'>{e(ent['title'])}</h2>")
            for n in ent["notes"]:
                parts.append(f"<div class='bad'>{e(n)}</div>")
            for s in ent["shots"]:
                bad = "".join(f"<div class='bad'>{e(p)}</div>" for p in s["problems"])
                parts.append(f"<figure><a href='{e(s['png'])}'><img src='{e(s['png'])}' loading='lazy'></a>"
                             f"<figcaption>{e(s['caption'])}{bad}</figcaption></figure>")
    (out / "index.html").write_text("\n".join(parts), encoding="utf-8")
    lines = []  # the same, as text: to read beside the pictures, or to compare two runs
    for label, entries in sections:
        for ent in entries:
            lines += [f"== {label}: {ent['title']}"] + [f"  ! {n}" for n in ent["notes"]]
            for s in ent["shots"]:
                lines += [f"  {s['png']}: {s['caption']}"] + [f"    ! {q}" for q in s["problems"]]
    (out / "index.txt").write_text("\n".join(lines) + "\n", encoding="utf-8")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--headless", action="store_true", help="matplotlib PNGs only, no browser")
    ap.add_argument("--only", default=None, help="only notebooks whose path contains this text")
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args(argv)
    out = args.out
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    sections = []
    import browserlab

    if not args.headless:
        if browserlab.chromium_available():
            sections.append(("In JupyterLab (Chromium, 1366 x 768, file browser open)", browser(out, args.only)))
        else:
            print(f"{browserlab.CHROMIUM_MISSING}; headless pictures only", file=sys.stderr)
    sections.append(("Headless (matplotlib Agg, each figure at its own size and dpi)", headless(out, args.only)))
    write_index(out, sections)
    n = sum(len(ent["shots"]) for _, ents in sections for ent in ents)
    print(f"{n} pictures: {out / 'index.html'}")


if __name__ == "__main__":
    main()

"""Open the built website in headless Chromium with the network blocked and check every page.

    python tools/check_site.py [build/site/_build/html] [--pages book/04-geodesics-and-exp.html ...]

The site is served on 127.0.0.1; every other request is aborted and counted. Per page: no failed
or outside request, no page error; every picture loaded with a non-zero size, visible, with an alt
text that is not a file name; every saved widget view drawn (non-zero size) by the widget
manager served from the site; every formula rendered by MathJax (no raw ``\\(...\\)`` or ``$...$``
left in the prose); every animation plays (its Play button changes the frame shown) and every pre-rendered sweep
moves (its slider, moved from the keyboard, changes the picture and the value shown); axe-core's
automated WCAG 2.1 A/AA checks, injected from the npm package, find no serious or critical
violation. Writes ``report-browser.json`` beside the site and exits 1 on any failure.
Uses Debian's /usr/bin/chromium through playwright (never ``playwright install``).
"""
from __future__ import annotations

import argparse
import functools
import http.server
import json
import socketserver
import sys
import threading
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
AXE = ROOT / "site" / "node_modules" / "axe-core" / "axe.min.js"
CHROMIUM = "/usr/bin/chromium"

_IMAGES = """() => [...document.querySelectorAll('article.bd-article img, article img')].map(img => {
  const r = img.getBoundingClientRect();
  return {src: img.getAttribute('src').slice(0, 80), alt: img.getAttribute('alt') || '',
          complete: img.complete, nw: img.naturalWidth, nh: img.naturalHeight, w: r.width, h: r.height,
          visible: getComputedStyle(img).visibility !== 'hidden' && getComputedStyle(img).display !== 'none'};
})"""

_RAW_MATH = r"""() => {
  const walker = document.createTreeWalker(document.querySelector('article') || document.body, NodeFilter.SHOW_TEXT);
  const bad = [];
  for (let n = walker.nextNode(); n; n = walker.nextNode()) {
    // rendered text everywhere, outputs included (code and preformatted output excepted): a TeX
    // delimiter or command left in it is a formula MathJax did not typeset
    if (n.parentElement.closest('pre, code, script, style, mjx-container, textarea, .highlight')) continue;
    const t = n.textContent;
    if (/\\\(|\\\[|\$[^$\s][^$]*\$|\\[a-zA-Z]{2,}/.test(t)) bad.push(t.trim().slice(0, 80));
  }
  return {bad, rendered: document.querySelectorAll('mjx-container').length,
          errors: document.querySelectorAll('mjx-merror').length};
}"""


#: The search page has finished: its status says so and every result's excerpt (a page's, not a
#: section's, which has a description instead) is typeset (site/gm-site.js marks each one).
_SEARCH_DONE = r"""() => {
  const status = document.querySelector('#search-results p.search-summary');
  const items = [...document.querySelectorAll('#search-results li')];
  return status && status.textContent.startsWith('Search finished') && items.length > 0 &&
    items.every(li => li.querySelector(':scope > span') ||
                      li.querySelector(':scope > p.context[data-gm-math="done"]'));
}"""
#: Searches whose excerpts hold formulas (checked beside every page).
SEARCHES = ("search.html?q=lifted+action", "search.html?q=exponential+map")


class _Quiet(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):
        pass


def serve(directory):
    srv = socketserver.ThreadingTCPServer(("127.0.0.1", 0), functools.partial(_Quiet, directory=str(directory)))
    srv.daemon_threads = True
    threading.Thread(target=srv.serve_forever, daemon=True).start()
    return srv


def _settle(page):
    """Wait until no request has been open for 0.5 s (at most 20 s; a page that never settles is
    judged as it is)."""
    try:
        page.wait_for_load_state("networkidle", timeout=20000)
    except Exception:  # noqa: BLE001 - playwright's TimeoutError
        pass


def check_page(page, base, path):
    failed, outside, errors = [], [], []

    def route(r):
        if r.request.url.startswith(base):
            r.continue_()
        else:
            outside.append(r.request.url)
            r.abort()

    page.route("**/*", route)
    page.on("requestfailed", lambda r: failed.append(r.url) if r.url.startswith(base) else None)
    page.on("response", lambda r: failed.append(f"{r.status} {r.url}") if r.status >= 400 else None)
    page.on("pageerror", lambda e: errors.append(str(e)[:300]))
    page.goto(base + path, wait_until="load")
    _settle(page)
    if "?q=" in path:                      # a search: every excerpt shown and typeset
        page.wait_for_function(_SEARCH_DONE, timeout=30000)
    page.wait_for_function("() => !window.MathJax || !MathJax.startup || MathJax.startup.promise", timeout=20000)
    page.evaluate("() => window.MathJax && MathJax.startup ? MathJax.startup.promise : null")
    out = {"page": path, "failed": failed, "outside": outside, "errors": errors}
    # lazily loaded pictures: scroll through the page once
    height = page.evaluate("document.body.scrollHeight")
    for y in range(0, height, 700):
        page.evaluate(f"window.scrollTo(0, {y})")
        page.wait_for_timeout(30)
    _settle(page)
    imgs = page.evaluate(_IMAGES)
    out["images"] = len(imgs)
    out["bad_images"] = [i for i in imgs if not (i["complete"] and i["nw"] > 0 and i["w"] > 0 and i["h"] > 0
                                                 and i["visible"])]
    out["missing_alt"] = [i["src"] for i in imgs if not i["alt"].strip() or i["alt"].endswith((".png", ".webp"))]
    math = page.evaluate(_RAW_MATH)
    out["math_rendered"], out["raw_math"], out["math_errors"] = math["rendered"], math["bad"], math["errors"]
    views = page.evaluate("""() => [...document.querySelectorAll('script[type="application/vnd.jupyter.widget-view+json"]')]
      .map(s => { const w = s.parentElement.querySelector('.jupyter-widgets, .lm-Widget');
                  const r = w ? w.getBoundingClientRect() : null;
                  return r && r.width > 0 && r.height > 0; })""")
    out["widgets"], out["blank_widgets"] = len(views), views.count(False)   # drawn from the saved state
    out["sweeps"], out["still_sweeps"] = 0, []
    for sweep in page.query_selector_all(".gm-sweep"):        # a pre-rendered slider sweep moves
        img, slider = sweep.query_selector("img.gm-anim-frame"), sweep.query_selector("input.gm-anim-slider")
        value = sweep.query_selector(".gm-sweep-value")
        if img is None or slider is None or value is None:
            out["still_sweeps"].append("a sweep without its picture, slider or value")
            continue
        out["sweeps"] += 1
        sweep.scroll_into_view_if_needed()
        before, shown = img.get_attribute("src")[-200:], value.text_content()
        at_end = slider.evaluate("s => s.value === s.max")
        slider.focus()
        page.keyboard.press("Home" if at_end else "End")        # what a keyboard user does
        try:
            page.wait_for_function("([el, b]) => el.getAttribute('src').slice(-200) !== b", arg=[img, before], timeout=5000)
            moved = value.text_content() != shown and img.bounding_box()["width"] > 0
        except Exception:  # noqa: BLE001 - playwright's TimeoutError
            moved = False
        if not moved:
            out["still_sweeps"].append(img.get_attribute("id"))
    out["animations"], out["still_animations"] = 0, []
    for player in page.query_selector_all(".gm-anim"):
        img = player.query_selector("img")
        if img is None:
            continue
        out["animations"] += 1
        before = img.get_attribute("src")[-200:]
        player.scroll_into_view_if_needed()
        player.query_selector("button[data-act='play']").click()
        try:                                  # the next frame shows within a few intervals
            page.wait_for_function("([el, b]) => el.getAttribute('src').slice(-200) !== b", arg=[img, before],
                                   timeout=8000)
            moved = True
        except Exception:  # noqa: BLE001 - playwright's TimeoutError
            moved = False
        player.query_selector("button[data-act='play']").click()      # pause again
        if not moved or img.bounding_box()["width"] == 0:
            out["still_animations"].append(img.get_attribute("id"))
    page.add_script_tag(path=str(AXE))
    axe = page.evaluate("""async () => {
      const r = await axe.run(document, {runOnly: {type: 'tag', values: ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa']}});
      return r.violations.map(v => ({id: v.id, impact: v.impact, help: v.help, nodes: v.nodes.length,
                                      first: v.nodes[0] ? v.nodes[0].target.join(' ') : ''}));
    }""")
    out["axe"] = axe
    out["axe_serious"] = [v for v in axe if v["impact"] in ("serious", "critical")]
    out["ok"] = not (failed or outside or errors or out["bad_images"] or out["missing_alt"] or out["raw_math"]
                     or out["math_errors"] or out["still_animations"] or out["still_sweeps"] or out["blank_widgets"]
                     or out["axe_serious"])
    return out


def check(html_dir, pages=None, playwright=None):
    """[per-page result] for ``pages`` (paths relative to the site, default every page).

    ``playwright``: a started sync Playwright to use (a test process has one; a second could not
    start beside it); by default the check starts and stops its own."""
    from playwright.sync_api import sync_playwright

    html_dir = Path(html_dir)
    if pages is None:
        pages = sorted(p.relative_to(html_dir).as_posix() for d in ("book", "exercises")
                       for p in (html_dir / d).glob("*.html"))
        pages += sorted(p.name for p in html_dir.glob("*.html"))      # index, genindex, search
        pages += list(SEARCHES)
    srv = serve(html_dir)
    base = f"http://127.0.0.1:{srv.server_address[1]}/"
    results = []
    own = playwright is None
    try:
        p = sync_playwright().start() if own else playwright
        try:
            browser = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
            for path in pages:
                page = browser.new_page(viewport={"width": 1366, "height": 768})
                try:
                    results.append(check_page(page, base, path))
                    print(f"  checked {path}", file=sys.stderr, flush=True)
                finally:
                    page.close()
            browser.close()
        finally:
            if own:
                p.stop()
    finally:
        srv.shutdown()
    return results


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python tools/check_site.py", description=__doc__.splitlines()[0])
    ap.add_argument("html", nargs="?", type=Path, default=ROOT / "build" / "site" / "_build" / "html")
    ap.add_argument("--pages", nargs="+")
    args = ap.parse_args(argv)
    results = check(args.html, args.pages)
    (args.html.parent.parent / "report-browser.json").write_text(json.dumps(results, indent=1) + "\n")
    for r in results:
        moderate = sorted({v["id"] for v in r["axe"] if v["impact"] not in ("serious", "critical")})
        print(f"{'ok  ' if r['ok'] else 'FAIL'} {r['page']}: {r['images']} pictures, {r['math_rendered']} formulas, "
              f"{r['animations']} animations ({r['sweeps']} sweeps), {r['widgets']} widgets; axe serious/critical {len(r['axe_serious'])}"
              f"{' (minor/moderate: ' + ', '.join(moderate) + ')' if moderate else ''}")
        if not r["ok"]:
            for k in ("failed", "outside", "errors", "bad_images", "missing_alt", "raw_math", "math_errors",
                      "still_animations", "still_sweeps", "blank_widgets", "axe_serious"):
                if r[k]:
                    print(f"     {k}: {json.dumps(r[k])[:600]}")
    return 0 if all(r["ok"] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())

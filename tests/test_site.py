"""The course website (tools/build_site.py), built for a representative subset of pages and read
in headless Chromium with the network blocked (tools/check_site.py).

The subset: chapter 4 (live panels, formulas and an animation) and exercise 1.1 (check
widgets). `make site` builds and checks every page. The build runs in its
own venv (.venv-site, Jupyter Book 1 from PyPI, made by tools/venvs.py); the front-end files come
from npm (site/package.json). Skipped, saying why, only when Chromium, npm or the packages are
not to be had."""
import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import build_site  # noqa: E402
import check_site  # noqa: E402
import venvs  # noqa: E402

PAGES = ["book/04-geodesics-and-exp", "exercises/ex1_1"]

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    if not Path(check_site.CHROMIUM).exists():
        pytest.skip("no /usr/bin/chromium (apt-get install chromium)")
    if shutil.which("npm") is None:
        pytest.skip("npm is needed for the site's MathJax, widget manager and axe-core (apt-get install npm)")
    try:
        bin_dir = venvs.ensure("site")
    except venvs.VenvError as exc:
        pytest.skip(f"Jupyter Book could not be installed from PyPI: {exc}")
    out = tmp_path_factory.mktemp("site")
    env = {k: v for k, v in os.environ.items() if k != "VIRTUAL_ENV"}
    env["PYTHONPATH"] = str(ROOT)
    res = subprocess.run([str(bin_dir / "python"), str(ROOT / "tools" / "build_site.py"), "--out", str(out),
                          "--only", *PAGES], cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert res.returncode == 0, res.stdout[-3000:] + res.stderr[-3000:]
    html = out / "_build" / "html"
    report = json.loads((out / "report.json").read_text())
    results = check_site.check(html, [p + ".html" for p in PAGES])
    return html, report, {r["page"]: r for r in results}


def test_every_page_passes_the_offline_browser_check(site):
    _, _, results = site
    bad = {p: {k: v for k, v in r.items() if v and k in ("failed", "outside", "errors", "bad_images", "missing_alt",
                                                          "raw_math", "math_errors", "still_animations", "axe_serious")}
           for p, r in results.items() if not r["ok"]}
    assert not bad, json.dumps(bad, indent=1)[:4000]


def test_the_check_saw_pictures_formulas_and_an_animation(site):
    _, _, results = site
    ch4 = results["book/04-geodesics-and-exp.html"]
    assert ch4["images"] >= 3, "live panels show their first state as a picture"
    assert ch4["math_rendered"] >= 10, "chapter 4's formulas are rendered by MathJax"
    assert ch4["animations"] >= 1, "chapter 4's animation is on the page and was played"


def test_pages_are_light_and_served_from_the_site(site):
    html, report, _ = site
    for page, r in report["pages"].items():
        assert r["bytes"] < 5_000_000, f"{page} is {r['bytes'] / 1e6:.1f} MB"
    text = (html / "book" / "04-geodesics-and-exp.html").read_text()
    assert "_static/mathjax/tex-mml-chtml.js" in text
    assert "_static/widgets/embed.js" in (html / "exercises" / "ex1_1.html").read_text(), "the check widgets"
    assert not re.search(r'(?:src|href)="https?://[^"]*(?:cdn|unpkg)', text)
    assert (html / "_static" / "font-awesome" / "css" / "font-awesome.min.css").exists()


def test_panels_carry_alt_text_and_links_point_at_site_pages(site):
    html, _, _ = site
    text = (html / "book" / "04-geodesics-and-exp.html").read_text()
    alts = re.findall(r'<img alt="([^"]+)"[^>]*_images/', text)
    assert alts and any(a.startswith("Interactive figure:") for a in alts), alts
    assert "workspace/ex" not in re.sub(r"<code.*?</code>", "", text, flags=re.S), "no links into workspace/"
    assert "mybinder.org/v2/gh/" in text and "urlpath=lab/tree/book/04-geodesics-and-exp.ipynb" in text
    ex = (html / "exercises" / "ex1_1.html").read_text()
    assert "urlpath=lab/tree/exercises/ex1_1.ipynb" in ex


def test_prepare_rewrites_links_and_halves_frames_within_budget():
    import nbformat

    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# T\nSee [ex](../workspace/ex1_1.ipynb), [c](02-lie-groups-and-se2.ipynb)"
                                              " and [r](../README.md).")]
    out = build_site.prepare(nb, "book/01-configuration-spaces.ipynb",
                             {"book/01-configuration-spaces.ipynb", "exercises/ex1_1.ipynb"})
    src = out.cells[0].source
    assert "(../exercises/ex1_1.ipynb)" in src
    assert "/blob/main/book/02-lie-groups-and-se2.ipynb" in src and "/blob/main/README.md" in src
    assert "mybinder.org" in out.cells[1].source
    nb.cells = [nbformat.v4.new_markdown_cell("# T\n<details><summary>A</summary>$\\mathbb{R}^1$, not $x$</details>")]
    out = build_site.prepare(nb, "book/01-configuration-spaces.ipynb", set())
    assert out.cells[0].source.count('<span class="math notranslate nohighlight">\\(') == 2


def test_compress_animation_keeps_a_playable_player():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.animation import FuncAnimation

    from gm_core.drawing.primitives import jshtml

    fig, ax = plt.subplots(figsize=(3, 2), dpi=100)
    (line,) = ax.plot([0, 1], [0, 0])
    anim = FuncAnimation(fig, lambda k: line.set_ydata([0, k / 10]), frames=24, interval=50)
    anim.gm_figure, anim.gm_interval = fig, 50     # as gm_core.drawing.primitives.animate sets them
    html = jshtml(anim).data
    small = build_site.compress_animation(html, keep_every=2)
    frames = build_site._frames(small)
    assert len(frames) == 12 and all(f.startswith("data:image/webp;base64,") for f in frames)
    assert 'data-frames="12"' in small and 'max="11"' in small and "1 / 12" in small and "interval = 100" in small
    assert f'src="{frames[0]}"' in small
    assert len(small) < len(html)

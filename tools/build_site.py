"""Build the course website, offline: ``make site`` (``python tools/build_site.py`` in .venv-site).

    python tools/build_site.py [--only book/00 exercises/ex1_1 ...] [--out build/site] [--fresh]

Steps (each page is a notebook of ``book/`` or ``exercises/``):

1. **execute** every notebook in a fresh kernel (nbclient, widget state stored), in a copy of the
   repository layout under ``OUT/src``; a kernel hook gives every figure an alt text from its
   titles and labels (panels bring their own, ``Panel.alt_text``). Results are cached by content.
2. **prepare** the executed notebooks for a static page: a live panel or ipympl canvas keeps only
   its picture (``image/png``, the panel's first state); widget state is pruned to what the
   remaining widget views use; animation frames are re-encoded as WebP (halving the frame count
   while a page would pass its budget); links to ``workspace/`` point at the exercise pages and
   links outside the site at the repository; each page starts with "open in JupyterLab/Binder".
3. **build** with Jupyter Book 1 (Sphinx + myst-nb, no execution), MathJax, the widget manager
   (@jupyter-widgets/html-manager), require.js and the player's icons (font-awesome) copied from
   ``site/node_modules`` (npm) into ``_static``: nothing is loaded from a CDN.
4. **finish** the HTML: alt text onto every picture, CDN references rewritten to ``_static``,
   and ``OUT/report.json`` with each page's size (HTML plus its own pictures).

The site is ``OUT/_build/html/index.html``. tests/test_site.py opens it in headless Chromium with
the network blocked and runs axe-core.
"""
from __future__ import annotations

import argparse
import base64
import hashlib
import io
import json
import os
import re
import shutil
import subprocess
import sys
import time
from html import escape, unescape
from pathlib import Path

import set_repository  # tools/: where the course is published ([tool.gm-course] of pyproject.toml)
import site_sweeps  # tools/: pre-rendered slider sweeps (site/sweeps.toml)

ROOT = Path(__file__).resolve().parent.parent
NPM_DIR = ROOT / "site"
DEFAULT_OUT = ROOT / "build" / "site"
PAGE_BUDGET = 4_500_000          # bytes of HTML + own pictures; the promise is 5 MB
WIDGET_VIEW = "application/vnd.jupyter.widget-view+json"
WIDGET_STATE = "application/vnd.jupyter.widget-state+json"
CDN = re.compile(r"https?://(?:maxcdn\.bootstrapcdn\.com|cdnjs\.cloudflare\.com|cdn\.jsdelivr\.net|unpkg\.com)"
                 r"[^\"')\s]*")
FONT_AWESOME_CDN = re.compile(r"https?://maxcdn\.bootstrapcdn\.com/font-awesome/[\d.]+/css/font-awesome(?:\.min)?\.css")

# Runs first in every kernel (and is removed from the page): alt text for every figure published.
KERNEL_SETUP = r'''
def __gm_site_setup():
    import re
    from IPython import get_ipython
    ip = get_ipython()
    used = set()
    ip.events.register("pre_execute", used.clear)

    def describe(fig):
        bits = []
        sup = fig.get_suptitle() if hasattr(fig, "get_suptitle") else ""
        if sup:
            bits.append(sup)
        for ax in fig.axes:
            texts = [ax.get_title(loc) for loc in ("left", "center", "right")]
            labels = [ax.get_xlabel(), ax.get_ylabel(), getattr(ax, "get_zlabel", lambda: "")()]
            leg = ax.get_legend()
            legend = [t.get_text() for t in leg.get_texts()] if leg else []
            part = "; ".join(t for t in texts if t)
            if any(labels):
                part += (" " if part else "") + "(" + " vs ".join(l for l in labels if l) + ")"
            if legend:
                part += (" " if part else "") + "showing " + ", ".join(legend[:6])
            if part:
                bits.append(part)
        text = ". ".join(dict.fromkeys(bits))
        return text.replace("$", "").replace("\\", "")[:400]

    def find(data):
        import matplotlib.pyplot as plt
        figs = [plt.figure(n) for n in plt.get_fignums()]
        view = data.get("application/vnd.jupyter.widget-view+json")
        if view:
            for f in figs:
                if getattr(f.canvas, "model_id", None) == view.get("model_id"):
                    return f
        m = re.match(r"<Figure size (\d+)x(\d+) with (\d+) Axes>", data.get("text/plain", ""))
        if m:
            w, h, n = map(int, m.groups())
            for f in figs:
                size = f.get_size_inches() * f.dpi
                if id(f) not in used and len(f.axes) == n and abs(size[0] - w) < 2 and abs(size[1] - h) < 2:
                    used.add(id(f))
                    return f
        return None

    def hook(msg):
        content = msg.get("content", {})
        data = content.get("data", {})
        if "image/png" in data:
            meta = content.setdefault("metadata", {})
            png = meta.setdefault("image/png", {})
            if not png.get("alt"):
                try:
                    fig = find(data)
                    if fig is not None:
                        png["alt"] = describe(fig)
                except Exception:
                    pass
        return msg

    ip.display_pub.register_hook(hook)

__gm_site_setup()
del __gm_site_setup
'''


def pages(only=None):
    """Relative paths (book/..., exercises/...) of the pages, in reading order."""
    book = sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "book").glob("*.ipynb"))
    ex = sorted((p.relative_to(ROOT).as_posix() for p in (ROOT / "exercises").glob("ex*.ipynb")),
                key=lambda s: tuple(int(x) for x in re.findall(r"\d+", Path(s).stem)))
    out = book + ex
    if only:
        out = [p for p in out if any(p.startswith(o) for o in only)]
        if not out:
            raise ValueError(f"only: no page matches {only}")
    return out


# ---- 1. execute --------------------------------------------------------------------------------

def execute(rel, src_dir, cache_dir, fresh=False):
    import nbformat
    from nbclient import NotebookClient

    text = (ROOT / rel).read_text(encoding="utf-8")
    code = "".join(p.read_text() for p in sorted((ROOT / "gm_core").rglob("*.py")))
    setup = KERNEL_SETUP + site_sweeps.kernel_code()
    key = hashlib.sha256((text + setup + code).encode()).hexdigest()[:20]   # page, setup and course code
    cached = cache_dir / (rel.replace("/", "__") + f".{key}.ipynb")
    if cached.exists() and not fresh:
        return nbformat.read(cached, as_version=4), 0.0
    nb = nbformat.reads(text, as_version=4)
    nb.cells.insert(0, nbformat.v4.new_code_cell(setup))
    work = src_dir / Path(rel).parent
    work.mkdir(parents=True, exist_ok=True)
    env_before = dict(os.environ)
    os.environ["PYTHONPATH"] = os.pathsep.join([str(ROOT)] + [p for p in env_before.get("PYTHONPATH", "").split(os.pathsep) if p])
    os.environ.pop("GM_COURSE_WORKSPACE", None)
    t = time.monotonic()
    try:
        # shutdown_kernel="immediate": the page is built from ``nb`` (its widget state included,
        # stored before the kernel ends), so nothing needs the kernel's orderly exit.
        NotebookClient(nb, timeout=900, kernel_name="python3", allow_errors=False, store_widget_state=True,
                       shutdown_kernel="immediate", resources={"metadata": {"path": str(work)}}).execute()
    finally:
        os.environ.clear()
        os.environ.update(env_before)
    nb.cells.pop(0)
    for c in nb.cells:                       # the setup cell shifted the counts by one
        if c.cell_type == "code" and c.get("execution_count"):
            c.execution_count -= 1
    cache_dir.mkdir(parents=True, exist_ok=True)
    for old in cache_dir.glob(rel.replace("/", "__") + ".*.ipynb"):
        old.unlink()
    nbformat.write(nb, cached)
    return nb, time.monotonic() - t


# ---- 2. prepare ----------------------------------------------------------------------------------

def _heading_before(nb, index):
    for cell in reversed(nb.cells[:index]):
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("#"):
                    return re.sub(r"[#*`$\\]", "", line).strip()
    return Path(nb.metadata.get("gm_site_page", "")).stem


def _refs(value, out):
    if isinstance(value, str):
        out.update(re.findall(r"IPY_MODEL_([0-9a-f]+)", value))
    elif isinstance(value, dict):
        for v in value.values():
            _refs(v, out)
    elif isinstance(value, list):
        for v in value:
            _refs(v, out)


def prune_widgets(nb):
    """Outputs with a picture keep only the picture (it has alt text; a live canvas cannot draw
    without a kernel); widget state keeps what the views left use. The views left are drawn from
    their saved state by the widget manager, ipympl's canvases by ipympl's front end; a view with
    a canvas that has no saved picture of its own (``_data_url``) is replaced by a note."""
    state = nb.metadata.get("widgets", {}).get(WIDGET_STATE, {}).get("state", {})
    roots = []
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            if WIDGET_VIEW in data:
                if "image/png" in data:
                    del data[WIDGET_VIEW]
                    data.pop("text/html", None)
                else:
                    roots.append((out, data[WIDGET_VIEW].get("model_id")))
    keep = set()
    for out, root in roots:
        need, todo = set(), [root]
        while todo:
            m = todo.pop()
            if m in need or m not in state:
                continue
            need.add(m)
            refs = set()
            _refs(state[m].get("state", {}), refs)
            todo += list(refs)
        if root not in state or any(state[m].get("model_name") == "MPLCanvasModel" and not state[m]["state"].get("_data_url")
                                    for m in need):
            del out["data"][WIDGET_VIEW]
            out["data"].setdefault("text/plain", "(an interactive control: open the page in JupyterLab to use it)")
        else:
            keep |= need
    if state:
        nb.metadata["widgets"][WIDGET_STATE]["state"] = {k: v for k, v in state.items() if k in keep}
        if not keep:
            del nb.metadata["widgets"]


_PLAYER_FRAMES = re.compile(r"frames = (\[.*?\]), interval = (\d+)", re.S)


def _frames(html):
    """The frames (data URLs) of a course player (gm_core.drawing.toolkit.player), or []."""
    m = _PLAYER_FRAMES.search(html)
    return json.loads(m.group(1)) if m else []


def compress_animation(html, keep_every=1):
    """Re-encode a course player's frames as WebP; keep every ``keep_every``-th frame (and make
    each shown ``keep_every`` times as long, so the motion keeps its speed). The frame the player
    starts at is kept (a sweep starts at its panel's first state), and a sweep's values follow."""
    from PIL import Image

    m = _PLAYER_FRAMES.search(html)
    if not m:
        return html
    frames = json.loads(m.group(1))
    st = re.search(r"first = (\d+);", html)
    start = int(st.group(1)) if st else 0
    pick = list(range(start % keep_every, len(frames), keep_every))
    start = pick.index(start)
    encoded = []
    for url in (frames[i] for i in pick):
        head, _, data = url.partition(",")
        if "webp" in head:
            encoded.append(url)
            continue
        buf = io.BytesIO()
        Image.open(io.BytesIO(base64.b64decode(data))).save(buf, "WEBP", quality=82, method=4)
        encoded.append("data:image/webp;base64," + base64.b64encode(buf.getvalue()).decode("ascii"))
    interval = int(m.group(2)) * keep_every
    n = len(encoded)
    html = html[:m.start()] + f"frames = {json.dumps(encoded)}, interval = {interval}" + html[m.end():]
    if st:
        html = re.sub(r"first = \d+;", f"first = {start};", html, count=1)
    html = re.sub(r'data-frames="\d+"', f'data-frames="{n}"', html, count=1)
    html = re.sub(r'(<img id="_anim_img\w+" src=")[^"]*"', lambda k: k.group(1) + encoded[start] + '"', html, count=1)
    html = re.sub(r'(class="gm-anim-slider" min="0" max=")\d+"( value=")\d+"',
                  lambda k: k.group(1) + f'{n - 1}"' + k.group(2) + f'{start}"', html, count=1)
    html = re.sub(r'(<span class="gm-anim-counter">)\d+ / \d+', lambda k: k.group(1) + f"{start + 1} / {n}", html, count=1)

    def values(k):
        vals = json.loads(unescape(k.group(1)))
        return 'data-values="' + escape(json.dumps([vals[i] for i in pick])) + '"'

    return re.sub(r'data-values="([^"]*)"', values, html, count=1)


def _is_animation(out):
    return "text/html" in out.get("data", {}) and 'class="gm-anim"' in "".join(out["data"]["text/html"])


def _page_bytes(nb):
    return len(json.dumps([c.get("outputs", []) for c in nb.cells]))


def _tex_span(tex, display=False):
    """A span MathJax renders, written so that it reads the same whether MyST then parses it as
    markdown (a paragraph inside <details>) or keeps it as raw HTML: backslashes, underscores and
    asterisks as character references, which markdown neither escapes nor turns into emphasis."""
    safe = tex.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
    safe = safe.replace("\\", "&#92;").replace("_", "&#95;").replace("*", "&#42;")
    left, right = ("&#92;[", "&#92;]") if display else ("&#92;(", "&#92;)")
    return f'<span class="math notranslate nohighlight">{left}{safe}{right}</span>'


def _html_math(m):
    """$$...$$ and $...$ inside a raw HTML block (MyST leaves them alone) -> spans MathJax renders."""
    text = re.sub(r"(?<!\\)\$\$(.+?)\$\$", lambda k: _tex_span(k.group(1), display=True), m.group(0), flags=re.S)
    return re.sub(r"(?<![\\$])\$([^$]+?)\$", lambda k: _tex_span(k.group(1)), text, flags=re.S)


def prepare(nb, rel, page_set):
    import nbformat

    nb.metadata["gm_site_page"] = rel
    for cell in nb.cells:
        for out in cell.get("outputs", []):
            site_sweeps.prefer_sweep(out)
    prune_widgets(nb)
    anims = []
    for i, cell in enumerate(nb.cells):
        for out in cell.get("outputs", []):
            if _is_animation(out):
                src = "".join(out["data"]["text/html"])
                n = len(_frames(src))
                alt = f"Animation ({n} frames) for “{_heading_before(nb, i)}”; the player's buttons step through it"
                if 'class="gm-sweep"' not in src:         # a sweep's pictures say what they show
                    src = re.sub(r'(<img id="_anim_img\w+" [^>]*?)alt="[^"]*"', lambda k: f'{k.group(1)}alt="{alt}"', src, count=1)
                out["data"]["text/html"] = src
                anims.append([out, src, 1])
            data = out.get("data", {})
            if "image/png" in data:
                meta = out.setdefault("metadata", {}).setdefault("image/png", {})
                if not meta.get("alt"):
                    meta["alt"] = f"Figure for “{_heading_before(nb, i)}”"
    for a in anims:
        a[0]["data"]["text/html"] = compress_animation(a[1], 1)
    while anims and _page_bytes(nb) > PAGE_BUDGET:
        big = max(anims, key=lambda a: len(a[0]["data"]["text/html"]))
        if len(_frames(big[1])) // (big[2] * 2) < 12:
            break
        big[2] *= 2
        big[0]["data"]["text/html"] = compress_animation(big[1], big[2])
    here = Path(rel).parent

    def link(m):
        target = m.group(2)
        if re.match(r"^[a-z]+:|^#", target):
            return m.group(0)
        path, _, anchor = target.partition("#")
        dest = (here / path).as_posix()
        norm = os.path.normpath(dest)
        norm = re.sub(r"^workspace/", "exercises/", norm)
        if norm in page_set:
            new = os.path.relpath(norm, here.as_posix())
        else:
            new = set_repository.file_url(norm)
        return f"{m.group(1)}({new}{'#' + anchor if anchor else ''})"

    for cell in nb.cells:
        if cell.cell_type == "markdown":
            cell.source = re.sub(r"(\]\s*)\(([^)\s]+)\)", link, cell.source)
            cell.source = re.sub(r"<details\b.*?</details>", _html_math, cell.source, flags=re.S)
    banner = (f"> **Live version.** [Open this notebook in JupyterLab on Binder]({set_repository.binder_url(rel)}), "
              f"or run `make lab` in a copy of the course and open `{rel}`. On this page every live "
              "figure is a picture of its first state; animations play here.")
    first_md = next((k for k, c in enumerate(nb.cells) if c.cell_type == "markdown"), -1)
    nb.cells.insert(first_md + 1, nbformat.v4.new_markdown_cell(banner))
    return nb


# ---- 3. build ------------------------------------------------------------------------------------

def npm_assets():
    mods = NPM_DIR / "node_modules"
    need = ["mathjax/es5/tex-mml-chtml.js", "@jupyter-widgets/html-manager/dist/embed-amd.js", "requirejs/require.js",
            "font-awesome/css/font-awesome.min.css", "axe-core/axe.min.js"]
    if not all((mods / n).exists() for n in need):
        subprocess.run(["npm", "install", "--no-audit", "--no-fund", "--loglevel=error"], cwd=NPM_DIR, check=True)
    return mods


def ipympl_front_end():
    """jupyter-matplotlib, ipympl's front end as an AMD module: the wheel installs it (for the
    classic notebook) under the venv's share/jupyter/nbextensions."""
    path = Path(sys.prefix) / "share" / "jupyter" / "nbextensions" / "jupyter-matplotlib" / "index.js"
    if not path.exists():
        raise RuntimeError(f"ipympl's front end is not at {path}: build the site in .venv-site (tools/venvs.py site)")
    return path


def copy_static(src_dir):
    mods = npm_assets()
    static = src_dir / "_assets"      # copied into the site's _static; not _static itself, whose
                                      # every .js Jupyter Book would add to every page
    static.mkdir(parents=True, exist_ok=True)
    for own in ("gm-site.css", "gm-site.js", "gm-widgets.js"):
        shutil.copyfile(NPM_DIR / own, static / own)
    (static / "require").mkdir(exist_ok=True)
    shutil.copyfile(mods / "requirejs" / "require.js", static / "require" / "require.js")
    (static / "ipympl").mkdir(exist_ok=True)
    front = ipympl_front_end()
    for name in ("index.js", "index.js.LICENSE.txt"):
        if (front.parent / name).exists():
            shutil.copyfile(front.parent / name, static / "ipympl" / name)
    for name, dest in (("mathjax/es5", "mathjax"), ("@jupyter-widgets/html-manager/dist", "widgets"),
                       ("font-awesome", "font-awesome")):
        if (static / dest).exists():
            shutil.rmtree(static / dest)
        shutil.copytree(mods / name, static / dest, ignore=shutil.ignore_patterns("*.map", "less", "scss", "*.md", "embed.js", "libembed-amd.js"))


def only_some(rels):
    """Is this a partial build (make site PAGES=...)? The instructor's page comes with full builds."""
    return set(rels) != set(pages())


def instructors_page():
    """The site's page for instructors: README's sections on instructors and the website, one text
    for both; links to files the site does not publish point at the repository."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    parts = [readme[readme.index(h):] for h in ("## For instructors", "## The website")]
    body = "\n".join(p[:p.index("\n## ", 3)].rstrip() + "\n" if "\n## " in p[3:] else p for p in parts)

    def link(m):
        target = m.group(2)
        if re.match(r"[a-z]+:|#", target):
            return m.group(0)
        return f"{m.group(1)}({set_repository.file_url(target)})"

    body = re.sub(r"(\]\s*)\(([^)\s]+)\)", link, body)
    return "# Publishing and grading the course\n\n" + body


def write_book(src_dir, rels):
    repo, branch = set_repository.read()
    book = [r for r in rels if r.startswith("book/")]
    ex = [r for r in rels if r.startswith("exercises/")]
    root = (book or ex)[0]
    toc = ["format: jb-book", f"root: {root.removesuffix('.ipynb')}"]
    chapters = [r for r in book if r != root]
    for caption, items in (("Chapters", chapters), ("Exercises", [r for r in ex if r != root])):
        if items:
            toc += ["parts:"] if "parts:" not in toc else []
            toc += [f"  - caption: {caption}", "    chapters:"]
            toc += [f"      - file: {r.removesuffix('.ipynb')}" for r in items]
    if book and root == book[0] and not only_some(rels):
        (src_dir / "instructors.md").write_text(instructors_page(), encoding="utf-8")
        toc += ["parts:"] if "parts:" not in toc else []
        toc += ["  - caption: For instructors", "    chapters:", "      - file: instructors"]
    (src_dir / "_toc.yml").write_text("\n".join(toc) + "\n")
    config = {
        "title": "Geometric mechanics, interactively",
        "author": "The gm-course authors (code MIT, text CC BY 4.0)",
        "copyright": "2026",
        "only_build_toc_files": True,
        "execute": {"execute_notebooks": "off"},
        "repository": {"url": repo, "branch": branch, "path_to_book": ""},
        "launch_buttons": {"binderhub_url": "https://mybinder.org", "notebook_interface": "jupyterlab"},
        "html": {"use_repository_button": True, "use_edit_page_button": False, "use_issues_button": False},
        "parse": {"myst_enable_extensions": ["dollarmath", "amsmath", "colon_fence", "html_image"]},
        "sphinx": {"config": {
            "mathjax_path": "mathjax/tex-mml-chtml.js",
            # require.js, then where the site keeps the widget modules (ipympl's front end), then
            # the widget manager, which renders every saved widget view from the page's state
            "nb_ipywidgets_js": {"require/require.js": {}, "gm-widgets.js": {}, "widgets/embed-amd.js": {}},
            "nb_mime_priority_overrides": [["html", "image/png", 1], ["html", WIDGET_VIEW, 2]],
            "html_static_path": ["_assets"],
            "suppress_warnings": ["mystnb.unknown_mime_type", "myst.header"],
            "html_show_sourcelink": False,
            "html_css_files": ["gm-site.css"],
            "html_js_files": ["gm-site.js"],
        }},
    }
    (src_dir / "_config.yml").write_text(json.dumps(config, indent=1) + "\n")   # JSON is YAML


def jb_build(src_dir, out):
    cmd = [str(Path(sys.executable).parent / "jupyter-book"), "build", str(src_dir), "--path-output", str(out), "--keep-going"]
    res = subprocess.run(cmd, capture_output=True, text=True)
    (out / "build.log").write_text(res.stdout + res.stderr)
    if res.returncode != 0 or not (out / "_build" / "html" / "index.html").exists():
        raise RuntimeError(f"jupyter-book build failed (see {out / 'build.log'}):\n{res.stdout[-3000:]}{res.stderr[-3000:]}")


# ---- 4. finish -----------------------------------------------------------------------------------

def finish(html_dir, alts, rels):
    static = html_dir / "_static"
    report = {}
    # the course's pages, then the pages Jupyter Book adds (start page, index, search): every page
    # gets the same fixes (the theme's names, one thebe script, no CDN)
    pages = {html_dir / Path(rel).with_suffix(".html"): rel for rel in rels}
    pages.update({p: None for p in sorted(html_dir.glob("*.html")) if p not in pages})
    for page, rel in pages.items():
        if not page.exists():
            continue
        text = page.read_text(encoding="utf-8")
        up = os.path.relpath(static, page.parent).replace(os.sep, "/")
        text = FONT_AWESOME_CDN.sub(f"{up}/font-awesome/css/font-awesome.min.css", text)

        def alt(m):
            tag = m.group(0)
            h = re.search(r'_images/([0-9a-f]{64})\.\w+"', tag)
            if not h or h.group(1) not in alts:
                return tag
            value = alts[h.group(1)].replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")
            tag = re.sub(r'\salt="[^"]*"', "", tag)
            return tag.replace("<img", f'<img alt="{value}"', 1)

        text = re.sub(r"<img\b[^>]*>", alt, text)
        # the theme's search button is named "Search" but shows "Search Ctrl+K" (WCAG 2.5.3): let
        # its visible text be its name
        text = re.sub(r'(<button class="btn search-button-field[^"]*"[^>]*?) aria-label="Search"', r"\1", text)
        # the colour-mode button shows the titles of its icons (Light, Dark, System Settings)
        text = text.replace('theme-switch-button pst-js-only" aria-label="Color mode"',
                            'theme-switch-button pst-js-only" aria-label="Color mode: Light, Dark or System Settings"')
        # sphinx-thebe (part of Jupyter Book, not enabled here) names its CDN script in a constant.
        # (and Jupyter Book writes that script twice, which is a page error: keep one, without the URL).
        thebe = re.compile(r'<script>const THEBE_JS_URL = "[^"]*";.*?</script>\s*', re.S)
        seen = []
        text = thebe.sub(lambda m: "" if seen else (seen.append(1) or re.sub(r'URL = "[^"]*"', 'URL = ""', m.group(0))), text)
        left = sorted({u for attr in re.findall(r'(?:src|href)="([^"]+)"', text) for u in CDN.findall(attr)})
        if left:
            raise RuntimeError(f"{page}: still refers to a CDN: {left[:3]}")
        page.write_text(text, encoding="utf-8")
        images = set(re.findall(r'src="([^"]*_images/[^"]+)"', text))
        size = len(text.encode()) + sum((page.parent / s).stat().st_size for s in images if (page.parent / s).exists())
        if rel is not None:
            report[rel] = {"bytes": size, "html_bytes": len(text.encode()), "images": len(images)}
    return report


def build(out=DEFAULT_OUT, only=None, fresh=False):
    out = Path(out)
    rels = pages(only)
    src = out / "src"
    if src.exists():
        shutil.rmtree(src)
    src.mkdir(parents=True)
    alts, timing = {}, {}
    t0 = time.monotonic()
    for rel in rels:
        nb, secs = execute(rel, src, out / "cache", fresh)
        timing[rel] = round(secs, 1)
        nb = prepare(nb, rel, set(rels))
        for cell in nb.cells:
            for o in cell.get("outputs", []):
                if "image/png" in o.get("data", {}):
                    digest = hashlib.sha256(base64.b64decode(o["data"]["image/png"])).hexdigest()
                    alts[digest] = o["metadata"]["image/png"]["alt"]
        import nbformat
        (src / rel).parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(nb, src / rel)
        print(f"  {rel}: executed in {secs:.0f} s" if secs else f"  {rel}: cached", flush=True)
    t1 = time.monotonic()
    copy_static(src)
    write_book(src, rels)
    jb_build(src, out)
    html = out / "_build" / "html"
    report = finish(html, alts, rels)
    t2 = time.monotonic()
    summary = {"pages": report, "execute_s": round(t1 - t0, 1), "render_s": round(t2 - t1, 1),
               "execute_per_page_s": timing, "largest_page": max(report.values(), key=lambda r: r["bytes"])}
    (out / "report.json").write_text(json.dumps(summary, indent=1) + "\n")
    return html, summary


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python tools/build_site.py", description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT)
    ap.add_argument("--only", nargs="+", help="build only the pages whose path starts with these")
    ap.add_argument("--fresh", action="store_true", help="re-execute every notebook (ignore the cache)")
    args = ap.parse_args(argv)
    html, summary = build(args.out, args.only, args.fresh)
    big = max(summary["pages"].items(), key=lambda kv: kv[1]["bytes"])
    total = sum(f.stat().st_size for f in html.rglob("*") if f.is_file())
    print(f"site: {html / 'index.html'} ({len(summary['pages'])} pages; executed in {summary['execute_s']:.0f} s, "
          f"rendered in {summary['render_s']:.0f} s; largest page {big[0]} {big[1]['bytes'] / 1e6:.2f} MB; "
          f"the whole site {total / 1e6:.1f} MB to publish)")
    over = [p for p, r in summary["pages"].items() if r["bytes"] > 5_000_000]
    if over:
        print(f"site: pages over 5 MB: {over}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""What the student sees in JupyterLab: layout, animations, panel state and the quiet start.

Helpers for tests/browser/test_student_view.py and tools/screenshots.py, on top of browserlab.py:

* :data:`STUDENT_WINDOW` (1366 x 768, a laptop) and :func:`show_file_browser` (the left file
  browser panel open, as after a fresh ``make lab``): the notebook gets what is left, ~930 px of
  output width.
* :func:`layout_problems`: after Run All, every output area whose content overflows it
  (``scrollWidth > clientWidth``), every ipympl canvas or image wider than its output area (or
  scaled down to fit it, which shrinks its text), and every jshtml animation whose ``<img>`` is
  laid out at zero size or never got a frame.
* :func:`kernel_panel_state` / :func:`expected_panel_state`: the values and titles/readouts of
  every Panel bound to a name in the notebook, read from the live kernel after Run All, and from
  a cell-by-cell run of the same notebook in this process (tests/nbfigures.py): they must agree
  (no widget's initial echo from the browser may overwrite a value the notebook set).
* :func:`news_prompt_shown`: whether the "Get notified about official Jupyter news?" toast is up.
"""
from __future__ import annotations

import json
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))  # tests/: nbfigures, figstd

STUDENT_WINDOW = (1366, 768)

# Printed by the kernel (after Run All) and by the cell-by-cell run: JSON of every named Panel.
PANEL_STATE_CODE = r'''
def __gm_panel_state():
    import json, numbers, sys
    # a notebook that never imported the widget layer holds no panel (and an exercise's kernel
    # need not import ipywidgets just to find that out)
    base = sys.modules.get("gm_core.widgets.base")
    out = {}
    for name, obj in list(globals().items()):
        if base is None or name.startswith("_") or not isinstance(obj, base.Panel):
            continue
        vals = {}
        for k, v in obj.values().items():
            vals[k] = round(float(v), 4) if isinstance(v, numbers.Real) and not isinstance(v, bool) else str(v)
        texts = []
        if obj.fig is not None:
            for ax in obj.fig.axes:
                for t in [ax.title, *ax.texts]:
                    if t.get_visible() and t.get_text().strip():
                        texts.append(t.get_text())
        out[name] = {"values": vals, "texts": texts}
    print("GM-PANEL-STATE " + json.dumps(out, sort_keys=True))
__gm_panel_state()
del __gm_panel_state
'''


def parse_panel_state(text: str) -> dict:
    for line in text.splitlines():
        if line.startswith("GM-PANEL-STATE "):
            return json.loads(line[len("GM-PANEL-STATE "):])
    raise ValueError(f"no panel state in the output: {text[-500:]!r}")


def expected_panel_state(path: Path) -> dict:
    """The named panels' state after this run's one execution of ``path``, cell by cell in a
    kernel of its own (tests/nbrun.py; its epilogue is :data:`PANEL_STATE_CODE`)."""
    import nbrun

    rec = nbrun.record(path)
    if rec["errors"] or not rec["complete"]:
        raise AssertionError("the cell-by-cell run failed: " + "; ".join(rec["errors"] or ["it did not finish"]))
    return parse_panel_state(rec["epilogue"]["stdout"])


_KERNEL_EXEC_JS = r"""
async ([id, code]) => {
  const app = window.jupyterapp;
  const w = [...app.shell.widgets('main')].find(w => w.id === id);
  const k = w && w.sessionContext.session && w.sessionContext.session.kernel;
  if (!k) return 'ERROR no kernel';
  const fut = k.requestExecute({code, silent: false, store_history: false});
  let out = '';
  fut.onIOPub = (msg) => {
    const t = msg.header.msg_type, c = msg.content;
    if (t === 'stream') out += c.text;
    if (t === 'error') out += `ERROR ${c.ename}: ${c.evalue}\n`;
  };
  await fut.done;
  return out;
}
"""


def kernel_exec(nbp, code: str) -> str:
    """Run ``code`` in the notebook's kernel (not in a cell: no execution count); its stdout."""
    return nbp.page.evaluate(_KERNEL_EXEC_JS, [nbp.read_status()["panelId"], code])


def kernel_panel_state(nbp) -> dict:
    out = kernel_exec(nbp, PANEL_STATE_CODE)
    if "ERROR" in out and "GM-PANEL-STATE" not in out:
        nbp.fail(f"reading the panels' state from the kernel failed: {out[-800:]}")
    return parse_panel_state(out)


def compare_panel_states(live: dict, expected: dict, atol: float = 0.011) -> list[str]:
    """Differences between the kernel's panel state and the cell-by-cell one, one line each."""
    out = []
    for name in sorted(set(live) | set(expected)):
        a, b = live.get(name), expected.get(name)
        if a is None or b is None:
            out.append(f"panel {name!r} exists only {'cell by cell' if a is None else 'after Run All'}")
            continue
        for k in sorted(set(a["values"]) | set(b["values"])):
            va, vb = a["values"].get(k), b["values"].get(k)
            same = (isinstance(va, float) and isinstance(vb, float) and abs(va - vb) <= atol) or va == vb
            if not same:
                out.append(f"{name}.{k} = {va} after Run All, {vb} cell by cell")
        if a["texts"] != b["texts"]:
            out.append(f"{name}'s titles/readouts after Run All {a['texts']} != cell by cell {b['texts']}")
    return out


_SHOW_FILE_BROWSER_JS = r"""
async () => {
  const app = window.jupyterapp;
  await app.commands.execute('filebrowser:activate');
  if (app.shell.leftCollapsed) app.shell.expandLeft();
  const fb = document.getElementById('filebrowser');
  const r = fb ? fb.getBoundingClientRect() : null;
  return r ? {width: r.width, height: r.height} : null;
}
"""


def show_file_browser(page) -> dict | None:
    """Open the left sidebar on the file browser (the state a student starts in)."""
    return page.evaluate(_SHOW_FILE_BROWSER_JS)


_LAYOUT_JS = r"""
(id) => {
  const root = document.getElementById(id);
  const problems = [], info = {outputs: 0, canvases: 0, images: 0, animations: 0, minWidth: null};
  if (!root) return {problems: ['notebook panel not in the DOM'], info};
  const cells = [...root.querySelectorAll('.jp-Cell')];
  let ncode = 0;
  const inNum = new Map();
  for (const c of cells) if (c.classList.contains('jp-CodeCell')) inNum.set(c, ++ncode);
  const where = (el) => {
    const cell = el.closest('.jp-Cell');
    return cell ? `In[${inNum.get(cell) || '?'}] (cell ${cells.indexOf(cell)})` : '(no cell)';
  };
  const px = (x) => Math.round(x);
  for (const out of root.querySelectorAll('.jp-OutputArea-output')) {
    info.outputs++;
    const w = out.clientWidth;
    if (w === 0) continue;  // collapsed / hidden output
    info.minWidth = info.minWidth === null ? w : Math.min(info.minWidth, w);
    if (out.scrollWidth > w + 1)
      problems.push(`${where(out)}: output overflows its area (content ${out.scrollWidth} px > ${w} px visible)`);
    const box = out.getBoundingClientRect();
    const media = [...out.querySelectorAll('canvas, img')];
    for (const m of media) {
      const r = m.getBoundingClientRect();
      const isAnim = m.tagName === 'IMG' && /^_anim_img/.test(m.id || '');
      if (m.tagName === 'CANVAS') {
        if (m.classList.contains('jupyter-widgets') === false && m.closest('.jupyter-matplotlib') === null) continue;
        info.canvases++;
      } else if (isAnim) info.animations++;
      else info.images++;
      if (isAnim && (r.width < 1 || r.height < 1 || !m.naturalWidth))
        problems.push(`${where(out)}: animation image is ${px(r.width)} x ${px(r.height)} px laid out` +
                      ` (natural ${m.naturalWidth} x ${m.naturalHeight}): the student sees no picture`);
      const natural = m.tagName === 'IMG' ? Number(m.getAttribute('width')) || m.naturalWidth : 0;
      if (natural > w + 1 && r.width <= w + 1)
        problems.push(`${where(out)}: ${isAnim ? 'animation image' : 'image'} is ${natural} px wide, shown` +
                      ` scaled down to ${px(r.width)} px to fit its output area (${w} px): its text shrinks`);
      if (r.width > w + 1 || r.right > box.right + 1)
        problems.push(`${where(out)}: ${isAnim ? 'animation image' : m.tagName.toLowerCase()} is ${px(r.width)} px wide,` +
                      ` its output area ${w} px (right edge ${px(r.right)} > ${px(box.right)})`);
    }
  }
  return {problems: [...new Set(problems)], info};
}
"""


def layout_problems(nbp) -> tuple[list[str], dict]:
    """(problems, counts) of the open notebook's outputs as laid out now (see module doc)."""
    res = nbp.page.evaluate(_LAYOUT_JS, nbp.read_status()["panelId"])
    return res["problems"], res["info"]


_IMAGES_LOADING_JS = r"""
(id) => {
  const root = document.getElementById(id);
  return root ? [...root.querySelectorAll('.jp-OutputArea-output img')].filter(i => !i.complete).length : 0;
}
"""


def settled_layout(nbp, still: float = 0.5, timeout: float = 20.0) -> tuple[list[str], dict]:
    """:func:`layout_problems` once the outputs have finished laying out: every image loaded and
    the same result for ``still`` s (after Run All the last outputs are still being rendered)."""
    deadline = time.monotonic() + timeout
    last, since = None, time.monotonic()
    while True:
        panel_id = nbp.read_status()["panelId"]
        res = layout_problems(nbp)
        loading = nbp.page.evaluate(_IMAGES_LOADING_JS, panel_id)
        if res != last or loading:
            last, since = res, time.monotonic()
        elif time.monotonic() - since >= still:
            return res
        if time.monotonic() > deadline:
            return res   # still changing: judged as it is now (the problems say what is wrong)
        nbp.page.wait_for_timeout(100)


_NEWS_JS = r"""
() => {
  const texts = [...document.querySelectorAll('.Toastify__toast, .jp-Notification-Toast, .jp-toast-message, .jp-Dialog')]
    .map(e => e.innerText || '');
  const body = document.body ? document.body.innerText : '';
  return texts.filter(t => /jupyter news/i.test(t)).concat(/official Jupyter news/i.test(body) ? ['(page text)'] : []);
}
"""


def news_prompt_shown(page) -> list[str]:
    """Texts of any visible "official Jupyter news" prompt (empty: none)."""
    return page.evaluate(_NEWS_JS)


def figure_notebooks(root: Path = HERE.parents[1], exclude=()) -> list[Path]:
    """Every notebook of book/, exercises/, solutions/ that draws (``%matplotlib`` in a code cell),
    except ``exclude``: found on disk when pytest collects, so new notebooks are covered."""
    out = []
    for d in ("book", "exercises", "solutions"):
        for path in sorted((root / d).glob("*.ipynb")):
            if path in exclude:
                continue
            try:
                nb = json.loads(path.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                continue
            srcs = ("".join(c.get("source", "")) if isinstance(c.get("source"), list) else c.get("source", "")
                    for c in nb.get("cells", []) if c.get("cell_type") == "code")
            if any("%matplotlib" in s for s in srcs):
                out.append(path)
    return out


LAYOUT_SELFCHECK_PATH = "_browser_selfcheck/layout.ipynb"


def layout_selfcheck_notebook() -> dict:
    """A notebook with one breach of each kind :func:`layout_problems` must find, and a good
    figure: In[2] a 1200 px ipympl canvas, In[3] an animation image that never gets a frame,
    In[4] an HTML block wider than the output area, In[5] a 500 px canvas (fine), In[6] a
    1200 px PNG (as %matplotlib inline shows a figure) that the output area scales down."""
    def code(i, src):
        return {"cell_type": "code", "execution_count": None, "id": f"layout-{i}", "metadata": {},
                "outputs": [], "source": src}
    cells = [
        code(1, "%matplotlib widget\nimport matplotlib.pyplot as plt\nfrom IPython.display import HTML\n"
                "def canvas(width_in):\n"
                "    with plt.ioff():\n"
                "        fig, ax = plt.subplots(figsize=(width_in, 2))\n"
                "    ax.plot([0, 1], [0, 1])\n"
                "    return fig.canvas\n"),
        code(2, "canvas(12)"),
        code(3, "HTML('<div class=\"animation\"><img id=\"_anim_imgselfcheck\"></div>')"),
        code(4, "HTML('<div style=\"width: 1500px; background: #eee\">a block wider than the notebook</div>')"),
        code(5, "canvas(5)"),
        code(6, "import io\nfrom IPython.display import Image\n"
                "with plt.ioff():\n"
                "    fig, ax = plt.subplots(figsize=(12, 2), dpi=100)\n"
                "buf = io.BytesIO()\nfig.savefig(buf, format='png')\nplt.close(fig)\n"
                "Image(buf.getvalue())"),
    ]
    return {"cells": cells, "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python",
                                                        "name": "python3"}},
            "nbformat": 4, "nbformat_minor": 5}

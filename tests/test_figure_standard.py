"""Every figure of the course meets the figure standard (CONTRIBUTING.md; issue #12 point 1).

* ``test_checker_*``: the checker (tests/figstd.py) finds each kind of breach on a synthetic bad
  figure, and passes a good one, so a green run means something.
* ``test_panel_initial_state``: every registered Panel (gm_core.widgets.base.all_panels()) as it
  first appears.
* ``test_notebook_figures``: every notebook of book/, exercises/ and solutions/, from the record of
  its one execution in this run (tests/nbrun.py, tests/nbrecord.py): each figure after the
  cell that made it and in its final state, and every frame of every animation shown through
  ``to_jshtml``, measured in the notebook's kernel. One test per notebook, so a failure names the
  notebook; each message names the cell (``In[k]``, as numbered by Run All), the figure and the
  text. Run alone, this file has the notebooks executed as it reads them.
* ``test_notebook_runner_catches_animation_frames`` / ``test_kernel_recorder_*``: the in-process
  runner and the notebook's kernel both see every frame of an animation, on a generated notebook.

``python tests/test_figure_standard.py`` writes the current list of breaches (build/breaches.txt, git-ignored).
"""
from __future__ import annotations

import functools
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.animation import FuncAnimation  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
import figstd  # noqa: E402
import nbfigures  # noqa: E402
import nbrun  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = nbfigures.course_notebooks()


def _good():
    fig, ax = plt.subplots(figsize=(6, 4), dpi=100, layout="constrained")
    ax.plot([0, 1], [0, 1])
    ax.set(xlabel="time t", ylabel="angle θ", title="a good figure")
    ax.text(0.05, 0.9, "θ = 0.80", transform=ax.transAxes)
    ax.quiver([0.2, 0.5, 0.8], [0.5, 0.5, 0.5], [0.1, 0.2, 0.0], [0.0, 0.1, 0.1], angles="xy",
              scale_units="xy", scale=1)
    ax.quiver([0.5, 0.5], [0.2, 0.2], [0.05, 0.0], [0.0, 0.05])  # a small frame: not a field
    return fig, ax


def _kinds(messages):
    return " | ".join(messages)


# -- the checker ------------------------------------------------------------------------------
def test_checker_measures_texts_where_a_real_draw_puts_them_and_draws_no_pixel():
    """The checker's renderer rasterises nothing, yet it sees the texts a real Agg draw draws,
    at the same places (one-line, several-line, mathtext, rotated, 3D and tick labels)."""
    fig = plt.figure(figsize=(7, 4), dpi=100, layout="constrained")
    ax = fig.add_subplot(1, 2, 1)
    ax.plot([0, 1], [0, 2])
    ax.imshow(np.random.default_rng(0).random((4, 4)), extent=(0, 1, 0, 2), aspect="auto")
    ax.set(title=r"$\dot g = g\,\xi$", xlabel="time t\nin seconds", ylabel="angle θ")
    ax.text(0.1, 1.5, "rotated", rotation=30)
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    ax3.text(0.2, 0.3, 0.4, "in 3D")
    renderer = figstd._draw(fig)
    assert not np.asarray(renderer.buffer_rgba())[..., 3].any(), "the checker's renderer put pixels down"
    fig.canvas.draw()    # a real draw: Agg rasterises, and each text is where this draw puts it
    real = fig.canvas.get_renderer()
    seen = {id(t): bb for t, bb in renderer.texts}
    drawn = [t for t in fig.findobj(plt.Text) if t.get_visible() and t.get_text().strip()
             and t.get_window_extent(real).width > 0 and id(t) in seen
             and (t.axes is not ax3 or t.get_text() == "in 3D")]   # (not the 3D axes' tick labels)
    assert {"rotated", "in 3D", "angle θ", "time t\nin seconds", r"$\dot g = g\,\xi$"} <= {t.get_text() for t in drawn}
    for t in drawn:
        if t.axes is ax3:   # a 3D text is at its projected place only while drawn: in its axes
            box, where = seen[id(t)], ax3.get_window_extent(real)
            assert where.x0 <= box.x0 and box.x1 <= where.x1 and where.y0 <= box.y0 and box.y1 <= where.y1, t
        else:
            np.testing.assert_allclose(seen[id(t)].bounds, t.get_window_extent(real).bounds, atol=0.5,
                                       err_msg=repr(t.get_text()))
    plt.close(fig)


def test_checker_passes_a_good_figure():
    fig, _ = _good()
    assert figstd.check_figure(fig, "good") == []


def test_checker_finds_a_figure_too_wide():
    fig, _ = _good()
    fig.set_size_inches(9.5, 4)
    msgs = figstd.check_figure(fig, "wide")
    assert len(msgs) == 1 and "950 px wide" in msgs[0] and msgs[0].startswith("wide: figure 'a good figure'")


def test_checker_finds_small_text():
    fig, ax = _good()
    ax.set_xlabel("time t", fontsize=6)  # 8.3 px at 100 dpi
    msgs = figstd.check_figure(fig)
    assert len(msgs) == 1 and "x-axis label 'time t' is 8.3 px" in msgs[0], _kinds(msgs)


def test_checker_finds_text_cut_by_the_figure_edge():
    fig, ax = _good()
    fig.text(0.97, 0.5, "cut off here")
    msgs = figstd.check_figure(fig)
    assert len(msgs) == 1 and "'cut off here' is cut by the figure edge (right by" in msgs[0], _kinds(msgs)


def test_checker_sees_multiline_and_math_texts():
    fig, ax = _good()
    ax.set_title("torus $\\mathbb{T}^2$\n(both pairs of edges glued)", fontsize=6)
    msgs = figstd.check_figure(fig)
    # one message, for the whole two-line title (matplotlib hands the renderer no artist for it),
    # naming the size of its smallest glyph: the superscript 2 at 0.7 x 6 pt = 5.8 px
    assert [m for m in msgs if "is 5.8 px in its smallest mathtext script" in m and "title 'torus $" in m
            and "(both pairs of edg" in m], _kinds(msgs)


def test_checker_measures_mathtext_scripts():
    """A sub- or superscript is drawn at 0.7 of its text's size: at 9 pt the subscripts of
    $T_gL_h$ are 8.75 px, below the standard, although the text's own size (12.5 px) is not; at
    MATH_PT they pass; a script of a script (0.49) fails even there. Text and PathText alike."""
    from gm_core.drawing.toolkit import MATH_PT, PathText

    fig, ax = _good()
    ax.set_xlabel("the lift $T_gL_h$", fontsize=9)
    msgs = figstd.check_figure(fig)
    assert len(msgs) == 1 and "x-axis label 'the lift $T_gL_h$' is 8.8 px in its smallest mathtext script" in msgs[0], \
        _kinds(msgs)
    ax.set_xlabel("the lift $T_gL_h$", fontsize=MATH_PT)
    assert figstd.check_figure(fig) == []
    ax.set_xlabel("time t  (12 $ and 5 $: no formula)", fontsize=8)   # two dollar signs, escaped: plain text
    ax.xaxis.label.set_text(r"time t  (12 \$ and 5 \$: no formula)")
    assert figstd.check_figure(fig) == []
    PathText(ax, 0.05, 0.5, r"$T_gR_{g^{-1}}$", size=MATH_PT, coords="axes")
    PathText(ax, 0.05, 0.3, r"$\xi^s$ readout", size=8, coords="axes")
    msgs = figstd.check_figure(fig)
    assert any("readout '$T_gR_{g^{-1}}$' is 7.1 px in its smallest mathtext script" in m for m in msgs), _kinds(msgs)
    assert any(r"readout '$\\xi^s$ readout' is 7.8 px in its smallest mathtext script" in m for m in msgs), _kinds(msgs)
    assert len(msgs) == 2, _kinds(msgs)


def test_checker_finds_overlapping_texts():
    fig, ax = _good()
    ax.set_ylabel("a long label " * 6)  # the y label cannot fit beside the axes: it crosses the tick labels
    fig.set_layout_engine("none")
    ax.set_title("title one")
    fig.text(0.5, 0.885, "title two", ha="center")  # on top of the axes title
    msgs = figstd.check_figure(fig)
    assert any("title 'title one' overlaps text 'title two'" in m for m in msgs), _kinds(msgs)


def test_checker_finds_tick_labels_meeting_at_a_corner():
    fig, ax = plt.subplots(figsize=(3, 3), dpi=100)
    ax.set(xlim=(-1000, 1000), ylim=(-1000, 1000))
    ax.tick_params(axis="y", pad=-30)  # y tick labels pushed onto the x tick labels at the corner
    ax.tick_params(axis="x", pad=-12)
    msgs = figstd.check_figure(fig)
    assert any("y tick label" in m and "overlaps" in m and "x tick label" in m for m in msgs), _kinds(msgs)


def test_checker_finds_an_axis_label_in_the_row_of_its_tick_labels():
    fig, ax = _good()
    ax.set_xlabel("longitude λ", labelpad=-14)  # pulled up into the tick labels' row: "0  longitude λ"
    ax.xaxis.set_label_coords(0.62, -0.03)
    msgs = figstd.check_figure(fig)
    assert any("x-axis label 'longitude λ' sits in the row of its tick labels" in m for m in msgs), _kinds(msgs)


def test_checker_finds_a_readout_running_past_its_axes():
    fig, ax = _good()
    ax.text(0.9, 0.5, "θ = 3.14159 rad, long readout", transform=ax.transAxes)
    msgs = figstd.check_figure(fig)
    assert any("readout 'θ = 3.14159 rad, long readout' runs past its axes (right by" in m for m in msgs), \
        _kinds(msgs)


def test_checker_leaves_captions_outside_the_axes_to_the_other_rules():
    fig, ax = _good()
    ax.text(0.5, -0.2, "a caption below the axes", transform=ax.transAxes, ha="center", va="top")
    assert figstd.check_figure(fig) == []


def test_checker_measures_glyph_outline_texts():
    """gm_core.drawing.toolkit.PathText draws text as paths: it is measured like a Text."""
    from gm_core.drawing.toolkit import PathText

    fig, ax = _good()
    PathText(ax, 0.8, 0.5, "a long PathText readout", size=10, coords="axes")
    PathText(ax, 0.02, 0.9, "θ = 0.80", size=10, coords="axes")  # on top of the Text readout
    msgs = figstd.check_figure(fig)
    assert any("readout 'a long PathText readout' runs past its axes (right by" in m for m in msgs), _kinds(msgs)
    assert any("overlaps readout 'θ = 0.80'" in m for m in msgs), _kinds(msgs)


def test_checker_finds_arrows_too_short_to_show_direction():
    fig, ax = _good()
    x, y = np.meshgrid(np.linspace(0, 1, 30), np.linspace(0, 1, 30))
    ax.quiver(x, y, np.ones_like(x), np.zeros_like(y))  # autoscaled: each arrow a few px
    msgs = figstd.check_figure(fig)
    assert len(msgs) == 1 and "vector field 2 of 2 (900 arrows): longest arrow" in msgs[0], _kinds(msgs)
    longest = float(msgs[0].split("longest arrow ")[1].split(" px")[0])
    assert 0 < longest < figstd.MIN_ARROW_PX


def test_checker_leaves_a_field_at_rest_with_masked_arrows_alone():
    """A field zero wherever it is defined, masked elsewhere, is at rest: no direction to judge.
    matplotlib fills a masked arrow's U, V with 1 (the mask lives in ``Quiver.Umask``), so the
    checker must not read those fillers as arrows; a nonzero field with masked arrows is still judged."""
    fig, ax = _good()
    x, y = np.meshgrid(np.linspace(0.1, 0.9, 5), np.linspace(0.1, 0.9, 5))
    U = np.ma.array(np.zeros_like(x), mask=np.eye(5, dtype=bool))
    q = ax.quiver(x, y, U, U.copy(), angles="xy", scale_units="xy", scale=1)
    assert np.asarray(q.Umask).any() and np.max(q.U) == 1.0  # the fillers the checker must skip
    assert figstd.check_figure(fig) == []
    q.set_UVC(np.ma.array(np.full_like(x, 0.01), mask=np.eye(5, dtype=bool)), U)  # ~2 px arrows
    msgs = figstd.check_figure(fig)
    assert any("vector field 2 of 2 (25 arrows): longest arrow" in m for m in msgs), _kinds(msgs)


def test_checker_measures_arrow_sets_marked_for_it():
    """A PolyCollection of arrows (toolkit.ArrowSet) is a field once marked ``gm_arrow_set``."""
    from gm_core.drawing.toolkit import ArrowSet

    fig, ax = _good()
    ax.set_aspect("equal")
    arrows = ArrowSet(ax, n=4)
    arrows.set([[0.2, 0.2], [0.4, 0.2], [0.6, 0.2], [0.8, 0.2]], [[0.01, 0.0]] * 4)  # ~3 px each
    arrows.poly.gm_arrow_set = arrows
    msgs = figstd.check_figure(fig)
    assert any("(4 arrows): longest arrow" in m and "direction unreadable" in m for m in msgs), _kinds(msgs)
    arrows.set([[0.2, 0.2], [0.4, 0.2], [0.6, 0.2], [0.8, 0.2]], [[0.15, 0.0]] * 4)
    assert figstd.check_figure(fig) == []


def test_checker_ignores_texts_that_are_not_drawn():
    fig, ax = _good()
    ax.set_xlim(0, 1)
    hidden = ax.text(0.5, 0.5, "x" * 200)
    hidden.set_visible(False)
    ax.text(0.5, 0.5, "   ")
    assert figstd.check_figure(fig) == []


def test_checker_measures_3d_texts_where_they_are_drawn():
    fig = plt.figure(figsize=(5, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    ax.text(0.0, 0.0, 0.0, "origin")
    msgs = [m for m in figstd.check_figure(fig) if "'origin'" in m]
    assert msgs == [], _kinds(msgs)


def test_frame_checker_checks_every_animation_frame():
    fig, ax = _good()
    label = ax.text(0.05, 0.8, "frame", transform=ax.transAxes)

    def update(k):
        label.set_fontsize(12 if k < 2 else 5)  # small from frame 2 on

    anim = FuncAnimation(fig, update, frames=4)
    checker = figstd.FrameChecker("anim")
    anim.save("unused", writer=checker)
    assert checker.frames == 4
    assert len(checker.breaches) == 1 and checker.breaches[0].startswith("anim frame 2: ") \
        and "readout 'frame' is 6.9 px" in checker.breaches[0], checker.breaches


def test_notebook_runner_catches_animation_frames(tmp_path):
    import nbformat

    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(
        "%matplotlib widget\n"
        "import matplotlib.pyplot as plt\n"
        "from matplotlib.animation import FuncAnimation\n"
        "fig, ax = plt.subplots(figsize=(10, 3))\n"
        "t = ax.set_title('tiny', fontsize=5)\n"
        "anim = FuncAnimation(fig, lambda k: None, frames=3)\n"
        "html = anim.to_jshtml()\n"
        "plt.close(fig)\n"),
        # any other movie writer (the course's player keeps PNG frames through one) is seen too
        nbformat.v4.new_code_cell(
        "from matplotlib.animation import AbstractMovieWriter\n"
        "class Keep(AbstractMovieWriter):\n"
        "    def setup(self, fig, outfile, dpi=None):\n"
        "        super().setup(fig, outfile, dpi=dpi)\n"
        "    def grab_frame(self, **kw):\n"
        "        pass\n"
        "    def finish(self):\n"
        "        pass\n"
        "fig2, ax2 = plt.subplots(figsize=(4, 3))\n"
        "ax2.set_xlabel('small', fontsize=6)\n"
        "FuncAnimation(fig2, lambda k: None, frames=2).save('kept', writer=Keep(fps=5))\n"
        "plt.close(fig2)\n")]
    path = tmp_path / "anim.ipynb"
    nbformat.write(nb, path)
    res = nbfigures.run_notebook(path, root=tmp_path)
    assert res.errors == [] and res.animations == 2 and res.figures == 0
    text = _kinds(res.breaches)
    assert "anim.ipynb In[1] animation frame 0: figure 'tiny': 1000 px wide" in text
    assert "title 'tiny' is 6.9 px" in text
    assert "anim.ipynb In[2] animation frame 0: " in text and "x-axis label 'small' is 8.3 px" in text


@nbrun.SELFCHECK
def test_kernel_recorder_catches_animation_frames(selfcheck_records):
    """The same notebook executed in a kernel, as the course's are: the recorder there sees every frame too."""
    res = selfcheck_records["anim.ipynb"]
    assert res["host"] == "kernel" and res["complete"] and res["errors"] == []
    assert res["animations"] == 1 and res["figures"] == 0
    text = _kinds(res["breaches"])
    assert "anim.ipynb In[1] animation frame 0: figure 'tiny': 1000 px wide" in text
    assert "title 'tiny' is 6.9 px" in text


_FRESH_SHELL = r"""
import json, sys
sys.path.insert(0, {tests!r})
from pathlib import Path
from IPython.core.interactiveshell import InteractiveShell
import nbrecord
shell = InteractiveShell.instance()
out = {{}}
for name, cells in (("quiet", ["x = 1 + 1\n", "print(x)\n"]),
                    ("anim", ["import matplotlib\nmatplotlib.use('Agg')\n"
                              "from matplotlib.animation import FuncAnimation\n"
                              "import matplotlib.pyplot as plt\n"
                              "fig, ax = plt.subplots(figsize=(10, 3))\n"
                              "t = ax.set_title('tiny', fontsize=5)\n"
                              "html = FuncAnimation(fig, lambda k: None, frames=3).to_jshtml()\n",
                              "fig2, ax2 = plt.subplots(figsize=(4, 3))\n"])):
    nb = {{"cells": [{{"cell_type": "code", "source": c, "metadata": {{}}}} for c in cells]}}
    path = Path({tmp!r}) / (name + ".ipynb")
    path.write_text(json.dumps(nb))
    rec = nbrecord.Recorder(shell, path, name, "in-process", match_cells=False)
    loaded = "matplotlib" in sys.modules
    for k, src, _ in rec.cells:
        rec.begin_cell(k)
        shell.run_cell(src, store_history=False)   # (silent=True would skip the cell events)
    r = rec.finish()
    out[name] = {{"loaded_by_recorder": loaded, "loaded_after": "matplotlib" in sys.modules,
                  "figures": r["figures"], "animations": r["animations"], "breaches": r["breaches"],
                  "errors": r["errors"], "finders": sum(type(f).__name__ == "_AfterImport" for f in sys.meta_path)}}
print(json.dumps(out))
"""


def test_recorder_loads_matplotlib_only_with_the_notebook_and_still_sees_every_animation(tmp_path):
    """In a fresh process, as in a notebook's kernel: recording a notebook that never uses matplotlib
    does not import it, and an animation saved in the very cell that first imports
    matplotlib.animation is still caught frame by frame (the save is wrapped on import)."""
    import json
    import subprocess

    code = _FRESH_SHELL.format(tests=str(ROOT / "tests"), tmp=str(tmp_path))
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=tmp_path)
    assert res.returncode == 0, res.stderr[-3000:]
    out = json.loads(res.stdout.strip().splitlines()[-1])
    quiet, anim = out["quiet"], out["anim"]
    assert not quiet["loaded_by_recorder"] and not quiet["loaded_after"], quiet
    assert quiet["figures"] == quiet["animations"] == 0 and quiet["errors"] == [] and quiet["finders"] == 0
    assert not anim["loaded_by_recorder"] and anim["errors"] == [] and anim["finders"] == 0, anim
    assert anim["animations"] == 1 and anim["figures"] == 2, anim
    text = _kinds(anim["breaches"])
    assert "anim In[1] animation frame 0: figure 'tiny': 1000 px wide" in text, text
    assert "title 'tiny' is 6.9 px" in text


# -- the course -------------------------------------------------------------------------------

def _panels():
    from gm_core.widgets.base import all_panels

    return sorted(all_panels().items())


PANELS = _panels()


@pytest.fixture(scope="module", autouse=True)
def _forget_fresh_panels():
    yield
    _fresh.cache_clear()


@functools.cache
def _fresh(cls):
    """One panel of ``cls`` as built, for the two tests below that only look at it (its figure
    as first drawn, its words): built once per test process, not once per test."""
    return cls()


@pytest.mark.parametrize("name,cls", PANELS, ids=[n for n, _ in PANELS])
def test_panel_initial_state(name, cls):
    panel = _fresh(cls)
    assert panel.fig is not None, f"{name} has no figure"
    msgs = figstd.check_figure(panel.fig, f"panel {name}")
    assert not msgs, f"{len(msgs)} breaches of the figure standard:\n  " + "\n  ".join(msgs)


@pytest.mark.parametrize("name,cls", PANELS, ids=[n for n, _ in PANELS])
def test_panel_words_have_no_raw_formula(name, cls):
    """A panel's title and its controls' labels are HTML (no MathJax in a slider's label): a
    formula there is Unicode or <sub>/<sup>, never ``ξ_β`` or ``p_y`` (issue 19 point 5)."""
    import re

    panel = _fresh(cls)
    words = [("title", re.sub(r"<[^>]+>", "", panel.title or ""))]
    for key, c in panel.controls.items():
        words.append((f"control {key!r}", (getattr(c, "description", "") or "") + " " + (getattr(c, "tooltip", "") or "")))
    bad = [f"{what}: {text.strip()!r} holds {figstd.raw_formula(text)!r}" for what, text in words
           if figstd.raw_formula(text) or "$" in text]
    # a symbol spelled out ("alpha1", "delta rate") where the prose and the other panels write α₁, δ
    spelled = re.compile(r"\b(alpha|beta|gamma|delta|theta|xi|psi|phi|omega|tau)(\d*|_\w*)\b", re.IGNORECASE)
    bad += [f"{what}: {text.strip()!r} spells out {m.group(0)!r}" for what, text in words
            if (m := spelled.search(text))]
    plt.close("all")
    assert not bad, f"{name}: raw formula markup in its words:\n  " + "\n  ".join(bad)


def test_raw_formula_markup_is_found_in_figures_and_words():
    fig, ax = _good()
    ax.set_title("the tangent line T_pS¹")
    msgs = figstd.check_figure(fig)
    assert len(msgs) == 1 and "holds raw formula markup 'T_p' outside $...$" in msgs[0], _kinds(msgs)
    ax.set_title(r"the tangent line $T_p\mathbb{S}^1$", fontsize=11)
    assert figstd.check_figure(fig) == []
    assert [figstd.raw_formula(t) for t in ("Ad_g ξ", "ξ^ g", "g_{a,b}", "body_velocity", "$x_1$", "hg = (1, 2)")] \
        == ["Ad_g", "^", "g_{", None, None, None]


@pytest.mark.parametrize("path", nbrun.params(NOTEBOOKS))
def test_notebook_figures(path, notebook_record):
    res = nbfigures.NotebookFigures.from_record(notebook_record(path))
    assert not res.errors, "cells failed, so not every figure was drawn:\n  " + "\n  ".join(res.errors)
    assert notebook_record(path)["complete"], f"{res.path}: its execution did not reach the end"
    assert not res.breaches, (f"{len(res.breaches)} breaches of the figure standard in {res.path} "
                              f"({res.figures} figures, {res.animations} animations):\n  "
                              + "\n  ".join(res.breaches))


def write_report(out: Path) -> int:
    """Write every current breach (panels, then notebooks) to ``out``; returns how many."""
    lines, n = [], 0
    for name, cls in PANELS:
        msgs = figstd.check_figure(cls().fig, f"panel {name}")
        plt.close("all")
        n += len(msgs)
        lines += msgs
    for nb in NOTEBOOKS:
        res = nbfigures.run_notebook(nb)
        n += len(res.breaches) + len(res.errors)
        lines += res.errors + res.breaches
    head = [f"# Breaches of the figure standard: {n} (tests/test_figure_standard.py; "
            "regenerate with `python tests/test_figure_standard.py`)", ""]
    out.write_text("\n".join(head + lines) + "\n", encoding="utf-8")
    return n


if __name__ == "__main__":
    import os

    os.environ.setdefault("GM_COURSE_TESTING", "1")
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build" / "breaches.txt"
    target.parent.mkdir(parents=True, exist_ok=True)
    print(f"{write_report(target)} breaches -> {target}")

"""ipywidgets front ends for the checkers: multiple choice, the slide rule (1.5), progress.

Imported only when a widget is asked for, so ``import gm_core.checks`` stays ipywidgets-free. The
slide rule of exercise 1.5 is the course's drawing (:class:`gm_core.drawing.groups.SlideRuleScene`).
"""
from __future__ import annotations

import contextlib
import html
import io
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from gm_core.checks.display import COLORS, progress_table_html
from gm_core.checks.exercise import progress
from gm_core.checks.store import Notice, pending_updates

if TYPE_CHECKING:
    import ipywidgets

    from gm_core.checks.choice import ChoicePart


def choice_widget(part: ChoicePart) -> ipywidgets.VBox:
    """RadioButtons with the options, a Check button and a feedback line; records progress."""
    import ipywidgets as W

    options = [(f"({k}) {text}", k) for k, text in part.options.items()]
    radio = W.RadioButtons(options=options, value=None, layout=W.Layout(width="auto"))
    button = W.Button(description="Check", button_style="primary")
    out = W.HTML()

    def on_click(_: object) -> None:
        v = part.check(radio.value, quiet=True)
        color = COLORS.get(v.status, "#6e7781")
        out.value = f'<span style="color:{color}"><b>{v.status}</b>: {html.escape(v.message)}</span>'

    button.on_click(on_click)
    box = W.VBox([W.HTML(f"<b>{html.escape(part.prompt)}</b>"), radio, button, out])
    box.radio, box.button, box.feedback = radio, button, out  # handles for tests
    return box


# ------------------------------------------------------------------------------ slide rule
def slide_rule(a: float = 2.0, b: float = 3.0) -> ipywidgets.VBox:
    """Two log scales sliding past each other: set a (slide) and b (cursor), read a*b on D.

    The picture is the course's one slide rule, :class:`gm_core.drawing.groups.SlideRuleScene`,
    rendered to a PNG on every change, so it moves under any matplotlib backend (the exercise
    notebook has no ``%matplotlib widget``). ``box.scene`` is the scene, ``box.view`` the image.
    """
    import io

    import ipywidgets as W
    import matplotlib.pyplot as plt

    from gm_core.drawing.groups import SlideRuleScene

    scene = SlideRuleScene()
    plt.close(scene.fig)   # rendered into the image below, never shown as a figure of its own
    # Linear sliders on 1..10 in steps of 0.01: the values a student types or drags to (2, 3, 2.5)
    # are exact, so the rule reads 2 x 3 = 6 (a log-spaced slider rounds 2 to 10**0.301 = 1.9999).
    sa = W.FloatSlider(value=a, min=1.0, max=10.0, step=0.01, description="a (slide)",
                       readout_format=".2f", continuous_update=True)
    sb = W.FloatSlider(value=b, min=1.0, max=10.0, step=0.01, description="b (cursor)",
                       readout_format=".2f", continuous_update=True)
    view = W.Image(format="png")
    text = W.HTML()

    def update(*_: object) -> None:
        scene.set(a=sa.value, b=sb.value)
        png = io.BytesIO()
        scene.fig.savefig(png, format="png")
        view.value = png.getvalue()
        text.value = (f"Slide shifted by log10(a) = {np.log10(sa.value):.4f} of a decade; cursor "
                      f"at a further log10(b) = {np.log10(sb.value):.4f}. D reads "
                      f"<b>{scene.reading:.4g}</b> (a &times; b = {sa.value * sb.value:.4g}).")

    sa.observe(update, "value")
    sb.observe(update, "value")
    update()
    box = W.VBox([W.HTML("<b>Slide rule</b>: the blue scale is C, its thick line starts at its "
                         "index (its 1); the red line is the cursor."), view, sa, sb, text])
    box.sliders = (sa, sb)
    box.view, box.readout, box.scene = view, text, scene
    return box


# ------------------------------------------------------------------------------ progress
def updates_html(pending: Sequence[Notice]) -> str:
    """An HTML list of pending course updates (the student's kept file and the new version)."""
    items = "".join(
        f"<li>your <code>{html.escape(n['file'])}</code> is kept as you left it; the course's new "
        f"version is beside it: <code>{html.escape(n['new_version'])}</code></li>" for n in pending)
    return (f'<div style="border-left:4px solid {COLORS["notice"]};padding:4px 10px">'
            f'<b style="color:{COLORS["notice"]}">Course updates</b><ul>{items}</ul>'
            "Open the new version to see what changed; copy over what you want to keep.</div>")


def progress_html(mark_seen: bool = False) -> str:
    """An HTML table of every exercise's status (the saved record), with parts passed, after any
    pending course updates."""
    with contextlib.redirect_stdout(io.StringIO()):   # the table says it itself when not saved
        table = progress()
    pending = pending_updates(mark_seen=mark_seen)
    return (updates_html(pending) if pending else "") + progress_table_html(table.rows(), table.where)


def progress_widget() -> ipywidgets.VBox:
    """A small widget showing progress() and pending course updates; Refresh re-reads the record."""
    import ipywidgets as W

    view = W.HTML(progress_html(mark_seen=True))
    button = W.Button(description="Refresh", layout=W.Layout(width="90px"))

    def refresh(_: object = None) -> None:
        view.value = progress_html()

    button.on_click(refresh)
    box = W.VBox([view, button])
    box.view, box.refresh = view, refresh
    return box

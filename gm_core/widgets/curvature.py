"""Panels of the geometry notebook (10): a gait on the curvature map, the connection in three frames,
and a progress display for gait optimisation.

Each panel pairs a Scene of :mod:`gm_core.drawing.curvature` with its controls (the one widget
pattern, CONTRIBUTING.md); the numbers come from :mod:`gm_core.geometry`.
"""
from __future__ import annotations

from typing import Any

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing import curvature as D
from gm_core.geometry import OptimalGait, optimize_gait
from gm_core.geometry.estimates import FRAMES
from gm_core.systems import LocomotionSystem
from gm_core.widgets.base import ScenePanel, TablePanel, register, slider

__all__ = ["GaitStokesPanel", "FrameFieldsPanel", "optimize_with_progress"]

#: ToggleButtons' default buttons are too narrow for "minimum perturbation" (cut to "minimum perturb…"):
#: wide enough for the longest frame name at the widgets' 13 px font
FRAME_BUTTONS = {"button_width": "15em"}


def _frame_buttons() -> W.ToggleButtons:
    return W.ToggleButtons(options=list(FRAMES), value="middle link", description="frame", style=FRAME_BUTTONS)


@register
class GaitStokesPanel(TablePanel):
    """Move, resize and reshape a gait on a curvature map; compare exact g(T), Stokes and ∫ξ dt.

    The numbers are in an HTML table under the figure (``self.numbers``: text rendered by the
    browser, not redrawn by matplotlib); ``self.estimates`` holds them (None while singular).
    """

    title = "A gait on the curvature map: exact displacement, Stokes estimate, body-velocity integral"
    scene_class = D.GaitStokesScene
    scene: D.GaitStokesScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"c1": slider(0.0, -1.5, 1.5, description="centre α₁"),
                "c2": slider(0.0, -1.5, 1.5, description="centre α₂"),
                "a": slider(1.0, 0.1, 1.5, description="size a"),
                "b": slider(0.6, 0.1, 1.5, description="size b"),
                "tilt": slider(0.78, -1.6, 1.6, description="tilt"),
                "bend": slider(0.0, -0.6, 0.6, description="bend"),
                "row": W.ToggleButtons(options=[(r, i) for i, r in enumerate(D.ROWS)], value=0,
                                       description="map row", style={"button_width": "3.5em"}),
                "frame": _frame_buttons()}


@register
class FrameFieldsPanel(ScenePanel):
    """The three rows of −A(r) as fields, in the frame chosen by a toggle (they straighten and shrink)."""

    title = "The connection seen from three body frames"
    scene_class = D.FrameFieldsScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"frame": _frame_buttons()}


def optimize_with_progress(system: LocomotionSystem, objective: str = "displacement", order: int = 3,
                           **kw: Any) -> OptimalGait:
    """Run :func:`gm_core.geometry.optimize_gait` showing a progress bar and the current value; returns the result."""
    from IPython.display import display

    maxiter = kw.pop("maxiter", 200)
    bar = W.IntProgress(value=0, min=0, max=maxiter, description=f"max {objective}",
                        style={"description_width": "initial"})
    label = W.HTML("starting ...")
    display(W.HBox([bar, label]))

    def cb(it: int, val: float) -> None:
        bar.value = min(it, maxiter)
        label.value = f"iteration {it}: {objective} = {val:.5f}"

    res = optimize_gait(system, objective, order=order, maxiter=maxiter, callback=cb, **kw)
    bar.value = bar.max
    label.value = f"done after {res.nit} iterations: {objective} = {res.history[-1]:.5f}"
    return res

"""Section 3.1 panels: pacing a square and the linearity of directional systems
(scenes of :mod:`gm_core.drawing.pacing`).
"""
from __future__ import annotations

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.pacing import DirectionalScene, PacingSquareScene
from gm_core.systems.directional import RATE_MAPS
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["PacingSquarePanel", "DirectionalLinearityPanel"]


@register
class PacingSquarePanel(ScenePanel):
    """Fig. 3.1 live: repace a shape loop and watch its position path get repaced the same way, (3.3)-(3.4).

    Sliders: the unevenness a of the pacing τ(t) = t − a sin(2πt)/2π and the time t.
    Options: ``system``, ``gait``.
    """

    title = "Fig. 3.1: repace the shape path, the position path follows"
    scene_class = PacingSquareScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"unevenness": slider(0.7, -0.9, 0.9, description="pacing unevenness a"),
                "t": slider(0.4, 0.0, 1.0, description="time t")}


@register
class DirectionalLinearityPanel(ScenePanel):
    """The box on directional linearity ((3.i)-(3.iv)): four maps b, each replayed at pace k and backwards."""

    title = "Directional linearity: four examples"
    scene_class = DirectionalScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"example": W.Dropdown(options=list(RATE_MAPS), value=list(RATE_MAPS)[0], description="example"),
                "pace": slider(2.0, 0.25, 3.0, description="pace k")}

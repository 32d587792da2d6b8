"""The start page's demo panel: one SE(2) frame and body driven by three sliders
(scene of :mod:`gm_core.drawing.start`). Every panel of the course has this shape: a Scene from
the drawing layer and the controls that drive it.
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.start import FrameScene
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["FrameDemo"]


@register
class FrameDemo(ScenePanel):
    """Drag x, y and theta: the body and its frame move to g = (x, y, theta), book (1.2)."""

    title = "A rigid body at g = (x, y, θ)"
    scene_class = FrameScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {
            "x": slider(1.0, -2.0, 2.0, description="x"),
            "y": slider(0.5, -2.0, 2.0, description="y"),
            "theta": slider(0.8, -np.pi, np.pi, description="θ"),
        }

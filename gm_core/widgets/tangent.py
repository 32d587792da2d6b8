"""Section 1.4 panel: tangent spaces (scene of :mod:`gm_core.drawing.tangent`).
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.tangent import TangentSpaceScene
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["TangentSpacePanel"]

PI = float(np.pi)


@register
class TangentSpacePanel(ScenePanel):
    """Figs 1.11-1.12: velocities are arrows in the tangent space at the moving point."""

    title = "Velocities live in tangent spaces (figs 1.11-1.12)"
    scene_class = TangentSpaceScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"s": slider(0.8, 0.0, 2 * PI, description="where along the curve s"),
                "speed": slider(1.0, -2.0, 2.0, description="speed ds/dt")}

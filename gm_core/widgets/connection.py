"""Section 3.3 panel: connection vector fields with a shape cursor
(scene of :mod:`gm_core.drawing.connection`).
"""
from __future__ import annotations

from typing import Any

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.connection import ConnectionFieldScene
from gm_core.systems import KinematicSnake, LocomotionSystem
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["ConnectionFieldPanel"]


@register
class ConnectionFieldPanel(ScenePanel):
    """The three rows of A as vector fields over shape space, a shape cursor, and the body there.

    Sliders set the shape (alpha1, alpha2) and the shape velocity; the fourth axes draws the body
    at that shape with its body velocity xi = -A(r) r_dot (3.10). For the kinematic snake the
    singular set is drawn in red and the velocity is hidden (with a flag) on it. Options:
    ``system``, ``alpha1``, ``alpha2`` (start), ``n``, ``velocity_scale``.
    """

    title = "Connection vector fields and a shape cursor"
    scene_class = ConnectionFieldScene
    system: LocomotionSystem

    @override
    def scene_options(self) -> dict[str, Any]:
        o = self.options
        self.system = o.get("system") or KinematicSnake()
        self.title = f"Connection vector fields: {self.system.name}"
        return dict(system=self.system, n=o.get("n"), velocity_scale=o.get("velocity_scale", 1.0))

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        (lo1, hi1), (lo2, hi2) = self.system.shape_limits
        return {
            "alpha1": slider(self.options.get("alpha1", 0.8), lo1, hi1, description="α₁"),
            "alpha2": slider(self.options.get("alpha2", -0.6), lo2, hi2, description="α₂"),
            "alpha1_dot": slider(1.0, -1.0, 1.0, description="α₁ rate"),
            "alpha2_dot": slider(0.0, -1.0, 1.0, description="α₂ rate"),
        }

"""Section 1.6 panels: geodesics of surfaces and groups, the exponential map
(scenes of :mod:`gm_core.drawing.geodesics`).
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.geodesics import (
    ExpFourWaysScene,
    HelixScene,
    PuckArcScene,
    RPlusGeodesicScene,
    SurfaceGeodesicsScene,
)
from gm_core.widgets.base import ScenePanel, int_slider, register, slider

__all__ = ["SurfaceGeodesicsPanel", "HelixPanel", "PuckArcPanel", "RPlusGeodesicPanel", "ExpFourWaysPanel"]

PI = float(np.pi)


@register
class SurfaceGeodesicsPanel(ScenePanel):
    """Fig. 1.16: geodesics of the cylinder (loops, helices, lines) and of the sphere (great circles)."""

    title = "Straightest lines on the cylinder and the sphere (fig. 1.16)"
    scene_class = SurfaceGeodesicsScene
    # curves wind behind the surfaces' wireframes: only a full 3D draw sorts them by depth
    blit = False

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"heading_deg": slider(15.0, -90.0, 90.0, step=1.0, description="heading (° up from around)",
                                      readout_format=".0f"),
                "length": slider(3 * PI, 0.1, 4 * PI, description="distance travelled")}


@register
class HelixPanel(ScenePanel):
    """Fig. 1.18: SE(2) geodesic helices and their circular shadows."""

    title = "SE(2) geodesics are helices (fig. 1.18)"
    scene_class = HelixScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"thetadot": slider(1.0, -3.0, 3.0, description="dθ/dt (turning rate)")}


@register
class PuckArcPanel(ScenePanel):
    """Fig. 1.19: spinning puck vs SE(2) arc, scrubbed by time."""

    title = "Spinning puck vs SE(2) arc (fig. 1.19)"
    scene_class = PuckArcScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"t": slider(1.5, 0.0, 2 * PI, description="time t"),
                "w": slider(1.0, 0.2, 2.0, description="ξᶿ")}


@register
class RPlusGeodesicPanel(ScenePanel):
    """Fig. 1.17: accelerating and decelerating geodesics of (R⁺, ×)."""

    title = "Geodesics of (R⁺, ×) (fig. 1.17)"
    scene_class = RPlusGeodesicScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"xi": slider(1.0, -1.5, 1.5, description="ξ")}


@register
class ExpFourWaysPanel(ScenePanel):
    """Section 1.6.4, exercise 1.4d: the exponential map four ways."""

    title = "exp(ξ) on SE(2), four ways"
    scene_class = ExpFourWaysScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"thetadot": slider(1.0, -3.0, 3.0, description="dθ/dt in ξ = (1, 0, dθ/dt)"),
                "n": int_slider(8, 1, 64, description="steps / terms n"),
                "side": W.Dropdown(options=["left", "right"], value="left", description="field")}

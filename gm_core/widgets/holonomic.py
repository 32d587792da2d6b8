"""Chapter 2 panels: pinned bodies, relative poses and the velocity of a beta frame
(scenes of :mod:`gm_core.drawing.holonomic`).
"""
from __future__ import annotations

from typing import Any

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.holonomic import BetaVelocityScene, PinnedBodiesScene, RelativePoseScene
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["PinnedBodiesPanel", "RelativePosePanel", "BetaVelocityPanel"]

PI = float(np.pi)


@register
class PinnedBodiesPanel(ScenePanel):
    """Two bodies, free or pinned at their frame origins: six numbers or four (fig. 2.1, section 2.1)."""

    title = "Two bodies pinned together (fig. 2.1): the pin's two constraints remove two numbers"
    scene_class = PinnedBodiesScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {
            "pinned": W.Checkbox(value=True, description="pin the frame origins together"),
            "x1": slider(-0.3, -1.5, 1.5, description="x₁"), "y1": slider(-0.2, -1.5, 1.5, description="y₁"),
            "theta1": slider(0.3, -PI, PI, description="θ₁"),
            "x2": slider(0.6, -1.5, 1.5, description="x₂"), "y2": slider(0.5, -1.5, 1.5, description="y₂"),
            "theta2": slider(1.6, -PI, PI, description="θ₂"),
        }

    @override
    def after_update(self, values: dict[str, Any]) -> None:
        for k in ("x2", "y2"):
            self.controls[k].disabled = bool(values["pinned"])


@register
class RelativePosePanel(ScenePanel):
    """Pick a frame, an observer and a frame in between: g_{a,b} = b^-1 a and its cancellation rules (2.iii)-(2.iv)."""

    title = "The notation box of section 2.2: the pose of one frame seen from another, <i>g</i><sub><i>a,b</i></sub> = <i>b</i>⁻¹<i>a</i>"
    scene_class = RelativePoseScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        names = list(RelativePoseScene.NAMES)
        return {
            "alpha1": slider(0.5, -PI, PI, description="α₁"),
            "alpha2": slider(0.9, -PI, PI, description="α₂"),
            "frame": W.Dropdown(options=names, value="h2", description="frame a"),
            "seen_from": W.Dropdown(options=names, value="g1", description="seen from b"),
            "via": W.Dropdown(options=names, value="h1", description="via c"),
        }


@register
class BetaVelocityPanel(ScenePanel):
    """The velocity of the centre-of-mass frame: carried by the middle link plus moved by the shape, (2.60)-(2.67)."""

    title = ("Velocity of a generalized body frame (fig. 2.9, section 2.5.6): <i>ξ</i><sub>β</sub> = "
             "Ad<sub>β</sub><sup>−1</sup> (<i>ξ</i><sub>2</sub> + <i>v</i><sub>β</sub>)")
    scene_class = BetaVelocityScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {
            "alpha1": slider(0.8, -2.5, 2.5, description="α₁"),
            "alpha2": slider(0.4, -2.5, 2.5, description="α₂"),
            "alpha1_dot": slider(1.2, -1.2, 1.2, description="α₁ rate"),
            "alpha2_dot": slider(0.6, -1.2, 1.2, description="α₂ rate"),
            "xi_x": slider(0.4, -0.7, 0.7, description="ξ₂ x"),
            "xi_y": slider(0.0, -0.7, 0.7, description="ξ₂ y"),
            "xi_theta": slider(0.4, -0.7, 0.7, description="ξ₂ θ"),
        }

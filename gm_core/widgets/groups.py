"""Sections 1.2-1.3 panels: the slide rule, the circle isomorphism, SE(2) acting and the
scale-shift group acting on its half-plane (scenes of :mod:`gm_core.drawing.groups`).
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.groups import (
    BodyPointsScene,
    CircleIsoScene,
    ForwardLeftScene,
    LeftRightActionScene,
    ScaleShiftActionScene,
    SlideRuleScene,
)
from gm_core.widgets.base import ScenePanel, int_slider, register, se2_sliders, slider

__all__ = ["SlideRulePanel", "CircleIsoPanel", "LeftRightActionPanel", "ForwardLeftPanel", "BodyPointsPanel",
           "ScaleShiftActionPanel"]

PI = float(np.pi)


@register
class SlideRulePanel(ScenePanel):
    """(R+, ×) ↔ (R, +) through log: a slide rule, (1.xii)."""

    title = "A slide rule multiplies by adding logarithms"
    scene_class = SlideRuleScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"a": slider(2.0, 1.0, 10.0, description="a"),
                "b": slider(3.0, 1.0, 10.0, description="b")}


@register
class CircleIsoPanel(ScenePanel):
    """(S¹, + mod 1) ↔ SO(2) through S1(1.0).matrix, (1.xiv)-(1.xvi)."""

    title = "Adding on the circle = multiplying rotations"
    scene_class = CircleIsoScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"a1": slider(0.2, 0.0, 0.99, description="a₁ (cycles)"),
                "a2": slider(0.35, 0.0, 0.99, description="a₂ (cycles)")}


@register
class LeftRightActionPanel(ScenePanel):
    """Figs. 1.8-1.9: left action h∘g and right action g∘h of SE(2)."""

    title = "SE(2): left action (move by h) vs right action (h relative to g)"
    scene_class = LeftRightActionScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = se2_sliders(1.5, 0.5, 0.5, labels=("g: x", "g: y", "g: θ"))
        c.update(se2_sliders(-1.0, 1.0, 0.9, names=("u", "v", "beta"), labels=("h: u", "h: v", "h: β")))
        return c


@register
class ForwardLeftPanel(ScenePanel):
    """Fig. 1.10: repeating a step in (R²×S¹, +) and in SE(2)."""

    title = "“Forward and to the left”, again and again (fig. 1.10)"
    scene_class = ForwardLeftScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = se2_sliders(1.0, 1.0, PI / 2, lim=2.0, labels=("g: x", "g: y", "g: θ"))
        c["n"] = int_slider(2, 1, ForwardLeftScene.N_MAX, description="steps n")
        return c


@register
class BodyPointsPanel(ScenePanel):
    """(1.11)-(1.12): a point fixed in the body and its world position."""

    title = "Points on a rigid body"
    scene_class = BodyPointsScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = se2_sliders(0.5, 0.3, 0.6, lim=2.0, labels=("g: x", "g: y", "g: θ"))
        c["px"] = slider(0.6, -0.8, 0.8, description="body point pᵇ: x")
        c["py"] = slider(0.3, -0.4, 0.4, description="body point pᵇ: y")
        return c


@register
class ScaleShiftActionPanel(ScenePanel):
    """R+ ⋉ R, the maps x ↦ αx + β: left and right actions of h on a grid, and exp(tξ), (1.xix), (1.46)-(1.47)."""

    title = "Scale-shift group: h∘g vs g∘h on the half-plane, and exp(tξ)"
    scene_class = ScaleShiftActionScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"alpha": slider(1.5, 0.4, 2.0, description="h: scale α"),
                "beta": slider(0.5, -1.0, 1.0, description="h: shift β"),
                "u": slider(0.6, -1.0, 1.0, description="ξ: scale rate u"),
                "v": slider(1.0, -1.5, 1.5, description="ξ: shift rate v")}

"""Sections 1.4-1.5 panels: vector fields, lifted actions, velocities and the adjoint
(scenes of :mod:`gm_core.drawing.vector_fields`).
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.vector_fields import (
    AdjointScene,
    LiftedScalarScene,
    LiftedSE2Scene,
    VectorFieldScene,
    VelocityScene,
)
from gm_core.fields import FIELDS
from gm_core.widgets.base import ScenePanel, register, se2_sliders, slider, xi_sliders

__all__ = ["VectorFieldPanel", "LiftedScalarPanel", "LiftedSE2Panel", "VelocityPanel", "AdjointPanel"]

PI = float(np.pi)


@register
class VectorFieldPanel(ScenePanel):
    """Figs. 1.13-1.14: integral curves of a vector field from a movable start point."""

    title = "Vector fields and integral curves"
    scene_class = VectorFieldScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"field": W.Dropdown(options=list(FIELDS), value="spiral sink", description="field"),
                "x0": slider(1.5, -2.9, 2.9, description="start x₀"),
                "y0": slider(1.0, -2.9, 2.9, description="start y₀")}


@register
class LiftedScalarPanel(ScenePanel):
    """(1.22)-(1.25): lifted actions on (R², +) and (R⁺, ×)."""

    title = "Lifted actions carry velocities between tangent spaces"
    scene_class = LiftedScalarScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"hx": slider(1.5, -1.0, 3.0, description="R²: h (x part)"),
                "hy": slider(1.0, -1.0, 2.5, description="R²: h (y part)"),
                "h": slider(2.5, 0.2, 6.0, description="R⁺: h")}


@register
class LiftedSE2Panel(ScenePanel):
    """(1.31), (1.37): left and right lifted actions of SE(2) on a moving body."""

    title = "SE(2): <i>T<sub>g</sub>L<sub>h</sub></i> keeps the body velocity, <i>T<sub>g</sub>R<sub>h</sub></i> keeps the spatial velocity"
    scene_class = LiftedSE2Scene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"theta": slider(0.3, -PI, PI, description="g: θ"),
                "u": slider(2.0, -1.5, 3.0, description="h: u"),
                "v": slider(1.5, -1.5, 3.0, description="h: v"),
                "beta": slider(1.0, -PI, PI, description="h: β")}


@register
class VelocityPanel(ScenePanel):
    """Fig. 1.15: world, body and spatial velocity."""

    title = "Four views of one velocity (fig. 1.15)"
    scene_class = VelocityScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = se2_sliders(1.2, 0.6, 0.7, lim=2.0, labels=("g: x", "g: y", "g: θ"))
        c.update(xi_sliders(0.8, 0.3, 0.6))
        return c


@register
class AdjointPanel(ScenePanel):
    """(1.40)-(1.45): the adjoint, checked three ways, live."""

    title = "The adjoint Ad<sub><i>g</i></sub> = <i>T<sub>g</sub>R<sub>g⁻¹</sub> T<sub>e</sub>L<sub>g</sub></i>, checked live"
    scene_class = AdjointScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = se2_sliders(1.0, -0.5, 0.8, lim=2.5, labels=("g: x", "g: y", "g: θ"))
        c.update(xi_sliders(0.5, 0.2, 0.7))
        return c

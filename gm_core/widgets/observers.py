"""Section 1.5 panels: the adjoint as a change of observer, the Frames box
(scenes of :mod:`gm_core.drawing.observers`).
"""
from __future__ import annotations

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.observers import FramesScene, ObserverScene
from gm_core.widgets.base import ScenePanel, register, se2_sliders, slider, xi_sliders

__all__ = ["ObserverPanel", "FramesPanel"]


@register
class ObserverPanel(ScenePanel):
    """The adjoint as a change of observer: move h, ξ stays, ξˢ changes; the ICR is one point."""

    title = "Change the observer: the body velocity stays, the spatial velocity changes"
    scene_class = ObserverScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = se2_sliders(-1.5, -1.0, 0.0, names=("hx", "hy", "htheta"), lim=2.5,
                         labels=("observer h: x", "observer h: y", "observer h: θ"))
        c.update(xi_sliders(0.8, 0.3, 0.6))
        return c


@register
class FramesPanel(ScenePanel):
    """The "Frames" box: one reference frame, two coordinate frames, the instantaneous body frame."""

    title = "Reference frame, coordinate frames, and the instantaneous body frame"
    scene_class = FramesScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = {"t": slider(1.2, 0.0, 6.0, description="time t")}
        c.update(se2_sliders(-1.8, 1.2, -0.5, names=("bx", "by", "btheta"), lim=2.5,
                              labels=("frame B: x", "frame B: y", "frame B: θ")))
        return c

"""Section 3.1 panels: a differential-drive car and an Ackerman car driven by sliders
(scenes of :mod:`gm_core.drawing.motion`).
"""
from __future__ import annotations

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.motion import AckermanScene, DiffDriveScene
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["DiffDriveCarPanel", "AckermanCarPanel"]


@register
class DiffDriveCarPanel(ScenePanel):
    """Differential-drive car (3.8), (3.29): two wheel-speed sliders and a duration."""

    title = "Differential-drive car: wheel speeds in, motion out"
    scene_class = DiffDriveScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {
            "wheel1_speed": slider(2.0, -4.0, 4.0, description="wheel 1 (left) rate"),
            "wheel2_speed": slider(3.0, -4.0, 4.0, description="wheel 2 (right) rate"),
            "duration": slider(3.0, 0.1, 6.0, description="duration T"),
        }


@register
class AckermanCarPanel(ScenePanel):
    """Kinematic-bicycle car (3.9): drive-wheel rate, starting steering angle and steering rate."""

    title = "Ackerman car: drive and steering in, motion out"
    scene_class = AckermanScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {
            "wheel_speed": slider(3.0, -4.0, 4.0, description="drive wheel rate"),
            "steering": slider(0.3, -1.4, 1.4, description="steering angle at t=0"),
            "steering_speed": slider(0.0, -1.0, 1.0, description="steering rate"),
            "duration": slider(3.0, 0.1, 6.0, description="duration T"),
        }

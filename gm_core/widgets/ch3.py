"""Chapter 3 panels: cars driven by sliders, connection vector fields with a shape cursor, gaits.

Each panel pairs controls with a scene that owns the figure and computes through
:mod:`gm_core.locomotion` / :mod:`gm_core.systems` (the one widget pattern,
:class:`~gm_core.widgets.base.ScenePanel`): cars in :mod:`gm_core.drawing.motion`, connection
fields in :mod:`gm_core.drawing.connection`, gaits in :mod:`gm_core.drawing.gaits`. Singular
shapes raise a SingularFlag and hide what cannot be drawn.
"""
from __future__ import annotations

import numpy as np

from ..drawing.connection import ConnectionFieldScene
from ..drawing.gaits import GaitScene
from ..drawing.motion import AckermanScene, DiffDriveScene
from ..examples import drive
from ..systems import KinematicSnake
from .base import ScenePanel, register, slider

__all__ = ["drive", "DiffDriveCarPanel", "AckermanCarPanel", "ConnectionFieldPanel", "GaitPanel"]

PI = float(np.pi)


# ======================================================================= cars
@register
class DiffDriveCarPanel(ScenePanel):
    """Differential-drive car (3.8), (3.29): two wheel-speed sliders and a duration."""

    title = "Differential-drive car: wheel speeds in, motion out"
    scene_class = DiffDriveScene

    def controls_spec(self):
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

    def controls_spec(self):
        return {
            "wheel_speed": slider(3.0, -4.0, 4.0, description="drive wheel rate"),
            "steering": slider(0.3, -1.4, 1.4, description="steering angle at t=0"),
            "steering_speed": slider(0.0, -1.0, 1.0, description="steering rate"),
            "duration": slider(3.0, 0.1, 6.0, description="duration T"),
        }


# ======================================================================= connection fields
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

    def scene_options(self):
        o = self.options
        self.system = o.get("system") or KinematicSnake()
        self.title = f"Connection vector fields: {self.system.name}"
        return dict(system=self.system, n=o.get("n"), velocity_scale=o.get("velocity_scale", 1.0))

    def controls_spec(self):
        (lo1, hi1), (lo2, hi2) = self.system.shape_limits
        return {
            "alpha1": slider(self.options.get("alpha1", 0.8), lo1, hi1, description="α1"),
            "alpha2": slider(self.options.get("alpha2", -0.6), lo2, hi2, description="α2"),
            "alpha1_dot": slider(1.0, -1.0, 1.0, description="α1 rate"),
            "alpha2_dot": slider(0.0, -1.0, 1.0, description="α2 rate"),
        }


# ======================================================================= gaits
@register
class GaitPanel(ScenePanel):
    """A circular gait drawn on the three connection fields and the motion it produces over one cycle.

    Sliders: the gait's radius and centre in shape space. Options: ``system``, ``amplitude``,
    ``center``, ``n``, ``lim``.
    """

    title = "Gaits on the connection fields"
    scene_class = GaitScene

    def scene_options(self):
        o = self.options
        self.system = o.get("system") or KinematicSnake()
        self.title = f"Gaits: {self.system.name}"
        return dict(system=self.system, n=o.get("n"), lim=o.get("lim"))

    def controls_spec(self):
        (lo1, hi1), (lo2, hi2) = self.system.shape_limits
        c = self.options.get("center", (0.0, 0.0))
        return {
            "amplitude": slider(self.options.get("amplitude", 1.0), 0.05, 2.0, description="radius"),
            "center1": slider(c[0], lo1 / 2, hi1 / 2, description="centre α1"),
            "center2": slider(c[1], lo2 / 2, hi2 / 2, description="centre α2"),
        }

"""Chapter 3 panels: cars driven by sliders, connection vector fields with a shape cursor, gaits.

Each panel pairs controls with a scene that owns the figure and computes through
:mod:`gm_core.locomotion` / :mod:`gm_core.systems` (the one widget pattern,
:class:`~gm_core.widgets.base.ScenePanel`): cars in :mod:`gm_core.drawing.motion`, connection
fields in :mod:`gm_core.drawing.connection`, gaits in :mod:`gm_core.drawing.gaits`. Singular
shapes raise a SingularFlag and hide what cannot be drawn.
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from ..drawing.base import jshtml
from ..drawing.connection import ConnectionFieldScene
from ..drawing.gaits import GAIT_SHAPES, GaitScene
from ..drawing.motion import AckermanScene, DiffDriveScene
from ..drawing.nonholonomy import ParallelParkScene
from ..drawing.pacing import DirectionalScene, PacingSquareScene
from ..locomotion import drive
from ..systems import FloatingSnake, KinematicSnake
from ..systems.directional import RATE_MAPS
from .base import ScenePanel, register, slider

__all__ = ["drive", "DiffDriveCarPanel", "AckermanCarPanel", "ConnectionFieldPanel", "GaitPanel", "body_frames", "ParallelParkPanel",
           "PacingSquarePanel", "DirectionalLinearityPanel"]

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
def body_frames(system):
    """Body-frame choices for ``system``: {name: system}; one entry unless the frame matters.

    The floating snake's connection depends on where its body frame sits: at the centre of
    mass (the translation rows vanish) or on the middle link (section 3.4.3).
    """
    if isinstance(system, FloatingSnake):
        kw = dict(lengths=system.lengths, masses=system.masses, inertias=system.inertias)
        names = {"com": "centre of mass", "middle": "middle link"}
        other = "middle" if system.frame == "com" else "com"
        return {names[system.frame]: system, names[other]: FloatingSnake(frame=other, **kw)}
    return {}


@register
class GaitPanel(ScenePanel):
    """A gait drawn on the three connection fields and the motion it produces over one cycle.

    Controls: the gait's shape (circle, tilted ellipse, serpenoid, figure eight, or a loop drawn
    with the mouse: pick "drawn" and drag the orange dots), its size, centre, aspect and angle,
    and for the floating snake the body frame. Works for every system of chapter 3 (three-link
    systems and cars). Options: ``system``, ``family``, ``amplitude``, ``center``, ``aspect``,
    ``angle``, ``n``, ``lim``. ``panel.animation()`` plays the current gait in the world.
    """

    title = "Gaits on the connection fields"
    scene_class = GaitScene

    def scene_options(self):
        o = self.options
        self.system = o.get("system") or KinematicSnake()
        self.title = f"Gaits: {self.system.name}"
        return dict(system=self.system, frames=body_frames(self.system), n=o.get("n"), lim=o.get("lim"))

    def build(self):
        super().build()
        self.scene.on_edit = self.refresh     # mouse edits of a drawn loop redraw like a slider

    def controls_spec(self):
        (lo1, hi1), (lo2, hi2) = self.system.shape_limits
        o = self.options
        c = o.get("center", (0.0, 0.0))
        big = 0.5 * min(hi1 - lo1, hi2 - lo2)
        spec = {
            "family": W.Dropdown(options=list(GAIT_SHAPES), value=o.get("family", "circle"), description="shape"),
            "amplitude": slider(o.get("amplitude", min(1.0, big)), 0.05, big, description="size"),
            "center1": slider(c[0], lo1 / 2, hi1 / 2, description="centre α1"),
            "center2": slider(c[1], lo2 / 2, hi2 / 2, description="centre α2"),
            "aspect": slider(o.get("aspect", 0.6), 0.1, 1.5, description="aspect"),
            "angle": slider(o.get("angle", 0.0), -PI, PI, description="tilt / phase"),
        }
        frames = list(self.scene.frames)
        if frames:
            spec["frame"] = W.Dropdown(options=frames, value=frames[0], description="body frame")
        return spec

    def after_update(self, values):
        self.system = self.scene.system       # the body frame may have changed
        fam = values.get("family", "circle")
        self.controls["aspect"].disabled = fam == "circle" or fam == "drawn"
        self.controls["angle"].disabled = fam == "circle" or fam == "drawn"
        for k in ("amplitude", "center1", "center2"):
            self.controls[k].disabled = fam == "drawn"

    def animation(self, n_frames=60, cycles=2, row=2):
        """The current gait as a kernel-free animation (HTML): body in the world, cursor on row ``row``."""
        anim, fig, traj = self.scene.animation(n_frames=n_frames, cycles=cycles, row=row)
        return jshtml(anim)


# ======================================================================= nonholonomy
@register
class ParallelParkPanel(ScenePanel):
    """A rolling disk parallel-parks by a loop of allowed moves; the integrable constraint (3.viii) cannot.

    Sliders: the drive distance d and the turn angle φ of the loop drive–turn–back–turn back.
    """

    title = "Nonholonomy: parallel parking a rolling disk"
    scene_class = ParallelParkScene

    def controls_spec(self):
        return {"d": slider(0.8, -1.2, 1.2, description="drive distance d"),
                "phi": slider(0.6, -1.5, 1.5, description="turn angle φ")}


# ======================================================================= pacing (section 3.1)
@register
class PacingSquarePanel(ScenePanel):
    """Fig. 3.1 live: repace a shape loop and watch its position path get repaced the same way, (3.3)-(3.4).

    Sliders: the unevenness a of the pacing τ(t) = t − a sin(2πt)/2π and the time t.
    Options: ``system``, ``gait``.
    """

    title = "Fig. 3.1: repace the shape path, the position path follows"
    scene_class = PacingSquareScene

    def controls_spec(self):
        return {"unevenness": slider(0.7, -0.9, 0.9, description="pacing unevenness a"),
                "t": slider(0.4, 0.0, 1.0, description="time t")}


@register
class DirectionalLinearityPanel(ScenePanel):
    """The box on directional linearity ((3.i)-(3.iv)): four maps b, each replayed at pace k and backwards."""

    title = "Directional linearity: four examples"
    scene_class = DirectionalScene

    def controls_spec(self):
        return {"example": W.Dropdown(options=list(RATE_MAPS), value=list(RATE_MAPS)[0], description="example"),
                "pace": slider(2.0, 0.25, 3.0, description="pace k")}

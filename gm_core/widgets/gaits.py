"""Sections 3.3-3.4 panel: a gait on the connection fields and the motion it produces
(scene of :mod:`gm_core.drawing.gaits`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.gaits import GAIT_SHAPES, GaitScene
from gm_core.drawing.toolkit.primitives import jshtml
from gm_core.systems import KinematicSnake, LocomotionSystem
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["GaitPanel"]

if TYPE_CHECKING:
    from IPython.display import HTML

PI = float(np.pi)


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
    scene: GaitScene
    system: LocomotionSystem

    @override
    def scene_options(self) -> dict[str, Any]:
        o = self.options
        self.system = o.get("system") or KinematicSnake()
        self.title = f"Gaits: {self.system.name}"
        # the frames the system's own physics defines (the floating snake's two, section 3.4.3)
        frames = self.system.body_frames(centre_of_mass=False, minimum_perturbation=False)
        return dict(system=self.system, frames=frames if len(frames) > 1 else {}, n=o.get("n"), lim=o.get("lim"))

    @override
    def build(self) -> None:
        super().build()
        self.scene.on_edit = self.refresh     # mouse edits of a drawn loop redraw like a slider

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        (lo1, hi1), (lo2, hi2) = self.system.shape_limits
        o = self.options
        c = o.get("center", (0.0, 0.0))
        big = 0.5 * min(hi1 - lo1, hi2 - lo2)
        spec = {
            "family": W.Dropdown(options=list(GAIT_SHAPES), value=o.get("family", "circle"), description="shape"),
            "amplitude": slider(o.get("amplitude", min(1.0, big)), 0.05, big, description="size"),
            "center1": slider(c[0], lo1 / 2, hi1 / 2, description="centre α₁"),
            "center2": slider(c[1], lo2 / 2, hi2 / 2, description="centre α₂"),
            "aspect": slider(o.get("aspect", 0.6), 0.1, 1.5, description="aspect"),
            "angle": slider(o.get("angle", 0.0), -PI, PI, description="tilt / phase"),
        }
        frames = list(self.scene.frames)
        if frames:
            spec["frame"] = W.Dropdown(options=frames, value=frames[0], description="body frame")
        return spec

    @override
    def after_update(self, values: dict[str, Any]) -> None:
        self.system = self.scene.system       # the body frame may have changed
        fam = values.get("family", "circle")
        self.controls["aspect"].disabled = fam == "circle" or fam == "drawn"
        self.controls["angle"].disabled = fam == "circle" or fam == "drawn"
        for k in ("amplitude", "center1", "center2"):
            self.controls[k].disabled = fam == "drawn"

    def animation(self, n_frames: int = 60, cycles: int = 2, row: int = 2) -> HTML:
        """The current gait as a kernel-free animation (HTML): body in the world, cursor on row ``row``."""
        anim, fig, traj = self.scene.animation(n_frames=n_frames, cycles=cycles, row=row)
        return jshtml(anim)

"""The locomotion lab (notebook 12): any chain of sysplotter's library, its curvature, a gait and the body.

sysplotter's workflow on one figure: pick a system by its file name
(:mod:`gm_core.systems.catalog`), see one row of its constraint curvature D(-A) as a map with the
same row of the connection field -A over it, shape a gait on the map, and see the body at a point
of the gait; the numbers (exact g(T), Stokes estimate, body-velocity integral) come from
:func:`gm_core.geometry.estimates.displacement_estimates` at its interactive resolution.

The systems offered (:func:`lab_names`) are the catalog's systems in the plane with a rigid body
for every part: its chains, the granular swimmer, the car and the kinematic snake. A system with
more than two shape variables is seen on the slice through its straight shape along its first two
(:func:`gm_core.systems.shape_slice`). The continuous bodies, the panel-method chain and the tape
measures are left out (:data:`SLOW`): one gait's three numbers cost them a second or more, too
slow for a slider; notebook 12 analyses a continuous body in a code cell. Each system's curvature grid is computed once
and cached (:func:`gm_core.geometry.estimates.curvature_grid`), so switching back is quick.
"""
from __future__ import annotations

import functools
from typing import Any, ClassVar

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from typing_extensions import override

from gm_core.drawing.connection import ConnectionFieldArtist, style_shape_axes
from gm_core.drawing.curvature import ROWS, CurvatureMapArtist, GaitArtist, estimates_table
from gm_core.drawing.motion import SystemArtist, system_extent
from gm_core.drawing.toolkit.primitives import SingularFlag
from gm_core.drawing.toolkit.style import PALETTE, Scene, new_figure
from gm_core.geometry.estimates import Estimates, displacement_estimates, shaped_gait
from gm_core.groups import SE2
from gm_core.systems import AffineRestriction, LocomotionSystem, SlenderBody, catalog, shape_slice
from gm_core.systems.panel_method import InteractingChain
from gm_core.systems.tape_measure import TapeMeasure
from gm_core.validation import SingularShapeError

__all__ = ["lab_names", "lab_system", "LabScene"]


#: Systems whose connection costs too much for a slider: a continuous body integrates along itself at
#: every quadrature node, the panel method solves a flow, the tape measure's Stokes estimate refines
#: around its singular edge; one gait's numbers take a second or more.
SLOW = (SlenderBody, InteractingChain, TapeMeasure)


def _offered(name: str) -> bool:
    system = catalog.load(name)
    return system.position_group is SE2 and not isinstance(system, SLOW) and bool(system.parts())


@functools.lru_cache(maxsize=1)
def lab_names() -> tuple[str, ...]:
    """The catalog's systems the lab offers (see the module docstring), in the catalog's order."""
    return tuple(n for n in catalog.names() if _offered(n))


@functools.lru_cache(maxsize=64)
def lab_system(name: str) -> LocomotionSystem:
    """The catalog's system ``name`` with two shape variables over its file's window (a slice if it has more)."""
    if name not in lab_names():
        raise ValueError(f"name must be one of the lab's systems ({', '.join(lab_names())}); got {name!r}")
    system = catalog.load(name)
    window = catalog.sysplotter_files()[name].grid_range
    if system.n_shape > 2:
        return shape_slice(system, np.zeros(system.n_shape), (0, 1), limits=window[:2])
    return AffineRestriction(system, np.eye(2), shape_names=system.shape_names, shape_limits=window[:2],
                             name=system.name)


class LabScene(Scene):
    """Left: a row of D(-A) with the same row of -A, a gait and the shape at ``phase``; right: the body there.

    Values: ``system`` (one of :func:`lab_names`), ``row`` (0, 1, 2: x, y, θ), the gait ``c1, c2``
    (centre), ``a, b`` (sizes), ``tilt`` (as :func:`~gm_core.geometry.estimates.shaped_gait`), the
    centre and sizes as fractions of the window's half-width, and ``phase`` (where along the gait
    the body is drawn, 0 to 1). ``self.table`` is the three estimates as HTML, ``self.estimates``
    the numbers (None when the gait is singular or leaves the window, when a flag says so).
    """

    MAP_N: ClassVar[int] = 33
    FIELD_N: ClassVar[int] = 9

    def __init__(self, system: str = "three_link_lowRe", **options: Any) -> None:
        self.name = system
        self.system = lab_system(system)
        super().__init__(**options)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, (self.ax, self.axb) = new_figure(1, 2, figsize=(9, 3.4), layout="compressed",
                                              gridspec_kw=dict(width_ratios=[1.15, 1]))
        return fig, [self.ax, self.axb]

    @override
    def decorate(self) -> None:
        self.axb.set_aspect("equal")
        self.axb.set_xticks([])
        self.axb.set_yticks([])

    @override
    def create(self) -> None:
        limits = self.system.shape_limits
        self.map = CurvatureMapArtist(self.ax, self.system, 0, limits=limits, n=self.MAP_N)
        self.field = ConnectionFieldArtist(self.ax, self.system, 0, n=self.FIELD_N, color="0.25")
        self.gait_artist = GaitArtist(self.ax)
        (self.dot,) = self.ax.plot([], [], "o", color=PALETTE["vermillion"], ms=7, zorder=6)
        self.flag = SingularFlag(self.ax)
        self.body = SystemArtist(self.axb, self.system)
        self._key: tuple[str, int] = ("", -1)
        self.estimates: Estimates | None = None
        self.table = ""
        self._switch(self.name, 0)

    def _switch(self, name: str, row: int) -> None:
        """Show another system or row: the map, the field, the axes and (for a new system) the body."""
        if name != self._key[0]:
            self.name, self.system = name, lab_system(name)
            limits = self.system.shape_limits
            self.map.limits = limits
            (lo1, hi1), (lo2, hi2) = limits
            self.map.image.set_extent((lo1, hi1, lo2, hi2))
            style_shape_axes(self.ax, self.system, limits=limits, pad=0.0)
            for artist in self.body.bodies:
                artist.patch.remove()
            self.body.frame.quiver.remove()
            self.body = SystemArtist(self.axb, self.system)
            corners = np.array(np.meshgrid(*limits)).reshape(2, -1).T
            size = 1.1 * max(system_extent(self.system, r) for r in np.vstack([corners, [[0.0, 0.0]]]))
            self.axb.set_xlim(-size, size)
            self.axb.set_ylim(-size, size)
            self.axb.set_title(f"{name} (body frame)", fontsize=9)
        self.map.set(self.system, row)
        self.field.set(self.system, row)
        self.ax.set_title(f"D(-A) and -A, row {ROWS[row]}", fontsize=9)
        self._key = (name, row)

    @override
    def set(self, system: str = "three_link_lowRe", row: int = 0, c1: float = 0.0, c2: float = 0.0, a: float = 0.5,
            b: float = 0.3, tilt: float = 0.78, phase: float = 0.0) -> None:
        row = int(row)
        if (system, row) != self._key:
            self._switch(system, row)
        half = self.system.shape_limits[0][1]
        gait = shaped_gait(c1 * half, c2 * half, a * half, b * half, tilt)
        self.gait_artist.set(gait)
        r = gait(float(phase) * gait.period)
        self.dot.set_data([r[0]], [r[1]])
        self.body.set((0.0, 0.0, 0.0), r)
        try:
            est = displacement_estimates(self.system, gait, interactive=True)
        except SingularShapeError as e:
            self.flag.show("gait leaves the map or is singular")
            self.estimates, self.table = None, estimates_table(None, str(e))
        else:
            (lo1, hi1), (lo2, hi2) = self.system.shape_limits
            p = self.gait_artist.points
            inside = bool(np.all((p[:, 0] >= lo1) & (p[:, 0] <= hi1) & (p[:, 1] >= lo2) & (p[:, 1] <= hi2)))
            if inside:
                self.flag.hide()
            else:   # the numbers hold (the system is defined there), but the picture does not show all of it
                self.flag.show("the gait leaves the map's window")
            self.estimates, self.table = est, estimates_table(est)

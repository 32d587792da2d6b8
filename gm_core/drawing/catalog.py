"""The locomotion lab (notebook 12): every system of sysplotter's library, its curvature, a gait and the body.

sysplotter's workflow on one figure: pick a system by its file name
(:mod:`gm_core.systems.catalog`), see one row of its constraint curvature D(-A) as a map with the
same row of the connection field -A over it, shape a gait on the map, and see the body at a point
of the gait; the numbers (exact g(T), Stokes estimate, body-velocity integral) come from
:func:`gm_core.geometry.estimates.displacement_estimates` at its interactive resolution.

The lab offers all of the catalog's systems (:func:`lab_names`), each over its file's window. A system
with more than two shape variables is seen on the slice through its straight shape along its first two
(:func:`gm_core.systems.catalog.window_slice`). Where the live numbers cost more than a slider allows (the
continuous bodies, the panel-method chain, the tape measures and the chains of 19 links or more), the lab
reads the connection from the stored table sysplotter's way, bicubically interpolated
(:func:`gm_core.systems.catalog.tabulated`, within :data:`~gm_core.systems.catalog.TABLE_RTOL` of the live
system; outside the window a table has no values, so a gait leaving it is flagged), and draws the live body.
twin_rotor turns in space: its rows are the rotation rates of SO(3) (the numbers use SO(3)'s bracket), and
having no rigid parts in the plane it is drawn as its body frame with one dial per rotor angle. Each system's
curvature grid is computed once and cached (:func:`gm_core.geometry.estimates.curvature_grid`), so switching
back is quick.
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
from gm_core.drawing.toolkit.primitives import FrameArtist, SingularFlag
from gm_core.drawing.toolkit.style import PALETTE, Scene, new_figure
from gm_core.geometry.estimates import Estimates, displacement_estimates, shaped_gait
from gm_core.geometry.optimal import FourierGait, fourier_gait
from gm_core.groups import SE2
from gm_core.systems import LocomotionSystem, catalog
from gm_core.systems.motion import position_group
from gm_core.validation import FloatArray, SingularShapeError

__all__ = ["lab_names", "lab_system", "lab_gait", "LabScene"]


@functools.lru_cache(maxsize=1)
def lab_names() -> tuple[str, ...]:
    """The catalog's systems the lab offers: all of them, in the catalog's order."""
    return catalog.names()


@functools.lru_cache(maxsize=64)
def lab_system(name: str) -> LocomotionSystem:
    """The catalog's system ``name`` with two shape variables over its file's window (a slice if it has more),
    as its stored table where the catalog has one (:func:`gm_core.systems.catalog.tabulated`)."""
    if name not in lab_names():
        raise ValueError(f"name must be one of the lab's systems ({', '.join(lab_names())}); got {name!r}")
    if name in catalog.tabulated_names():
        return catalog.tabulated(name)
    return catalog.window_slice(name)


def lab_gait(system: LocomotionSystem, c1: float, c2: float, a: float, b: float, tilt: float) -> FourierGait:
    """The lab's gait: :func:`~gm_core.geometry.estimates.shaped_gait` with centre and sizes as fractions of
    the half-widths of ``system``'s window, about the window's middle (scaled along each axis if they differ)."""
    (lo1, hi1), (lo2, hi2) = system.shape_limits
    m, h = np.array([lo1 + hi1, lo2 + hi2]) / 2, np.array([hi1 - lo1, hi2 - lo2]) / 2
    if m[0] == m[1] == 0.0 and h[0] == h[1]:       # a centred square window: the gait in shape units
        return shaped_gait(c1 * h[0], c2 * h[0], a * h[0], b * h[0], tilt)
    unit = shaped_gait(c1, c2, a, b, tilt)
    return fourier_gait(h[:, None] * unit.a, h[:, None] * unit.b, m + h * unit.center, period=unit.period, name="shaped gait")


def _row_names(system: LocomotionSystem) -> tuple[str, ...]:
    return ROWS if position_group(system) is SE2 else ("ωx", "ωy", "ωz")


class RotorDials:
    """A body with no rigid parts in the plane (twin_rotor): its body frame's x and y axes and one dial per shape
    variable (a rotor's angle about the body's z axis), with a note saying so."""

    def __init__(self, ax: Axes, system: LocomotionSystem) -> None:
        self.bodies: list[Any] = []
        self.frame = FrameArtist(ax, length=0.5)
        colours = [PALETTE["orange"], PALETTE["purple"]]
        self.dials = [ax.plot([], [], "-o", color=colours[k % 2], lw=2, ms=4, markevery=[1])[0] for k in range(system.n_shape)]
        self.radii = np.linspace(0.9, 0.6, system.n_shape)
        self.note = ax.text(0.5, 0.02, f"{system.name}: no rigid parts in the plane;\nbody x, y axes and the rotor angles",
                            transform=ax.transAxes, ha="center", va="bottom", fontsize=8)

    def set(self, g: Any, r: Any) -> None:
        for line, radius, angle in zip(self.dials, self.radii, np.asarray(r, float)):
            line.set_data([0.0, radius * np.cos(angle)], [0.0, radius * np.sin(angle)])

    def set_visible(self, visible: bool) -> None:
        for artist in [self.frame.quiver, *self.dials, self.note]:
            artist.set_visible(visible)


def _first_shape(system: LocomotionSystem) -> FloatArray:
    """The window's middle ((0, 0) is outside the tape measures' windows), or a shape just beside it where the
    body is undefined there (the triangle waves' straight shape)."""
    limits = np.array(system.shape_limits)
    middle = limits.mean(axis=1)
    if np.all(np.isfinite(system.part_poses(middle))):
        return middle
    return middle + 0.01 * (limits[:, 1] - limits[:, 0])


def _body_artist(ax: Axes, system: LocomotionSystem) -> SystemArtist | RotorDials:
    return SystemArtist(ax, system, r=_first_shape(system), update_limits=False) if system.parts() else RotorDials(ax, system)


@functools.lru_cache(maxsize=64)
def _body_size(name: str) -> float:
    """Half-width of a square that holds ``name``'s body at its window's corners and middle (1 with no parts)."""
    system = lab_system(name)
    if not system.parts():
        return 1.0
    limits = system.shape_limits
    shapes = np.vstack([np.array(np.meshgrid(*limits)).reshape(2, -1).T, [_first_shape(system)]])
    return 1.1 * max(system_extent(system, r) for r in shapes)


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
        self.body = _body_artist(self.axb, self.system)
        self._bodies = {self.name: self.body}      # one body per system seen, hidden when not shown
        self._key: tuple[str, int] = ("", -1)
        self.estimates: Estimates | None = None
        self.table = ""
        self._switch(self.name, 0)

    def _switch(self, name: str, row: int) -> None:
        """Show another system or row: the map, the field, the axes and (for a new system) the body (made once per system)."""
        if name != self._key[0]:
            self.name, self.system = name, lab_system(name)
            limits = self.system.shape_limits
            self.map.limits = limits
            (lo1, hi1), (lo2, hi2) = limits
            self.map.image.set_extent((lo1, hi1, lo2, hi2))
            style_shape_axes(self.ax, self.system, limits=limits, pad=0.0)
            self.body.set_visible(False)
            if name not in self._bodies:
                self._bodies[name] = _body_artist(self.axb, self.system)
            self.body = self._bodies[name]
            self.body.set_visible(True)
            size = _body_size(name)
            self.axb.set_xlim(-size, size)
            self.axb.set_ylim(-size, size)
            self.axb.set_title(f"{name} (body frame)", fontsize=9)
        self.map.set(self.system, row)
        self.field.set(self.system, row)
        self.ax.set_title(f"D(-A) and -A, row {_row_names(self.system)[row]}", fontsize=9)
        self._key = (name, row)

    @override
    def set(self, system: str = "three_link_lowRe", row: int = 0, c1: float = 0.0, c2: float = 0.0, a: float = 0.5,
            b: float = 0.3, tilt: float = 0.78, phase: float = 0.0) -> None:
        row = int(row)
        if (system, row) != self._key:
            self._switch(system, row)
        gait = lab_gait(self.system, c1, c2, a, b, tilt)
        self.gait_artist.set(gait)
        r = gait(float(phase) * gait.period)
        self.dot.set_data([r[0]], [r[1]])
        try:
            self.body.set((0.0, 0.0, 0.0), r)
        except ValueError:      # the body's model is undefined there (a tape measure at alpha < 0): keep the last one
            pass
        try:
            est = displacement_estimates(self.system, gait, interactive=True)
        except SingularShapeError as e:
            self.flag.show("gait leaves the map or is singular")
            self.estimates, self.table = None, estimates_table(None, str(e), _row_names(self.system))
        else:
            (lo1, hi1), (lo2, hi2) = self.system.shape_limits
            p = self.gait_artist.points
            inside = bool(np.all((p[:, 0] >= lo1) & (p[:, 0] <= hi1) & (p[:, 1] >= lo2) & (p[:, 1] <= hi2)))
            if inside:
                self.flag.hide()
            else:   # the numbers hold (the system is defined there), but the picture does not show all of it
                self.flag.show("the gait leaves the map's window")
            self.estimates, self.table = est, estimates_table(est, rows=_row_names(self.system))

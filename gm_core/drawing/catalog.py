"""The locomotion lab (notebook 12): every system of sysplotter's library, its curvature, a gait and the body.

sysplotter's workflow on one figure: pick a system by its file name
(:mod:`gm_core.systems.catalog`), see one row of its constraint curvature D(-A) as a map with the
same row of the connection field -A over it, in the file's body frame or Hatton's minimum-perturbation
frame (:func:`lab_view`), shape a gait on the map with sliders, draw one by clicking points (a
periodic spline through them) or load one from a code cell, see the body at a point of the gait,
optimise the gait for speed or efficiency (:func:`gm_core.geometry.optimize_gait`) and animate it
(:func:`gm_core.drawing.gaits.animate_gait`); the numbers (exact g(T), Stokes estimate,
body-velocity integral) come from :func:`gm_core.geometry.estimates.displacement_estimates` at its
interactive resolution, in the chosen frame.

The lab offers all of the catalog's systems (:func:`lab_names`), each over its file's window, and any system
of two shape variables a user adds (:func:`add_lab_system`), over its own ``shape_limits``. A system
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
import time
from collections.abc import Callable
from typing import Any, ClassVar

import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from typing_extensions import override

from gm_core.drawing.connection import ConnectionFieldArtist, style_shape_axes
from gm_core.drawing.curvature import ROWS, CurvatureMapArtist, GaitArtist, estimates_table
from gm_core.drawing.gaits import animate_gait
from gm_core.drawing.motion import SystemArtist, system_extent
from gm_core.drawing.toolkit.primitives import FrameArtist, SingularFlag
from gm_core.drawing.toolkit.style import PALETTE, Scene, new_figure
from gm_core.geometry.coordinates import minimum_perturbation_coordinates
from gm_core.geometry.estimates import Estimates, displacement_estimates, shaped_gait
from gm_core.geometry.optimal import FourierGait, OptimalGait, fourier_fit, fourier_gait, optimize_gait
from gm_core.groups import SE2
from gm_core.systems import LocomotionSystem, catalog
from gm_core.systems.gaits import Gait, GaitLike, as_gait
from gm_core.systems.motion import Trajectory, position_group
from gm_core.validation import FloatArray, SingularShapeError, check_option

__all__ = ["lab_names", "lab_system", "add_lab_system", "lab_gait", "LAB_FRAMES", "OBJECTIVES", "lab_view", "drawn_gait", "LabScene"]

#: The lab's body frames, in the order of its dropdown.
LAB_FRAMES = ("file's frame", "minimum perturbation")

#: The optimiser's objectives as the lab names them: speed is distance per cycle (the cycle's
#: period is fixed), efficiency that distance per unit of the system's cost metric.
OBJECTIVES = {"speed": "displacement", "efficiency": "efficiency"}


#: Systems a user added to the lab (:func:`add_lab_system`), by name, in the order added.
_OWN: dict[str, LocomotionSystem] = {}


def lab_names() -> tuple[str, ...]:
    """The systems the lab offers: all of the catalog's, in its order, then those added with :func:`add_lab_system`."""
    return catalog.names() + tuple(_OWN)


def add_lab_system(system: LocomotionSystem, name: str | None = None) -> str:
    """Offer ``system`` (a locomotion system of two shape variables: for more, a slice,
    :func:`gm_core.systems.shape_slice`) in the lab under ``name`` (default: its own name),
    over its ``shape_limits``; returns the name. A name is given once: one of the catalog's,
    or one already given to another system, raises ValueError."""
    if not isinstance(system, LocomotionSystem):
        raise TypeError(f"system must be a locomotion system (gm_core.systems); got {type(system).__name__}")
    if system.n_shape != 2:
        raise ValueError(f"system must have two shape variables (the lab's map is a plane); {system.name} has "
                         f"{system.n_shape}: add a slice of it, gm_core.systems.shape_slice(system, ...)")
    name = system.name if name is None else name
    if not isinstance(name, str) or not name.strip():
        raise TypeError(f"name must be a non-empty string; got {name!r}")
    if name in catalog.names() or _OWN.get(name, system) is not system:
        raise ValueError(f"name {name!r} is taken (by {'the catalog' if name in catalog.names() else 'another system'}): "
                         "give this system another name")
    _OWN[name] = system
    return name


def lab_system(name: str) -> LocomotionSystem:
    """The lab's system ``name``: one added with :func:`add_lab_system` as it is, else the catalog's with two
    shape variables over its file's window (a slice if it has more), as its stored table where the catalog
    has one (:func:`gm_core.systems.catalog.tabulated`)."""
    if name in _OWN:
        return _OWN[name]
    if name not in catalog.names():
        raise ValueError(f"name must be one of the lab's systems ({', '.join(lab_names())}); got {name!r}")
    return _catalog_system(name)


@functools.lru_cache(maxsize=64)
def _catalog_system(name: str) -> LocomotionSystem:
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
    try:
        if np.all(np.isfinite(system.part_poses(middle))):
            return middle
    except ValueError:          # a reframed body refuses NaN poses
        pass
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


@functools.lru_cache(maxsize=64)
def lab_view(name: str, frame: str = "file's frame") -> LocomotionSystem:
    """The lab's system ``name`` seen from ``frame`` (one of :data:`LAB_FRAMES`), solved once and cached.

    "file's frame" is :func:`lab_system` itself; "minimum perturbation" is Hatton's frame over the
    file's window (:func:`~gm_core.geometry.coordinates.minimum_perturbation_coordinates`, about a
    tenth of a second). Raises SingularShapeError if the window holds singular shapes, or if the system
    turns in SO(3) (twin_rotor; the frame is solved in SE(2)).
    """
    frame = check_option(frame, "frame", LAB_FRAMES)
    system = lab_system(name)
    if frame != LAB_FRAMES[0] and position_group(system) is not SE2:
        raise SingularShapeError(f"{name} turns in {position_group(system).name}; the minimum-perturbation frame is solved in SE(2)")
    return system if frame == LAB_FRAMES[0] else minimum_perturbation_coordinates(system, system.shape_limits)


def drawn_gait(points: Any) -> Gait:
    """The gait drawn through clicked shapes ``points`` (K >= 3, 2): the periodic cubic spline through them,
    period 1 (:meth:`~gm_core.systems.gaits.Gait.from_samples`)."""
    return Gait.from_samples(points, 1.0, name="drawn gait")


class LabScene(Scene):
    """Left: a row of D(-A) with the same row of -A, a gait and the shape at ``phase``; right: the body there.

    Values: ``system`` (one of :func:`lab_names`), ``frame`` (one of :data:`LAB_FRAMES`), ``row``
    (0, 1, 2: x, y, θ), the gait ``c1, c2`` (centre), ``a, b`` (sizes), ``tilt`` (as
    :func:`~gm_core.geometry.estimates.shaped_gait`), the centre and sizes as fractions of the
    window's half-width, and ``phase`` (where along the gait the body is drawn, 0 to 1). A gait
    drawn (:meth:`add_point`), loaded (:meth:`load_gait`) or optimised (:meth:`optimize`) replaces
    the sliders' gait until a gait slider or the system changes. ``self.table`` is the three
    estimates as HTML, ``self.estimates`` the numbers (None when the gait is singular or leaves
    the window where the frame is defined, when a flag says so).
    """

    MAP_N: ClassVar[int] = 33
    FIELD_N: ClassVar[int] = 9
    #: The optimiser's bounds: Fourier order, iteration cap, seconds (it stops after the iteration
    #: that passes them) and time steps per cycle (its objective's resolution).
    OPT_ORDER: ClassVar[int] = 2
    OPT_MAXITER: ClassVar[int] = 25
    OPT_SECONDS: ClassVar[float] = 6.0
    OPT_INTERVALS: ClassVar[int] = 256

    def __init__(self, system: str = "three_link_lowRe", **options: Any) -> None:
        self.name = system
        self.system = lab_system(system)
        super().__init__(**options)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, (self.ax, self.axb) = new_figure(1, 2, figsize=(9, 3.3), layout="compressed",
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
        self.view: LocomotionSystem = self.system
        self.frame_error = ""
        self.map = CurvatureMapArtist(self.ax, self.system, 0, limits=limits, n=self.MAP_N)
        self.field = ConnectionFieldArtist(self.ax, self.system, 0, n=self.FIELD_N, color="0.25")
        self.gait_artist = GaitArtist(self.ax)
        (self.clicks,) = self.ax.plot([], [], "+", color=PALETTE["vermillion"], ms=9, mew=2, zorder=7)
        (self.dot,) = self.ax.plot([], [], "o", color=PALETTE["vermillion"], ms=7, zorder=6)
        self.flag = SingularFlag(self.ax)
        self.body = _body_artist(self.axb, self.system)
        self._bodies = {(self.name, LAB_FRAMES[0]): self.body}   # one body per system and frame seen, hidden when not shown
        self._key: tuple[str, str, int] = ("", "", -1)
        self._sliders: tuple[Any, ...] = ()
        self.points: list[tuple[float, float]] = []
        self.custom: Gait | None = None
        self.gait: Gait = shaped_gait(a=0.5, b=0.3)
        self.row = 0
        self.estimates: Estimates | None = None
        self.table = ""
        self._switch(self.name, LAB_FRAMES[0], 0)

    def _switch(self, name: str, frame: str, row: int) -> None:
        """Show another system, frame or row: the map, the field, the axes and (for a new system) the body."""
        frame = check_option(frame, "frame", LAB_FRAMES)
        if name != self._key[0]:
            self.name, self.system = name, lab_system(name)
            limits = self.system.shape_limits
            self.map.limits = limits
            (lo1, hi1), (lo2, hi2) = limits
            self.map.image.set_extent((lo1, hi1, lo2, hi2))
            style_shape_axes(self.ax, self.system, limits=limits, pad=0.0)
            size = _body_size(name)
            self.axb.set_xlim(-size, size)
            self.axb.set_ylim(-size, size)
        if (name, frame) != self._key[:2]:
            try:
                self.view, self.frame_error = lab_view(name, frame), ""
            except SingularShapeError as e:   # the kinematic snake's window holds singular shapes
                self.view, self.frame_error = self.system, f"no minimum-perturbation frame: {e}"
            shown = LAB_FRAMES[0] if self.view is self.system else frame
            self.body.set_visible(False)
            if (name, shown) not in self._bodies:     # its parts placed in the frame shown
                self._bodies[name, shown] = _body_artist(self.axb, self.view)
            self.body = self._bodies[name, shown]
            self.body.set_visible(True)
            self.axb.set_title(f"{name} ({shown})", fontsize=9)
        self.map.set(self.view, row)
        self.field.set(self.view, row)
        #: the names of the rows of the system shown (x, y, θ in SE(2); ωx, ωy, ωz in SO(3))
        self.row_names = _row_names(self.system)
        self.ax.set_title(f"D(-A) and -A, row {self.row_names[row]}", fontsize=9)
        self._key, self.row = (name, frame, row), row

    @override
    def set(self, system: str = "three_link_lowRe", row: int = 0, c1: float = 0.0, c2: float = 0.0, a: float = 0.5,
            b: float = 0.3, tilt: float = 0.78, phase: float = 0.0, frame: str = "file's frame") -> None:
        row = int(row)
        if (system, frame, row) != self._key:
            self._switch(system, frame, row)
        sliders = (system, c1, c2, a, b, tilt)
        if sliders != self._sliders:   # the sliders' gait again: a drawn, loaded or optimised one is let go
            self._sliders, self.custom, self.points = sliders, None, []
        self.gait = self.custom if self.custom is not None else lab_gait(self.system, c1, c2, a, b, tilt)
        self.clicks.set_data([p[0] for p in self.points], [p[1] for p in self.points])
        self._show(float(phase))

    def _show(self, phase: float) -> None:
        """Draw ``self.gait``, the body at ``phase`` of it, and its three numbers in the frame shown."""
        gait = self.gait
        self.gait_artist.set(gait)
        r = gait(phase * gait.period)
        self.dot.set_data([r[0]], [r[1]])
        try:
            self.body.set((0.0, 0.0, 0.0), r)
        except ValueError:      # the body's model is undefined there (a tape measure at alpha < 0): keep the last one
            pass
        # the flag sits on the map (264 px wide): each message in lines that fit it
        said = ["no minimum-perturbation\nframe: the file's"] if self.frame_error else []
        try:
            est = displacement_estimates(self.view, gait, interactive=True)
        except SingularShapeError as e:
            where = "the minimum-perturbation window" if self.view is not self.system else "the map"
            self.estimates, self.table = None, estimates_table(None, str(e), _row_names(self.system))
            said.append(f"gait is singular or leaves\n{where}")
        else:
            (lo1, hi1), (lo2, hi2) = self.system.shape_limits
            p = self.gait_artist.points
            if not np.all((p[:, 0] >= lo1) & (p[:, 0] <= hi1) & (p[:, 1] >= lo2) & (p[:, 1] <= hi2)):
                # the numbers hold (the system is defined there), but the picture does not show all of it
                said.append("the gait leaves the map's window")
            self.estimates, self.table = est, estimates_table(est, rows=_row_names(self.system))
        if said:
            self.flag.show("\n".join(said))
        else:
            self.flag.hide()
        if self.frame_error:
            self.table += estimates_table(None, self.frame_error)

    # -- gaits not made by the sliders -------------------------------------------------------
    def add_point(self, x: float, y: float) -> int:
        """Add the shape (x, y) to the gait being drawn; from 3 points on, the gait is the periodic
        spline through them (:func:`drawn_gait`). Returns the number of points; call ``set`` after."""
        self.points.append((float(x), float(y)))
        if len(self.points) >= 3:
            self.custom = drawn_gait(self.points)
        return len(self.points)

    def clear_points(self) -> None:
        """Forget the drawn or loaded gait: the sliders' gait again (call ``set`` after)."""
        self.points, self.custom = [], None

    def load_gait(self, gait: GaitLike, period: float = 1.0) -> Gait:
        """Use ``gait`` (a Gait, a callable t -> r of period ``period``, or closed-path shapes (K, 2),
        a periodic spline through them) until a gait slider or the system changes; call ``set`` after.
        Raises ValueError or TypeError naming ``gait`` if it is not a closed gait of two shape variables."""
        if isinstance(gait, Gait) or callable(gait):
            loaded = as_gait(gait, period)
        else:
            points = np.asarray(gait, dtype=float) if not isinstance(gait, (str, bytes)) else None
            if points is None or points.ndim != 2 or points.shape[-1] != 2:
                shape = "a string" if points is None else f"shape {points.shape}"
                raise ValueError(f"gait must be shapes (K, 2) of a closed path, a callable t -> r or a Gait; got {shape}")
            loaded = Gait.from_samples(points, period, name="loaded gait")
        if loaded.n_shape != 2:
            raise ValueError(f"gait must have 2 shape variables, as {self.name} in the lab; got {loaded.n_shape}")
        loaded.require_closed("the lab")
        self.custom, self.points = loaded, []
        return loaded

    def optimize(self, objective: str = "speed", callback: Callable[[int, float], object] | None = None) -> OptimalGait:
        """The gait shown, optimised for ``objective`` ("speed" or "efficiency", :data:`OBJECTIVES`) by
        :func:`~gm_core.geometry.optimize_gait`, becomes the gait shown; returns the OptimalGait.

        As in sysplotter, the optimiser measures in the minimum-perturbation frame over the file's
        window (confined to it), starting from the gait shown (its Fourier series of order
        :attr:`OPT_ORDER`); it stops after :attr:`OPT_MAXITER` iterations or the first past
        :attr:`OPT_SECONDS`. ``callback(iteration, value)`` reports progress. Call ``set`` after.
        """
        objective = check_option(objective, "objective", tuple(OBJECTIVES))
        start = self.gait if isinstance(self.gait, FourierGait) else fourier_fit(self.gait, self.OPT_ORDER)
        try:
            system, coordinates = lab_view(self.name, LAB_FRAMES[1]), "minimum perturbation"
        except SingularShapeError:
            system, coordinates = self.system, "given"
        t0 = time.perf_counter()

        def progress(it: int, value: float) -> None:
            if callback is not None:
                callback(it, value)
            if time.perf_counter() - t0 > self.OPT_SECONDS:
                raise StopIteration   # scipy's way for a callback to end the search, keeping the best so far

        result = optimize_gait(system, OBJECTIVES[objective], order=self.OPT_ORDER, start=start,
                               coordinates=coordinates, maxiter=self.OPT_MAXITER, intervals=self.OPT_INTERVALS,
                               callback=progress)
        self.custom, self.points = result.gait, []
        return result

    def animation(self, n_frames: int = 32, cycles: int = 2) -> tuple[FuncAnimation, Figure, Trajectory]:
        """The gait shown, on the row shown, with the body moving in the frame shown: (anim, fig, traj) of
        :func:`~gm_core.drawing.gaits.animate_gait`, for the course's player."""
        return animate_gait(self.view, self.gait, n_frames=n_frames, row=self.row, cycles=cycles)

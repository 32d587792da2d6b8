"""Gaits (book chapter 3): a gait drawn on the three connection fields with the motion it makes
(a live scene), and the same as an animation that plays without a kernel.

Trajectories come from :func:`gm_core.systems.motion.trajectory` (fourth-order Magnus steps).
"""
from __future__ import annotations

import warnings
from collections.abc import Callable, Mapping
from typing import Any, ClassVar, TypedDict

import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.artist import Artist
from matplotlib.backend_bases import MouseEvent
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from typing_extensions import override

from gm_core.drawing.connection import (
    ROW_LABELS,
    WIDE_SHAPES,
    ConnectionFieldArtist,
    FieldGridScene,
    GridSize,
    ShapeCursorArtist,
    draw_singular_set,
    style_shape_axes,
    thin_labels,
)
from gm_core.drawing.motion import MovingView, SystemArtist, draw_system_naive, style_world_axes, system_extent
from gm_core.drawing.toolkit.primitives import SingularFlag, TrailArtist, animate
from gm_core.drawing.toolkit.recent import Recent
from gm_core.drawing.toolkit.style import PALETTE, PathText, freeze_layout, new_figure, readout, signed
from gm_core.systems import LocomotionSystem
from gm_core.systems.gaits import GAIT_FAMILIES, Gait, GaitLike, GaitWarning, as_gait, family_gait
from gm_core.systems.motion import Trajectory, net_displacement, trajectory
from gm_core.validation import FloatArray, SingularShapeError

__all__ = ["GaitScene", "GAIT_SHAPES", "animate_gait"]


#: The gait shapes of :class:`GaitScene`: the families of :mod:`gm_core.systems.gaits` and a loop drawn
#: with the mouse ("drawn": drag the dots on any shape-space axes).
GAIT_SHAPES = GAIT_FAMILIES + ("drawn",)


class _GaitValues(TypedDict, total=False):
    """The values of a :class:`GaitScene` (see its docstring); a missing one takes its default."""

    family: str
    amplitude: float
    center1: float
    center2: float
    aspect: float
    angle: float
    frame: str | None


#: What :meth:`GaitScene.motion` gives: the gait, its trajectory and None, or None and the error.
Motion = tuple[Gait, Trajectory | None, SingularShapeError | None]


class GaitScene(FieldGridScene):
    """A gait on the three connection fields and the motion it produces over one cycle.

    Values: ``family`` (one of :data:`GAIT_SHAPES`), ``amplitude`` (radius / semi-axis /
    amplitude), ``center1``, ``center2`` (centre in shape space), ``aspect`` (ratio of the second
    semi-axis or amplitude to the first), ``angle`` (ellipse tilt, serpenoid phase) and, when
    the scene was given several body frames, ``frame``. The world axes show the trail of the
    body frame over one period, the body at start and at g(T), and the net displacement per
    cycle ``net``. A gait that meets a singular shape raises the flag and hides the motion.

    With ``family="drawn"`` the loop is a periodic spline (:meth:`Gait.from_samples`) through
    control points drawn as dots on the shape axes; drag one with the mouse (ipympl delivers
    button_press / motion_notify / button_release events) and the motion follows. Options:
    ``system`` (required), ``frames`` (dict name -> system: the same system with different body
    frames), ``n`` (field grid), ``lim`` (world half-width), ``n_points`` (control points).
    """

    #: Magnus steps between two of the 61 frames: 720 per cycle put g(T) within ~1e-10 of
    #: net_displacement's converged value on the course's gaits (1e-12 relative), far below a pixel.
    substeps: ClassVar[int] = 12
    cache_size: ClassVar[int] = 256
    #: a press within this many pixels of a control point grabs it
    pick_px: ClassVar[float] = 12.0

    def __init__(self, system: LocomotionSystem, frames: Mapping[str, LocomotionSystem] | None = None,
                 n: GridSize | None = None, lim: float | None = None, n_points: int = 8, **options: Any) -> None:
        self.frames = dict(frames or {})
        self.system, self.n = system, n
        self.lim = lim or 1.3 * system_extent(system)
        self._cache: Recent[tuple[object, ...], Motion] = Recent(self.cache_size)
        self.n_points = int(n_points)
        self.points: FloatArray | None = None    # control points of the drawn loop (K, 2), seeded on first use
        self._grab: int | None = None
        self._values: _GaitValues = {}
        #: called (with no arguments) after a mouse edit; a panel sets it to its refresh
        self.on_edit: Callable[[], object] | None = None
        super().__init__(**options)

    @override
    def decorate(self) -> None:
        s = self.system
        self.fields: list[ConnectionFieldArtist] = []
        for i, ax in enumerate(self.field_axes):
            style_shape_axes(ax, s, ROW_LABELS[i])
            self.fields.append(ConnectionFieldArtist(ax, s, i, n=self.n, color="0.5"))
            draw_singular_set(ax, s)
        thin_labels(self.field_axes, self.ax)

    @override
    def create(self) -> None:
        s = self.system
        self.paths: list[tuple[Line2D, Line2D]] = []   # the gait and its start, on each field
        self.handles: list[Line2D] = []                 # the drawn loop's control points
        for ax in self.field_axes:
            (line,) = ax.plot([], [], color=PALETTE["blue"], lw=2)
            (start,) = ax.plot([], [], "o", color=PALETTE["blue"], ms=5)
            (dots,) = ax.plot([], [], "o", color=PALETTE["orange"], mec="k", ms=7, zorder=8)
            self.paths.append((line, start))
            self.handles.append(dots)
        # The window follows the motion through a transform, not through the axes limits: a new
        # limit would force a full redraw of all four axes instead of a blit.
        self.view = MovingView(self.ax, self.lim)
        self.ax.set_title("motion over one cycle")
        self.trail = TrailArtist(self.ax, color=PALETTE["green"], lw=2)
        grey: dict[str, Any] = dict(facecolor="0.8", alpha=0.5, edgecolor="0.5")
        self.start = SystemArtist(self.ax, s, styles={"link": grey, "chassis": grey})
        self.body = SystemArtist(self.ax, s)
        self.view.attach(self.trail.line, *(b.patch for art in (self.start, self.body) for b in art.bodies),
                         self.start.frame.quiver, self.body.frame.quiver)
        self.flag = SingularFlag(self.ax)
        self.text = readout(self.ax, 0.02, 0.02)
        self._moving: list[Artist | PathText] = [
            self.trail.line, self.start.frame.quiver, self.body.frame.quiver, self.flag.text, self.text,
            *(b.patch for art in (self.start, self.body) for b in art.bodies), *self.handles]
        canvas = self.fig.canvas
        self._cids = [canvas.mpl_connect("button_press_event", self.on_press),
                      canvas.mpl_connect("motion_notify_event", self.on_motion),
                      canvas.mpl_connect("button_release_event", self.on_release)]

    # -- the gait ------------------------------------------------------------------------------
    def seed_points(self, v: _GaitValues | None = None) -> FloatArray:
        """Control points of the drawn loop: K samples of the current family's gait (a circle at first)."""
        v = (self._values if v is None else v).copy()
        fam = v.get("family", "circle")
        v["family"] = "circle" if fam == "drawn" else fam
        g = self.gait(v)
        self.points = points = g(np.arange(self.n_points) / self.n_points * g.period)
        return points

    def gait(self, v: _GaitValues) -> Gait:
        """The :class:`~gm_core.systems.gaits.Gait` for the values ``v`` (see the class docstring)."""
        fam = v.get("family", "circle")
        if fam == "drawn":
            points = self.seed_points({**v, "family": "circle"}) if self.points is None else self.points
            with warnings.catch_warnings():
                # the control points are a closed loop by construction: no "open path" warning
                warnings.simplefilter("ignore", GaitWarning)
                return Gait.from_samples(points, name="drawn loop")
        return family_gait(fam, v["amplitude"], (v["center1"], v["center2"]), v.get("aspect", 1.0),
                           v.get("angle", 0.0))

    def _key(self, v):
        fam = v.get("family", "circle")
        frame = v.get("frame")
        if fam == "drawn":
            return ("drawn", frame, self.points.tobytes())
        return (fam, frame, float(v["amplitude"]), float(v["center1"]), float(v["center2"]),
                float(v.get("aspect", 1.0)), float(v.get("angle", 0.0)))

    def motion(self, v: _GaitValues) -> Motion:
        """(gait, trajectory, error) for the values; the trajectory is None (and ``error`` the
        SingularShapeError) when the gait meets a singular shape. Cached by gait parameters."""
        gait = self.gait(v)
        key = self._key(v)
        def make() -> Motion:
            try:
                return (gait, trajectory(self.system, gait, 61, substeps=self.substeps), None)
            except SingularShapeError as e:
                return (gait, None, e)

        return self._cache.get(key, make)

    def _use_frame(self, frame: str | None) -> None:
        if frame is None or not self.frames:
            return
        system = self.frames[frame]
        if system is self.system:
            return
        self.system = system
        for f in self.fields:
            f.set(system)
        self.start.system = self.body.system = system

    def _fit_view(self, g: FloatArray) -> None:
        """Centre the window on the trail, at least the default size, with room for the body."""
        lo, hi = g[:, :2].min(0), g[:, :2].max(0)
        half = 1.2 * max(self.lim, 0.5 * float(np.max(hi - lo)) + 0.9 * self.lim)
        # the motion in the upper part of the window: the readout's two lines below it stay clear
        self.view.set((lo + hi) / 2 - [0.0, 0.17 * half], half)

    @override
    def set(self, family: str = "circle", amplitude: float = 1.0, center1: float = 0.0, center2: float = 0.0,
            aspect: float = 0.6, angle: float = 0.0, frame: str | None = None) -> None:
        v: _GaitValues = dict(family=family, amplitude=amplitude, center1=center1, center2=center2, aspect=aspect,
                              angle=angle, frame=frame)
        if family == "drawn" and self.points is None:
            self.seed_points({**(self._values or v), "family": self._values.get("family", "circle")})
        self._values = v
        self._use_frame(frame)
        gait, self.traj, err = self.motion(v)
        path = gait(np.linspace(0.0, gait.period, 161))
        for line, start in self.paths:
            line.set_data(path[:, 0], path[:, 1])
            start.set_data([path[0, 0]], [path[0, 1]])
        pts = self.points if family == "drawn" and self.points is not None else np.empty((0, 2))   # seeded above
        for dots in self.handles:
            dots.set_data(pts[:, 0], pts[:, 1])
        # Everything that can change (the flag appears, the body is hidden) is marked changed on
        # every update, so the blitter learns the moving artists on the first frame.
        self.view.touch()
        for a in self._moving:
            a.stale = True
        if self.traj is None:
            self.net: FloatArray | None = None
            self.flag.show("gait meets a singular shape")
            self.message = str(err)
            self.trail.line.set_visible(False)
            self.body.set_visible(False)
            # The picture is a function of the values alone: the body at its start (identity,
            # the gait's first shape) in the default window, not the start and window of the
            # last non-singular gait the slider passed through (a quick drag's ghost, issue 19).
            self._fit_view(np.zeros((1, 3)))
            self.start.set(np.zeros(3), path[0])
            self.text.set_text("no motion: the connection is\nundefined on the red line")
            return
        self.flag.hide()
        self.message = ""
        self.trail.line.set_visible(True)
        self.body.set_visible(True)
        self.net = self.traj.g[-1]
        self._fit_view(self.traj.g)
        self.start.set(self.traj.g[0], self.traj.r[0])
        self.trail.set(self.traj.g[:, :2])
        self.body.set(self.traj.g[-1], self.traj.r[-1])
        self.text.set_text(f"net displacement per cycle\nx, y, θ: {signed(self.net)}")

    # -- mouse editing of the drawn loop -------------------------------------------------------
    def _nearest(self, event):
        if self._values.get("family") != "drawn" or event.inaxes not in self.field_axes or self.points is None:
            return None
        px = event.inaxes.transData.transform(self.points)
        d = np.hypot(px[:, 0] - event.x, px[:, 1] - event.y)
        k = int(np.argmin(d))
        return k if d[k] <= self.pick_px else None

    def on_press(self, event: MouseEvent) -> None:
        """Grab the control point under the mouse (left button, drawn loop only)."""
        if getattr(event, "button", 1) not in (1, None):
            return
        self._grab = self._nearest(event)

    def on_motion(self, event: MouseEvent) -> None:
        """Move the grabbed control point to the mouse (clamped to the shape window) and update."""
        if self._grab is None or self.points is None or event.inaxes not in self.field_axes or event.xdata is None \
                or event.ydata is None:
            return
        (lo1, hi1), (lo2, hi2) = self.system.shape_limits
        pts = self.points.copy()
        pts[self._grab] = (np.clip(event.xdata, lo1, hi1), np.clip(event.ydata, lo2, hi2))
        self.points = pts
        self._edited()

    def on_release(self, event: MouseEvent) -> None:
        """Let go of the control point."""
        if self._grab is not None:
            self._grab = None
            self._edited()

    def _edited(self) -> None:
        if self.on_edit is not None:
            self.on_edit()
        else:
            self.set(**self._values)
            self.fig.canvas.draw_idle()

    def animation(self, n_frames: int = 60, cycles: int = 2, row: int = 2) -> tuple[FuncAnimation, Figure, Trajectory]:
        """A kernel-free animation (FuncAnimation) of the current gait in the world: see :func:`animate_gait`."""
        return animate_gait(self.system, self.gait(self._values), n_frames=n_frames, cycles=cycles, row=row)

    @override
    def replot(self, family: str = "circle", amplitude: float = 1.0, center1: float = 0.0, center2: float = 0.0,
               aspect: float = 0.6, angle: float = 0.0, frame: str | None = None) -> None:
        self._use_frame(frame)
        v: _GaitValues = dict(family=family, amplitude=amplitude, center1=center1, center2=center2, aspect=aspect,
                              angle=angle)
        gait = self.gait(v)
        path = gait(np.linspace(0.0, gait.period, 161))
        for i, ax in enumerate(self.field_axes):
            ax.clear()
            style_shape_axes(ax, self.system, ROW_LABELS[i])
            ConnectionFieldArtist(ax, self.system, i, n=self.n)
            draw_singular_set(ax, self.system)
            ax.plot(path[:, 0], path[:, 1], color=PALETTE["blue"])
        self.ax.clear()
        style_world_axes(self.ax, self.lim)
        try:
            g = net_displacement(self.system, gait)
            tr = trajectory(self.system, gait, 61)
            self.ax.plot(tr.g[:, 0], tr.g[:, 1], color=PALETTE["green"])
            draw_system_naive(self.ax, self.system, g, tr.r[-1])
        except SingularShapeError:
            self.ax.set_title("singular")


def animate_gait(system: LocomotionSystem, gait: GaitLike, n_frames: int = 60, row: int = 2, cycles: int = 1,
                 world_lim: float | None = None, interval: float = 60) -> tuple[FuncAnimation, Figure, Trajectory]:
    """An animation (FuncAnimation): the gait on connection row ``row`` and the body moving in the plane.

    Left: shape space with the field -A^row, the gait and a cursor at the current shape. Right: the
    body at g(t) with its trail. Returns (anim, fig, traj). Use ``drawing.primitives.jshtml(anim)``.
    Frames are rendered at the standard resolution, so animation text is never smaller than on a
    live figure.
    """
    gait = as_gait(gait)
    traj = trajectory(system, gait, n_frames, cycles=cycles)
    (lo1, hi1), (lo2, hi2) = system.shape_limits
    wide = (hi1 - lo1) > WIDE_SHAPES * (hi2 - lo2)   # a wide shape window gets the wider axes
    fig, (axs, axw) = new_figure(1, 2, figsize=(8, 3.8), gridspec_kw=dict(width_ratios=[1.7, 1] if wide else [1, 1]))
    style_shape_axes(axs, system, f"gait on {ROW_LABELS[row]}")
    ConnectionFieldArtist(axs, system, row, color="0.5")
    draw_singular_set(axs, system)
    path = gait(np.linspace(0, gait.period, 200))
    axs.plot(path[:, 0], path[:, 1], color=PALETTE["blue"], lw=2)
    cursor = ShapeCursorArtist(axs)
    body = SystemArtist(axw, system, traj.g[0], traj.r[0])
    trail = TrailArtist(axw, color=PALETTE["green"])
    size = system_extent(system)
    lo = traj.g[:, :2].min(0) - 1.1 * size
    hi = traj.g[:, :2].max(0) + 1.1 * size
    c, half = (lo + hi) / 2, max(hi - lo) / 2
    if world_lim is not None:
        half = world_lim
    style_world_axes(axw, half, c)
    axw.set_title(system.name)

    def update(k: int) -> list[Artist]:
        k = int(k)
        body.set(traj.g[k], traj.r[k])
        trail.set(traj.g[: k + 1, :2])
        cursor.set(traj.r[k], gait.velocity(np.array([traj.t[k]]))[0] * 0.05)
        return []

    update(0)
    freeze_layout(fig)   # lay out once: every frame is drawn with the same axes (about 40 % faster)
    anim = animate(fig, update, range(n_frames), interval=interval)
    return anim, fig, traj



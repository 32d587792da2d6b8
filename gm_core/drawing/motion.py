"""Locomoting bodies (book chapter 3): a system drawn at position g and shape r, its body
velocity, and a world view that follows the motion without changing axis limits.

The physics (poses of the parts, trajectories) lives in :mod:`gm_core.systems` and
:mod:`gm_core.systems.motion`; every artist here is built once and moved in place.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, cast

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.quiver import Quiver
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.drawing.toolkit.axes import square_axes
from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist, SingularFlag, TrailArtist
from gm_core.drawing.toolkit.style import PALETTE, PathText, Scene, readout, signed
from gm_core.groups import SE2
from gm_core.systems import Ackerman, DifferentialDrive, LocomotionSystem
from gm_core.systems.motion import Trajectory, drive
from gm_core.validation import FloatArray, SingularShapeError

__all__ = ["PART_STYLES", "SystemArtist", "system_extent", "draw_system_naive", "VelocityArtist",
           "style_world_axes", "MovingView", "CarScene", "DiffDriveScene", "AckermanScene"]

#: Polygon properties of a system's parts, by their kind.
PART_STYLES: dict[str, dict[str, Any]] = {
    "chassis": dict(facecolor=PALETTE["blue"], alpha=0.35, edgecolor="k"),
    "wheel": dict(facecolor="0.15", alpha=0.9, edgecolor="k"),
    "link": dict(facecolor=PALETTE["orange"], alpha=0.6, edgecolor="k"),
}


# ------------------------------------------------------------------------------ bodies
class SystemArtist:
    """A locomotor drawn at position g and shape r: one polygon per rigid part plus its body frame."""

    def __init__(self, ax: Axes, system: LocomotionSystem, g: ArrayLike = (0.0, 0.0, 0.0), r: ArrayLike = (0.0, 0.0),
                 frame_length: float | None = None, styles: Mapping[str, dict[str, Any]] | None = None,
                 zorder: float = 3, update_limits: bool = True) -> None:
        self.system = system
        self.parts = system.parts()
        styles = dict(PART_STYLES, **(styles or {}))
        self.bodies = [BodyArtist(ax, p.outline, update_limits=update_limits, **dict(styles.get(p.kind, {}), zorder=zorder))
                       for p in self.parts]
        size = max(np.ptp(np.vstack([p.outline for p in self.parts]), axis=0))
        self.frame = FrameArtist(ax, length=frame_length or 0.3 * size)
        self.set(g, r)

    def set(self, g: ArrayLike, r: ArrayLike) -> None:
        """Place the body: part i at g o pose_i(r)."""
        self.g = np.asarray(g, dtype=float)
        self.r = np.asarray(r, dtype=float)
        poses = SE2.compose(self.g, self.system.part_poses(self.r))
        for b, pose in zip(self.bodies, poses):
            b.set(pose)
        self.frame.set(self.g)

    def set_visible(self, visible: bool) -> None:
        for b in self.bodies:
            b.patch.set_visible(visible)
        self.frame.quiver.set_visible(visible)

    def world_outlines(self) -> list[FloatArray]:
        """Current world outlines (list of (k, 2)) of the parts (for tests)."""
        return [np.asarray(b.patch.get_xy()) for b in self.bodies]


def system_extent(system: LocomotionSystem, r: ArrayLike | None = None) -> float:
    """Half-size of a square (centred on the body frame) that holds the body at shape r (default 0)."""
    r = np.zeros(system.n_shape) if r is None else np.asarray(r, float)
    pts = np.vstack([SE2.act_on_points(pose, p.outline)
                     for p, pose in zip(system.parts(), system.part_poses(r))])
    return float(np.abs(pts).max())


def draw_system_naive(ax: Axes, system: LocomotionSystem, g: ArrayLike, r: ArrayLike) -> None:
    """Plot the body from scratch with ax.fill (the clear-and-replot baseline)."""
    poses = SE2.compose(np.asarray(g, float), system.part_poses(np.asarray(r, float)))
    for p, pose in zip(system.parts(), poses):
        xy = SE2.act_on_points(pose, p.outline)
        ax.fill(xy[:, 0], xy[:, 1], **PART_STYLES.get(p.kind, {}))


class VelocityArtist:
    """The body velocity xi drawn at the body frame: an arrow for (xi^x, xi^y) and an arc for xi^theta."""

    def __init__(self, ax: Axes, scale: float = 1.0, color: ColorType = PALETTE["purple"], zorder: float = 6) -> None:
        self.scale = float(scale)
        self.quiver = ax.quiver([0.0], [0.0], [0.0], [0.0], color=color, angles="xy", scale_units="xy",
                                scale=1.0, width=0.012, zorder=zorder)
        (self.arc,) = ax.plot([], [], color=color, lw=2, zorder=zorder)
        (self.tip,) = ax.plot([], [], marker=(3, 0, 0), color=color, ms=8, ls="none", zorder=zorder)
        self.xi = np.zeros(3)

    def set(self, g: ArrayLike, xi: ArrayLike) -> bool:
        """Show xi (body velocity) at pose g; hidden (returns False) if xi is not finite."""
        xi = np.asarray(xi, dtype=float)
        ok = bool(np.all(np.isfinite(xi)))
        for a in (self.quiver, self.arc, self.tip):
            a.set_visible(ok)
        if not ok:
            return False
        self.xi = xi
        g = np.asarray(g, dtype=float)
        v = SE2.body_to_world(g, xi)[:2] * self.scale
        self.quiver.set_offsets([g[:2]])
        self.quiver.set_UVC([v[0]], [v[1]])
        w = float(np.clip(xi[2] * self.scale, -1.9 * np.pi, 1.9 * np.pi))
        rad = 0.25
        s = np.linspace(0.0, w, 30) + g[2] + np.pi / 2
        self.arc.set_data(g[0] + rad * np.cos(s), g[1] + rad * np.sin(s))
        self.tip.set_data([g[0] + rad * np.cos(s[-1])], [g[1] + rad * np.sin(s[-1])])
        self.tip.set_marker((3, 0, np.degrees(s[-1]) + (0 if w >= 0 else 180)))
        return True

    def world_vector(self) -> FloatArray:
        """The drawn linear-velocity arrow (2,) in world coordinates (for tests)."""
        U, V = cast(np.ma.MaskedArray, self.quiver.U), cast(np.ma.MaskedArray, self.quiver.V)   # set_UVC's arrays
        return np.array([U[0], V[0]])


def style_world_axes(ax: Axes, half: float, center: Sequence[float] = (0.0, 0.0)) -> None:
    """Square world axes of half-width ``half`` about ``center``, light grid, four ticks per axis."""
    square_axes(ax, half, center, nticks=4)
    ax.tick_params(pad=2)


# ------------------------------------------------------------------------------ moving world view
class MovingView:
    """World axes whose visible window follows the motion without changing the axes limits.

    A live panel is redrawn by blitting (gm_core.drawing.toolkit.blit); a new axis limit forces a full
    redraw of the whole figure (~80 ms for a 2 x 2 figure). Here the axes keep fixed limits
    ``(-half0, half0)``; the artists attached with :meth:`attach` keep their *world* data and
    are drawn through ``view + transData``, where ``view`` maps the window ``center +- half`` onto
    the fixed limits. Grid lines, tick marks and tick labels (MaxNLocator(4), ScalarFormatter
    labels, as :func:`style_world_axes` shows them) are moving artists updated by :meth:`set`.
    Quiver arrows given in data units are rescaled with the window.
    """

    def __init__(self, ax: Axes, half: float, nticks: int = 4, max_ticks: int = 8) -> None:
        import matplotlib as mpl
        from matplotlib.collections import LineCollection
        from matplotlib.markers import TICKDOWN, TICKLEFT
        from matplotlib.ticker import MaxNLocator
        from matplotlib.transforms import Affine2D

        self.ax, self.half0 = ax, float(half)
        style_world_axes(ax, self.half0)
        ax.grid(False)
        ax.set_xticks([])
        ax.set_yticks([])
        self.view = Affine2D()
        self.transform = self.view + ax.transData
        self.locator = MaxNLocator(nticks)
        rc = mpl.rcParams
        self.grid = LineCollection([], colors=rc["grid.color"], linewidths=rc["grid.linewidth"],
                                   linestyles=rc["grid.linestyle"], alpha=0.3, zorder=1.5, snap=True)
        ax.add_collection(self.grid, autolim=False)
        length, width, pad = rc["xtick.major.size"], rc["xtick.major.width"], 1.0
        xt, yt = ax.get_xaxis_transform(), ax.get_yaxis_transform()
        (self.xticks,) = ax.plot([], [], ls="none", marker=TICKDOWN, ms=length, mew=width, color=rc["xtick.color"],
                                 transform=xt, clip_on=False)
        (self.yticks,) = ax.plot([], [], ls="none", marker=TICKLEFT, ms=length, mew=width, color=rc["ytick.color"],
                                 transform=yt, clip_on=False)
        size = rc["xtick.labelsize"] if not isinstance(rc["xtick.labelsize"], str) else 8.0
        gap = length + pad + 1.5
        self.xlabels = [PathText(ax, 0.0, 0.0, "", size=size, ha="center", va="top", coords="xaxis",
                                 offset=(0, -gap)) for _ in range(max_ticks)]
        self.ylabels = [PathText(ax, 0.0, 0.0, "", size=size, ha="right", va="center", coords="yaxis",
                                 offset=(-gap, 0)) for _ in range(max_ticks)]
        self.quivers: list[tuple[Quiver, float]] = []     # each with its scale at the window's start
        self.center, self.half = np.zeros(2), self.half0
        self.set((0.0, 0.0), self.half0)

    def attach(self, *artists: Artist) -> None:
        """Draw these artists (world data) through the moving window."""
        for a in artists:
            if isinstance(a, Quiver):
                a.set_offset_transform(self.transform)
                self.quivers.append((a, cast(float, a.scale)))   # arrows in data units: a fixed scale
            else:
                a.set_transform(self.transform)
        self.set(self.center, self.half)

    def limits(self) -> tuple[float, float, float, float]:
        """The world window shown: ``(x0, x1, y0, y1)``."""
        c, h = self.center, self.half
        return (c[0] - h, c[0] + h, c[1] - h, c[1] + h)

    def set(self, center: ArrayLike, half: float) -> None:
        from matplotlib.ticker import ScalarFormatter

        self.center, self.half = np.asarray(center, float).copy(), float(half)
        k = self.half0 / self.half
        self.view.clear().translate(-self.center[0], -self.center[1]).scale(k)
        for q, scale in self.quivers:
            q.scale = scale / k
            q.stale = True
        segs: list[list[list[float]]] = []
        xt: list[float] = []
        yt: list[float] = []
        for axis, (lo, hi), marks, labels in ((0, self.limits()[:2], xt, self.xlabels),
                                              (1, self.limits()[2:], yt, self.ylabels)):
            eps = 1e-9 * (hi - lo)
            locs = [v for v in self.locator.tick_values(lo, hi) if lo - eps <= v <= hi + eps]
            fmt = ScalarFormatter()
            fmt.create_dummy_axis()
            fmt.axis.set_view_interval(lo, hi)  # type: ignore[union-attr]  # create_dummy_axis has set it
            text = fmt.format_ticks(locs)
            for i, t in enumerate(labels):
                if i < len(locs):
                    p = (locs[i] - self.center[axis]) * k
                    t.set_position((p, 0.0) if axis == 0 else (0.0, p))
                    t.set_text(text[i].replace("-", "−"))
                    t.set_visible(True)
                else:
                    t.set_visible(False)
            for v in locs:
                p = (v - self.center[axis]) * k
                marks.append(p)
                segs.append([[p, -self.half0], [p, self.half0]] if axis == 0 else [[-self.half0, p], [self.half0, p]])
        self.grid.set_segments(segs)
        self.grid.set_transform(self.ax.transData)
        self.xticks.set_data(xt, np.zeros(len(xt)))
        self.yticks.set_data(np.zeros(len(yt)), yt)

    def touch(self) -> None:
        """Mark the view's artists changed (so a blitter counts them as moving from the first frame)."""
        for a in [self.grid, self.xticks, self.yticks] + self.xlabels + self.ylabels:
            a.stale = True




# ------------------------------------------------------------------------------ cars
def _fmt(xi: ArrayLike) -> str:
    return f"ξ = ({signed(xi)})"


class CarScene(Scene):
    """A car whose shape moves at a constant rate (chapter 3): trail, start, body and velocity.

    Subclasses give ``make_system()`` and ``shape_path(values) -> (r0, r_dot, duration)``. A
    path that reaches a singular shape raises the flag and hides the motion (``message`` says
    why). Options: ``system``, ``lim``.
    """

    lim: float = 4.0
    traj: Trajectory | None          # the last motion (None: it reached a singular shape)

    def __init__(self, system: LocomotionSystem | None = None, lim: float | None = None, **options: Any) -> None:
        self.system = system or self.make_system()
        self.lim = float(lim or self.lim)
        super().__init__(**options)

    def make_system(self) -> LocomotionSystem:
        raise NotImplementedError

    def shape_path(self, values: Mapping[str, float]) -> tuple[FloatArray, FloatArray, float]:
        raise NotImplementedError

    FIGSIZE = (5.5, 5.0)

    @override
    def decorate(self) -> None:
        style_world_axes(self.ax, self.lim)

    @override
    def create(self) -> None:
        ax = self.ax
        self.trail = TrailArtist(ax, color=PALETTE["green"], lw=2)
        self.start = SystemArtist(ax, self.system, styles={"chassis": dict(facecolor="0.8", alpha=0.4,
                                                                           edgecolor="0.5")})
        self.body = SystemArtist(ax, self.system)
        self.vel = VelocityArtist(ax, scale=1.0)
        self.flag = SingularFlag(ax)
        self.text = readout(ax, 0.02, 0.02)

    def compute(self, values: Mapping[str, float]) -> tuple[Trajectory, FloatArray, FloatArray]:
        r0, rd, T = self.shape_path(values)
        traj = drive(self.system, r0, rd, T)
        return traj, rd, self.system.body_velocity(traj.r[-1], rd)

    @override
    def set(self, **values: float) -> None:
        self.flag.text.stale = True  # may appear on any change: a moving artist from the first frame
        self.text.stale = True
        try:
            self.traj, rd, self.xi = self.compute(values)
        except SingularShapeError as e:
            self.traj = None
            self.flag.show("singular shape reached")
            self.message = str(e)
            self.trail.line.set_visible(False)
            self.body.set_visible(False)
            self.vel.set(np.zeros(3), np.full(3, np.nan))
            self.text.set_text("")
            return
        self.flag.hide()
        self.trail.line.set_visible(True)
        self.body.set_visible(True)
        self.start.set(self.traj.g[0], self.traj.r[0])
        self.trail.set(self.traj.g[:, :2])
        self.body.set(self.traj.g[-1], self.traj.r[-1])
        self.vel.set(self.traj.g[-1], self.xi)
        g = self.traj.g[-1]
        self.text.set_text(f"{_fmt(self.xi)}\ng(T) = ({g[0]:+.2f}, {g[1]:+.2f}, {g[2]:+.2f})")

    @override
    def replot(self, **values: float) -> None:
        ax = self.ax
        ax.clear()
        style_world_axes(ax, self.lim)
        try:
            traj, rd, xi = self.compute(values)
        except SingularShapeError:
            ax.set_title("singular shape reached")
            return
        ax.plot(traj.g[:, 0], traj.g[:, 1], color=PALETTE["green"], lw=2)
        draw_system_naive(ax, self.system, traj.g[-1], traj.r[-1])


class DiffDriveScene(CarScene):
    """Differential-drive car (3.8), (3.29): values ``wheel1_speed``, ``wheel2_speed``, ``duration``."""

    @override
    def make_system(self) -> DifferentialDrive:
        return DifferentialDrive(wheel_radius=0.3, half_width=0.5)

    @override
    def shape_path(self, v: Mapping[str, float]) -> tuple[FloatArray, FloatArray, float]:
        return np.zeros(2), np.array([v["wheel1_speed"], v["wheel2_speed"]]), v["duration"]


class AckermanScene(CarScene):
    """Kinematic-bicycle car (3.9): values ``wheel_speed``, ``steering``, ``steering_speed``, ``duration``."""

    @override
    def make_system(self) -> Ackerman:
        return Ackerman(wheel_radius=0.3, wheelbase=1.0)

    @override
    def shape_path(self, v: Mapping[str, float]) -> tuple[FloatArray, FloatArray, float]:
        return (np.array([0.0, v["steering"]]), np.array([v["wheel_speed"], v["steering_speed"]]),
                v["duration"])

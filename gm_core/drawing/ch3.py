"""Chapter 3 drawing: locomoting bodies at a shape, connection vector fields, gaits and trails.

All artists are created once and moved in place (``set_xy``, ``set_data``, ``set_UVC``). Values
that are undefined (the local connection at a singular shape) are masked or hidden, never passed
to matplotlib as NaN.

Sign convention of the fields: row i of the local connection is drawn as the vector field
``-A^i(r)`` over shape space, so that ``xi^i = <-A^i, r_dot>`` (3.10): moving the shape along an
arrow gives positive body velocity component i, across it gives none.
"""
from __future__ import annotations

import numpy as np

from ..groups import SE2
from ..locomotion import as_gait, trajectory
from .base import BodyArtist, FrameArtist, SingularFlag, TrailArtist, animate, new_figure

__all__ = ["PART_STYLES", "SystemArtist", "ConnectionFieldArtist", "ShapeCursorArtist", "VelocityArtist",
           "shape_grid", "connection_field", "system_extent", "style_world_axes", "draw_singular_set", "draw_system_naive",
           "connection_fields_figure", "regimes_figure", "poor_pictures_figure", "animate_gait", "ROW_LABELS"]

PART_STYLES = {
    "chassis": dict(facecolor="tab:blue", alpha=0.35, edgecolor="k"),
    "wheel": dict(facecolor="0.15", alpha=0.9, edgecolor="k"),
    "link": dict(facecolor="tab:orange", alpha=0.6, edgecolor="k"),
}
ROW_LABELS = ("ξx (forward)", "ξy (sideways)", "ξθ (turning)")  # plain text: no mathtext parse cost


# ------------------------------------------------------------------------------ bodies
class SystemArtist:
    """A locomotor drawn at position g and shape r: one polygon per rigid part plus its body frame."""

    def __init__(self, ax, system, g=(0.0, 0.0, 0.0), r=(0.0, 0.0), frame_length=None, styles=None, zorder=3):
        self.system = system
        self.parts = system.parts()
        styles = dict(PART_STYLES, **(styles or {}))
        self.bodies = [BodyArtist(ax, p.outline, **dict(styles.get(p.kind, {}), zorder=zorder)) for p in self.parts]
        size = max(np.ptp(np.vstack([p.outline for p in self.parts]), axis=0))
        self.frame = FrameArtist(ax, length=frame_length or 0.3 * size)
        self.set(g, r)

    def set(self, g, r):
        """Place the body: part i at g o pose_i(r)."""
        self.g = np.asarray(g, dtype=float)
        self.r = np.asarray(r, dtype=float)
        poses = SE2.compose(self.g, self.system.part_poses(self.r))
        for b, pose in zip(self.bodies, poses):
            b.set(pose)
        self.frame.set(self.g)

    def set_visible(self, visible):
        for b in self.bodies:
            b.patch.set_visible(visible)
        self.frame.quiver.set_visible(visible)

    def world_outlines(self):
        """Current world outlines (list of (k, 2)) of the parts (for tests)."""
        return [np.asarray(b.patch.get_xy()) for b in self.bodies]


def system_extent(system, r=None):
    """Half-size of a square (centred on the body frame) that holds the body at shape r (default 0)."""
    r = np.zeros(system.n_shape) if r is None else np.asarray(r, float)
    pts = np.vstack([SE2.act_on_points(pose, p.outline)
                     for p, pose in zip(system.parts(), system.part_poses(r))])
    return float(np.abs(pts).max())


def draw_system_naive(ax, system, g, r):
    """Plot the body from scratch with ax.fill (the clear-and-replot baseline)."""
    poses = SE2.compose(np.asarray(g, float), system.part_poses(np.asarray(r, float)))
    for p, pose in zip(system.parts(), poses):
        xy = SE2.act_on_points(pose, p.outline)
        ax.fill(xy[:, 0], xy[:, 1], **PART_STYLES.get(p.kind, {}))


class VelocityArtist:
    """The body velocity xi drawn at the body frame: an arrow for (xi^x, xi^y) and an arc for xi^theta."""

    def __init__(self, ax, scale=1.0, color="tab:purple", zorder=6):
        self.scale = float(scale)
        self.quiver = ax.quiver([0.0], [0.0], [0.0], [0.0], color=color, angles="xy", scale_units="xy",
                                scale=1.0, width=0.012, zorder=zorder)
        (self.arc,) = ax.plot([], [], color=color, lw=2, zorder=zorder)
        (self.tip,) = ax.plot([], [], marker=(3, 0, 0), color=color, ms=8, ls="none", zorder=zorder)
        self.xi = np.zeros(3)

    def set(self, g, xi):
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

    def world_vector(self):
        """The drawn linear-velocity arrow (2,) in world coordinates (for tests)."""
        return np.array([self.quiver.U[0], self.quiver.V[0]])


# ------------------------------------------------------------------------------ fields
def shape_grid(system, n=21, limits=None):
    """(a1, a2, r): a n x n grid over the system's shape window; r has shape (n, n, 2)."""
    (lo1, hi1), (lo2, hi2) = limits or system.shape_limits
    a1, a2 = np.meshgrid(np.linspace(lo1, hi1, n), np.linspace(lo2, hi2, n), indexing="xy")
    return a1, a2, np.stack([a1, a2], -1)


def connection_field(system, row, n=21, limits=None):
    """(a1, a2, U, V): the field -A^row over a shape grid, U and V masked where A is undefined.

    Entries below 1e-10 of the largest entry of A on the grid are set to exactly zero, so a row
    that vanishes analytically (e.g. the floating snake's translation rows) is not drawn as
    magnified round-off.
    """
    a1, a2, r = shape_grid(system, n, limits)
    A = system.connection(r)
    finite = np.isfinite(A)
    big = float(np.max(np.abs(A[finite]))) if finite.any() else 0.0
    U = -A[..., row, 0]
    V = -A[..., row, 1]
    with np.errstate(invalid="ignore"):
        tiny = np.hypot(U, V) <= 1e-10 * big
    U = np.where(tiny, 0.0, U)
    V = np.where(tiny, 0.0, V)
    U = np.ma.masked_invalid(U)
    V = np.ma.masked_invalid(V)
    mask = np.ma.getmaskarray(U) | np.ma.getmaskarray(V)
    return a1, a2, np.ma.array(U, mask=mask), np.ma.array(V, mask=mask)


class ConnectionFieldArtist:
    """Quiver of one connection row, -A^row(r), over shape space; arrows are clipped for readability.

    Arrows longer than ``clip`` x the median length are shortened to that length (near singular
    shapes the connection grows without bound); undefined arrows are masked. ``factor`` is the
    data-to-arrow scale in use, so the drawn arrow is ``factor * (-A^row)`` unless clipped.
    """

    def __init__(self, ax, system, row, n=17, limits=None, clip=3.0, color="k", **kw):
        self.ax, self.n, self.limits, self.clip, self.row = ax, n, limits, float(clip), row
        self.system = system
        a1, a2, U, V = connection_field(system, row, n, limits)
        self.quiver = ax.quiver(a1, a2, np.zeros_like(a1), np.zeros_like(a1), color=color, angles="xy",
                                scale_units="xy", scale=1.0, width=0.005, pivot="mid", **kw)
        self.set(system, row)

    def set(self, system=None, row=None):
        """Recompute the field for (system, row) and move the arrows in place (set_UVC)."""
        if system is not None:
            self.system = system
        if row is not None:
            self.row = row
        a1, a2, U, V = connection_field(self.system, self.row, self.n, self.limits)
        self.quiver.set_offsets(np.column_stack([a1.ravel(), a2.ravel()]))
        mag = np.ma.sqrt(U ** 2 + V ** 2)
        spacing = min(np.ptp(a1) / (self.n - 1), np.ptp(a2) / (self.n - 1))
        nonzero = np.ma.masked_equal(mag, 0.0)
        med = float(np.ma.median(nonzero)) if nonzero.count() else 0.0
        cap = self.clip * med if med > 0 else (float(mag.max()) if mag.count() else 1.0)
        cap = cap if cap > 0 else 1.0
        self.factor = 0.9 * spacing / cap
        shrink = np.ma.where(mag > cap, cap / np.ma.where(mag > 0, mag, 1.0), 1.0)
        self.U, self.V = U, V
        self.quiver.set_UVC(U * shrink * self.factor, V * shrink * self.factor)
        self.clipped = np.ma.filled(mag > cap, False)
        return self


def draw_singular_set(ax, system, n=161, limits=None, **style):
    """Draw the singular shapes (det omega_xi = 0) as red lines; returns the contour set or None."""
    if not system.may_be_singular:
        return None
    a1, a2, r = shape_grid(system, n, limits)
    d = system.singularity(r)
    if not (np.nanmin(d) < 0 < np.nanmax(d)):
        return None
    style.setdefault("colors", "crimson")
    style.setdefault("linewidths", 2.0)
    return ax.contour(a1, a2, d, levels=[0.0], **style)


class ShapeCursorArtist:
    """A marker at shape r on a shape-space axes and an arrow for the shape velocity r_dot."""

    def __init__(self, ax, color="tab:green", arrow_scale=0.5):
        (self.marker,) = ax.plot([0.0], [0.0], "o", color=color, ms=8, zorder=7)
        self.arrow = ax.quiver([0.0], [0.0], [0.0], [0.0], color=color, angles="xy", scale_units="xy",
                               scale=1.0, width=0.01, zorder=7)
        self.arrow_scale = arrow_scale

    def set(self, r, r_dot=(0.0, 0.0)):
        r = np.asarray(r, float)
        d = np.asarray(r_dot, float) * self.arrow_scale
        self.marker.set_data([r[0]], [r[1]])
        self.arrow.set_offsets([r])
        self.arrow.set_UVC([d[0]], [d[1]])


def _tick_label(v):
    if np.isclose(abs(v), np.pi):
        return "−π" if v < 0 else "π"
    return f"{v:g}".replace("-", "−")


def _style_shape_axes(ax, system, title=None):
    """Shape-space axes: equal aspect, three ticks per axis (few labels keep redraws cheap)."""
    (lo1, hi1), (lo2, hi2) = system.shape_limits
    ax.set_xlim(lo1, hi1)
    ax.set_ylim(lo2, hi2)
    ax.set_aspect("equal")
    ax.set_xticks([lo1, 0.0, hi1], [_tick_label(v) for v in (lo1, 0.0, hi1)])
    ax.set_yticks([lo2, 0.0, hi2], [_tick_label(v) for v in (lo2, 0.0, hi2)])
    ax.tick_params(labelsize=8, pad=1)
    ax.set_xlabel("α₁", fontsize=9, labelpad=0)
    ax.set_ylabel("α₂", fontsize=9, labelpad=0)
    if title:
        ax.set_title(title, fontsize=9)


def style_world_axes(ax, half, center=(0.0, 0.0)):
    """Square world axes of half-width ``half`` about ``center``, light grid, few ticks."""
    from matplotlib.ticker import MaxNLocator

    ax.set_xlim(center[0] - half, center[0] + half)
    ax.set_ylim(center[1] - half, center[1] + half)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    ax.xaxis.set_major_locator(MaxNLocator(4))
    ax.yaxis.set_major_locator(MaxNLocator(4))
    ax.tick_params(labelsize=8, pad=1)


def connection_fields_figure(system, n=17, figsize=(10, 3.4)):
    """A static figure: the three connection rows of ``system`` as vector fields, singular set in red."""
    fig, axes = new_figure(1, 3, figsize=figsize)
    arts = []
    for i, ax in enumerate(axes):
        _style_shape_axes(ax, system, ROW_LABELS[i])
        arts.append(ConnectionFieldArtist(ax, system, i, n=n))
        draw_singular_set(ax, system)
    fig.suptitle(f"{system.name}: the rows of −A(r) as fields", fontsize=10)
    fig.subplots_adjust(left=0.06, right=0.98, bottom=0.14, top=0.84, wspace=0.3)
    return fig, axes, arts


def regimes_figure(systems, n=13, figsize=(9, 11)):
    """Static grid: one row per system, one column per connection row (x, y, theta)."""
    systems = list(systems)
    fig, axes = new_figure(len(systems), 3, figsize=figsize, squeeze=False)
    for k, s in enumerate(systems):
        for i in range(3):
            ax = axes[k, i]
            _style_shape_axes(ax, s, f"{s.name}: {ROW_LABELS[i]}")
            ConnectionFieldArtist(ax, s, i, n=n)
            draw_singular_set(ax, s)
    fig.subplots_adjust(left=0.07, right=0.98, bottom=0.05, top=0.97, wspace=0.35, hspace=0.45)
    return fig, axes


def poor_pictures_figure(system, row=2, n=6, figsize=(11, 3.6)):
    """Three pictures of one connection row: a plane field, local contour lines, and arrows.

    (a) at each grid shape r0, a small tilted square: the graph of the linear function
    r_dot -> <-A^row(r0), r_dot>; (b) at each grid shape, three short parallel segments along which
    that linear function is constant, spaced inversely to its gain; (c) the arrow field -A^row.
    Singular grid shapes are skipped. Returns (fig, axes).
    """
    fig, axes = new_figure(1, 3, figsize=figsize)
    axes = list(axes)
    axes[0].remove()
    axes[0] = fig.add_subplot(1, 3, 1, projection="3d")
    a1, a2, U, V = connection_field(system, row, n)
    (lo1, hi1), (lo2, hi2) = system.shape_limits
    h = 0.35 * min(hi1 - lo1, hi2 - lo2) / n
    big = float(np.ma.max(np.ma.sqrt(U ** 2 + V ** 2))) or 1.0
    s = np.linspace(-h, h, 2)
    S1, S2 = np.meshgrid(s, s)
    for k in np.ndindex(a1.shape):
        if np.ma.is_masked(U[k]) or np.ma.is_masked(V[k]):
            continue
        u, v = float(U[k]), float(V[k])
        axes[0].plot_surface(a1[k] + S1, a2[k] + S2, (u * S1 + v * S2) / big, color="tab:blue", alpha=0.6,
                             linewidth=0.3, edgecolor="k")
        m = np.hypot(u, v)
        if m > 0:
            t = np.array([-v, u]) / m  # along a level line of the local linear function
            nrm = np.array([u, v]) / m
            gap = min(h, 0.25 * h * big / m)
            for j in (-1, 0, 1):
                c = np.array([a1[k], a2[k]]) + j * gap * nrm
                axes[1].plot([c[0] - h * t[0], c[0] + h * t[0]], [c[1] - h * t[1], c[1] + h * t[1]],
                             color="tab:purple", lw=1)
    axes[0].set(xlabel="α₁", ylabel="α₂", title="(a) plane field")
    axes[0].title.set_fontsize(9)
    for ax, title in zip(axes[1:], ["(b) local level lines", "(c) connection vector field"]):
        _style_shape_axes(ax, system, title)
    ConnectionFieldArtist(axes[2], system, row, n=n)
    for ax in axes[1:]:
        draw_singular_set(ax, system)
    fig.suptitle(f"{system.name}, row {ROW_LABELS[row]}", fontsize=10)
    fig.subplots_adjust(left=0.02, right=0.98, bottom=0.14, top=0.84, wspace=0.3)
    return fig, axes


# ------------------------------------------------------------------------------ gaits
def animate_gait(system, gait, n_frames=60, row=2, cycles=1, world_lim=None, interval=60, dpi=72):
    """An animation (FuncAnimation): the gait on connection row ``row`` and the body moving in the plane.

    Left: shape space with the field -A^row, the gait and a cursor at the current shape. Right: the
    body at g(t) with its trail. Returns (anim, fig, traj). Use ``drawing.base.jshtml(anim)``.
    """
    gait = as_gait(gait)
    traj = trajectory(system, gait, n_frames, cycles=cycles)
    fig, (axs, axw) = new_figure(1, 2, figsize=(9, 4), dpi=dpi)
    _style_shape_axes(axs, system, f"gait on {ROW_LABELS[row]}")
    ConnectionFieldArtist(axs, system, row, n=15, color="0.5")
    draw_singular_set(axs, system)
    path = gait(np.linspace(0, gait.period, 200))
    axs.plot(path[:, 0], path[:, 1], color="tab:blue", lw=2)
    cursor = ShapeCursorArtist(axs)
    body = SystemArtist(axw, system, traj.g[0], traj.r[0])
    trail = TrailArtist(axw, color="tab:green")
    size = system_extent(system)
    lo = traj.g[:, :2].min(0) - 1.1 * size
    hi = traj.g[:, :2].max(0) + 1.1 * size
    c, half = (lo + hi) / 2, max(hi - lo) / 2
    if world_lim is not None:
        half = world_lim
    style_world_axes(axw, half, c)
    axw.set_title(system.name, fontsize=9)
    fig.subplots_adjust(left=0.08, right=0.98, bottom=0.12, top=0.92, wspace=0.25)

    def update(k):
        k = int(k)
        body.set(traj.g[k], traj.r[k])
        trail.set(traj.g[: k + 1, :2])
        cursor.set(traj.r[k], gait.velocity(np.array([traj.t[k]]))[0] * 0.05)
        return []

    anim = animate(fig, update, range(n_frames), interval=interval)
    return anim, fig, traj


__all__ += ["SingularFlag"]


# ------------------------------------------------------------------------------ moving world view
class MovingView:
    """World axes whose visible window follows the motion without changing the axes limits.

    A live panel is redrawn by blitting (gm_core.drawing.blit); a new axis limit forces a full
    redraw of the whole figure (~80 ms for a 2 x 2 figure). Here the axes keep fixed limits
    ``(-half0, half0)``; the artists attached with :meth:`attach` keep their *world* data and
    are drawn through ``view + transData``, where ``view`` maps the window ``center +- half`` onto
    the fixed limits. Grid lines, tick marks and tick labels (MaxNLocator(4), ScalarFormatter
    labels, as :func:`style_world_axes` shows them) are moving artists updated by :meth:`set`.
    Quiver arrows given in data units are rescaled with the window.
    """

    def __init__(self, ax, half, nticks=4, max_ticks=8):
        import matplotlib as mpl
        from matplotlib.collections import LineCollection
        from matplotlib.lines import Line2D
        from matplotlib.markers import TICKDOWN, TICKLEFT
        from matplotlib.ticker import MaxNLocator
        from matplotlib.transforms import Affine2D, offset_copy

        from .ch2 import ReadoutText

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
        fig = ax.get_figure()
        xlab = offset_copy(xt, fig, y=-(length + pad), units="points")
        ylab = offset_copy(yt, fig, x=-(length + pad), units="points")
        self.xlabels, self.ylabels = [], []
        for labels, tr, kw in ((self.xlabels, xlab, dict(ha="center", va="top")),
                               (self.ylabels, ylab, dict(ha="right", va="center_baseline"))):
            for _ in range(max_ticks):
                t = ReadoutText(0.0, 0.0, "", transform=tr, fontsize=8, clip_on=False, **kw)
                t.template = False
                ax._add_text(t)
                labels.append(t)
        self.quivers = []
        self.center, self.half = np.zeros(2), self.half0
        self.set((0.0, 0.0), self.half0)

    def attach(self, *artists):
        """Draw these artists (world data) through the moving window."""
        from matplotlib.quiver import Quiver

        for a in artists:
            if isinstance(a, Quiver):
                a.set_offset_transform(self.transform)
                self.quivers.append((a, a.scale))
            else:
                a.set_transform(self.transform)
        self.set(self.center, self.half)

    def limits(self):
        """The world window shown: ``(x0, x1, y0, y1)``."""
        c, h = self.center, self.half
        return (c[0] - h, c[0] + h, c[1] - h, c[1] + h)

    def set(self, center, half):
        from matplotlib.ticker import ScalarFormatter

        self.center, self.half = np.asarray(center, float).copy(), float(half)
        k = self.half0 / self.half
        self.view.clear().translate(-self.center[0], -self.center[1]).scale(k)
        for q, scale in self.quivers:
            q.scale = scale / k
            q.stale = True
        segs, xt, yt = [], [], []
        for axis, (lo, hi), marks, labels in ((0, self.limits()[:2], xt, self.xlabels),
                                              (1, self.limits()[2:], yt, self.ylabels)):
            eps = 1e-9 * (hi - lo)
            locs = [v for v in self.locator.tick_values(lo, hi) if lo - eps <= v <= hi + eps]
            fmt = ScalarFormatter()
            fmt.create_dummy_axis()
            fmt.axis.set_view_interval(lo, hi)
            text = fmt.format_ticks(locs)
            for i, t in enumerate(labels):
                if i < len(locs):
                    p = (locs[i] - self.center[axis]) * k
                    t.set_position((p, 0.0) if axis == 0 else (0.0, p))
                    t.set_text(text[i])
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

    def touch(self):
        """Mark the view's artists changed (so a blitter counts them as moving from the first frame)."""
        for a in [self.grid, self.xticks, self.yticks] + self.xlabels + self.ylabels:
            a.stale = True


__all__ += ["MovingView"]

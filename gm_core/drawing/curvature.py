"""Drawing for the geometry notebook: curvature maps, gaits on them, connection fields, swimmer animations.

Built on :mod:`gm_core.drawing.primitives` only. Every artist is created once and moved with
``set(...)``. Figures are at most 9 in x 100 dpi = 900 px wide, use constrained layout and fonts
of 9 pt or more (12.5 px at 100 dpi). Singular or undefined shapes are masked (grey), never
handed to matplotlib as NaN colours silently.
"""
from __future__ import annotations

import numpy as np

from ..geometry import constraint_curvature
from ..groups import SE2
from .connection import auto_grid, inset_limits
from .primitives import BodyArtist, TrailArtist, animate
from .toolkit import PALETTE, new_figure

__all__ = ["ROWS", "shape_grid", "CurvatureMapArtist", "GaitArtist", "FieldArtist", "SwimmerArtist",
           "curvature_maps_figure", "animate_swimmer", "FONT", "DPI"]

ROWS = ("x", "y", "θ")
FONT = 9
DPI = 100
_CMAP = "RdBu_r"


def shape_grid(limits, n):
    """Grid axes a1 (n,), a2 (n,) and shapes (n, n, 2) (index [j, i] = (a1[i], a2[j]), image order)."""
    (lo1, hi1), (lo2, hi2) = limits
    a1, a2 = np.linspace(lo1, hi1, n), np.linspace(lo2, hi2, n)
    A1, A2 = np.meshgrid(a1, a2)
    return a1, a2, np.stack([A1, A2], -1)


def _style(ax, limits, title=None):
    (lo1, hi1), (lo2, hi2) = limits
    ax.set_xlim(lo1, hi1)
    ax.set_ylim(lo2, hi2)
    ax.set_aspect("equal")
    ax.set_xlabel("α₁", fontsize=FONT, labelpad=0)
    ax.set_ylabel("α₂", fontsize=FONT, labelpad=0)
    ax.tick_params(labelsize=FONT)
    if title:
        ax.set_title(title, fontsize=FONT)


class CurvatureMapArtist:
    """One row of the constraint curvature D(-A) as an image over a rectangle of shape space.

    Red is positive, blue negative, colour limits symmetric about zero (a high percentile of
    |F|, so a singular line does not wash out the picture, and never below 1e-6 of the largest
    row, so a row that vanishes up to rounding shows white); singular shapes are grey.
    """

    def __init__(self, ax, system, row=0, limits=None, n=81):
        self.ax, self.n = ax, int(n)
        self.limits = tuple(tuple(map(float, lim)) for lim in (limits or system.shape_limits))
        (lo1, hi1), (lo2, hi2) = self.limits
        import matplotlib

        cmap = matplotlib.colormaps[_CMAP].with_extremes(bad="0.75")
        self.image = ax.imshow(np.zeros((self.n, self.n)), origin="lower", extent=(lo1, hi1, lo2, hi2),
                               cmap=cmap, interpolation="bilinear", aspect="equal", zorder=1)
        self._cache = {}
        self.set(system, row)

    def values(self, system):
        """Curvature (n, n, 3) of ``system`` on the grid (cached per system object)."""
        key = id(system)
        if key not in self._cache:
            _, _, grid = shape_grid(self.limits, self.n)
            self._cache[key] = (system, constraint_curvature(system, grid))
        return self._cache[key][1]

    def set(self, system=None, row=None):
        if system is not None:
            self.system = system
        if row is not None:
            self.row = int(row)
        Fall = self.values(self.system)
        F = Fall[..., self.row]
        finite = np.isfinite(F)
        q = 95 if getattr(self.system, "may_be_singular", False) else 99
        vmax = float(np.percentile(np.abs(F[finite]), q)) if finite.any() else 1.0
        every = np.abs(Fall[np.isfinite(Fall)])
        vmax = max(vmax, 1e-6 * float(every.max()) if every.size else 0.0)
        vmax = vmax if vmax > 0 else 1.0
        self.image.set_data(np.ma.masked_invalid(F))
        self.image.set_clim(-vmax, vmax)
        self.vmax = vmax
        return vmax


class GaitArtist:
    """A gait drawn as a closed curve with a start dot and an arrow showing its direction."""

    def __init__(self, ax, color="k", lw=1.8, samples=200):
        (self.line,) = ax.plot([], [], color=color, lw=lw, zorder=4)
        (self.start,) = ax.plot([], [], "o", color=color, ms=5, zorder=5)
        self.arrow = ax.annotate("", xy=(0, 0), xytext=(0, 0), zorder=5,
                                 arrowprops=dict(arrowstyle="-|>", color=color, lw=lw))
        self.samples = samples

    def set(self, gait):
        t = np.linspace(0, gait.period, self.samples + 1)
        p = gait(t)
        self.line.set_data(p[:, 0], p[:, 1])
        self.start.set_data([p[0, 0]], [p[0, 1]])
        k = self.samples // 8
        self.arrow.xy, self.arrow.xyann = tuple(p[k + 1]), tuple(p[k])
        self.points = p

    def set_visible(self, visible):
        for a in (self.line, self.start, self.arrow):
            a.set_visible(visible)


class FieldArtist:
    """One row of -A(r) as a quiver (the body velocity per unit shape velocity), rescaled to a common length.

    ``n=None`` (grid points per side) picks the grid from the axes' size (connection.auto_grid),
    so the arrows (0.9 grid spacings at the 95th percentile length) meet the figure standard."""

    def __init__(self, ax, system, row, limits=None, n=None, color="k"):
        self.limits = tuple(tuple(map(float, lim)) for lim in (limits or system.shape_limits))
        if n is None:  # grid from the axes' size: arrows of 0.9 spacings are >= MIN_ARROW_PX long
            n = min(auto_grid(ax, self.limits, inset=True))
        n = int(n)
        # cell centres, half a cell inside the window: no arrow is sliced by the axes frame
        _, _, self.grid = shape_grid(inset_limits(self.limits, n), n)
        self.row = row
        self.quiver = ax.quiver(self.grid[..., 0], self.grid[..., 1], np.zeros((n, n)), np.zeros((n, n)),
                                color=color, angles="xy", scale_units="xy", scale=1.0, pivot="mid",
                                width=0.006, zorder=3)
        self.set(system)

    def set(self, system, scale=None):
        V = -system.connection(self.grid)[..., self.row, :]
        ok = np.isfinite(V).all(-1)
        V = np.where(ok[..., None], V, 0.0)
        step = (self.limits[0][1] - self.limits[0][0]) / self.grid.shape[1]
        norm = scale if scale is not None else (np.percentile(np.linalg.norm(V, axis=-1)[ok], 95) if ok.any() else 1)
        norm = norm if norm > 0 else 1.0
        self.quiver.set_UVC(V[..., 0] * 0.9 * step / norm, V[..., 1] * 0.9 * step / norm)
        return norm


class SwimmerArtist:
    """A locomotor's rigid parts (BodyArtist each) at world pose g and shape r."""

    def __init__(self, ax, system, colors=(PALETTE["blue"], PALETTE["orange"], PALETTE["green"])):
        self.system = system
        self.bodies = [BodyArtist(ax, p.outline, facecolor=colors[i % len(colors)], alpha=0.8, zorder=3)
                       for i, p in enumerate(system.parts())]

    def set(self, g, r):
        poses = SE2.compose(np.asarray(g, dtype=float)[None], self.system.part_poses(r))
        for b, pose in zip(self.bodies, poses):
            b.set(pose)
        return poses


def curvature_maps_figure(cases, n=81, figsize=(9, 7.6)):
    """Grid of curvature maps: one column per case, rows x, y, theta; ``cases`` = {title: (system, gait or None)}."""
    fig, axes = new_figure(3, len(cases), figsize=figsize, dpi=DPI, layout="constrained", squeeze=False)
    for j, (title, (system, gait)) in enumerate(cases.items()):
        for i in range(3):
            ax = axes[i, j]
            m = CurvatureMapArtist(ax, system, i, n=n)
            _style(ax, m.limits, f"{title}\nD(−A), row {ROWS[i]}" if i == 0 else f"row {ROWS[i]}")
            vals = m.values(system)[..., i]
            flat = not np.nanmax(np.abs(vals)) > 1e-9
            ax.text(0.02, 0.02, "≡ 0" if flat else f"±{m.vmax:.2g}", transform=ax.transAxes, fontsize=FONT, va="bottom",
                    bbox=dict(facecolor="white", alpha=0.7, lw=0))
            if gait is not None:
                GaitArtist(ax).set(gait)
    return fig


def animate_swimmer(system, gait, traj, n_frames=60, row=0, limits=None, figsize=(9, 4), dpi=DPI, interval=60):
    """Animation (fig, FuncAnimation) of ``system`` swimming ``traj`` (a locomotion.Trajectory) beside its gait.

    Left: the curvature row ``row`` with the gait and a moving dot; right: the swimmer in the
    world with the trail of its body frame. Frames are shortened under the test suite.
    """
    fig, (axs, axw) = new_figure(1, 2, figsize=figsize, dpi=dpi, layout="constrained")
    m = CurvatureMapArtist(axs, system, row, limits=limits, n=61)
    _style(axs, m.limits, f"D(−A), row {ROWS[row]}, with the gait")
    GaitArtist(axs).set(gait)
    (dot,) = axs.plot([], [], "o", color="gold", mec="k", ms=8, zorder=6)
    sw = SwimmerArtist(axw, system)
    trail = TrailArtist(axw, color="k", lw=1.2)
    g, r = traj.g, traj.r
    reach = max(sum(getattr(system, "lengths", (1.0,))) * 0.6, 0.5)
    lo, hi = g[:, :2].min(0) - reach, g[:, :2].max(0) + reach
    half = float(max(hi - lo) / 2)
    c = (lo + hi) / 2
    axw.set_xlim(c[0] - half, c[0] + half)
    axw.set_ylim(c[1] - half, c[1] + half)
    axw.set_aspect("equal")
    axw.tick_params(labelsize=FONT)
    axw.set_title(system.name, fontsize=FONT)
    idx = np.linspace(0, len(g) - 1, n_frames).round().astype(int)

    def update(k):
        i = idx[k]
        sw.set(g[i], r[i])
        dot.set_data([r[i, 0]], [r[i, 1]])
        trail.set(g[: i + 1, :2])
        return []

    update(0)
    return fig, animate(fig, update, len(idx), interval=interval)


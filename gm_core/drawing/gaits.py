"""Gaits (book chapter 3): a gait drawn on the three connection fields with the motion it makes
(a live scene), and the same as an animation that plays without a kernel.

Trajectories come from :func:`gm_core.locomotion.trajectory` (fourth-order Magnus steps).
"""
from __future__ import annotations

import numpy as np

from .._validate import SingularShapeError
from ..locomotion import as_gait, circle_gait, net_displacement, trajectory
from .base import SingularFlag, TrailArtist, animate
from .connection import (ROW_LABELS, ConnectionFieldArtist, ShapeCursorArtist, draw_singular_set, field_grid_axes,
                         style_shape_axes, thin_labels)
from .motion import MovingView, SystemArtist, draw_system_naive, style_world_axes, system_extent
from .toolkit import PALETTE, Scene, new_figure, readout

__all__ = ["GaitScene", "animate_gait"]


class GaitScene(Scene):
    """A circular gait on the three connection fields and the motion it produces over one cycle.

    Values: ``amplitude`` (radius), ``center1``, ``center2`` (centre in shape space). The world
    axes show the trail of the body frame over one period, the body at start and at g(T), and
    the net displacement ``net``. A gait that meets a singular shape raises the flag and hides
    the motion. Options: ``system`` (required), ``n`` (field grid), ``lim`` (world half-width).
    """

    #: Magnus steps between two of the 61 frames: 720 per cycle put g(T) within ~1e-10 of
    #: net_displacement's converged value on the course's gaits (1e-12 relative), far below a pixel.
    substeps = 12
    cache_size = 256

    def __init__(self, system, n=None, lim=None, **options):
        self.system, self.n = system, n
        self.lim = lim or 1.3 * system_extent(system)
        self._cache = {}
        super().__init__(**options)

    def make_figure(self):
        fig, self.field_axes, self.ax = field_grid_axes()
        return fig, self.field_axes + [self.ax]

    def decorate(self):
        s = self.system
        for i, ax in enumerate(self.field_axes):
            style_shape_axes(ax, s, ROW_LABELS[i])
            ConnectionFieldArtist(ax, s, i, n=self.n, color="0.5")
            draw_singular_set(ax, s)
        thin_labels(self.field_axes, self.ax)

    def create(self):
        s = self.system
        self.paths = []
        for ax in self.field_axes:
            (line,) = ax.plot([], [], color=PALETTE["blue"], lw=2)
            (start,) = ax.plot([], [], "o", color=PALETTE["blue"], ms=5)
            self.paths.append((line, start))
        # The window follows the motion through a transform, not through the axes limits: a new
        # limit would force a full redraw of all four axes instead of a blit.
        self.view = MovingView(self.ax, self.lim)
        self.ax.set_title("motion over one cycle")
        self.trail = TrailArtist(self.ax, color=PALETTE["green"], lw=2)
        grey = dict(facecolor="0.8", alpha=0.5, edgecolor="0.5")
        self.start = SystemArtist(self.ax, s, styles={"link": grey, "chassis": grey})
        self.body = SystemArtist(self.ax, s)
        self.view.attach(self.trail.line, *(b.patch for art in (self.start, self.body) for b in art.bodies),
                         self.start.frame.quiver, self.body.frame.quiver)
        self.flag = SingularFlag(self.ax)
        self.text = readout(self.ax, 0.02, 0.02)
        self._moving = [self.trail.line, self.start.frame.quiver, self.body.frame.quiver, self.flag.text,
                        self.text] + [b.patch for art in (self.start, self.body) for b in art.bodies]

    @staticmethod
    def gait(v):
        return circle_gait(v["amplitude"], (v["center1"], v["center2"]))

    def motion(self, v):
        """(gait, trajectory, error) for the values; the trajectory is None (and ``error`` the
        SingularShapeError) when the gait meets a singular shape. Cached by gait parameters."""
        key = (float(v["amplitude"]), float(v["center1"]), float(v["center2"]))
        hit = self._cache.get(key)
        if hit is None:
            gait = self.gait(v)
            try:
                hit = (gait, trajectory(self.system, gait, 61, substeps=self.substeps), None)
            except SingularShapeError as e:
                hit = (gait, None, e)
            if len(self._cache) >= self.cache_size:
                self._cache.pop(next(iter(self._cache)))
            self._cache[key] = hit
        return hit

    def _fit_view(self, g):
        """Centre the window on the trail, at least the default size, with room for the body."""
        lo, hi = g[:, :2].min(0), g[:, :2].max(0)
        half = max(self.lim, 0.5 * float(np.max(hi - lo)) + 0.9 * self.lim)
        self.view.set((lo + hi) / 2, half)

    def set(self, amplitude=1.0, center1=0.0, center2=0.0):
        v = dict(amplitude=amplitude, center1=center1, center2=center2)
        gait, self.traj, err = self.motion(v)
        path = gait(np.linspace(0.0, 1.0, 121))
        for line, start in self.paths:
            line.set_data(path[:, 0], path[:, 1])
            start.set_data([path[0, 0]], [path[0, 1]])
        # Everything that can change (the flag appears, the body is hidden) is marked changed on
        # every update, so the blitter learns the moving artists on the first frame.
        self.view.touch()
        for a in self._moving:
            a.stale = True
        if self.traj is None:
            self.net = None
            self.flag.show("gait meets a singular shape")
            self.message = str(err)
            self.trail.line.set_visible(False)
            self.body.set_visible(False)
            self.text.set_text("no motion: the connection is\nundefined on the red line")
            return
        self.flag.hide()
        self.trail.line.set_visible(True)
        self.body.set_visible(True)
        self.net = self.traj.g[-1]
        self._fit_view(self.traj.g)
        self.start.set(self.traj.g[0], self.traj.r[0])
        self.trail.set(self.traj.g[:, :2])
        self.body.set(self.traj.g[-1], self.traj.r[-1])
        d = self.net
        self.text.set_text(f"net displacement g(T) =\n({d[0]:+.4f}, {d[1]:+.4f}, {d[2]:+.4f})")

    def replot(self, amplitude=1.0, center1=0.0, center2=0.0):
        gait = self.gait(dict(amplitude=amplitude, center1=center1, center2=center2))
        path = gait(np.linspace(0.0, 1.0, 121))
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


def animate_gait(system, gait, n_frames=60, row=2, cycles=1, world_lim=None, interval=60, dpi=None):
    """An animation (FuncAnimation): the gait on connection row ``row`` and the body moving in the plane.

    Left: shape space with the field -A^row, the gait and a cursor at the current shape. Right: the
    body at g(t) with its trail. Returns (anim, fig, traj). Use ``drawing.base.jshtml(anim)``.
    Frames are rendered at the standard resolution (``dpi`` is accepted for compatibility and
    ignored, so animation text is never smaller than on a live figure).
    """
    gait = as_gait(gait)
    traj = trajectory(system, gait, n_frames, cycles=cycles)
    fig, (axs, axw) = new_figure(1, 2, figsize=(8, 3.8))
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

    def update(k):
        k = int(k)
        body.set(traj.g[k], traj.r[k])
        trail.set(traj.g[: k + 1, :2])
        cursor.set(traj.r[k], gait.velocity(np.array([traj.t[k]]))[0] * 0.05)
        return []

    anim = animate(fig, update, range(n_frames), interval=interval)
    return anim, fig, traj



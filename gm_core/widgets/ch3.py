"""Chapter 3 panels: cars driven by sliders, connection vector fields with a shape cursor, gaits.

Every panel takes its numbers from ``gm_core.locomotion`` / ``gm_core.systems`` and draws with
the in-place artists of ``gm_core.drawing.ch3``; ``naive_update`` is the clear-and-replot
baseline for the latency benchmark. Singular shapes raise a SingularFlag and hide what cannot
be drawn.
"""
from __future__ import annotations

import numpy as np

from .._validate import SingularShapeError
from ..drawing.base import SingularFlag, TrailArtist
from ..drawing.connection import (ROW_LABELS, ConnectionFieldArtist, ShapeCursorArtist, draw_singular_set,
                                  style_shape_axes)
from ..drawing.motion import (MovingView, SystemArtist, VelocityArtist, draw_system_naive, style_world_axes,
                              system_extent)
from ..drawing.toolkit import PALETTE, new_figure, readout
from ..examples import drive
from ..locomotion import circle_gait, net_displacement, trajectory
from ..systems import Ackerman, DifferentialDrive, KinematicSnake
from .base import Panel, register, slider

__all__ = ["drive", "DiffDriveCarPanel", "AckermanCarPanel", "ConnectionFieldPanel", "GaitPanel"]

PI = float(np.pi)


def _square(ax, lim, center=(0.0, 0.0)):
    style_world_axes(ax, lim, center)


def _thin_labels(field_axes, body_ax, body_labels=True):
    """Fewer texts, faster redraws: tick labels only on the outer edges of the 2 x 2 grid."""
    top_left, top_right, bottom_left = field_axes
    for ax in (top_left, top_right):
        ax.tick_params(labelbottom=False)
        ax.set_xlabel("")
    top_right.tick_params(labelleft=False)
    top_right.set_ylabel("")
    if not body_labels:
        body_ax.tick_params(labelbottom=False, labelleft=False)


def _fmt(xi):
    return f"xi = ({xi[0]:+.3f}, {xi[1]:+.3f}, {xi[2]:+.3f})"


# ======================================================================= cars
class _CarPanel(Panel):
    """A car whose wheels (and steering) turn at slider-set rates; the trail shows where it went."""

    lim = 4.0

    def make_system(self):
        raise NotImplementedError

    def shape_path(self, v):
        """(r0, r_dot, duration) from the control values."""
        raise NotImplementedError

    def build(self):
        self.system = self.options.get("system") or self.make_system()
        self.fig, self.ax = new_figure(figsize=(5.5, 5.0))
        _square(self.ax, self.options.get("lim", self.lim))
        self.trail = TrailArtist(self.ax, color=PALETTE["green"], lw=2)
        self.start = SystemArtist(self.ax, self.system, styles={"chassis": dict(facecolor="0.8", alpha=0.4,
                                                                             edgecolor="0.5")})
        self.body = SystemArtist(self.ax, self.system)
        self.vel = VelocityArtist(self.ax, scale=1.0)
        self.flag = SingularFlag(self.ax)
        self.text = readout(self.ax, 0.02, 0.02)
        self.add_controls()

    def compute(self, v):
        r0, rd, T = self.shape_path(v)
        traj = drive(self.system, r0, rd, T)
        xi_end = self.system.body_velocity(traj.r[-1], rd)
        return traj, rd, xi_end

    def update(self, **v):
        self.flag.text.stale = True  # may appear on any change: a moving artist from the first frame
        self.text.stale = True
        try:
            self.traj, rd, self.xi = self.compute(v)
        except SingularShapeError as e:
            self.traj = None
            self.flag.show("singular shape reached")
            self.message = str(e)
            for a in (self.trail.line,):
                a.set_visible(False)
            self.body.set_visible(False)
            self.vel.set(np.zeros(3), np.full(3, np.nan))
            self.text.set_text("")
            self.fig.canvas.draw_idle()
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
        self.fig.canvas.draw_idle()

    def naive_update(self, **v):
        self.ax.clear()
        _square(self.ax, self.options.get("lim", self.lim))
        try:
            traj, rd, xi = self.compute(v)
        except SingularShapeError:
            self.ax.set_title("singular shape reached")
            self.fig.canvas.draw_idle()
            return
        self.ax.plot(traj.g[:, 0], traj.g[:, 1], color=PALETTE["green"], lw=2)
        draw_system_naive(self.ax, self.system, traj.g[-1], traj.r[-1])
        self.fig.canvas.draw_idle()


@register
class DiffDriveCarPanel(_CarPanel):
    """Differential-drive car (3.8), (3.29): two wheel-speed sliders and a duration."""

    title = "Differential-drive car: wheel speeds in, motion out"

    def make_system(self):
        return DifferentialDrive(wheel_radius=0.3, half_width=0.5)

    def add_controls(self):
        self.controls = {
            "wheel1_speed": slider(2.0, -4.0, 4.0, description="wheel 1 (left) rate"),
            "wheel2_speed": slider(3.0, -4.0, 4.0, description="wheel 2 (right) rate"),
            "duration": slider(3.0, 0.1, 6.0, description="duration T"),
        }

    def shape_path(self, v):
        return np.zeros(2), np.array([v["wheel1_speed"], v["wheel2_speed"]]), v["duration"]


@register
class AckermanCarPanel(_CarPanel):
    """Kinematic-bicycle car (3.9): drive-wheel rate, starting steering angle and steering rate."""

    title = "Ackerman car: drive and steering in, motion out"

    def make_system(self):
        return Ackerman(wheel_radius=0.3, wheelbase=1.0)

    def add_controls(self):
        self.controls = {
            "wheel_speed": slider(3.0, -4.0, 4.0, description="drive wheel rate"),
            "steering": slider(0.3, -1.4, 1.4, description="steering angle at t=0"),
            "steering_speed": slider(0.0, -1.0, 1.0, description="steering rate"),
            "duration": slider(3.0, 0.1, 6.0, description="duration T"),
        }

    def shape_path(self, v):
        return (np.array([0.0, v["steering"]]), np.array([v["wheel_speed"], v["steering_speed"]]),
                v["duration"])


# ======================================================================= connection fields
@register
class ConnectionFieldPanel(Panel):
    """The three rows of A as vector fields over shape space, a shape cursor, and the body there.

    Sliders set the shape (alpha1, alpha2) and the shape velocity; the fourth axes draws the body
    at that shape with its body velocity xi = -A(r) r_dot (3.10). For the kinematic snake the
    singular set is drawn in red and the velocity is hidden (with a flag) on it.
    """

    title = "Connection vector fields and a shape cursor"

    def build(self):
        self.system = self.options.get("system") or KinematicSnake()
        s = self.system
        self.title = f"Connection vector fields: {s.name}"
        self.fig, axes = new_figure(2, 2, figsize=(8, 7.5))
        self.field_axes = [axes[0, 0], axes[0, 1], axes[1, 0]]
        self.ax = axes[1, 1]
        self.fields, self.cursors = [], []
        for i, ax in enumerate(self.field_axes):
            style_shape_axes(ax, s, f"row {i + 1}: {ROW_LABELS[i]}")
            self.fields.append(ConnectionFieldArtist(ax, s, i, n=self.options.get("n"), color="0.35"))
            draw_singular_set(ax, s)
            self.cursors.append(ShapeCursorArtist(ax))
        _square(self.ax, 1.15 * system_extent(s))
        self.ax.set_title("body at this shape; arrow: body velocity", fontsize=9)
        self.body = SystemArtist(self.ax, s)
        self.vel = VelocityArtist(self.ax, scale=self.options.get("velocity_scale", 1.0))
        self.flag = SingularFlag(self.ax)
        self.text = readout(self.ax, 0.02, 0.02)
        (lo1, hi1), (lo2, hi2) = s.shape_limits
        self.controls = {
            "alpha1": slider(self.options.get("alpha1", 0.8), lo1, hi1, description="alpha1"),
            "alpha2": slider(self.options.get("alpha2", -0.6), lo2, hi2, description="alpha2"),
            "alpha1_dot": slider(1.0, -1.0, 1.0, description="alpha1 rate"),
            "alpha2_dot": slider(0.0, -1.0, 1.0, description="alpha2 rate"),
        }
        _thin_labels(self.field_axes, self.ax, body_labels=False)


    def update(self, **v):
        r = np.array([v["alpha1"], v["alpha2"]])
        rd = np.array([v["alpha1_dot"], v["alpha2_dot"]])
        for c in self.cursors:
            c.set(r, rd)
        self.body.set(np.zeros(3), r)
        self.flag.text.stale = True  # may appear on any change: a moving artist from the first frame
        if self.system.is_singular(r):
            self.xi = np.full(3, np.nan)
            self.vel.set(np.zeros(3), self.xi)
            self.flag.show("singular shape: A undefined")
            self.text.set_text("xi undefined")
        else:
            self.xi = self.system.body_velocity(r, rd)
            self.flag.hide()
            self.vel.set(np.zeros(3), self.xi)
            self.text.set_text(_fmt(self.xi))
        self.fig.canvas.draw_idle()

    def naive_update(self, **v):
        r = np.array([v["alpha1"], v["alpha2"]])
        rd = np.array([v["alpha1_dot"], v["alpha2_dot"]])
        for i, ax in enumerate(self.field_axes):
            ax.clear()
            style_shape_axes(ax, self.system, ROW_LABELS[i])
            ConnectionFieldArtist(ax, self.system, i, n=self.options.get("n"))
            draw_singular_set(ax, self.system)
            ax.plot([r[0]], [r[1]], "o", color=PALETTE["green"])
        self.ax.clear()
        _square(self.ax, 2.0)
        draw_system_naive(self.ax, self.system, np.zeros(3), r)
        if not self.system.is_singular(r):
            xi = self.system.body_velocity(r, rd)
            self.ax.quiver([0], [0], [xi[0]], [xi[1]], angles="xy", scale_units="xy", scale=1.0)
        self.fig.canvas.draw_idle()


# ======================================================================= gaits
@register
class GaitPanel(Panel):
    """A circular gait drawn on the three connection fields and the motion it produces over one cycle.

    Sliders: the gait's radius and centre in shape space. The world axes show the trail of the
    body frame over one period, the body at start and at g(T), and the net displacement. A gait
    that meets a singular shape raises the flag and hides the motion.
    """

    title = "Gaits on the connection fields"

    def build(self):
        self.system = self.options.get("system") or KinematicSnake()
        s = self.system
        self.title = f"Gaits: {s.name}"
        self.fig, axes = new_figure(2, 2, figsize=(8, 7.5))
        self.field_axes = [axes[0, 0], axes[0, 1], axes[1, 0]]
        self.ax = axes[1, 1]
        self.paths = []
        for i, ax in enumerate(self.field_axes):
            style_shape_axes(ax, s, ROW_LABELS[i])
            ConnectionFieldArtist(ax, s, i, n=self.options.get("n"), color="0.5")
            draw_singular_set(ax, s)
            (line,) = ax.plot([], [], color=PALETTE["blue"], lw=2)
            (start,) = ax.plot([], [], "o", color=PALETTE["blue"], ms=5)
            self.paths.append((line, start))
        self.lim = self.options.get("lim", 1.3 * system_extent(s))
        # The window follows the motion through a transform, not through the axes limits: a new
        # limit would force a full redraw of all four axes instead of a blit.
        self.view = MovingView(self.ax, self.lim)
        self.ax.set_title("motion over one cycle", fontsize=9)
        self.trail = TrailArtist(self.ax, color=PALETTE["green"], lw=2)
        self.start = SystemArtist(self.ax, s, styles={"link": dict(facecolor="0.8", alpha=0.5, edgecolor="0.5"),
                                                       "chassis": dict(facecolor="0.8", alpha=0.5, edgecolor="0.5")})
        self.body = SystemArtist(self.ax, s)
        self.view.attach(self.trail.line, *(b.patch for art in (self.start, self.body) for b in art.bodies),
                         self.start.frame.quiver, self.body.frame.quiver)
        self.flag = SingularFlag(self.ax)
        self.text = readout(self.ax, 0.02, 0.02)
        self._moving = [self.trail.line, self.start.frame.quiver, self.body.frame.quiver, self.flag.text,
                        self.text] + [b.patch for art in (self.start, self.body) for b in art.bodies]
        self._cache = {}
        (lo1, hi1), (lo2, hi2) = s.shape_limits
        c = self.options.get("center", (0.0, 0.0))
        self.controls = {
            "amplitude": slider(self.options.get("amplitude", 1.0), 0.05, 2.0, description="radius"),
            "center1": slider(c[0], lo1 / 2, hi1 / 2, description="centre alpha1"),
            "center2": slider(c[1], lo2 / 2, hi2 / 2, description="centre alpha2"),
        }
        _thin_labels(self.field_axes, self.ax)


    def gait(self, v):
        return circle_gait(v["amplitude"], (v["center1"], v["center2"]))

    #: Magnus steps between two of the 61 frames: 720 per cycle put g(T) within ~1e-10 of
    #: net_displacement's converged value on the course's gaits (1e-12 relative), far below a pixel.
    substeps = 12
    cache_size = 256

    def motion(self, v):
        """(gait, trajectory) for the control values; the trajectory is None (and ``error`` the
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

    def update(self, **v):
        gait, self.traj, err = self.motion(v)
        path = gait(np.linspace(0.0, 1.0, 121))
        for line, start in self.paths:
            line.set_data(path[:, 0], path[:, 1])
            start.set_data([path[0, 0]], [path[0, 1]])
        # Everything that can change (the flag appears, the body is hidden) is marked changed on
        # every update, so the blitter learns the moving artists on the first frame: showing the
        # flag or the body later is then a blit, not a full redraw.
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
            self.fig.canvas.draw_idle()
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
        self.fig.canvas.draw_idle()

    def naive_update(self, **v):
        gait = self.gait(v)
        path = gait(np.linspace(0.0, 1.0, 121))
        for i, ax in enumerate(self.field_axes):
            ax.clear()
            style_shape_axes(ax, self.system, ROW_LABELS[i])
            ConnectionFieldArtist(ax, self.system, i, n=self.options.get("n"))
            draw_singular_set(ax, self.system)
            ax.plot(path[:, 0], path[:, 1], color=PALETTE["blue"])
        self.ax.clear()
        _square(self.ax, self.lim)
        try:
            g = net_displacement(self.system, gait)
            tr = trajectory(self.system, gait, 61)
            self.ax.plot(tr.g[:, 0], tr.g[:, 1], color=PALETTE["green"])
            draw_system_naive(self.ax, self.system, g, tr.r[-1])
        except SingularShapeError:
            self.ax.set_title("singular")
        self.fig.canvas.draw_idle()

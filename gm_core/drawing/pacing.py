"""Pacing (book section 3.1): the commuting square of fig. 3.1 (shape path -> position path, with a
change of pace on both sides) and the four examples of the directional-linearity box (3.i)-(3.iv).

Math: :func:`gm_core.systems.motion.displacement_until`, :func:`gm_core.systems.pacing.sine_pacing`,
:mod:`gm_core.systems.directional`.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any, cast

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine
from matplotlib.lines import Line2D
from matplotlib.patches import ConnectionPatch
from typing_extensions import override

from gm_core.drawing.toolkit.primitives import FrameArtist
from gm_core.drawing.toolkit.recent import Recent
from gm_core.drawing.toolkit.style import MATH_PT, PALETTE, Scene, new_figure, readout
from gm_core.systems.directional import RATE_MAPS, rate_map, replay
from gm_core.systems.gaits import Gait, circle_gait
from gm_core.systems.motion import SystemLike, Trajectory, displacement_until, trajectory
from gm_core.systems.pacing import sine_pacing

__all__ = ["PacingSquareScene", "DirectionalScene"]

N_DOTS = 24


def _arrow(fig: Figure, ax_a: Axes, xy_a: tuple[float, float], ax_b: Axes, xy_b: tuple[float, float], label: str,
           ha: str = "center") -> ConnectionPatch:
    con = ConnectionPatch(xyA=xy_a, coordsA=ax_a.transAxes, xyB=xy_b, coordsB=ax_b.transAxes,
                          arrowstyle="-|>", mutation_scale=16, lw=1.5, color="0.25")
    fig.add_artist(con)
    return con


class PacingSquareScene(Scene):
    """Fig. 3.1 drawn: a shape loop ψ (top left) and the position path g^ψ it produces (top right);
    the same loop repaced, ψ'(t) = ψ(τ(t)) (bottom left), and its position path (bottom right).

    Dots mark equal time steps (T/24): the repaced rows crowd where τ lingers. A marker at time
    ``t`` sits on the bottom row at t and on the top row at τ(t): (3.4) says the two position
    markers coincide, and the readouts print both. World axes show the body frame only (the
    swimmer is much larger than its net motion). Values: ``unevenness`` (a in
    τ(t) = t − a sin(2πt)/2π) and ``t``. Options: ``system`` (default a low-Reynolds swimmer),
    ``gait`` (default a unit circle).
    """

    def __init__(self, system: SystemLike | None = None, gait: Gait | None = None, **options: Any) -> None:
        from gm_core.systems import LowReSwimmer

        self.system = system or LowReSwimmer()
        self.loop = gait or circle_gait(1.0)
        self.base = trajectory(self.system, self.loop, 241)
        self._cache: Recent[float, tuple[Callable[[Any], Any], Gait, Trajectory]] = Recent(64)
        super().__init__(**options)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        # h_pad pads the suptitle too (0.25 in left a 50 px band under it): the room between the
        # rows for the "repace" arrows comes from hspace instead
        fig, axes = new_figure(2, 2, figsize=(6.2, 5.5))
        cast(ConstrainedLayoutEngine, fig.get_layout_engine()).set(w_pad=0.3, h_pad=0.05, wspace=0.12, hspace=0.2)
        return fig, list(axes.ravel())

    @override
    def decorate(self) -> None:
        ax_s, ax_g, ax_s2, ax_g2 = self.axes
        path = self.base.r
        lo, hi = self.base.g[:, :2].min(0), self.base.g[:, :2].max(0)
        c, half = (lo + hi) / 2, 0.6 * float(np.max(hi - lo)) + 0.05
        for ax, ttl in ((ax_s, "shape path ψ"), (ax_s2, "repaced ψ′(t) = ψ(τ(t))")):
            ax.plot(path[:, 0], path[:, 1], color="0.75", lw=1)
            pad = 0.25 * np.ptp(path, axis=0).max()
            ax.set(xlim=(path[:, 0].min() - pad, path[:, 0].max() + pad),
                   ylim=(path[:, 1].min() - pad, path[:, 1].max() + pad), aspect="equal", title=ttl)
            ax.set_xlabel(r"$\alpha_1$", labelpad=1, fontsize=MATH_PT)
            ax.set_ylabel(r"$\alpha_2$", labelpad=1, fontsize=MATH_PT)
        for ax, ttl in ((ax_g, "its position path"), (ax_g2, "position path of ψ′")):
            ax.plot(self.base.g[:, 0], self.base.g[:, 1], color="0.75", lw=1)
            # room below the path for the readout
            ax.set(xlim=(c[0] - 1.3 * half, c[0] + 1.3 * half), ylim=(c[1] - 1.6 * half, c[1] + 1.0 * half),
                   aspect="equal", title=ttl)
            ax.set_xlabel("x", labelpad=1)
            ax.set_ylabel("y", labelpad=1)
            ax.grid(True, alpha=0.3)
        fig = self.fig
        self.links = [_arrow(fig, ax_s, (1.04, 0.8), ax_g, (-0.25, 0.8), "reconstruct"),
                      _arrow(fig, ax_s2, (1.04, 0.8), ax_g2, (-0.25, 0.8), "reconstruct"),
                      # between the tick labels 0 and 1 (x = 0.68), clear of the axis label below the middle
                      _arrow(fig, ax_s, (0.68, -0.2), ax_s2, (0.68, 1.2), "repace"),
                      _arrow(fig, ax_g, (0.68, -0.2), ax_g2, (0.68, 1.2), "repace")]
        fig.suptitle("→ reconstruct the motion, ξ = −A(r) ṙ (3.10)     ↓ repace the clock, t ↦ τ(t) (3.3)",
                     fontsize=10)

    @override
    def create(self) -> None:
        col = (PALETTE["blue"], PALETTE["orange"])
        self.dots: list[Line2D] = []
        for k, ax in enumerate(self.axes):
            (d,) = ax.plot([], [], "o", color=col[k // 2], ms=4)
            self.dots.append(d)
        self.markers = [ax.plot([], [], "o", ms=10, mfc="none", mec="k", mew=2, zorder=6)[0] for ax in self.axes]
        half = np.diff(self.axes[1].get_xlim())[0] / 2
        self.frames = [FrameArtist(ax, length=0.25 * half) for ax in (self.axes[1], self.axes[3])]
        self.text_top = readout(self.axes[1], 0.03, 0.03)
        self.text_bot = readout(self.axes[3], 0.03, 0.03)

    def _repaced(self, a: float) -> tuple[Callable[[Any], Any], Gait, Trajectory]:
        def make() -> tuple[Callable[[Any], Any], Gait, Trajectory]:
            tau, tau_dot = sine_pacing(a, self.loop.period)
            rep = self.loop.reparameterized(tau, tau_dot)
            return (tau, rep, trajectory(self.system, rep, N_DOTS + 1))

        return self._cache.get(a, make)

    @override
    def set(self, unevenness: float = 0.7, t: float = 0.4) -> None:
        a, t = float(unevenness), float(t)
        tau, rep, tr = self._repaced(a)
        T = self.loop.period
        even = self.base.r[:: 240 // N_DOTS], self.base.g[:: 240 // N_DOTS]
        self.dots[0].set_data(even[0][:, 0], even[0][:, 1])
        self.dots[1].set_data(even[1][:, 0], even[1][:, 1])
        self.dots[2].set_data(tr.r[:, 0], tr.r[:, 1])
        self.dots[3].set_data(tr.g[:, 0], tr.g[:, 1])
        ts = max(t, 1e-9) * T
        s = float(tau(ts))
        self.g_top = displacement_until(self.system, self.loop, s) if s > 0 else np.zeros(3)
        self.g_bot = displacement_until(self.system, rep, ts)
        r_top, r_bot = self.loop(np.array([s]))[0], rep(np.array([ts]))[0]
        for m, p in zip(self.markers, (r_top, self.g_top, r_bot, self.g_bot)):
            m.set_data([p[0]], [p[1]])
        self.frames[0].set(self.g_top)
        self.frames[1].set(self.g_bot)
        gt, gb = self.g_top, self.g_bot
        self.text_top.set_text(f"ψ at τ(t) = {s:.3f}:\n({gt[0]:+.3f},{gt[1]:+.3f},{gt[2]:+.3f})")
        self.text_bot.set_text(f"ψ′ at t = {ts:.3f}:\n({gb[0]:+.3f},{gb[1]:+.3f},{gb[2]:+.3f})")


class DirectionalScene(Scene):
    """The four examples of the directional-linearity box as toy locomotors x_dot = b(r_dot).

    Left: b over the plane of shape velocities (colour), with the rays along which (3.ii) asks
    for linearity. Right: the position x along the demo shape path run at pace 1 (grey), at
    pace k (blue) and backwards from the end at pace k (orange dashed, plotted against the path
    parameter so a retrace lies on the blue curve). Values: ``example`` (a key of RATE_MAPS),
    ``pace``.
    """

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, (self.ax_b, self.ax_x) = new_figure(1, 2, figsize=(8.6, 3.9))
        return fig, [self.ax_b, self.ax_x]

    @override
    def decorate(self) -> None:
        ax = self.ax_b
        ax.set(xlim=(-1, 1), ylim=(-1, 1), aspect="equal", title="b(ṙ) over shape velocities")
        ax.set_xlabel(r"$\dot r_1$", labelpad=1, fontsize=MATH_PT)
        ax.set_ylabel(r"$\dot r_2$", labelpad=1, fontsize=MATH_PT)
        for ang in np.linspace(0, np.pi, 6, endpoint=False):
            ax.plot([-np.cos(ang), np.cos(ang)], [-np.sin(ang), np.sin(ang)], color="0.3", lw=0.6)
        ax = self.ax_x
        ax.set(xlim=(0, 1), title="position x along the shape path")
        ax.set_xlabel("fraction of the shape path", labelpad=1)
        ax.set_ylabel("x", labelpad=1)
        ax.grid(True, alpha=0.3)

    @override
    def create(self) -> None:
        g = np.linspace(-1, 1, 121)
        self.grid = np.stack(np.meshgrid(g, g), -1)
        self.image = self.ax_b.imshow(np.zeros((121, 121)), extent=(-1, 1, -1, 1), origin="lower", cmap="RdBu_r",
                                      vmin=-1.2, vmax=1.2, zorder=0)
        (self.x1,) = self.ax_x.plot([], [], color="0.55", lw=3, label="pace 1")
        (self.xk,) = self.ax_x.plot([], [], color=PALETTE["blue"], lw=1.8, label="pace k")
        (self.xb,) = self.ax_x.plot([], [], color=PALETTE["orange"], lw=1.8, ls="--", label="back, pace k")
        self.ax_x.legend(loc="upper left", fontsize=8)
        # one fixed range that holds every example at every pace (fixed limits keep updates blittable)
        ends = [replay(e, k, rev, x0=replay(e, k)[1][-1] if rev else 0.0, n=200)[1]
                for e in RATE_MAPS for k in (0.25, 3.0) for rev in (False, True)]
        lo, hi = min(float(x.min()) for x in ends), max(float(x.max()) for x in ends)
        self.ax_x.set_ylim(lo - 0.45 * (hi - lo), hi + 0.1 * (hi - lo))
        self.text = readout(self.ax_x, 0.03, 0.03)
        self._example: str | None = None

    @override
    def set(self, example: str = "(a) directionally linear", pace: float = 2.0) -> None:
        if example != self._example:
            self.image.set_data(rate_map(example)(self.grid))
            self._example = example
        s, x1 = replay(example, 1.0)
        _, xk = replay(example, pace)
        sb, xb = replay(example, pace, reverse=True, x0=xk[-1])
        self.x1.set_data(s, x1)
        self.xk.set_data(s, xk)
        self.xb.set_data(sb, xb)
        self.ends = (float(x1[-1]), float(xk[-1]), float(xb[-1]))
        z = lambda v: 0.0 if abs(v) < 5e-4 else v  # noqa: E731 (never "-0.000")
        self.text.set_text(f"end at pace 1: {z(x1[-1]):+.3f}\nend at pace {pace:.2f}: {z(xk[-1]):+.3f}\n"
                           f"back at start: {z(xb[-1]):+.3f}")

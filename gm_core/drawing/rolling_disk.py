"""Nonholonomy made visible (book, box "Nonholonomic constraints", (3.v)-(3.ix)): a rolling disk
parallel-parks by a loop of allowed moves, a point under the integrable constraint (3.viii) cannot.

The math is :mod:`gm_core.systems.rolling_disk`; this module only draws it.
"""
from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from typing_extensions import override

from gm_core.drawing.toolkit.axes import plane
from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist, TrailArtist
from gm_core.drawing.toolkit.style import PALETTE, ArrowSet, Scene, new_figure, readout, signed
from gm_core.groups import SE2
from gm_core.systems.rolling_disk import (
    bracket_estimate,
    disk_moves_path,
    parallel_park_displacement,
    parallel_park_moves,
    radial_loop_moves,
    radial_point_path,
)

__all__ = ["ParallelParkScene", "DISK_OUTLINE"]

#: An upright coin seen from above: a thin bar (its diameter) along the heading.
DISK_OUTLINE = BodyArtist.rectangle(0.6, 0.12)
MOVE_COLORS = (PALETTE["blue"], PALETTE["orange"], PALETTE["sky"], PALETTE["vermillion"])


class ParallelParkScene(Scene):
    """Left: the disk runs drive d, turn phi, back d, turn -phi and ends displaced sideways; the
    net displacement is compared with the small-loop estimate d phi [X_drive, X_turn]. Right: a
    point obeying x x' + y y' = 0 (3.viii) runs the same kind of loop (amount phi along X1,
    d along X2, back, back) and returns exactly to its start on its circle.

    Values: ``d`` (drive distance), ``phi`` (turn angle, radians).
    """

    lim: ClassVar[float] = 1.6

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, (self.ax, self.ax2) = new_figure(1, 2, figsize=(8.6, 4.4))
        return fig, [self.ax, self.ax2]

    @override
    def decorate(self) -> None:
        plane(self.ax, self.lim, step=0.5)
        self.ax.set_title("rolling disk: drive, turn, back, turn back")
        plane(self.ax2, self.lim, step=0.5)
        self.ax2.set_title("x x′ + y y′ = 0 (3.viii): same loop")
        s = np.linspace(0, 2 * np.pi, 200)
        self.ax2.plot(np.cos(s), np.sin(s), ls="--", color="0.5", lw=1)
        self.ax2.plot([0], [0], "+", color="k", ms=8)

    @override
    def create(self) -> None:
        ax, ax2 = self.ax, self.ax2
        self.segments = [ax.plot([], [], color=c, lw=2.5, label=lab)[0]
                         for c, lab in zip(MOVE_COLORS, ("drive d", "turn φ", "back d", "turn −φ"))]
        ax.legend(loc="upper right", fontsize=8, handlelength=1.2, framealpha=0.9)
        grey: dict[str, Any] = dict(facecolor="0.8", edgecolor="0.4", alpha=0.7)
        self.disk0 = BodyArtist(ax, DISK_OUTLINE, **grey, zorder=3)
        self.disk = BodyArtist(ax, DISK_OUTLINE, facecolor=PALETTE["orange"], alpha=0.8, zorder=4)
        self.frame = FrameArtist(ax, length=0.35)
        self.net_arrow = ArrowSet(ax, color=PALETTE["purple"], width=0.012, zorder=7)
        self.text = readout(ax, 0.03, 0.03)
        self.trail2 = TrailArtist(ax2, color=PALETTE["blue"], lw=2.5)
        (self.start2,) = ax2.plot([], [], "o", color="k", ms=7, zorder=5)
        (self.end2,) = ax2.plot([], [], "o", color=PALETTE["orange"], ms=4, zorder=6)
        self.text2 = readout(ax2, 0.03, 0.03)
        self.disk_scale = 1.0

    @override
    def set(self, d: float = 0.8, phi: float = 0.6) -> None:
        moves = parallel_park_moves(d, phi)
        t, g = disk_moves_path(moves, g0=(0.0, -0.4, 0.0), n_per_move=30)
        for k, line in enumerate(self.segments):
            seg = g[30 * k: 30 * (k + 1) + 1]
            if k % 2:   # a turn in place: drawn as the arc its heading sweeps, radius 0.2
                seg = seg[:, :2] + 0.2 * np.stack([np.cos(seg[:, 2]), np.sin(seg[:, 2])], -1)
            line.set_data(seg[:, 0], seg[:, 1])
        self.disk0.set(g[0])
        self.disk.set(g[-1])
        self.frame.set(g[-1])
        self.net = parallel_park_displacement(d, phi)
        self.estimate = bracket_estimate(d, phi)
        self.g_end = g[-1]
        self.net_arrow.set(g[0, :2], g[-1, :2] - g[0, :2])
        n, e = self.net, self.estimate
        self.text.set_text(f"net   (x, y, θ) = ({signed(n)})\nd·φ·[drive, turn] = ({signed(e)})")
        q = radial_point_path(radial_loop_moves(phi, d), q0=(0.0, -1.0), n_per_move=30)
        self.q = q
        self.trail2.set(q)
        self.start2.set_data([q[0, 0]], [q[0, 1]])
        self.end2.set_data([q[-1, 0]], [q[-1, 1]])
        r = np.hypot(q[:, 0], q[:, 1])
        gap = float(np.hypot(*(q[-1] - q[0])))
        self.text2.set_text(f"gap to the start  {gap:.1e}\nradius varies by  {np.ptp(r):.1e}")

    @override
    def replot(self, d: float = 0.8, phi: float = 0.6) -> None:
        for ax in self.axes:
            ax.clear()
        self.decorate()
        moves = parallel_park_moves(d, phi)
        t, g = disk_moves_path(moves, g0=(0.0, -0.4, 0.0), n_per_move=30)
        self.ax.plot(g[:, 0], g[:, 1], color=PALETTE["blue"])
        for pose in (g[0], g[-1]):
            xy = SE2.act_on_points(pose, DISK_OUTLINE)
            self.ax.fill(xy[:, 0], xy[:, 1], color=PALETTE["orange"])
        q = radial_point_path(radial_loop_moves(phi, d), q0=(0.0, -1.0), n_per_move=30)
        self.ax2.plot(q[:, 0], q[:, 1], color=PALETTE["blue"])
        self.ax.text(0.03, 0.03, f"net {parallel_park_displacement(d, phi).round(3)}", transform=self.ax.transAxes)

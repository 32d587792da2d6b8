"""Geodesics and the exponential map (book section 1.6): SE(2) helices, the spinning puck vs the
SE(2) arc (live and as an animation), geodesics of (R+, x), and exp computed four ways.

Geodesics come from :mod:`gm_core.fields`, exp histories from :mod:`gm_core.calculus`.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar, TypedDict

import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from mpl_toolkits.mplot3d.art3d import Line3DCollection
from typing_extensions import override

from gm_core.calculus import exp_history
from gm_core.drawing.groups import BODY
from gm_core.drawing.toolkit.axes import plain_3d, plane, wire
from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist, TrailArtist, animate
from gm_core.drawing.toolkit.style import (
    MATH_PT,
    PALETTE,
    PathText,
    Scene,
    arrow,
    axes_row,
    axis_label,
    margins,
    new_figure,
    readout,
    set_arrows,
    title,
    xticks,
    yticks,
)
from gm_core.fields import puck_vs_arc, rplus_geodesics, se2_helices, se2_helix
from gm_core.groups import SE2, RPlus
from gm_core.groups.base import TWO_PI
from gm_core.manifolds.spaces import cylinder_xyz, sphere_xyz, wrap_segments
from gm_core.manifolds.tangent import cylinder_geodesic, great_circle, sphere_tangent_basis
from gm_core.validation import FloatArray

if TYPE_CHECKING:
    from mpl_toolkits.mplot3d.axes3d import Axes3D

__all__ = ["SurfaceGeodesicsScene", "helix_geometry", "HelixScene", "PuckArcScene", "puck_vs_arc_animation", "RPlusGeodesicScene",
           "ExpFourWaysScene"]


# ================================================================= 1.6.1 geodesics of surfaces
class SurfaceGeodesicsScene(Scene):
    """Fig. 1.16: straightest lines on the cylinder and on the sphere, started the same way.

    Values ``heading_deg`` (the starting direction, measured from "around" -- the cylinder's
    circle, the sphere's equator -- towards "up") and ``length`` (distance travelled at unit
    speed). On the cylinder the geodesic is a loop, a helix or an axial line, and the flattened
    cylinder shows it as a straight line (the cylinder is flat); on the sphere it is a great
    circle whatever the heading. Both from :mod:`gm_core.manifolds`.
    """

    H: ClassVar[float] = 3.0            # the drawn piece of the cylinder: heights |s| <= H (it goes on forever)
    N: ClassVar[int] = 300

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        return axes_row((9, 3.6), ("3d", None, "3d"), left=0.0, right=1.0, bottom=0.12, top=0.9, wspace=0.08)

    @override
    def decorate(self) -> None:
        ax_c: Axes3D
        ax_s: Axes3D
        ax_c, ax_f, ax_s = self.axes
        A, S = np.meshgrid(np.linspace(0, TWO_PI, 19), np.linspace(-self.H, self.H, 7))
        P = cylinder_xyz(S, A)
        wire(ax_c, P[..., 0], P[..., 1], P[..., 2], color="0.8", behind=True)
        plain_3d(ax_c, axes_lines=False)
        ax_c.set_xlim(-1.2, 1.2)
        ax_c.set_ylim(-1.2, 1.2)
        ax_c.set_zlim(-self.H, self.H)
        ax_c.set_box_aspect((1, 1, 2.0), zoom=1.1)
        ax_c.view_init(elev=18, azim=-60)
        title(ax_c, "cylinder: loop, helix or line")
        ax_f.set_xlim(-0.2, TWO_PI + 0.2)
        ax_f.set_ylim(-self.H - 0.1, self.H + 0.1)
        for x in (0.0, TWO_PI):
            ax_f.plot([x, x], [-self.H, self.H], color=PALETTE["vermillion"], lw=1.5)
        axis_label(ax_f, "x", "angle a (left edge = right edge)",
                   ticks=xticks(ax_f, [0, np.pi, TWO_PI], ["0", "π", "2π"]))
        axis_label(ax_f, "y", "s", ticks=yticks(ax_f, [-3, 0, 3], ["−3", "0", "3"]))
        title(ax_f, "flattened cylinder: straight")
        lat, lon = np.meshgrid(np.linspace(-np.pi / 2, np.pi / 2, 9), np.linspace(0, TWO_PI, 17))
        P = sphere_xyz(lat, lon)
        wire(ax_s, P[..., 0], P[..., 1], P[..., 2], color="0.8", behind=True)
        plain_3d(ax_s, lim=1.0, axes_lines=False)
        ax_s.set_box_aspect((1, 1, 1), zoom=1.2)
        ax_s.view_init(elev=18, azim=-60)
        title(ax_s, "sphere: a great circle")

    @override
    def create(self) -> None:
        ax_c: Axes3D
        ax_s: Axes3D
        ax_c, ax_f, ax_s = self.axes
        col = PALETTE["blue"]
        (self.cyl_curve,) = ax_c.plot([], [], [], color=col, lw=2, zorder=3)
        (self.cyl_start,) = ax_c.plot([], [], [], "o", color="k", ms=5, zorder=4)
        from matplotlib.collections import LineCollection

        self.flat = LineCollection([], colors=col, linewidths=2)
        ax_f.add_collection(self.flat)
        (self.flat_start,) = ax_f.plot([], [], "o", color="k", ms=5)
        (self.sph_curve,) = ax_s.plot([], [], [], color=col, lw=2, zorder=3)
        (self.sph_start,) = ax_s.plot([], [], [], "o", color="k", ms=5, zorder=4)
        self.readout = readout(ax_f, 0.07, 1.0, "", size=7.5, va="top", offset=(0, -4))

    @override
    def set(self, heading_deg: float = 15.0, length: float = 3 * np.pi) -> None:
        h = np.deg2rad(heading_deg)
        t = np.linspace(0.0, length, self.N)
        # cylinder (radius 1): unit speed split between going around (cos h) and going up (sin h)
        s_dot, a_dot = np.sin(h), np.cos(h)
        inside = np.abs(s_dot * t) <= self.H + 1e-12        # stop where it leaves the drawn piece
        n = int(np.argmin(inside)) if not inside.all() else len(t)
        self.cyl_t = t[:max(n, 2)]
        C = cylinder_geodesic(0.0, 0.0, s_dot, a_dot, self.cyl_t)
        self.cyl_points = C
        self.cyl_curve.set_data_3d(C[:, 0], C[:, 1], C[:, 2])
        self.cyl_start.set_data_3d([1.0], [0.0], [0.0])
        self.flat_segments = wrap_segments(a_dot * self.cyl_t, s_dot * self.cyl_t, TWO_PI, 0)
        self.flat.set_segments(self.flat_segments)
        self.flat_start.set_data([0.0], [0.0])
        # sphere (radius 1): start on the equator at longitude 0, heading h from east towards north
        east, north = sphere_tangent_basis(0.0, 0.0)
        p0 = sphere_xyz(0.0, 0.0)
        self.sph_points, self.sph_velocity = great_circle(p0, np.cos(h) * east + np.sin(h) * north, t)
        S = self.sph_points
        self.sph_curve.set_data_3d(S[:, 0], S[:, 1], S[:, 2])
        self.sph_start.set_data_3d([p0[0]], [p0[1]], [p0[2]])
        turn = "loop" if abs(s_dot) < 1e-9 else ("axial line" if abs(a_dot) < 1e-9 else
                                                f"helix, rises {TWO_PI * abs(np.tan(h)):.2f} a turn")
        self.readout.set_text(f"heading {heading_deg:.0f}°, length {length:.2f}\ncylinder: {turn}")


# ============================================================================ 1.6 geodesics, exp
class HelixGeometry(TypedDict):
    """What :func:`helix_geometry` gives: sizes of the helix (inf for a straight line), its centre."""

    diameter: float
    radius: float
    period: float
    pitch: float
    arclength: float
    straight: bool
    centre: FloatArray


def helix_geometry(thetadot: float, speed: float = 1.0) -> HelixGeometry:
    """Diameter, period and pitch of the SE(2) geodesic of xi = (speed, 0, thetadot): a dict.

    Thin wrapper over :func:`gm_core.fields.se2_helix` returning plain floats (inf for a
    straight line, thetadot = 0).
    """
    geo = se2_helix(np.array([speed, 0.0, thetadot]))
    return {"diameter": float(geo.diameter), "radius": float(geo.radius), "period": float(geo.period),
            "pitch": float(geo.pitch), "arclength": float(geo.arclength),
            "straight": bool(geo.straight), "centre": np.asarray(geo.centre, float)}


class HelixScene(Scene):
    """Fig. 1.18: SE(2) geodesics exp(t (1, 0, thetadot)) as helices in (x, y, theta) and their
    xy shadows, circles through the origin tangent to the x axis. Value ``thetadot``.
    """

    FAMILY: ClassVar[tuple[float, ...]] = (-2.0, -1.0, -0.5, 0.5, 1.0, 2.0)
    T: ClassVar[FloatArray] = np.linspace(-np.pi, np.pi, 121)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        return axes_row((9, 4.2), ("3d", None), left=0.0, right=0.98, bottom=0.04, top=0.9, wspace=0.05)

    @override
    def decorate(self) -> None:
        ax3: Axes3D
        ax3, ax2 = self.axes
        plain_3d(ax3, lim=3.2, labels=("x", "y", "θ"))
        ax3.set_zlim(-7.0, 7.0)
        ax3.set_box_aspect((1, 1, 1.1), zoom=1.45)    # the helices fill their half of the figure
        ax3.view_init(elev=22, azim=-62)
        plane(ax2, 3.2)
        title(ax2, "xy projection: circles through the origin")
        paths, _ = se2_helices(np.array(self.FAMILY), self.T)
        segs3 = [p for p in paths]
        ax3.add_collection3d(Line3DCollection(segs3, colors="0.7", linewidths=0.8))
        ax2.add_collection(LineCollection([p[:, :2] for p in paths], colors="0.75", linewidths=0.8))

    @override
    def create(self) -> None:
        ax3: Axes3D
        ax3, ax2 = self.axes
        (self.helix,) = ax3.plot([], [], [], color=PALETTE["vermillion"], lw=2.2)
        (self.circle,) = ax2.plot([], [], color=PALETTE["vermillion"], lw=2.2)
        (self.unit,) = ax2.plot([], [], color="k", lw=3.5, alpha=0.6)
        (self.centre,) = ax2.plot([], [], "+", color=PALETTE["vermillion"], ms=9)
        self.title3 = PathText(ax3, 0.5, 0.98, "", size=9, ha="center", va="top", coords="axes")
        self.info = PathText(ax2, 0.03, 0.03, "", size=8, va="bottom", coords="axes")

    @override
    def set(self, thetadot: float = 1.0) -> None:
        paths, _ = se2_helices(np.array([thetadot]), self.T)
        self.path = paths[0]
        self.helix.set_data_3d(self.path[:, 0], self.path[:, 1], self.path[:, 2])
        self.geometry = geo = helix_geometry(thetadot)
        self.circle.set_data(self.path[:, 0], self.path[:, 1])
        unit = SE2.exp(np.linspace(0, 1, 30)[:, None] * np.array([1.0, 0.0, thetadot]))
        self.unit.set_data(unit[:, 0], unit[:, 1])
        self.title3.set_text(f"helix in (x, y, θ) for ξ = (1, 0, {thetadot:.2f})")
        if geo["straight"]:
            self.centre.set_visible(False)
            self.info.set_text("dθ/dt = 0: a straight line\n(the circle's diameter is infinite)")
        else:
            self.centre.set_visible(True)
            self.centre.set_data([geo["centre"][0]], [geo["centre"][1]])
            self.info.set_text(f"diameter 2|v|/|dθ/dt| = {geo['diameter']:.2f}\none turn: t = "
                               f"{geo['period']:.2f}, θ rises 2π\nblack: exp(ξ), xy length |v| = 1")


class PuckArcScene(Scene):
    """Fig. 1.19: the (R^2 x S^1, +) 'spinning puck' and the SE(2) arc, same xi, same time t.

    Values ``t`` and ``w`` (xi = (1, 1, w) as in the book for w = 1). A third panel shows each
    path's *body-frame* forward velocity: constant on SE(2), oscillating for the puck.
    """

    T_MAX: ClassVar[float] = 2 * np.pi

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, axes = new_figure(1, 3, figsize=(10, 3.6), gridspec_kw=dict(width_ratios=[1, 1, 1.1]))
        margins(fig, left=0.02, right=0.98, bottom=0.15, top=0.88, wspace=0.12)
        return fig, list(axes)

    @override
    def decorate(self) -> None:
        a, b, c = self.axes
        plane(a, 4.5)
        plane(b, 4.5)
        title(a, r"$(\mathbb{R}^2 \times \mathbb{S}^1, +)$: line, spinning", size=MATH_PT)
        title(b, "SE(2): arc, constant body velocity")
        c.set_xlim(0, self.T_MAX)
        c.set_ylim(-1.6, 1.6)
        c.axhline(0, color="0.6", lw=0.8)
        axis_label(c, "x", "time t", ticks=xticks(c, [0, np.pi, 2 * np.pi], ["0", "π", "2π"]))
        yticks(c, [-1, 0, 1], ["−1", "0", "1"])
        title(c, "forward speed seen by the body")

    @override
    def create(self) -> None:
        a, b, c = self.axes
        self.paths = [TrailArtist(ax, color=col, lw=1.2, alpha=0.6) for ax, col in
                      ((a, PALETTE["purple"]), (b, PALETTE["blue"]))]
        self.trails = [TrailArtist(ax, color=col, lw=2.5) for ax, col in ((a, PALETTE["purple"]), (b, PALETTE["blue"]))]
        self.bodies = [BodyArtist(ax, BODY * 1.4, facecolor=col) for ax, col in
                       ((a, PALETTE["purple"]), (b, PALETTE["blue"]))]
        self.frames = [FrameArtist(ax, length=0.5) for ax in (a, b)]
        (self.fwd_puck,) = c.plot([], [], color=PALETTE["purple"], lw=1.8)
        (self.fwd_arc,) = c.plot([], [], color=PALETTE["blue"], lw=1.8)
        (self.now,) = c.plot([], [], color="k", lw=1)
        self._w: float | None = None

    @override
    def set(self, t: float = 1.0, w: float = 1.0) -> None:
        if w != self._w:
            ts = np.linspace(0, self.T_MAX, 181)
            self.full = puck_vs_arc(ts, xi=(1.0, 1.0, w))
            self.paths[0].set(self.full.puck[:, :2])
            self.paths[1].set(self.full.arc[:, :2])
            self.fwd_puck.set_data(ts, self.full.puck_body_velocity[:, 0])
            self.fwd_arc.set_data(ts, self.full.arc_body_velocity[:, 0])
            self._w = w
        now = puck_vs_arc(np.linspace(0, t, 60), xi=(1.0, 1.0, w))
        self.now_state = now
        for k, P in enumerate((now.puck, now.arc)):
            self.trails[k].set(P[:, :2])
            self.bodies[k].set(P[-1])
            self.frames[k].set(P[-1])
        self.now.set_data([t, t], [-1.6, 1.6])


def puck_vs_arc_animation(w: float = 1.0, frames: int = 48, interval: float = 80) -> FuncAnimation:
    """FuncAnimation of fig. 1.19 (play it with ``gm_core.drawing.toolkit.primitives.jshtml``; no kernel needed)."""
    scene = PuckArcScene()
    ts = np.linspace(0.0, PuckArcScene.T_MAX, frames)

    def step(k: int) -> list[Artist]:
        scene.set(t=float(ts[k]), w=w)
        return []

    scene.set(t=0.0, w=w)
    return animate(scene.fig, step, frames=frames, interval=interval)


class RPlusGeodesicScene(Scene):
    """Fig. 1.17: geodesics g(t) = exp(t xi) of (R+, x) from e = 1, with the invariant field's arrows.

    Value ``xi``. Every unit of time multiplies g by the same factor exp(xi), so the curve speeds
    up (xi > 0) or slows down (xi < 0); the dashed line is the additive (R, +) geodesic with the
    same starting velocity, for contrast.
    """

    T: ClassVar[FloatArray] = np.linspace(0.0, 3.0, 121)

    FIGSIZE = (6.4, 4.2)
    MARGINS = dict(left=0.15, right=0.97, bottom=0.14, top=0.9)

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        ax.set_xlim(0, 3)
        ax.set_ylim(0, 8)
        xticks(ax, [0, 1, 2, 3], ["0", "1", "2", "3"])
        ticks = yticks(ax, [0, 1, np.e, 4, 6, 8], ["0", "1 (= e)", "2.718 (ℯ)", "4", "6", "8"])
        axis_label(ax, "x", "time t", ticks=ticks[:1])
        axis_label(ax, "y", "g", ticks=ticks)
        ax.axhline(1.0, color="0.7", lw=0.8)
        g, _ = rplus_geodesics(np.array([-1.0, -0.5, 0.5, 1.0]), self.T)
        ax.add_collection(LineCollection([np.c_[self.T, gi] for gi in g], colors="0.8", linewidths=1))

    @override
    def create(self) -> None:
        (ax,) = self.axes
        (self.curve,) = ax.plot([], [], color=PALETTE["vermillion"], lw=2.2)
        (self.additive,) = ax.plot([], [], color=PALETTE["blue"], lw=1.2, ls="--")
        self.arrows = arrow(ax, color=PALETTE["vermillion"], n=4, width=0.006)
        (self.marks,) = ax.plot([], [], "o", color="k", ms=5)
        self.title = title(ax)
        self.info = PathText(ax, 0.03, 0.93, "", size=8, va="top", coords="axes")

    @override
    def set(self, xi: float = 1.0) -> None:
        g, g_dot = rplus_geodesics(np.array(xi), self.T)
        self.g = g
        self.curve.set_data(self.T, g)
        self.additive.set_data(self.T, 1.0 + xi * self.T)
        tk = np.array([0.0, 1.0, 2.0, 3.0])
        gk = RPlus.exp(tk[:, None] * xi)[:, 0]
        self.slopes = xi * gk                    # T_eL_g xi = g xi, the left-invariant field (1.46)
        dt = 0.35
        set_arrows(self.arrows, np.c_[tk, gk], np.c_[np.full(4, dt), dt * self.slopes])
        self.marks.set_data(tk, gk)
        self.ratios = gk[1:] / gk[:-1]
        self.title.set_text(f"ξ = {xi:.2f}: exp(ξ) = {np.exp(xi):.4f}"
                            + ("  — this is e" if abs(xi - 1) < 1e-12 else ""))
        self.info.set_text("g(t+1)/g(t) = " + ", ".join(f"{r:.4f}" for r in self.ratios)
                           + "\narrows: slope ġ = ξ g (left-invariant field)")


class ExpFourWaysScene(Scene):
    """Section 1.6.4 / exercise 1.4d: exp(xi) on SE(2) by closed form, Taylor series, the product
    (I + xi^/n)^n and Euler steps, for xi = (1, 0, thetadot).

    Values ``thetadot``, ``n`` and ``side`` ("left" or "right" invariant field, for Euler). Left:
    error against the number of steps/terms (log-log), with the current n marked. Right: the
    intermediate values of each method in the xy plane, over the closed-form arc.
    """

    NS: ClassVar[tuple[int, ...]] = tuple(2 ** k for k in range(7))
    METHODS: ClassVar[tuple[tuple[str, str, str], ...]] = (
        ("taylor", PALETTE["green"], "Taylor partial sums"), ("product", PALETTE["blue"], r"$(I + \hat\xi/n)^k$"),
        ("euler", PALETTE["orange"], "Euler steps"))

    FIGSIZE = (9.6, 4.0)
    NCOLS = 2
    MARGINS = dict(left=0.08, right=0.98, bottom=0.11, top=0.9, wspace=0.15)

    @override
    def decorate(self) -> None:
        a, b = self.axes
        a.set_xlim(-0.2, 6.3)
        a.set_ylim(-17, 1.5)
        xticks(a, range(7), [str(n) for n in self.NS])
        yticks(a, [0, -4, -8, -12, -16], ["1", "1e-4", "1e-8", "1e-12", "1e-16"])
        title(a, r"error $\|$estimate $-\, \exp(\hat\xi)\|$ against n (log scales)", size=MATH_PT)
        PathText(a, 6.2, -16.5, "n steps / terms →", size=7.5, ha="right")
        b.set_aspect("equal")
        b.set_xticks([])
        b.set_yticks([])
        # one fixed window holds every arc exp(s xi), |thetadot| <= 3 (fixed limits keep slider
        # changes cheap); early Taylor partial sums may leave it, which is part of the story
        b.set_xlim(-0.55, 1.35)
        b.set_ylim(-0.95, 0.95)
        b.axhline(0, color="0.85", lw=0.8, zorder=0)
        b.axvline(0, color="0.85", lw=0.8, zorder=0)
        title(b, "intermediate values in the xy plane", size=MATH_PT)

    @override
    def create(self) -> None:
        a, b = self.axes
        self.err_lines: dict[str, Line2D] = {}
        self.err_marks: dict[str, Line2D] = {}
        self.path_lines: dict[str, Line2D] = {}
        for k, (m, col, label) in enumerate(self.METHODS):
            (self.err_lines[m],) = a.plot([], [], "-o", color=col, ms=4, lw=1.5)
            (self.err_marks[m],) = a.plot([], [], "*", color=col, ms=13, mec="k", mew=0.5)
            (self.path_lines[m],) = b.plot([], [], "-o", color=col, ms=3.5, lw=1.0, alpha=0.85)
            PathText(a, 0.03, 0.30 - 0.08 * k, label, size=MATH_PT, color=col, coords="axes")
        (self.arc,) = b.plot([], [], color="0.3", lw=2.5, alpha=0.5)
        (self.target,) = b.plot([], [], "k*", ms=12)
        self.info = PathText(b, 0.02, 0.03, "", size=7.5, va="bottom", coords="axes", family="monospace")
        self._key: tuple[float, str] | None = None

    @override
    def set(self, thetadot: float = 1.0, n: float = 8, side: str = "left") -> None:
        n = int(n)
        xi = np.array([1.0, 0.0, thetadot])
        key = (thetadot, side)
        if key != self._key:
            self.histories = {m: exp_history(SE2, xi, self.NS, m, side) for m, _, _ in self.METHODS}
            for m, h in self.histories.items():
                self.err_lines[m].set_data(np.log2(h.n), np.log10(np.maximum(h.error, 1e-16)))
            s = np.linspace(0, 1, 60)
            arc = SE2.exp(s[:, None] * xi)
            self.arc.set_data(arc[:, 0], arc[:, 1])
            end = SE2.exp(xi)
            self.target.set_data([end[0]], [end[1]])
            self._key = key
        self.final_error: dict[str, float] = {}
        for m, _, _ in self.METHODS:
            path = self.histories[m].path(n)
            self.final_error[m] = float(path.error[-1]) if m != "taylor" else float(
                np.linalg.norm(path.matrices[-1] - SE2.matrix(SE2.exp(xi))))
            self.err_marks[m].set_data([np.log2(n)], [np.log10(max(self.final_error[m], 1e-16))])
            pts = path.matrices[:, :2, 2] if m != "taylor" else path.matrices[1:, :2, 2]
            self.path_lines[m].set_data(pts[:, 0], pts[:, 1])
        self.info.set_text(f"n = {n}, error:\n" + "\n".join(
            f"{m:<8}{self.final_error[m]:.1e}" for m, _, _ in self.METHODS))


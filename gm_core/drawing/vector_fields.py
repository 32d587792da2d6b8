"""Velocities (book sections 1.4-1.5): vector fields and integral curves, lifted actions, world,
body and spatial velocities, and the adjoint.

The example fields are mathematics in :mod:`gm_core.fields`, rigid-body point velocities in
:mod:`gm_core.manifolds.observers`;
integral curves come from :func:`gm_core.fields.integral_curve` (scipy's solve_ivp).
"""
from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import ClassVar

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.drawing.groups import BODY
from gm_core.drawing.toolkit.axes import plane
from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist
from gm_core.drawing.toolkit.style import (
    MATH_PT,
    PALETTE,
    ArrowSet,
    PathText,
    Scene,
    arrow,
    margins,
    new_figure,
    set_arrows,
    text_panel,
    title,
    xticks,
)
from gm_core.fields import FIELDS, integral_curve
from gm_core.groups import SE2, RPlus
from gm_core.manifolds.observers import icr, point_velocities
from gm_core.validation import FloatArray

__all__ = ["VectorFieldScene", "LiftedScalarScene", "LiftedSE2Scene", "VelocityScene", "AdjointScene",
           "vec_text"]


class VectorFieldScene(Scene):
    """Figs. 1.13-1.14: a vector field, some integral curves, and one from a movable start point.

    Values ``field`` (a key of :data:`FIELDS`), ``x0``, ``y0``. The movable curve is drawn
    forwards (solid) and backwards in time (dashed, the flow of -X); curves computed with
    :func:`gm_core.fields.integral_curve` (scipy solve_ivp).
    """

    LIM: ClassVar[float] = 3.0
    T: ClassVar[float] = 6.0
    N: ClassVar[int] = 240

    FIGSIZE = (5.2, 5.0)
    MARGINS = dict(left=0.03, right=0.97, bottom=0.03, top=0.93)

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        plane(ax, self.LIM, grid=False)
        self._field: str | None = None

    @override
    def create(self) -> None:
        (ax,) = self.axes
        g = np.linspace(-self.LIM + 0.25, self.LIM - 0.25, 13)
        self._grid = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
        self.quiver = ArrowSet(ax, n=len(self._grid), color="0.6", width=0.0045, zorder=1)
        self.background = LineCollection([], colors=PALETTE["blue"], linewidths=1.0, alpha=0.55, zorder=2)
        ax.add_collection(self.background)
        (self.forward,) = ax.plot([], [], color=PALETTE["vermillion"], lw=2.2, zorder=4)
        (self.backward,) = ax.plot([], [], color=PALETTE["vermillion"], lw=1.5, ls="--", zorder=4)
        (self.start,) = ax.plot([], [], "o", color="k", ms=7, zorder=5)
        self.title = title(ax)
        self._field = None

    def _background(self, name: str) -> list[FloatArray]:
        """A few fixed integral curves (both directions), cut where they leave the view: segments."""
        starts = np.array([[2.5, 0.0], [-2.5, 0.5], [0.5, 2.5], [-0.5, -2.5], [1.2, 1.2], [-1.5, -1.0],
                           [0.3, 0.05], [2.8, 2.8], [-2.8, 2.2]])
        segs: list[FloatArray] = []
        for sign in (1.0, -1.0):
            for q0 in starts:
                seg = _flow(FIELDS[name], q0, 4.0, 100, 1.5 * self.LIM, sign)
                if len(seg) > 1:
                    segs.append(seg)
        return segs

    def curve(self, name: str, x0: float, y0: float) -> list[FloatArray]:
        """Forward and backward integral curves from (x0, y0), each (m, 2), by solve_ivp.

        Uses :func:`gm_core.fields.integral_curve` (scipy's solve_ivp) on X and on -X, stopping
        early if the curve leaves a box three times the view (so runaway curves never overflow).
        """
        return [_flow(FIELDS[name], [x0, y0], self.T, self.N, 3 * self.LIM, sign) for sign in (1.0, -1.0)]

    @override
    def set(self, field: str = "spiral sink", x0: float = 1.5, y0: float = 1.0) -> None:
        if field != self._field:
            v = FIELDS[field](self._grid)
            n = np.linalg.norm(v, axis=1, keepdims=True)
            v = 0.32 * v / np.maximum(n, 1e-12) * (n > 1e-12)
            self.quiver.set(self._grid - v / 2, v)   # arrows centred on the grid points
            self.background.set_segments(self._background(field))
            self._field = field
        fwd, bwd = self.curve(field, x0, y0)
        # a curve that runs away (saddle, backwards van der Pol) is cut where it leaves the view
        self.fwd_pts, self.bwd_pts = (c[: _first_outside(c, 3 * self.LIM)] for c in (fwd, bwd))
        self.forward.set_data(self.fwd_pts[:, 0], self.fwd_pts[:, 1])
        self.backward.set_data(self.bwd_pts[:, 0], self.bwd_pts[:, 1])
        self.start.set_data([x0], [y0])
        self.title.set_text(f"{field}: forward (solid) and backward (dashed) from ({x0:.2f}, {y0:.2f})")


def _flow(f: Callable[[FloatArray], FloatArray], q0: ArrayLike, T: float, n: int, lim: float,
          sign: float = 1.0) -> FloatArray:
    """Integral curve of sign * f from q0 at n + 1 equal times on [0, T], stopped where it leaves
    the box |x|, |y| < lim (gm_core.fields.integral_curve with a terminal event): (m, 2)."""
    def leave(t: float, y: FloatArray) -> float:
        return lim - np.max(np.abs(y))

    leave.terminal = True  # type: ignore[attr-defined]  # solve_ivp reads an event function's attribute
    c = integral_curve(lambda q, t: sign * f(q), q0, (0.0, T), t_eval=np.linspace(0.0, T, n + 1),
                       method="RK45", rtol=1e-5, atol=1e-8, events=leave)
    return c.q


def _first_outside(c: FloatArray, lim: float) -> int:
    bad = ~np.all(np.isfinite(c) & (np.abs(c) < lim), axis=1)
    return int(np.argmax(bad)) if bad.any() else len(c)




class LiftedScalarScene(Scene):
    """Lifted actions on (R^2, +) and (R+, x), (1.22)-(1.25): a velocity carried from g to hg.

    Values ``hx``, ``hy`` (a translation of R^2) and ``h`` (a factor in R+). On R^2 the arrow is
    carried unchanged; on R+ it is scaled by h, like interest proportional to the balance.
    """

    G_R2: ClassVar[FloatArray] = np.array([-1.0, -0.5])
    V_R2: ClassVar[FloatArray] = np.array([0.8, 0.4])
    G_RP: ClassVar[float] = 1.5
    V_RP: ClassVar[float] = 0.6

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, axes = new_figure(1, 2, figsize=(9, 3.6), gridspec_kw=dict(width_ratios=[1, 1.5]))
        margins(fig, left=0.03, right=0.98, bottom=0.14, top=0.88, wspace=0.12)
        return fig, list(axes)

    @override
    def decorate(self) -> None:
        ax2, ax1 = self.axes
        plane(ax2, 2.5)
        title(ax2, r"$(\mathbb{R}^2, +)$: $T_gL_h$ = identity", size=MATH_PT)
        ax1.set_xlim(-0.2, 10.5)
        ax1.set_ylim(-1.0, 1.6)
        ax1.set_yticks([])
        ax1.plot([0, 10.5], [0, 0], color="k", lw=1)
        xticks(ax1, [0, 1, 4, 6, 8, 10], ["0", "1 = e", "4", "6", "8", "10"])
        title(ax1, r"$(\mathbb{R}^+, \times)$: $T_gL_h$ = h scales the arrow", size=MATH_PT)

    @override
    def create(self) -> None:
        ax2, ax1 = self.axes
        (self.pts2,) = ax2.plot([], [], "o", color="k", ms=6)
        self.arrows2 = ArrowSet(ax2, color=[PALETTE["blue"], PALETTE["orange"]], n=2, width=0.012)
        self.shift2 = ArrowSet(ax2, color="0.6", width=0.005)
        (self.pts1,) = ax1.plot([], [], "o", color="k", ms=6)
        self.arrows1 = arrow(ax1, color=[PALETTE["blue"], PALETTE["orange"]], n=2, width=0.008)
        self.text1 = PathText(ax1, 0.02, 0.05, "", size=MATH_PT, coords="axes", va="bottom")

    @override
    def set(self, hx: float = 1.5, hy: float = 1.0, h: float = 2.5) -> None:
        g2 = self.G_R2
        hg2 = g2 + np.array([hx, hy])
        self.pts2.set_data([g2[0], hg2[0]], [g2[1], hg2[1]])
        self.v_R2 = np.stack([self.V_R2, np.eye(2) @ self.V_R2])
        set_arrows(self.arrows2, [g2, hg2], self.v_R2)
        set_arrows(self.shift2, g2, [hx, hy])
        g1 = self.G_RP
        hg1 = RPlus.compose([h], [g1])[0]
        lifted = (RPlus.left_lifted_action([h], [g1]) @ [self.V_RP])[0]
        self.v_RP = np.array([self.V_RP, lifted])
        self.pts1.set_data([g1, hg1], [0, 0])
        set_arrows(self.arrows1, [[g1, 0.5], [hg1, 0.5]], [[self.V_RP, 0], [lifted, 0]])
        self.text1.set_text(f"g = {g1:.2f}, ġ = {self.V_RP:.2f}  →  hg = {hg1:.2f}, "
                            f"$T_gL_h\\,\\dot g$ = {lifted:.2f}\n"
                            f"ratio ġ/g = {self.V_RP / g1:.3f} = {lifted / hg1:.3f} (the same at g and hg)")


def vec_text(a: Iterable[float], digits: int = 2) -> str:
    """'(+0.12, -0.50, +0.00)': fixed-width numbers for readouts, never printing -0.00."""
    tiny = 0.5 * 10.0 ** -digits
    return "(" + ", ".join(f"{(c if abs(c) >= tiny else 0.0):+.{digits}f}" for c in a) + ")"




class LiftedSE2Scene(Scene):
    """Lifted actions on SE(2), (1.31) and (1.37): a body's motion carried from g to hg and to gh.

    Values ``theta`` (heading of g), ``u, v, beta`` (h). The body at g moves with world velocity
    g_dot (body velocity XI0). Arrows are the velocities of the body's corners: at hg they are
    T_gL_h g_dot (same motion *as seen by the body*), at gh they are T_gR_h g_dot (the motion of a
    frame welded to g, same *spatial* velocity).
    """

    XI0: ClassVar[FloatArray] = np.array([0.7, 0.0, 0.9])
    G_XY: ClassVar[FloatArray] = np.array([-1.2, -1.0])
    SCALE: ClassVar[float] = 0.7

    FIGSIZE = (5.8, 5.4)
    MARGINS = dict(left=0.02, right=0.98, bottom=0.12, top=0.93)

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        plane(ax, 3.5)

    @override
    def create(self) -> None:
        (ax,) = self.axes
        colors = ("0.45", PALETTE["blue"], PALETTE["orange"])
        self.bodies = [BodyArtist(ax, BODY * 1.6, facecolor=c, alpha=0.45) for c in colors]
        self.vel = [ArrowSet(ax, color=c, n=4, width=0.007) for c in colors]
        (self.weld,) = ax.plot([], [], color=PALETTE["orange"], ls=":", lw=1.5)
        self.title = title(ax, size=MATH_PT)
        # below the plane, where no body or arrow can run under it
        self.text = PathText(ax, 0.0, -0.015, "", size=7.5, va="top", coords="axes", family="monospace")

    @override
    def set(self, theta: float = 0.3, u: float = 2.0, v: float = 1.5, beta: float = 1.0) -> None:
        g = np.array([self.G_XY[0], self.G_XY[1], theta])
        h = np.array([u, v, beta])
        g_dot = SE2.body_to_world(g, self.XI0)
        self.poses = [g, SE2.compose(h, g), SE2.compose(g, h)]
        self.world_vels = [g_dot, SE2.left_lifted_action(h, g) @ g_dot, SE2.right_lifted_action(h, g) @ g_dot]
        for body, q, pose, gd in zip(self.bodies, self.vel, self.poses, self.world_vels):
            body.set(pose)
            pts = np.vstack([pose[:2], SE2.act_on_points(pose, body.outline)])
            set_arrows(q, pts, self.SCALE * point_velocities(pose, gd, pts))
        self.weld.set_data([g[0], self.poses[2][0]], [g[1], self.poses[2][1]])
        xi = [SE2.world_to_body(p, gd) for p, gd in zip(self.poses, self.world_vels)]
        xs = [SE2.world_to_spatial(p, gd) for p, gd in zip(self.poses, self.world_vels)]
        self.body_vels, self.spatial_vels = np.array(xi), np.array(xs)
        self.title.set_text(r"grey: g     blue: hg with $T_gL_h\,\dot g$     orange: gh with $T_gR_h\,\dot g$")
        f = vec_text
        self.text.set_text("    body ξ                spatial ξˢ\n" + "\n".join(
            f"{name:<3}{f(b)}  {f(s)}" for name, b, s in zip(("g", "hg", "gh"), xi, xs)))


class VelocityScene(Scene):
    """Fig. 1.15: world, body and spatial velocity of a body at g with body velocity xi.

    Values ``x, y, theta`` (g) and ``vx, vy, w`` (the body velocity xi).
    """

    LIM: ClassVar[float] = 3.0

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, axes = new_figure(2, 2, figsize=(6.2, 5.9))
        margins(fig, left=0.02, right=0.98, bottom=0.02, top=0.95, wspace=0.06, hspace=0.12)
        return fig, list(np.ravel(axes))

    @override
    def decorate(self) -> None:
        names = ["(a) world velocity ġ", "(b) body velocity ξ, in the body frame",
                 "(c) ξ after moving the body to e", r"(d) spatial velocity $\xi^s$ at the origin"]
        for ax, name in zip(self.axes, names):
            plane(ax, self.LIM)
            title(ax, name, size=MATH_PT)

    @override
    def create(self) -> None:
        a, b, c, d = self.axes
        self.bodies = [BodyArtist(ax, BODY * 1.5, facecolor=PALETTE["blue"], alpha=0.4) for ax in self.axes]
        self.frames = [FrameArtist(ax, length=0.6) for ax in (b, c)]
        self.world = ArrowSet(a, color="k", width=0.012)
        self.components = ArrowSet(b, color=[PALETTE["vermillion"], PALETTE["green"]], n=2, width=0.012)
        self.at_e = ArrowSet(c, color="k", width=0.012)
        self.spatial_parts = ArrowSet(d, color=["0.55", PALETTE["purple"]], n=2, width=0.008)
        self.spatial = ArrowSet(d, color=PALETTE["vermillion"], width=0.012)
        (self.lever,) = d.plot([], [], color=PALETTE["purple"], ls=":", lw=1.5)
        # the instantaneous centre of rotation: the one point of the moving plane at rest (a, d)
        self.icr_marks = [ax.plot([], [], "*", color=PALETTE["orange"], ms=12, mec="k", mew=0.5, zorder=7)[0]
                          for ax in (a, d)]
        self.texts = [PathText(ax, 0.03, 0.02, "", size=MATH_PT, coords="axes", va="bottom")
                      for k, ax in enumerate(self.axes)]

    @override
    def set(self, x: float = 1.2, y: float = 0.6, theta: float = 0.7, vx: float = 0.8, vy: float = 0.3,
            w: float = 0.6) -> None:
        g = np.array([x, y, theta])
        xi = np.array([vx, vy, w])
        self.g_dot = SE2.body_to_world(g, xi)
        self.xi_s = SE2.body_to_spatial(g, xi)
        for k in (0, 1, 3):
            self.bodies[k].set(g)
        self.bodies[2].set(SE2.identity())
        self.frames[0].set(g)
        self.frames[1].set(SE2.identity())
        set_arrows(self.world, g[:2], self.g_dot[:2])
        axes_b = SE2.matrix(g)[:2, :2]
        self.component_vecs = np.stack([vx * axes_b[:, 0], vy * axes_b[:, 1]])
        set_arrows(self.components, [g[:2], g[:2] + self.component_vecs[0]], self.component_vecs)
        set_arrows(self.at_e, [0, 0], xi[:2])
        lever = -g[:2]                         # from the body's frame origin to the world origin
        swirl = w * np.array([-lever[1], lever[0]])
        self.spatial_parts_vecs = np.stack([self.g_dot[:2], swirl])
        set_arrows(self.spatial_parts, [np.zeros(2), self.g_dot[:2]], self.spatial_parts_vecs)
        set_arrows(self.spatial, [0, 0], self.xi_s[:2])
        self.lever.set_data([x, 0], [y, 0])
        p, far = icr(xi)
        self.icr_world = c = None if far else SE2.act_on_points(g, p)
        shown = c is not None and np.max(np.abs(c)) <= self.LIM
        for m in self.icr_marks:
            m.set_visible(bool(shown))
            if shown and c is not None:
                m.set_data([c[0]], [c[1]])
        f = vec_text
        where = ("ICR at infinity: pure translation" if c is None else
                 f"ICR ★ ({c[0]:+.2f}, {c[1]:+.2f})" + ("" if shown else ", off view"))
        self.texts[0].set_text(f"ġ = {f(self.g_dot)}\n{where}")
        self.texts[1].set_text(f"ξ = {f(xi)}\n" + r"(red: $\xi^x$, green: $\xi^y$)")
        self.texts[2].set_text(r"$\xi = T_gL_g^{-1}\,\dot g$" + f"\n= {f(SE2.world_to_body(g, self.g_dot))}")
        self.texts[3].set_text(r"$\xi^s$" + f" = {f(self.xi_s)}\n= ġ + " + r"$\xi^\theta$ × (lever to the origin)")


def _matrix_lines(M: FloatArray) -> str:
    return "\n".join("[" + "  ".join(f"{v:+7.3f}" for v in row) + " ]" for row in M)


class AdjointScene(Scene):
    """(1.40)-(1.45): Ad_g three ways, plus the spatial velocity by finite differences of g(t) g(t)^-1.

    Values ``x, y, theta`` (g) and ``vx, vy, w`` (body velocity xi).
    """

    FIGSIZE = (7.6, 2.05)
    MARGINS = dict(left=0.0, right=1.0, bottom=0.0, top=1.0)

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        text_panel(ax)
        # R_g^{-1} = R_{g^{-1}}, written with one level of scripts (a script of a script is 5 px)
        heads = [r"$\mathrm{Ad}_g$, closed form (1.43)", r"$T_gR_g^{-1}\,T_eL_g$  (1.40)", "same, finite differences"]
        for k, s in enumerate(heads):
            PathText(ax, 0.02 + 0.33 * k, 0.9, s, size=MATH_PT, weight="bold")

    @override
    def create(self) -> None:
        (ax,) = self.axes
        self.blocks = [PathText(ax, 0.02 + 0.33 * k, 0.8, "", size=8.5, va="top", color=c, family="monospace")
                       for k, c in enumerate(("k", PALETTE["blue"], PALETTE["green"]))]
        # numbers (changing, plain glyphs: fast) and what they are (fixed mathtext, laid out once)
        self.difference = PathText(ax, 0.02, 0.44, "", size=MATH_PT, va="top")
        self.summary = PathText(ax, 0.02, 0.44, "", size=MATH_PT, va="top", offset=(0, -1.3 * MATH_PT))
        PathText(ax, 0.335, 0.44, "\n".join((
            r"$\xi^s = \mathrm{Ad}_g\,\xi$",
            r"$\xi^s$ from $d/dt\,(g(t)\,g^{-1})$ by finite differences, $g(t) = g\,\exp(t\xi)$",
            r"back again: $\mathrm{Ad}_g^{-1}\,\xi^s = \xi$")), size=MATH_PT, va="top", offset=(0, -1.3 * MATH_PT))

    @override
    def set(self, x: float = 1.0, y: float = -0.5, theta: float = 0.8, vx: float = 0.5, vy: float = 0.2,
            w: float = 0.7) -> None:
        g = np.array([x, y, theta])
        xi = np.array([vx, vy, w])
        e = SE2.identity()
        ginv = SE2.inverse(g)
        self.Ad = SE2.Ad(g)
        Ad_tn = SE2.right_lifted_action(ginv, g) @ SE2.left_lifted_action(g, e)
        self.Ad_fd = SE2.numerical_right_lifted_action(ginv, g) @ SE2.numerical_left_lifted_action(g, e)
        # independent check with velocities: xi_s = d/dt (g(t) g^-1) at t = 0 with g(t) = g exp(t xi)
        hstep = 1e-6
        Mp = SE2.matrix(SE2.compose(g, SE2.exp(hstep * xi))) @ SE2.matrix(ginv)
        Mm = SE2.matrix(SE2.compose(g, SE2.exp(-hstep * xi))) @ SE2.matrix(ginv)
        self.xi_s_fd = SE2.vee((Mp - Mm) / (2 * hstep))
        self.xi_s = self.Ad @ xi
        self.mismatch = float(max(np.abs(self.Ad - Ad_tn).max(), np.abs(self.Ad - self.Ad_fd).max()))
        for blk, M in zip(self.blocks, (self.Ad, Ad_tn, self.Ad_fd)):
            blk.set_text(_matrix_lines(M))
        f = lambda a: vec_text(a, 4)  # noqa: E731
        self.difference.set_text(f"largest difference between the three matrices: {self.mismatch:.1e}")
        self.summary.set_text(
            f"{f(self.xi_s)}\n{f(self.xi_s_fd)}\n{f(SE2.Ad_inv(g) @ self.xi_s)}")


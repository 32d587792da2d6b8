"""The adjoint as a change of observer (book section 1.5, (1.38)-(1.45)), and the "Frames" box:
reference frame versus coordinate frame, and the instantaneous body frame.

Mathematics in :mod:`gm_core.manifolds.observers` (observed_velocity, icr, conjugation) and
:mod:`gm_core.groups`; here it is drawn. A centre of rotation at infinity (no turning) is
flagged in words, never handed to matplotlib as inf.
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains.jacobians import relative_pose
from gm_core.drawing.groups import BODY
from gm_core.drawing.toolkit.axes import plane
from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist, TrailArtist
from gm_core.drawing.toolkit.style import (
    MATH_PT,
    PALETTE,
    ArrowSet,
    PathText,
    Scene,
    margins,
    new_figure,
    readout,
    set_arrows,
    text_panel,
    title,
)
from gm_core.drawing.vector_fields import vec_text
from gm_core.groups import SE2
from gm_core.manifolds.observers import conjugation, icr, observed_velocity, point_in_frame
from gm_core.validation import FloatArray

__all__ = ["ObserverScene", "FramesScene", "matrix_text"]


def matrix_text(M: ArrayLike, digits: int = 2) -> str:
    """Rows of a small matrix as fixed-width text (never printing -0.00)."""
    tiny = 0.5 * 10.0 ** -digits
    return "\n".join("[" + " ".join(f"{(v if abs(v) >= tiny else 0.0):+.{digits}f}" for v in row) + "]"
                     for row in np.asarray(M))


class ObserverScene(Scene):
    """Move the observer (the world origin) and watch the body velocity stay put while the
    spatial velocity changes; the instantaneous centre of rotation (ICR) is one point for all.

    Values ``hx, hy, htheta`` (the observer's coordinate frame h) and ``vx, vy, w`` (the body
    velocity xi). The body sits at :attr:`G`. Left: the page, with the observer's frame, the
    velocity of the body's origin (black), the velocity of the body point over the observer's
    origin (the spatial velocity seen from h, vermillion) and the ICR (orange star). Right:
    Ad as conjugation, (h^-1 g) xi^ (h^-1 g)^-1 = (Ad xi)^.
    """

    G: ClassVar[FloatArray] = np.array([1.0, 0.6, 0.6])
    LIM: ClassVar[float] = 3.0
    FAR: ClassVar[float] = 6.0          # an ICR farther than this from the view's centre is reported, not drawn
    SCALE: ClassVar[float] = 1.0        # arrow length per unit velocity

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, axes = new_figure(1, 2, figsize=(8.4, 3.8), gridspec_kw=dict(width_ratios=[1, 0.95]))
        margins(fig, left=0.01, right=0.99, bottom=0.01, top=0.93, wspace=0.04)
        return fig, list(axes)

    @override
    def decorate(self) -> None:
        ax, tx = self.axes
        plane(ax, self.LIM)
        FrameArtist(ax, (0, 0, 0), length=0.5, colors=("0.6", "0.6"), zorder=2)
        PathText(ax, -0.1, -0.1, "page", size=7.5, color="0.5", ha="right", va="top")
        title(ax, "one motion, watched from the frame h", size=MATH_PT)
        text_panel(tx)
        title(tx, r"what h measures; Ad as conjugation, $g\,\hat\xi\,g^{-1} = (\mathrm{Ad}_g\,\xi)^\wedge$",
              size=MATH_PT)
        PathText(tx, 0.02, 0.70, r"$\hat\xi$  (same for all h)", size=MATH_PT, weight="bold")
        PathText(tx, 0.52, 0.70, r"$g = h^{-1}\,g_\mathrm{body}$", size=MATH_PT, weight="bold")
        PathText(tx, 0.02, 0.40, r"$g\,\hat\xi\,g^{-1}$  (products)", size=MATH_PT, weight="bold")
        PathText(tx, 0.52, 0.40, r"$(\mathrm{Ad}_g\,\xi)^\wedge$  (1.43)", size=MATH_PT, weight="bold")

    @override
    def create(self) -> None:
        ax, tx = self.axes
        self.body = BodyArtist(ax, BODY * 1.5, self.G, facecolor=PALETTE["blue"], alpha=0.45)
        self.body_frame = FrameArtist(ax, self.G, length=0.5)
        self.observer = FrameArtist(ax, length=0.7, colors=(PALETTE["purple"], PALETTE["purple"]), zorder=4)
        self.observer_label = PathText(ax, 0, 0, "h", size=9, color=PALETTE["purple"], weight="bold",
                                       offset=(-10, -12), ha="center")
        self.v_body = ArrowSet(ax, color="k", width=0.011)
        self.v_spatial = ArrowSet(ax, color=PALETTE["vermillion"], width=0.011)
        (self.spokes,) = ax.plot([], [], color=PALETTE["orange"], ls=":", lw=1.3, zorder=3)
        (self.icr_mark,) = ax.plot([], [], "*", color=PALETTE["orange"], ms=14, mec="k", mew=0.6, zorder=7)
        self.icr_note = PathText(ax, 0.5, 0.965, "", size=MATH_PT, ha="center", va="top", coords="axes",
                                 color=PALETTE["vermillion"], weight="bold")
        # the numbers go beside the picture, so no arrow ever runs under them
        self.readout = readout(tx, 0.02, 0.96, "", size=8, va="top")
        self.blocks = [PathText(tx, x, y, "", size=8, va="top", family="monospace", color=c)
                       for x, y, c in ((0.02, 0.65, "k"), (0.52, 0.65, PALETTE["purple"]),
                                       (0.02, 0.35, PALETTE["blue"]), (0.52, 0.35, PALETTE["green"]))]
        self.check = PathText(tx, 0.02, 0.04, "", size=8, va="bottom", family="monospace")

    @override
    def set(self, hx: float = -1.5, hy: float = -1.0, htheta: float = 0.0, vx: float = 0.8, vy: float = 0.3,
            w: float = 0.6) -> None:
        g = self.G
        h = np.array([hx, hy, htheta])
        self.xi = xi = np.array([vx, vy, w])
        self.h = h
        self.xi_s = observed_velocity(g, xi, h)               # Ad_{h^-1 g} xi
        self.g_rel = relative_pose(g, h)
        self.observer.set(h)
        self.observer_label.set_position(h[:2])
        # velocity of the body's origin, drawn in the page: R(theta) (v_x, v_y)
        self.origin_velocity = SE2.matrix(g)[:2, :2] @ xi[:2]
        set_arrows(self.v_body, g[:2], self.SCALE * self.origin_velocity)
        # the spatial velocity seen from h: the body point over h's origin, its velocity turned into the page
        self.spatial_arrow = SE2.matrix(h)[:2, :2] @ self.xi_s[:2]
        set_arrows(self.v_spatial, h[:2], self.SCALE * self.spatial_arrow)
        p_body, far = icr(xi)
        self.at_infinity = bool(far)
        if self.at_infinity:
            self.icr_world: FloatArray | None = None
            self.icr_mark.set_visible(False)
            self.spokes.set_visible(False)
            self.icr_note.set_text(r"$\xi^\theta = 0$: ICR at infinity (pure translation)")
        else:
            self.icr_world = SE2.act_on_points(g, p_body)
            inside = np.max(np.abs(self.icr_world)) <= self.LIM
            self.icr_mark.set_visible(bool(inside))
            self.icr_mark.set_data([self.icr_world[0]], [self.icr_world[1]])
            c = self.icr_world
            self.spokes.set_visible(True)
            self.spokes.set_data([g[0], c[0], h[0]], [g[1], c[1], h[1]])
            self.icr_note.set_text("" if inside else
                                   f"ICR outside the view, at ({c[0]:.1f}, {c[1]:.1f})")
        p_h, _ = icr(self.xi_s)
        self.icr_in_body = None if self.at_infinity else p_body
        self.icr_in_observer = None if self.at_infinity else p_h
        f = vec_text
        icr_line = ("ICR: at infinity" if self.at_infinity else
                    f"ICR: ({p_body[0]:+.2f}, {p_body[1]:+.2f}) in body frame,\n"
                    f"     ({p_h[0]:+.2f}, {p_h[1]:+.2f}) in h's frame")
        self.readout.set_text(f"ξ  = {f(xi)}  body velocity (stays)\nξˢ = {f(self.xi_s)}  spatial, seen from h\n"
                              f"{icr_line}")
        conj, hat_ad = conjugation(self.g_rel, xi)
        self.conj, self.hat_ad = conj, hat_ad
        for blk, M in zip(self.blocks, (SE2.hat(xi), SE2.matrix(self.g_rel), conj, hat_ad)):
            blk.set_text(matrix_text(M))
        self.mismatch = float(np.max(np.abs(conj - hat_ad)))
        self.check.set_text(f"largest difference: {self.mismatch:.1e}\n"
                            f"vee of both = ξˢ = {f(self.xi_s)}")


class FramesScene(Scene):
    """The "Frames" box of section 1.5: one reference frame (the page), two coordinate frames
    on it, and a body frame versus the instantaneous body frame.

    Values ``t`` (time along a motion of constant body velocity :attr:`XI`) and ``bx, by,
    btheta`` (where the second coordinate frame B sits on the page). The body's nose moves with
    one velocity arrow in the page; frames A (the page's own) and B only write it with different
    numbers. The grey frame (long arrows) is the instantaneous body frame: aligned with the body at time t
    but fixed to the page. The faded body is the body :attr:`DT` later: against the grey frame
    it has moved by exp(DT xi), so the body velocity is what the body does relative to its
    instantaneous frame, while against its own (moving) body frame it never moves at all.
    """

    XI: ClassVar[FloatArray] = np.array([0.8, 0.0, 0.8])
    G0: ClassVar[FloatArray] = np.array([1.3, -0.1, 0.0])  # a circle of radius 1 about (1.3, 0.9), clear of frame A
    TIP: ClassVar[FloatArray] = np.array([0.45, 0.0])      # a point fixed on the body (its nose), in body coordinates
    LIM: ClassVar[float] = 3.0
    DT: ClassVar[float] = 0.8

    FIGSIZE = (6.2, 5.2)
    MARGINS = dict(left=0.01, right=0.99, bottom=0.01, top=0.94)

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        plane(ax, self.LIM, grid=False)
        FrameArtist(ax, (0, 0, 0), length=0.6, zorder=2)
        PathText(ax, -0.08, -0.08, "A", size=9, weight="bold", ha="right", va="top")
        ts = np.linspace(0.0, 8.0, 120)
        path = SE2.compose(self.G0, SE2.exp(ts[:, None] * self.XI))
        ax.plot(path[:, 0], path[:, 1], color="0.8", lw=1, zorder=1)
        title(ax, "one page (reference frame), coordinate frames A and B")

    @override
    def create(self) -> None:
        (ax,) = self.axes
        self.frame_b = FrameArtist(ax, length=0.6, colors=(PALETTE["purple"], PALETTE["purple"]), zorder=3)
        self.label_b = PathText(ax, 0, 0, "B", size=9, weight="bold", color=PALETTE["purple"], offset=(-8, -12))
        self.ghost = BodyArtist(ax, BODY * 1.5, facecolor=PALETTE["sky"], alpha=0.3, edgecolor="0.5")
        self.ghost_frame = FrameArtist(ax, length=0.45, alpha=0.4)
        self.body = BodyArtist(ax, BODY * 1.5, facecolor=PALETTE["blue"], alpha=0.45)
        self.body_frame = FrameArtist(ax, length=0.45)
        self.inst = FrameArtist(ax, length=0.8, colors=("0.3", "0.3"), zorder=2)
        self.inst.quiver.set_linestyle("--")
        self.trail = TrailArtist(ax, color=PALETTE["blue"], lw=2)
        self.tip_velocity = ArrowSet(ax, color="k", width=0.011)
        self.readout = readout(ax, 0.02, 0.02, "", size=7.5)

    @override
    def set(self, t: float = 1.2, bx: float = -1.8, by: float = 1.2, btheta: float = -0.5) -> None:
        b = np.array([bx, by, btheta])
        self.frame_b.set(b)
        self.label_b.set_position(b[:2])
        ts = np.linspace(0.0, t, 60)
        path = SE2.compose(self.G0, SE2.exp(ts[:, None] * self.XI))
        g = path[-1]
        self.g = g
        self.body.set(g)
        self.body_frame.set(g)
        self.inst.set(g)               # the instantaneous body frame: where the body frame is now
        self.trail.set(path[:, :2])
        tip = SE2.act_on_points(g, self.TIP)
        g_dot = SE2.body_to_world(g, self.XI)
        # velocity of a body point in the page: translation plus turning rate times the lever, quarter-turned
        lever = tip - g[:2]
        v = g_dot[:2] + g_dot[2] * np.array([-lever[1], lever[0]])
        self.tip, self.tip_v = tip, v
        set_arrows(self.tip_velocity, tip, v)
        # the same point and arrow in frame A (the page's coordinates) and in frame B
        self.in_a = (tip, v)
        self.in_b = (point_in_frame(b, tip), SE2.matrix(b)[:2, :2].T @ v)
        # the body a moment later, seen from the instantaneous body frame (fixed to the page at g):
        # g^-1 g(t + DT) = exp(DT xi) for a constant body velocity, so log(...) / DT is xi itself
        later = SE2.compose(g, SE2.exp(self.DT * self.XI))
        self.ghost.set(later)
        self.ghost_frame.set(later)
        self.seen_from_instant = SE2.log(relative_pose(later, g)) / self.DT
        f = vec_text
        self.readout.set_text(
            f"nose in A: {f(self.in_a[0])} moving {f(self.in_a[1])}\n"
            f"nose in B: {f(self.in_b[0])} moving {f(self.in_b[1])}\n"
            f"faded body vs grey frame:  log(g⁻¹g')/Δt = {f(self.seen_from_instant)} = ξ\n"
            "body vs its own body frame: never moves")

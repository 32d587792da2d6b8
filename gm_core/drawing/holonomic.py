"""Pinned bodies and frames of chapter 2: pinned bodies (fig. 2.1), relative poses (the notation box, (2.iii)-(2.iv)) and
the velocity of a generalized body frame (fig. 2.9, section 2.5.6).

Each scene computes with :mod:`gm_core.chains.holonomic`, :mod:`gm_core.chains` and
:mod:`gm_core.chains.three_link` and moves its artists in place; the panels are in
:mod:`gm_core.widgets.holonomic`. Scenes with a table of numbers draw the plane on the left and the
numbers in a text-only axes on the right (:func:`plane_and_notes`).
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any, ClassVar, TypedDict

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike
from typing_extensions import Unpack, override

from gm_core.chains import chain as C
from gm_core.chains.holonomic import pin_constraints, pinned_pair
from gm_core.chains.three_link import beta_frame_velocity, com_frame
from gm_core.drawing.chains import ArrowsArtist, ChainArtist, ThreeLinkScene
from gm_core.drawing.toolkit.axes import square_axes
from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist
from gm_core.drawing.toolkit.style import MATH_PT, PALETTE, PathText, Scene, new_figure, readout
from gm_core.groups import SE2
from gm_core.validation import FloatArray

__all__ = ["plane_and_notes", "notes_text", "PinnedBodiesScene", "RelativePoseScene", "BetaVelocityScene",
           "BODY_OUTLINE"]

#: Outline of a link-like body in its own frame: the frame sits near one end, where the pin goes.
BODY_OUTLINE = np.array([[-0.18, -0.14], [1.1, -0.1], [1.25, 0.0], [1.1, 0.1], [-0.18, 0.14]])


def plane_and_notes(figsize: Sequence[float] = (8.0, 4.4),
                    ratio: Sequence[float] = (3, 2)) -> tuple[Figure, Axes, Axes]:
    """``(fig, ax, notes)``: square world axes on the left, a text-only axes for readouts on the right."""
    fig, (ax, notes) = new_figure(1, 2, figsize=figsize, gridspec_kw=dict(width_ratios=list(ratio)))
    notes.set_axis_off()
    return fig, ax, notes


def notes_text(notes: Axes, y: float = 1.0, size: float = 8.5, **kw: Any) -> PathText:
    """A monospace readout hanging from the top-left of the notes axes (lines grow downwards)."""
    return readout(notes, 0.0, y, size=size, va="top", **kw)


def _label(ax: Axes, text: str, color: ColorType = "k") -> PathText:
    return PathText(ax, 0.0, 0.0, text, size=9, color=color, coords="data", offset=(5, 5), weight="bold")


def _fmt(v: ArrayLike) -> str:
    return "(%+.2f, %+.2f, %+.2f)" % tuple(np.asarray(v, float))


# ============================================================== fig. 2.1: two pinned bodies
class PinnedBodiesScene(Scene):
    """Two rigid bodies, free in SE(2) x SE(2) or pinned at their frame origins (fig. 2.1, section 2.1).

    Values: ``x1, y1, theta1, x2, y2, theta2`` and ``pinned`` (bool). Pinned, body 2 is placed by
    :func:`gm_core.chains.holonomic.pinned_pair` from body 1's pose and alpha = theta2 - theta1 (its own
    x2, y2 are ignored: the constraint fixes them); free, the dashed segment between the two frame
    origins is the value of the pin constraints (2.1), :func:`gm_core.chains.holonomic.pin_constraints`.
    """

    lim: ClassVar[float] = 2.2
    COLORS: ClassVar[tuple[str, str]] = (PALETTE["blue"], PALETTE["orange"])

    FIGSIZE = (5.0, 4.6)

    @override
    def decorate(self) -> None:
        square_axes(self.ax, self.lim)

    @override
    def create(self) -> None:
        ax = self.ax
        self.bodies = [BodyArtist(ax, BODY_OUTLINE, facecolor=c, alpha=0.45, zorder=2) for c in self.COLORS]
        self.frames = [FrameArtist(ax, length=0.45, zorder=5) for _ in range(2)]
        self.labels = [_label(ax, f"g{i + 1}", c) for i, c in enumerate(self.COLORS)]
        (self.gap,) = ax.plot([], [], "--", color="k", lw=1.5, zorder=3)
        (self.pin,) = ax.plot([], [], "o", ms=11, mfc="white", mec="k", mew=2, zorder=6)
        self.text = readout(ax, 0.02, 0.02, size=8)

    def compute(self, **values: float) -> tuple[FloatArray, FloatArray]:
        """Poses ``(2, 3)`` of the two bodies and the pin-constraint values ``(2,)``."""
        g1 = np.array([values["x1"], values["y1"], values["theta1"]], float)
        if values.get("pinned", False):
            g = pinned_pair(g1, values["theta2"] - values["theta1"])
        else:
            g = np.stack([g1, np.array([values["x2"], values["y2"], values["theta2"]], float)])
        return g, pin_constraints(g[0], g[1])

    @override
    def set(self, **values: float) -> None:
        g, f = self.compute(**values)
        pinned = bool(values.get("pinned", False))
        self.poses, self.constraints = g, f
        for body, fa, lab, gi in zip(self.bodies, self.frames, self.labels, g):
            body.set(gi)
            fa.set(gi)
            lab.set_position(SE2.act_on_points(gi, BODY_OUTLINE[2]))
        self.gap.set_data(g[:, 0], g[:, 1])
        self.gap.set_visible(not pinned)
        self.pin.set_data([g[0, 0]], [g[0, 1]])
        self.pin.set_visible(pinned)
        alpha = float(SE2.difference(g[1], g[0])[2])
        lines = ["pin constraints (2 equations):",
                 f"  x1 - x2 = {f[0]:+.2f}   y1 - y2 = {f[1]:+.2f}"]
        if pinned:
            lines += ["pinned: 4 free numbers,", f"  (x, y, θ1) in SE(2) and α = θ2 - θ1 = {alpha:+.2f}"]
        else:
            lines += ["free: 6 numbers, SE(2) × SE(2)"]
        self.text.set_text("\n".join(lines))


# ======================================================= the notation box, (2.iii)-(2.iv)
class _RelativePoseValues(TypedDict):
    """The values of a :class:`RelativePoseScene`: the arm's angles and three of its frames' names."""

    alpha1: float
    alpha2: float
    frame: str
    seen_from: str
    via: str


class RelativePoseScene(Scene):
    """The frames of a two-link arm and the pose of one seen from another, g_{a,b} = b^-1 a (2.iii).

    Values: ``alpha1, alpha2`` (the arm), ``frame`` (a), ``seen_from`` (b) and ``via`` (c), each one
    of :attr:`NAMES`. Drawn: the observer b's axes extended as light lines, the arrow from b to a
    and a's coordinates in b as a dashed path along b's x axis then its y axis; the route through c
    (b to c, then c to a) in grey. The numbers (``self.rel``, ``self.chained``, ``self.swapped``)
    show the cancellation rules: g_{c,b} g_{a,c} = g_{a,b} and g_{a,b}^-1 = g_{b,a}.
    """

    NAMES: ClassVar[tuple[str, ...]] = ("e", "g1", "h1", "g2", "h2")
    lim: ClassVar[float] = 2.4

    def __init__(self, lengths: ArrayLike = (1.2, 1.0), **options: Any) -> None:
        self.chain = C.Chain("RR", lengths)
        super().__init__(**options)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, self.ax, self.notes = plane_and_notes(figsize=(8.4, 4.4))
        return fig, [self.ax, self.notes]

    @override
    def decorate(self) -> None:
        square_axes(self.ax, self.lim)
        self.ax.set_xlim(-self.lim + 0.6, self.lim + 0.6)
        self.notes.set_axis_off()

    @override
    def create(self) -> None:
        ax = self.ax
        self.art = ChainArtist(ax, 2, width=0.1, frames_shown=("g", "h"), pivot=True, frame_length=0.35,
                               colors=["0.8", "0.8"])
        self.origin = FrameArtist(ax, length=0.35)
        self.labels = {n: _label(ax, n.replace("1", "₁").replace("2", "₂")) for n in self.NAMES}
        (self.observer,) = ax.plot([], [], "-", color=PALETTE["sky"], lw=1.0, zorder=1)
        (self.coord_x,) = ax.plot([], [], "--", color=PALETTE["x"], lw=2.0, zorder=3)
        (self.coord_y,) = ax.plot([], [], "--", color=PALETTE["y"], lw=2.0, zorder=3)
        self.route = ArrowsArtist(ax, 2, color=PALETTE["purple"], width=0.006, zorder=5)
        self.arrow = ArrowsArtist(ax, 1, color="k", width=0.009, zorder=7)
        # proportional text at MATH_PT: its mathtext subscripts ($g_{h2,g1}$) are 10 px; the
        # changing numbers sit on lines of their own, so a formula is laid out once per choice
        self.text = PathText(self.notes, 0.0, 1.0, "", size=MATH_PT, va="top", coords="axes")

    def poses(self, alpha1: float, alpha2: float) -> dict[str, FloatArray]:
        """World poses of the named frames: dict name -> ``(3,)``."""
        fr = self.chain.frames([alpha1, alpha2])
        return {"e": SE2.identity(), "g1": fr["g"][0], "h1": fr["h"][0], "g2": fr["g"][1], "h2": fr["h"][1]}

    def compute(self, **values: Unpack[_RelativePoseValues]
                ) -> tuple[dict[str, FloatArray], FloatArray, FloatArray, FloatArray]:
        P = self.poses(values["alpha1"], values["alpha2"])
        a, b, c = P[values["frame"]], P[values["seen_from"]], P[values["via"]]
        rel = C.relative_pose(a, b)                                       # g_{a,b} = b^-1 a
        chained = SE2.compose(C.relative_pose(c, b), C.relative_pose(a, c))   # g_{c,b} g_{a,c}
        swapped = C.relative_pose(b, a)                                   # g_{b,a}
        return P, rel, chained, swapped

    @override
    def set(self, **values: Unpack[_RelativePoseValues]) -> None:
        P, rel, chained, swapped = self.compute(**values)
        self.P, self.rel, self.chained, self.swapped = P, rel, chained, swapped
        fr = self.chain.frames([values["alpha1"], values["alpha2"]])
        self.art.set(fr)
        for n, lab in self.labels.items():
            lab.set_position(P[n][:2])
        na, nb, nc = values["frame"], values["seen_from"], values["via"]
        a, b, c = P[na], P[nb], P[nc]
        # b's axes as long lines: "seen from b" means measured along these
        L = 2 * self.lim
        ends = SE2.act_on_points(b, np.array([[-L, 0], [L, 0], [0, 0], [0, -L], [0, L]]))
        ends[2] = np.nan                                                     # two separate lines
        self.observer.set_data(ends[:, 0], ends[:, 1])
        corner = SE2.act_on_points(b, np.array([[0.0, 0.0], [rel[0], 0.0], [rel[0], rel[1]]]))
        self.coord_x.set_data(corner[:2, 0], corner[:2, 1])
        self.coord_y.set_data(corner[1:, 0], corner[1:, 1])
        self.arrow.set(b[:2], a[:2] - b[:2])
        self.route.set(np.stack([b[:2], c[:2]]), np.stack([c[:2] - b[:2], a[:2] - c[:2]]))
        sub = lambda x, y: f"$g_{{{x},{y}}}$"                                # noqa: E731 (mathtext)
        err = float(np.max(np.abs(SE2.difference(chained, rel))))
        inv_err = float(np.max(np.abs(SE2.difference(SE2.inverse(rel), swapped))))
        self.text.set_text("\n".join([
            f"pose of {na} seen from {nb} (black):",
            f"  {sub(na, nb)[:-1]} = {nb}^{{-1}}\\,{na}$",
            f"     = {_fmt(rel)}",
            f"  x, y: along {nb}'s axes (dashed),",
            f"  {nb}'s axes drawn long in blue",
            "",
            f"through {nc} (purple; {nc} cancels):",
            f"  {sub(nc, nb)[:-1]}\\,{sub(na, nc)[1:]}",
            f"     = {_fmt(chained)}, differs by {err:.0e}",
            "",
            "swap the subscripts = invert:",
            f"  {sub(nb, na)[:-1]} = {sub(na, nb)[1:-1]}^{{-1}}$",
            f"     = {_fmt(swapped)}, differs by {inv_err:.0e}",
        ]))


# ============================================ fig. 2.9, section 2.5.6: the velocity of beta
class BetaVelocityScene(ThreeLinkScene):
    """The velocity of the centre-of-mass frame g = g_2 beta(alpha) split into its two causes, (2.60)-(2.67).

    The middle link sits at the identity and moves with body velocity xi; the shape changes at
    alpha_dot. At the origin of the frame: the velocity it would have if welded to the middle link
    (blue, Ad_beta^-1 xi), plus the velocity from the shape change (orange, drawn from the blue
    tip, Ad_beta^-1 v_beta), which add to the frame's velocity (black). Dotted: the paths the
    origin would follow under each cause alone; each arrow is tangent to its own path. Values:
    ``alpha1, alpha2, alpha1_dot, alpha2_dot, xi_x, xi_y, xi_theta``.
    """

    figsize = (8.4, 4.15)   # with its seven sliders above: 620 px, on one laptop screen
    SCALE: ClassVar[float] = 1.2
    # what the numbers are: fixed mathtext lines (PathText lays each distinct line out once), the
    # changing numbers on lines of their own
    NOTES: ClassVar[tuple[str, ...]] = (
        "body velocity of the frame, (2.60):",
        r"$\xi_\beta = \mathrm{Ad}_\beta^{-1}\,\xi_2 + \mathrm{Ad}_\beta^{-1}\,v_\beta$",
        "",
        r"$\mathrm{Ad}_\beta^{-1}\,\xi_2$   carried by link 2 (blue)",
        "   {carried}",
        "",
        r"$\mathrm{Ad}_\beta^{-1}\,v_\beta$   from the shape change (orange)",
        "   {shape}",
        "",
        r"$\xi_\beta$   sum (black)",
        "   {body}",
        "",
        r"$v_\beta = T_\beta R_\beta^{-1}\,\dot\beta$, (2.61):",
        "   {v_beta}",
    )
    KEY: ClassVar[str] = ("dotted: the path of the frame's origin under each cause\n"
           "alone; faint orange: the shape part again, from the origin;\n"
           "thin blue: link 2's velocity; arrows: world velocity × {SCALE}")
    COLORS: ClassVar[dict[str, str]] = {"carried": PALETTE["blue"], "shape": PALETTE["orange"], "body": "k"}

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, self.ax, self.notes = plane_and_notes(figsize=self.figsize)
        return fig, [self.ax, self.notes]

    @override
    def decorate(self) -> None:
        self.lim = 0.55 * sum(self.lengths)
        square_axes(self.ax, self.lim)
        self.notes.set_axis_off()

    @override
    def create(self) -> None:
        ax = self.ax
        self.art = ChainArtist(ax, 3, frames_shown=(), base_link=1, colors=["0.75", PALETTE["sky"], "0.75"])
        self.beta_art = FrameArtist(ax, length=0.3, colors=("0.35", "0.6"), zorder=8)
        (self.lever,) = ax.plot([], [], ":", color="k", lw=1.2, zorder=3)
        (self.centres,) = ax.plot([], [], "s", color="k", ms=4, zorder=4)
        (self.path_carried,) = ax.plot([], [], ":", color=self.COLORS["carried"], lw=2, zorder=3)
        (self.path_shape,) = ax.plot([], [], ":", color=self.COLORS["shape"], lw=2, zorder=3)
        self.link_vel = ArrowsArtist(ax, 1, color=self.COLORS["carried"], scale=self.SCALE, width=0.006)
        self.arrows = {k: ArrowsArtist(ax, 1, color=c, scale=self.SCALE, width=0.006 if k == "body" else 0.011,
                                       zorder=10 if k == "body" else 9) for k, c in self.COLORS.items()}
        # the shape part again at the origin, faint: tangent to its own dotted path
        self.shape_at_origin = ArrowsArtist(ax, 1, color=self.COLORS["shape"], scale=self.SCALE, width=0.005,
                                            zorder=7)
        self.shape_at_origin.quiver.set_alpha(0.6)
        self.text = PathText(self.notes, 0.0, 1.0, "", size=MATH_PT, va="top", coords="axes")
        PathText(self.notes, 0.0, 0.0, self.KEY.replace("{SCALE}", f"{self.SCALE:g}"), size=8, va="bottom",
                 coords="axes")
        self.s = np.linspace(-1.0, 1.0, 41)[:, None]

    def compute(self, **values: float) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, dict[str, FloatArray]]:
        """Shape, beta, its velocity parts (dict of ``(3,)``) and the frames of the chain."""
        a = np.array([values["alpha1"], values["alpha2"]], float)
        ad = np.array([values["alpha1_dot"], values["alpha2_dot"]], float)
        xi = np.array([values["xi_x"], values["xi_y"], values["xi_theta"]], float)
        beta, dbeta = com_frame(a, self.lengths)
        parts = beta_frame_velocity(beta, dbeta, xi, ad)
        return a, ad, xi, beta, parts

    @override
    def set(self, **values: float) -> None:
        a, ad, xi, beta, parts = self.compute(**values)
        fr = self.chain.frames(a)                     # middle link at e: g = g_2 beta = beta
        self.art.set(fr)
        self.beta_art.set(beta)
        self.lever.set_data([0.0, beta[0]], [0.0, beta[1]])
        self.centres.set_data(fr["g"][:, 0], fr["g"][:, 1])
        world = {k: SE2.body_to_world(beta, parts[k]) for k in ("carried", "shape", "body")}
        p = beta[:2]
        self.arrows["carried"].set(p, world["carried"][:2])
        self.arrows["shape"].set(p + self.SCALE * world["carried"][:2], world["shape"][:2])
        self.arrows["body"].set(p, world["body"][:2])
        self.shape_at_origin.set(p, world["shape"][:2])
        self.link_vel.set(fr["g"][1, :2], xi[:2])
        self.world, self.parts = world, parts
        # each cause alone: the middle link moving along exp(s xi) with beta welded on; the shape moving
        carried = SE2.compose(SE2.exp(self.s * xi), beta)
        shaped = com_frame(a + self.s * ad, self.lengths)[0]
        self.path_carried.set_data(carried[:, 0], carried[:, 1])
        self.path_shape.set_data(shaped[:, 0], shaped[:, 1])
        numbers = {k: _fmt(parts[k]) for k in ("carried", "shape", "body", "v_beta")}
        text = "\n".join(self.NOTES)
        for k, v in numbers.items():
            text = text.replace("{" + k + "}", v)
        self.text.set_text(text)

    @override
    def replot(self, **values: Any) -> None:
        Scene.replot(self, **values)

"""Kinematic chains (book chapter 2): kinematic chains, joints, frames and velocity arrows, all moved in place.

``ChainArtist`` draws a chain from the frame dictionary returned by ``gm_core.chains``
(``{"f", "g", "h"}`` of shape ``(n_links, 3)``): each link a rectangle from its proximal to its
distal frame, joints as dots, and any of the f/g/h frames with ``FrameArtist``. ``ArrowsArtist``
draws translational velocities (e.g. end-effector velocities) as arrows.
"""
from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Polygon
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains import chain as C
from gm_core.chains.arms import rp_arm_body_jacobians
from gm_core.chains.holonomic import accessible_circle, circle_constraints, sample_accessible_manifold
from gm_core.chains.three_link import com_frame, three_link_chain, three_link_jacobians
from gm_core.drawing.toolkit.axes import square_axes
from gm_core.drawing.toolkit.primitives import FrameArtist
from gm_core.drawing.toolkit.style import PALETTE, Scene, new_figure, readout
from gm_core.groups import SE2
from gm_core.validation import FloatArray

if TYPE_CHECKING:
    from mpl_toolkits.mplot3d.axes3d import Axes3D

#: A chain's frames as gm_core.chains gives them: {"f", "g", "h"} of shape (n_links, 3).
Frames = Mapping[str, ArrayLike]
#: The joints of a chain: "R"/"P" letters ("RPR") or a sequence of joint types.
JointsLike = str | Sequence[str | C.Joint]

__all__ = ["link_outline", "ChainArtist", "ArrowsArtist", "draw_chain_naive", "draw_accessible_manifold",
           "ArmScene", "OffsetRPArmScene", "MobileChainScene", "BetaFrameScene",
           "ThreeLinkVelocityScene", "JacobianMethodsScene", "ThreeLinkScene"]


def link_outline(p: ArrayLike, q: ArrayLike, width: float) -> FloatArray:
    """World corners ``(4, 2)`` of a rectangle of ``width`` around the segment from p to q."""
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    d = q - p
    n = np.hypot(*d)
    u = d / n if n > 1e-12 else np.array([1.0, 0.0])
    v = np.array([-u[1], u[0]]) * (width / 2)
    return np.array([p - v, q - v, q + v, p + v])


class ChainArtist:
    """A planar chain: link rectangles, joint dots and SE(2) frames, updated by ``set(frames)``.

    ``frames_shown`` picks which of "f", "g", "h" get a FrameArtist; ``joints`` is a list of
    (link index, "f" or "h") naming where joint dots go (default: the proximal end of every link
    after the first, and the base pivot if ``pivot``).
    """

    def __init__(self, ax: Axes, n_links: int, width: float = 0.12, frames_shown: Iterable[str] = ("g",),
                 colors: Sequence[ColorType] | None = None, pivot: bool = False, frame_length: float = 0.3,
                 base_link: int | None = None, lengths: ArrayLike | None = None, offsets: ArrayLike | None = None,
                 **style: Any) -> None:
        self.ax = ax
        self.lengths = None if lengths is None else np.asarray(lengths, dtype=float)
        self.offsets = None if offsets is None else np.asarray(offsets, dtype=float)
        # a link whose distal frame is offset sideways (fig. 2.10) is drawn as a bar plus an elbow
        self.elbows: Line2D | None = None
        if self.lengths is not None and self.offsets is not None and np.any(self.offsets != 0):
            (self.elbows,) = ax.plot([], [], "-", color="0.25", lw=4, solid_capstyle="round", zorder=2)
        self.n_links = int(n_links)
        self.width = float(width)
        colors = colors or [f"C{i}" for i in range(self.n_links)]
        self.links: list[Polygon] = []
        for i in range(self.n_links):
            patch = Polygon(np.zeros((4, 2)), closed=True, facecolor=colors[i % len(colors)], alpha=0.45,
                            edgecolor="k", lw=1.2 if i != base_link else 2.5, zorder=2, **style)
            ax.add_patch(patch)
            self.links.append(patch)
        (self.joint_dots,) = ax.plot([], [], "o", ms=7, mfc="white", mec="k", mew=1.5, zorder=4)
        self.pivot = pivot
        if pivot:
            (self.pivot_mark,) = ax.plot([0], [0], "^", ms=12, color="0.3", zorder=1)
        self.frames_shown = tuple(frames_shown)
        self.frames = {k: [FrameArtist(ax, length=frame_length) for _ in range(self.n_links)]
                       for k in self.frames_shown}
        self.last: dict[str, FloatArray] | None = None

    def set_base_link(self, b: int) -> None:
        for i, patch in enumerate(self.links):
            patch.set_linewidth(2.5 if i == b else 1.2)

    def set(self, frames: Frames) -> bool:
        """Move every artist to ``frames`` (dict f, g, h of ``(n_links, 3)``); hides them if not finite."""
        f, h = np.asarray(frames["f"], float), np.asarray(frames["h"], float)
        ok = all(np.all(np.isfinite(np.asarray(frames[k], float))) for k in ("f", "g", "h"))
        for art in self.all_artists():
            art.set_visible(ok)
        if not ok:
            return False
        ends = h[:, :2]
        if self.elbows is not None and self.lengths is not None:   # elbows are drawn only given lengths
            c, s = np.cos(f[:, 2]), np.sin(f[:, 2])
            ends = f[:, :2] + self.lengths[:, None] * np.stack([c, s], -1)
            pts = np.concatenate([ends[:, None], h[:, None, :2], np.full((len(f), 1, 2), np.nan)], 1)
            self.elbows.set_data(pts[..., 0].ravel(), pts[..., 1].ravel())
        for i, patch in enumerate(self.links):
            patch.set_xy(link_outline(f[i, :2], ends[i], self.width))
        pts = [f[i, :2] for i in range(1, self.n_links)]
        if self.pivot:
            self.pivot_mark.set_data([f[0, 0]], [f[0, 1]])
            pts = [f[0, :2]] + pts
        pts = np.array(pts).reshape(-1, 2)
        self.joint_dots.set_data(pts[:, 0], pts[:, 1])
        for k, arts in self.frames.items():
            for i, fa in enumerate(arts):
                fa.set(np.asarray(frames[k], float)[i])
        self.last = {k: np.array(frames[k], dtype=float) for k in ("f", "g", "h")}
        return True

    def all_artists(self) -> list[Artist]:
        arts: list[Artist] = [*self.links, self.joint_dots, *([self.pivot_mark] if self.pivot else [])]
        if self.elbows is not None:
            arts.append(self.elbows)
        for v in self.frames.values():
            arts += [fa.quiver for fa in v]
        return arts

    def link_corners(self, i: int) -> FloatArray:
        """Current world corners ``(4, 2)`` of link i's rectangle (for tests)."""
        return np.asarray(self.links[i].get_xy())[:4]


class ArrowsArtist:
    """Velocity arrows: ``set(points (k, 2), vectors (k, 2))``; non-finite arrows are hidden."""

    def __init__(self, ax: Axes, k: int, color: ColorType = PALETTE["purple"], scale: float = 1.0, width: float = 0.008,
                 zorder: float = 6, label: str | None = None) -> None:
        self.k = int(k)
        self.scale = float(scale)
        self.quiver = ax.quiver(np.zeros(k), np.zeros(k), np.zeros(k), np.zeros(k), color=color,
                                angles="xy", scale_units="xy", scale=1.0 / self.scale, width=width,
                                zorder=zorder, label=label)
        self.points = np.zeros((k, 2))
        self.vectors = np.zeros((k, 2))

    def set(self, points: ArrayLike, vectors: ArrayLike) -> bool:
        points = np.asarray(points, float).reshape(self.k, 2)
        vectors = np.asarray(vectors, float).reshape(self.k, 2)
        ok = bool(np.all(np.isfinite(points)) and np.all(np.isfinite(vectors)))
        self.quiver.set_visible(ok)
        if not ok:
            return False
        self.quiver.set_offsets(points)
        self.quiver.set_UVC(vectors[:, 0], vectors[:, 1])
        self.points, self.vectors = points, vectors
        return True


def draw_chain_naive(ax: Axes, frames: Frames, width: float = 0.12, frames_shown: Iterable[str] = ("g",),
                     frame_length: float = 0.3) -> None:
    """Plot a chain from scratch with plain ax.plot/fill calls (the clear-and-replot baseline)."""
    f, h = np.asarray(frames["f"], float), np.asarray(frames["h"], float)
    for i in range(len(f)):
        c = link_outline(f[i, :2], h[i, :2], width)
        ax.fill(c[:, 0], c[:, 1], color=f"C{i}", alpha=0.45, ec="k")
    ax.plot(f[1:, 0], f[1:, 1], "o", mfc="white", mec="k")
    for k in frames_shown:
        for g in np.asarray(frames[k], float):
            x, y, t = g
            ax.arrow(x, y, frame_length * np.cos(t), frame_length * np.sin(t), color=PALETTE["vermillion"])
            ax.arrow(x, y, -frame_length * np.sin(t), frame_length * np.cos(t), color=PALETTE["green"])


def draw_accessible_manifold(ax3d: Axes3D, n: int = 60, rng: np.random.Generator | None = None) -> FloatArray:
    """Draw the holonomic-constraint box of section 2.1 on 3D axes: plane (2.i), cone (2.ii), their circle."""
    u = np.linspace(-1.6, 1.6, 2)
    X, Y = np.meshgrid(u, u)
    ax3d.plot_surface(X, Y, np.ones_like(X), alpha=0.15, color=PALETTE["blue"])
    r, t = np.meshgrid(np.linspace(0, 1.6, 12), np.linspace(0, 2 * np.pi, 40))
    ax3d.plot_surface(r * np.cos(t), r * np.sin(t), r - 1.0, alpha=0.15, color=PALETTE["orange"])
    c = accessible_circle(200)
    ax3d.plot(c[:, 0], c[:, 1], c[:, 2], color="k", lw=2, label="accessible manifold")
    pts = sample_accessible_manifold(circle_constraints, n=n, rng=rng)
    ax3d.scatter(pts[:, 0], pts[:, 1], pts[:, 2], color=PALETTE["vermillion"], s=12, label="projected samples")
    ax3d.set_xlabel("x")
    ax3d.set_ylabel("y")
    ax3d.set_zlabel("z")
    return pts


# ====================================================================== scenes of chapter 2
class _ChainScene(Scene):
    """A chain on one square axes; subclasses set ``lim`` and create the chain's artists."""

    figsize: ClassVar[tuple[float, float]] = (5.5, 4.5)
    lim: float                       # half-width of the square axes, set by each scene
    naive: Callable[..., None]       # the clear-and-replot drawing of the scene's values

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, ax = new_figure(figsize=self.figsize)
        self.ax = ax
        return fig, [ax]

    @override
    def decorate(self) -> None:
        square_axes(self.ax, self.lim)

    @override
    def replot(self, **values: Any) -> None:
        """Naive baseline: clear and plot the chain from scratch (see :func:`draw_chain_naive`)."""
        self.ax.clear()
        square_axes(self.ax, self.lim)
        self.naive(**values)


class ArmScene(_ChainScene):
    """A fixed-base arm (figs. 2.2-2.4, 2.10): frames, joint dots, the end effector's velocity.

    Options: ``joints`` ("R"/"P" letters), ``lengths``, ``offsets``, ``names`` (one joint value
    name per joint; ``name + "_dot"`` is its rate), ``frames_shown``, ``lim``. Values: the joint
    values and rates by name.
    """

    def __init__(self, joints: JointsLike = "R", lengths: ArrayLike = (1.0,), offsets: ArrayLike | None = None,
                 names: Sequence[str] = ("alpha",), frames_shown: Sequence[str] = ("f", "h"), lim: float = 1.4,
                 **options: Any) -> None:
        self.chain = C.Chain(joints, lengths, offsets=offsets)
        self.names, self.frames_shown, self.lim = tuple(names), tuple(frames_shown), float(lim)
        super().__init__(**options)

    @override
    def create(self) -> None:
        ax = self.ax
        self.art = ChainArtist(ax, self.chain.n_links, frames_shown=self.frames_shown, pivot=True,
                               lengths=self.chain.lengths, offsets=self.chain.offsets)
        (self.sleeves,) = ax.plot([], [], "--", color="0.3", lw=2, zorder=1)
        self.vel = ArrowsArtist(ax, 1, label="end-effector velocity")
        self.text = readout(ax, 0.02, 0.02)

    def compute(self, **values: float) -> tuple[dict[str, FloatArray], FloatArray, FloatArray]:
        """Frames, end-effector world velocity and Jacobian for the joint values and rates."""
        q = np.array([values[n] for n in self.names])
        qd = np.array([values[n + "_dot"] for n in self.names])
        fr = self.chain.frames(q)
        J = self.chain.jacobians(q, method="body")["h"][-1]
        return fr, J @ qd, J

    @override
    def set(self, **values: float) -> None:
        fr, v, J = self.compute(**values)
        self.art.set(fr)
        self.vel.set(fr["h"][-1, :2], v[:2])
        ends: list[ArrayLike] = []    # the slide of each prismatic joint, NaN-separated
        for i, jt in enumerate(self.chain.joints):
            if jt.kind == "prismatic" and i > 0:
                ends += [fr["h"][i - 1, :2], fr["f"][i, :2], [np.nan, np.nan]]
        pts = np.array(ends).reshape(-1, 2)
        self.sleeves.set_data(pts[:, 0], pts[:, 1])
        self.text.set_text("end effector h: ẋ=%+.2f ẏ=%+.2f dθ/dt=%+.2f" % tuple(v))

    def naive(self, **values: float) -> None:
        fr, v, _ = self.compute(**values)
        draw_chain_naive(self.ax, fr, frames_shown=self.frames_shown)
        self.ax.quiver([fr["h"][-1, 0]], [fr["h"][-1, 1]], [v[0]], [v[1]], angles="xy", scale_units="xy", scale=1)


class OffsetRPArmScene(ArmScene):
    """The offset rotary-prismatic arm (fig. 2.10, exercise 2.2), also checked by its closed form."""

    @override
    def compute(self, **values: float) -> tuple[dict[str, FloatArray], FloatArray, FloatArray]:
        fr, v, J = super().compute(**values)
        q = np.array([values[n] for n in self.names])
        qd = np.array([values[n + "_dot"] for n in self.names])
        l1, l2 = self.chain.lengths[0], self.chain.lengths[1]
        Jb = rp_arm_body_jacobians(q[0], q[1], l1, l2, offset=self.chain.offsets[0])["h2"]
        self.closed_form = SE2.body_to_world(fr["h"][-1], Jb @ qd)
        return fr, v, J


class MobileChainScene(_ChainScene):
    """A free-floating chain (figs. 2.5, 2.6, 2.8): the base link's medial frame at (x, y, theta),
    joint angles alpha1..., a chosen base link, and for three links an even/odd shape symmetry.
    """

    def __init__(self, lengths: Iterable[float] = (1.0, 1.0, 1.0), **options: Any) -> None:
        self.lengths = tuple(lengths)
        self.n = len(self.lengths)
        self.chains = [C.MobileChain(self.lengths, base_link=b) for b in range(self.n)]
        self.lim = 0.75 * sum(self.lengths) + 0.5
        super().__init__(**options)

    @override
    def create(self) -> None:
        self.art = ChainArtist(self.ax, self.n, frames_shown=("f", "g", "h"), frame_length=0.25)
        self.body = FrameArtist(self.ax, length=0.5, colors=("darkred", "darkgreen"), zorder=7)

    def shape(self, values: Mapping[str, float | str]) -> FloatArray:
        """The joint angles after applying the symmetry choice: ``(n - 1,)``."""
        a = np.array([values[f"alpha{j + 1}"] for j in range(self.n - 1)], dtype=float)
        mode = values.get("shape", "free")
        if mode == "even":
            a[1] = a[0]
        elif mode == "odd":
            a[1] = -a[0]
        return a

    def compute(self, **values: float | str) -> tuple[dict[str, FloatArray], FloatArray, int]:
        g = np.array([values["x"], values["y"], values["theta"]])
        b = int(values["base_link"])
        return self.chains[b].frames(self.shape(values), g), g, b

    @override
    def set(self, **values: float | str) -> None:
        fr, g, b = self.compute(**values)
        self.art.set(fr)
        self.art.set_base_link(b)
        self.body.set(g)
        show = bool(values.get("all_frames", False))
        for k in ("f", "h"):
            for fa in self.art.frames[k]:
                fa.quiver.set_visible(show)

    def naive(self, **values: float | str) -> None:
        fr, g, b = self.compute(**values)
        draw_chain_naive(self.ax, fr, frames_shown=("g",))


class ThreeLinkScene(_ChainScene):
    """Three links, middle link at the identity and drawn as the base (the convention of (2.57))."""

    def __init__(self, lengths: Iterable[float] = (1.0, 1.0, 1.0), **options: Any) -> None:
        self.lengths = tuple(lengths)
        self.chain = three_link_chain(self.lengths)
        self.lim = 0.75 * sum(self.lengths)
        super().__init__(**options)

    @override
    def create(self) -> None:
        self.art = ChainArtist(self.ax, 3, frames_shown=("g",), frame_length=0.25, base_link=1)


class BetaFrameScene(ThreeLinkScene):
    """A body frame g = g_2 beta placed by values (fig. 2.7) or at the centre of mass (fig. 2.9)."""

    @override
    def create(self) -> None:
        super().create()
        self.beta_art = FrameArtist(self.ax, length=0.5, colors=("k", PALETTE["sky"]), zorder=8)
        (self.link_line,) = self.ax.plot([], [], ":", color="k", lw=1.5)
        (self.centres,) = self.ax.plot([], [], "s", color="k", ms=4)

    def compute(self, **values: float | str) -> tuple[dict[str, FloatArray], FloatArray]:
        a = np.array([values["alpha1"], values["alpha2"]])
        fr = self.chain.frames(a)
        if values["frame"] == "centre of mass":
            beta, _ = com_frame(a, self.lengths)
        else:
            beta = np.array([values["beta_x"], values["beta_y"], values["beta_theta"]])
        return fr, beta

    @override
    def set(self, **values: float | str) -> None:
        fr, beta = self.compute(**values)
        self.art.set(fr)
        g = SE2.compose(fr["g"][1], beta)  # middle link at e here, so g = beta (2.14)
        self.beta_art.set(g)
        self.link_line.set_data([fr["g"][1, 0], g[0]], [fr["g"][1, 1], g[1]])
        self.centres.set_data(fr["g"][:, 0], fr["g"][:, 1])

    def naive(self, **values: float | str) -> None:
        fr, beta = self.compute(**values)
        draw_chain_naive(self.ax, fr)
        draw_chain_naive(self.ax, {"f": beta[None], "g": beta[None], "h": beta[None]}, width=0.0)


class ThreeLinkVelocityScene(ThreeLinkScene):
    """Body velocities of the three links from (xi, alpha_dot) through the corrected (2.57)-(2.59)."""

    @override
    def create(self) -> None:
        super().create()
        self.arrows = ArrowsArtist(self.ax, 3, color=PALETTE["purple"], scale=0.5, label="link velocity (x 0.5)")
        self.text = readout(self.ax, 0.02, 0.02)

    def compute(self, **values: float) -> tuple[dict[str, FloatArray], FloatArray, FloatArray]:
        """Frames (middle link at e), link body velocities ``(3, 3)`` and their world velocities ``(3, 3)``."""
        a = np.array([values["alpha1"], values["alpha2"]])
        u = np.array([values[k] for k in ("xi_x", "xi_y", "xi_theta", "alpha1_dot", "alpha2_dot")])
        fr = self.chain.frames(a)
        xis = np.stack([J @ u for J in three_link_jacobians(a, self.lengths)])
        return fr, xis, SE2.body_to_world(fr["g"], xis)

    @override
    def set(self, **values: float) -> None:
        fr, xis, world = self.compute(**values)
        self.art.set(fr)
        self.arrows.set(fr["g"][:, :2], world[:, :2])
        self.text.set_text("\n".join(f"ξ{i + 1} = ({x[0]:+.2f}, {x[1]:+.2f}, {x[2]:+.2f})" for i, x in enumerate(xis)))

    def naive(self, **values: float) -> None:
        fr, xis, world = self.compute(**values)
        draw_chain_naive(self.ax, fr)
        self.ax.quiver(fr["g"][:, 0], fr["g"][:, 1], world[:, 0], world[:, 1], angles="xy", scale_units="xy",
                       scale=2.0)


class JacobianMethodsScene(_ChainScene):
    """The end-effector velocity by the three Jacobian methods of section 2.5, side by side."""

    COLORS: ClassVar[dict[str, str]] = {"direct": PALETTE["blue"], "world": PALETTE["orange"],
                                        "body": PALETTE["purple"]}
    figsize = (6, 4.5)

    def __init__(self, joints: JointsLike = "RPR", lengths: ArrayLike = (1.0, 0.5, 0.7), **options: Any) -> None:
        self.chain = C.Chain(joints, lengths)
        self.lim = float(self.chain.lengths.sum() + 1.2)
        self._at: tuple[float, ...] | None = None
        self._fr: dict[str, FloatArray]          # frames and Jacobians at the joint values self._at
        self._J: dict[str, FloatArray]
        super().__init__(**options)

    @override
    def create(self) -> None:
        ax = self.ax
        self.art = ChainArtist(ax, self.chain.n_joints, frames_shown=("h",), pivot=True, frame_length=0.25)
        widths = {"direct": 0.016, "world": 0.010, "body": 0.005}
        self.arrows = {m: ArrowsArtist(ax, 1, color=self.COLORS[m], width=widths[m], label=m) for m in C.METHODS}
        ax.legend(loc="upper right")
        self.text = readout(ax, 0.02, 0.02)
        self._at = None

    def compute(self, **values: float) -> tuple[dict[str, FloatArray], dict[str, FloatArray]]:
        n = self.chain.n_joints
        q = np.array([values[f"q{i + 1}"] for i in range(n)])
        qd = np.array([values[f"q{i + 1}_dot"] for i in range(n)])
        key = tuple(q)
        if self._at != key:  # frames and Jacobians depend on q only: a rate change reuses them
            self._fr = self.chain.frames(q)
            self._J = {m: self.chain.jacobians(q, method=m)["h"][-1] for m in C.METHODS}
            self._at = key
        return self._fr, {m: J @ qd for m, J in self._J.items()}

    @override
    def set(self, **values: float) -> None:
        fr, v = self.compute(**values)
        self.art.set(fr)
        p = fr["h"][-1, :2]
        for m, a in self.arrows.items():
            a.set(p, v[m][:2])
        self.spread = max(np.abs(v[m] - v["direct"]).max() for m in C.METHODS)
        lines = ["method      ẋ        ẏ    dθ/dt"]
        lines += [f"{m:7s} {v[m][0]:+8.4f} {v[m][1]:+8.4f} {v[m][2]:+8.4f}" for m in C.METHODS]
        lines.append(f"largest disagreement {self.spread:.1e}")
        self.text.set_text("\n".join(lines))

    def naive(self, **values: float) -> None:
        fr, v = self.compute(**values)
        draw_chain_naive(self.ax, fr, frames_shown=("h",))
        p = fr["h"][-1]
        for m in C.METHODS:
            self.ax.quiver([p[0]], [p[1]], [v[m][0]], [v[m][1]], color=self.COLORS[m], angles="xy",
                           scale_units="xy", scale=1)

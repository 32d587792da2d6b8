"""Lie groups and SE(2) (book sections 1.2-1.3): the slide rule,
the circle vs SO(2), left and right actions, repeated steps, points on a rigid body, and the
scale-shift group's actions on its half-plane.

The group axioms ("group or not?") are drawn by :mod:`.group_or_not`.
"""
from __future__ import annotations

from typing import Any, ClassVar, TypedDict

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.lines import Line2D
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.drawing.toolkit.axes import plane
from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist
from gm_core.drawing.toolkit.style import MATH_PT, PALETTE, ArrowSet, PathText, Scene, arrow, set_arrows, title
from gm_core.groups import S1, SE2, R2xS1, ScaleShift
from gm_core.groups.axioms import powers
from gm_core.groups.base import TWO_PI
from gm_core.validation import FloatArray

__all__ = ["BODY", "SlideRuleScene", "CircleIsoScene",
           "LeftRightActionScene", "ForwardLeftScene", "BodyPointsScene", "ScaleShiftActionScene"]

BODY = BodyArtist.triangle(0.35)


#: the axioms' figure is now the "group or not?" table (the residual bar chart it replaced
#: showed only that round-off is small); kept under its old name


class SlideRuleScene(Scene):
    """A slide rule: (R+, x) multiplication done as (R, +) addition of logarithms, (1.xii).

    Values ``a`` and ``b`` in [1, 10]. The sliding C scale is shifted by log10(a); the cursor at
    log10(a) + log10(b) reads a*b on the fixed D scale (which runs over two decades, 1-100).
    """

    FIGSIZE = (8, 2.0)      # no empty band above the readout
    MARGINS = dict(left=0.02, right=0.98, bottom=0.03, top=0.97)
    #: the cursor hairline crosses both scales' ticks and reaches down to the arrows, with a gap
    #: (the NaN) around the D labels' row, so it points at the reading and crosses no label; it
    #: stops below the C labels (their baseline is 0.35)
    CURSOR_Y: ClassVar[FloatArray] = np.array([0.3, -0.32, np.nan, -0.58, -0.8])

    @staticmethod
    def _ticks(decades: int, y0: float, up: bool) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        vals = np.concatenate([np.arange(1, 10, 0.5) * 10 ** d for d in range(decades)] + [[10 ** decades]])
        x = np.log10(vals)
        major = np.isclose(vals / 10 ** np.floor(np.log10(vals) + 1e-12), np.round(vals / 10 ** np.floor(
            np.log10(vals) + 1e-12)))
        length = np.where(major, 0.25, 0.12) * (1 if up else -1)
        segs = np.stack([np.stack([x, np.full_like(x, y0)], -1), np.stack([x, y0 + length], -1)], 1)
        return vals, x, segs, major

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        ax.set_xlim(-0.08, 2.05)  # room for the scale letter "D" left of 1
        ax.set_ylim(-1.0, 0.95)
        ax.axis("off")
        vals, x, segs, major = self._ticks(2, 0.0, False)
        ax.add_collection(LineCollection(segs, colors="k", linewidths=1))  # type: ignore[arg-type]  # array, see set
        for v, xx, m in zip(vals, x, major):
            if m and v not in (70, 90):     # 70 and 90 would crowd their neighbours
                PathText(ax, xx, -0.45, f"{v:g}", size=7.5, ha="center")
        PathText(ax, -0.03, -0.3, "D", size=9, weight="bold", ha="right")
        ax.plot([0, 2], [0, 0], "k", lw=1)
        vals, x, segs, major = self._ticks(1, 0.0, True)
        self._c_vals, self._c_x, self._c_segs, self._c_major = vals, x, segs, major

    @override
    def create(self) -> None:
        (ax,) = self.axes
        self.slide = LineCollection(self._c_segs, colors=PALETTE["blue"], linewidths=1)  # type: ignore[arg-type]
        ax.add_collection(self.slide)
        self.c_labels = [PathText(ax, x, 0.35, f"{v:g}", size=7, ha="center", color=PALETTE["blue"])
                         for v, x, m in zip(self._c_vals, self._c_x, self._c_major) if m]
        self._c_label_x = np.array([x for x, m in zip(self._c_x, self._c_major) if m])
        (self.slide_edge,) = ax.plot([0, 1], [0.02, 0.02], color=PALETTE["blue"], lw=2)
        (self.cursor,) = ax.plot([0] * len(self.CURSOR_Y), self.CURSOR_Y, color=PALETTE["vermillion"], lw=1.5)
        self.add_a = arrow(ax, color=PALETTE["orange"], width=0.006)
        self.add_b = arrow(ax, color=PALETTE["green"], width=0.006)
        self.readout = PathText(ax, 1.0, 0.75, "", size=9, ha="center")

    @override
    def set(self, a: float = 2.0, b: float = 3.0) -> None:
        la, lb = np.log10(a), np.log10(b)
        segs = self._c_segs.copy()
        segs[..., 0] += la
        # segments as one (n, 2, 2) array, which matplotlib takes, not the Sequence its stub names
        self.slide.set_segments(segs)  # type: ignore[arg-type]
        for t, x in zip(self.c_labels, self._c_label_x):
            t.set_position((x + la, 0.35))
        self.slide_edge.set_data([la, la + 1], [0.02, 0.02])
        self.cursor_x = la + lb
        self.cursor.set_data(np.full(len(self.CURSOR_Y), self.cursor_x), self.CURSOR_Y)
        set_arrows(self.add_a, [0, -0.85], [la, 0])
        set_arrows(self.add_b, [la, -0.85], [lb, 0])
        self.reading = 10 ** self.cursor_x
        self.readout.set_text(f"log a + log b = {la:.3f} + {lb:.3f} = {la + lb:.3f}   →   "
                              f"read on D: {self.reading:.3f} = a × b = {a * b:.3f}")


class CircleIsoScene(Scene):
    """(S^1, + mod 1) vs SO(2): adding cycles on the circle = multiplying rotation matrices, (1.xvi).

    Values ``a1``, ``a2`` in cycles [0, 1). Each point (left) and arrow tip (right) carries its
    name just outside the circle; names whose points are close are moved apart along the circle
    (:meth:`place_names`), and the two captions sit below every name, so no text covers another
    whatever the sliders say.
    """

    G: ClassVar[S1] = S1(1.0)

    FIGSIZE = (7.6, 3.6)
    NCOLS = 2
    MARGINS = dict(left=0.01, right=0.99, bottom=0.02, top=0.9, wspace=0.04)
    #: the names keep this far from the centre (data units; the circle has radius 1)
    NAME_RADIUS: ClassVar[float] = 1.1
    #: the captions' top edge and the axes' limits: below the lowest a name can reach
    CAPTION_Y: ClassVar[float] = -1.42
    YLIM: ClassVar[tuple[float, float]] = (-1.72, 1.45)

    @override
    def decorate(self) -> None:
        t = np.linspace(0, TWO_PI, 120)
        for ax in self.axes:
            ax.plot(np.cos(t), np.sin(t), color="0.7")
            ax.set_xlim(-1.75, 1.75)
            ax.set_ylim(*self.YLIM)
            ax.set_aspect("equal")
            ax.axis("off")
        title(self.axes[0], r"circle $(\mathbb{S}^1$, + mod 1): add cycles", size=MATH_PT)
        title(self.axes[1], r"SO(2): multiply matrices, act on $e_1$", size=MATH_PT)

    @override
    def create(self) -> None:
        ax_s, ax_r = self.axes
        self.pts = ax_s.scatter([0, 0, 0], [0, 0, 0], c=[PALETTE["blue"], PALETTE["orange"], PALETTE["vermillion"]],
                                s=[50, 50, 90],
                                zorder=5)
        self.vecs = ArrowSet(ax_r, color=[PALETTE["blue"], PALETTE["orange"], PALETTE["vermillion"]], n=3, width=0.012)
        self.check = ArrowSet(ax_r, color="k", width=0.005)
        self.readout = PathText(ax_s, 0, self.CAPTION_Y, "", size=9, ha="center", va="top")
        self.r_readout = PathText(ax_r, 0, self.CAPTION_Y, "", size=MATH_PT, ha="center", va="top")
        # a key on the picture: each point (left) and arrow tip (right) carries its name
        colors = (PALETTE["blue"], PALETTE["orange"], PALETTE["vermillion"])
        names = (r"$a_1$", r"$a_2$", r"$a_1 \oplus a_2$")
        self.names = [[PathText(ax, 0, 0, n, size=MATH_PT, color=c, ha="center", va="center")
                       for n, c in zip(names, colors)] for ax in (ax_s, ax_r)]
        # each name's box about its anchor, in data units (its glyphs are fixed; so is the layout)
        self._name_boxes = [self._data_box(name) for name in self.names[0]]

    def _data_box(self, name: PathText) -> FloatArray:
        """(x0, y0, x1, y1) of ``name``'s glyphs about its anchor, in data units of its axes."""
        ax = name.ax
        pos = ax.get_position(original=True)
        w_in, h_in = pos.width * self.fig.get_figwidth(), pos.height * self.fig.get_figheight()
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        per_unit = min(w_in / (x1 - x0), h_in / (y1 - y0))    # inches per data unit (equal aspect)
        pts = np.concatenate([p.vertices for p in name.collection.get_paths()])
        return np.concatenate([pts.min(0), pts.max(0)]) / per_unit

    @classmethod
    def place_names(cls, angles: ArrayLike, boxes: ArrayLike, step: float = 0.08,
                    pad: float = 0.04) -> FloatArray:
        """Anchors (n, 2) for names of the points at ``angles`` (radians) on the unit circle.

        ``boxes`` (n, 4) are the names' (x0, y0, x1, y1) about their anchors. Each name lies just
        outside :attr:`NAME_RADIUS` in its point's direction; a name that would touch one placed
        before it moves along the circle, ``step`` radians at a time, the nearer way first."""
        boxes = np.asarray(boxes, float)
        placed: list[FloatArray] = []
        out = np.zeros((len(boxes), 2))
        for k, (a, box) in enumerate(zip(np.asarray(angles, float), boxes)):
            corners = np.array([[box[0], box[1]], [box[0], box[3]], [box[2], box[1]], [box[2], box[3]]])
            for j in range(80):
                shift = step * ((j + 1) // 2) * (1 if j % 2 else -1)
                u = np.array([np.cos(a + shift), np.sin(a + shift)])
                centre = (cls.NAME_RADIUS + np.max(-corners @ u)) * u   # whole box outside the radius
                mine = np.concatenate([centre, centre]) + box
                if all(mine[0] >= q[2] + pad or q[0] >= mine[2] + pad or mine[1] >= q[3] + pad
                       or q[1] >= mine[3] + pad for q in placed):
                    break
            placed.append(mine)
            out[k] = centre
        return out

    @override
    def set(self, a1: float = 0.2, a2: float = 0.35) -> None:
        G = self.G
        g1, g2 = np.array([a1]), np.array([a2])
        s = G.compose(g1, g2)
        ang = TWO_PI * np.array([a1, a2, s[0]])
        self.pts.set_offsets(np.stack([np.cos(ang), np.sin(ang)], -1))
        M = G.matrix(g1) @ G.matrix(g2)
        e1 = np.array([1.0, 0.0])
        v = np.stack([G.matrix(g1) @ e1, G.matrix(g2) @ e1, M @ e1])
        set_arrows(self.vecs, np.zeros((3, 2)), v)
        self.product_matrix = M
        self.sum_matrix = G.matrix(s)
        set_arrows(self.check, [0, 0], self.sum_matrix @ e1 * 0.6)
        self.mismatch = float(np.max(np.abs(M - self.sum_matrix)))
        self.readout.set_text(f"{a1:.2f} + {a2:.2f} mod 1 = {s[0]:.2f} cycles")
        self.r_readout.set_text(r"$\max\,|R(a_1)R(a_2) - R(a_1 \oplus a_2)|$" + f" = {self.mismatch:.1e}")
        anchors = self.place_names(ang, self._name_boxes)
        for labels in self.names:
            for lab, xy in zip(labels, anchors):
                lab.set_position(xy)


# ================================================================================ 1.3 SE(2)
class _ActionNames(TypedDict):
    """The names following the bodies of a :class:`LeftRightActionScene` (g on both axes)."""

    g: list[PathText]
    hg: PathText
    h: PathText
    gh: PathText


class LeftRightActionScene(Scene):
    """Figs. 1.8-1.9: a body at g, moved by the left action (h g) and by the right action (g h).

    Values ``x, y, theta`` (g) and ``u, v, beta`` (h).
    """

    LIM: ClassVar[float] = 4.0

    FIGSIZE = (9, 4.3)
    NCOLS = 2
    MARGINS = dict(left=0.05, right=0.99, bottom=0.1, top=0.88, wspace=0.15)

    @override
    def decorate(self) -> None:
        for ax in self.axes:
            plane(ax, self.LIM)
            FrameArtist(ax, (0, 0, 0), length=0.6, colors=("0.55", "0.55"), zorder=2)
        title(self.axes[0], "left action: hg (fig. 1.8)")
        title(self.axes[1], "right action: gh (fig. 1.9)")

    @override
    def create(self) -> None:
        ax_l, ax_r = self.axes
        self.g_body = [BodyArtist(ax, BODY, facecolor="0.6") for ax in self.axes]
        self.g_frame = [FrameArtist(ax, length=0.5) for ax in self.axes]
        self.hg_body = BodyArtist(ax_l, BODY, facecolor=PALETTE["blue"])
        self.hg_frame = FrameArtist(ax_l, length=0.5)
        self.gh_body = BodyArtist(ax_r, BODY, facecolor=PALETTE["orange"])
        self.gh_frame = FrameArtist(ax_r, length=0.5)
        # left action = rotate about the world origin by beta, then translate by (u, v)
        (self.arc,) = ax_l.plot([], [], color=PALETTE["blue"], ls=":", lw=1.5)
        self.shift = ArrowSet(ax_l, color=PALETTE["blue"], width=0.006)
        # h drawn in the world frame (left) and in g's frame (right)
        self.h_frame_l = FrameArtist(ax_l, length=0.35, colors=("0.3", "0.3"), zorder=3)
        (self.h_in_g,) = ax_r.plot([], [], color=PALETTE["orange"], ls="--", lw=1.2)
        (self.h_in_g_corner,) = ax_r.plot([], [], color=PALETTE["orange"], ls=":", lw=1.0)
        self.l_text = PathText(ax_l, 0.02, 0.03, "", size=7.5, va="bottom", coords="axes")
        self.r_text = PathText(ax_r, 0.02, 0.03, "", size=7.5, va="bottom", coords="axes")
        # the key: each body and the frame h carry their name, following them
        label: dict[str, Any] = dict(size=9, weight="bold", ha="left", va="bottom", offset=(5.0, 5.0))  # PathText's
        self.names: _ActionNames = {"g": [PathText(ax, 0, 0, "g", color="0.35", **label) for ax in self.axes],
                      "hg": PathText(ax_l, 0, 0, "hg", color=PALETTE["blue"], **label),
                      "h": PathText(ax_l, 0, 0, "h", color="0.2", **label),
                      "gh": PathText(ax_r, 0, 0, "gh", color=PALETTE["orange"], **label)}
        for name in [*self.names["g"], self.names["hg"], self.names["h"], self.names["gh"]]:
            name.collection.set_clip_on(True)     # a body near the edge never pushes its name outside

    @override
    def set(self, x: float = 1.5, y: float = 0.5, theta: float = 0.5, u: float = -1.0, v: float = 1.0,
            beta: float = 0.9) -> None:
        g = np.array([x, y, theta])
        h = np.array([u, v, beta])
        self.hg = SE2.compose(h, g)
        self.gh = SE2.compose(g, h)
        for b, f in zip(self.g_body, self.g_frame):
            b.set(g)
            f.set(g)
        self.hg_body.set(self.hg)
        self.hg_frame.set(self.hg)
        self.gh_body.set(self.gh)
        self.gh_frame.set(self.gh)
        s = np.linspace(0.0, 1.0, 40)[:, None]
        rot = SE2.act_on_points(np.concatenate([0 * s, 0 * s, beta * s], -1), g[:2])
        self.arc.set_data(rot[:, 0], rot[:, 1])
        set_arrows(self.shift, rot[-1], [u, v])
        self.h_frame_l.set(h)
        corner = SE2.act_on_points(g, np.array([u, 0.0]))
        self.h_in_g.set_data([x, self.gh[0]], [y, self.gh[1]])
        self.h_in_g_corner.set_data([x, corner[0], self.gh[0]], [y, corner[1], self.gh[1]])
        for name in self.names["g"]:
            name.set_position(g[:2])
        self.names["hg"].set_position(self.hg[:2])
        self.names["h"].set_position(h[:2])
        self.names["gh"].set_position(self.gh[:2])
        self.l_text.set_text(f"hg = ({self.hg[0]:.2f}, {self.hg[1]:.2f}, {self.hg[2]:.2f})\n"
                             "rotate g about the origin by β, then shift by (u, v)")
        self.r_text.set_text(f"gh = ({self.gh[0]:.2f}, {self.gh[1]:.2f}, {self.gh[2]:.2f})\n"
                             "step (u, v) along g's own axes, then turn by β")




class ForwardLeftScene(Scene):
    """Fig. 1.10: repeat the step g in (R^2 x S^1, +) and in SE(2); values ``x, y, theta, n``.

    Each step's displacement, read in the body frame it starts from, is printed: constant in
    SE(2) ("forward and to the left" for g = (1, 1, pi/2)), changing in (R^2 x S^1, +).

    Both axes show the same square window, the smallest of :attr:`ZOOMS` that holds every pose
    of both paths with their bodies (n long steps in (R^2 x S^1, +) reach 8 times as far as one);
    the grid spacing and the drawn bodies grow with the window, so they look the same size.
    """

    N_MAX: ClassVar[int] = 8
    LIM: ClassVar[float] = 4.5
    #: half-widths of the window, multiples of LIM: the panel's farthest pose (eight steps of
    #: (-2, -2, -0.17) in SE(2)) is 20.6 from the origin along an axis
    ZOOMS: ClassVar[tuple[float, ...]] = (4.5, 9.0, 13.5, 18.0, 22.5, 27.0)

    FIGSIZE = (9, 4.4)
    NCOLS = 2
    MARGINS = dict(left=0.05, right=0.99, bottom=0.1, top=0.88, wspace=0.15)

    @override
    def decorate(self) -> None:
        for ax in self.axes:
            plane(ax, self.LIM, grid=False)
        title(self.axes[0], r"$(\mathbb{R}^2 \times \mathbb{S}^1, +)$:  g + g + …", size=MATH_PT)
        title(self.axes[1], "SE(2):  g ∘ g ∘ …", size=MATH_PT)

    @override
    def create(self) -> None:
        self.bodies: list[PolyCollection] = []
        self.frames: list[LineCollection] = []
        self.steps: list[LineCollection] = []
        self.texts: list[PathText] = []
        self.grids: list[LineCollection] = []
        for ax, color in zip(self.axes, (PALETTE["purple"], PALETTE["blue"])):
            grid = LineCollection([], linewidths=0.7, zorder=0)
            bodies = PolyCollection([], facecolors=color, edgecolors="k", alpha=0.4, linewidths=0.8)
            frames = LineCollection([], linewidths=1.8, zorder=4)
            steps = LineCollection([], colors=color, linewidths=1.2, linestyles="--")
            for c in (grid, bodies, frames, steps):
                ax.add_collection(c)
            self.grids.append(grid)
            self.bodies.append(bodies)
            self.frames.append(frames)
            self.steps.append(steps)
            self.texts.append(PathText(ax, 0.02, 0.03, "", size=7.5, va="bottom", coords="axes"))
        self.lim = 0.0
        self.scale = 1.0

    def _zoom(self, lim: float) -> None:
        """Show the window [-lim, lim]^2 on both axes, with a grid line every lim / 4.5 units."""
        if lim == self.lim:
            return
        self.lim, self.scale = lim, lim / self.LIM
        k = np.arange(-np.floor(self.LIM), np.floor(self.LIM) + 1) * self.scale
        segs = [[(v, -lim), (v, lim)] for v in k] + [[(-lim, v), (lim, v)] for v in k]
        colors = ["0.6" if v == 0 else "0.88" for v in k] * 2
        for ax, grid in zip(self.axes, self.grids):
            ax.set_xlim(-lim, lim)
            ax.set_ylim(-lim, lim)
            grid.set_segments(segs)
            grid.set_color(colors)

    @staticmethod
    def body_displacements(poses: FloatArray) -> FloatArray:
        """Displacement of each step, written in the body frame it starts from: (k, 2)."""
        d = poses[1:, :2] - poses[:-1, :2]
        t = poses[:-1, 2]
        c, s = np.cos(t), np.sin(t)
        return np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]], -1)

    @staticmethod
    def describe(d: FloatArray) -> str:
        fwd = "forward" if d[0] > 1e-9 else ("backward" if d[0] < -1e-9 else "")
        side = "to the left" if d[1] > 1e-9 else ("to the right" if d[1] < -1e-9 else "")
        return " and ".join(w for w in (fwd, side) if w) or "no move"

    @override
    def set(self, x: float = 1.0, y: float = 1.0, theta: float = np.pi / 2, n: float = 2) -> None:
        n = int(n)
        g = np.array([x, y, theta])
        self.poses = [powers(R2xS1, g, n), powers(SE2, g, n)]
        reach = max(float(np.abs(P[:, :2]).max()) for P in self.poses)
        # the smallest window holding every pose with its body and frame (0.4 x scale) and a margin
        self._zoom(next((z for z in self.ZOOMS if reach + 0.6 * z / self.LIM <= z), self.ZOOMS[-1]))
        body = BODY * self.scale
        axes = np.array([[0.4, 0.0], [0.0, 0.4]]) * self.scale
        for k in range(2):
            P = self.poses[k]
            # (n, k, 2) arrays, not the Sequences of matplotlib's stubs (set_verts' fast path)
            self.bodies[k].set_verts(SE2.act_on_points(P[:, None, :], body))  # type: ignore[arg-type]
            origin = P[:, :2]
            tips = SE2.act_on_points(P[:, None, :], axes)
            self.frames[k].set_segments(np.concatenate([np.stack([origin, tips[:, 0]], 1),  # type: ignore[arg-type]
                                                        np.stack([origin, tips[:, 1]], 1)]))
            self.frames[k].set_color([PALETTE["vermillion"]] * (n + 1) + [PALETTE["green"]] * (n + 1))
            self.steps[k].set_segments(np.stack([P[:-1, :2], P[1:, :2]], 1))  # type: ignore[arg-type]
            d = self.body_displacements(P)
            lines = [f"step {j + 1}: ({d[j, 0]:+.2f}, {d[j, 1]:+.2f}) {self.describe(d[j])}"
                     for j in range(min(n, 4))]
            if n > 4:
                lines.append("...")
            self.texts[k].set_text("in the body frame:\n" + "\n".join(lines))
            self._place_text(self.texts[k], P)

    def _place_text(self, text: PathText, poses: FloatArray) -> None:
        """The readout in the lower left corner, or in the upper left one when fewer of the
        bodies lie under it there: the words never hide the path they describe."""
        ax = text.ax
        box = text.get_window_extent().transformed(ax.transAxes.inverted())
        w, h = box.width + 0.02, box.height + 0.02
        at = (poses[:, :2] + self.lim) / (2 * self.lim)                 # axes fractions
        near = 0.6 * self.scale / (2 * self.lim)                           # a body's reach
        left = at[:, 0] < 0.02 + w + near
        low = int(np.sum(left & (at[:, 1] < 0.03 + h + near)))
        high = int(np.sum(left & (at[:, 1] > 0.97 - h - near)))
        if high < low:
            text.set_alignment(va="top")
            text.set_position((0.02, 0.97))
        else:
            text.set_alignment(va="bottom")
            text.set_position((0.02, 0.03))


class BodyPointsScene(Scene):
    """(1.11)-(1.12): a point fixed in the body, carried to the world by g; values ``x, y, theta, px, py``."""

    OUTLINE: ClassVar[FloatArray] = BodyArtist.rectangle(1.6, 0.8)

    FIGSIZE = (5, 4.4)
    MARGINS = dict(left=0.1, right=0.98, bottom=0.1, top=0.9)

    @override
    def decorate(self) -> None:
        (ax,) = self.axes
        plane(ax, 3.0)
        FrameArtist(ax, (0, 0, 0), length=0.6, colors=("0.55", "0.55"), zorder=2)

    @override
    def create(self) -> None:
        (ax,) = self.axes
        self.body = BodyArtist(ax, self.OUTLINE, facecolor=PALETTE["blue"], alpha=0.3)
        self.frame = FrameArtist(ax, length=0.6)
        (self.legs,) = ax.plot([], [], color=PALETTE["blue"], ls="--", lw=1)
        (self.point,) = ax.plot([], [], "o", color=PALETTE["vermillion"], ms=7, zorder=7)
        self.text = title(ax, size=8)

    @override
    def set(self, x: float = 0.5, y: float = 0.3, theta: float = 0.6, px: float = 0.6, py: float = 0.3) -> None:
        g = np.array([x, y, theta])
        pb = np.array([px, py])
        self.body.set(g)
        self.frame.set(g)
        self.world = SE2.act_on_points(g, pb)
        via_matrix = (SE2.matrix(g) @ np.array([px, py, 1.0]))[:2]
        self.matrix_mismatch = float(np.max(np.abs(via_matrix - self.world)))
        corner = SE2.act_on_points(g, np.array([px, 0.0]))
        self.legs.set_data([x, corner[0], self.world[0]], [y, corner[1], self.world[1]])
        self.point.set_data([self.world[0]], [self.world[1]])
        self.text.set_text(f"body point ({px:.2f}, {py:.2f}) → world ({self.world[0]:.2f}, "
                           f"{self.world[1]:.2f})\nmatrix (1.12) agrees to {self.matrix_mismatch:.0e}")


# ================================================================================ R+ x| R
class ScaleShiftActionScene(Scene):
    """The scale-shift group R+ x| R (semi-direct product (1.xix)) acting on its own half-plane a > 0.

    Values ``alpha``, ``beta`` (the acting element h = (alpha, beta)) and ``u``, ``v`` (an algebra
    vector xi). Each axes shows a grid of elements g = (a, b) (grey) and its image under the left
    action h o g (left axes) or the right action g o h (right axes), together with the
    one-parameter subgroup exp(t xi) through e (dashed) and its image, h o exp(t xi) or
    exp(t xi) o h: the left- or right-invariant flow through h, (1.46)-(1.47).
    """

    #: the grid of elements g that the actions move: a in A_GRID, b in B_GRID
    A_GRID: ClassVar[FloatArray] = np.array([0.5, 1.0, 1.5, 2.0])
    B_GRID: ClassVar[FloatArray] = np.array([-1.0, -0.5, 0.0, 0.5, 1.0])
    #: times of the drawn one-parameter subgroup
    T: ClassVar[FloatArray] = np.linspace(-1.5, 1.5, 61)
    #: a dot on the drawn flows every MARK_EVERY samples of T (every half unit of time)
    MARK_EVERY: ClassVar[int] = 10
    XLIM: ClassVar[tuple[float, float]] = (-0.6, 5.4)
    YLIM: ClassVar[tuple[float, float]] = (-3.1, 3.1)

    FIGSIZE = (6.6, 3.8)
    NCOLS = 2
    MARGINS = dict(left=0.02, right=0.98, bottom=0.17, top=0.92, wspace=0.06)

    @override
    def decorate(self) -> None:
        x0, x1 = self.XLIM
        y0, y1 = self.YLIM
        lines = [[(v, y0), (v, y1)] for v in range(0, int(x1) + 1)] + \
                [[(x0, v), (x1, v)] for v in range(int(np.ceil(y0)), int(y1) + 1)]
        for ax in self.axes:
            ax.set_xlim(x0, x1)
            ax.set_ylim(y0, y1)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            ax.add_collection(LineCollection(lines, colors="0.9", linewidths=0.6, zorder=0))
            ax.axvspan(x0, 0.0, color="0.85", zorder=0)            # a <= 0: no element
            ax.plot([0, 0], [y0, y1], color="0.3", lw=1.0, zorder=1)
            ax.plot([0, x1], [0, 0], color="0.6", lw=0.8, zorder=1)
            PathText(ax, x1 - 0.1, 0.12, "a", size=9, ha="right", va="bottom")
            PathText(ax, 0.12, y1 - 0.1, "b", size=9, ha="left", va="top")
            ax.plot([1.0], [0.0], "o", color="k", ms=5, zorder=6)         # the identity e = (1, 0)
        title(self.axes[0], r"left action  $g \mapsto h\circ g$", size=MATH_PT)
        title(self.axes[1], r"right action  $g \mapsto g\circ h$", size=MATH_PT)

    @override
    def create(self) -> None:
        a, b = np.meshgrid(self.A_GRID, self.B_GRID, indexing="ij")
        self.grid = np.stack([a, b], -1)                       # (n_a, n_b, 2) elements g
        self.moved: list[LineCollection] = []
        self.moved_dots: list[Line2D] = []
        self.subgroup_lines: list[Line2D] = []
        self.flows: list[Line2D] = []
        self.h_marks: list[Line2D] = []
        self.formulas: list[PathText] = []
        for ax, color in zip(self.axes, (PALETTE["left"], PALETTE["right"])):
            ax.add_collection(LineCollection(self._mesh(self.grid), colors="0.55", linewidths=0.8, zorder=2))
            ax.scatter(self.grid[..., 0].ravel(), self.grid[..., 1].ravel(), s=10, color="0.45", zorder=3)
            mesh = LineCollection([], colors=color, linewidths=1.0, zorder=4)
            ax.add_collection(mesh)
            self.moved.append(mesh)
            # one Line2D of markers (Agg stamps one marker), not a scatter (a path per dot): cheaper per move
            self.moved_dots.append(ax.plot(self.grid[..., 0].ravel(), self.grid[..., 1].ravel(), "o", ls="none",
                                           ms=np.sqrt(14), mew=1.0, color=color, zorder=5)[0])
            # a dot every half unit of t: the flows are straight rays, run at an exponential pace
            self.subgroup_lines.append(ax.plot([], [], color="k", ls="--", lw=1.2, marker="o", ms=3,
                                               markevery=self.MARK_EVERY, zorder=5)[0])
            self.flows.append(ax.plot([], [], color=color, lw=2.0, marker="o", ms=4, markevery=self.MARK_EVERY,
                                      zorder=5)[0])
            self.h_marks.append(ax.plot([], [], "*", color=PALETTE["vermillion"], ms=12, mec="k", mew=0.6,
                                        zorder=7)[0])
            self.formulas.append(PathText(ax, 0.5, 0.0, "", size=MATH_PT, ha="center", va="top", coords="axes",
                                          offset=(0, -5)))
        words = ("scale everything by α about (0, 0), then shift by β\n"
                 "dashed: exp(tξ);  thick: h∘exp(tξ);  dots every ½ in t",
                 "scale a by α, shift b by β a: a shear\n"
                 "dashed: exp(tξ);  thick: exp(tξ)∘h;  dots every ½ in t")
        for ax, text in zip(self.axes, words):
            PathText(ax, 0.5, 0.0, text, size=8, ha="center", va="top", coords="axes", offset=(0, -24))

    @staticmethod
    def _mesh(points: FloatArray) -> list[FloatArray]:
        """The grid's lines through ``points (n_a, n_b, 2)``: each row and each column as a polyline."""
        return [points[i] for i in range(points.shape[0])] + [points[:, j] for j in range(points.shape[1])]

    @override
    def set(self, alpha: float = 1.5, beta: float = 0.5, u: float = 0.6, v: float = 1.0) -> None:
        G = ScaleShift
        h = np.array([alpha, beta])
        xi = np.array([u, v])
        self.left_images = G.compose(h, self.grid)             # h o g for every g of the grid
        self.right_images = G.compose(self.grid, h)            # g o h
        self.subgroup = G.exp(self.T[:, None] * xi)
        self.left_flow = G.compose(h, self.subgroup)           # h o exp(t xi), (1.46)
        self.right_flow = G.compose(self.subgroup, h)          # exp(t xi) o h, (1.47)
        for k, (images, flow) in enumerate(((self.left_images, self.left_flow),
                                            (self.right_images, self.right_flow))):
            self.moved[k].set_segments(self._mesh(images))
            self.moved_dots[k].set_data(images[..., 0].ravel(), images[..., 1].ravel())
            self.subgroup_lines[k].set_data(self.subgroup[:, 0], self.subgroup[:, 1])
            self.flows[k].set_data(flow[:, 0], flow[:, 1])
            self.h_marks[k].set_data([alpha], [beta])
        # the numbers stand outside the $...$ spans (the sign stays in, spaced as an operator):
        # each span is laid out once (PathText's cache), not parsed by mathtext on every move
        a_, sign, b_ = f"{alpha:.2f}", "-" if beta < 0 else "+", f"{abs(beta):.2f}"
        self.formulas[0].set_text(r"$h\circ g = ($" + a_ + r"$\,a,\ $" + a_ + rf"$\,b {sign}$" + b_ + ")")
        self.formulas[1].set_text(r"$g\circ h = ($" + a_ + rf"$\,a,\ b {sign}$" + b_ + r"$\,a$" + ")")

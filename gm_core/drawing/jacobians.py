"""The end-effector Jacobian built one joint at a time (section 2.5, (2.33)-(2.37)): a step-through.

At step k only joint k moves: the links from joint k outward turn (or slide) as one rigid body
with the joint's frame f_k, so every frame on them has the velocity of that one motion, carried
out link by link by adjoints (:func:`gm_core.chains.transported_columns`). At the end effector
that velocity, times the joint rate, is column k of J q_dot; the columns found so far are laid
head to tail and their sum grows towards J q_dot (grey), reached at the last step.
"""
from __future__ import annotations

from typing import Any

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains import chain as C
from gm_core.drawing.chains import ChainArtist, JointsLike
from gm_core.drawing.holonomic import plane_and_notes
from gm_core.drawing.toolkit.axes import square_axes
from gm_core.drawing.toolkit.style import MATH_PT, PALETTE, PathText, Scene, arrow, set_arrows
from gm_core.groups import SE2
from gm_core.validation import FloatArray

__all__ = ["JacobianStepScene", "COLUMN_COLORS"]

#: One colour per joint (column of the Jacobian).
COLUMN_COLORS = (PALETTE["blue"], PALETTE["orange"], PALETTE["green"], PALETTE["vermillion"], PALETTE["purple"])

_SUB = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _fmt(v: ArrayLike) -> str:
    return "(%+.2f, %+.2f, %+.2f)" % tuple(np.asarray(v, float))


class JacobianStepScene(Scene):
    """Step k = 0..n through a fixed-base chain: joint k's velocity carried out to the tip, columns summed.

    Options: ``joints``, ``lengths`` (default the R-P-R chain of the methods panel), ``scale``
    (arrow length per unit velocity). Values: ``q1..qn``, ``q1_dot..qn_dot`` and ``step``.
    After ``set``: ``self.frames (2n, 3)``, ``self.columns (n, 3)`` (body-velocity columns of the
    end effector times the rates), ``self.partial (3,)`` (body velocity, sum of the columns up to
    the step), ``self.full (3,)`` (J q_dot by the body-iterative method of the chain).
    """

    def __init__(self, joints: JointsLike = "RPR", lengths: ArrayLike = (1.0, 0.5, 0.7), scale: float = 0.5,
                 **options: Any) -> None:
        self.chain = C.Chain(joints, lengths)
        self.n = self.chain.n_joints
        self.scale = float(scale)
        self.lim = 0.55 * float(self.chain.lengths.sum() + 1.0) + 0.9
        super().__init__(**options)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, self.ax, self.notes = plane_and_notes(figsize=(8.6, 4.2), ratio=(1, 1))
        return fig, [self.ax, self.notes]

    @override
    def decorate(self) -> None:
        square_axes(self.ax, self.lim, center=(0.4, 0.4))
        self.notes.set_axis_off()

    @override
    def create(self) -> None:
        ax, n = self.ax, self.n
        colors = [COLUMN_COLORS[j % len(COLUMN_COLORS)] for j in range(n)]
        self.colors = colors
        self.art = ChainArtist(ax, n, width=0.1, frames_shown=(), pivot=True,
                               colors=["0.7"] * n)
        self.target = arrow(ax, color="0.8", width=0.02, zorder=3, minlength=0)
        self.carried = arrow(ax, color=colors[0], width=0.007, zorder=6, n=2 * n, minlength=0)
        self.steps = arrow(ax, color=colors, width=0.01, zorder=8, n=n, minlength=0)
        self.total = arrow(ax, color="k", width=0.005, zorder=9, minlength=0)
        (self.ring,) = ax.plot([], [], "o", ms=18, mfc="none", mew=2.5, zorder=7)
        (self.sleeves,) = ax.plot([], [], "--", color="0.3", lw=2, zorder=1)   # the slide of a P joint
        # proportional text at MATH_PT so the formula's scripts are 10 px (each distinct line is laid
        # out once; the numbers change on lines without mathtext)
        self.text = PathText(self.notes, 0.0, 1.0, "", size=MATH_PT, va="top", coords="axes")

    def compute(self, **values: float) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Frames ``(2n, 3)``, rate-weighted body columns ``(n, 2n, 3)`` and J q_dot ``(3,)`` of the tip."""
        q = np.array([values[f"q{i + 1}"] for i in range(self.n)], float)
        qd = np.array([values[f"q{i + 1}_dot"] for i in range(self.n)], float)
        frames, cols = C.transported_columns(self.chain, q)
        full = self.chain.jacobians(q, method="body", velocity="body")["h"][-1] @ qd
        return frames, cols * qd[:, None, None], full

    @override
    def set(self, **values: float) -> None:
        frames, cols, full = self.compute(**values)
        n, k = self.n, int(values["step"])
        if not 0 <= k <= n:
            raise ValueError(f"step must be an integer from 0 to {n}; got {values['step']!r}")
        fr = self.chain.frames([values[f"q{i + 1}"] for i in range(n)])
        self.art.set(fr)
        gaps = [np.array([fr["h"][i - 1, :2], fr["f"][i, :2], [np.nan, np.nan]])
                for i, jt in enumerate(self.chain.joints) if jt.kind == "prismatic" and i > 0]
        gaps = np.concatenate(gaps) if gaps else np.zeros((0, 2))
        self.sleeves.set_data(gaps[:, 0], gaps[:, 1])
        tip = frames[-1]
        s = self.scale
        self.frames, self.columns, self.full = frames, cols[:, -1], full
        self.partial = cols[:k, -1].sum(0)
        # step k: every frame from f_k outward moves with joint k alone (zero before it)
        if k:
            world = SE2.body_to_world(frames, cols[k - 1])
            set_arrows(self.carried, frames[:, :2], s * world[:, :2])
            self.carried.set_color(self.colors[k - 1])
            self.ring.set_data([frames[2 * (k - 1), 0]], [frames[2 * (k - 1), 1]])
            self.ring.set_markeredgecolor(self.colors[k - 1])
        else:
            set_arrows(self.carried, frames[:, :2], np.zeros((2 * n, 2)))
        self.ring.set_visible(k > 0)
        for i, patch in enumerate(self.art.links):
            on = k > 0 and i >= k - 1
            patch.set_edgecolor(self.colors[k - 1] if on else "k")
            patch.set_linewidth(2.5 if on else 1.0)
        # the columns found so far, head to tail at the tip, and their sum
        wcols = SE2.body_to_world(tip, cols[:, -1])[:, :2] * s
        wcols[k:] = 0.0
        starts = tip[:2] + np.vstack([np.zeros(2), np.cumsum(wcols, 0)[:-1]])
        set_arrows(self.steps, starts, wcols)
        set_arrows(self.total, tip[:2], wcols.sum(0))
        set_arrows(self.target, tip[:2], s * SE2.body_to_world(tip, full)[:2])
        self.text.set_text(self._table(k, cols[:, -1], values))

    def _table(self, k: int, cols: FloatArray, values: dict[str, float]) -> str:
        n = self.n
        tipname = f"h{n}".translate(_SUB)
        if k == 0:
            head = [f"step 0 of {n}: the base is fixed,", "nothing has moved yet"]
        else:
            jt = self.chain.joints[k - 1]
            fk = f"f{k}".translate(_SUB)
            head = [f"step {k} of {n}: joint {k} ({jt.letter}) moves alone;",
                    f"links {k}-{n} ride with frame {fk}" if k < n else f"link {n} rides with frame {fk}"]
        rows = [f" {j + 1}  {_fmt(cols[j])}" if j < k else f" {j + 1}    ·" for j in range(n)]
        return "\n".join(head + [
            "",
            f"columns: body velocity of {tipname}, (2.37):",
            rf"  $\mathrm{{Ad}}_g^{{-1}}\,X_j\,\dot q_j$ with $g = f_j^{{-1}}h_{n}$",
            "",
        ] + rows + [
            "",
            f"sum of columns 1..{k} (black)" if k else "sum: no columns yet",
            f"     {_fmt(self.partial)}",
            "J dq/dt, all joints at once (grey)",
            f"     {_fmt(self.full)}",
            f"arrows: world velocity × {self.scale:g}",
        ])

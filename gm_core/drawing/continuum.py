"""Drawing of arcs in chains and of extensible continuum bodies (notebook 05, beyond the draft).

* :func:`draw_backbones`: the links of a :class:`gm_core.chains.Chain` as the arcs they are
  (:meth:`~gm_core.chains.Chain.backbone`), joints as open circles, medial frames as dots;
* :func:`draw_continuum`: a :class:`gm_core.chains.continuum.ContinuumBody` at one shape, its
  backbone and its frames at evenly spaced reference arc lengths (dots);
* :func:`arcs_figure`: both side by side, the body at several shapes.

The math is in :mod:`gm_core.chains.chain` and :mod:`gm_core.chains.continuum`; this module only draws.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import ArrayLike

from gm_core.chains.chain import Chain
from gm_core.chains.continuum import ContinuumBody
from gm_core.drawing.toolkit.style import PALETTE, new_figure
from gm_core.groups import SE2

__all__ = ["draw_backbones", "draw_continuum", "arcs_figure"]

_LINK_COLOURS = {"straight": PALETTE["grey"], "arc": PALETTE["blue"], "bend": PALETTE["orange"]}


def draw_backbones(ax: Axes, chain: Chain, alpha: ArrayLike, n: int = 32) -> None:
    """Draw every link of ``chain`` at ``alpha`` as its arc (grey straight, blue fixed arc, orange bend), a
    sliding joint's travel dashed."""
    bb = chain.backbone(alpha, n)
    frames = chain.frames(alpha)
    for i, (jt, link) in enumerate(zip(chain.joints, chain.links)):
        kind = "bend" if jt.kind == "bend" else ("arc" if link.curvature else "straight")
        ax.plot(bb[i, :, 0], bb[i, :, 1], color=_LINK_COLOURS[kind], lw=5, solid_capstyle="round", zorder=2)
    h = frames["h"]
    t = np.linspace(0.0, 1.0, n)
    for i, jt in enumerate(chain.joints):  # a sliding joint's travel, dashed: h_{i-1} exp(t q X), t in [0, 1]
        if jt.kind in ("prismatic", "arc"):
            start = h[i - 1] if i else chain.base
            path = SE2.compose(start, jt.element(t * np.asarray(alpha, dtype=float)[i]))
            ax.plot(path[:, 0], path[:, 1], "--", color="black", lw=1.2, zorder=3)
    f, g = frames["f"], frames["g"]
    ax.plot(f[:, 0], f[:, 1], "o", ms=7, mfc="white", mec="black", zorder=4)
    ax.plot(g[:, 0], g[:, 1], ".", ms=8, color=PALETTE["vermillion"], zorder=5)
    ax.set_aspect("equal")


def draw_continuum(ax: Axes, body: ContinuumBody, r: ArrayLike, color: str = PALETTE["blue"],
                   label: str | None = None, marks: int = 11) -> None:
    """Draw ``body`` at shape ``r``: its backbone and dots at ``marks`` equally spaced reference arc lengths."""
    g = body.frames(r, np.linspace(0.0, body.length, 121))
    dots = body.frames(r, np.linspace(0.0, body.length, marks))
    ax.plot(g[:, 0], g[:, 1], color=color, lw=3, label=label, zorder=2)
    ax.plot(dots[:, 0], dots[:, 1], "o", ms=4, color=color, zorder=3)
    ax.set_aspect("equal")


def arcs_figure(chain: Chain, alpha: ArrayLike, body: ContinuumBody, shapes: Sequence[ArrayLike],
                labels: Sequence[str]) -> Figure:
    """An arc chain (left) and a continuum body at several shapes (right), 8.5 x 3.6 in."""
    fig, (ax0, ax1) = new_figure(1, 2, figsize=(8.5, 3.6))
    draw_backbones(ax0, chain, alpha)
    ax0.set_title("a chain with an arc joint and a bend", fontsize=9)
    colours = [PALETTE["grey"], PALETTE["blue"], PALETTE["orange"], PALETTE["green"]]
    for k, (r, lab) in enumerate(zip(shapes, labels)):
        draw_continuum(ax1, body, r, colours[k % len(colours)], lab)
    ax1.set_title("one body, curvature and stretch", fontsize=9)
    ax1.legend(fontsize=8, frameon=False, loc="center right")
    for ax in (ax0, ax1):
        ax.tick_params(labelsize=8)
        ax.set_xlabel("x", fontsize=9, labelpad=0)
        ax.set_ylabel("y", fontsize=9, labelpad=0)
    return fig

"""Axes helpers of the rendering toolkit: the SE(2) plane, square world axes, cheap 3D axes and
wireframes (re-exported by :mod:`gm_core.drawing.toolkit`, where every scene imports them)."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike

if TYPE_CHECKING:   # mpl_toolkits has no type information: to mypy these are Any (named for the reader)
    from mpl_toolkits.mplot3d.art3d import Line3DCollection
    from mpl_toolkits.mplot3d.axes3d import Axes3D

__all__ = ["plane", "square_axes", "plain_3d", "wire"]


def plane(ax: Axes, lim: float = 2.5, grid: bool = True, step: float = 1.0) -> None:
    """Square plot window for SE(2) pictures: a unit grid drawn as one collection, no tick labels.

    (Tick labels are the most expensive thing matplotlib redraws; the grid spacing is one unit.)
    """
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    if grid:
        k = np.arange(np.ceil(-lim / step), np.floor(lim / step) + 1) * step
        segs = [[(v, -lim), (v, lim)] for v in k] + [[(-lim, v), (lim, v)] for v in k]
        colors = ["0.6" if v == 0 else "0.88" for v in k] * 2
        ax.add_collection(LineCollection(segs, colors=colors, linewidths=0.7, zorder=0))


def square_axes(ax: Axes, half: float, center: Sequence[float] = (0.0, 0.0), nticks: int | None = None) -> None:
    """Square world axes of half-width ``half`` about ``center`` with a light grid
    (``nticks``: at most that many ticks per axis, fewer labels redraw faster)."""
    ax.set_xlim(center[0] - half, center[0] + half)
    ax.set_ylim(center[1] - half, center[1] + half)
    ax.set_aspect("equal")
    ax.grid(True, alpha=0.3)
    if nticks:
        from matplotlib.ticker import MaxNLocator

        ax.xaxis.set_major_locator(MaxNLocator(nticks))
        ax.yaxis.set_major_locator(MaxNLocator(nticks))


def plain_3d(ax: Axes3D, lim: float | None = None, labels: Sequence[str] = ("x", "y", "z"),
             axes_lines: bool = True) -> None:
    """Make a 3D axes cheap to draw: no panes, ticks or grid; three labelled axis lines instead."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    ax.set_axis_off()
    if lim is not None:
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_zlim(-lim, lim)
    if axes_lines:
        L = lim if lim is not None else 1.0
        segs = [[(-L, 0, 0), (L, 0, 0)], [(0, -L, 0), (0, L, 0)], [(0, 0, -L), (0, 0, L)]]
        ax.add_collection3d(Line3DCollection(segs, colors="0.55", linewidths=0.8))
        for k, name in enumerate(labels):
            pos = [0.0, 0.0, 0.0]
            pos[k] = 1.08 * L
            ax.text(*pos, name, fontsize=9, color="0.3")


def wire(ax: Axes3D, X: ArrayLike, Y: ArrayLike, Z: ArrayLike, color: ColorType = "0.75", lw: float = 0.4,
         behind: bool = False) -> Line3DCollection:
    """A light wireframe on a 3D axes; ``behind=True`` keeps it under every marker and curve
    (no depth sorting on that axes), so a wireframe never hides the dots drawn on the surface."""
    w = ax.plot_wireframe(X, Y, Z, color=color, lw=lw, rstride=1, cstride=1)
    if behind:
        ax.computed_zorder = False
        w.set_zorder(0.5)
    return w

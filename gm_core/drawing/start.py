"""The start page's picture: one rigid body and its frame at g = (x, y, theta), book (1.2).

A page topic, not a math module: the start page shows what every later panel does, a Scene whose
``set`` moves artists made once (:class:`gm_core.drawing.toolkit.style.Scene`).
"""
from __future__ import annotations

from typing import Any

import numpy as np
from typing_extensions import override

from gm_core.drawing.toolkit.primitives import BodyArtist, FrameArtist
from gm_core.drawing.toolkit.style import Scene

__all__ = ["FrameScene"]


class FrameScene(Scene):
    """A triangular body and its frame at g = (x, y, theta) over the grey world frame.

    Values: ``x``, ``y`` (position) and ``theta`` (heading, radians).
    """

    FIGSIZE = (4.5, 4.5)
    LIM = 2.5

    @override
    def decorate(self) -> None:
        ax = self.ax
        ax.set_xlim(-self.LIM, self.LIM)
        ax.set_ylim(-self.LIM, self.LIM)
        ax.set_aspect("equal")
        ax.grid(True, alpha=0.3)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        FrameArtist(ax, (0.0, 0.0, 0.0), length=0.5, colors=("0.6", "0.6"))  # the world frame

    @override
    def create(self) -> None:
        self.body = BodyArtist(self.ax, BodyArtist.triangle(0.5))
        self.frame = FrameArtist(self.ax, length=0.6)
        self.label = self.ax.set_title("")

    @override
    def set(self, **values: Any) -> None:
        x, y, theta = (float(values[k]) for k in ("x", "y", "theta"))
        g = np.array([x, y, theta])
        self.body.set(g)
        self.frame.set(g)
        self.label.set_text(f"g = ({x:.2f}, {y:.2f}, {theta:.2f})")

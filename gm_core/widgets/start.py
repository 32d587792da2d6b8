"""The start page's demo panel: one SE(2) frame and body driven by three sliders."""
from __future__ import annotations

import numpy as np

from ..drawing.primitives import BodyArtist, FrameArtist
from ..drawing.toolkit import new_figure
from .base import Panel, register, slider


@register
class FrameDemo(Panel):
    """Drag x, y and theta: the body and its frame move to g = (x, y, theta), book (1.2)."""

    title = "A rigid body at g = (x, y, θ)"

    def build(self):
        self.fig, self.ax = new_figure(figsize=(4.5, 4.5))
        ax = self.ax
        ax.set_xlim(-2.5, 2.5)
        ax.set_ylim(-2.5, 2.5)
        ax.set_aspect("equal")
        ax.grid(True, alpha=0.3)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        FrameArtist(ax, (0.0, 0.0, 0.0), length=0.5, colors=("0.6", "0.6"))  # the world frame
        self.body = BodyArtist(ax, BodyArtist.triangle(0.5))
        self.frame = FrameArtist(ax, length=0.6)
        self.label = ax.set_title("")
        self.controls = {
            "x": slider(1.0, -2.0, 2.0, description="x"),
            "y": slider(0.5, -2.0, 2.0, description="y"),
            "theta": slider(0.8, -np.pi, np.pi, description="θ"),
        }

    def update(self, x, y, theta):
        g = np.array([x, y, theta])
        self.body.set(g)
        self.frame.set(g)
        self.label.set_text(f"g = ({x:.2f}, {y:.2f}, {theta:.2f})")
        self.redraw()

    def naive_update(self, x, y, theta):
        ax = self.ax
        ax.clear()
        ax.set_xlim(-2.5, 2.5)
        ax.set_ylim(-2.5, 2.5)
        ax.set_aspect("equal")
        ax.grid(True, alpha=0.3)
        g = np.array([x, y, theta])
        FrameArtist(ax, (0.0, 0.0, 0.0), length=0.5, colors=("0.6", "0.6"))
        BodyArtist(ax, BodyArtist.triangle(0.5), g)
        FrameArtist(ax, g, length=0.6)
        ax.set_title(f"g = ({x:.2f}, {y:.2f}, {theta:.2f})")
        self.redraw()

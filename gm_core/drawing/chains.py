"""Kinematic chains (book chapter 2): kinematic chains, joints, frames and velocity arrows, all moved in place.

``ChainArtist`` draws a chain from the frame dictionary returned by ``gm_core.chains``
(``{"f", "g", "h"}`` of shape ``(n_links, 3)``): each link a rectangle from its proximal to its
distal frame, joints as dots, and any of the f/g/h frames with ``FrameArtist``. ``ArrowsArtist``
draws translational velocities (e.g. end-effector velocities) as arrows.
"""
from __future__ import annotations

import numpy as np
from matplotlib.patches import Polygon

from ..chains import accessible_circle, circle_constraints, sample_accessible_manifold
from .base import FrameArtist
from .toolkit import PALETTE

__all__ = ["link_outline", "ChainArtist", "ArrowsArtist", "draw_chain_naive", "draw_accessible_manifold"]


def link_outline(p, q, width):
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

    def __init__(self, ax, n_links, width=0.12, frames_shown=("g",), colors=None, pivot=False,
                 frame_length=0.3, base_link=None, lengths=None, offsets=None, **style):
        self.ax = ax
        self.lengths = None if lengths is None else np.asarray(lengths, dtype=float)
        self.offsets = None if offsets is None else np.asarray(offsets, dtype=float)
        # a link whose distal frame is offset sideways (fig. 2.10) is drawn as a bar plus an elbow
        self.elbows = None
        if self.lengths is not None and self.offsets is not None and np.any(self.offsets != 0):
            (self.elbows,) = ax.plot([], [], "-", color="0.25", lw=4, solid_capstyle="round", zorder=2)
        self.n_links = int(n_links)
        self.width = float(width)
        colors = colors or [f"C{i}" for i in range(self.n_links)]
        self.links = []
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
        self.last = None

    def set_base_link(self, b):
        for i, patch in enumerate(self.links):
            patch.set_linewidth(2.5 if i == b else 1.2)

    def set(self, frames):
        """Move every artist to ``frames`` (dict f, g, h of ``(n_links, 3)``); hides them if not finite."""
        f, h = np.asarray(frames["f"], float), np.asarray(frames["h"], float)
        ok = all(np.all(np.isfinite(np.asarray(frames[k], float))) for k in ("f", "g", "h"))
        for art in self.all_artists():
            art.set_visible(ok)
        if not ok:
            return False
        ends = h[:, :2]
        if self.elbows is not None:
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

    def all_artists(self):
        arts = list(self.links) + [self.joint_dots] + ([self.pivot_mark] if self.pivot else [])
        if self.elbows is not None:
            arts.append(self.elbows)
        for v in self.frames.values():
            arts += [fa.quiver for fa in v]
        return arts

    def link_corners(self, i):
        """Current world corners ``(4, 2)`` of link i's rectangle (for tests)."""
        return np.asarray(self.links[i].get_xy())[:4]


class ArrowsArtist:
    """Velocity arrows: ``set(points (k, 2), vectors (k, 2))``; non-finite arrows are hidden."""

    def __init__(self, ax, k, color=PALETTE["purple"], scale=1.0, width=0.008, zorder=6, label=None):
        self.k = int(k)
        self.scale = float(scale)
        self.quiver = ax.quiver(np.zeros(k), np.zeros(k), np.zeros(k), np.zeros(k), color=color,
                                angles="xy", scale_units="xy", scale=1.0 / self.scale, width=width,
                                zorder=zorder, label=label)
        self.points = np.zeros((k, 2))
        self.vectors = np.zeros((k, 2))

    def set(self, points, vectors):
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


def draw_chain_naive(ax, frames, width=0.12, frames_shown=("g",), frame_length=0.3):
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


def draw_accessible_manifold(ax3d, n=60, rng=None):
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

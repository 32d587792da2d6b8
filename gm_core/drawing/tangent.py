"""Tangent spaces (book section 1.4, figs 1.11-1.12): a velocity is an arrow living in the
tangent space at the current point -- the tangent line of a circle, the line itself for R^1,
the tangent plane of a sphere.

Mathematics in :mod:`gm_core.manifolds` (circle_point_velocity, sphere_tangent_basis,
sphere_velocity); here it is drawn.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, ClassVar

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.drawing.toolkit.axes import plain_3d, wire
from gm_core.drawing.toolkit.style import MATH_PT, PALETTE, ArrowSet, PathText, Scene, axes_row, readout, set_arrows
from gm_core.drawing.vector_fields import vec_text
from gm_core.groups.base import TWO_PI
from gm_core.manifolds.spaces import sphere_xyz
from gm_core.manifolds.tangent import circle_point_velocity, sphere_tangent_basis, sphere_velocity
from gm_core.validation import FloatArray

if TYPE_CHECKING:
    from mpl_toolkits.mplot3d.axes3d import Axes3D

__all__ = ["TangentSpaceScene", "arrow_3d"]


def arrow_3d(p: ArrayLike, v: ArrayLike, normal: ArrayLike, head: float = 0.18) -> FloatArray:
    """Segments ``(3, 2, 3)`` of a 3D arrow from ``p`` along ``v``: the shaft and two head barbs
    lying in the plane with unit ``normal`` (so an arrow in a tangent plane stays in it)."""
    p, v, normal = (np.asarray(a, float) for a in (p, v, normal))
    tip = p + v
    L = np.linalg.norm(v)
    if L == 0:
        return np.array([[p, p]] * 3)
    d = v / L
    side = np.cross(normal, d)
    h = min(head, 0.5 * L)
    return np.array([[p, tip], [tip, tip - h * (0.9 * d + 0.45 * side)], [tip, tip - h * (0.9 * d - 0.45 * side)]])


def _num(x: float) -> str:
    return f"{(x if abs(x) >= 0.005 else 0.0):+.2f}"


class TangentSpaceScene(Scene):
    """Figs 1.11-1.12: a point moving on the circle, on the line and on the sphere, with its
    velocity drawn in the tangent space at the point.

    Values ``s`` (where along the curves, radians) and ``speed`` (the rate along them). The
    sphere curve is the wavy path lat = :attr:`AMP` sin(2 lon), lon = s; the 3D view turns with
    the point so its tangent plane always faces the reader (``camera``; on a live canvas it turns
    at the end of a slider burst, :meth:`settle`, so during the burst the moving artists are
    blitted over a still view: the sphere is drawn without depth sorting, so the picture is the
    same either way).
    """

    AMP: ClassVar[float] = 0.45
    HALF: ClassVar[float] = 0.6          # half-size of the drawn tangent plane patch
    ARROW: ClassVar[float] = 0.55        # drawn length per unit speed
    LINE_Y: ClassVar[float] = -1.45      # where the line R^1 is drawn, below the circle
    LINE_RATE: ClassVar[float] = 0.6     # the point on R^1 sits at x = LINE_RATE (s - pi)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        return axes_row((7.4, 3.5), (None, "3d"), left=0.01, right=0.99, bottom=0.01, top=0.92, wspace=0.02)

    @override
    def decorate(self) -> None:
        ax3: Axes3D
        ax2, ax3 = self.axes
        ax2.set_xlim(-2.5, 2.5)
        ax2.set_ylim(-2.75, 2.3)
        ax2.set_aspect("equal")
        ax2.set_axis_off()
        u = np.linspace(0, TWO_PI, 200)
        ax2.plot(np.cos(u), np.sin(u), color="0.35", lw=1.5)
        ax2.plot([-2.2, 2.2], [self.LINE_Y, self.LINE_Y], color="0.35", lw=1.5)
        PathText(ax2, -0.78, -0.78, r"$\mathbb{S}^1$", size=MATH_PT, ha="right", va="top")
        PathText(ax2, -2.2, self.LINE_Y - 0.12, "the line ℝ (its tangent spaces lie along the line itself)",
                 size=8, va="top")
        PathText(ax2, 0.5, 1.0, "fig. 1.11: tangent line to the circle, and the line", size=9, ha="center",
                 va="bottom", coords="axes", offset=(0, 2))
        lat, lon = np.meshgrid(np.linspace(-np.pi / 2, np.pi / 2, 9), np.linspace(0, TWO_PI, 17))
        P = sphere_xyz(lat, lon)
        wire(ax3, P[..., 0], P[..., 1], P[..., 2], color="0.8", behind=True)
        plain_3d(ax3, lim=1.0, axes_lines=False)
        ax3.set_box_aspect((1, 1, 1), zoom=1.25)
        PathText(ax3, 0.5, 1.0, "fig. 1.12: the tangent plane of the sphere", size=9, ha="center", va="bottom",
                 coords="axes", offset=(0, 2))
        t = np.linspace(0, TWO_PI, 240)
        C = sphere_xyz(self.AMP * np.sin(2 * t), t)
        ax3.plot(C[:, 0], C[:, 1], C[:, 2], color=PALETTE["blue"], lw=1.4, zorder=1)

    @override
    def create(self) -> None:
        ax3: Axes3D
        ax2, ax3 = self.axes
        (self.tangent_line,) = ax2.plot([], [], color=PALETTE["sky"], lw=2.5, alpha=0.8, zorder=2)
        (self.points2,) = ax2.plot([], [], "o", color="k", ms=6, zorder=5)
        self.arrows2 = ArrowSet(ax2, n=2, color=PALETTE["vermillion"], width=0.011, zorder=6)
        self.label_line = PathText(ax2, 0, 0, r"$T_p\mathbb{S}^1$", size=MATH_PT, color=PALETTE["blue"], ha="center")
        self.readout2 = readout(ax2, 0.0, 0.0, "", size=7.5)
        self.plane = Poly3DCollection([np.zeros((4, 3))], facecolors=PALETTE["sky"], edgecolors=PALETTE["blue"],
                                      alpha=0.45, linewidths=1.0, zorder=2)
        ax3.add_collection3d(self.plane)
        self.arrow3 = Line3DCollection(np.zeros((3, 2, 3)), colors=PALETTE["vermillion"], linewidths=2.5, zorder=4)
        ax3.add_collection3d(self.arrow3)
        (self.point3,) = ax3.plot([], [], [], "o", color="k", ms=6, zorder=5)
        self.label_plane = ax3.text(0, 0, 0, r"$T_p\mathbb{S}^2$", fontsize=MATH_PT, color=PALETTE["blue"], zorder=6)
        self.readout3 = readout(ax3, 0.02, 0.02, "", size=7.5)

    @override
    def set(self, s: float = 0.8, speed: float = 1.0) -> None:
        ax3: Axes3D
        ax2, ax3 = self.axes
        # circle and line (fig. 1.11)
        p, v = circle_point_velocity(s, speed)
        self.circle_p, self.circle_v = p, v
        tdir = np.array([-np.sin(s), np.cos(s)])
        self.tangent_line.set_data(*np.stack([p - 1.0 * tdir, p + 1.0 * tdir], 1))
        self.label_line.set_position(p + 1.18 * tdir - [0.0, 0.08])
        x = self.LINE_RATE * (s - np.pi)                # a point sliding along the line R^1 as s grows
        self.line_p = x
        self.line_v = self.LINE_RATE * speed            # its velocity dx/dt (with ds/dt = speed)
        self.points2.set_data([p[0], x], [p[1], self.LINE_Y])
        set_arrows(self.arrows2, np.array([p, [x, self.LINE_Y + 0.15]]), np.array([self.ARROW * v, [self.line_v, 0.0]]))
        self.readout2.set_text(f"circle: p = {vec_text(p)}\n        v = {vec_text(v)}, p·v = {_num(float(p @ v))}\n"
                               f"line:   x = {x:+.2f}, ẋ = {self.line_v:+.2f}")
        # sphere (fig. 1.12): lat = AMP sin(2 lon), lon = s, moving at rate speed in lon
        lat, lon = self.AMP * np.sin(2 * s), s
        P = sphere_xyz(lat, lon)
        V = sphere_velocity(lat, lon, 2 * self.AMP * np.cos(2 * s) * speed, speed)
        east, north = sphere_tangent_basis(lat, lon)
        self.sphere_p, self.sphere_v, self.basis = P, V, (east, north)
        h = self.HALF
        corners = [P + h * (a * east + b * north) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        self.plane_corners = np.array(corners)
        self.plane.set_verts([self.plane_corners])
        self.arrow_segments = arrow_3d(P, self.ARROW * V, P)
        self.arrow3.set_segments(self.arrow_segments)
        self.point3.set_data_3d([P[0]], [P[1]], [P[2]])
        lab = P + 1.05 * h * (east + north)
        self.label_plane.set_position_3d(lab)
        self.camera = (float(np.rad2deg(lat) * 0.6 + 12), float(np.rad2deg(lon) - 20))    # (elev, azim)
        if not self.settle_later:
            self.settle()
        self.readout3.set_text(f"p = {vec_text(P)}\nv = {vec_text(V)}\np·v = {_num(float(P @ V))}: v lies in the tangent plane")

    @override
    def settle(self) -> None:
        """Turn the 3D view to :attr:`camera`, so the tangent plane at the point faces the reader."""
        ax3: Axes3D = self.axes[1]
        elev, azim = self.camera
        ax3.view_init(elev=elev, azim=azim)

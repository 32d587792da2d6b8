"""Configuration spaces (book section 1.1): the gallery of spaces, flattened views, a path on the
torus, loops on the torus and the sphere, and the pole of the latitude/longitude chart.

The surfaces and charts themselves are mathematics in :mod:`gm_core.manifolds`; here they are
drawn. Anything singular (the pole of a chart) is flagged with a SingularFlag and the affected
artist hidden: no NaN or inf is handed to matplotlib.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Any, ClassVar, Literal, cast

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine
from matplotlib.typing import ColorType
from typing_extensions import override

from gm_core.drawing.toolkit.axes import plain_3d, wire
from gm_core.drawing.toolkit.primitives import SingularFlag
from gm_core.drawing.toolkit.style import (
    MATH_PT,
    PALETTE,
    PathText,
    Scene,
    arrow,
    axes_row,
    axis_label,
    figure,
    margins,
    new_figure,
    set_arrows,
    title,
    xticks,
    yticks,
)
from gm_core.groups.base import TWO_PI
from gm_core.manifolds.spaces import (
    chart_speed,
    cylinder_xyz,
    polar_chart_velocity,
    sphere_xyz,
    torus_xyz,
    wrap_segments,
)
from gm_core.validation import FloatArray

if TYPE_CHECKING:
    from mpl_toolkits.mplot3d.axes3d import Axes3D

__all__ = ["configuration_space_gallery", "flattened_views", "TorusPathScene", "LoopsScene",
           "PoleChartScene"]


def configuration_space_gallery() -> Figure:
    """Static figure: the six spaces of section 1.1 (figs 1.1-1.6) with systems that live on each."""
    fig = figure(figsize=(9, 6.0))
    spaces = [
        ("$\\mathbb{R}^1$: the line", "prismatic joint, bead on a wire,\nposition along a track"),
        ("$\\mathbb{S}^1$: the circle", "wheel angle, free revolute joint,\ncar on a closed track"),
        ("$\\mathbb{R}^2$: the plane", "robot position on a floor,\ntwo sliders, two points on a line"),
        ("$\\mathbb{R}^1\\times\\mathbb{S}^1$: the cylinder", "slider + free revolute joint,\n"
         "point on a pipe"),
        ("$\\mathbb{T}^2$: the torus (circle × circle)", "two free revolute joints\n"
         "(a double pendulum)"),
        ("$\\mathbb{S}^2$: the sphere", "direction of a pointer,\npendulum bob on a rod"),
    ]
    for i, (name, systems) in enumerate(spaces):
        three_d = i >= 3
        ax = fig.add_subplot(2, 3, i + 1, projection="3d" if three_d else None)
        ax.set_title(name, fontsize=MATH_PT)
        if i == 0:
            ax.plot([-3, 3], [0, 0], "k", lw=2)
            for x in range(-3, 4):
                ax.plot([x, x], [-0.08, 0.08], "k", lw=1)
                ax.text(x, -0.3, str(x), ha="center", fontsize=8.5)
            ax.plot([1.3], [0], "o", color=PALETTE["blue"], ms=9)
            ax.set_xlim(-3.3, 3.3)
            ax.set_ylim(-1.2, 1.2)
            ax.axis("off")
        elif i == 1:
            t = np.linspace(0, TWO_PI, 200)
            ax.plot(np.cos(t), np.sin(t), "k", lw=2)
            for k in range(8):
                a = k * TWO_PI / 8
                ax.text(1.18 * np.cos(a), 1.18 * np.sin(a), f"{k / 8:g}", ha="center", va="center",
                        fontsize=8, color=PALETTE["vermillion"])
                ax.text(0.78 * np.cos(a), 0.78 * np.sin(a), f"{k}π/4" if k else "0", ha="center",
                        va="center", fontsize=8, color=PALETTE["blue"])
            ax.text(0, 0, "radians (inside)\ncycles (outside)", ha="center", va="center", fontsize=8)
            ax.set_xlim(-1.4, 1.4)
            ax.set_ylim(-1.4, 1.4)
            ax.set_aspect("equal")
            ax.axis("off")
        elif i == 2:
            ax.grid(True, alpha=0.3)
            ax.set_xlim(-2, 2)
            ax.set_ylim(-2, 2)
            ax.set_aspect("equal")
            ax.plot([0.8], [0.6], "o", color=PALETTE["blue"], ms=9)
            ax.set_xticks([-2, -1, 0, 1, 2], [])
            ax.set_yticks([-2, -1, 0, 1, 2], [])
        else:
            u = np.linspace(0, TWO_PI, 25)
            if i == 3:
                s = np.linspace(-1.5, 1.5, 7)
                A, S = np.meshgrid(u, s)
                P = cylinder_xyz(S, A)
                p = cylinder_xyz(0.5, 1.0)
            elif i == 4:
                A, B = np.meshgrid(u, np.linspace(0, TWO_PI, 13))
                P = torus_xyz(A, B)
                p = torus_xyz(1.0, 0.5)
            else:
                A, B = np.meshgrid(np.linspace(-np.pi / 2, np.pi / 2, 13), u)
                P = sphere_xyz(A, B) * 1.6
                p = sphere_xyz(0.5, 1.0) * 1.6
            ax3 = cast("Axes3D", ax)   # made with projection="3d"
            wire(ax3, P[..., 0], P[..., 1], P[..., 2], behind=True)   # the dot stays in front
            ax3.plot([p[0]], [p[1]], [p[2]], "o", color=PALETTE["blue"], ms=7, zorder=5)
            plain_3d(ax3, lim=2.0, axes_lines=False)
            ax3.set_box_aspect((1, 1, 1))
        # the systems that live on the space, as the axes' x label (so the layout makes room)
        if three_d:
            cast("Axes3D", ax).text2D(0.5, -0.02, systems, transform=ax.transAxes, ha="center", va="top", fontsize=8.5,
                      color="0.25")
        else:
            ax.text(0.5, -0.04, systems, transform=ax.transAxes, ha="center", va="top", fontsize=8.5,
                    color="0.25")
    cast(ConstrainedLayoutEngine, fig.get_layout_engine()).set(h_pad=0.12, hspace=0.12)   # figure()'s layout
    return fig


def _identified_edges(ax: Axes, w: float, h: float, kind: Literal["cylinder", "torus", "sphere"]) -> None:
    """Mark identified edges of a w x h rectangle: single arrows on one pair, double on the other."""
    def mark(x0: float, y0: float, dx: float, dy: float, count: int, color: ColorType) -> None:
        off = (np.arange(count) - (count - 1) / 2) * 0.06
        ax.plot(x0 + dx * (0.5 + off), y0 + dy * (0.5 + off), ls="none", marker="^" if dx == 0 else ">",
                color=color, ms=8)

    box: dict[str, Any] = dict(color="k", lw=1.2)   # Line2D properties
    ax.plot([0, 0], [0, h], **box)
    ax.plot([w, w], [0, h], **box)
    if kind in ("torus", "sphere"):
        ax.plot([0, w], [0, 0], **box)
        ax.plot([0, w], [h, h], **box)
    else:  # the cylinder's R direction goes on forever
        ax.plot([0, w], [0, 0], ls=":", color="0.5")
        ax.plot([0, w], [h, h], ls=":", color="0.5")
    # every kind glues its left edge to its right edge: the cylinder's and torus's angle, the
    # sphere chart's longitude seam (lambda = -180 deg is lambda = +180 deg)
    mark(0, 0, 0, h, 1, PALETTE["vermillion"])
    mark(w, 0, 0, h, 1, PALETTE["vermillion"])
    if kind == "torus":
        mark(0, 0, w, 0, 2, PALETTE["sky"])
        mark(0, h, w, 0, 2, PALETTE["sky"])


def flattened_views() -> Figure:
    """Static figure: cylinder, torus and the sphere's latitude/longitude chart, flattened (figs 1.4-1.6).

    Matching arrow marks are edges glued together; on the sphere chart each whole horizontal
    edge is glued to a single point (a pole), which is where the chart breaks down.
    """
    fig = new_figure(1, 3, figsize=(9, 3.4))[0]
    axes = fig.axes
    # cylinder: angle across (identified), height up (unbounded)
    ax = axes[0]
    _identified_edges(ax, TWO_PI, 3.0, "cylinder")
    t = np.linspace(0, 1.6 * TWO_PI, 300)
    for seg in wrap_segments(t + 0.4, 0.2 + 0.5 * t / TWO_PI * 2.5, TWO_PI, 0):
        ax.plot(seg[:, 0], seg[:, 1], color=PALETTE["purple"], lw=2)
    ax.set_title("cylinder $\\mathbb{S}^1\\times\\mathbb{R}^1$\n(left edge = right edge)", fontsize=MATH_PT)
    ax.set_xlabel("angle a")
    ax.set_ylabel("height s")
    # torus: both directions identified
    ax = axes[1]
    _identified_edges(ax, TWO_PI, TWO_PI, "torus")
    t = np.linspace(0, 3 * TWO_PI, 500)
    for seg in wrap_segments(t + 0.3, 2.0 / 3.0 * t + 1.0):
        ax.plot(seg[:, 0], seg[:, 1], color=PALETTE["purple"], lw=2)
    ax.set_title("torus $\\mathbb{T}^2$\n(both pairs of edges glued)", fontsize=MATH_PT)
    ax.set_xlabel("joint angle a")
    ax.set_ylabel("joint angle b")
    # sphere: lat/lon chart
    ax = axes[2]
    _identified_edges(ax, TWO_PI, np.pi, "sphere")
    ax.plot([0, TWO_PI], [np.pi, np.pi], color="darkred", lw=4, alpha=0.6)
    ax.plot([0, TWO_PI], [0, 0], color="darkred", lw=4, alpha=0.6)
    # the labels sit clear of the thick edge lines they name (below the top one, above the bottom one)
    ax.text(np.pi, np.pi - 0.2, "whole edge = north pole", ha="center", va="top", fontsize=8.5, color="darkred")
    ax.text(np.pi, 0.2, "whole edge = south pole", ha="center", va="bottom", fontsize=8.5, color="darkred")
    # the longitude seam: the left edge (lambda = -180 deg) and the right edge (+180 deg) are one meridian
    for x in (0.0, TWO_PI):
        ax.plot([x, x], [0, np.pi], color=PALETTE["vermillion"], lw=3, alpha=0.5, solid_capstyle="butt")
    ax.text(np.pi, np.pi / 2, "left edge = right edge:\nthe seam λ = ±180°", ha="center", va="center",
            fontsize=8.5, color=PALETTE["vermillion"])
    ax.set_title("sphere, latitude/longitude chart\n(seam glued, edges = the poles)", fontsize=MATH_PT)
    ax.set_xlabel("longitude λ")
    ax.set_ylabel("latitude φ")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xticks([0, np.pi, TWO_PI], ["0", "π", "2π"])
    axes[2].set_xticks([0, np.pi, TWO_PI], ["−180°", "0", "180°"])
    axes[2].set_yticks([0, np.pi / 2, np.pi], ["−90°", "0", "90°"])   # bottom edge: the south pole
    axes[1].set_yticks([0, np.pi, TWO_PI], ["0", "π", "2π"])
    return fig


class TorusPathScene(Scene):
    """A straight line on the flattened torus and the same path wound round the 3D torus.

    Values: ``a0``, ``b0`` (start), ``slope`` (db/da), ``turns`` (how far to go in a).
    """

    N: ClassVar[int] = 360

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        return axes_row((8, 3.6), ("3d", None), left=0.02, right=0.97, bottom=0.14, top=0.9, wspace=0.15)

    @override
    def decorate(self) -> None:
        ax3: Axes3D
        ax3, ax2 = self.axes
        u = np.linspace(0, TWO_PI, 21)
        A, B = np.meshgrid(u, np.linspace(0, TWO_PI, 11))
        P = torus_xyz(A, B)
        wire(ax3, P[..., 0], P[..., 1], P[..., 2], color="0.8")
        plain_3d(ax3, lim=2.4, axes_lines=False)
        ax3.set_box_aspect((1, 1, 0.5))
        ax3.set_zlim(-1.2, 1.2)
        ax3.view_init(elev=35, azim=-60)
        _identified_edges(ax2, TWO_PI, TWO_PI, "torus")
        ax2.set_xlim(-0.3, TWO_PI + 0.3)
        ax2.set_ylim(-0.3, TWO_PI + 0.3)
        ax2.set_aspect("equal")
        axis_label(ax2, "x", "a (round the hole)", ticks=xticks(ax2, [0, np.pi, TWO_PI], ["0", "π", "2π"]))
        axis_label(ax2, "y", "b", ticks=yticks(ax2, [0, np.pi, TWO_PI], ["0", "π", "2π"]))

    @override
    def create(self) -> None:
        ax3: Axes3D
        ax3, ax2 = self.axes
        (self.curve3d,) = ax3.plot([], [], [], color=PALETTE["purple"], lw=1.8)
        (self.start3d,) = ax3.plot([], [], [], "o", color="k", ms=5)
        self.flat = LineCollection([], colors=PALETTE["purple"], linewidths=1.8)
        ax2.add_collection(self.flat)
        (self.start2d,) = ax2.plot([], [], "o", color="k", ms=5)
        self.title = title(ax2)

    def path(self, a0: float, b0: float, slope: float, turns: float) -> tuple[FloatArray, FloatArray]:
        t = np.linspace(0.0, turns * TWO_PI, self.N)
        return a0 + t, b0 + slope * t

    @override
    def set(self, a0: float = 0.0, b0: float = 0.0, slope: float = 0.5, turns: float = 2.0) -> None:
        a, b = self.path(a0, b0, slope, turns)
        P = torus_xyz(a, b)
        self.curve3d.set_data_3d(P[:, 0], P[:, 1], P[:, 2])
        self.start3d.set_data_3d(P[:1, 0], P[:1, 1], P[:1, 2])
        self.segments = wrap_segments(a, b)
        self.flat.set_segments(self.segments)
        self.start2d.set_data([a0 % TWO_PI], [b0 % TWO_PI])
        self.title.set_text(f"flattened: {len(self.segments)} straight pieces, slope {slope:.2f}")


def _surface_points(kind: str) -> FloatArray:
    if kind == "torus":
        A, B = np.meshgrid(np.linspace(0, TWO_PI, 21), np.linspace(0, TWO_PI, 11))
        return torus_xyz(A, B)
    A, B = np.meshgrid(np.linspace(-np.pi / 2, np.pi / 2, 11), np.linspace(0, TWO_PI, 21))
    return sphere_xyz(A, B) * 1.6


class LoopsScene(Scene):
    """Fig. 1.6: try to shrink a loop. On the sphere it contracts to a point; on the torus it can't.

    Value ``s`` in [0, 1]: the sphere loop is the circle of latitude s * 90 degrees (a point at
    s = 1); the torus loop is a tube circle carried round the hole to angle 2 pi s -- whatever we
    do it keeps wrapping once round the tube, so its length never drops below 2 pi r.
    """

    R: ClassVar[float] = 2.0      # the torus' radii
    r: ClassVar[float] = 0.7
    rho: ClassVar[float] = 1.6    # the sphere's radius

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        return axes_row((8, 2.9), ("3d", "3d"), left=0.0, right=1.0, bottom=-0.14, top=0.93, wspace=0.0)

    @override
    def decorate(self) -> None:
        ax_t: Axes3D
        ax_s: Axes3D
        ax_t, ax_s = self.axes
        for ax, kind in ((ax_t, "torus"), (ax_s, "sphere")):
            P = _surface_points(kind)
            wire(ax, P[..., 0], P[..., 1], P[..., 2], color="0.82")
            plain_3d(ax, lim=2.2, axes_lines=False)
            # equal scales on all three axes (the box's height over its width is the z range over
            # the x range), so the sphere is round and the torus not flattened
            zlim = 1.2 if kind == "torus" else 2.2
            ax.set_zlim(-zlim, zlim)
            ax.set_box_aspect((1, 1, zlim / 2.2), zoom=1.0 if kind == "torus" else 1.1)
            ax.view_init(elev=28, azim=-55)
        u = np.linspace(0, TWO_PI, 120)
        L = torus_xyz(u, 0.0 * u + np.pi / 2)  # the loop round the hole, drawn fixed for reference
        ax_t.plot(L[:, 0], L[:, 1], L[:, 2], color=PALETTE["blue"], lw=1.2, alpha=0.6)

    @override
    def create(self) -> None:
        ax_t: Axes3D
        ax_s: Axes3D
        ax_t, ax_s = self.axes
        (self.torus_loop,) = ax_t.plot([], [], [], color=PALETTE["vermillion"], lw=2.5)
        (self.sphere_loop,) = ax_s.plot([], [], [], color=PALETTE["vermillion"], lw=2.5)
        (self.sphere_point,) = ax_s.plot([], [], [], "o", color=PALETTE["vermillion"], ms=6)
        self.t_title = PathText(ax_t, 0.5, 0.97, "", size=9, ha="center", va="top", coords="axes")
        self.s_title = PathText(ax_s, 0.5, 0.97, "", size=9, ha="center", va="top", coords="axes")

    @override
    def set(self, s: float = 0.0) -> None:
        u = np.linspace(0, TWO_PI, 90)
        T = torus_xyz(TWO_PI * s + 0 * u, u, self.R, self.r)
        self.torus_loop.set_data_3d(T[:, 0], T[:, 1], T[:, 2])
        self.torus_length = TWO_PI * self.r
        lat = 0.5 * np.pi * s
        S = sphere_xyz(lat + 0 * u, u) * self.rho
        self.sphere_length = TWO_PI * self.rho * np.cos(lat)
        contracted = self.sphere_length < 1e-9
        self.sphere_loop.set_visible(not contracted)
        self.sphere_point.set_visible(contracted)
        self.sphere_loop.set_data_3d(S[:, 0], S[:, 1], S[:, 2])
        self.sphere_point.set_data_3d([0.0], [0.0], [self.rho])
        self.t_title.set_text(f"torus: tube loop length {self.torus_length:.2f}\n(cannot shrink)")
        self.s_title.set_text(f"sphere: loop length {self.sphere_length:.2f}"
                              + ("\n(contracted to the pole)" if contracted else "\n(shrinks to a point)"))




class PoleChartScene(Scene):
    """A walker moving at unit speed on the sphere, seen in two charts of an atlas.

    Left: the latitude/longitude chart, where the arrow (coordinate velocity) grows without bound
    as the walker nears a pole and the chart fails at the pole itself (flagged, arrow hidden).
    Middle: a polar chart (projection onto the equator plane), smooth at the north pole. Right:
    coordinate speed against latitude. Values: ``lat_deg``, ``heading_deg``.
    """

    POLE_TOL_DEG: ClassVar[float] = 1e-6
    WARN_SPEED: ClassVar[float] = 50.0
    ARROW: ClassVar[float] = 0.25  # radians drawn per unit coordinate speed

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, axes = new_figure(1, 3, figsize=(10, 3.4), gridspec_kw=dict(width_ratios=[1.5, 1, 1.1]))
        margins(fig, left=0.06, right=0.98, bottom=0.2, top=0.88, wspace=0.35)
        return fig, list(axes)

    @override
    def decorate(self) -> None:
        ax_c, ax_p, ax_v = self.axes
        ax_c.set_xlim(-np.pi, np.pi)
        ax_c.set_ylim(-np.pi / 2 - 0.15, np.pi / 2 + 0.15)
        ax_c.axhspan(np.pi / 2, np.pi / 2 + 0.15, color="mistyrose")
        ax_c.axhspan(-np.pi / 2 - 0.15, -np.pi / 2, color="mistyrose")
        axis_label(ax_c, "x", "longitude λ", ticks=xticks(ax_c, [-np.pi, 0, np.pi], ["−π", "0", "π"]))
        axis_label(ax_c, "y", "φ", ticks=yticks(ax_c, [-np.pi / 2, 0, np.pi / 2], ["−π/2", "0", "π/2"]))
        title(ax_c, "latitude/longitude chart")
        t = np.linspace(0, TWO_PI, 100)
        ax_p.plot(np.cos(t), np.sin(t), color="0.6", lw=1)
        ax_p.set_xlim(-1.2, 1.2)
        ax_p.set_ylim(-1.2, 1.2)
        ax_p.set_aspect("equal")
        title(ax_p, "polar chart (northern half)")
        ax_p.plot([0], [0], "+", color="0.3")
        ax_p.set_xticks([])
        ax_p.set_yticks([])
        lat = np.linspace(-np.pi / 2 + 0.01, np.pi / 2 - 0.01, 200)
        ax_v.set_xlim(-np.pi / 2, np.pi / 2)
        ax_v.set_ylim(-0.3, 2.3)
        axis_label(ax_v, "x", "latitude φ", ticks=xticks(ax_v, [-np.pi / 2, 0, np.pi / 2], ["−π/2", "0", "π/2"]))
        yticks(ax_v, [0, 1, 2], ["1", "10", "100"])
        title(ax_v, "chart speed (log scale)")
        self._lat_grid = lat

    @override
    def create(self) -> None:
        ax_c, ax_p, ax_v = self.axes
        (self.pt_c,) = ax_c.plot([], [], "o", color=PALETTE["blue"], ms=7, zorder=7)
        self.arrow_c = arrow(ax_c, color=PALETTE["vermillion"], width=0.012)
        (self.pt_p,) = ax_p.plot([], [], "o", color=PALETTE["blue"], ms=7, zorder=7)
        self.arrow_p = arrow(ax_p, color=PALETTE["green"], width=0.015)
        (self.speed_curve,) = ax_v.plot([], [], color=PALETTE["vermillion"], lw=1.5)
        (self.speed_pt,) = ax_v.plot([], [], "o", color=PALETTE["vermillion"], ms=6)
        self.flag = SingularFlag(ax_c, loc=(0.5, 0.55))
        self.p_note = PathText(ax_p, 0.5, 0.03, "", size=8, ha="center", coords="axes")
        self.readout = PathText(ax_c, 0.02, 0.03, "", size=8, coords="axes")
        self._heading: float | None = None

    @override
    def set(self, lat_deg: float = 45.0, heading_deg: float = 45.0) -> None:
        lat = np.deg2rad(lat_deg)
        h = np.deg2rad(heading_deg)
        lon = 0.0
        if self._heading != heading_deg:  # the speed-vs-latitude curve only depends on the heading
            dl, dn = chart_speed(self._lat_grid, h)
            self.speed_curve.set_data(self._lat_grid, np.log10(np.hypot(dl, dn)))
            self._heading = heading_deg
        at_pole = abs(abs(lat_deg) - 90.0) < self.POLE_TOL_DEG
        dlat, dlon = chart_speed(lat, h)
        speed = float(np.hypot(dlat, dlon))
        self.at_pole = at_pole
        self.chart_speed = speed
        if at_pole:
            self.flag.show("pole: longitude undefined,\nchart velocity does not exist")
            self.pt_c.set_visible(False)
            self.arrow_c.set_visible(False)
            self.speed_pt.set_visible(False)
            self.readout.set_text("φ = ±90°: every λ names this one point")
        else:
            if speed > self.WARN_SPEED:  # still finite, but the chart is visibly failing
                self.flag.show(f"near the pole: chart speed {speed:.0f}\n(unbounded as φ → ±90°)")
            else:
                self.flag.hide()
            self.pt_c.set_visible(True)
            self.arrow_c.set_visible(True)
            self.speed_pt.set_visible(True)
            self.pt_c.set_data([lon], [lat])
            self.arrow_vec = self.ARROW * np.array([float(dlon), float(dlat)])
            set_arrows(self.arrow_c, [lon, lat], self.arrow_vec)
            self.speed_pt.set_data([lat], [np.log10(speed)])
            self.readout.set_text(f"dφ/dt = {float(dlat):+.2f}, dλ/dt = {float(dlon):+.2f}, "
                                  f"speed {speed:.2f}")
        # polar chart: X = cos(lat) cos(lon), Y = cos(lat) sin(lon); smooth at the north pole
        north = lat >= 0
        self.pt_p.set_visible(north)
        self.arrow_p.set_visible(north)
        if north:
            (X, Y), v = polar_chart_velocity(lat, lon, h)
            self.pt_p.set_data([X], [Y])
            self.polar_vec = self.ARROW * v
            set_arrows(self.arrow_p, [X, Y], self.polar_vec)
            self.p_note.set_text(f"chart speed {np.hypot(*v):.2f} (finite)")
        else:
            self.p_note.set_text("(walker is on the southern half)")


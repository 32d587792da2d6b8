"""Charts of the plane (book section 1.1): one vector field, one point and one vector drawn in the
Cartesian and the polar chart side by side, so the overlap map is seen acting on all three.

The charts and their transitions are mathematics in :mod:`gm_core.manifolds.charts`; integral
curves come from :func:`gm_core.fields.integral_curve`. A point on the polar chart's missing ray
(y = 0, x <= 0) is flagged with a SingularFlag and the polar artists hidden: nothing non-finite
is handed to matplotlib.
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from typing_extensions import override

from gm_core.drawing.toolkit.axes import plane
from gm_core.drawing.toolkit.primitives import SingularFlag
from gm_core.drawing.toolkit.style import (
    PALETTE,
    ArrowSet,
    PathText,
    Scene,
    axis_label,
    margins,
    new_figure,
    readout,
    title,
    xticks,
    yticks,
)
from gm_core.fields import FIELDS, VectorField, integral_curve
from gm_core.manifolds.charts import (
    CARTESIAN,
    POLAR,
    Chart,
    in_overlap,
    transition_field,
    transition_jacobian,
    transition_path,
    transition_vector,
)
from gm_core.validation import FloatArray

__all__ = ["PlaneChartsScene"]

PI = float(np.pi)


class PlaneChartsScene(Scene):
    """A vector field on the plane in the Cartesian chart (left) and the polar chart (right).

    Values: ``field`` (a key of :data:`gm_core.fields.FIELDS`), the point ``x``, ``y`` and the
    vector's direction ``v_angle`` (degrees from the x axis) and length ``v_length``. Both panels
    show the field's direction (grey arrows; the polar ones are X_2 = J X_1), the point and the
    vector (purple; v_2 = J v_1 on the right, to the same scale), the integral curve through the
    point (black) and the four coordinate lines through it: x and y (straight on the left, curved
    on the right) and r and theta (curved on the left, straight on the right).
    """

    LIM: ClassVar[float] = 3.0
    R_MAX: ClassVar[float] = 4.3
    FIELD_ARROW_PX: ClassVar[float] = 27.0   # drawn length of the field's direction arrows, in pixels
    V_SCALE: ClassVar[float] = 0.8        # drawn length per unit of the chosen vector, in both charts
    T: ClassVar[float] = 3.0              # integral curve: time forwards from the point
    LINES: ClassVar[tuple[tuple[str, str], ...]] = (("x", PALETTE["x"]), ("y", PALETTE["y"]),
                                                   ("r", PALETTE["orange"]), ("θ", PALETTE["theta"]))

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, axes = new_figure(1, 2, figsize=(7.8, 4.8), gridspec_kw=dict(width_ratios=[1.0, 0.7]))
        margins(fig, left=0.06, right=0.99, bottom=0.17, top=0.94, wspace=0.22)
        return fig, list(axes)

    @override
    def decorate(self) -> None:
        ax_c, ax_p = self.axes
        plane(ax_c, self.LIM)
        axis_label(ax_c, "x", "x")
        axis_label(ax_c, "y", "y")
        ax_c.plot([0.0, -self.LIM], [0.0, 0.0], color="0.35", lw=3.0, ls=(0, (4, 3)), zorder=1)
        PathText(ax_c, -self.LIM + 0.1, -0.2, "ray not in the\npolar chart", size=8, color="0.3", va="top")
        title(ax_c, "Cartesian chart (x, y)")
        ax_p.set_xlim(0.0, self.R_MAX)
        ax_p.set_ylim(-PI - 0.8, PI + 0.15)     # room for the readout below theta = -pi
        ax_p.set_aspect("equal")
        for th in (-PI, PI):
            ax_p.plot([0.0, self.R_MAX], [th, th], color="0.35", lw=2.0, ls=(0, (4, 3)), zorder=1)
        ax_p.axhline(0.0, color="0.75", lw=0.7, zorder=0)
        axis_label(ax_p, "x", "r", ticks=xticks(ax_p, [0, 1, 2, 3, 4], ["0", "1", "2", "3", "4"]))
        axis_label(ax_p, "y", "θ", ticks=yticks(ax_p, [-PI, -PI / 2, 0, PI / 2, PI], ["−π", "−π/2", "0", "π/2", "π"]))
        title(ax_p, "polar chart (r, θ)")
        keys = [Line2D([], [], color=c, lw=1.6, label=f"{n} = {n}₀") for n, c in self.LINES]
        keys += [Line2D([], [], color="k", lw=1.4, label="integral curve"),
                 Line2D([], [], color=PALETTE["purple"], lw=3, label="vector v")]
        self.fig.legend(handles=keys, loc="lower center", ncol=6, fontsize=9, frameon=False,
                        bbox_to_anchor=(0.5, 0.0))

    @override
    def create(self) -> None:
        ax_c, ax_p = self.axes
        g = np.linspace(-self.LIM + 0.3, self.LIM - 0.3, 11)
        self._grid_c = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
        r, th = np.linspace(0.35, 4.0, 8), np.linspace(-PI + 0.3, PI - 0.3, 13)
        self._grid_p = np.stack(np.meshgrid(r, th), -1).reshape(-1, 2)
        self.field_c = ArrowSet(ax_c, n=len(self._grid_c), color="0.6", width=0.0045, zorder=2)
        self.field_p = ArrowSet(ax_p, n=len(self._grid_p), color="0.6", width=0.0065, zorder=2)
        self.lines: dict[str, list[LineCollection]] = {}
        for name, color in self.LINES:
            pair = [LineCollection([], colors=color, linewidths=1.6, zorder=3) for _ in self.axes]
            for ax, lc in zip(self.axes, pair):
                ax.add_collection(lc, autolim=False)
            self.lines[name] = pair
        self.curves = [LineCollection([], colors="k", linewidths=1.4, zorder=4) for _ in self.axes]
        for ax, lc in zip(self.axes, self.curves):
            ax.add_collection(lc, autolim=False)
        self.vec_c = ArrowSet(ax_c, color=PALETTE["purple"], width=0.012, zorder=6)
        self.vec_p = ArrowSet(ax_p, color=PALETTE["purple"], width=0.017, zorder=6)
        (self.pt_c,) = ax_c.plot([], [], "o", color="k", ms=7, zorder=7)
        (self.pt_p,) = ax_p.plot([], [], "o", color="k", ms=7, zorder=7)
        ax_c.add_patch(Rectangle((0.0, 0.0), 1.0, 0.075, transform=ax_c.transAxes, facecolor="white", alpha=0.9,
                                 edgecolor="none", zorder=8))   # a quiet strip under the readout
        self.read_c = readout(ax_c, 0.02, 0.02, "", zorder=9)
        self.read_p = readout(ax_p, 0.03, 0.01, "", zorder=9)
        self.flag = SingularFlag(ax_p, loc=(0.5, 0.86))
        self._field: str | None = None

    def _draw_field(self, name: str) -> None:
        X1 = VectorField(FIELDS[name], 2, name=name)
        X2 = transition_field(X1, CARTESIAN, POLAR)
        for ax, arrows, grid, X in ((self.axes[0], self.field_c, self._grid_c, X1),
                                    (self.axes[1], self.field_p, self._grid_p, X2)):
            v = X(grid)
            n = np.hypot(v[:, 0], v[:, 1])[:, None]
            ax.apply_aspect()                                             # the box equal aspect leaves
            x0, x1 = ax.get_xlim()
            length = self.FIELD_ARROW_PX * (x1 - x0) / ax.bbox.width     # equal aspect: one scale both ways
            d = length * np.divide(v, n, out=np.zeros_like(v), where=n > 1e-12)
            arrows.set(grid - d / 2, d)       # direction only, centred on the grid point
        self.X2 = X2
        self._field = name

    def _coordinate_lines(self, q1: FloatArray, q2: FloatArray | None) -> dict[str, tuple[Chart, FloatArray]]:
        """The coordinate lines through the point, each sampled in the chart where it is straight."""
        s = np.linspace(-self.LIM * 1.5, self.LIM * 1.5, 241)
        out: dict[str, tuple[Chart, FloatArray]] = {"x": (CARTESIAN, np.stack([np.full_like(s, q1[0]), s], -1)),
               "y": (CARTESIAN, np.stack([s, np.full_like(s, q1[1])], -1))}
        if q2 is not None:
            th = np.linspace(-PI, PI, 361)[1:-1]
            r = np.linspace(0.0, 1.5 * self.R_MAX, 241)[1:]
            out["r"] = (POLAR, np.stack([np.full_like(th, q2[0]), th], -1))
            out["θ"] = (POLAR, np.stack([r, np.full_like(r, q2[1])], -1))
        return out

    def integral_curve(self, field: str, x: float, y: float) -> FloatArray:
        """The integral curve ``(m, 2)`` of the field from (x, y) for time T, in the Cartesian chart,
        stopped where it leaves a box twice the view (:func:`gm_core.fields.integral_curve`)."""
        lim = 2 * self.LIM

        def leave(t: float, q: FloatArray) -> float:
            return lim - float(np.max(np.abs(q)))

        leave.terminal = True  # type: ignore[attr-defined]  # solve_ivp reads an event function's attribute
        return integral_curve(VectorField(FIELDS[field], 2), [x, y], (0.0, self.T),
                              t_eval=np.linspace(0.0, self.T, 121), method="RK45", rtol=1e-6, atol=1e-9,
                              events=leave).q

    @override
    def set(self, field: str = "spiral sink", x: float = 1.5, y: float = 1.0, v_angle: float = 60.0,
            v_length: float = 1.0) -> None:
        if field != self._field:
            self._draw_field(field)
        a = np.deg2rad(v_angle)
        self.q1 = np.array([x, y], float)
        self.v1 = v_length * np.array([np.cos(a), np.sin(a)])
        covered = bool(in_overlap(self.q1, CARTESIAN, POLAR))
        self.q2: FloatArray | None = None
        self.v2: FloatArray | None = None
        if covered:
            self.q2, self.v2 = transition_vector(self.q1, self.v1, CARTESIAN, POLAR)
            self.J = transition_jacobian(self.q1, CARTESIAN, POLAR)
        self.pt_c.set_data([x], [y])
        self.vec_c.set(self.q1, self.V_SCALE * self.v1)
        for name, (chart, path) in self._coordinate_lines(self.q1, self.q2).items():
            left, right = self.lines[name]
            left.set_segments(transition_path(path, chart, CARTESIAN))
            right.set_segments(transition_path(path, chart, POLAR))
        if not covered:
            for name in ("r", "θ"):
                for lc in self.lines[name]:
                    lc.set_segments([])
        self.curve = self.integral_curve(field, x, y)
        self.curves[0].set_segments([self.curve])
        self.curves[1].set_segments(transition_path(self.curve, CARTESIAN, POLAR))
        self.read_c.set_text(f"q₁ = ({x:+.2f}, {y:+.2f})   v₁ = ({self.v1[0]:+.2f}, {self.v1[1]:+.2f})")
        for artist in (self.pt_p, self.vec_p):
            artist.set_visible(covered)
        if self.q2 is not None and self.v2 is not None:
            self.flag.hide()
            self.pt_p.set_data([self.q2[0]], [self.q2[1]])
            self.vec_p.set(self.q2, self.V_SCALE * self.v2)
            self.read_p.set_text(f"q₂ = ({self.q2[0]:.2f}, {self.q2[1]:+.2f})\n"
                                 f"v₂ = J v₁ = ({self.v2[0]:+.2f}, {self.v2[1]:+.2f})")
        else:
            where = "the origin has no angle θ" if x == 0 and y == 0 else "θ would be both π and −π"
            self.flag.show(f"not in the polar chart:\n{where}")
            self.read_p.set_text("q₂: none (outside the chart)")

"""Drawing for the geometry notebook (10): curvature maps, gaits on them, the three estimates of a
gait's displacement, the connection seen from three body frames, the swimmer animation.

The numbers come from :mod:`gm_core.geometry` (``estimates``: shaped gaits, the three estimates,
row scaling, field sizes, cached frames and curvature grids); the shape-space axes, fields and
their style are :mod:`.connection`'s. Every artist is created once and moved with ``set``;
singular or undefined shapes are masked (grey) and flagged, never drawn as NaN silently.
"""
from __future__ import annotations

import html
from collections.abc import Mapping, Sequence
from typing import Any, ClassVar

import matplotlib
import numpy as np
from matplotlib.animation import FuncAnimation
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.container import BarContainer
from matplotlib.figure import Figure
from matplotlib.patches import Patch
from matplotlib.typing import ColorType
from typing_extensions import override

from gm_core.drawing.connection import ConnectionFieldArtist, Limits, shape_grid, style_shape_axes
from gm_core.drawing.motion import SystemArtist
from gm_core.drawing.toolkit.primitives import SingularFlag, TrailArtist, animate
from gm_core.drawing.toolkit.style import PALETTE, Scene, freeze_layout, new_figure
from gm_core.geometry.estimates import (
    Estimates,
    curvature_grid,
    displacement_estimates,
    field_rms,
    frames_of,
    row_scaled,
    shaped_gait,
)
from gm_core.systems import LocomotionSystem, LowReSwimmer
from gm_core.systems.gaits import Gait
from gm_core.systems.motion import Trajectory
from gm_core.validation import FloatArray, SingularShapeError

__all__ = ["ROWS", "LIMITS", "CurvatureMapArtist", "GaitArtist", "curvature_maps_figure", "animate_swimmer",
           "GaitStokesScene", "FrameFieldsScene", "estimates_table"]

ROWS = ("x", "y", "θ")
#: The shape window of notebook 10's panels (the minimum-perturbation frame is solved over it).
LIMITS = ((-2.5, 2.5), (-2.5, 2.5))
_CMAP = "RdBu_r"
#: Colour bands of the curvature maps: they read as filled contours, and a banded picture is a
#: third of the PNG bytes of a smooth one (what a live panel sends the browser on every change).
#: Odd, so that zero lies inside the middle band, the map's own white, not on a band's edge.
CMAP_BANDS = 25


class CurvatureMapArtist:
    """One row of the constraint curvature D(-A) as an image over a rectangle of shape space.

    Red is positive, blue negative, in :data:`CMAP_BANDS` bands, colour limits symmetric about
    zero (a high percentile of |F|, so a singular line does not wash out the picture, and never
    below 1e-6 of the largest row, so a row that vanishes up to rounding shows white); singular
    shapes are grey. The values are :func:`gm_core.geometry.estimates.curvature_grid` (cached in the math layer).
    """

    def __init__(self, ax: Axes, system: LocomotionSystem, row: int = 0, limits: Limits | None = None,
                 n: int = 81) -> None:
        self.ax, self.n = ax, int(n)
        self.limits = tuple((float(lo), float(hi)) for lo, hi in (limits or system.shape_limits))
        (lo1, hi1), (lo2, hi2) = self.limits
        cmap = matplotlib.colormaps[_CMAP].resampled(CMAP_BANDS).with_extremes(bad="0.75")
        self.image = ax.imshow(np.zeros((self.n, self.n)), origin="lower", extent=(lo1, hi1, lo2, hi2),
                               cmap=cmap, interpolation="bilinear", aspect="equal", zorder=1)
        self.set(system, row)

    def values(self, system: LocomotionSystem | None = None) -> FloatArray:
        """Curvature (n, n, 3) of ``system`` (default: the one shown) on the map's grid."""
        return curvature_grid(system or self.system, self.limits, self.n)

    def set(self, system: LocomotionSystem | None = None, row: int | None = None) -> float:
        if system is not None:
            self.system = system
        if row is not None:
            self.row = int(row)
        Fall = self.values()
        F = Fall[..., self.row]
        finite = np.isfinite(F)
        q = 95 if getattr(self.system, "may_be_singular", False) else 99
        vmax = float(np.percentile(np.abs(F[finite]), q)) if finite.any() else 1.0
        every = np.abs(Fall[np.isfinite(Fall)])
        vmax = max(vmax, 1e-6 * float(every.max()) if every.size else 0.0)
        vmax = vmax if vmax > 0 else 1.0
        self.image.set_data(np.ma.masked_invalid(F))
        self.image.set_clim(-vmax, vmax)
        self.vmax = vmax
        return vmax


class GaitArtist:
    """A gait drawn as a closed curve with a start dot and an arrow showing its direction."""

    def __init__(self, ax: Axes, color: ColorType = "k", lw: float = 1.8, samples: int = 200) -> None:
        (self.line,) = ax.plot([], [], color=color, lw=lw, zorder=4)
        (self.start,) = ax.plot([], [], "o", color=color, ms=5, zorder=5)
        self.arrow = ax.annotate("", xy=(0, 0), xytext=(0, 0), zorder=5,
                                 arrowprops=dict(arrowstyle="-|>", color=color, lw=lw))
        self.samples = samples

    def set(self, gait: Gait) -> None:
        t = np.linspace(0, gait.period, self.samples + 1)
        p = gait(t)
        self.line.set_data(p[:, 0], p[:, 1])
        self.start.set_data([p[0, 0]], [p[0, 1]])
        k = self.samples // 8
        self.arrow.xy, self.arrow.xyann = tuple(p[k + 1]), tuple(p[k])
        self.points = p

    def set_visible(self, visible: bool) -> None:
        for a in (self.line, self.start, self.arrow):
            a.set_visible(visible)


def _map_axes(ax: Axes, system: LocomotionSystem, limits: Limits, title: str | None = None) -> None:
    style_shape_axes(ax, system, title, limits=limits, pad=0.0)


def curvature_maps_figure(cases: Mapping[str, tuple[LocomotionSystem, Gait | None]], n: int = 81,
                          figsize: Sequence[float] = (9, 7.6)) -> Figure:
    """Grid of curvature maps: one column per case, rows x, y, θ; ``cases`` = {title: (system, gait or None)}."""
    fig, axes = new_figure(3, len(cases), figsize=figsize, squeeze=False)
    for j, (title, (system, gait)) in enumerate(cases.items()):
        for i in range(3):
            ax = axes[i, j]
            m = CurvatureMapArtist(ax, system, i, n=n)
            _map_axes(ax, system, m.limits, f"{title}\nD(−A), row {ROWS[i]}" if i == 0 else f"row {ROWS[i]}")
            flat = not np.nanmax(np.abs(m.values()[..., i])) > 1e-9
            ax.text(0.02, 0.02, "≡ 0" if flat else f"±{m.vmax:.2g}", transform=ax.transAxes, va="bottom",
                    bbox=dict(facecolor="white", alpha=0.7, lw=0))
            if gait is not None:
                GaitArtist(ax).set(gait)
    return fig


def animate_swimmer(system: LocomotionSystem, gait: Gait, traj: Trajectory, n_frames: int = 60, row: int = 0,
                    limits: Limits | None = None, figsize: Sequence[float] = (9, 4),
                    interval: float = 60) -> tuple[Figure, FuncAnimation]:
    """Animation (fig, FuncAnimation) of ``system`` swimming ``traj`` (a locomotion.Trajectory) beside its gait.

    Left: the curvature row ``row`` with the gait and a moving dot; right: the swimmer in the
    world with the trail of its body frame. Frames are shortened under the test suite.
    """
    fig, (axs, axw) = new_figure(1, 2, figsize=figsize)
    m = CurvatureMapArtist(axs, system, row, limits=limits, n=61)
    _map_axes(axs, system, m.limits, f"D(−A), row {ROWS[row]}, with the gait")
    GaitArtist(axs).set(gait)
    (dot,) = axs.plot([], [], "o", color="gold", mec="k", ms=8, zorder=6)
    body = SystemArtist(axw, system)
    trail = TrailArtist(axw, color="k", lw=1.2)
    g, r = traj.g, traj.r
    reach = max(sum(getattr(system, "lengths", (1.0,))) * 0.6, 0.5)
    lo, hi = g[:, :2].min(0) - reach, g[:, :2].max(0) + reach
    half = float(max(hi - lo) / 2)
    c = (lo + hi) / 2
    axw.set_xlim(c[0] - half, c[0] + half)
    axw.set_ylim(c[1] - half, c[1] + half)
    axw.set_aspect("equal")
    axw.set_title(system.name)
    idx = np.linspace(0, len(g) - 1, n_frames).round().astype(int)

    def update(k: int) -> list[Artist]:
        i = idx[k]
        body.set(g[i], r[i])
        dot.set_data([r[i, 0]], [r[i, 1]])
        trail.set(g[: i + 1, :2])
        return []

    update(0)
    freeze_layout(fig)   # lay out once: every frame is drawn with the same axes (about 40 % faster)
    return fig, animate(fig, update, len(idx), interval=interval)


def estimates_table(est: Estimates | None, error: str | None = None, rows: tuple[str, ...] = ROWS) -> str:
    """HTML table of the three estimates (columns ``rows``, by default x, y, θ of g(T)), 4 decimals; or the error in red."""
    if est is None:
        return f"<p style='color:darkred'>{html.escape(error or '')}</p>"
    cell = "padding:1px 8px;line-height:1.25"   # compact rows: the panel stays on one screen
    head = "".join(f"<th style='{cell}'>{html.escape(r)}</th>" for r in rows)
    rows = "".join(f"<tr><td style='{cell}'>{name}</td>" + "".join(f"<td style='{cell}'>{(0.0 if abs(v) < 5e-5 else v):+.4f}</td>" for v in vals)
                   + "</tr>" for name, vals in zip(Estimates.NAMES, est.as_array()))
    return f"<table style='font-family:monospace;font-size:13px;margin:2px 0'><tr><th style='{cell}'></th>{head}</tr>{rows}</table>"


class GaitStokesScene(Scene):
    """A gait on one row of a curvature map, and its exact g(T), Stokes estimate and ∫ξ dt as bars.

    Values: ``c1, c2`` (centre), ``a, b`` (sizes), ``tilt``, ``bend`` (see
    :func:`~gm_core.geometry.estimates.shaped_gait`), ``row`` (0, 1, 2: the map's row) and
    ``frame`` (one of :data:`~gm_core.geometry.estimates.FRAMES`). Each ``set`` computes the three
    estimates at the interactive resolution. The bars of each row are that row divided by its
    largest |value| (:func:`~gm_core.geometry.estimates.row_scaled`), so the axis never rescales;
    the numbers are ``self.table`` (HTML, for a widget under the figure) and ``self.estimates``
    (None while the gait is singular or leaves the window, when a flag says so).
    Options: ``system`` (default the low-Reynolds swimmer), ``limits`` (the map's window).
    """

    YLIM: ClassVar[tuple[float, float]] = (-1.1, 1.45)

    def __init__(self, system: LocomotionSystem | None = None, limits: Limits = LIMITS, **options: Any) -> None:
        self.system = system if system is not None else LowReSwimmer()
        self.limits = limits
        self.frames = frames_of(self.system, limits)
        super().__init__(**options)

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        fig, (self.ax, self.axb) = new_figure(1, 2, figsize=(9, 3.3), layout="compressed",
                                              gridspec_kw=dict(width_ratios=[1.1, 1]))
        return fig, [self.ax, self.axb]

    @override
    def decorate(self) -> None:
        _map_axes(self.ax, self.system, self.limits)
        axb = self.axb
        axb.set_xticks(np.arange(3), ROWS)
        # fixed limits, legend above the bars' reach, grid below them: nothing static is ever
        # covered by a moving bar, so blitted frames equal full redraws
        axb.set_xlim(-0.6, 2.6)
        axb.set_ylim(*self.YLIM)
        axb.set_ylabel("each row ÷ its largest |value|")
        axb.set_axisbelow(True)
        axb.yaxis.grid(True, lw=0.6, color="0.8")
        axb.axhline(0.0, color="0.4", lw=0.8, zorder=0.5)
        axb.legend(handles=[Patch(color=c, label=n) for c, n in zip(self.COLORS, Estimates.NAMES)],
                   loc="upper center", ncols=3, handlelength=1.2, columnspacing=1.0)

    COLORS: ClassVar[tuple[str, str, str]] = ("k", PALETTE["vermillion"], PALETTE["grey"])

    @override
    def create(self) -> None:
        self.map = CurvatureMapArtist(self.ax, self.frames["middle link"], 0, limits=self.limits)
        self._map_key: tuple[str, int] = ("middle link", 0)
        self.gait_artist = GaitArtist(self.ax)
        self.flag = SingularFlag(self.ax)
        x = np.arange(3)
        self.bars: dict[str, BarContainer] = {name: self.axb.bar(x + (k - 1) * 0.27, np.zeros(3), 0.25, color=color)
                     for k, (name, color) in enumerate(zip(Estimates.NAMES, self.COLORS))}
        self.estimates: Estimates | None = None
        self.table = ""

    @override
    def set(self, c1: float = 0.0, c2: float = 0.0, a: float = 1.0, b: float = 0.6, tilt: float = 0.78,
            bend: float = 0.0, row: int = 0, frame: str = "middle link") -> None:
        if frame not in self.frames:
            raise ValueError(f"frame must be one of {list(self.frames)}; got {frame!r}")
        if (frame, row) != self._map_key:  # the image is redrawn only when the map changes
            self.map.set(self.frames[frame], row)
            self._map_key = (frame, row)
        gait = shaped_gait(c1, c2, a, b, tilt, bend)
        self.gait_artist.set(gait)
        try:
            est = displacement_estimates(self.frames[frame], gait, interactive=True)
        except SingularShapeError as e:
            self.flag.show("gait leaves the map or is singular")
            heights = np.zeros((3, 3))
            self.estimates, self.table = None, estimates_table(None, str(e))
        else:
            self.flag.hide()
            heights = row_scaled(est.as_array())
            self.estimates, self.table = est, estimates_table(est)
        for bars, hs in zip(self.bars.values(), heights):
            for rect, h in zip(bars, hs):
                rect.set_height(h)


class FrameFieldsScene(Scene):
    """The three rows of −A(r) as fields, in one of three body frames (they straighten and shrink).

    Value: ``frame`` (one of :data:`~gm_core.geometry.estimates.FRAMES`). Arrows keep the
    middle-link frame's scale in every frame, so a smaller field draws shorter arrows; each title
    gives the row's root-mean-square size over the window (``self.rms``, from
    :func:`~gm_core.geometry.estimates.field_rms`). Options: ``system``, ``limits``.
    """

    FIGSIZE = (9, 3.3)
    NCOLS = 3

    def __init__(self, system: LocomotionSystem | None = None, limits: Limits = LIMITS, **options: Any) -> None:
        self.system = system if system is not None else LowReSwimmer()
        self.limits = limits
        self.frames = frames_of(self.system, limits)
        super().__init__(**options)

    @override
    def decorate(self) -> None:
        for i, ax in enumerate(self.axes):
            style_shape_axes(ax, self.system, f"row {ROWS[i]} of −A", limits=self.limits)

    @override
    def create(self) -> None:
        base = self.frames["middle link"]
        self.fields = [ConnectionFieldArtist(ax, base, i, limits=self.limits) for i, ax in enumerate(self.axes)]
        self.caps = [f.cap for f in self.fields]            # the middle-link scale, kept in every frame
        a1, a2, _ = shape_grid(base, self.fields[0].n, self.fields[0].grid_limits)
        self.grid = np.stack([a1, a2], -1)                   # the arrows' shapes
        self.rms: FloatArray | None = None

    @override
    def set(self, frame: str = "middle link") -> None:
        if frame not in self.frames:
            raise ValueError(f"frame must be one of {list(self.frames)}; got {frame!r}")
        system = self.frames[frame]
        self.rms = field_rms(system, self.grid)
        for i, (f, ax, cap) in enumerate(zip(self.fields, self.axes, self.caps)):
            f.set(system, i, cap=cap)
            ax.title.set_text(f"row {ROWS[i]} of −A\nrms |row| = {self.rms[i]:.3f}")


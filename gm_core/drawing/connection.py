"""Connection vector fields (book chapter 3): the rows of the local connection drawn over shape
space, the singular set, a shape cursor, the static figures of chapters 8-9 and the gait animation.

Sign convention of the fields: row i of the local connection is drawn as the vector field
``-A^i(r)`` over shape space, so that ``xi^i = <-A^i, r_dot>`` (3.10): moving the shape along an
arrow gives positive body velocity component i, across it gives none. Undefined values (at a
singular shape) are masked, never passed to matplotlib as NaN.
"""
from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any, ClassVar, cast

import numpy as np
from matplotlib.axes import Axes
from matplotlib.contour import QuadContourSet
from matplotlib.figure import Figure
from matplotlib.gridspec import SubplotSpec
from matplotlib.patches import Rectangle
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike, NDArray
from typing_extensions import Self, override

from gm_core.drawing.motion import SystemArtist, VelocityArtist, draw_system_naive, style_world_axes, system_extent
from gm_core.drawing.toolkit.primitives import SingularFlag
from gm_core.drawing.toolkit.style import MATH_PT, PALETTE, Scene, new_figure, readout, signed
from gm_core.systems import LocomotionSystem
from gm_core.validation import FloatArray

__all__ = ["ROW_LABELS", "math_title", "shape_grid", "connection_field", "ConnectionFieldArtist", "draw_singular_set",
           "ShapeCursorArtist", "style_shape_axes", "singular_contour_grid", "SHAPE_PAD", "connection_fields_figure", "regimes_figure",
           "poor_pictures_figure", "ConnectionFieldScene", "field_grid_axes", "FieldGridScene", "WIDE_SHAPES"]

ROW_LABELS = ("ξx (forward)", "ξy (sideways)", "ξθ (turning)")  # plain text: no mathtext parse cost

#: A window of shape space, ``((lo1, hi1), (lo2, hi2))`` (as a system's ``shape_limits``).
Limits = Sequence[tuple[float, float]]
#: Grid points of a field: ``n`` each way, or ``(n1, n2)`` along alpha1 and alpha2.
GridSize = int | tuple[int, int]


# ------------------------------------------------------------------------------ fields
def shape_grid(system: LocomotionSystem, n: GridSize = 21,
               limits: Limits | None = None) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(a1, a2, r): a grid over the system's shape window, ``n`` points per side (or ``(n1, n2)``:
    n1 along alpha1, n2 along alpha2); r has shape (n2, n1, 2)."""
    (lo1, hi1), (lo2, hi2) = limits or system.shape_limits
    n1, n2 = cast("tuple[int, int]", (n, n) if np.ndim(n) == 0 else n)   # one number: both ways
    a1, a2 = np.meshgrid(np.linspace(lo1, hi1, int(n1)), np.linspace(lo2, hi2, int(n2)), indexing="xy")
    return a1, a2, np.stack([a1, a2], -1)


def connection_field(system: LocomotionSystem, row: int, n: GridSize = 21, limits: Limits | None = None
                     ) -> tuple[FloatArray, FloatArray, np.ma.MaskedArray, np.ma.MaskedArray]:
    """(a1, a2, U, V): the field -A^row over a shape grid, U and V masked where A is undefined.

    Entries below 1e-10 of the largest entry of A on the grid are set to exactly zero, so a row
    that vanishes analytically (e.g. the floating snake's translation rows) is not drawn as
    magnified round-off.
    """
    a1, a2, r = shape_grid(system, n, limits)
    A = system.connection(r)
    finite = np.isfinite(A)
    big = float(np.max(np.abs(A[finite]))) if finite.any() else 0.0
    U = -A[..., row, 0]
    V = -A[..., row, 1]
    with np.errstate(invalid="ignore"):
        tiny = np.hypot(U, V) <= 1e-10 * big
    U = np.where(tiny, 0.0, U)
    V = np.where(tiny, 0.0, V)
    U = np.ma.masked_invalid(U)
    V = np.ma.masked_invalid(V)
    mask = np.ma.getmaskarray(U) | np.ma.getmaskarray(V)
    return a1, a2, np.ma.array(U, mask=mask), np.ma.array(V, mask=mask)


#: Longest arrow of a field on screen, in pixels (the figure standard).
MIN_ARROW_PX = 25.0


def auto_grid(ax: Axes, limits: Limits | None = None, lo: int = 5, hi: int = 15,
              inset: bool = False) -> tuple[int, int]:
    """Grid points ``(n1, n2)`` for a field over ``limits`` ((lo1, hi1), (lo2, hi2)) drawn on
    ``ax`` with equal aspect: the same spacing both ways, at least MIN_ARROW_PX / 0.9 pixels
    (at least ``lo`` points along the longer side, at most ``hi`` along either).

    ``inset=True``: the points are the centres of n cells (see :func:`inset_limits`), so the
    spacing is span / n rather than span / (n - 1)."""
    fig = cast(Figure, ax.figure)   # the course's axes are on figures, never on subfigures
    bbox = ax.get_position(original=True)
    w, h = bbox.width * fig.get_figwidth() * fig.dpi, bbox.height * fig.get_figheight() * fig.dpi
    if limits is None:
        (a0, a1), (b0, b1) = ax.get_xlim(), ax.get_ylim()
    else:
        (a0, a1), (b0, b1) = limits
    pa, pb = abs(a1 - a0) or 1.0, abs(b1 - b0) or 1.0
    unit = min(w / pa, h / pb)                      # pixels per data unit (equal aspect)
    gap = MIN_ARROW_PX / 0.9 + 2                    # pixels between grid points
    extra = 0 if inset else 1                       # n points span n - 1 gaps, or n cells
    n_long = int(np.clip(unit * max(pa, pb) // gap + extra, lo, hi))
    step = max(pa, pb) / (n_long - extra)           # data units between grid points
    n_short = int(np.clip(round(min(pa, pb) / step) + extra, 2, hi))
    return (n_long, n_short) if pa >= pb else (n_short, n_long)


def inset_limits(limits: Limits, n: GridSize) -> tuple[tuple[float, float], ...]:
    """The window ``limits`` shrunk by half a cell on each side, for ``n`` (or ``(n1, n2)``) grid
    points at the centres of equal cells: an arrow of 0.9 spacings drawn about such a point
    (pivot "mid") stays inside the window, never sliced by the axes frame."""
    n1, n2 = cast("tuple[int, int]", (n, n) if np.ndim(n) == 0 else n)   # one number: both ways
    out = []
    for (lo, hi), k in zip(limits, (n1, n2)):
        half = 0.5 * (hi - lo) / int(k)
        out.append((lo + half, hi - half))
    return tuple(out)


class ConnectionFieldArtist:
    """Quiver of one connection row, -A^row(r), over shape space; arrows are clipped for readability.

    Arrows longer than ``clip`` x the median length are shortened to that length (near singular
    shapes the connection grows without bound); undefined arrows are masked. ``factor`` is the
    data-to-arrow scale in use, so the drawn arrow is ``factor * (-A^row)`` unless clipped.
    ``n=None`` picks the grid from the axes' size so that the longest arrow (0.9 grid spacings)
    is at least :data:`MIN_ARROW_PX` long on screen (the figure standard). A row that is zero on
    the whole grid hides its arrows and says "≡ 0" inside the axes (``zero``); a row much smaller
    than the largest entry of A (below ``SMALL`` of it) is still drawn at full length, with a note
    of its enlargement (``enlarged``).
    """

    #: a row whose longest arrow is below this fraction of the largest entry of A is "small"
    SMALL: ClassVar[float] = 0.05
    #: where the "≡ 0" note may sit (its centre, in axes fractions), in order of preference: the
    #: first one whose box crosses no singular shape of the system (:meth:`place_zero_note`)
    NOTE_SPOTS: ClassVar[tuple[tuple[float, float], ...]] = (
        (0.5, 0.86), (0.5, 0.5), (0.5, 0.14), (0.68, 0.3), (0.32, 0.7), (0.68, 0.7), (0.32, 0.3))

    def __init__(self, ax: Axes, system: LocomotionSystem, row: int, n: GridSize | None = None,
                 limits: Limits | None = None, clip: float = 3.0, color: ColorType = "k", **kw: Any) -> None:
        n = auto_grid(ax, limits or system.shape_limits, inset=True) if n is None else n
        self.ax, self.n, self.limits, self.clip, self.row = ax, n, limits, float(clip), row
        #: the grid's own window: cell centres, half a cell inside the shape window
        self.grid_limits = inset_limits(limits or system.shape_limits, n)
        self.system = system
        a1, a2, U, V = connection_field(system, row, n, self.grid_limits)
        self.quiver = ax.quiver(a1, a2, np.zeros_like(a1), np.zeros_like(a1), color=color, angles="xy",
                                scale_units="xy", scale=1.0, width=0.008, headwidth=3.5, headlength=4.5,
                                headaxislength=4.0, pivot="mid", **kw)
        # a row that vanishes on the whole window is said in words, not drawn as a grid of dots;
        # a row much smaller than the largest entry of A is drawn enlarged and says by how much
        note: dict[str, Any] = dict(transform=ax.transAxes, fontsize=9, color="0.25", visible=False, zorder=6,
                    bbox=dict(boxstyle="round,pad=0.25", fc="white", ec="0.6", alpha=0.9))
        self.zero_note = ax.text(*self.NOTE_SPOTS[0], "≡ 0\neverywhere", ha="center", va="center",
                                 multialignment="center", **note)
        self.scale_note = ax.text(0.97, 0.03, "", ha="right", va="bottom", **note)
        self.set(system, row)

    def set(self, system: LocomotionSystem | None = None, row: int | None = None, cap: float | None = None) -> Self:
        """Recompute the field for (system, row) and move the arrows in place (set_UVC).

        ``cap``: the size of -A^row drawn as the longest arrow (0.9 grid spacings); by default
        this field's own (``clip`` x its median, at most its largest). Giving another field's
        ``cap`` draws both to one scale (e.g. one system seen from several body frames); the
        enlargement note is then off, since nothing is enlarged."""
        if system is not None:
            self.system = system
        if row is not None:
            self.row = row
        if self.limits is None:  # the system (its shape window) may have changed
            self.grid_limits = inset_limits(self.system.shape_limits, self.n)
        a1, a2, U, V = connection_field(self.system, self.row, self.n, self.grid_limits)
        A = self.system.connection(np.stack([a1, a2], -1))
        finite = np.isfinite(A)
        biggest = float(np.max(np.abs(A[finite]))) if finite.any() else 0.0
        self.quiver.set_offsets(np.column_stack([a1.ravel(), a2.ravel()]))
        mag = np.ma.sqrt(U ** 2 + V ** 2)
        n1, n2 = a1.shape[1], a1.shape[0]
        spacing = min(np.ptp(a1) / max(n1 - 1, 1), np.ptp(a2) / max(n2 - 1, 1))
        nonzero = np.ma.masked_equal(mag, 0.0)
        med = float(np.ma.median(nonzero)) if nonzero.count() else 0.0
        top = float(mag.max()) if mag.count() else 0.0
        # the longest drawn arrow is 0.9 grid spacings: the largest arrow, or clip x the median
        own = cap is None
        if cap is None:
            cap = min(self.clip * med, top) if med > 0 else (top or 1.0)
        cap = float(cap) if cap > 0 else 1.0
        #: the size of -A^row drawn as the longest arrow
        self.cap = cap
        self.factor = 0.9 * spacing / cap
        shrink = np.ma.where(mag > cap, cap / np.ma.where(mag > 0, mag, 1.0), 1.0)
        self.U, self.V = U, V
        self.quiver.set_UVC(U * shrink * self.factor, V * shrink * self.factor)
        self.clipped = np.ma.filled(mag > cap, False)
        self.zero = not top > 0
        self.quiver.set_visible(not self.zero)
        self.zero_note.set_visible(self.zero)
        if self.zero:
            self.place_zero_note()
        #: how much the arrows are enlarged against the largest entry of A on the grid (None: not)
        self.enlarged = biggest / top if own and top > 0 and top < self.SMALL * biggest else None
        if self.enlarged is not None:
            self.scale_note.set_text(f"small row: arrows enlarged ×{self.enlarged:.2g}")
        self.scale_note.set_visible(self.enlarged is not None)
        return self


    def _note_size(self) -> tuple[float, float]:
        """The "≡ 0" note's box (text and its rounded pad) in fractions of its axes' size, a
        quarter larger than measured: the axes shrink a little when the figure is laid out."""
        from matplotlib.textpath import TextToPath

        note = self.zero_note
        size = float(note.get_fontproperties().get_size_in_points())
        lines = note.get_text().split("\n")
        sizes = [TextToPath().get_text_width_height_descent(t, note.get_fontproperties(), False) for t in lines]
        w = max(s[0] for s in sizes)
        h = size * 1.2 * (len(lines) - 1) + sizes[-1][1]   # 1.2: the default line spacing
        pad = 2 * 0.25 * size + 2          # the box's pad on both sides, and its edge (pt)
        fig = self.ax.get_figure(root=True)
        assert fig is not None                             # an artist of an axes on a figure
        box = self.ax.get_position()
        return (1.25 * (w + pad) / (box.width * fig.get_figwidth() * 72),
                1.25 * (h + pad) / (box.height * fig.get_figheight() * 72))

    def place_zero_note(self) -> tuple[float, float]:
        """Move the "≡ 0" note to the first of :attr:`NOTE_SPOTS` where its box hides no singular
        shape of the system (no sign change of det omega_xi under it, the red lines of
        :func:`draw_singular_set`, which may lie on the window's edge): the note never covers the
        lines that frame the regions of shape space. Returns the spot (axes fractions)."""
        spot = self.NOTE_SPOTS[0]
        if self.system.may_be_singular:
            w, h = self._note_size()
            (x0, x1), (y0, y1) = self.ax.get_xlim(), self.ax.get_ylim()
            a1, a2, d = singular_contour_grid(self.system, 81, ((x0, x1), (y0, y1)), pad=0.0)
            fx, fy = (a1 - x0) / (x1 - x0), (a2 - y0) / (y1 - y0)
            step = 1.0 / 80                                 # one grid cell, so a line between samples is seen
            for cx, cy in self.NOTE_SPOTS:
                under = d[(np.abs(fx - cx) <= w / 2 + step) & (np.abs(fy - cy) <= h / 2 + step)]
                if np.isfinite(under).all() and (np.all(under > 0) or np.all(under < 0)):
                    spot = (cx, cy)
                    break
        self.zero_note.set_position(spot)
        return spot


#: Shape-space windows are drawn this fraction wider on each side, so that singular lines on the
#: window's edge (the kinematic snake's fold lines alpha_i = +-pi) are drawn whole, not half-clipped.
SHAPE_PAD = 0.03


def _padded(limits: Limits, pad: float) -> tuple[tuple[float, float], ...]:
    return tuple((lo - pad * (hi - lo), hi + pad * (hi - lo)) for lo, hi in limits)


def singular_contour_grid(system: LocomotionSystem, n: GridSize = 161, limits: Limits | None = None,
                          pad: float = 2 * SHAPE_PAD) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(a1, a2, d): the scaled det omega_xi over the shape window widened by ``pad`` on each side.

    Sampling beyond the window matters: a singular line on the window's edge (the kinematic
    snake's alpha_i = +-pi, where D = 4 sin((a1 - a2)/2) cos(a1/2) cos(a2/2) for equal links)
    is a sign change of d only when both of its sides are sampled.
    """
    a1, a2, r = shape_grid(system, n, _padded(limits or system.shape_limits, pad))
    return a1, a2, system.singularity(r)


def draw_singular_set(ax: Axes, system: LocomotionSystem, n: GridSize = 161, limits: Limits | None = None,
                      **style: Any) -> QuadContourSet | None:
    """Draw every singular shape (det omega_xi = 0) as red lines; returns the contour set or None.

    The zero contour is taken over a slightly wider window than the axes show (see
    :func:`singular_contour_grid`), so singular lines lying on the window's edge are drawn too.
    """
    if not system.may_be_singular:
        return None
    a1, a2, d = singular_contour_grid(system, n, limits)
    if not (np.nanmin(d) < 0 < np.nanmax(d)):
        return None
    style.setdefault("colors", "crimson")
    style.setdefault("linewidths", 2.0)
    cs = ax.contour(a1, a2, d, levels=[0.0], **style)
    # show the edge lines whole, but not the stubs of the wider sampling window beyond them
    (x0, x1), (y0, y1) = _padded(limits or system.shape_limits, SHAPE_PAD / 3)
    cs.set_clip_path(Rectangle((x0, y0), x1 - x0, y1 - y0, transform=ax.transData))
    return cs


class ShapeCursorArtist:
    """A marker at shape r on a shape-space axes and an arrow for the shape velocity r_dot."""

    def __init__(self, ax: Axes, color: ColorType = PALETTE["green"], arrow_scale: float = 0.5) -> None:
        (self.marker,) = ax.plot([0.0], [0.0], "o", color=color, ms=8, zorder=7)
        self.arrow = ax.quiver([0.0], [0.0], [0.0], [0.0], color=color, angles="xy", scale_units="xy",
                               scale=1.0, width=0.01, zorder=7)
        self.arrow_scale = arrow_scale

    def set(self, r: ArrayLike, r_dot: ArrayLike = (0.0, 0.0)) -> None:
        r = np.asarray(r, float)
        d = np.asarray(r_dot, float) * self.arrow_scale
        self.marker.set_data([r[0]], [r[1]])
        self.arrow.set_offsets([r])
        self.arrow.set_UVC([d[0]], [d[1]])


def _tick_label(v: float) -> str:
    for k, text in ((1.0, "π"), (0.5, "π/2")):
        if np.isclose(abs(v), k * np.pi):
            return "−" + text if v < 0 else text
    return f"{v:.3g}".replace("-", "−")


def _ticks(lo: float, hi: float) -> list[float]:
    """Three ticks: the ends of [lo, hi] and 0 (the straight shape), or the middle if 0 is outside."""
    return [lo, 0.0 if lo < 0.0 < hi else (lo + hi) / 2, hi]


def style_shape_axes(ax: Axes, system: LocomotionSystem, title: str | None = None, limits: Limits | None = None,
                     pad: float = SHAPE_PAD) -> None:
    """Shape-space axes: equal aspect (unless one side is over twice the other), three ticks per axis.

    Few labels keep redraws cheap: the window's ends and 0 (its middle if 0 is outside it).

    The window is ``limits`` (default: the system's ``shape_limits``) widened by ``pad`` of its
    size on each side (``pad=0`` for an image that fills the window)."""
    limits = limits or system.shape_limits
    (lo1, hi1), (lo2, hi2) = limits
    (x0, x1), (y0, y1) = _padded(limits, pad)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ratio = (hi1 - lo1) / (hi2 - lo2)
    ax.set_aspect("equal" if 0.5 <= ratio <= 2.0 else "auto")   # a long thin window fills the axes
    for set_ticks, (lo, hi) in ((ax.set_xticks, (lo1, hi1)), (ax.set_yticks, (lo2, hi2))):
        ticks = _ticks(lo, hi)
        set_ticks(ticks, [_tick_label(v) for v in ticks])
    ax.tick_params(labelsize=8, pad=2)
    ax.set_xlabel(r"$\alpha_1$", labelpad=1, fontsize=MATH_PT)
    ax.set_ylabel(r"$\alpha_2$", labelpad=1, fontsize=MATH_PT)
    if title:
        title = math_title(title)
        ax.set_title(title, fontsize=MATH_PT if "$" in title else None)


#: the row names of :data:`ROW_LABELS` as mathtext, for figure titles (a dropdown keeps the plain ones)
_ROW_MATH = {"ξx": r"$\xi^x$", "ξy": r"$\xi^y$", "ξθ": r"$\xi^\theta$"}


def math_title(text: str) -> str:
    """``text`` with the plain row names of :data:`ROW_LABELS` (``ξx``) written as mathtext (``$\\xi^x$``)."""
    for plain, math in _ROW_MATH.items():
        text = text.replace(plain, math)
    return text


def connection_fields_figure(system: LocomotionSystem, n: GridSize | None = None, figsize: Sequence[float] = (9, 3.3)
                             ) -> tuple[Figure, NDArray[np.object_], list[ConnectionFieldArtist]]:
    """A static figure: the three connection rows of ``system`` as vector fields, singular set in red."""
    fig, axes = new_figure(1, 3, figsize=figsize)
    arts = []
    for i, ax in enumerate(axes):
        style_shape_axes(ax, system, ROW_LABELS[i])
        arts.append(ConnectionFieldArtist(ax, system, i, n=n))
        draw_singular_set(ax, system)
    fig.suptitle(f"{system.name}: the rows of −A(r) as fields")
    return fig, axes, arts


def regimes_figure(systems: Iterable[LocomotionSystem], n: GridSize | None = None,
                   figsize: Sequence[float] = (8.5, 11)) -> tuple[Figure, NDArray[np.object_]]:
    """Static grid: one row per system, one column per connection row (x, y, theta)."""
    systems = list(systems)
    fig, axes = new_figure(len(systems), 3, figsize=figsize, squeeze=False)
    for k, s in enumerate(systems):
        for i in range(3):
            ax = axes[k, i]
            style_shape_axes(ax, s, ROW_LABELS[i] if k == 0 else None)
            if i == 0:
                ax.set_ylabel(f"{s.name}\n" + r"$\alpha_2$", labelpad=1, fontsize=MATH_PT)
            ConnectionFieldArtist(ax, s, i, n=n)
            draw_singular_set(ax, s)
    return fig, axes


def poor_pictures_figure(system: LocomotionSystem, row: int = 2, n: int = 6, figsize: Sequence[float] = (9, 3.4)
                         ) -> tuple[Figure, list[Axes]]:
    """Three pictures of one connection row: a plane field, local contour lines, and arrows.

    (a) at each grid shape r0, a small tilted square: the graph of the linear function
    r_dot -> <-A^row(r0), r_dot>; (b) at each grid shape, three short parallel segments along which
    that linear function is constant, spaced inversely to its gain; (c) the arrow field -A^row.
    Singular grid shapes are skipped. Returns (fig, axes).
    """
    fig, axes = new_figure(1, 3, figsize=figsize)
    axes = list(axes)
    axes[0].remove()
    axes[0] = fig.add_subplot(1, 3, 1, projection="3d")
    # the grid of picture (c)'s ConnectionFieldArtist: cell centres, so (a)-(c) show the same shapes
    a1, a2, U, V = connection_field(system, row, n, inset_limits(system.shape_limits, n))
    (lo1, hi1), (lo2, hi2) = system.shape_limits
    h = 0.35 * min(hi1 - lo1, hi2 - lo2) / n
    big = float(np.ma.max(np.ma.sqrt(U ** 2 + V ** 2))) or 1.0
    s = np.linspace(-h, h, 2)
    S1, S2 = np.meshgrid(s, s)
    for k in np.ndindex(a1.shape):
        if np.ma.is_masked(U[k]) or np.ma.is_masked(V[k]):
            continue
        u, v = float(U[k]), float(V[k])
        axes[0].plot_surface(a1[k] + S1, a2[k] + S2, (u * S1 + v * S2) / big, color=PALETTE["blue"], alpha=0.6,
                             linewidth=0.3, edgecolor="k")
        m = np.hypot(u, v)
        if m > 0:
            t = np.array([-v, u]) / m  # along a level line of the local linear function
            nrm = np.array([u, v]) / m
            gap = min(h, 0.25 * h * big / m)
            for j in (-1, 0, 1):
                c = np.array([a1[k], a2[k]]) + j * gap * nrm
                axes[1].plot([c[0] - h * t[0], c[0] + h * t[0]], [c[1] - h * t[1], c[1] + h * t[1]],
                             color=PALETTE["purple"], lw=1)
    axes[0].set(title="(a) plane field")
    axes[0].set_xlabel(r"$\alpha_1$", fontsize=MATH_PT)
    axes[0].set_ylabel(r"$\alpha_2$", fontsize=MATH_PT)
    axes[0].tick_params(labelsize=7.5, pad=0)
    for ax, title in zip(axes[1:], ["(b) local level lines", "(c) connection vector field"]):
        style_shape_axes(ax, system, title)
    ConnectionFieldArtist(axes[2], system, row, n=n)
    for ax in axes[1:]:
        draw_singular_set(ax, system)
    fig.suptitle(f"{system.name}, row {math_title(ROW_LABELS[row])}", fontsize=MATH_PT)
    return fig, axes


#: a shape window wider than this (width / height) is drawn in the stacked layout
WIDE_SHAPES = 1.6


def field_grid_axes(figsize: Sequence[float] = (6.2, 5.9),
                    limits: Limits | None = None) -> tuple[Figure, list[Axes], Axes]:
    """Three shape-space axes (one per connection row) and a world axes: ``(fig, field_axes, ax)``.

    A square-ish shape window (``limits``, default square) gets a 2 x 2 grid. A wide one (width
    over height above :data:`WIDE_SHAPES`, e.g. the Ackerman car's wheel angle by steering angle)
    would leave squashed fields and large gaps in that grid, so its three fields are stacked in
    the left column with the world to their right, in a figure of about the same size."""
    wide = False
    if limits is not None:
        (x0, x1), (y0, y1) = _padded(limits, SHAPE_PAD)
        wide = (x1 - x0) > WIDE_SHAPES * (y1 - y0)
    if not wide:
        fig, axes = new_figure(2, 2, figsize=figsize)
        return fig, [axes[0, 0], axes[0, 1], axes[1, 0]], axes[1, 1]
    fig, axes = new_figure(3, 2, figsize=(figsize[0], figsize[1] - 0.5),
                           gridspec_kw=dict(width_ratios=[1.15, 1]))
    world = fig.add_subplot(axes[0, 1].get_subplotspec().get_gridspec()[:, 1])
    for ax in axes[:, 1]:
        ax.remove()
    return fig, list(axes[:, 0]), world


class FieldGridScene(Scene):
    """A scene on the grid of :func:`field_grid_axes` (its layout chosen by the system's shape
    window): ``self.field_axes`` (the three connection rows over shape space) and ``self.ax``
    (the world)."""

    field_axes: list[Axes]

    @override
    def make_figure(self) -> tuple[Figure, list[Axes]]:
        system = getattr(self, "system", None)
        fig, self.field_axes, self.ax = field_grid_axes(limits=getattr(system, "shape_limits", None))
        return fig, self.field_axes + [self.ax]


def thin_labels(field_axes: Sequence[Axes], body_ax: Axes, body_labels: bool = True) -> None:
    """Fewer texts, faster redraws: tick labels only on the outer edges of the grid (2 x 2: the
    bottom row and the left column; stacked: the bottom field)."""
    top_left, top_right, bottom_left = field_axes
    spec_left, spec_right = (cast(SubplotSpec, ax.get_subplotspec()) for ax in (top_left, top_right))   # subplots
    stacked = spec_left.colspan == spec_right.colspan
    for ax in (top_left, top_right):
        ax.tick_params(labelbottom=False)
        ax.set_xlabel("")
    if not stacked:
        top_right.tick_params(labelleft=False)
        top_right.set_ylabel("")
    if not body_labels:
        body_ax.tick_params(labelbottom=False, labelleft=False)


def _fmt(xi: ArrayLike) -> str:
    return f"ξ = ({signed(xi)})"


class ConnectionFieldScene(FieldGridScene):
    """The three rows of A as vector fields over shape space, a shape cursor, and the body there.

    Values: ``alpha1``, ``alpha2`` (the shape) and ``alpha1_dot``, ``alpha2_dot`` (its velocity);
    the fourth axes draws the body at that shape with its body velocity xi = -A(r) r_dot (3.10).
    At a singular shape the velocity is hidden and a flag says why. Options: ``system`` (required),
    ``n`` (field grid; default from the axes size), ``velocity_scale``.
    """

    def __init__(self, system: LocomotionSystem, n: GridSize | None = None, velocity_scale: float = 1.0,
                 **options: Any) -> None:
        self.system, self.n, self.velocity_scale = system, n, velocity_scale
        super().__init__(**options)

    @override
    def decorate(self) -> None:
        s = self.system
        for i, ax in enumerate(self.field_axes):
            style_shape_axes(ax, s, f"row {i + 1}: {ROW_LABELS[i]}")
            draw_singular_set(ax, s)
        style_world_axes(self.ax, 1.4 * system_extent(s))   # room below the body for the readout
        self.ax.set_title("body at this shape; arrow: body velocity")
        thin_labels(self.field_axes, self.ax, body_labels=False)

    @override
    def create(self) -> None:
        s = self.system
        self.fields = [ConnectionFieldArtist(ax, s, i, n=self.n, color="0.35") for i, ax in enumerate(self.field_axes)]
        self.cursors = [ShapeCursorArtist(ax) for ax in self.field_axes]
        self.body = SystemArtist(self.ax, s)
        self.vel = VelocityArtist(self.ax, scale=self.velocity_scale)
        self.flag = SingularFlag(self.ax)
        self.text = readout(self.ax, 0.02, 0.02)

    @override
    def set(self, alpha1: float = 0.0, alpha2: float = 0.0, alpha1_dot: float = 1.0, alpha2_dot: float = 0.0) -> None:
        r = np.array([alpha1, alpha2])
        rd = np.array([alpha1_dot, alpha2_dot])
        for c in self.cursors:
            c.set(r, rd)
        self.body.set(np.zeros(3), r)
        self.flag.text.stale = True  # may appear on any change: a moving artist from the first frame
        if self.system.is_singular(r):
            self.xi = np.full(3, np.nan)
            self.vel.set(np.zeros(3), self.xi)
            self.flag.show("singular shape: A undefined")
            self.text.set_text("ξ undefined")
        else:
            self.xi = self.system.body_velocity(r, rd)
            self.flag.hide()
            self.vel.set(np.zeros(3), self.xi)
            self.text.set_text(_fmt(self.xi))

    @override
    def replot(self, alpha1: float = 0.0, alpha2: float = 0.0, alpha1_dot: float = 1.0,
               alpha2_dot: float = 0.0) -> None:
        r = np.array([alpha1, alpha2])
        rd = np.array([alpha1_dot, alpha2_dot])
        for i, ax in enumerate(self.field_axes):
            ax.clear()
            style_shape_axes(ax, self.system, ROW_LABELS[i])
            ConnectionFieldArtist(ax, self.system, i, n=self.n)
            draw_singular_set(ax, self.system)
            ax.plot([r[0]], [r[1]], "o", color=PALETTE["green"])
        self.ax.clear()
        style_world_axes(self.ax, 2.0)
        draw_system_naive(self.ax, self.system, np.zeros(3), r)
        if not self.system.is_singular(r):
            xi = self.system.body_velocity(r, rd)
            self.ax.quiver([0], [0], [xi[0]], [xi[1]], angles="xy", scale_units="xy", scale=1.0)

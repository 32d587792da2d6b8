"""The rendering toolkit every chapter draws with, and the course's figure standard.

* **The figure standard** (see CONTRIBUTING.md, "The figure standard"): figures are made by :func:`new_figure`
  or :func:`figure`, which fix the resolution (:data:`DPI`, one inch = 100 CSS px in JupyterLab,
  inline and in ``to_jshtml`` frames) and cap the width at :data:`MAX_WIDTH_IN` inches (900 px);
  :data:`STYLE` (applied on import) sets font sizes so no text is below :data:`MIN_TEXT_PX`
  pixels, the colour-blind-safe :data:`PALETTE` (Okabe-Ito) as colour cycle, and constrained
  layout is the default so labels are never cut. :class:`PathText` never draws below
  :data:`MIN_TEXT_PT`. Colours: x axis / first component ``PALETTE["x"]``, y ``PALETTE["y"]``,
  theta ``PALETTE["theta"]``; left/right (actions, wheels) ``PALETTE["left"]`` / ``["right"]``.
* **Fast text**: :class:`PathText` draws text as glyph outlines (``TextPath``) in one
  ``PathCollection``; a changing readout costs a few array concatenations, not a font layout.
  Public matplotlib API only; the one fast-text strategy of the course.
* **Arrows**: :class:`ArrowSet` (a PolyCollection, cheap to redraw) and :func:`arrow` (a quiver).
* **Ticks and titles** without matplotlib's Axis machinery: :func:`xticks`, :func:`yticks`,
  :func:`title`, :func:`axis_label`.
* **Axes** (in :mod:`.axes`): :func:`plane`, :func:`square_axes`, :func:`plain_3d`,
  :func:`wire`; figure layouts :func:`axes_row` (one row, 2D or 3D) and :func:`text_panel`.
* **Scenes**: :class:`Scene`, the base of every live drawing: it owns its figure (``FIGSIZE`` /
  ``NCOLS`` / ``MARGINS`` for one row of plain axes); ``set(**values)`` moves artists;
  ``replot(**values)`` is the clear-and-replot baseline of the benchmark.
"""
from __future__ import annotations

import os
import re
from abc import ABC, abstractmethod
from collections.abc import Sequence
from typing import IO, Any, ClassVar, Literal, overload

import matplotlib as mpl
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.axes import Axes
from matplotlib.backend_bases import RendererBase
from matplotlib.collections import LineCollection, PathCollection, PolyCollection
from matplotlib.figure import Figure
from matplotlib.font_manager import FontProperties, findfont, get_font
from matplotlib.layout_engine import ConstrainedLayoutEngine, PlaceHolderLayoutEngine
from matplotlib.path import Path
from matplotlib.quiver import Quiver
from matplotlib.textpath import TextPath
from matplotlib.transforms import Bbox
from matplotlib.transforms import blended_transform_factory as _blend
from matplotlib.typing import ColorType, RcKeyType
from numpy.typing import ArrayLike, NDArray
from typing_extensions import override

from gm_core.drawing.toolkit.blit import hold_pictures_until_view
from gm_core.printing import shown
from gm_core.validation import FloatArray

__all__ = [
    "signed",
    "DPI", "MAX_WIDTH_IN", "MIN_TEXT_PX", "MIN_TEXT_PT", "MATH_PT", "PALETTE", "STYLE", "apply_style",
    "new_figure", "figure", "margins", "freeze_layout", "PathText", "readout", "ArrowSet", "arrow", "set_arrows",
    "title",
    "xticks", "yticks", "axis_label", "axes_row", "text_panel", "Scene",
]

# ------------------------------------------------------------------------- the figure standard
#: Figure resolution: 1 inch = DPI pixels on screen (ipympl, inline and to_jshtml frames).
DPI = 100
#: Widest figure, in inches: MAX_WIDTH_IN * DPI = 900 CSS px fits a laptop's output area.
MAX_WIDTH_IN = 9.0
#: Smallest text on screen, in pixels, and the point size that gives it at DPI.
MIN_TEXT_PX = 10.0
MIN_TEXT_PT = 7.5           # 7.5 pt * 100 / 72 = 10.4 px
#: Smallest size of a text holding mathtext sub- or superscripts (``$T_gL_h$``, ``$\\xi^s$``):
#: matplotlib draws a script at 0.7 of its text's size, 0.7 * 10.5 pt = 10.2 px at DPI. Nested
#: scripts (0.49) cannot meet the standard: write ``$R_g^{-1}$``, not ``$R_{g^{-1}}$``.
MATH_PT = 10.5

#: Okabe & Ito's colour-blind-safe palette, with the roles the course gives its colours.
PALETTE = {
    "black": "#000000", "orange": "#E69F00", "sky": "#56B4E9", "green": "#009E73",
    "yellow": "#F0E442", "blue": "#0072B2", "vermillion": "#D55E00", "purple": "#CC79A7",
    "grey": "#999999",
}
PALETTE.update(x=PALETTE["vermillion"], y=PALETTE["green"], theta=PALETTE["blue"],
               left=PALETTE["blue"], right=PALETTE["orange"])

#: rcParams of the figure standard (applied when gm_core.drawing is imported).
STYLE: dict[RcKeyType, Any] = {
    "figure.dpi": DPI,
    "savefig.dpi": "figure",
    "figure.figsize": (6.0, 4.0),
    "font.size": 9.0,
    "axes.titlesize": 9.5,
    "axes.labelsize": 9.0,
    "xtick.labelsize": 8.0,
    "ytick.labelsize": 8.0,
    "legend.fontsize": 8.0,
    "figure.titlesize": 10.0,
    "axes.prop_cycle": mpl.cycler(color=[PALETTE[k] for k in (  # type: ignore[attr-defined]
        "blue", "orange", "green", "vermillion", "purple", "sky", "yellow", "black")]),
    "image.cmap": "cividis",
    "figure.constrained_layout.h_pad": 0.06,
    "figure.constrained_layout.w_pad": 0.06,
}


def apply_style() -> None:
    """Apply :data:`STYLE` to matplotlib's rcParams (done once on import of gm_core.drawing)."""
    mpl.rcParams.update(STYLE)


apply_style()


def _fit(figsize: Sequence[float]) -> tuple[float, float]:
    w, h = (float(v) for v in figsize)
    if w > MAX_WIDTH_IN:
        h, w = h * MAX_WIDTH_IN / w, MAX_WIDTH_IN
    return (w, h)


class CourseFigure(Figure):
    """The figures :func:`new_figure` makes: a matplotlib ``Figure`` with two differences.

    * ``tight_layout()`` may also be called on a figure made with the toolkit's constrained
      layout. It then lays the figure out tightly, once, exactly as matplotlib does; the
      constrained engine is released first, so that asking for the tight layout is not reported
      as an unexpected change of layout.
    * ``savefig`` of a figure whose layout is frozen (:func:`freeze_layout`) skips the extra
      draw matplotlib makes before saving a figure that has a layout engine (for the engine to
      lay it out): a frozen layout lays out nothing. The file is the same, byte for byte, at
      about three quarters of the cost; every animation frame and every panel's picture is such
      a save.
    """

    @override
    def tight_layout(self, *, pad: float = 1.08, h_pad: float | None = None, w_pad: float | None = None,
                     rect: tuple[float, float, float, float] | None = None) -> None:
        if isinstance(self.get_layout_engine(), ConstrainedLayoutEngine):
            self.set_layout_engine("none")   # a placeholder: positions kept until the tight layout runs
        super().tight_layout(pad=pad, h_pad=h_pad, w_pad=w_pad, rect=rect)

    @override
    def savefig(self, fname: str | os.PathLike[str] | IO[bytes] | IO[str], *, transparent: bool | None = None,
                **kwargs: Any) -> None:
        engine = self.get_layout_engine()
        if (not isinstance(engine, PlaceHolderLayoutEngine) or mpl.rcParams["figure.autolayout"]
                or mpl.rcParams["figure.constrained_layout.use"]):   # there None would mean an engine
            return super().savefig(fname, transparent=transparent, **kwargs)
        self.set_layout_engine(None)
        try:
            return super().savefig(fname, transparent=transparent, **kwargs)
        finally:
            self.set_layout_engine(engine)


#: The layouts :func:`new_figure` accepts: matplotlib's engine names, or None for explicit margins.
Layout = Literal["constrained", "compressed", "tight", "none"] | None


@overload
def new_figure(nrows: Literal[1] = 1, ncols: Literal[1] = 1, *, figsize: Sequence[float] = (6, 4),
               subplot_kw: dict[str, Any] | None = None, layout: Layout = "constrained", dpi: float = DPI,
               squeeze: Literal[True] = True, **kw: Any) -> tuple[Figure, Axes]: ...
@overload
def new_figure(nrows: int = 1, ncols: int = 1, *, figsize: Sequence[float] = (6, 4),
               subplot_kw: dict[str, Any] | None = None, layout: Layout = "constrained", dpi: float = DPI,
               squeeze: Literal[False], **kw: Any) -> tuple[Figure, NDArray[np.object_]]: ...
@overload
def new_figure(nrows: int = 1, ncols: int = 1, *, figsize: Sequence[float] = (6, 4),
               subplot_kw: dict[str, Any] | None = None, layout: Layout = "constrained", dpi: float = DPI,
               squeeze: bool = True, **kw: Any) -> tuple[Figure, Any]: ...
def new_figure(nrows: int = 1, ncols: int = 1, *, figsize: Sequence[float] = (6, 4),
               subplot_kw: dict[str, Any] | None = None, layout: Layout = "constrained", dpi: float = DPI,
               squeeze: bool = True, **kw: Any) -> tuple[Figure, Any]:
    """``(fig, axes)`` made to the figure standard, not auto-displayed (a panel places the canvas).

    The width is capped at :data:`MAX_WIDTH_IN` (the height shrinks with it), the resolution is
    :data:`DPI`, and the layout is constrained unless ``layout=None`` (then give explicit margins
    with :func:`margins`). Under ipympl (``%matplotlib widget``) the toolbar header is hidden and
    no picture is sent before the browser's view is ready (:func:`.blit.hold_pictures_until_view`);
    its hover toolbar, which would float over the tick labels, is switched off.

    ``axes`` is what :func:`matplotlib.pyplot.subplots` returns, and is typed as it types it: one
    ``Axes`` for a 1 x 1 grid, an array of them with ``squeeze=False``, otherwise either (``Any``:
    a single Axes or an array, as the grid's shape decides at run time).
    """
    with plt.ioff():
        fig, ax = plt.subplots(nrows, ncols, figsize=_fit(figsize), subplot_kw=subplot_kw, dpi=dpi,
                               squeeze=squeeze, layout=layout, FigureClass=kw.pop("FigureClass", CourseFigure),
                               **kw)
    canvas = fig.canvas
    if hasattr(canvas, "header_visible") and hasattr(canvas, "footer_visible") and hasattr(canvas, "resizable"):
        canvas.header_visible = False
        canvas.footer_visible = False
        canvas.resizable = False
    if hasattr(canvas, "toolbar_visible"):
        # ipympl's toolbar floats over the figure (absolutely positioned, wherever
        # toolbar_position puts it) and fades in on hover, covering tick labels; the course's
        # figures are fixed pictures (panels are blitted and never panned or zoomed), so it is
        # switched off as ipympl documents: canvas.toolbar_visible = False
        canvas.toolbar_visible = False
    hold_pictures_until_view(fig)   # ipympl: no picture before the browser's view is ready
    return fig, ax


def figure(figsize: Sequence[float] = (6, 4), dpi: float = DPI, layout: Layout = "constrained") -> Figure:
    """An empty figure made like :func:`new_figure`, for mixed 2D/3D layouts (``add_subplot``)."""
    fig, ax = new_figure(figsize=figsize, dpi=dpi, layout=layout)
    ax.remove()
    return fig


def freeze_layout(fig: Figure) -> Figure:
    """Run the figure's layout engine once and keep the result: axes stop moving afterwards.

    A live figure is redrawn by blitting over a cached background; a layout that re-ran on
    every full draw could shift the axes when a title's text changes. Called by every panel
    after its first update.
    """
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    engine = fig.get_layout_engine()
    if engine is not None and not isinstance(engine, PlaceHolderLayoutEngine):
        engine.execute(fig)
        fig.set_layout_engine("none")    # a placeholder engine: keeps the positions, never re-runs
    return fig


def margins(fig: Figure, **kw: float) -> Figure:
    """Explicit margins (``subplots_adjust`` keywords) instead of constrained layout."""
    fig.set_layout_engine(None)
    fig.subplots_adjust(**kw)
    return fig


# --------------------------------------------------------------------------------- fast text
_FAMILIES = {"sans": "DejaVu Sans", "monospace": "DejaVu Sans Mono"}
#: The fonts, alignments and coordinate systems of a :class:`PathText`.
Family = Literal["sans", "monospace"]
HAlign = Literal["left", "center", "right"]
VAlign = Literal["baseline", "bottom", "center", "top"]
Coords = Literal["data", "axes", "figure", "xaxis", "yaxis"]
_PATH_CACHE: dict = {}


def _char(c, size, weight, family="sans"):
    """(vertices in inches, codes, advance in inches) of one character (cached)."""
    key = (c, size, weight, family)
    hit = _PATH_CACHE.get(key)
    if hit is None:
        prop = FontProperties(family=_FAMILIES[family], weight=weight)
        font = get_font(findfont(prop))
        font.set_size(size, 72)
        advance = font.load_char(ord(c)).linearHoriAdvance / 65536.0 / 72.0
        if c.isspace():
            hit = (np.zeros((0, 2)), np.zeros(0, np.uint8), advance)
        else:
            tp = TextPath((0, 0), c, size=size / 72.0, prop=prop)
            hit = (tp.vertices.copy(), tp.codes.copy(), advance)
        _PATH_CACHE[key] = hit
    return hit


#: a ``$...$`` span of a line (``\\$`` is a literal dollar sign, as in matplotlib's mathtext)
_MATH_SPAN = re.compile(r"(?<!\\)\$(.*?)(?<!\\)\$")


def _math(span, size, weight, family="sans"):
    """(vertices in inches, codes, advance in inches) of one ``$...$`` span laid out by
    matplotlib's mathtext (cached: a span is parsed once, whatever numbers surround it)."""
    key = (span, size, weight, family, "math")
    hit = _PATH_CACHE.get(key)
    if hit is None:
        from matplotlib.mathtext import MathTextParser

        prop = FontProperties(family=_FAMILIES[family], weight=weight, size=size)
        tp = TextPath((0, 0), span, size=size / 72.0, prop=prop)
        # the advance as mathtext places what follows the span (parsed at 7200 dpi: the
        # parser rounds its box up to whole pixels)
        advance = MathTextParser("path").parse(span, dpi=7200, prop=prop).width / 7200.0
        hit = (tp.vertices.copy(), tp.codes.copy(), advance)
        _PATH_CACHE[key] = hit
    return hit


def _glyphs(line, size, weight, family="sans"):
    """Outline of one line of text as a Path in inches, left/baseline at (0, 0), and its width.

    Built from cached per-character outlines and advances (no kerning), so changing a numeric
    readout costs a few array concatenations instead of a font layout. A ``$...$`` span is laid
    out as matplotlib mathtext (``"$T_gL_h$ = identity"``), once per distinct span, so a
    readout whose numbers change beside a formula never re-parses the formula.
    """
    key = (line, size, weight, family, "line")
    hit = _PATH_CACHE.get(key)
    if hit is None:
        pieces = []     # (vertices, codes, advance) in order
        spans = list(_MATH_SPAN.finditer(line))
        at = 0
        for m in spans + [None]:
            plain = line[at:m.start() if m else len(line)]
            if spans:
                plain = plain.replace("\\$", "$")
            pieces += [_char(c, size, weight, family) for c in plain]
            if m:
                pieces.append(_math(m.group(0), size, weight, family))
                at = m.end()
        verts, codes, x = [], [], 0.0
        for v, k, adv in pieces:
            if len(v):
                verts.append(v + (x, 0.0))
                codes.append(k)
            x += adv
        if verts:
            hit = (Path(np.concatenate(verts), np.concatenate(codes)), x)
        else:
            hit = (Path(np.zeros((0, 2))), x)
        if len(_PATH_CACHE) > 20000:
            _PATH_CACHE.clear()
        _PATH_CACHE[key] = hit
    return hit


class _FlatPathCollection(PathCollection):
    """A 2D PathCollection that an Axes3D accepts (drawn on top, never depth-sorted)."""

    gm_path_text: PathText   # the PathText drawing this collection (read by layout checks)

    def do_3d_projection(self) -> float:
        return -1e9


class PathText:
    """Text drawn as glyph outlines in one PathCollection: redraws ~10x faster than a Text.

    Matplotlib re-rasterizes every Text (and every tick label) on each draw, which dominates the
    cost of a slider update; glyph outlines are filled by Agg like any other path. ``set_text``
    and ``set_position`` move it in place. ``coords`` is "data", "axes", "figure" or
    "xaxis"/"yaxis" (x in data and y in axes coordinates, or the other way round, for tick
    labels). ``offset`` shifts the text by (dx, dy) points. ``family`` is "sans" or "monospace"
    (aligned numeric columns). Sizes below :data:`MIN_TEXT_PT` are raised to it (the figure
    standard).
    """

    def __init__(self, ax: Axes, x: float, y: float, text: object = "", size: float = 9, color: ColorType = "k",
                 ha: HAlign = "left", va: VAlign = "baseline", coords: Coords = "data", weight: str = "normal",
                 zorder: float = 7, offset: tuple[float, float] = (0.0, 0.0), family: Family = "sans") -> None:
        from matplotlib.transforms import ScaledTranslation

        self.ax = ax
        fig = ax.figure
        if family not in _FAMILIES:
            raise ValueError(f"family must be one of {sorted(_FAMILIES)}; got {family!r}")
        self.size, self.ha, self.va, self.weight = max(float(size), MIN_TEXT_PT), ha, va, weight
        self.family = family
        trans = {"data": ax.transData, "axes": ax.transAxes, "figure": fig.transFigure,
                 "xaxis": _blend(ax.transData, ax.transAxes),
                 "yaxis": _blend(ax.transAxes, ax.transData)}[coords]
        if any(offset):
            trans = trans + ScaledTranslation(offset[0] / 72.0, offset[1] / 72.0, fig.dpi_scale_trans)
        self.collection = _FlatPathCollection([], offsets=np.zeros((0, 2)), offset_transform=trans,
                                              transform=fig.dpi_scale_trans, facecolors=color,
                                              edgecolors="none", zorder=zorder, clip_on=False)
        self.collection.set_in_layout(False)
        self.collection.gm_path_text = self       # lets layout checks find the text of a collection
        ax.add_collection(self.collection, autolim=False)
        self.text: str
        self.xy: FloatArray = np.array([x, y], float)
        self._show(str(text))

    def _paths(self, text):
        lines = text.split("\n")
        step = 1.3 * self.size / 72.0
        glyphs = [_glyphs(line, self.size, self.weight, self.family) if line else (None, 0.0) for line in lines]
        height = step * (len(lines) - 1)
        cap = 0.72 * self.size / 72.0
        dy = {"baseline": 0.0, "bottom": height + 0.22 * self.size / 72.0, "center": height / 2 - cap / 2,
              "top": -cap}[self.va]
        out = []
        for k, (p, w) in enumerate(glyphs):
            if p is None or not len(p.vertices):
                continue
            dx = {"left": 0.0, "center": -w / 2, "right": -w}[self.ha]
            out.append(Path(p.vertices + np.array([dx, dy - k * step]), p.codes))
        return out

    def set_text(self, text: object) -> None:
        text = str(text)
        if text != self.text:
            self._show(text)

    def _show(self, text: str) -> None:
        self.text = text
        paths = self._paths(text)
        self.collection.set_paths(paths)
        self.collection.set_offsets(np.tile(self.xy, (len(paths), 1)))

    def get_text(self) -> str:
        return self.text

    def set_alignment(self, ha: HAlign | None = None, va: VAlign | None = None) -> None:
        """Anchor the text differently (``ha``, ``va`` as in the constructor; None keeps one):
        a readout moving to another corner of its axes keeps its anchor at that corner."""
        ha, va = ha or self.ha, va or self.va
        if (ha, va) != (self.ha, self.va):
            self.ha, self.va = ha, va
            self._show(self.text)

    def set_position(self, xy: ArrayLike) -> None:
        self.xy = np.asarray(xy, float)
        self.collection.set_offsets(np.tile(self.xy, (len(self.collection.get_paths()), 1)))

    def set_visible(self, b: bool) -> None:
        self.collection.set_visible(b)

    def get_visible(self) -> bool:
        return self.collection.get_visible()

    def set_color(self, c: ColorType) -> None:
        self.collection.set_facecolor(c)

    def get_window_extent(self, renderer: RendererBase | None = None) -> Bbox:
        """Bounding box of the drawn glyphs in display pixels (for layout checks)."""
        paths = self.collection.get_paths()
        if not paths:
            return Bbox.null()
        off = self.collection.get_offset_transform().transform(self.xy)
        pts = self.ax.figure.dpi_scale_trans.transform(np.concatenate([p.vertices for p in paths]))
        return Bbox.from_extents(*(pts.min(0) + off), *(pts.max(0) + off))

    @property
    def stale(self) -> bool:
        return self.collection.stale

    @stale.setter
    def stale(self, v: bool) -> None:
        self.collection.stale = v


def readout(ax: Axes, x: float, y: float, s: object = "", size: float = 8, **kw: Any) -> PathText:
    """A monospace :class:`PathText` readout in axes coordinates (numbers that change every frame)."""
    kw.setdefault("coords", "axes")
    kw.setdefault("family", "monospace")
    kw.setdefault("va", "bottom")
    kw.pop("fontsize", None)
    return PathText(ax, x, y, s, size=size, **kw)


def signed(values: ArrayLike, decimals: int = 3) -> str:
    """Numbers as a readout prints them, with their signs: ``"+0.125, -1.000, +0.000"``; rounded
    as shown (gm_core.printing.shown), so a value that is zero up to round-off never reads -0.000."""
    return ", ".join(f"{v:+.{decimals}f}" for v in np.atleast_1d(shown(values, decimals)).tolist())


def title(ax: Axes, text: object = "", size: float = 9) -> PathText:
    """A PathText title centred above ``ax``."""
    return PathText(ax, 0.5, 1.0, text, size=size, ha="center", va="bottom", coords="axes", offset=(0, 4))


def axis_label(ax: Axes, which: Literal["x", "y"], text: object, size: float = 9,
               ticks: Sequence[PathText] = ()) -> PathText:
    """An axis label as PathText, clear of the tick labels (``ticks``: the PathTexts returned by
    :func:`xticks` / :func:`yticks`), so it is never squeezed into them.

    x: centred below the tick labels; y: horizontal, left of the tick labels, centred on the axis.
    """
    if which == "x":
        drop = 5 + 1.35 * max([t.size for t in ticks], default=0.0)
        return PathText(ax, 0.5, 0.0, text, size=size, ha="center", va="top", coords="axes",
                        offset=(0, -(drop + 3)))
    widest = max([max(_glyphs(line, t.size, t.weight, t.family)[1] for line in t.text.split("\n")) for t in ticks],
                 default=0.0) * 72.0
    return PathText(ax, 0.0, 0.5, text, size=size, ha="right", va="center", coords="axes",
                    offset=(-(5 + widest + 5), 0))


def xticks(ax: Axes, values: Sequence[float], labels: Sequence[object], size: float = 8) -> list[PathText]:
    """Tick marks and labels on the x axis without matplotlib's Axis machinery (cheap to redraw)."""
    ax.set_xticks([])
    tr = _blend(ax.transData, ax.transAxes)
    segs = [[(v, 0.0), (v, -0.02)] for v in values]
    ax.add_collection(LineCollection(segs, colors="k", linewidths=0.8, clip_on=False, transform=tr), autolim=False)
    return [PathText(ax, v, 0.0, lab, size=size, ha="center", va="top", coords="xaxis", offset=(0, -5))
            for v, lab in zip(values, labels)]


def yticks(ax: Axes, values: Sequence[float], labels: Sequence[object], size: float = 8) -> list[PathText]:
    """Tick marks and labels on the y axis without matplotlib's Axis machinery (cheap to redraw)."""
    ax.set_yticks([])
    tr = _blend(ax.transAxes, ax.transData)
    segs = [[(0.0, v), (-0.015, v)] for v in values]
    ax.add_collection(LineCollection(segs, colors="k", linewidths=0.8, clip_on=False, transform=tr), autolim=False)
    return [PathText(ax, 0.0, v, lab, size=size, ha="right", va="center", coords="yaxis", offset=(-5, 0))
            for v, lab in zip(values, labels)]


# ------------------------------------------------------------------------------------ arrows
class ArrowSet:
    """``n`` arrows drawn as one PolyCollection in data units, for equal-aspect axes only.

    Cheaper to redraw than a Quiver (whose arrow polygons are rebuilt at every draw). Mirrors
    the bits of the Quiver API the tests read: ``U``, ``V``, ``get_offsets()``, visibility.
    ``width`` is the shaft width as a fraction of the x-range of the axes.
    """

    def __init__(self, ax: Axes, n: int = 1, color: ColorType | Sequence[ColorType] = "k", width: float = 0.008,
                 zorder: float = 6) -> None:
        x0, x1 = ax.get_xlim()
        self.w = width * abs(x1 - x0)
        self.n = n
        # an (n, 7, 2) array, not the Sequence of matplotlib's stub: set_verts takes the array's fast path
        self.poly = PolyCollection(np.zeros((n, 7, 2)), facecolors=color, edgecolors="none",  # type: ignore[arg-type]
                                   zorder=zorder)
        ax.add_collection(self.poly, autolim=False)
        self.set(np.zeros((n, 2)), np.zeros((n, 2)))

    def set(self, origins: ArrayLike, vectors: ArrayLike) -> None:
        P = np.asarray(origins, float).reshape(-1, 2)
        V = np.asarray(vectors, float).reshape(-1, 2)
        self.offsets, self.U, self.V = P, V[:, 0].copy(), V[:, 1].copy()
        L = np.hypot(V[:, 0], V[:, 1])[:, None]
        d = np.divide(V, L, out=np.zeros_like(V), where=L > 0)
        nrm = np.stack([-d[:, 1], d[:, 0]], -1)
        w = self.w
        hl = np.minimum(3.5 * w, 0.6 * L)          # shorter arrows get proportionally smaller heads
        hw = np.minimum(1.6 * w, 0.3 * L + 0.5 * w)
        base = P + d * (L - hl)
        tip = P + V
        verts = np.stack([P - nrm * w / 2, base - nrm * w / 2, base - nrm * hw, tip,
                          base + nrm * hw, base + nrm * w / 2, P + nrm * w / 2], 1)
        self.poly.set_verts(verts)  # type: ignore[arg-type]  # an (n, 7, 2) array: the fast path, see __init__

    def get_offsets(self) -> FloatArray:
        return self.offsets

    def set_visible(self, b: bool) -> None:
        self.poly.set_visible(b)

    def get_visible(self) -> bool:
        return self.poly.get_visible()


def arrow(ax: Axes, color: ColorType | Sequence[ColorType] = "k", width: float = 0.008, zorder: float = 6, n: int = 1,
          **kw: Any) -> Quiver:
    """A quiver of ``n`` arrows in data units, to be moved with :func:`set_arrows`."""
    return ax.quiver(np.zeros(n), np.zeros(n), np.ones(n), np.zeros(n), color=color, angles="xy",
                     scale_units="xy", scale=1.0, width=width, zorder=zorder, **kw)


def set_arrows(q: Quiver | ArrowSet, origins: ArrayLike, vectors: ArrayLike) -> None:
    """Move a quiver or an :class:`ArrowSet`: arrows from ``origins (k, 2)`` along ``vectors (k, 2)``."""
    origins = np.asarray(origins, dtype=float).reshape(-1, 2)
    vectors = np.asarray(vectors, dtype=float).reshape(-1, 2)
    if isinstance(q, ArrowSet):
        q.set(origins, vectors)
        return
    q.set_offsets(origins)
    q.set_UVC(vectors[:, 0], vectors[:, 1])


def axes_row(figsize: Sequence[float], projections: Sequence[str | None],
             **margin_kw: float) -> tuple[Figure, list[Axes]]:
    """A figure with one row of axes, ``projections`` giving each one's kind (None or "3d"); the
    keywords go to :func:`margins`. Returns ``(fig, [axes...])``."""
    fig = figure(figsize=figsize)
    n = len(projections)
    axes = [fig.add_subplot(1, n, k + 1, projection=p) for k, p in enumerate(projections)]
    margins(fig, **margin_kw)
    return fig, axes


def text_panel(ax: Axes) -> Axes:
    """Turn ``ax`` into a blank panel for text and tables: no axis, limits (0, 1) both ways."""
    ax.set_axis_off()
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1)
    return ax


# ------------------------------------------------------------------------------------ figures and scenes
class Scene(ABC):
    """Base of every live drawing: it owns its figure; ``set`` moves, ``replot`` rebuilds.

    Subclasses implement ``make_figure()`` (returns the figure and a list of axes),
    ``decorate()`` (limits, labels, static artists) and ``create()`` (the moving artists), and
    ``set(**values)``. A widget panel pairs the scene with controls (gm_core.widgets).
    A scene with one row of plain axes may instead set ``FIGSIZE`` (and ``NCOLS``, default 1,
    and ``MARGINS``, keywords of :func:`margins`): the default ``make_figure`` then makes them
    (a single axes is also ``self.ax``).
    """

    FIGSIZE: ClassVar[tuple[float, float] | None] = None
    NCOLS: ClassVar[int] = 1
    MARGINS: ClassVar[dict[str, float] | None] = None
    ax: Axes
    #: Set by a live panel (ipympl canvas, with key frames): ``set`` may leave to :meth:`settle`
    #: what need not follow every step of a slider burst, such as a 3-D camera turning with the
    #: point; the key frame after the burst settles it. False (the default): ``set`` does it all.
    settle_later: bool = False

    def __init__(self, **options: Any) -> None:
        self.options: dict[str, Any] = options
        self.fig: Figure
        self.axes: list[Axes]
        self.fig, self.axes = self.make_figure()
        self.decorate()
        self.create()

    def make_figure(self) -> tuple[Figure, list[Axes]]:
        if self.FIGSIZE is None:
            raise NotImplementedError(f"{type(self).__name__} must set FIGSIZE or implement make_figure")
        fig, axes = new_figure(1, self.NCOLS, figsize=self.FIGSIZE)
        if self.MARGINS:
            margins(fig, **self.MARGINS)
        if self.NCOLS > 1:
            return fig, list(axes)
        self.ax = axes
        return fig, [axes]

    def decorate(self) -> None:  # noqa: B027 (an optional hook: most scenes have static artists)
        """Limits, labels and static artists, drawn once (optional; nothing by default)."""

    @abstractmethod
    def create(self) -> None:
        raise NotImplementedError

    def settle(self) -> None:  # noqa: B027 (an optional hook: most scenes leave nothing for later)
        """Do what ``set`` left for the end of a burst (see :attr:`settle_later`); nothing by default."""

    @abstractmethod
    def set(self, *args: Any, **values: Any) -> None:
        """Move the artists to ``values``; each scene names its own keywords (and a few take
        positional values). ``*args: Any, **values: Any`` is the typing's "any signature", so a
        scene's ``set(theta: float = 0.3)`` is checked as an override of this one."""
        raise NotImplementedError

    def replot(self, *args: Any, **values: Any) -> None:
        """The naive baseline: clear every axes, draw everything again, then set the values.

        It takes the keywords of the scene's ``set``, by keyword only; the signature is ``set``'s
        "any signature", so that a scene's own ``replot`` may name them."""
        if args:
            raise TypeError(f"{type(self).__name__}.replot takes its values by keyword")
        for ax in self.axes:
            ax.clear()
        self.decorate()
        self.create()
        self.set(**values)

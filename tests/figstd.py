"""The course's figure standard (CONTRIBUTING.md, issue #12 point 1), measured on a matplotlib figure.

:func:`check_figure` draws a figure once with a recording Agg renderer that measures and does not
rasterise (so it sees exactly the texts that are drawn: tick labels outside the view limits,
empty and hidden texts are not) and returns one line per breach, naming the figure (``where``)
and the text:

* the figure is at most ``MAX_WIDTH_PX`` (900) CSS px wide: width in inches x dpi (an ipympl canvas
  is laid out at ``fig.dpi`` CSS px per inch; a jshtml frame is an image of that many pixels);
* no text is smaller than ``MIN_TEXT_PX`` (10) px: font size in points x dpi / 72, and for
  mathtext its smallest glyph (matplotlib draws sub- and superscripts at 0.7 of the size, so
  ``$T_gL_h$`` at 9 pt has 8.75 px subscripts: too small);
* no text holds formula markup outside mathtext (``T_pS``, ``ξ^``, ``g_{a,b}``: it reaches the
  student raw; write ``$T_p\\mathbb{S}^1$``);
* no text is sliced by the figure edge: its window extent lies inside the figure;
* no two texts overlap (tick labels, axis labels, titles, legends, readouts), beyond
  ``OVERLAP_TOL_PX`` in both directions, and no axis label sits in the row (x) or column (y) of
  its own tick labels (2D axes);
* readouts (texts placed on an axes with ``ax.text``/``ax.annotate`` and anchored inside it) lie
  wholly inside their axes (a caption anchored outside its axes is judged as any other text);
* every vector field (a quiver, or a collection marked ``gm_arrow_set`` like the toolkit's
  ArrowSet, of ``MIN_FIELD_ARROWS`` arrows or more; an SE(2) frame's two arrows are not a field)
  has a longest arrow of at least ``MIN_ARROW_PX`` (25) px.

Texts drawn as glyph outlines by gm_core.drawing.toolkit.PathText (found through the
``gm_path_text`` attribute of their PathCollection) are measured like Text artists.

Used by tests/test_figure_standard.py (every notebook's figures, every panel, animation frames),
tools/screenshots.py and the browser tests. :class:`FrameChecker` is a matplotlib movie writer
that runs the check on every frame an animation renders (``anim.save(..., writer=FrameChecker())``).
"""
from __future__ import annotations

import gc
import itertools
import re
import types

import numpy as np
from matplotlib import cbook
from matplotlib.animation import AbstractMovieWriter
from matplotlib.backends.backend_agg import RendererAgg
from matplotlib.font_manager import FontProperties
from matplotlib.mathtext import MathTextParser
from matplotlib.quiver import Quiver
from matplotlib.text import Text

MAX_WIDTH_PX = 900
MIN_TEXT_PX = 10.0
MIN_ARROW_PX = 25.0
#: a quiver with at least this many arrows is a vector field (frames are 2 arrows, not judged)
MIN_FIELD_ARROWS = 3
OVERLAP_TOL_PX = 1.0
EDGE_TOL_PX = 0.5
#: padding of ``bbox_inches="tight"`` (savefig.pad_inches), used for ``%matplotlib inline`` figures
TIGHT_PAD_IN = 0.1

__all__ = ["check_figure", "breaches", "raw_formula", "FrameChecker", "figure_name", "MAX_WIDTH_PX", "MIN_TEXT_PX", "MIN_ARROW_PX"]


def _draws_nothing(*args, **kwargs):
    return None


class _DrawsNothing:
    """A renderer's drawing method that puts no pixel down. A data descriptor, so it stays in
    place where RendererAgg binds its C++ drawing methods to each instance (``draw_markers``,
    ``draw_image``, ...): assigning to it is ignored."""

    def __get__(self, obj, objtype=None):
        return _draws_nothing

    def __set__(self, obj, value):
        pass


class _RecordingRenderer(RendererAgg):
    """An Agg renderer that remembers every Text artist it draws, with its extent at that moment,
    and rasterises nothing.

    matplotlib hands ``draw_text`` the artist only for one-line texts, so each Text gets a
    temporary gid (public ``set_gid``) that ``Text.draw`` passes to ``open_group``: the renderer
    then knows which text it is drawing, one line or several, mathtext included. Texts are
    measured with Agg's own font metrics (``get_text_width_height_descent``, inherited), as the
    figure is shown; no pixel is ever read, so the drawing methods draw nothing (a fifth of the
    checks' time over the book and the solutions went into rasterising lines, images and glyphs
    nobody looked at)."""

    PREFIX = "gm-figstd-text-"
    draw_path = draw_markers = draw_path_collection = draw_image = _DrawsNothing()
    draw_gouraud_triangles = draw_quad_mesh = _DrawsNothing()

    def __init__(self, width, height, dpi, by_gid):
        super().__init__(width, height, dpi)
        self.by_gid = by_gid
        self.texts: list[tuple[Text, object]] = []
        self._seen: set[int] = set()
        self._stack: list[Text | None] = []

    def open_group(self, s, gid=None):
        self._stack.append(self.by_gid.get(gid) if s == "text" else None)
        return super().open_group(s, gid)

    def close_group(self, s):
        if self._stack:
            self._stack.pop()
        return super().close_group(s)

    def draw_text(self, gc, x, y, s, prop, angle, ismath=False, mtext=None):
        t = mtext if mtext is not None else next((a for a in reversed(self._stack) if a is not None), None)
        if t is not None and id(t) not in self._seen and str(s).strip():
            self._seen.add(id(t))
            # the extent is taken now: a 3D text is at its projected position only while drawn
            self.texts.append((t, t.get_window_extent(self).frozen()))


def _label(t, limit: int = 40) -> str:
    s = " ".join((t if isinstance(t, str) else t.get_text()).split())
    return repr(s if len(s) <= limit else s[: limit - 1] + "…")


_MATH = MathTextParser("path")
_SMALLEST: dict = {}


def _smallest_pt(text: str, size: float, prop=None, parse_math: bool = True) -> float:
    """Point size of the smallest glyph ``text`` is drawn with at font size ``size``: ``size``
    itself, or for a line holding mathtext (``$...$``, laid out per line as matplotlib does) its
    smallest sub- or superscript, measured by matplotlib's own mathtext parser."""
    smallest = float(size)
    if not parse_math:
        return smallest
    for line in str(text).split("\n"):
        if not cbook.is_math_text(line):
            continue
        key = (line, float(size), None if prop is None else hash(prop))
        hit = _SMALLEST.get(key)
        if hit is None:
            fp = (prop.copy() if prop is not None else FontProperties())
            fp.set_size(size)
            try:
                glyphs = _MATH.parse(line, 72, fp).glyphs
                hit = min((float(g[1]) for g in glyphs), default=float(size))
            except ValueError:  # not valid mathtext: matplotlib would fail to draw it anyway
                hit = float(size)
            _SMALLEST[key] = hit
        smallest = min(smallest, hit)
    return smallest


# formula markup that mathtext renders only between $...$ (as tests/test_notebook_text.py for markdown):
# ``_{``, any ``^``, a backslash command, or a one-letter name with a subscript (``T_p``, ``g_1``)
_RAW = re.compile(r"_\{|\^|\\[A-Za-z]+|(?<![\w/.-])(?:Ad|ad|[A-Za-zα-ωΑ-Ω])_[A-Za-z0-9α-ωΑ-Ω{]")
_IN_MATH = re.compile(r"(?<!\\)\$.+?(?<!\\)\$")


def raw_formula(text: str) -> str | None:
    """The first piece of formula markup in ``text`` outside mathtext (None: there is none)."""
    m = _RAW.search(_IN_MATH.sub(" ", str(text)))
    return m.group(0) if m else None


def _roles(fig) -> dict[int, tuple[str, object]]:
    """id(text) -> (what it is, its axes) for the texts matplotlib makes for every axes: tick
    labels, axis labels, titles, readouts (``ax.text``/``ax.annotate``); anything else is "text"."""
    roles: dict[int, tuple[str, object]] = {}
    for ax in fig.get_axes():
        for name in ("xaxis", "yaxis", "zaxis"):
            axis = getattr(ax, name, None)
            if axis is None:
                continue
            roles[id(axis.label)] = (f"{name[0]}-axis label", ax)
            roles[id(axis.get_offset_text())] = (f"{name[0]}-axis offset text", ax)
            for tick in itertools.chain(axis.get_major_ticks(), axis.get_minor_ticks()):
                roles[id(tick.label1)] = (f"{name[0]} tick label", ax)
                roles[id(tick.label2)] = (f"{name[0]} tick label", ax)
        for t in (ax.title, getattr(ax, "_left_title", None), getattr(ax, "_right_title", None)):
            if t is not None:
                roles[id(t)] = ("title", ax)
        for t in ax.texts:
            roles[id(t)] = ("readout", ax)
    sup = getattr(fig, "_suptitle", None)
    if sup is not None:
        roles[id(sup)] = ("suptitle", None)
    return roles


def _owner(fig) -> str | None:
    """Class name of the object holding ``fig`` as its ``.fig`` attribute: a Panel (it has
    ``controls``) before a scene, if any."""
    found = []
    for d in gc.get_referrers(fig):
        if isinstance(d, (type, types.ModuleType, AbstractMovieWriter)) or type(d).__module__.startswith("matplotlib"):
            continue
        if not isinstance(d, dict):  # an instance whose attributes live inline (Python >= 3.11)
            if getattr(d, "fig", None) is fig:
                found.append(d)
            continue
        if d.get("fig") is fig:
            found += [o for o in gc.get_referrers(d)
                      if getattr(o, "__dict__", None) is d and not isinstance(o, types.ModuleType)]
    if not found:
        return None
    return type(next((o for o in found if hasattr(o, "controls")), found[0])).__name__


def figure_name(fig) -> str:
    """A short human name for a figure: the panel holding it, its suptitle or first axes title,
    else its label or number."""
    owner = _owner(fig)
    sup = getattr(fig, "_suptitle", None)
    title = ""
    if sup is not None and sup.get_text().strip():
        title = sup.get_text()
    else:
        title = next((ax.get_title() for ax in fig.axes if ax.get_title().strip()), "")
    title = " ".join(title.split())
    title = title if len(title) <= 50 else title[:49] + "…"
    if owner and title:
        return f"{owner}: {title}"
    return owner or title or fig.get_label() or f"figure {getattr(fig, 'number', '?')}"


def _draw(fig):
    """Lay the figure out and draw it into a recording renderer; returns the renderer."""
    w, h = fig.get_size_inches() * fig.dpi
    texts = fig.findobj(Text)
    saved = [(t, t.get_gid()) for t in texts]
    by_gid = {}
    for t in texts:
        gid = f"{_RecordingRenderer.PREFIX}{id(t)}"
        by_gid[gid] = t
        t.set_gid(gid)
    renderer = _RecordingRenderer(int(round(w)), int(round(h)), fig.dpi, by_gid)
    # A live panel blits: its moving artists are "animated", which a plain draw skips. They are
    # measured too (as the student sees them), and the figure's own draw_event listeners (the
    # blitter's background cache) are not told about this off-screen draw.
    animated = fig.findobj(lambda a: a.get_animated())
    for a in animated:
        a.set_animated(False)
    try:
        with fig.canvas.callbacks.blocked(signal="draw_event"):
            fig.draw(renderer)
    finally:
        for t, gid in saved:
            t.set_gid(gid)
        for a in animated:
            a.set_animated(True)
    return renderer


def _labels_in_tick_rows(boxes, roles) -> list[str]:
    """An x (y) axis label must sit below/above (beside) its tick labels, never in their row
    (column), where it reads as one more tick: "0  longitude λ"."""
    out = []
    by_axes: dict[int, dict[str, list]] = {}
    for t, desc, bb in boxes:
        role, ax = roles.get(id(t), ("text", None))
        if ax is None or getattr(ax, "name", "") == "3d" or role[:1] not in "xy":
            continue
        slot = by_axes.setdefault(id(ax), {})
        if role.endswith("tick label"):
            slot.setdefault(role[0] + "ticks", []).append(bb)
        elif role.endswith("-axis label"):
            slot.setdefault(role[0] + "label", []).append((desc, bb))
    for slot in by_axes.values():
        for axis, lo, hi in (("x", "y0", "y1"), ("y", "x0", "x1")):
            ticks = slot.get(axis + "ticks", [])
            for desc, bb in slot.get(axis + "label", []):
                for tb in ticks:
                    shared = min(getattr(bb, hi), getattr(tb, hi)) - max(getattr(bb, lo), getattr(tb, lo))
                    if shared > OVERLAP_TOL_PX:
                        where = "row" if axis == "x" else "column"
                        out.append(f"{desc} sits in the {where} of its tick labels (reads as one more tick)")
                        break
    return out


def _path_texts(fig) -> list[tuple]:
    """Texts drawn as glyph outlines (gm_core.drawing.toolkit.PathText: a PathCollection that
    carries its PathText as ``gm_path_text``), as items of :func:`breaches`. Call after drawing.
    One anchored strictly inside its axes is a readout; titles, ticks and labels sit outside."""
    out = []
    for coll in fig.findobj(lambda a: hasattr(a, "gm_path_text")):
        pt = coll.gm_path_text
        ax = getattr(pt, "ax", None)
        if not coll.get_visible() or (ax is not None and not ax.get_visible()):
            continue
        text = pt.get_text() or ""
        if not text.strip() or not len(coll.get_paths()):
            continue
        bb = pt.get_window_extent()
        anchor = tuple(coll.get_offset_transform().transform(np.asarray(pt.xy, float)))
        role = "text"
        if ax is not None and _inside(anchor, ax.get_window_extent(), tol=-0.5):
            role = "readout"
        out.append((pt, f"{role} (PathText)" if role == "text" else role, ax, text,
                    _smallest_pt(text, float(getattr(pt, "size", 0.0))), bb, anchor))
    return out


def _anchor(t: Text, bb) -> tuple[float, float]:
    """The display point a text is aligned to (its ha/va corner of the drawn extent)."""
    ha, va = t.get_horizontalalignment(), t.get_verticalalignment()
    x = {"left": bb.x0, "right": bb.x1}.get(ha, (bb.x0 + bb.x1) / 2)
    y = {"top": bb.y1, "bottom": bb.y0, "baseline": bb.y0}.get(va, (bb.y0 + bb.y1) / 2)
    return x, y


def _inside(point, box, tol: float = 1.0) -> bool:
    x, y = point
    return box.x0 - tol <= x <= box.x1 + tol and box.y0 - tol <= y <= box.y1 + tol


def _arrow_set_longest_px(coll) -> float | None:
    """Longest arrow, in display px, of an ArrowSet-like collection (``gm_arrow_set`` with
    ``offsets``, ``U``, ``V`` in data units); None when every arrow is zero."""
    a = coll.gm_arrow_set
    P = np.asarray(a.get_offsets(), float).reshape(-1, 2)
    V = np.stack([np.asarray(a.U, float), np.asarray(a.V, float)], -1)
    if not len(P) or not np.any(np.hypot(V[:, 0], V[:, 1]) > 0):
        return None
    trans = coll.axes.transData if coll.axes is not None else coll.get_transform()
    d = trans.transform(P + V) - trans.transform(P)
    return float(np.nanmax(np.hypot(d[:, 0], d[:, 1])))


def _quiver_longest_px(q: Quiver) -> float | None:
    """Length in display px of the longest arrow of a drawn quiver (None when it has no arrows)."""
    paths = q.get_paths()
    if not paths:
        return None
    trans = q.get_transform()
    best = 0.0
    for p in paths:
        v = trans.transform(p.vertices) if len(p.vertices) else p.vertices
        if len(v) < 2 or not np.all(np.isfinite(v)):
            continue
        d = v[:, None, :] - v[None, :, :]
        best = max(best, float(np.sqrt((d ** 2).sum(-1)).max()))
    uv = np.hypot(np.ma.filled(q.U, 0.0), np.ma.filled(q.V, 0.0))
    # matplotlib keeps a masked arrow's mask in ``Umask`` and fills its U, V with 1: not an arrow
    uv = np.where(np.ma.getmaskarray(np.ma.array(uv, mask=np.broadcast_to(q.Umask, uv.shape))), 0.0, uv)
    if not np.any(uv > 0):
        return None  # every arrow is zero (a field at rest): nothing to judge
    return best


def check_figure(fig, where: str = "", tight: bool = False) -> list[str]:
    """Every breach of the figure standard in ``fig``, one message each (empty list: it complies).

    ``tight=True`` measures the figure as ``%matplotlib inline`` shows it: saved with
    ``bbox_inches="tight"`` (0.1 in padding), so its width is that of its drawn contents and no
    text can be cut by the edge. Each message reads ``"<where>: figure '<name>': <what>"``."""
    found = breaches(fig, tight=tight)
    if not found:
        return []   # naming the figure searches the whole heap for its owner: only for a message
    name = (f"{where}: " if where else "") + f"figure {figure_name(fig)!r}"
    return [f"{name}: {m}" for m in found]


def breaches(fig, tight: bool = False) -> list[str]:
    """The breaches of ``fig`` without the figure's name (see :func:`check_figure`)."""
    out = []
    dpi = fig.dpi
    renderer = _draw(fig)
    if tight:
        width_px = (fig.get_tightbbox(renderer).width + 2 * TIGHT_PAD_IN) * dpi
        how = "as shown inline, tight bounding box"
    else:
        width_px = fig.get_figwidth() * dpi
        how = f"{fig.get_figwidth():.2f} in x {dpi:.0f} dpi"
    if width_px > MAX_WIDTH_PX + 0.5:
        out.append(f"{width_px:.0f} px wide (> {MAX_WIDTH_PX} px: {how})")
    roles = _roles(fig)
    W, H = renderer.width, renderer.height
    items = []  # (object, role, axes, text, size in pt, extent, anchor)
    for t, bb in renderer.texts:
        if t.get_visible():
            role, ax = roles.get(id(t), ("text", None))
            size = t.get_fontsize()
            if not t.get_usetex():
                size = _smallest_pt(t.get_text(), size, t.get_fontproperties(), t.get_parse_math())
            items.append((t, role, ax, t.get_text(), size, bb, _anchor(t, bb)))
    items += _path_texts(fig)
    boxes = []
    for t, role, ax, text, size, bb, anchor in items:
        px = size * dpi / 72.0
        desc = f"{role} {_label(text)}"
        raw = raw_formula(text)
        if raw:
            out.append(f"{desc} holds raw formula markup {raw!r} outside $...$ (write it as mathtext)")
        if px < MIN_TEXT_PX - 1e-6:
            scripts = " in its smallest mathtext script" if "$" in str(text) else ""
            out.append(f"{desc} is {px:.1f} px{scripts} (< {MIN_TEXT_PX:.0f} px)")
        if not np.all(np.isfinite([bb.x0, bb.y0, bb.x1, bb.y1])):
            continue
        cut = {"left": -bb.x0, "right": bb.x1 - W, "bottom": -bb.y0, "top": bb.y1 - H}
        cut = {k: v for k, v in cut.items() if v > EDGE_TOL_PX}
        if cut and not tight:
            out.append(f"{desc} is cut by the figure edge ("
                       + ", ".join(f"{k} by {v:.0f} px" for k, v in cut.items()) + ")")
        ab = ax.get_window_extent(renderer) if role == "readout" else None
        if ab is not None and _inside(anchor, ab):  # anchored outside: a caption, not a readout
            past = {"left": ab.x0 - bb.x0, "right": bb.x1 - ab.x1, "bottom": ab.y0 - bb.y0, "top": bb.y1 - ab.y1}
            past = {k: v for k, v in past.items() if v > EDGE_TOL_PX}
            if past:
                out.append(f"{desc} runs past its axes ("
                           + ", ".join(f"{k} by {v:.0f} px" for k, v in past.items()) + ")")
        boxes.append((t, desc, bb))
    for (_t1, d1, b1), (_t2, d2, b2) in itertools.combinations(boxes, 2):
        ox = min(b1.x1, b2.x1) - max(b1.x0, b2.x0)
        oy = min(b1.y1, b2.y1) - max(b1.y0, b2.y0)
        if ox > OVERLAP_TOL_PX and oy > OVERLAP_TOL_PX:
            out.append(f"{d1} overlaps {d2} ({ox:.0f} x {oy:.0f} px)")
    out += _labels_in_tick_rows(boxes, roles)
    fields = [(q, _quiver_longest_px) for q in fig.findobj(Quiver)
              if q.get_visible() and len(q.get_paths()) >= MIN_FIELD_ARROWS]
    fields += [(c, _arrow_set_longest_px) for c in fig.findobj(lambda a: hasattr(a, "gm_arrow_set"))
               if c.get_visible() and len(c.gm_arrow_set.U) >= MIN_FIELD_ARROWS]
    for i, (q, measure) in enumerate(fields, 1):
        longest = measure(q)
        if longest is not None and longest < MIN_ARROW_PX:
            which = f"vector field {i} of {len(fields)}" if len(fields) > 1 else "vector field"
            out.append(f"{which} ({len(q.get_paths())} arrows): longest arrow {longest:.1f} px "
                       f"(< {MIN_ARROW_PX:.0f} px, direction unreadable)")
    return out


class FrameChecker(AbstractMovieWriter):
    """A movie writer that writes nothing and checks every frame: ``anim.save('x', writer=FrameChecker())``.

    ``breaches`` collects the messages of every frame (each message once, with its first frame)."""

    def __init__(self, where: str = "", every: int = 1):
        super().__init__(fps=5)
        self.where = where
        self.every = max(1, int(every))
        self.breaches: list[str] = []
        self._seen: set[str] = set()
        self._n = 0

    def setup(self, fig, outfile, dpi=None):
        super().setup(fig, outfile, dpi=dpi)

    def grab_frame(self, **savefig_kwargs):
        k = self._n
        self._n += 1
        if k % self.every:
            return
        for msg in breaches(self.fig):
            if msg not in self._seen:
                self._seen.add(msg)
                where = f"{self.where} frame {k}".strip()
                self.breaches.append(f"{where}: figure {figure_name(self.fig)!r}: {msg}")

    def finish(self):
        pass

    @property
    def frames(self) -> int:
        return self._n

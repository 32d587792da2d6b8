"""Chapter 1 drawings: configuration spaces, SE(2) actions, velocities, geodesics, exp.

Each figure of the chapter-1 notebooks is a *scene*: a class that builds its figure and artists
once (``__init__``), moves them in place for new parameter values (``set(**values)``), and, for
the latency benchmark only, offers the clear-and-replot baseline (``replot(**values)``). The
widget panels of :mod:`gm_core.widgets.ch1` wrap these scenes with sliders; the headless tests
read the artists' data back and compare with gm_core's mathematics.

Anything singular (the pole of a latitude/longitude chart, an infinite helix diameter) is shown
with a :class:`~gm_core.drawing.base.SingularFlag` and the affected artist is hidden: no NaN or
inf is ever handed to matplotlib.
"""
from __future__ import annotations

from math import factorial

import numpy as np
from matplotlib.collections import LineCollection, PathCollection, PolyCollection
from matplotlib.font_manager import FontProperties
from matplotlib.path import Path
from matplotlib.textpath import TextPath
from mpl_toolkits.mplot3d import Axes3D  # noqa: F401  (registers the 3d projection)
from mpl_toolkits.mplot3d.art3d import Line3DCollection

from ..groups import ALL_GROUPS, S1, SE2, R2xS1, RPlus
from .base import BodyArtist, FrameArtist, SingularFlag, TrailArtist, animate, new_figure

__all__ = [
    "Scene", "figure", "PathText", "ArrowSet", "AXIOMS", "torus_xyz", "sphere_xyz", "cylinder_xyz", "wrap_segments",
    "configuration_space_gallery", "flattened_views", "TorusPathScene", "LoopsScene",
    "PoleChartScene", "chart_speed",
    "axiom_residuals", "GroupAxiomsScene", "SlideRuleScene", "CircleIsoScene",
    "LeftRightActionScene", "ForwardLeftScene", "BodyPointsScene",
    "FIELDS", "rk4_curve", "VectorFieldScene", "LiftedScalarScene", "LiftedSE2Scene",
    "point_velocities", "VelocityScene", "AdjointScene",
    "HelixScene", "helix_geometry", "PuckArcScene", "puck_vs_arc_animation", "RPlusGeodesicScene",
    "ExpFourWaysScene", "binomial_table",
]

TWO_PI = 2.0 * np.pi
BODY = BodyArtist.triangle(0.35)


# ====================================================================================== helpers
def figure(figsize=(6, 4), dpi=None):
    """An empty figure made like :func:`new_figure` (not auto-displayed), for mixed 2D/3D layouts."""
    fig, ax = new_figure(figsize=figsize)
    ax.remove()
    if dpi:
        fig.set_dpi(dpi)
    return fig


def _plain_3d(ax, lim=None, labels=("x", "y", "z"), axes_lines=True):
    """Make a 3D axes cheap to draw: no panes, ticks or grid; three labelled axis lines instead."""
    ax.set_axis_off()
    if lim is not None:
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_zlim(-lim, lim)
    if axes_lines:
        L = lim if lim is not None else 1.0
        segs = [[(-L, 0, 0), (L, 0, 0)], [(0, -L, 0), (0, L, 0)], [(0, 0, -L), (0, 0, L)]]
        ax.add_collection3d(Line3DCollection(segs, colors="0.55", linewidths=0.8))
        for k, name in enumerate(labels):
            pos = [0.0, 0.0, 0.0]
            pos[k] = 1.08 * L
            ax.text(*pos, name, fontsize=8, color="0.3")  # three short labels


def _MaxN(n):
    from matplotlib.ticker import MaxNLocator

    return MaxNLocator(n)


def _plane(ax, lim=2.5, grid=True, labels=True, step=1.0):
    """Square plot window for SE(2) pictures: a unit grid drawn as one collection, no tick labels.

    (Tick labels are the most expensive thing matplotlib redraws; the grid spacing is one unit.)
    """
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    if grid:
        k = np.arange(np.ceil(-lim / step), np.floor(lim / step) + 1) * step
        segs = [[(v, -lim), (v, lim)] for v in k] + [[(-lim, v), (lim, v)] for v in k]
        colors = ["0.6" if v == 0 else "0.88" for v in k] * 2
        ax.add_collection(LineCollection(segs, colors=colors, linewidths=0.7, zorder=0))


def _arrow(ax, color="k", width=0.008, zorder=6, n=1, **kw):
    """A quiver of ``n`` arrows in data units, to be moved with set_offsets / set_UVC."""
    return ax.quiver(np.zeros(n), np.zeros(n), np.ones(n), np.zeros(n), color=color, angles="xy",
                     scale_units="xy", scale=1.0, width=width, zorder=zorder, **kw)


def _set_arrows(q, origins, vectors):
    origins = np.asarray(origins, dtype=float).reshape(-1, 2)
    vectors = np.asarray(vectors, dtype=float).reshape(-1, 2)
    if isinstance(q, ArrowSet):
        q.set(origins, vectors)
        return
    q.set_offsets(origins)
    q.set_UVC(vectors[:, 0], vectors[:, 1])


class ArrowSet:
    """``n`` arrows drawn as one PolyCollection in data units, for equal-aspect axes only.

    Cheaper to redraw than a Quiver (whose arrow polygons are rebuilt at every draw). Mirrors
    the bits of the Quiver API the tests read: ``U``, ``V``, ``get_offsets()``, visibility.
    ``width`` is the shaft width as a fraction of the x-range of the axes.
    """

    def __init__(self, ax, n=1, color="k", width=0.008, zorder=6):
        x0, x1 = ax.get_xlim()
        self.w = width * abs(x1 - x0)
        self.n = n
        self.poly = PolyCollection(np.zeros((n, 7, 2)), facecolors=color, edgecolors="none", zorder=zorder)
        ax.add_collection(self.poly, autolim=False)
        self.set(np.zeros((n, 2)), np.zeros((n, 2)))

    def set(self, origins, vectors):
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
        self.poly.set_verts(verts)

    def get_offsets(self):
        return self.offsets

    def set_visible(self, b):
        self.poly.set_visible(b)

    def get_visible(self):
        return self.poly.get_visible()


_FONT = FontProperties(family="DejaVu Sans")
_PATH_CACHE: dict = {}


def _char(c, size, weight):
    """(vertices in inches, codes, advance in inches) of one character (cached)."""
    key = (c, size, weight)
    hit = _PATH_CACHE.get(key)
    if hit is None:
        from matplotlib.font_manager import findfont, get_font

        prop = _FONT.copy()
        prop.set_weight(weight)
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


def _glyphs(line, size, weight):
    """Outline of one line of text as a Path in inches, left/baseline at (0, 0), and its width.

    Built from cached per-character outlines and advances (no kerning), so changing a numeric
    readout costs a few array concatenations instead of a font layout.
    """
    key = (line, size, weight, "line")
    hit = _PATH_CACHE.get(key)
    if hit is None:
        verts, codes, x = [], [], 0.0
        for c in line:
            v, k, adv = _char(c, size, weight)
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

    def do_3d_projection(self):
        return -1e9


class PathText:
    """Text drawn as glyph outlines in one PathCollection: redraws ~10x faster than a Text.

    Matplotlib re-rasterizes every Text (and every tick label) on each draw, which dominates the
    cost of a slider update; glyph outlines are filled by Agg like any other path. ``set_text``
    and ``set_position`` move it in place. ``coords`` is "data", "axes" or "xaxis"/"yaxis"
    (x in data and y in axes coordinates, or the other way round, for tick labels).
    """

    def __init__(self, ax, x, y, text="", size=8, color="k", ha="left", va="baseline", coords="data",
                 weight="normal", zorder=7):
        from matplotlib.transforms import blended_transform_factory as blend

        self.ax = ax
        self.size, self.ha, self.va, self.weight = size, ha, va, weight
        trans = {"data": ax.transData, "axes": ax.transAxes,
                 "xaxis": blend(ax.transData, ax.transAxes),
                 "yaxis": blend(ax.transAxes, ax.transData)}[coords]
        self.collection = _FlatPathCollection([], offsets=np.zeros((0, 2)), offset_transform=trans,
                                         transform=ax.figure.dpi_scale_trans, facecolors=color,
                                         edgecolors="none", zorder=zorder, clip_on=False)
        ax.add_collection(self.collection, autolim=False)
        self.text = None
        self.xy = np.array([x, y], float)
        self.set_text(text)

    def _paths(self, text):
        lines = text.split("\n")
        step = 1.3 * self.size / 72.0
        glyphs = [_glyphs(line, self.size, self.weight) if line else (None, 0.0) for line in lines]
        raw = [g[0] for g in glyphs]
        widths = [g[1] for g in glyphs]
        height = step * (len(lines) - 1)
        cap = 0.72 * self.size / 72.0
        dy = {"baseline": 0.0, "bottom": height, "center": height / 2 - cap / 2, "top": -cap}[self.va]
        out = []
        for k, (p, w) in enumerate(zip(raw, widths)):
            if p is None or not len(p.vertices):
                continue
            dx = {"left": 0.0, "center": -w / 2, "right": -w}[self.ha]
            v = p.vertices + np.array([dx, dy - k * step])
            out.append(Path(v, p.codes))
        return out

    def set_text(self, text):
        text = str(text)
        if text != self.text:
            self.text = text
            paths = self._paths(text)
            self.collection.set_paths(paths)
            self.collection.set_offsets(np.tile(self.xy, (len(paths), 1)))

    def get_text(self):
        return self.text

    def set_position(self, xy):
        self.xy = np.asarray(xy, float)
        self.collection.set_offsets(np.tile(self.xy, (len(self.collection.get_paths()), 1)))

    def set_visible(self, b):
        self.collection.set_visible(b)


def _title(ax, text="", size=9):
    return PathText(ax, 0.5, 1.025, text, size=size, ha="center", va="bottom", coords="axes")


def _xticks(ax, values, labels, size=7):
    """Tick marks and labels on the x axis without matplotlib's Axis machinery (cheap to redraw)."""
    from matplotlib.transforms import blended_transform_factory as blend

    ax.set_xticks([])
    segs = [[(v, 0.0), (v, -0.02)] for v in values]
    ax.add_collection(LineCollection(segs, colors="k", linewidths=0.8, clip_on=False,
                                     transform=blend(ax.transData, ax.transAxes)), autolim=False)
    for v, lab in zip(values, labels):
        PathText(ax, v, -0.035, lab, size=size, ha="center", va="top", coords="xaxis")


def _yticks(ax, values, labels, size=7):
    """Tick marks and labels on the y axis without matplotlib's Axis machinery (cheap to redraw)."""
    from matplotlib.transforms import blended_transform_factory as blend

    ax.set_yticks([])
    segs = [[(0.0, v), (-0.015, v)] for v in values]
    ax.add_collection(LineCollection(segs, colors="k", linewidths=0.8, clip_on=False,
                                     transform=blend(ax.transAxes, ax.transData)), autolim=False)
    for v, lab in zip(values, labels):
        PathText(ax, -0.025, v, lab, size=size, ha="right", va="center", coords="yaxis")


class Scene:
    """Base of every chapter-1 drawing: ``build`` once, ``set`` to move, ``replot`` to rebuild.

    Subclasses implement ``make_figure()`` (returns the figure and a list of axes),
    ``decorate()`` (limits, labels, static artists) and ``create()`` (the moving artists).
    """

    def __init__(self, **options):
        self.options = options
        self.fig, self.axes = self.make_figure()
        self.decorate()
        self.create()

    def make_figure(self):
        raise NotImplementedError

    def decorate(self):
        pass

    def create(self):
        raise NotImplementedError

    def set(self, **values):
        raise NotImplementedError

    def replot(self, **values):
        """The naive baseline: clear every axes, draw everything again, then set the values."""
        for ax in self.axes:
            ax.clear()
        self.decorate()
        self.create()
        self.set(**values)


# ====================================================================== 1.1 configuration spaces
def cylinder_xyz(s, a, radius=1.0):
    """Embedding of the cylinder R^1 x S^1 in 3D: height s, angle a; arrays (..., 3)."""
    s, a = np.broadcast_arrays(np.asarray(s, float), np.asarray(a, float))
    return np.stack([radius * np.cos(a), radius * np.sin(a), s], -1)


def torus_xyz(a, b, R=2.0, r=0.7):
    """Embedding of the torus S^1 x S^1 in 3D: a around the hole, b around the tube; (..., 3)."""
    a, b = np.broadcast_arrays(np.asarray(a, float), np.asarray(b, float))
    rho = R + r * np.cos(b)
    return np.stack([rho * np.cos(a), rho * np.sin(a), r * np.sin(b)], -1)


def sphere_xyz(lat, lon, radius=1.0):
    """Point of the sphere S^2 at latitude ``lat`` and longitude ``lon`` (radians); (..., 3)."""
    lat, lon = np.broadcast_arrays(np.asarray(lat, float), np.asarray(lon, float))
    c = np.cos(lat)
    return radius * np.stack([c * np.cos(lon), c * np.sin(lon), np.sin(lat)], -1)


def wrap_segments(a, b, period_a=TWO_PI, period_b=TWO_PI):
    """Cut a path (a(t), b(t)) into segments inside the square [0, pa) x [0, pb) of a flat torus.

    Returns a list of (k, 2) arrays, one per visit of the square, so a LineCollection can draw the
    path on the flattened view without joining its exit point to its re-entry point.
    """
    a = np.asarray(a, float)
    b = np.asarray(b, float)
    ia = np.floor(a / period_a) if period_a else np.zeros_like(a)
    ib = np.floor(b / period_b) if period_b else np.zeros_like(b)
    cuts = np.flatnonzero((np.diff(ia) != 0) | (np.diff(ib) != 0)) + 1
    aw = a - ia * period_a if period_a else a
    bw = b - ib * period_b if period_b else b
    pts = np.stack([aw, bw], -1)
    return [seg for seg in np.split(pts, cuts) if len(seg) > 1]


def _wire(ax, X, Y, Z, color="0.75", lw=0.4):
    ax.plot_wireframe(X, Y, Z, color=color, lw=lw, rstride=1, cstride=1)


def configuration_space_gallery():
    """Static figure: the six spaces of section 1.1 (figs 1.1-1.6) with systems that live on each."""
    fig = figure(figsize=(10, 6.2))
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
    for i, (title, systems) in enumerate(spaces):
        three_d = i >= 3
        ax = fig.add_subplot(2, 3, i + 1, projection="3d" if three_d else None)
        ax.set_title(title, fontsize=10)
        if i == 0:
            ax.plot([-3, 3], [0, 0], "k", lw=2)
            for x in range(-3, 4):
                ax.plot([x, x], [-0.08, 0.08], "k", lw=1)
                ax.text(x, -0.3, str(x), ha="center", fontsize=8)
            ax.plot([1.3], [0], "o", color="tab:blue", ms=9)
            ax.set_xlim(-3.3, 3.3)
            ax.set_ylim(-1.2, 1.2)
            ax.axis("off")
        elif i == 1:
            t = np.linspace(0, TWO_PI, 200)
            ax.plot(np.cos(t), np.sin(t), "k", lw=2)
            for k in range(8):
                a = k * TWO_PI / 8
                ax.text(1.18 * np.cos(a), 1.18 * np.sin(a), f"{k / 8:g}", ha="center", va="center",
                        fontsize=7, color="tab:red")
                ax.text(0.78 * np.cos(a), 0.78 * np.sin(a), f"{k}π/4" if k else "0", ha="center",
                        va="center", fontsize=7, color="tab:blue")
            ax.text(0, 0, "radians (inside)\ncycles (outside)", ha="center", va="center", fontsize=7)
            ax.set_xlim(-1.4, 1.4)
            ax.set_ylim(-1.4, 1.4)
            ax.set_aspect("equal")
            ax.axis("off")
        elif i == 2:
            ax.grid(True, alpha=0.3)
            ax.set_xlim(-2, 2)
            ax.set_ylim(-2, 2)
            ax.set_aspect("equal")
            ax.plot([0.8], [0.6], "o", color="tab:blue", ms=9)
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
            _wire(ax, P[..., 0], P[..., 1], P[..., 2])
            ax.plot([p[0]], [p[1]], [p[2]], "o", color="tab:blue", ms=7)
            _plain_3d(ax, lim=2.0, axes_lines=False)
            ax.set_box_aspect((1, 1, 1))
        ax.text2D(0.5, -0.04, systems, transform=ax.transAxes, ha="center", va="top", fontsize=8,
                  color="0.25") if three_d else ax.text(
            0.5, -0.04, systems, transform=ax.transAxes, ha="center", va="top", fontsize=8, color="0.25")
    fig.subplots_adjust(hspace=0.45, wspace=0.15, bottom=0.08, top=0.94)
    return fig


def _identified_edges(ax, w, h, kind):
    """Mark identified edges of a w x h rectangle: single arrows on one pair, double on the other."""
    def mark(x0, y0, dx, dy, count, color):
        off = (np.arange(count) - (count - 1) / 2) * 0.06
        ax.plot(x0 + dx * (0.5 + off), y0 + dy * (0.5 + off), ls="none", marker="^" if dx == 0 else ">",
                color=color, ms=8)

    box = dict(color="k", lw=1.2)
    ax.plot([0, 0], [0, h], **box)
    ax.plot([w, w], [0, h], **box)
    if kind in ("torus", "sphere"):
        ax.plot([0, w], [0, 0], **box)
        ax.plot([0, w], [h, h], **box)
    else:  # the cylinder's R direction goes on forever
        ax.plot([0, w], [0, 0], ls=":", color="0.5")
        ax.plot([0, w], [h, h], ls=":", color="0.5")
    if kind == "sphere":
        return
    mark(0, 0, 0, h, 1, "tab:red")
    mark(w, 0, 0, h, 1, "tab:red")
    if kind == "torus":
        mark(0, 0, w, 0, 2, "tab:blue")
        mark(0, h, w, 0, 2, "tab:blue")


def flattened_views():
    """Static figure: cylinder, torus and the sphere's latitude/longitude chart, flattened (figs 1.4-1.6).

    Matching arrow marks are edges glued together; on the sphere chart each whole horizontal
    edge is glued to a single point (a pole), which is where the chart breaks down.
    """
    fig = new_figure(1, 3, figsize=(10, 3.4))[0]
    axes = fig.axes
    # cylinder: angle across (identified), height up (unbounded)
    ax = axes[0]
    _identified_edges(ax, TWO_PI, 3.0, "cylinder")
    t = np.linspace(0, 1.6 * TWO_PI, 300)
    for seg in wrap_segments(t + 0.4, 0.2 + 0.5 * t / TWO_PI * 2.5, TWO_PI, 0):
        ax.plot(seg[:, 0], seg[:, 1], color="tab:purple", lw=2)
    ax.set_title("cylinder $\\mathbb{S}^1\\times\\mathbb{R}^1$\n(left edge = right edge)", fontsize=9)
    ax.set_xlabel("angle a")
    ax.set_ylabel("height s")
    # torus: both directions identified
    ax = axes[1]
    _identified_edges(ax, TWO_PI, TWO_PI, "torus")
    t = np.linspace(0, 3 * TWO_PI, 500)
    for seg in wrap_segments(t + 0.3, 2.0 / 3.0 * t + 1.0):
        ax.plot(seg[:, 0], seg[:, 1], color="tab:purple", lw=2)
    ax.set_title("torus $\\mathbb{T}^2$\n(both pairs of edges glued)", fontsize=9)
    ax.set_xlabel("joint angle a")
    ax.set_ylabel("joint angle b")
    # sphere: lat/lon chart
    ax = axes[2]
    _identified_edges(ax, TWO_PI, np.pi, "sphere")
    ax.plot([0, TWO_PI], [np.pi, np.pi], color="darkred", lw=4, alpha=0.6)
    ax.plot([0, TWO_PI], [0, 0], color="darkred", lw=4, alpha=0.6)
    ax.text(np.pi, np.pi - 0.25, "whole edge = north pole", ha="center", fontsize=8, color="darkred")
    ax.text(np.pi, 0.12, "whole edge = south pole", ha="center", fontsize=8, color="darkred")
    ax.set_title("sphere, latitude/longitude chart\n(edges collapse at the poles)", fontsize=9)
    ax.set_xlabel("longitude")
    ax.set_ylabel("colatitude")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xticks([0, np.pi, TWO_PI], ["0", "π", "2π"])
        ax.tick_params(labelsize=7)
    axes[2].set_yticks([0, np.pi / 2, np.pi], ["0", "π/2", "π"])
    axes[1].set_yticks([0, np.pi, TWO_PI], ["0", "π", "2π"])
    fig.tight_layout()
    return fig


class TorusPathScene(Scene):
    """A straight line on the flattened torus and the same path wound round the 3D torus.

    Values: ``a0``, ``b0`` (start), ``slope`` (db/da), ``turns`` (how far to go in a).
    """

    N = 360

    def make_figure(self):
        fig = figure(figsize=(8, 3.6))
        ax3 = fig.add_subplot(1, 2, 1, projection="3d")
        ax2 = fig.add_subplot(1, 2, 2)
        fig.subplots_adjust(left=0.02, right=0.97, bottom=0.14, top=0.9, wspace=0.15)
        return fig, [ax3, ax2]

    def decorate(self):
        ax3, ax2 = self.axes
        u = np.linspace(0, TWO_PI, 21)
        A, B = np.meshgrid(u, np.linspace(0, TWO_PI, 11))
        P = torus_xyz(A, B)
        _wire(ax3, P[..., 0], P[..., 1], P[..., 2], color="0.8")
        _plain_3d(ax3, lim=2.4, axes_lines=False)
        ax3.set_box_aspect((1, 1, 0.5))
        ax3.set_zlim(-1.2, 1.2)
        ax3.view_init(elev=35, azim=-60)
        _identified_edges(ax2, TWO_PI, TWO_PI, "torus")
        ax2.set_xlim(-0.3, TWO_PI + 0.3)
        ax2.set_ylim(-0.3, TWO_PI + 0.3)
        ax2.set_aspect("equal")
        _xticks(ax2, [0, np.pi, TWO_PI], ["0", "π", "2π  a (round the hole)"])
        _yticks(ax2, [0, np.pi, TWO_PI], ["0", "π", "b  2π"])

    def create(self):
        ax3, ax2 = self.axes
        (self.curve3d,) = ax3.plot([], [], [], color="tab:purple", lw=1.8)
        (self.start3d,) = ax3.plot([], [], [], "o", color="k", ms=5)
        self.flat = LineCollection([], colors="tab:purple", linewidths=1.8)
        ax2.add_collection(self.flat)
        (self.start2d,) = ax2.plot([], [], "o", color="k", ms=5)
        self.title = _title(ax2)

    def path(self, a0, b0, slope, turns):
        t = np.linspace(0.0, turns * TWO_PI, self.N)
        return a0 + t, b0 + slope * t

    def set(self, a0=0.0, b0=0.0, slope=0.5, turns=2.0):
        a, b = self.path(a0, b0, slope, turns)
        P = torus_xyz(a, b)
        self.curve3d.set_data_3d(P[:, 0], P[:, 1], P[:, 2])
        self.start3d.set_data_3d(P[:1, 0], P[:1, 1], P[:1, 2])
        self.segments = wrap_segments(a, b)
        self.flat.set_segments(self.segments)
        self.start2d.set_data([a0 % TWO_PI], [b0 % TWO_PI])
        self.title.set_text(f"flattened: {len(self.segments)} straight pieces, slope {slope:.2f}")


def _surface_points(kind):
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

    R, r, rho = 2.0, 0.7, 1.6

    def make_figure(self):
        fig = figure(figsize=(8, 3.6))
        axes = [fig.add_subplot(1, 2, k, projection="3d") for k in (1, 2)]
        fig.subplots_adjust(left=0.0, right=1.0, bottom=0.02, top=0.88, wspace=0.0)
        return fig, axes

    def decorate(self):
        ax_t, ax_s = self.axes
        for ax, kind in ((ax_t, "torus"), (ax_s, "sphere")):
            P = _surface_points(kind)
            _wire(ax, P[..., 0], P[..., 1], P[..., 2], color="0.82")
            _plain_3d(ax, lim=2.2, axes_lines=False)
            ax.set_box_aspect((1, 1, 0.55 if kind == "torus" else 1))
            ax.set_zlim(-1.2, 1.2) if kind == "torus" else ax.set_zlim(-1.7, 1.7)
            ax.view_init(elev=28, azim=-55)
        u = np.linspace(0, TWO_PI, 120)
        L = torus_xyz(u, 0.0 * u + np.pi / 2)  # the loop round the hole, drawn fixed for reference
        ax_t.plot(L[:, 0], L[:, 1], L[:, 2], color="tab:blue", lw=1.2, alpha=0.6)

    def create(self):
        ax_t, ax_s = self.axes
        (self.torus_loop,) = ax_t.plot([], [], [], color="tab:red", lw=2.5)
        (self.sphere_loop,) = ax_s.plot([], [], [], color="tab:red", lw=2.5)
        (self.sphere_point,) = ax_s.plot([], [], [], "o", color="tab:red", ms=6)
        self.t_title = PathText(ax_t, 0.5, 0.97, "", size=9, ha="center", va="top", coords="axes")
        self.s_title = PathText(ax_s, 0.5, 0.97, "", size=9, ha="center", va="top", coords="axes")

    def set(self, s=0.0):
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
        self.t_title.set_text(f"torus: red loop length {self.torus_length:.2f}\n(cannot shrink)")
        self.s_title.set_text(f"sphere: loop length {self.sphere_length:.2f}"
                              + ("\n(contracted to the pole)" if contracted else "\n(shrinks to a point)"))


def chart_speed(lat, heading):
    """Coordinate speed (dlat/dt, dlon/dt) of a unit-speed walker at latitude ``lat`` (radians).

    ``heading`` is measured from north towards east. Returns ``(dlat, dlon)``; ``dlon`` is
    ``inf`` at the poles (cos lat = 0) unless the walker heads due north or south, where the
    longitude itself is undefined. Used by :class:`PoleChartScene`, which flags instead of plotting.
    """
    lat = np.asarray(lat, float)
    c = np.cos(lat)
    dlat = np.cos(heading) * np.ones_like(lat)
    with np.errstate(divide="ignore", invalid="ignore"):
        dlon = np.where(np.abs(c) > 1e-12, np.sin(heading) / np.where(c == 0, 1, c), np.inf)
    return dlat, dlon


class PoleChartScene(Scene):
    """A walker moving at unit speed on the sphere, seen in two charts of an atlas.

    Left: the latitude/longitude chart, where the arrow (coordinate velocity) grows without bound
    as the walker nears a pole and the chart fails at the pole itself (flagged, arrow hidden).
    Middle: a polar chart (projection onto the equator plane), smooth at the north pole. Right:
    coordinate speed against latitude. Values: ``lat_deg``, ``heading_deg``.
    """

    POLE_TOL_DEG = 1e-6
    WARN_SPEED = 50.0
    ARROW = 0.25  # radians drawn per unit coordinate speed

    def make_figure(self):
        fig, axes = new_figure(1, 3, figsize=(10, 3.4), gridspec_kw=dict(width_ratios=[1.5, 1, 1.1]))
        fig.subplots_adjust(left=0.06, right=0.98, bottom=0.16, top=0.86, wspace=0.35)
        return fig, list(axes)

    def decorate(self):
        ax_c, ax_p, ax_v = self.axes
        ax_c.set_xlim(-np.pi, np.pi)
        ax_c.set_ylim(-np.pi / 2 - 0.15, np.pi / 2 + 0.15)
        ax_c.axhspan(np.pi / 2, np.pi / 2 + 0.15, color="mistyrose")
        ax_c.axhspan(-np.pi / 2 - 0.15, -np.pi / 2, color="mistyrose")
        _xticks(ax_c, [-np.pi, 0, np.pi], ["−π", "0  longitude λ", "π"])
        _yticks(ax_c, [-np.pi / 2, 0, np.pi / 2], ["−π/2", "φ  0", "π/2"])
        _title(ax_c, "latitude/longitude chart")
        t = np.linspace(0, TWO_PI, 100)
        ax_p.plot(np.cos(t), np.sin(t), color="0.6", lw=1)
        ax_p.set_xlim(-1.2, 1.2)
        ax_p.set_ylim(-1.2, 1.2)
        ax_p.set_aspect("equal")
        _title(ax_p, "polar chart (northern half)")
        ax_p.plot([0], [0], "+", color="0.3")
        ax_p.set_xticks([])
        ax_p.set_yticks([])
        lat = np.linspace(-np.pi / 2 + 0.01, np.pi / 2 - 0.01, 200)
        ax_v.set_xlim(-np.pi / 2, np.pi / 2)
        ax_v.set_ylim(-0.3, 2.3)
        _xticks(ax_v, [-np.pi / 2, 0, np.pi / 2], ["−π/2", "0  latitude φ", "π/2"])
        _yticks(ax_v, [0, 1, 2], ["1", "10", "100"])
        _title(ax_v, "chart speed (log scale)")
        self._lat_grid = lat

    def create(self):
        ax_c, ax_p, ax_v = self.axes
        (self.pt_c,) = ax_c.plot([], [], "o", color="tab:blue", ms=7, zorder=7)
        self.arrow_c = _arrow(ax_c, color="tab:red", width=0.012)
        (self.pt_p,) = ax_p.plot([], [], "o", color="tab:blue", ms=7, zorder=7)
        self.arrow_p = _arrow(ax_p, color="tab:green", width=0.015)
        (self.speed_curve,) = ax_v.plot([], [], color="tab:red", lw=1.5)
        (self.speed_pt,) = ax_v.plot([], [], "o", color="tab:red", ms=6)
        self.flag = SingularFlag(ax_c, loc=(0.5, 0.55))
        self.p_note = PathText(ax_p, 0.5, 0.03, "", size=8, ha="center", coords="axes")
        self.readout = PathText(ax_c, 0.02, 0.03, "", size=8, coords="axes")
        self._heading = None

    def set(self, lat_deg=45.0, heading_deg=45.0):
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
            _set_arrows(self.arrow_c, [lon, lat], self.arrow_vec)
            self.speed_pt.set_data([lat], [np.log10(speed)])
            self.readout.set_text(f"dφ/dt = {float(dlat):+.2f}, dλ/dt = {float(dlon):+.2f}, "
                                  f"speed {speed:.2f}")
        # polar chart: X = cos(lat) cos(lon), Y = cos(lat) sin(lon); smooth at the north pole
        north = lat >= 0
        self.pt_p.set_visible(north)
        self.arrow_p.set_visible(north)
        if north:
            X, Y = np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon)
            # d/dt of (X, Y) for dlat = cos h, and the east component sin h (no 1/cos(lat) here)
            dX = -np.sin(lat) * np.cos(h)
            dY = np.sin(h)
            self.pt_p.set_data([X], [Y])
            self.polar_vec = self.ARROW * np.array([dX, dY])
            _set_arrows(self.arrow_p, [X, Y], self.polar_vec)
            self.p_note.set_text(f"chart speed {np.hypot(dX, dY):.2f} (finite)")
        else:
            self.p_note.set_text("(walker is on the southern half)")


# ============================================================================ 1.2 Lie groups
AXIOMS = ("associativity", "identity", "inverse")


def _short_name(G):
    return {"(R, +)": "R", "(R^2, +)": "R²", "(R+, x)": "R⁺", "SO(2)": "SO(2)",
            "(S^1, + mod 2pi)": "S¹ (2π)", "(S^1, + mod 1)": "S¹ (1)", "(R^2 x S^1, +)": "R²×S¹",
            "SE(2)": "SE(2)"}.get(str(G), str(G))


def _in_group(G, g):
    """Closure check: is ``g`` a valid element of G (finite, right shape, in range)?"""
    ok = g.shape[-1] == G.dim and np.all(np.isfinite(g))
    if G is RPlus:
        ok = ok and np.all(g > 0)
    if isinstance(G, S1):
        ok = ok and np.all((g >= 0) & (g < G.period))
    return bool(ok)


def axiom_residuals(G, rng, n=20, scale=1.0):
    """Worst-case residuals of the group axioms (1.ii)-(1.v) over ``n`` random triples of G.

    Returns a dict: ``closure`` (bool, every product is again an element) and, for
    associativity, identity and inverse, the largest coordinate difference (angles compared
    modulo their period) between the two sides of the law.
    """
    g1, g2, g3 = (G.random(rng, n) for _ in range(3))
    if scale != 1.0:
        if G is RPlus:
            g1, g2, g3 = g1 ** scale, g2 ** scale, g3 ** scale
        else:
            lin = ~np.array(G.angular)
            for g in (g1, g2, g3):
                g[..., lin] *= scale
    e = G.identity((n,))
    closure = all(_in_group(G, G.compose(a, b)) for a, b in ((g1, g2), (g2, g3), (g1, g3)))
    closure = closure and _in_group(G, G.inverse(g1))
    assoc = G.difference(G.compose(g1, G.compose(g2, g3)), G.compose(G.compose(g1, g2), g3))
    ident = np.maximum(np.abs(G.difference(G.compose(e, g1), g1)),
                       np.abs(G.difference(G.compose(g1, e), g1)))
    inv = np.maximum(np.abs(G.difference(G.compose(G.inverse(g1), g1), e)),
                     np.abs(G.difference(G.compose(g1, G.inverse(g1)), e)))
    return {"closure": closure, "associativity": float(np.max(np.abs(assoc))),
            "identity": float(np.max(ident)), "inverse": float(np.max(inv))}


class GroupAxiomsScene(Scene):
    """Bar chart of the axiom residuals for every group in gm_core.ALL_GROUPS (values ``seed``, ``scale``)."""

    FLOOR = 1e-18
    TOL = 1e-9

    def make_figure(self):
        fig, ax = new_figure(figsize=(8, 3.4))
        fig.subplots_adjust(left=0.08, right=0.99, bottom=0.12, top=0.9)
        return fig, [ax]

    def decorate(self):
        (ax,) = self.axes
        self.names = list(ALL_GROUPS)
        ax.set_yscale("log")
        ax.set_ylim(self.FLOOR / 3, 1e-3)
        ax.axhline(self.TOL, color="darkred", ls="--", lw=1)
        PathText(ax, len(self.names) - 0.5, self.TOL * 2, "tolerance 1e-9", size=7, ha="right",
                 color="darkred")
        ax.set_xlim(-0.6, len(self.names) - 0.4)
        _xticks(ax, np.arange(len(self.names)), [_short_name(ALL_GROUPS[k]) for k in self.names])
        _yticks(ax, [1e-18, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3], ["≤1e-18", "1e-15", "1e-12", "1e-9",
                                                               "1e-6", "1e-3"])
        ax.minorticks_off()
        for k, (axiom, color) in enumerate(zip(AXIOMS, ("tab:blue", "tab:orange", "tab:green"))):
            PathText(ax, 0.02 + 0.25 * k, 0.93, "■ " + axiom, size=7.5, color=color, coords="axes")

    def create(self):
        (ax,) = self.axes
        x = np.arange(len(self.names))
        self.bars = {}
        for k, (axiom, color) in enumerate(zip(AXIOMS, ("tab:blue", "tab:orange", "tab:green"))):
            self.bars[axiom] = ax.bar(x + (k - 1) * 0.27, np.full(len(x), self.FLOOR), width=0.27,
                                      bottom=self.FLOOR / 3, color=color, label=axiom)
        self.title = _title(ax)

    def set(self, seed=0, scale=1.0):
        rng = np.random.default_rng(int(seed))
        self.results = {k: axiom_residuals(G, rng, scale=scale) for k, G in ALL_GROUPS.items()}
        for axiom in AXIOMS:
            for rect, k in zip(self.bars[axiom], self.names):
                rect.set_height(max(self.results[k][axiom], self.FLOOR) - self.FLOOR / 3)
        closed = all(r["closure"] for r in self.results.values())
        worst = max(r[a] for r in self.results.values() for a in AXIOMS)
        self.title.set_text(f"seed {int(seed)}: closure {'holds' if closed else 'FAILS'} for every group;"
                            f" worst residual {worst:.1e}")


class SlideRuleScene(Scene):
    """A slide rule: (R+, x) multiplication done as (R, +) addition of logarithms, (1.xii).

    Values ``a`` and ``b`` in [1, 10]. The sliding C scale is shifted by log10(a); the cursor at
    log10(a) + log10(b) reads a*b on the fixed D scale (which runs over two decades, 1-100).
    """

    def make_figure(self):
        fig, ax = new_figure(figsize=(8, 2.6))
        fig.subplots_adjust(left=0.02, right=0.98, bottom=0.05, top=0.85)
        return fig, [ax]

    @staticmethod
    def _ticks(decades, y0, up):
        vals = np.concatenate([np.arange(1, 10, 0.5) * 10 ** d for d in range(decades)] + [[10 ** decades]])
        x = np.log10(vals)
        major = np.isclose(vals / 10 ** np.floor(np.log10(vals) + 1e-12), np.round(vals / 10 ** np.floor(
            np.log10(vals) + 1e-12)))
        length = np.where(major, 0.25, 0.12) * (1 if up else -1)
        segs = np.stack([np.stack([x, np.full_like(x, y0)], -1), np.stack([x, y0 + length], -1)], 1)
        return vals, x, segs, major

    def decorate(self):
        (ax,) = self.axes
        ax.set_xlim(-0.05, 2.05)
        ax.set_ylim(-1.1, 1.3)
        ax.axis("off")
        vals, x, segs, major = self._ticks(2, 0.0, False)
        ax.add_collection(LineCollection(segs, colors="k", linewidths=1))
        for v, xx, m in zip(vals, x, major):
            if m:
                PathText(ax, xx, -0.45, f"{v:g}", size=7, ha="center")
        PathText(ax, -0.03, -0.3, "D", size=9, weight="bold", ha="right")
        ax.plot([0, 2], [0, 0], "k", lw=1)
        vals, x, segs, major = self._ticks(1, 0.0, True)
        self._c_vals, self._c_x, self._c_segs, self._c_major = vals, x, segs, major

    def create(self):
        (ax,) = self.axes
        self.slide = LineCollection(self._c_segs, colors="tab:blue", linewidths=1)
        ax.add_collection(self.slide)
        self.c_labels = [PathText(ax, x, 0.35, f"{v:g}", size=7, ha="center", color="tab:blue")
                         for v, x, m in zip(self._c_vals, self._c_x, self._c_major) if m]
        self._c_label_x = np.array([x for x, m in zip(self._c_x, self._c_major) if m])
        (self.slide_edge,) = ax.plot([0, 1], [0.02, 0.02], color="tab:blue", lw=2)
        (self.cursor,) = ax.plot([0, 0], [-0.8, 0.9], color="tab:red", lw=1.5)
        self.add_a = _arrow(ax, color="tab:orange", width=0.006)
        self.add_b = _arrow(ax, color="tab:green", width=0.006)
        self.readout = PathText(ax, 1.0, 1.05, "", size=9, ha="center")

    def set(self, a=2.0, b=3.0):
        la, lb = np.log10(a), np.log10(b)
        segs = self._c_segs.copy()
        segs[..., 0] += la
        self.slide.set_segments(segs)
        for t, x in zip(self.c_labels, self._c_label_x):
            t.set_position((x + la, 0.35))
        self.slide_edge.set_data([la, la + 1], [0.02, 0.02])
        self.cursor_x = la + lb
        self.cursor.set_data([self.cursor_x, self.cursor_x], [-0.8, 0.9])
        _set_arrows(self.add_a, [0, -0.85], [la, 0])
        _set_arrows(self.add_b, [la, -0.85], [lb, 0])
        self.reading = 10 ** self.cursor_x
        self.readout.set_text(f"log a + log b = {la:.3f} + {lb:.3f} = {la + lb:.3f}   →   "
                              f"read on D: {self.reading:.3f} = a × b = {a * b:.3f}")


class CircleIsoScene(Scene):
    """(S^1, + mod 1) vs SO(2): adding cycles on the circle = multiplying rotation matrices, (1.xvi).

    Values ``a1``, ``a2`` in cycles [0, 1).
    """

    G = S1(1.0)

    def make_figure(self):
        fig, axes = new_figure(1, 2, figsize=(7, 3.4))
        fig.subplots_adjust(left=0.02, right=0.98, bottom=0.05, top=0.84, wspace=0.1)
        return fig, list(axes)

    def decorate(self):
        t = np.linspace(0, TWO_PI, 120)
        for ax in self.axes:
            ax.plot(np.cos(t), np.sin(t), color="0.7")
            ax.set_xlim(-1.35, 1.35)
            ax.set_ylim(-1.35, 1.35)
            ax.set_aspect("equal")
            ax.axis("off")
        _title(self.axes[0], "circle (S¹, + mod 1): add cycles")
        _title(self.axes[1], "SO(2): multiply matrices, act on e₁")

    def create(self):
        ax_s, ax_r = self.axes
        self.pts = ax_s.scatter([0, 0, 0], [0, 0, 0], c=["tab:blue", "tab:orange", "tab:red"], s=[50, 50, 90],
                                zorder=5)
        self.vecs = ArrowSet(ax_r, color=["tab:blue", "tab:orange", "tab:red"], n=3, width=0.012)
        self.check = ArrowSet(ax_r, color="k", width=0.005)
        self.readout = PathText(ax_s, 0, -1.3, "", size=8, ha="center")
        self.r_readout = PathText(ax_r, 0, -1.3, "", size=8, ha="center")

    def set(self, a1=0.2, a2=0.35):
        G = self.G
        g1, g2 = np.array([a1]), np.array([a2])
        s = G.compose(g1, g2)
        ang = TWO_PI * np.array([a1, a2, s[0]])
        self.pts.set_offsets(np.stack([np.cos(ang), np.sin(ang)], -1))
        M = G.matrix(g1) @ G.matrix(g2)
        e1 = np.array([1.0, 0.0])
        v = np.stack([G.matrix(g1) @ e1, G.matrix(g2) @ e1, M @ e1])
        _set_arrows(self.vecs, np.zeros((3, 2)), v)
        self.product_matrix = M
        self.sum_matrix = G.matrix(s)
        _set_arrows(self.check, [0, 0], self.sum_matrix @ e1 * 0.6)
        self.mismatch = float(np.max(np.abs(M - self.sum_matrix)))
        self.readout.set_text(f"{a1:.2f} + {a2:.2f} mod 1 = {s[0]:.2f} cycles")
        self.r_readout.set_text(f"max |R(a1)R(a2) − R(a1 ⊕ a2)| = {self.mismatch:.1e}")


# ================================================================================ 1.3 SE(2)
class LeftRightActionScene(Scene):
    """Figs. 1.8-1.9: a body at g, moved by the left action (h g) and by the right action (g h).

    Values ``x, y, theta`` (g) and ``u, v, beta`` (h).
    """

    LIM = 4.0

    def make_figure(self):
        fig, axes = new_figure(1, 2, figsize=(9, 4.3))
        fig.subplots_adjust(left=0.05, right=0.99, bottom=0.1, top=0.88, wspace=0.15)
        return fig, list(axes)

    def decorate(self):
        for ax in self.axes:
            _plane(ax, self.LIM)
            FrameArtist(ax, (0, 0, 0), length=0.6, colors=("0.55", "0.55"), zorder=2)
        _title(self.axes[0], "left action: hg (fig. 1.8)")
        _title(self.axes[1], "right action: gh (fig. 1.9)")

    def create(self):
        ax_l, ax_r = self.axes
        self.g_body = [BodyArtist(ax, BODY, facecolor="0.6") for ax in self.axes]
        self.g_frame = [FrameArtist(ax, length=0.5) for ax in self.axes]
        self.hg_body = BodyArtist(ax_l, BODY, facecolor="tab:blue")
        self.hg_frame = FrameArtist(ax_l, length=0.5)
        self.gh_body = BodyArtist(ax_r, BODY, facecolor="tab:orange")
        self.gh_frame = FrameArtist(ax_r, length=0.5)
        # left action = rotate about the world origin by beta, then translate by (u, v)
        (self.arc,) = ax_l.plot([], [], color="tab:blue", ls=":", lw=1.5)
        self.shift = ArrowSet(ax_l, color="tab:blue", width=0.006)
        # h drawn in the world frame (left) and in g's frame (right)
        self.h_frame_l = FrameArtist(ax_l, length=0.35, colors=("0.3", "0.3"), zorder=3)
        (self.h_in_g,) = ax_r.plot([], [], color="tab:orange", ls="--", lw=1.2)
        (self.h_in_g_corner,) = ax_r.plot([], [], color="tab:orange", ls=":", lw=1.0)
        self.l_text = PathText(ax_l, 0.02, 0.03, "", size=7.5, va="bottom", coords="axes")
        self.r_text = PathText(ax_r, 0.02, 0.03, "", size=7.5, va="bottom", coords="axes")

    def set(self, x=1.5, y=0.5, theta=0.5, u=-1.0, v=1.0, beta=0.9):
        g = np.array([x, y, theta])
        h = np.array([u, v, beta])
        self.hg = SE2.compose(h, g)
        self.gh = SE2.compose(g, h)
        for b, f in zip(self.g_body, self.g_frame):
            b.set(g)
            f.set(g)
        self.hg_body.set(self.hg)
        self.hg_frame.set(self.hg)
        self.gh_body.set(self.gh)
        self.gh_frame.set(self.gh)
        s = np.linspace(0.0, 1.0, 40)[:, None]
        rot = SE2.act_on_points(np.concatenate([0 * s, 0 * s, beta * s], -1), g[:2])
        self.arc.set_data(rot[:, 0], rot[:, 1])
        _set_arrows(self.shift, rot[-1], [u, v])
        self.h_frame_l.set(h)
        corner = SE2.act_on_points(g, np.array([u, 0.0]))
        self.h_in_g.set_data([x, self.gh[0]], [y, self.gh[1]])
        self.h_in_g_corner.set_data([x, corner[0], self.gh[0]], [y, corner[1], self.gh[1]])
        self.l_text.set_text(f"hg = ({self.hg[0]:.2f}, {self.hg[1]:.2f}, {self.hg[2]:.2f})\n"
                             "rotate g about the origin by β, then shift by (u, v)")
        self.r_text.set_text(f"gh = ({self.gh[0]:.2f}, {self.gh[1]:.2f}, {self.gh[2]:.2f})\n"
                             "step (u, v) along g's own axes, then turn by β")


def _powers(G, g, n):
    out = [G.identity()]
    for _ in range(n):
        out.append(G.compose(out[-1], g))
    return np.array(out)


class ForwardLeftScene(Scene):
    """Fig. 1.10: repeat the step g in (R^2 x S^1, +) and in SE(2); values ``x, y, theta, n``.

    Each step's displacement, read in the body frame it starts from, is printed: constant in
    SE(2) ("forward and to the left" for g = (1, 1, pi/2)), changing in (R^2 x S^1, +).
    """

    N_MAX = 8
    LIM = 4.5

    def make_figure(self):
        fig, axes = new_figure(1, 2, figsize=(9, 4.4))
        fig.subplots_adjust(left=0.05, right=0.99, bottom=0.1, top=0.88, wspace=0.15)
        return fig, list(axes)

    def decorate(self):
        for ax in self.axes:
            _plane(ax, self.LIM)
        _title(self.axes[0], "(R² × S¹, +):  g + g + …")
        _title(self.axes[1], "SE(2):  g ∘ g ∘ …")

    def create(self):
        self.bodies, self.frames, self.steps, self.texts = [], [], [], []
        for ax, color in zip(self.axes, ("tab:purple", "tab:blue")):
            bodies = PolyCollection([], facecolors=color, edgecolors="k", alpha=0.4, linewidths=0.8)
            frames = LineCollection([], linewidths=1.8, zorder=4)
            steps = LineCollection([], colors=color, linewidths=1.2, linestyles="--")
            for c in (bodies, frames, steps):
                ax.add_collection(c)
            self.bodies.append(bodies)
            self.frames.append(frames)
            self.steps.append(steps)
            self.texts.append(PathText(ax, 0.02, 0.03, "", size=7.5, va="bottom", coords="axes"))

    @staticmethod
    def body_displacements(poses):
        """Displacement of each step, written in the body frame it starts from: (k, 2)."""
        d = poses[1:, :2] - poses[:-1, :2]
        t = poses[:-1, 2]
        c, s = np.cos(t), np.sin(t)
        return np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]], -1)

    @staticmethod
    def describe(d):
        fwd = "forward" if d[0] > 1e-9 else ("backward" if d[0] < -1e-9 else "")
        side = "to the left" if d[1] > 1e-9 else ("to the right" if d[1] < -1e-9 else "")
        return " and ".join(w for w in (fwd, side) if w) or "no move"

    def set(self, x=1.0, y=1.0, theta=np.pi / 2, n=2):
        n = int(n)
        g = np.array([x, y, theta])
        self.poses = [_powers(R2xS1, g, n), _powers(SE2, g, n)]
        for k in range(2):
            P = self.poses[k]
            self.bodies[k].set_verts(SE2.act_on_points(P[:, None, :], BODY))
            origin = P[:, :2]
            tips = SE2.act_on_points(P[:, None, :], np.array([[0.4, 0.0], [0.0, 0.4]]))
            self.frames[k].set_segments(np.concatenate([np.stack([origin, tips[:, 0]], 1),
                                                        np.stack([origin, tips[:, 1]], 1)]))
            self.frames[k].set_color(["tab:red"] * (n + 1) + ["tab:green"] * (n + 1))
            self.steps[k].set_segments(np.stack([P[:-1, :2], P[1:, :2]], 1))
            d = self.body_displacements(P)
            lines = [f"step {j + 1}: ({d[j, 0]:+.2f}, {d[j, 1]:+.2f}) {self.describe(d[j])}"
                     for j in range(min(n, 4))]
            if n > 4:
                lines.append("...")
            self.texts[k].set_text("in the body frame:\n" + "\n".join(lines))


class BodyPointsScene(Scene):
    """(1.11)-(1.12): a point fixed in the body, carried to the world by g; values ``x, y, theta, px, py``."""

    OUTLINE = BodyArtist.rectangle(1.6, 0.8)

    def make_figure(self):
        fig, ax = new_figure(figsize=(5, 4.4))
        fig.subplots_adjust(left=0.1, right=0.98, bottom=0.1, top=0.9)
        return fig, [ax]

    def decorate(self):
        (ax,) = self.axes
        _plane(ax, 3.0)
        FrameArtist(ax, (0, 0, 0), length=0.6, colors=("0.55", "0.55"), zorder=2)

    def create(self):
        (ax,) = self.axes
        self.body = BodyArtist(ax, self.OUTLINE, facecolor="tab:blue", alpha=0.3)
        self.frame = FrameArtist(ax, length=0.6)
        (self.legs,) = ax.plot([], [], color="tab:blue", ls="--", lw=1)
        (self.point,) = ax.plot([], [], "o", color="tab:red", ms=7, zorder=7)
        self.text = _title(ax, size=8)

    def set(self, x=0.5, y=0.3, theta=0.6, px=0.6, py=0.3):
        g = np.array([x, y, theta])
        pb = np.array([px, py])
        self.body.set(g)
        self.frame.set(g)
        self.world = SE2.act_on_points(g, pb)
        via_matrix = (SE2.matrix(g) @ np.array([px, py, 1.0]))[:2]
        self.matrix_mismatch = float(np.max(np.abs(via_matrix - self.world)))
        corner = SE2.act_on_points(g, np.array([px, 0.0]))
        self.legs.set_data([x, corner[0], self.world[0]], [y, corner[1], self.world[1]])
        self.point.set_data([self.world[0]], [self.world[1]])
        self.text.set_text(f"body point ({px:.2f}, {py:.2f}) → world ({self.world[0]:.2f}, "
                           f"{self.world[1]:.2f})\nmatrix (1.12) agrees to {self.matrix_mismatch:.0e}")


# ============================================================================ 1.4 velocities
def _field_funcs():
    def spiral(q, t=0.0):
        x, y = q[..., 0], q[..., 1]
        return np.stack([-0.25 * x - y, x - 0.25 * y], -1)

    def saddle(q, t=0.0):
        return np.stack([q[..., 0], -q[..., 1]], -1)

    def rotation(q, t=0.0):
        return np.stack([-q[..., 1], q[..., 0]], -1)

    def vdp(q, t=0.0):
        x, y = q[..., 0], q[..., 1]
        return np.stack([y, (1.0 - x * x) * y - x], -1)

    return {"spiral sink": spiral, "saddle": saddle, "closed loops": rotation,
            "limit cycle (van der Pol)": vdp}


#: The example vector fields of figs. 1.13-1.14, as functions (q (..., 2), t) -> q_dot.
FIELDS = _field_funcs()


def rk4_curve(f, q0, T, n):
    """Integral curve of a time-invariant field by n classical RK4 steps over [0, T]: (n+1, ..., 2)."""
    q = np.asarray(q0, float)
    h = T / n
    out = np.empty((n + 1,) + q.shape)
    out[0] = q
    for k in range(n):
        k1 = f(q)
        k2 = f(q + 0.5 * h * k1)
        k3 = f(q + 0.5 * h * k2)
        k4 = f(q + h * k3)
        q = q + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        out[k + 1] = q
    return out


class VectorFieldScene(Scene):
    """Figs. 1.13-1.14: a vector field, some integral curves, and one from a movable start point.

    Values ``field`` (a key of :data:`FIELDS`), ``x0``, ``y0``. The movable curve is drawn
    forwards (solid) and backwards in time (dashed, the flow of -X); curves computed with
    :func:`gm_core.fields.integral_curve` (scipy solve_ivp).
    """

    LIM = 3.0
    T = 6.0
    N = 240

    def make_figure(self):
        fig, ax = new_figure(figsize=(5.2, 5.0))
        fig.subplots_adjust(left=0.03, right=0.97, bottom=0.03, top=0.93)
        return fig, [ax]

    def decorate(self):
        (ax,) = self.axes
        _plane(ax, self.LIM, grid=False)
        self._field = None

    def create(self):
        (ax,) = self.axes
        g = np.linspace(-self.LIM + 0.25, self.LIM - 0.25, 13)
        self._grid = np.stack(np.meshgrid(g, g), -1).reshape(-1, 2)
        self.quiver = ArrowSet(ax, n=len(self._grid), color="0.6", width=0.0045, zorder=1)
        self.background = LineCollection([], colors="tab:blue", linewidths=1.0, alpha=0.55, zorder=2)
        ax.add_collection(self.background)
        (self.forward,) = ax.plot([], [], color="tab:red", lw=2.2, zorder=4)
        (self.backward,) = ax.plot([], [], color="tab:red", lw=1.5, ls="--", zorder=4)
        (self.start,) = ax.plot([], [], "o", color="k", ms=7, zorder=5)
        self.title = _title(ax)
        self._field = None

    def _background(self, name):
        """A few fixed integral curves (both directions), cut where they leave the view: segments."""
        f = FIELDS[name]
        starts = np.array([[2.5, 0.0], [-2.5, 0.5], [0.5, 2.5], [-0.5, -2.5], [1.2, 1.2], [-1.5, -1.0],
                           [0.3, 0.05], [2.8, 2.8], [-2.8, 2.2]])
        segs = []
        with np.errstate(over="ignore", invalid="ignore"):
            for sign in (1.0, -1.0):
                q = rk4_curve(lambda p: sign * f(p), starts, 4.0, 200)
                for j in range(len(starts)):
                    seg = q[:, j][: _first_outside(q[:, j], 1.5 * self.LIM)]
                    if len(seg) > 1:
                        segs.append(seg)
        return segs

    def curve(self, name, x0, y0):
        """Forward and backward integral curves from (x0, y0), each (m, 2), by solve_ivp.

        Uses :func:`gm_core.fields.integral_curve` (scipy's solve_ivp) on X and on -X, stopping
        early if the curve leaves a box three times the view (so runaway curves never overflow).
        """
        from ..fields import integral_curve

        f = FIELDS[name]
        lim = 3 * self.LIM
        t_eval = np.linspace(0.0, self.T, self.N + 1)

        def leave(t, y):
            return lim - np.max(np.abs(y))

        leave.terminal = True
        out = []
        for sign in (1.0, -1.0):
            c = integral_curve(lambda q, t, s=sign: s * f(q), [x0, y0], (0.0, self.T), t_eval=t_eval,
                               method="RK45", rtol=1e-5, atol=1e-8, events=leave)
            out.append(c.q)
        return out

    def set(self, field="spiral sink", x0=1.5, y0=1.0):
        if field != self._field:
            v = FIELDS[field](self._grid)
            n = np.linalg.norm(v, axis=1, keepdims=True)
            v = 0.32 * v / np.maximum(n, 1e-12) * (n > 1e-12)
            self.quiver.set(self._grid - v / 2, v)   # arrows centred on the grid points
            self.background.set_segments(self._background(field))
            self._field = field
        fwd, bwd = self.curve(field, x0, y0)
        # a curve that runs away (saddle, backwards van der Pol) is cut where it leaves the view
        self.fwd_pts, self.bwd_pts = (c[: _first_outside(c, 3 * self.LIM)] for c in (fwd, bwd))
        self.forward.set_data(self.fwd_pts[:, 0], self.fwd_pts[:, 1])
        self.backward.set_data(self.bwd_pts[:, 0], self.bwd_pts[:, 1])
        self.start.set_data([x0], [y0])
        self.title.set_text(f"{field}: forward (solid) and backward (dashed) from ({x0:.2f}, {y0:.2f})")


def _first_outside(c, lim):
    bad = ~np.all(np.isfinite(c) & (np.abs(c) < lim), axis=1)
    return int(np.argmax(bad)) if bad.any() else len(c)


class LiftedScalarScene(Scene):
    """Lifted actions on (R^2, +) and (R+, x), (1.22)-(1.25): a velocity carried from g to hg.

    Values ``hx``, ``hy`` (a translation of R^2) and ``h`` (a factor in R+). On R^2 the arrow is
    carried unchanged; on R+ it is scaled by h, like interest proportional to the balance.
    """

    G_R2 = np.array([-1.0, -0.5])
    V_R2 = np.array([0.8, 0.4])
    G_RP = 1.5
    V_RP = 0.6

    def make_figure(self):
        fig, axes = new_figure(1, 2, figsize=(9, 3.6), gridspec_kw=dict(width_ratios=[1, 1.5]))
        fig.subplots_adjust(left=0.03, right=0.98, bottom=0.14, top=0.88, wspace=0.12)
        return fig, list(axes)

    def decorate(self):
        ax2, ax1 = self.axes
        _plane(ax2, 2.5)
        _title(ax2, "(R², +): T_gL_h = identity")
        ax1.set_xlim(-0.2, 10.5)
        ax1.set_ylim(-1.0, 1.6)
        ax1.set_yticks([])
        ax1.plot([0, 10.5], [0, 0], color="k", lw=1)
        _xticks(ax1, [0, 1, 4, 6, 8, 10], ["0", "1 = e", "4", "6", "8", "10"])
        _title(ax1, "(R⁺, ×): T_gL_h = h scales the arrow")

    def create(self):
        ax2, ax1 = self.axes
        (self.pts2,) = ax2.plot([], [], "o", color="k", ms=6)
        self.arrows2 = ArrowSet(ax2, color=["tab:blue", "tab:orange"], n=2, width=0.012)
        self.shift2 = ArrowSet(ax2, color="0.6", width=0.005)
        (self.pts1,) = ax1.plot([], [], "o", color="k", ms=6)
        self.arrows1 = _arrow(ax1, color=["tab:blue", "tab:orange"], n=2, width=0.008)
        self.text1 = PathText(ax1, 0.02, 0.06, "", size=8, coords="axes")

    def set(self, hx=1.5, hy=1.0, h=2.5):
        g2 = self.G_R2
        hg2 = g2 + np.array([hx, hy])
        self.pts2.set_data([g2[0], hg2[0]], [g2[1], hg2[1]])
        self.v_R2 = np.stack([self.V_R2, np.eye(2) @ self.V_R2])
        _set_arrows(self.arrows2, [g2, hg2], self.v_R2)
        _set_arrows(self.shift2, g2, [hx, hy])
        g1 = self.G_RP
        hg1 = RPlus.compose([h], [g1])[0]
        lifted = (RPlus.left_lifted_action([h], [g1]) @ [self.V_RP])[0]
        self.v_RP = np.array([self.V_RP, lifted])
        self.pts1.set_data([g1, hg1], [0, 0])
        _set_arrows(self.arrows1, [[g1, 0.5], [hg1, 0.5]], [[self.V_RP, 0], [lifted, 0]])
        self.text1.set_text(f"g = {g1:.2f}, ġ = {self.V_RP:.2f}  →  hg = {hg1:.2f}, "
                            f"T_gL_h ġ = {lifted:.2f};  ratio ġ/g = {self.V_RP / g1:.3f} = "
                            f"{lifted / hg1:.3f}")


def _vec(a, digits=2):
    """'(+0.12, -0.50, +0.00)': fixed-width numbers for readouts, never printing -0.00."""
    tiny = 0.5 * 10.0 ** -digits
    return "(" + ", ".join(f"{(c if abs(c) >= tiny else 0.0):+.{digits}f}" for c in a) + ")"


def point_velocities(g, g_dot, points):
    """World velocities of world points rigidly attached to a body at g moving with g_dot.

    v(p) = (x_dot, y_dot) + theta_dot * J (p - (x, y)), J the quarter turn; shapes (..., 2).
    """
    g = np.asarray(g, float)
    g_dot = np.asarray(g_dot, float)
    r = np.asarray(points, float) - g[..., None, :2]
    return g_dot[..., None, :2] + g_dot[..., None, 2:3] * np.stack([-r[..., 1], r[..., 0]], -1)


class LiftedSE2Scene(Scene):
    """Lifted actions on SE(2), (1.31) and (1.37): a body's motion carried from g to hg and to gh.

    Values ``theta`` (heading of g), ``u, v, beta`` (h). The body at g moves with world velocity
    g_dot (body velocity XI0). Arrows are the velocities of the body's corners: at hg they are
    T_gL_h g_dot (same motion *as seen by the body*), at gh they are T_gR_h g_dot (the motion of a
    frame welded to g, same *spatial* velocity).
    """

    XI0 = np.array([0.7, 0.0, 0.9])
    G_XY = np.array([-1.2, -1.0])
    SCALE = 0.7

    def make_figure(self):
        fig, ax = new_figure(figsize=(5.8, 4.9))
        fig.subplots_adjust(left=0.02, right=0.98, bottom=0.02, top=0.93)
        return fig, [ax]

    def decorate(self):
        (ax,) = self.axes
        _plane(ax, 3.5)

    def create(self):
        (ax,) = self.axes
        colors = ("0.45", "tab:blue", "tab:orange")
        self.bodies = [BodyArtist(ax, BODY * 1.6, facecolor=c, alpha=0.45) for c in colors]
        self.vel = [ArrowSet(ax, color=c, n=4, width=0.007) for c in colors]
        (self.weld,) = ax.plot([], [], color="tab:orange", ls=":", lw=1.5)
        self.title = _title(ax, size=8)
        self.text = PathText(ax, 0.02, 0.03, "", size=7, va="bottom", coords="axes")

    def set(self, theta=0.3, u=2.0, v=1.5, beta=1.0):
        g = np.array([self.G_XY[0], self.G_XY[1], theta])
        h = np.array([u, v, beta])
        g_dot = SE2.body_to_world(g, self.XI0)
        self.poses = [g, SE2.compose(h, g), SE2.compose(g, h)]
        self.world_vels = [g_dot, SE2.left_lifted_action(h, g) @ g_dot, SE2.right_lifted_action(h, g) @ g_dot]
        for body, q, pose, gd in zip(self.bodies, self.vel, self.poses, self.world_vels):
            body.set(pose)
            pts = np.vstack([pose[:2], SE2.act_on_points(pose, body.outline)])
            _set_arrows(q, pts, self.SCALE * point_velocities(pose, gd, pts))
        self.weld.set_data([g[0], self.poses[2][0]], [g[1], self.poses[2][1]])
        xi = [SE2.world_to_body(p, gd) for p, gd in zip(self.poses, self.world_vels)]
        xs = [SE2.world_to_spatial(p, gd) for p, gd in zip(self.poses, self.world_vels)]
        self.body_vels, self.spatial_vels = np.array(xi), np.array(xs)
        self.title.set_text("grey: g     blue: hg with T_gL_h ġ     orange: gh with T_gR_h ġ")
        f = _vec
        self.text.set_text(f"body ξ:     g {f(xi[0])}  hg {f(xi[1])}  gh {f(xi[2])}\n"
                           f"spatial ξˢ: g {f(xs[0])}  hg {f(xs[1])}  gh {f(xs[2])}")


class VelocityScene(Scene):
    """Fig. 1.15: world, body and spatial velocity of a body at g with body velocity xi.

    Values ``x, y, theta`` (g) and ``vx, vy, w`` (the body velocity xi).
    """

    LIM = 3.0

    def make_figure(self):
        fig, axes = new_figure(2, 2, figsize=(7.2, 7.0))
        fig.subplots_adjust(left=0.02, right=0.98, bottom=0.02, top=0.95, wspace=0.06, hspace=0.12)
        return fig, list(np.ravel(axes))

    def decorate(self):
        names = ["(a) world velocity ġ", "(b) body velocity ξ, in the body frame",
                 "(c) ξ after moving the body to e", "(d) spatial velocity ξˢ at the origin"]
        for ax, name in zip(self.axes, names):
            _plane(ax, self.LIM)
            _title(ax, name, size=8.5)

    def create(self):
        a, b, c, d = self.axes
        self.bodies = [BodyArtist(ax, BODY * 1.5, facecolor="tab:blue", alpha=0.4) for ax in self.axes]
        self.frames = [FrameArtist(ax, length=0.6) for ax in (b, c)]
        self.world = ArrowSet(a, color="k", width=0.012)
        self.components = ArrowSet(b, color=["tab:red", "tab:green"], n=2, width=0.012)
        self.at_e = ArrowSet(c, color="k", width=0.012)
        self.spatial_parts = ArrowSet(d, color=["0.55", "tab:purple"], n=2, width=0.008)
        self.spatial = ArrowSet(d, color="tab:red", width=0.012)
        (self.lever,) = d.plot([], [], color="tab:purple", ls=":", lw=1.5)
        self.texts = [PathText(ax, 0.03, 0.04, "", size=8, coords="axes") for ax in self.axes]

    def set(self, x=1.2, y=0.6, theta=0.7, vx=0.8, vy=0.3, w=0.6):
        g = np.array([x, y, theta])
        xi = np.array([vx, vy, w])
        self.g_dot = SE2.body_to_world(g, xi)
        self.xi_s = SE2.body_to_spatial(g, xi)
        for k in (0, 1, 3):
            self.bodies[k].set(g)
        self.bodies[2].set(SE2.identity())
        self.frames[0].set(g)
        self.frames[1].set(SE2.identity())
        _set_arrows(self.world, g[:2], self.g_dot[:2])
        axes_b = SE2.matrix(g)[:2, :2]
        self.component_vecs = np.stack([vx * axes_b[:, 0], vy * axes_b[:, 1]])
        _set_arrows(self.components, [g[:2], g[:2] + self.component_vecs[0]], self.component_vecs)
        _set_arrows(self.at_e, [0, 0], xi[:2])
        lever = -g[:2]                         # from the body's frame origin to the world origin
        swirl = w * np.array([-lever[1], lever[0]])
        self.spatial_parts_vecs = np.stack([self.g_dot[:2], swirl])
        _set_arrows(self.spatial_parts, [[0, 0], self.g_dot[:2]], self.spatial_parts_vecs)
        _set_arrows(self.spatial, [0, 0], self.xi_s[:2])
        self.lever.set_data([x, 0], [y, 0])
        f = _vec
        self.texts[0].set_text(f"ġ = {f(self.g_dot)}")
        self.texts[1].set_text(f"ξ = {f(xi)}  (red: ξˣ, green: ξʸ)")
        self.texts[2].set_text(f"ξ = T_gL_g⁻¹ ġ = {f(SE2.world_to_body(g, self.g_dot))}")
        self.texts[3].set_text(f"ξˢ = {f(self.xi_s)} = ġ + ξᶿ × l")


def _matrix_lines(M):
    return "\n".join("[" + "  ".join(f"{v:+7.3f}" for v in row) + " ]" for row in M)


class AdjointScene(Scene):
    """(1.40)-(1.45): Ad_g three ways, plus the spatial velocity by finite differences of g(t) g(t)^-1.

    Values ``x, y, theta`` (g) and ``vx, vy, w`` (body velocity xi).
    """

    def make_figure(self):
        fig, ax = new_figure(figsize=(7.6, 2.9))
        fig.subplots_adjust(left=0.0, right=1.0, bottom=0.0, top=1.0)
        return fig, [ax]

    def decorate(self):
        (ax,) = self.axes
        ax.set_axis_off()
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1)
        heads = ["Ad_g, closed form (1.43)", "T_gR_g⁻¹ · T_eL_g  (1.40)", "same, finite differences"]
        for k, s in enumerate(heads):
            PathText(ax, 0.02 + 0.33 * k, 0.92, s, size=8, weight="bold")

    def create(self):
        (ax,) = self.axes
        self.blocks = [PathText(ax, 0.02 + 0.33 * k, 0.82, "", size=8, va="top", color=c)
                       for k, c in enumerate(("k", "tab:blue", "tab:green"))]
        self.summary = PathText(ax, 0.02, 0.42, "", size=8, va="top")

    def set(self, x=1.0, y=-0.5, theta=0.8, vx=0.5, vy=0.2, w=0.7):
        g = np.array([x, y, theta])
        xi = np.array([vx, vy, w])
        e = SE2.identity()
        ginv = SE2.inverse(g)
        self.Ad = SE2.Ad(g)
        Ad_tn = SE2.right_lifted_action(ginv, g) @ SE2.left_lifted_action(g, e)
        self.Ad_fd = SE2.numerical_right_lifted_action(ginv, g) @ SE2.numerical_left_lifted_action(g, e)
        # independent check with velocities: xi_s = d/dt (g(t) g^-1) at t = 0 with g(t) = g exp(t xi)
        hstep = 1e-6
        Mp = SE2.matrix(SE2.compose(g, SE2.exp(hstep * xi))) @ SE2.matrix(ginv)
        Mm = SE2.matrix(SE2.compose(g, SE2.exp(-hstep * xi))) @ SE2.matrix(ginv)
        self.xi_s_fd = SE2.vee((Mp - Mm) / (2 * hstep))
        self.xi_s = self.Ad @ xi
        self.mismatch = float(max(np.abs(self.Ad - Ad_tn).max(), np.abs(self.Ad - self.Ad_fd).max()))
        for blk, M in zip(self.blocks, (self.Ad, Ad_tn, self.Ad_fd)):
            blk.set_text(_matrix_lines(M))
        f = lambda a: _vec(a, 4)  # noqa: E731
        self.summary.set_text(
            f"largest difference between the three matrices: {self.mismatch:.1e}\n"
            f"{f(self.xi_s)}   ξˢ = Ad_g ξ\n"
            f"{f(self.xi_s_fd)}   ξˢ from d/dt (g(t) g⁻¹) by finite differences, g(t) = g exp(tξ)\n"
            f"{f(SE2.Ad_inv(g) @ self.xi_s)}   back again: Ad_g⁻¹ ξˢ = ξ")


# ============================================================================ 1.6 geodesics, exp
def helix_geometry(thetadot, speed=1.0):
    """Diameter, period and pitch of the SE(2) geodesic of xi = (speed, 0, thetadot): a dict.

    Thin wrapper over :func:`gm_core.fields.se2_helix` returning plain floats (inf for a
    straight line, thetadot = 0).
    """
    from ..fields import se2_helix

    geo = se2_helix(np.array([speed, 0.0, thetadot]))
    return {"diameter": float(geo.diameter), "radius": float(geo.radius), "period": float(geo.period),
            "pitch": float(geo.pitch), "arclength": float(geo.arclength),
            "straight": bool(geo.straight), "centre": np.asarray(geo.centre, float)}


class HelixScene(Scene):
    """Fig. 1.18: SE(2) geodesics exp(t (1, 0, thetadot)) as helices in (x, y, theta) and their
    xy shadows, circles through the origin tangent to the x axis. Value ``thetadot``.
    """

    FAMILY = (-2.0, -1.0, -0.5, 0.5, 1.0, 2.0)
    T = np.linspace(-np.pi, np.pi, 121)

    def make_figure(self):
        fig = figure(figsize=(9, 4.2))
        ax3 = fig.add_subplot(1, 2, 1, projection="3d")
        ax2 = fig.add_subplot(1, 2, 2)
        fig.subplots_adjust(left=0.0, right=0.98, bottom=0.04, top=0.9, wspace=0.05)
        return fig, [ax3, ax2]

    def decorate(self):
        from ..fields import se2_helices

        ax3, ax2 = self.axes
        _plain_3d(ax3, lim=3.2, labels=("x", "y", "θ"))
        ax3.set_zlim(-7.0, 7.0)
        ax3.view_init(elev=22, azim=-62)
        _plane(ax2, 3.2)
        _title(ax2, "xy projection: circles through the origin")
        paths, _ = se2_helices(np.array(self.FAMILY), self.T)
        segs3 = [p for p in paths]
        ax3.add_collection3d(Line3DCollection(segs3, colors="0.7", linewidths=0.8))
        ax2.add_collection(LineCollection([p[:, :2] for p in paths], colors="0.75", linewidths=0.8))

    def create(self):
        ax3, ax2 = self.axes
        (self.helix,) = ax3.plot([], [], [], color="tab:red", lw=2.2)
        (self.circle,) = ax2.plot([], [], color="tab:red", lw=2.2)
        (self.unit,) = ax2.plot([], [], color="k", lw=3.5, alpha=0.6)
        (self.centre,) = ax2.plot([], [], "+", color="tab:red", ms=9)
        self.title3 = PathText(ax3, 0.5, 0.98, "", size=9, ha="center", va="top", coords="axes")
        self.info = PathText(ax2, 0.03, 0.04, "", size=8, coords="axes")

    def set(self, thetadot=1.0):
        from ..fields import se2_helices

        paths, _ = se2_helices(np.array([thetadot]), self.T)
        self.path = paths[0]
        self.helix.set_data_3d(self.path[:, 0], self.path[:, 1], self.path[:, 2])
        self.geometry = geo = helix_geometry(thetadot)
        self.circle.set_data(self.path[:, 0], self.path[:, 1])
        unit = SE2.exp(np.linspace(0, 1, 30)[:, None] * np.array([1.0, 0.0, thetadot]))
        self.unit.set_data(unit[:, 0], unit[:, 1])
        self.title3.set_text(f"helix in (x, y, θ) for ξ = (1, 0, {thetadot:.2f})")
        if geo["straight"]:
            self.centre.set_visible(False)
            self.info.set_text("dθ/dt = 0: a straight line (the circle's diameter is infinite)")
        else:
            self.centre.set_visible(True)
            self.centre.set_data([geo["centre"][0]], [geo["centre"][1]])
            self.info.set_text(f"diameter 2|v|/|dθ/dt| = {geo['diameter']:.2f};  one turn: t = "
                               f"{geo['period']:.2f}, θ rises 2π\nblack: exp(ξ), xy length |v| = 1")


class PuckArcScene(Scene):
    """Fig. 1.19: the (R^2 x S^1, +) 'spinning puck' and the SE(2) arc, same xi, same time t.

    Values ``t`` and ``w`` (xi = (1, 1, w) as in the book for w = 1). A third panel shows each
    path's *body-frame* forward velocity: constant on SE(2), oscillating for the puck.
    """

    T_MAX = 2 * np.pi

    def make_figure(self):
        fig, axes = new_figure(1, 3, figsize=(10, 3.6), gridspec_kw=dict(width_ratios=[1, 1, 1.1]))
        fig.subplots_adjust(left=0.02, right=0.98, bottom=0.12, top=0.88, wspace=0.12)
        return fig, list(axes)

    def decorate(self):
        a, b, c = self.axes
        _plane(a, 4.5)
        _plane(b, 4.5)
        _title(a, "(R² × S¹, +): straight line, spinning")
        _title(b, "SE(2): arc, constant body velocity")
        c.set_xlim(0, self.T_MAX)
        c.set_ylim(-1.6, 1.6)
        c.axhline(0, color="0.6", lw=0.8)
        _xticks(c, [0, np.pi, 2 * np.pi], ["0", "π", "2π  t"])
        _yticks(c, [-1, 0, 1], ["−1", "0", "1"])
        _title(c, "forward speed seen by the body")

    def create(self):
        a, b, c = self.axes
        self.paths = [TrailArtist(ax, color=col, lw=1.2, alpha=0.6) for ax, col in
                      ((a, "tab:purple"), (b, "tab:blue"))]
        self.trails = [TrailArtist(ax, color=col, lw=2.5) for ax, col in ((a, "tab:purple"), (b, "tab:blue"))]
        self.bodies = [BodyArtist(ax, BODY * 1.4, facecolor=col) for ax, col in
                       ((a, "tab:purple"), (b, "tab:blue"))]
        self.frames = [FrameArtist(ax, length=0.5) for ax in (a, b)]
        (self.fwd_puck,) = c.plot([], [], color="tab:purple", lw=1.8)
        (self.fwd_arc,) = c.plot([], [], color="tab:blue", lw=1.8)
        (self.now,) = c.plot([], [], color="k", lw=1)
        self._w = None

    def set(self, t=1.0, w=1.0):
        from ..fields import puck_vs_arc

        if w != self._w:
            ts = np.linspace(0, self.T_MAX, 181)
            self.full = puck_vs_arc(ts, xi=(1.0, 1.0, w))
            self.paths[0].set(self.full.puck[:, :2])
            self.paths[1].set(self.full.arc[:, :2])
            self.fwd_puck.set_data(ts, self.full.puck_body_velocity[:, 0])
            self.fwd_arc.set_data(ts, self.full.arc_body_velocity[:, 0])
            self._w = w
        now = puck_vs_arc(np.linspace(0, t, 60), xi=(1.0, 1.0, w))
        self.now_state = now
        for k, P in enumerate((now.puck, now.arc)):
            self.trails[k].set(P[:, :2])
            self.bodies[k].set(P[-1])
            self.frames[k].set(P[-1])
        self.now.set_data([t, t], [-1.6, 1.6])


def puck_vs_arc_animation(w=1.0, frames=48, interval=80):
    """FuncAnimation of fig. 1.19 (play it with ``gm_core.drawing.base.jshtml``; no kernel needed)."""
    scene = PuckArcScene()
    ts = np.linspace(0.0, PuckArcScene.T_MAX, frames)

    def step(k):
        scene.set(t=float(ts[k]), w=w)
        return []

    scene.set(t=0.0, w=w)
    return animate(scene.fig, step, frames=frames, interval=interval)


class RPlusGeodesicScene(Scene):
    """Fig. 1.17: geodesics g(t) = exp(t xi) of (R+, x) from e = 1, with the invariant field's arrows.

    Value ``xi``. Every unit of time multiplies g by the same factor exp(xi), so the curve speeds
    up (xi > 0) or slows down (xi < 0); the dashed line is the additive (R, +) geodesic with the
    same starting velocity, for contrast.
    """

    T = np.linspace(0.0, 3.0, 121)

    def make_figure(self):
        fig, ax = new_figure(figsize=(6.4, 4.2))
        fig.subplots_adjust(left=0.09, right=0.97, bottom=0.1, top=0.9)
        return fig, [ax]

    def decorate(self):
        from ..fields import rplus_geodesics

        (ax,) = self.axes
        ax.set_xlim(0, 3)
        ax.set_ylim(0, 8)
        _xticks(ax, [0, 1, 2, 3], ["0", "1", "2", "3  t"])
        _yticks(ax, [0, 1, np.e, 4, 6, 8], ["0", "1 = e (identity)", "ℯ = 2.718…", "4", "6", "8"])
        ax.axhline(1.0, color="0.7", lw=0.8)
        g, _ = rplus_geodesics(np.array([-1.0, -0.5, 0.5, 1.0]), self.T)
        ax.add_collection(LineCollection([np.c_[self.T, gi] for gi in g], colors="0.8", linewidths=1))

    def create(self):
        (ax,) = self.axes
        (self.curve,) = ax.plot([], [], color="tab:red", lw=2.2)
        (self.additive,) = ax.plot([], [], color="tab:blue", lw=1.2, ls="--")
        self.arrows = _arrow(ax, color="tab:red", n=4, width=0.006)
        (self.marks,) = ax.plot([], [], "o", color="k", ms=5)
        self.title = _title(ax)
        self.info = PathText(ax, 0.03, 0.93, "", size=8, va="top", coords="axes")

    def set(self, xi=1.0):
        from ..fields import rplus_geodesics

        g, g_dot = rplus_geodesics(np.array(xi), self.T)
        self.g = g
        self.curve.set_data(self.T, g)
        self.additive.set_data(self.T, 1.0 + xi * self.T)
        tk = np.array([0.0, 1.0, 2.0, 3.0])
        gk = RPlus.exp(tk[:, None] * xi)[:, 0]
        self.slopes = xi * gk                    # T_eL_g xi = g xi, the left-invariant field (1.46)
        dt = 0.35
        _set_arrows(self.arrows, np.c_[tk, gk], np.c_[np.full(4, dt), dt * self.slopes])
        self.marks.set_data(tk, gk)
        self.ratios = gk[1:] / gk[:-1]
        self.title.set_text(f"ξ = {xi:.2f}: exp(ξ) = {np.exp(xi):.4f}"
                            + ("  — this is e" if abs(xi - 1) < 1e-12 else ""))
        self.info.set_text("g(t+1)/g(t) = " + ", ".join(f"{r:.4f}" for r in self.ratios)
                           + "\narrows: slope ġ = ξ g (left-invariant field)")


class ExpFourWaysScene(Scene):
    """Section 1.6.4 / exercise 1.4d: exp(xi) on SE(2) by closed form, Taylor series, the product
    (I + xi^/n)^n and Euler steps, for xi = (1, 0, thetadot).

    Values ``thetadot``, ``n`` and ``side`` ("left" or "right" invariant field, for Euler). Left:
    error against the number of steps/terms (log-log), with the current n marked. Right: the
    intermediate values of each method in the xy plane, over the closed-form arc.
    """

    NS = tuple(2 ** k for k in range(7))
    METHODS = (("taylor", "tab:green", "Taylor partial sums"), ("product", "tab:blue", "(I + ξ^/n)ᵏ"),
               ("euler", "tab:orange", "Euler steps"))

    def make_figure(self):
        fig, axes = new_figure(1, 2, figsize=(9.6, 4.0))
        fig.subplots_adjust(left=0.08, right=0.98, bottom=0.11, top=0.9, wspace=0.15)
        return fig, list(axes)

    def decorate(self):
        a, b = self.axes
        a.set_xlim(-0.2, 6.3)
        a.set_ylim(-17, 1.5)
        _xticks(a, range(7), [str(n) for n in self.NS])
        _yticks(a, [0, -4, -8, -12, -16], ["1", "1e-4", "1e-8", "1e-12", "1e-16"])
        _title(a, "error ‖estimate − exp(ξ^)‖ against n (log scales)")
        PathText(a, 6.2, -16.5, "n steps / terms →", size=7.5, ha="right")
        b.set_aspect("equal")
        b.set_xticks([])
        b.set_yticks([])
        # one fixed window holds every arc exp(s xi), |thetadot| <= 3 (fixed limits keep slider
        # changes cheap); early Taylor partial sums may leave it, which is part of the story
        b.set_xlim(-0.55, 1.35)
        b.set_ylim(-0.95, 0.95)
        b.axhline(0, color="0.85", lw=0.8, zorder=0)
        b.axvline(0, color="0.85", lw=0.8, zorder=0)
        _title(b, "intermediate values in the xy plane")

    def create(self):
        a, b = self.axes
        self.err_lines, self.err_marks, self.path_lines = {}, {}, {}
        for k, (m, col, label) in enumerate(self.METHODS):
            (self.err_lines[m],) = a.plot([], [], "-o", color=col, ms=4, lw=1.5)
            (self.err_marks[m],) = a.plot([], [], "*", color=col, ms=13, mec="k", mew=0.5)
            (self.path_lines[m],) = b.plot([], [], "-o", color=col, ms=3.5, lw=1.0, alpha=0.85)
            PathText(a, 0.03, 0.30 - 0.07 * k, label, size=8, color=col, coords="axes")
        (self.arc,) = b.plot([], [], color="0.3", lw=2.5, alpha=0.5)
        (self.target,) = b.plot([], [], "k*", ms=12)
        self.info = PathText(b, 0.02, 0.03, "", size=7.5, coords="axes")
        self._key = None

    def set(self, thetadot=1.0, n=8, side="left"):
        from ..calculus import exp_history

        n = int(n)
        xi = np.array([1.0, 0.0, thetadot])
        key = (thetadot, side)
        if key != self._key:
            self.histories = {m: exp_history(SE2, xi, self.NS, m, side) for m, _, _ in self.METHODS}
            for m, h in self.histories.items():
                self.err_lines[m].set_data(np.log2(h.n), np.log10(np.maximum(h.error, 1e-16)))
            s = np.linspace(0, 1, 60)
            arc = SE2.exp(s[:, None] * xi)
            self.arc.set_data(arc[:, 0], arc[:, 1])
            end = SE2.exp(xi)
            self.target.set_data([end[0]], [end[1]])
            self._key = key
        self.final_error = {}
        for m, _, _ in self.METHODS:
            path = self.histories[m].path(n)
            self.final_error[m] = float(path.error[-1]) if m != "taylor" else float(
                np.linalg.norm(path.matrices[-1] - SE2.matrix(SE2.exp(xi))))
            self.err_marks[m].set_data([np.log2(n)], [np.log10(max(self.final_error[m], 1e-16))])
            pts = path.matrices[:, :2, 2] if m != "taylor" else path.matrices[1:, :2, 2]
            self.path_lines[m].set_data(pts[:, 0], pts[:, 1])
        self.info.set_text("n = {}:  ".format(n) + "   ".join(
            f"{m} {self.final_error[m]:.1e}" for m, _, _ in self.METHODS))


def binomial_table(ns=(5, 10, 100, 1000), kmax=5):
    """Rows (n, k, C(n,k), C(n,k)/n^k, 1/k!, n^k/k!) showing why (I + A/n)^n -> sum A^k/k!.

    Uses :func:`gm_core.calculus.binomial_terms`; the last column is the draft's coefficient in
    (1.50), which is *not* C(n, k).
    """
    from ..calculus import binomial_terms

    rows = []
    for n in ns:
        for k in range(kmax + 1):
            c, ratio = binomial_terms(n, k)
            rows.append((n, k, c, ratio, 1.0 / factorial(k), n ** k / factorial(k)))
    return rows

"""Shared drawing primitives: SE(2) frames, rigid bodies, trails, animations.

Every artist here is built once and then updated with ``set(...)`` (``set_data``, ``set_xy``,
``set_UVC``), so a slider callback only moves existing artists and never builds a new figure.
"""
from __future__ import annotations

import base64
import io
import os
import pathlib
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any, SupportsInt, cast

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.animation import AbstractMovieWriter, FuncAnimation
from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Polygon
from matplotlib.typing import ColorType
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.drawing.toolkit.style import DPI, PALETTE
from gm_core.groups import SE2
from gm_core.validation import FloatArray

if TYPE_CHECKING:
    from IPython.display import HTML

__all__ = ["testing", "n_frames", "FrameArtist", "BodyArtist", "TrailArtist",
           "SingularFlag", "animate", "jshtml", "ProgressNote"]


def testing() -> bool:
    """True when running under the test suite (GM_COURSE_TESTING=1): animations get shorter."""
    return os.environ.get("GM_COURSE_TESTING", "") == "1"


def n_frames(n: int, under_test: int = 6) -> int:
    """Number of animation frames to render: ``n`` normally, ``under_test`` under the test suite."""
    return min(n, under_test) if testing() else n


class FrameArtist:
    """An SE(2) coordinate frame drawn as two arrows (x axis ``PALETTE["x"]``, y axis ``PALETTE["y"]``) at g."""

    def __init__(self, ax: Axes, g: ArrayLike = (0.0, 0.0, 0.0), length: float = 0.4,
                 colors: Sequence[ColorType] = (PALETTE["x"], PALETTE["y"]), zorder: float = 5, **kw: Any) -> None:
        self.ax = ax
        self.length = float(length)
        self.quiver = ax.quiver([0, 0], [0, 0], [1, 0], [0, 1], color=list(colors), angles="xy",
                                scale_units="xy", scale=1.0, width=0.006, zorder=zorder, **kw)
        self.set(g)

    def set(self, g: ArrayLike) -> None:
        x, y, t = np.asarray(g, dtype=float)
        L = self.length
        c, s = np.cos(t), np.sin(t)
        self.quiver.set_offsets([[x, y], [x, y]])
        self.quiver.set_UVC([L * c, -L * s], [L * s, L * c])
        self.g = np.array([x, y, t])

    def remove(self) -> None:
        self.quiver.remove()


class BodyArtist:
    """A rigid body: a polygon given in body-frame coordinates, placed at g by (1.11)-(1.12).

    ``update_limits=False`` adds the polygon without updating the axes' data limits (for a scene that
    sets its limits itself; matplotlib's update costs a few milliseconds per polygon).
    """

    def __init__(self, ax: Axes, outline: ArrayLike, g: ArrayLike = (0.0, 0.0, 0.0), update_limits: bool = True,
                 **style: Any) -> None:
        self.outline = np.asarray(outline, dtype=float)
        style.setdefault("facecolor", PALETTE["blue"])
        style.setdefault("alpha", 0.5)
        style.setdefault("edgecolor", "k")
        self.patch = Polygon(self.outline, closed=True, **style)
        if update_limits:
            ax.add_patch(self.patch)
        else:                     # add_patch without its data-limit update: clipped to the axes all the same
            ax.add_artist(self.patch)
        self.set(g)

    def set(self, g: ArrayLike) -> None:
        self.g = np.asarray(g, dtype=float)
        self.patch.set_xy(SE2.act_on_points(self.g, self.outline))

    @staticmethod
    def triangle(size: float = 0.3) -> FloatArray:
        """Outline of an isosceles triangle pointing along the body x axis (the book's robot)."""
        return size * np.array([[1.0, 0.0], [-0.6, 0.55], [-0.6, -0.55]])

    @staticmethod
    def rectangle(length: float, width: float) -> FloatArray:
        """Outline of a length x width rectangle centred on the body frame."""
        a, b = length / 2, width / 2
        return np.array([[-a, -b], [a, -b], [a, b], [-a, b]])


class TrailArtist:
    """A path drawn as one Line2D; ``set(points)`` replaces its data, ``append(p)`` extends it."""

    def __init__(self, ax: Axes, points: ArrayLike | None = None, **style: Any) -> None:
        style.setdefault("lw", 1.5)
        (self.line,) = ax.plot([], [], **style)
        self._pts = np.zeros((0, 2))
        if points is not None:
            self.set(points)

    def set(self, points: ArrayLike) -> None:
        self._pts = np.asarray(points, dtype=float).reshape(-1, 2)
        self.line.set_data(self._pts[:, 0], self._pts[:, 1])

    def append(self, p: ArrayLike) -> None:
        self.set(np.vstack([self._pts, np.asarray(p, dtype=float)[:2]]))


class SingularFlag:
    """A text banner shown on an axes when a configuration is singular, hidden otherwise.

    Drawing code must never pass inf or NaN silently to the plot: it calls ``flag.show(msg)``
    instead and hides the affected artists.
    """

    def __init__(self, ax: Axes, loc: tuple[float, float] = (0.5, 0.95)) -> None:
        self.text = ax.text(*loc, "", transform=ax.transAxes, ha="center", va="top", color="darkred",
                            fontsize=10, fontweight="bold",
                            bbox=dict(facecolor="mistyrose", edgecolor="darkred", alpha=0.9))
        self.text.set_visible(False)

    def show(self, message: str) -> None:
        self.text.set_text(message)
        self.text.set_visible(True)

    def hide(self) -> None:
        self.text.set_visible(False)

    @property
    def visible(self) -> bool:
        return self.text.get_visible()


class _KeptAnimation(FuncAnimation):
    """A FuncAnimation that keeps, for :func:`jshtml`, what FuncAnimation keeps privately."""

    gm_figure: Figure
    gm_interval: float
    gm_palette: bool
    gm_frames: int


def animate(fig: Figure, update: Callable[[Any], Iterable[Artist] | None], frames: int | Iterable[Any],
            interval: float = 50, palette: bool = False, **kw: Any) -> FuncAnimation:
    """A FuncAnimation calling ``update(frame)``; shortened under the test suite (see n_frames).

    ``palette=True`` lets :func:`jshtml` store the frames with 256 colours (about a third of the
    bytes): right for line art, where it changes no pixel by more than a few levels; wrong for
    smooth colour maps, which it would band.
    """
    if np.isscalar(frames):
        frames = count = n_frames(int(cast(SupportsInt, frames)))   # a scalar here: a count of frames
    else:
        frames = list(cast(Iterable[Any], frames))   # not a scalar: the frames themselves
        if testing():
            idx = np.linspace(0, len(frames) - 1, n_frames(len(frames))).round().astype(int)
            frames = [frames[i] for i in idx]
        count = len(frames)
    anim = _KeptAnimation(fig, update, frames=frames, interval=interval, blit=False, **kw)
    anim.gm_figure = fig   # read by jshtml (FuncAnimation keeps its figure and interval privately)
    anim.gm_interval = interval
    anim.gm_palette = bool(palette)
    anim.gm_frames = count   # for jshtml's progress note
    return anim


class _FrameCollector(AbstractMovieWriter):
    """A movie writer (matplotlib's public writer interface) that keeps every frame as a PNG data
    URL; ``on_frame(k)`` (if given) is called after frame ``k`` (from 1) is kept."""

    def __init__(self, palette: bool = False, on_frame: Callable[[int], object] | None = None) -> None:
        super().__init__(fps=20)
        self.frames: list[str] = []
        self.palette = palette
        self.on_frame = on_frame

    @override
    def setup(self, fig: Figure, outfile: str | pathlib.Path, dpi: float | None = None) -> None:
        super().setup(fig, outfile, dpi=dpi)

    @override
    def grab_frame(self, **savefig_kwargs: Any) -> None:
        self.frames.append(_png_data_url(self.fig, self.dpi, self.palette, **savefig_kwargs))
        if self.on_frame is not None:
            self.on_frame(len(self.frames))

    @override
    def finish(self) -> None:
        pass


def _png_data_url(fig: Figure, dpi: float, palette: bool = False, **savefig_kwargs: Any) -> str:
    """The figure as a PNG data URL; with ``palette``, in at most 256 colours.

    Line art holds a couple of thousand distinct colours, nearly all antialiasing shades, so a
    max-coverage palette (which keeps rare colours such as a small marker's; median cut turned a
    gold dot orange) changes no pixel by more than about ten levels and makes a frame about a third
    as large: notebook 11's 48-frame gait animation went from 4.0 MB to 1.4 MB of page.
    """
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, **savefig_kwargs)
    if palette:
        from PIL import Image

        with Image.open(buf) as im:
            buf = io.BytesIO()
            im.convert("RGB").quantize(256, method=Image.Quantize.MAXCOVERAGE).save(buf, format="png")
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def _in_kernel() -> bool:
    """True inside a Jupyter kernel (where a display can be updated in place)."""
    try:
        from IPython import get_ipython
    except ImportError:   # IPython is a dependency of the widgets, not of the drawing layer
        return False
    return getattr(get_ipython(), "kernel", None) is not None


class ProgressNote:
    """A one-line note shown while something is drawn, updated in place and removed when done.

    ``ProgressNote("drawing the animation")`` displays the line (with an IPython display id),
    ``update(k, n)`` says ``frame k of n``, and ``done()`` replaces it by nothing, so no stale
    "drawing ..." line stays above the result. Outside a kernel (``show=False``) it does nothing.
    Also a context manager: ``done()`` runs on exit, whatever happened.
    """

    def __init__(self, what: str = "drawing the animation", show: bool | None = None) -> None:
        self.what = what
        self.shown = _in_kernel() if show is None else bool(show)
        self.handle: Any = None
        if self.shown:
            from IPython.display import HTML, display

            self.handle = display(HTML(self._html(f"{what} …")), display_id=True)

    @staticmethod
    def _html(text: str) -> str:
        return f'<span class="gm-progress-note" style="color: #555">{text}</span>'

    def update(self, k: int, n: int) -> None:
        """Say that step ``k`` of ``n`` is done."""
        if self.handle is not None:
            from IPython.display import HTML

            self.handle.update(HTML(self._html(f"{self.what}: frame {k} of {n} …")))

    def done(self) -> None:
        """Remove the note (its output becomes empty): nothing stale stays on the page."""
        if self.handle is not None:
            from IPython.display import HTML

            self.handle.update(HTML(""))
            self.handle = None

    def __enter__(self) -> ProgressNote:
        return self

    def __exit__(self, *exc: object) -> None:
        self.done()


def jshtml(anim: FuncAnimation, default_mode: str = "loop", progress: bool | None = None) -> HTML:
    """An IPython HTML object that plays ``anim`` in the page, with no live kernel and offline.

    Every frame is rendered at the figure standard's resolution through ``anim.save`` (a movie
    writer that keeps PNG frames); :func:`gm_core.drawing.toolkit.player.player_html` writes the player:
    the first frame is the image's own source (a picture before, or without, any script), the
    icons are inline SVG and the script is the course's own (no CDN, no request).

    While the frames are drawn, a :class:`ProgressNote` says which one (``progress``: default in a
    Jupyter kernel only); it is removed when the player is ready, so a notebook needs no
    "drawing the animation ..." line of its own, which would stay behind.
    """
    from IPython.display import HTML

    from gm_core.drawing.toolkit.player import player_html

    fig = getattr(anim, "gm_figure", None)
    if fig is None:
        raise TypeError("jshtml needs an animation made by gm_core.drawing.toolkit.primitives.animate")
    fig.set_dpi(DPI)          # frames at the standard's resolution: 1 inch = 100 CSS px
    n = getattr(anim, "gm_frames", None)
    with ProgressNote("drawing the animation", show=progress) as note:
        writer = _FrameCollector(palette=getattr(anim, "gm_palette", False),
                                 on_frame=None if n is None else (lambda k: note.update(k, n)))
        anim.save("frames-kept-in-memory", writer=writer, dpi=DPI)
    plt.close(fig)
    return HTML(player_html(writer.frames, interval=getattr(anim, "gm_interval", 50),
                            width=fig.get_figwidth() * DPI, mode=default_mode))

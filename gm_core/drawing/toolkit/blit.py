"""Blitting for live panels: redraw only the artists a slider moved.

A full matplotlib draw re-renders every tick label, grid line and static curve; for a four-axes
figure that is 50-100 ms, whatever the update did. Blitting (the technique of matplotlib's
"Faster rendering by using blitting" guide) keeps a picture of the static background and, for
each frame, pastes it back and draws just the moving artists on top. ipympl supports it through
webagg's diff images: ``canvas.blit`` marks the picture old and sends only changed pixels.

:class:`Blitter` needs no list of moving artists from the panel. During a frame it intercepts
``canvas.draw_idle``; afterwards the leaf artists that the update made *stale* are the moving
ones. New moving artists, a changed view (axis limits; for 3D axes also the viewing angles, which
a student changes by dragging), a new axis label or a missing background trigger one full draw
(the ``draw_event`` callback then captures the background without the animated artists and
paints them on top); every later frame is a blit. In 3D the moving artists are projected with the view of the last
full draw, which the view check keeps current (3-D collections through their public
``do_3d_projection``, which only the axes' own draw would call).

Every picture of a live (webagg/ipympl) canvas leaves at once: a blit is sent by ``canvas.blit``,
and a full draw, the blitter's or a non-blitted panel's (:func:`drawn_at_once`), is drawn and sent
right after the update instead of through webagg's ``draw_idle``, which asks the browser to ask
for the picture (a round trip before the draw).

:class:`KeyFrames` makes a live (webagg/ipympl) canvas always end on the truth. webagg sends
each picture as a *difference* from the one sent before, and the browser drops a picture that
arrives while the previous one is still loading (matplotlib issue 19116, PR 19762): after a
fast drag the next differences are painted over a picture the browser never showed, and old
arms, curves and readouts stay on the canvas. So once the changes stop for ``delay`` seconds, a
key frame is sent: the figure is drawn in full and sent whole (webagg's own "refresh" request,
which is what a newly connected browser asks for). A slider burst still gets the fast
difference frames; its last picture is always complete.

Both assume that one thread draws the figure: the slider updates, the browser's draw requests
(answered by ipympl) and the key frame's timer all run on the kernel's main thread. JupyterLab's
``commsOverSubshells`` setting must be off for that (the course's settings turn it off,
tools/lab_settings.py): with it on, ipykernel >= 7 serves widget messages on a subshell thread
and two threads draw into one Agg buffer at once (half-drawn pictures, lost frames).
"""
from __future__ import annotations

from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, cast

from matplotlib.artist import Artist
from matplotlib.axes import Axes
from matplotlib.axis import Axis
from matplotlib.backend_bases import DrawEvent, FigureCanvasBase
from matplotlib.figure import Figure
from matplotlib.image import AxesImage
from matplotlib.legend import Legend
from matplotlib.spines import Spine
from matplotlib.text import Text
from matplotlib.transforms import Bbox

if TYPE_CHECKING:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.backends.backend_webagg_core import FigureCanvasWebAggCore
    from mpl_toolkits.mplot3d.axes3d import Axes3D

__all__ = ["Blitter", "KeyFrames", "can_blit", "drawn_at_once", "hold_pictures_until_view", "sends_differences"]


def can_blit(fig: Figure) -> bool:
    """True if ``fig`` can be blitted: its canvas can copy and restore regions (Agg-based)."""
    canvas = fig.canvas
    return hasattr(canvas, "copy_from_bbox") and hasattr(canvas, "restore_region")


def sends_differences(fig: Figure) -> bool:
    """True if ``fig``'s canvas sends pictures to a browser as differences (webagg, ipympl)."""
    from matplotlib.backends.backend_webagg_core import FigureCanvasWebAggCore

    return isinstance(fig.canvas, FigureCanvasWebAggCore)


def _overlap(a: Bbox, b: Bbox) -> bool:
    """True if two display boxes share an area (touching edges or empty boxes do not count)."""
    i = Bbox.intersection(a, b)
    return i is not None and i.width > 0 and i.height > 0


def _no_view_yet(canvas: FigureCanvasBase) -> bool:
    """True while an ipympl canvas has no initialised browser view (``syncing_data_url``): a
    picture sent then only replaces the canvas' ``_data_url`` (without its ``data:`` prefix, so
    the browser's image breaks). Until the view asks for its first picture, only draw requests
    (``draw_idle``, answered by the browser) are made."""
    return bool(getattr(canvas, "syncing_data_url", False))


def hold_pictures_until_view(fig: Figure) -> bool:
    """Under ipympl, send no picture of ``fig`` before its browser view has said 'initialized'.

    ipympl 0.10 treats a picture sent before that message (``syncing_data_url``) as the figure's
    saved state: it stores it in ``_data_url`` without the ``data:`` prefix and sends the browser
    raw pixels for a PNG, so the canvas breaks and later differences are painted on nothing. The
    kernel only draws when asked, but the browser's answer ('draw') to a draw request can be
    handled before its own earlier 'initialized': JupyterLab >= 4.4 sends a new canvas's first
    messages on the main shell, behind the cells Run All queued, and its later ones on a kernel
    subshell that ipykernel 7 serves at once (commsOverSubshells, on by default; the course's
    settings turn it off, see the module doc, but a student's JupyterLab may not). Until then every
    picture is held back (webagg's ``manager.refresh_all``, which ``draw`` and ``blit`` call to
    send); the one held back goes out whole right after 'initialized'. Other canvases are left
    as they are. Returns True if ``fig`` is held."""
    canvas = fig.canvas
    manager = getattr(canvas, "manager", None)
    if manager is None or not (_no_view_yet(canvas) and hasattr(canvas, "on_msg") and hasattr(manager, "refresh_all")):
        return False
    send = manager.refresh_all
    held = False

    def refresh_all() -> None:
        nonlocal held
        if _no_view_yet(canvas):
            held = True   # webagg's picture stays due (_png_is_old); nothing is diffed or sent
        else:
            send()

    def on_msg(widget: object, content: dict[str, Any], buffers: list[bytes]) -> None:
        # runs after ipympl's own handler (registered first), which ends syncing_data_url
        nonlocal held
        if content.get("type") == "initialized" and held and not _no_view_yet(canvas):
            held = False
            send()

    manager.refresh_all = refresh_all
    canvas.on_msg(on_msg)
    return True


@contextmanager
def drawn_at_once(fig: Figure) -> Iterator[None]:
    """Run a panel update inside; on exit a live figure that was asked to redraw is drawn and sent.

    For panels that are not blitted. On a webagg (ipympl) canvas ``draw_idle`` does not draw: it
    asks the browser to ask for a picture, a round trip kernel -> browser -> kernel before the
    draw even starts. Here the update's requests are collected and answered by one full draw,
    which webagg sends at once. A burst of slider changes does not pile up draws: ipywidgets
    sends a control's next value only when the kernel is idle again (its message throttle).
    Until the browser's view exists (:func:`hold_pictures_until_view`) the request is passed on
    instead; on other canvases (Agg, where ``draw_idle`` draws) too.
    """
    canvas = fig.canvas
    if not sends_differences(fig) or _no_view_yet(canvas):
        yield
        return
    requested: list[bool] = []
    real_draw_idle = canvas.draw_idle
    canvas.draw_idle = lambda *a, **k: requested.append(True)  # type: ignore[method-assign]
    try:
        yield
    finally:
        canvas.draw_idle = real_draw_idle  # type: ignore[method-assign]  # put back
    if requested:
        canvas.draw()


def _view(ax: Axes) -> tuple[object, ...]:
    """Everything that places an axes' content on the canvas: limits, and for 3D the camera."""
    # Only side-effect-free reads: get_position() would run apply_aspect(), mark the figure stale
    # and, under ipympl, request another draw from inside the draw callback (a redraw loop).
    view = (tuple(ax.viewLim.bounds),)
    if getattr(ax, "name", "") == "3d":
        ax3 = cast("Axes3D", ax)
        view += (tuple(ax3.get_zlim()), ax3.elev, ax3.azim, getattr(ax3, "roll", 0.0))
    return view


def _leaf_artists(fig: Figure) -> Iterator[Artist]:
    for ax in fig.axes:
        skip = {id(ax.patch)}
        for a in ax.get_children():
            if id(a) in skip or isinstance(a, (Axis, Spine, Legend)):
                continue
            yield a
    yield from fig.texts
    yield from fig.lines
    yield from fig.patches


class Blitter:
    """Render frames of ``fig`` by blitting the artists that changed since the last frame."""

    def __init__(self, fig: Figure) -> None:
        self.fig = fig
        # blitting copies and restores regions of an Agg canvas (ipympl's and inline's; see can_blit)
        self.canvas = cast("FigureCanvasAgg", fig.canvas)
        self.dynamic: list[Artist] = []
        self._ids: set[int] = set()
        self._background: object | None = None   # Agg's saved region (copy_from_bbox), opaque
        self._limits = self._view_limits()
        self._labels = self._axis_labels()
        self._real_draw_idle = self.canvas.draw_idle
        self._cid = self.canvas.mpl_connect("draw_event", self._on_draw)
        self.full_draws = 0
        self.blits = 0

    # -- bookkeeping ------------------------------------------------------------------
    def _view_limits(self) -> list[tuple[object, ...]]:
        return [_view(ax) for ax in self.fig.axes]

    def _on_draw(self, event: DrawEvent | None) -> None:
        """After every full draw: keep the background, then paint the animated artists on it."""
        if self.canvas.is_saving() or (event is not None and event.canvas is not self.canvas):
            # savefig: matplotlib draws animated artists itself while saving, and that picture
            # is not the live background.
            return
        self._background = self.canvas.copy_from_bbox(self.fig.bbox)
        self._limits = self._view_limits()
        self._labels = self._axis_labels()
        self._paint()

    def _axis_labels(self) -> list[str]:
        """The axis labels' texts: parts of their axes, not leaf artists, so never blitted; a new
        one makes the frame a full draw (else it would show only with the key frame, and leave
        the figure stale, which pyplot's draw_all redraws once more when the kernel goes idle:
        a round trip through the browser)."""
        return [axis.label.get_text() for ax in self.fig.axes
                for axis in (ax.xaxis, ax.yaxis, getattr(ax, "zaxis", None)) if axis is not None]

    def _make_dynamic(self, a: Artist) -> None:
        a.set_animated(True)
        self.dynamic.append(a)
        self._ids.add(id(a))

    def _covering(self) -> list[Artist]:
        """Static artists drawn *above* a moving one and overlapping it (a ✓ on a badge whose
        colour changes; the axes frame around a moving image): pasted under the
        moving artist they would vanish, so they move too. Found once, when the set of moving
        artists grows (never per frame)."""
        spines = [sp for ax in self.fig.axes for sp in ax.spines.values()]
        leaves = list(_leaf_artists(self.fig)) + spines
        order = {id(a): (a.get_zorder(), i) for i, a in enumerate(leaves)}
        renderer = self.canvas.get_renderer() if hasattr(self.canvas, "get_renderer") else None

        def extent(a: Artist) -> Bbox | None:
            try:
                box = a.get_window_extent(renderer)
            except Exception:  # an artist without a usable extent: assume it covers everything
                return None
            if isinstance(a, Spine):   # the extent leaves out the line's width, which straddles it
                box = box.padded(a.get_linewidth() * self.fig.dpi / 72.0)
            clip = a.get_clip_box() if a.get_clip_on() else None
            if clip is not None:
                # what a clipped artist paints lies inside its clip box (a body reaching past
                # the axes edge never covers the title above it); an unknown (null) extent
                # becomes the clip box
                box = Bbox.intersection(box, clip) or Bbox([[0.0, 0.0], [0.0, 0.0]])
            return box

        out: list[Artist] = []
        moving = [a for a in self.dynamic if a.figure is not None]
        leaves = [a for a in leaves if not (isinstance(a, Text) and not a.get_text().strip())]
        boxes = {id(a): extent(a) for a in moving}
        changed = True
        while changed:
            changed = False
            for s in leaves:
                if id(s) in self._ids or id(s) in {id(o) for o in out} or not s.get_visible():
                    continue
                for d in moving:
                    if d.axes is not s.axes or order.get(id(s), (0, 0)) <= order.get(id(d), (0, 0)):
                        continue
                    if isinstance(s, Spine) and not isinstance(d, AxesImage):
                        continue   # a frame covers what fills its axes: an image
                    bs, bd = extent(s), boxes.get(id(d))
                    if bs is None or bd is None or _overlap(bs, bd):
                        out.append(s)
                        moving.append(s)
                        boxes[id(s)] = bs
                        changed = True
                        break
        return out

    def _sorted(self) -> list[Artist]:
        # the moving artists in the order a full draw paints them (z-order, then insertion)
        order = {id(a): (a.get_zorder(), i) for i, a in enumerate(_leaf_artists(self.fig))}
        return sorted((a for a in self.dynamic if a.figure is not None),
                      key=lambda a: order.get(id(a), (a.get_zorder(), 0)))

    def _paint(self) -> None:
        for a in self._sorted():
            if a.axes is not None:
                project = getattr(a, "do_3d_projection", None)
                if project is not None and getattr(a.axes, "name", "") == "3d":
                    # a 3-D collection is projected by its axes' draw, not its own: project it here
                    project()
                a.axes.draw_artist(a)
            else:
                self.fig.draw_artist(a)

    # -- frames -------------------------------------------------------------------------
    @contextmanager
    def frame(self) -> Iterator[None]:
        """Run a panel update inside; on exit the figure is refreshed by a blit or a full draw."""
        requested: list[bool] = []
        # the canvas's draw_idle is swapped on the instance for the frame, then put back
        self.canvas.draw_idle = lambda *a, **k: requested.append(True)  # type: ignore[method-assign]
        try:
            yield
        finally:
            self.canvas.draw_idle = self._real_draw_idle  # type: ignore[method-assign]  # put back
        self.refresh()

    def refresh(self) -> None:
        new = [a for a in _leaf_artists(self.fig) if a.stale and id(a) not in self._ids]
        if self._background is None or _no_view_yet(self.canvas):
            # No background yet (never drawn): everything is new, nothing is known to move. (Or
            # no browser view yet: only the browser's own draw request may send a picture.)
            self._full_draw()
            return
        if new or self._view_limits() != self._limits or self._axis_labels() != self._labels:
            for a in new:
                self._make_dynamic(a)
            if new:
                for a in self._covering():
                    self._make_dynamic(a)
            self._full_draw()
            return
        self.canvas.restore_region(self._background)
        self._paint()
        self.canvas.blit(self.fig.bbox)
        self.blits += 1

    def _full_draw(self) -> None:
        self._background = None
        self.full_draws += 1
        if sends_differences(self.fig) and not _no_view_yet(self.canvas):
            self.canvas.draw()   # at once: webagg's draw_idle is a round trip through the browser
        else:
            self._real_draw_idle()

    def disconnect(self) -> None:
        self.canvas.mpl_disconnect(self._cid)
        for a in self.dynamic:
            a.set_animated(False)
        self.dynamic.clear()
        self._ids.clear()


class KeyFrames:
    """Send one whole picture of ``fig`` after the last change of every burst (see module doc).

    :meth:`touch` (called after every update) and every full draw restart a single-shot timer of
    ``delay`` seconds on the canvas's own event loop; when it fires the figure is drawn in full
    and sent as a complete image. The key frame's own draw does not restart the timer, and it
    asks the browser for nothing, so the key frame is the last picture the browser receives.
    ``before`` (optional) runs just before the key frame is drawn: what a panel leaves for the
    end of a burst (a 3-D camera that turns with the point, :meth:`~gm_core.drawing.toolkit.style.Scene.settle`).
    """

    def __init__(self, fig: Figure, delay: float = 0.25, before: Callable[[], object] | None = None) -> None:
        self.fig = fig
        self.before = before
        # a key frame is webagg's "refresh" (ipympl's canvas is a webagg one; see sends_differences)
        self.canvas = cast("FigureCanvasWebAggCore", fig.canvas)
        self.delay = float(delay)
        self.sent = 0
        self._sending = False
        self._timer = self.canvas.new_timer(interval=max(1, int(self.delay * 1000)))
        self._timer.single_shot = True
        self._timer.add_callback(self.send)
        self._cid = self.canvas.mpl_connect("draw_event", self._on_draw)

    def touch(self) -> None:
        """A picture was just sent (or is about to be): the key frame follows ``delay`` s later."""
        self._timer.stop()
        self._timer.start()

    def _on_draw(self, event: DrawEvent) -> None:
        if not self._sending and not self.canvas.is_saving():
            self.touch()

    def send(self) -> None:
        """Draw the figure in full now and send it whole (not as a difference)."""
        canvas = self.canvas
        if _no_view_yet(canvas):
            return   # no browser shows the figure yet: it asks for its first (whole) picture itself
        self._sending = True
        try:
            if self.before is not None:
                self.before()
            # webagg's "refresh" marks the next picture as a full one; it also asks the browser
            # to request a draw, which would send one more (difference) picture after the key
            # frame: that request is left out, the figure is drawn here instead.
            real_draw_idle = canvas.draw_idle
            canvas.draw_idle = lambda *a, **k: None  # type: ignore[method-assign]  # swapped for the refresh
            try:
                canvas.handle_event({"type": "refresh"})
            finally:
                canvas.draw_idle = real_draw_idle  # type: ignore[method-assign]  # put back
            canvas.draw()
            self.sent += 1
        finally:
            self._sending = False

    def disconnect(self) -> None:
        self._timer.stop()
        self.canvas.mpl_disconnect(self._cid)

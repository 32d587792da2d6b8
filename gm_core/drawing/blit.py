"""Blitting for live panels: redraw only the artists a slider moved.

A full matplotlib draw re-renders every tick label, grid line and static curve; for a four-axes
figure that is 50-100 ms, whatever the update did. Blitting (the technique of matplotlib's
"Faster rendering by using blitting" guide) keeps a picture of the static background and, for
each frame, pastes it back and draws just the moving artists on top. ipympl supports it through
webagg's diff images: ``canvas.blit`` marks the picture old and sends only changed pixels.

:class:`Blitter` needs no list of moving artists from the panel. During a frame it intercepts
``canvas.draw_idle``; afterwards the leaf artists that the update made *stale* are the moving
ones. New moving artists, a changed view (axis limits; for 3D axes also the viewing angles, which
a student changes by dragging) or a missing background trigger one full draw (the ``draw_event``
callback then captures the background without the animated artists and paints them on top);
every later frame is a blit. In 3D the moving artists are projected with the view of the last
full draw, which the view check keeps current.
"""
from __future__ import annotations

from contextlib import contextmanager

from matplotlib.axis import Axis
from matplotlib.legend import Legend
from matplotlib.spines import Spine

__all__ = ["Blitter", "can_blit"]


def can_blit(fig) -> bool:
    """True if ``fig`` can be blitted: its canvas can copy and restore regions (Agg-based)."""
    canvas = fig.canvas
    return hasattr(canvas, "copy_from_bbox") and hasattr(canvas, "restore_region")


def _view(ax):
    """Everything that places an axes' content on the canvas: limits, and for 3D the camera."""
    # Only side-effect-free reads: get_position() would run apply_aspect(), mark the figure stale
    # and, under ipympl, request another draw from inside the draw callback (a redraw loop).
    view = (tuple(ax.viewLim.bounds),)
    if getattr(ax, "name", "") == "3d":
        view += (tuple(ax.get_zlim()), ax.elev, ax.azim, getattr(ax, "roll", 0.0))
    return view


def _leaf_artists(fig):
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

    def __init__(self, fig):
        self.fig = fig
        self.canvas = fig.canvas
        self.dynamic: list = []
        self._ids: set = set()
        self._background = None
        self._limits = self._view_limits()
        self._real_draw_idle = self.canvas.draw_idle
        self._cid = self.canvas.mpl_connect("draw_event", self._on_draw)
        self.full_draws = 0
        self.blits = 0

    # -- bookkeeping ------------------------------------------------------------------
    def _view_limits(self):
        return [_view(ax) for ax in self.fig.axes]

    def _on_draw(self, event):
        """After every full draw: keep the background, then paint the animated artists on it."""
        if self.canvas.is_saving() or (event is not None and event.canvas is not self.canvas):
            # savefig: matplotlib draws animated artists itself while saving, and that picture
            # is not the live background.
            return
        self._background = self.canvas.copy_from_bbox(self.fig.bbox)
        self._limits = self._view_limits()
        self._paint()

    def _sorted(self):
        return sorted((a for a in self.dynamic if a.figure is not None), key=lambda a: a.get_zorder())

    def _paint(self):
        for a in self._sorted():
            if a.axes is not None:
                a.axes.draw_artist(a)
            else:
                self.fig.draw_artist(a)

    # -- frames -------------------------------------------------------------------------
    @contextmanager
    def frame(self):
        """Run a panel update inside; on exit the figure is refreshed by a blit or a full draw."""
        requested = []
        self.canvas.draw_idle = lambda *a, **k: requested.append(True)
        try:
            yield
        finally:
            self.canvas.draw_idle = self._real_draw_idle
        self.refresh()

    def refresh(self):
        new = [a for a in _leaf_artists(self.fig) if a.stale and id(a) not in self._ids]
        if self._background is None:
            # No background yet (never drawn): everything is new, nothing is known to move.
            self._full_draw()
            return
        if new or self._view_limits() != self._limits:
            for a in new:
                a.set_animated(True)
                self.dynamic.append(a)
                self._ids.add(id(a))
            self._full_draw()
            return
        self.canvas.restore_region(self._background)
        self._paint()
        self.canvas.blit(self.fig.bbox)
        self.blits += 1

    def _full_draw(self):
        self._background = None
        self.full_draws += 1
        self._real_draw_idle()

    def disconnect(self):
        self.canvas.mpl_disconnect(self._cid)
        for a in self.dynamic:
            a.set_animated(False)
        self.dynamic.clear()
        self._ids.clear()

"""The Panel protocol shared by every interactive figure of the course.

A subclass implements

* ``build()``: create the figure (``gm_core.drawing.new_figure``), its artists and
  ``self.controls`` (an ordered dict of ipywidgets value widgets, e.g. FloatSlider);
* ``update(**values)``: recompute and move artists in place, then ``self.fig.canvas.draw_idle()``;
* ``naive_update(**values)``: the baseline a beginner would write (clear the axes and re-plot
  everything); used only by ``benchmarks/widget_latency.py`` to show what in-place updates save;
* optionally ``sample_values(rng)``: random control values for the benchmark (defaults to a
  uniform draw inside each slider's range).

Changing a control calls ``update`` with the values of all controls, so a test can set
``panel.controls["theta"].value = 1.0`` and then inspect the artists, with no browser.

In a live notebook (ipympl canvas) each change is rendered by blitting
(:class:`gm_core.drawing.blit.Blitter`): only the artists the update changed are redrawn over a
cached background. A panel that must not be blitted sets ``blit = False``.
"""
from __future__ import annotations

import importlib
import pkgutil

import ipywidgets as W
import numpy as np

__all__ = ["Panel", "PANELS", "register", "all_panels"]

#: name -> Panel subclass, filled by @register.
PANELS: dict[str, type] = {}


def register(cls):
    """Class decorator: make a Panel visible to the latency benchmark and the panel tests."""
    PANELS[cls.__name__] = cls
    return cls


def all_panels():
    """Import every module of gm_core.widgets and return the registry of Panel classes."""
    import gm_core.widgets as pkg

    for mod in pkgutil.iter_modules(pkg.__path__):
        importlib.import_module(f"{pkg.__name__}.{mod.name}")
    return dict(PANELS)


class Panel:
    """Controls plus a live figure; display it by leaving the panel as the last line of a cell."""

    title = ""
    #: Render slider changes by blitting where the canvas allows it (see gm_core.drawing.blit).
    blit = True
    #: Blit on non-widget canvases too (Agg); the latency benchmark and blit tests turn it on.
    blit_everywhere = False
    blitter = None

    def __init__(self, **options):
        self.options = options
        self.controls: dict[str, W.ValueWidget] = {}
        self.fig = None
        self.build()
        for c in self.controls.values():
            c.continuous_update = True
            c.observe(self._on_change, names="value")
        self.update(**self.values())
        if self.fig is not None:
            from ..drawing.toolkit import freeze_layout

            freeze_layout(self.fig)   # constrained layout once, then fixed (blitting needs still axes)
        self.blitter = None
        if self.blit and self.fig is not None:
            from ..drawing.blit import Blitter, can_blit

            live = isinstance(self.fig.canvas, W.DOMWidget)
            if (live or self.blit_everywhere) and can_blit(self.fig):
                self.blitter = Blitter(self.fig)

    # -- to implement -------------------------------------------------------------
    def build(self):
        raise NotImplementedError

    def update(self, **values):
        raise NotImplementedError

    def naive_update(self, **values):
        raise NotImplementedError

    # -- shared -------------------------------------------------------------------
    def values(self):
        return {k: c.value for k, c in self.controls.items()}

    def set(self, **values):
        """Set several controls at once and update once (what a test or a demo button does)."""
        with self.hold():
            for k, v in values.items():
                if k not in self.controls:
                    raise ValueError(f"unknown control {k!r}; this panel has {sorted(self.controls)}")
                self.controls[k].value = v
        self.refresh()

    def hold(self):
        panel = self

        class _Hold:
            def __enter__(self):
                panel._held = True

            def __exit__(self, *exc):
                panel._held = False

        return _Hold()

    _held = False

    def _on_change(self, change):
        if not self._held:
            self.refresh()

    def refresh(self, **values):
        """Update to the controls' values (overridden by ``values``) and show the new frame.

        This is exactly what one slider change does: ``update`` moves the artists, then the
        figure is refreshed by a blit (live canvases) or a full draw.
        """
        values = {**self.values(), **values}
        if self.blitter is None:
            self.update(**values)
            return
        with self.blitter.frame():
            self.update(**values)

    def sample_values(self, rng):
        out = {}
        for k, c in self.controls.items():
            if hasattr(c, "min") and hasattr(c, "max") and isinstance(c.value, (int, float)) \
                    and not isinstance(c.value, bool):
                v = rng.uniform(c.min, c.max)
                out[k] = int(round(v)) if isinstance(c.value, int) else float(v)
            else:
                out[k] = c.value
        return out

    def redraw(self):
        if self.fig is not None:
            self.fig.canvas.draw_idle()

    @property
    def widget(self):
        """The ipywidgets box: controls on the left, the figure on the right."""
        if getattr(self, "_widget", None) is None:
            canvas = self.fig.canvas
            if isinstance(canvas, W.DOMWidget):
                view = canvas
            else:  # non-widget backend (e.g. inline): show a static rendering
                view = W.Output()
                with view:
                    from IPython.display import display
                    display(self.fig)
            controls = W.VBox(list(self.controls.values()),
                              layout=W.Layout(min_width="260px", justify_content="flex-start"))
            children = [controls, view]
            box = W.HBox(children, layout=W.Layout(align_items="flex-start", flex_flow="row wrap"))
            if self.title:
                box = W.VBox([W.HTML(f"<b>{self.title}</b>"), box])
            self._widget = box
        return self._widget

    def _ipython_display_(self):
        from IPython.display import display

        display(self.widget)


def slider(value, lo, hi, step=0.01, description="", readout_format=".2f", **kw):
    """A FloatSlider with the course's defaults (continuous updates, readable description)."""
    return W.FloatSlider(value=value, min=lo, max=hi, step=step, description=description,
                         readout_format=readout_format, continuous_update=True,
                         style={"description_width": "initial"}, **kw)


def finite_or_flag(values, flag, message):
    """Return True if every value is finite; otherwise show ``flag`` with ``message`` and return False."""
    ok = bool(np.all(np.isfinite(values)))
    if ok:
        flag.hide()
    else:
        flag.show(message)
    return ok

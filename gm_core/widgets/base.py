"""The Panel protocol shared by every interactive figure of the course.

**The pattern: a ScenePanel.** Every panel of the course is a :class:`ScenePanel` that pairs a
drawing :class:`~gm_core.drawing.toolkit.style.Scene` with the controls that drive it; the model
to copy is ``gm_core/drawing/start.py`` (the scene) and ``gm_core/widgets/start.py`` (the panel)::

    class FrameScene(Scene):                     # gm_core/drawing/<topic>.py
        FIGSIZE = (4.5, 4.5)
        def decorate(self) -> None: ...          # limits, labels, static artists (once)
        def create(self) -> None: ...            # the moving artists (once)
        def set(self, **values) -> None: ...     # move them in place

    @register
    class FrameDemo(ScenePanel):                 # gm_core/widgets/<topic>.py
        title = "A rigid body at g = (x, y, θ)"
        scene_class = FrameScene
        def controls_spec(self) -> dict[str, W.ValueWidget]:
            return {"x": slider(1.0, -2.0, 2.0, description="x"), ...}

``Scene`` and ``Panel`` are abstract base classes: a scene must implement ``create`` and ``set``,
a ScenePanel must set ``scene_class`` and implement ``controls_spec``; ``scene_options()``
(keywords for the scene, default the panel's options) and ``sample_values(rng)`` (random control
values for ``benchmarks/widget_latency.py``, default a uniform draw inside each slider's range)
are optional. :func:`register` puts the panel in the blitting test, the figure-standard test and
the latency benchmark.

A ScenePanel's ``update(**values)`` hands the control values to ``scene.set`` and asks for a
redraw; ``naive_update(**values)`` is the scene's clear-and-replot baseline (``Scene.replot``),
used only by the latency benchmark to show what in-place updates save. A bare :class:`Panel`
(rare) implements ``build()`` (the figure, its artists and ``self.controls``), ``update`` and
``naive_update`` itself.

Changing a control calls ``update`` with the values of all controls, so a test can set
``panel.controls["theta"].value = 1.0`` and then inspect the artists, with no browser.

In a live notebook (ipympl canvas) each change is rendered by blitting
(:class:`gm_core.drawing.toolkit.blit.Blitter`): only the artists the update changed are redrawn over a
cached background; after the last change of a burst a key frame
(:class:`gm_core.drawing.toolkit.blit.KeyFrames`) sends the whole picture, so the browser always ends on
the truth; just before it the panel's :meth:`Panel.settle` finishes what the scene left for the
end of the burst (:attr:`gm_core.drawing.toolkit.style.Scene.settle_later`: a 3-D camera that turns
with the point turns then, so the burst's frames are blits over a still view). A panel that must
not be blitted sets ``blit = False``; it is drawn in full, once per
change, and sent at once (:func:`gm_core.drawing.toolkit.blit.drawn_at_once`). :attr:`Panel.widget` lays the
controls out for a 1366 x 768 laptop: labels above their controls, beside the figure when both
fit, else in rows above it.
"""
from __future__ import annotations

import importlib
import pkgutil
import time
from abc import ABC, abstractmethod
from contextlib import AbstractContextManager, ExitStack
from typing import TYPE_CHECKING, Any, TypeVar

import ipywidgets as W
import numpy as np
from typing_extensions import override

if TYPE_CHECKING:   # matplotlib is imported by the drawing layer, only when a panel is built
    from matplotlib.figure import Figure

    from gm_core.drawing.toolkit.style import Scene

__all__ = [
    "Panel", "ScenePanel", "TablePanel", "PANELS", "register", "all_panels", "slider", "int_slider",
    "se2_sliders", "xi_sliders", "show",
]

P = TypeVar("P", bound="Panel")

#: name -> Panel subclass, filled by @register.
PANELS: dict[str, type[Panel]] = {}


def register(cls: type[P]) -> type[P]:
    """Class decorator: make a Panel visible to the latency benchmark and the panel tests."""
    PANELS[cls.__name__] = cls
    return cls


def all_panels() -> dict[str, type[Panel]]:
    """Import every module of gm_core.widgets and return the registry of Panel classes."""
    import gm_core.widgets as pkg

    for mod in pkgutil.iter_modules(pkg.__path__):
        importlib.import_module(f"{pkg.__name__}.{mod.name}")
    return dict(PANELS)


class Panel(ABC):
    """Controls plus a live figure; display it by leaving the panel as the last line of a cell."""

    title: str = ""
    #: Render slider changes by blitting where the canvas allows it (see gm_core.drawing.toolkit.blit).
    blit = True
    #: Send a whole picture after the last change of a burst on live canvases (KeyFrames): the
    #: picture a student is left with is always complete, however fast the slider moved.
    key_frames = True
    #: Blit on non-widget canvases too (Agg); the latency benchmark and blit tests turn it on.
    blit_everywhere = False
    blitter: Any = None

    def __init__(self, **options: Any) -> None:
        self.options = options
        self._pinned: dict[str, tuple[Any, Any, float]] = {}
        self._exact: dict[str, Any] = {}
        self.controls: dict[str, W.ValueWidget] = {}
        self.fig: Figure | None = None
        self._constructing = True   # redraw() waits until the layout is fixed (see redraw)
        self.build()
        # The browser shows each slider on its grid (min + k * step) and may echo that rounded
        # position when it first renders: the exact starting values are kept (see set()).
        self._exact = {k: c.value for k, c in self.controls.items() if getattr(c, "step", None)}
        for c in self.controls.values():
            c.continuous_update = True
            c.observe(self._on_change, names="value")
        self.update(**self.values())
        if self.fig is not None:
            from gm_core.drawing.toolkit.style import freeze_layout

            freeze_layout(self.fig)   # constrained layout once, then fixed (blitting needs still axes)
        self.blitter = None
        self.keyframes = None
        self._constructing = False
        if self.fig is not None:
            from gm_core.drawing.toolkit.blit import Blitter, KeyFrames, can_blit, sends_differences

            live = isinstance(self.fig.canvas, W.DOMWidget)
            if live:
                self.redraw()   # the request the first update made (a live canvas answers it later)
            if self.blit and (live or self.blit_everywhere) and can_blit(self.fig):
                self.blitter = Blitter(self.fig)
            if self.key_frames and live and sends_differences(self.fig):
                # the browser gets differences during a drag, and one whole picture after it
                self.keyframes = KeyFrames(self.fig, before=self.settle)

    # -- to implement -------------------------------------------------------------
    @abstractmethod
    def build(self) -> None:
        raise NotImplementedError

    @abstractmethod
    def update(self, **values: Any) -> None:
        raise NotImplementedError

    @abstractmethod
    def naive_update(self, **values: Any) -> None:
        raise NotImplementedError

    # -- shared -------------------------------------------------------------------
    def values(self) -> dict[str, Any]:
        """The controls' values (a value set by :meth:`set` is reported exactly, not as rounded
        by the browser's slider grid)."""
        out = {k: c.value for k, c in self.controls.items()}
        for k, v in self._exact.items():
            if _same(self.controls[k], out[k], v):
                out[k] = v
        return out

    #: Seconds after :meth:`set` during which a control change back to the value it had before
    #: is treated as a stale echo from the browser (its first render) and undone.
    echo_window = 5.0

    def set(self, **values: Any) -> None:
        """Set several controls at once and update once (what a test, a demo or a notebook does).

        The sliders themselves take the values. The browser shows a slider on its grid
        (min + k * step) and may echo that rounded position back: an echo within half a step of
        the value set here keeps the exact value (``values()`` reports it). For a few seconds a
        change back to the old value (a slider's initial echo arriving late after Run All) is
        undone: a value set from code is never overwritten by a widget's first render.
        """
        unknown = [k for k in values if k not in self.controls]
        if unknown:
            raise ValueError(f"unknown control {unknown[0]!r}; this panel has {sorted(self.controls)}")
        now = time.monotonic()
        with self.hold():
            for k, v in values.items():
                c = self.controls[k]
                self._pinned[k] = (c.value, v, now)
                self._exact[k] = v
                c.value = v
        self.refresh()
        self.settle()   # a value set from code is not a burst: nothing waits for its end

    def settle(self) -> None:  # noqa: B027 (an optional hook)
        """Finish what an update left for the end of a slider burst; the key frame calls it just
        before its draw (live canvases). Nothing by default; a ScenePanel settles its scene."""

    def draw_now(self) -> None:
        """Draw the figure in full now and send it to a live canvas at once (webagg's ``draw``),
        instead of asking the browser to ask for it: whatever is said after this call (a status
        line) reaches the page after the picture. A key frame still follows (see KeyFrames)."""
        if self.fig is None:
            return
        self.fig.canvas.draw()
        if self.keyframes is not None:
            self.keyframes.touch()

    def follow(self, key: str, value: Any) -> None:
        """Move control ``key`` to ``value`` without an update: a value the picture already uses,
        shown by a control that follows the others (a greyed slider under a symmetry). The
        control then agrees with the picture, and ``values()`` reports ``value`` exactly."""
        control = self.controls[key]
        with self.hold():
            control.value = value
        self._exact[key] = value
        self._pinned.pop(key, None)

    def hold(self) -> AbstractContextManager[None]:
        panel = self

        class _Hold:
            def __enter__(self):
                panel._held = True

            def __exit__(self, *exc):
                panel._held = False

        return _Hold()

    _held = False

    def _on_change(self, change):
        if self._held:
            return
        key = next((k for k, c in self.controls.items() if c is change["owner"]), None)
        pinned = self._pinned.get(key)
        if pinned is not None:
            before, wanted, t = pinned
            if time.monotonic() - t < self.echo_window and _same(change["owner"], change["new"], before) \
                    and not _same(change["owner"], change["new"], wanted):
                # a stale echo of the value before set(): put the programmatic value back
                with self.hold():
                    change["owner"].value = wanted
                return
            del self._pinned[key]
        if key in self._exact:
            if _same(change["owner"], change["new"], self._exact[key]):
                return   # the browser's rounding of a value set from code: keep the exact value
            del self._exact[key]
        if _same(change["owner"], change["new"], change["old"], exact=True):
            return   # an echo of the value the kernel already has (float round-off): nothing moved
        self.refresh()

    def refresh(self, **values: Any) -> None:
        """Update to the controls' values (overridden by ``values``) and show the new frame.

        This is exactly what one slider change does: ``update`` moves the artists, then the
        figure is refreshed by a blit (live canvases) or a full draw.
        """
        values = {**self.values(), **values}
        with ExitStack() as after_the_picture:
            # what the update says in widgets (a table of numbers, a status line, a control it
            # moves) reaches the page after the picture: the browser paints the canvas first
            for w in self._page_widgets():
                after_the_picture.enter_context(w.hold_sync())
            if self.blitter is None and self.fig is not None:
                from gm_core.drawing.toolkit.blit import drawn_at_once

                with drawn_at_once(self.fig):   # a live canvas draws at once, not via the browser
                    self.update(**values)
            elif self.blitter is None:
                self.update(**values)
            else:
                with self.blitter.frame():
                    self.update(**values)
        if self.keyframes is not None:
            self.keyframes.touch()

    def _page_widgets(self) -> list[W.Widget]:
        """The panel's widgets but its canvas: its controls and those it keeps (numbers, status)."""
        canvas = self.fig.canvas if self.fig is not None else None
        own = [w for w in vars(self).values() if isinstance(w, W.Widget)]
        return [w for w in {id(w): w for w in [*self.controls.values(), *own]}.values()
                if w is not canvas]

    def sample_values(self, rng: np.random.Generator) -> dict[str, Any]:
        out = {}
        for k, c in self.controls.items():
            if hasattr(c, "min") and hasattr(c, "max") and isinstance(c.value, (int, float)) \
                    and not isinstance(c.value, bool):
                v = rng.uniform(c.min, c.max)
                out[k] = int(round(v)) if isinstance(c.value, int) else float(v)
            else:
                out[k] = c.value
        return out

    _constructing = False

    def redraw(self) -> None:
        """Ask the canvas for a new picture: every ``update`` ends here. Not while the panel is
        being built: its layout is fixed after the first update, and a non-widget canvas (Agg,
        inline) draws at once, so the whole figure would be laid out and drawn twice (about a
        third of the time it takes to build a panel); it draws when shown instead."""
        if self.fig is not None and not self._constructing:
            self.fig.canvas.draw_idle()

    #: Width of the controls column in CSS px: a slider's track gets this minus its readout
    #: (>= 150 px); long labels stand above their control, whole.
    CONTROL_WIDTH = 260
    #: Width of a notebook's output area at 1366 x 768 with the file browser open (CSS px): a
    #: figure narrower than this minus the controls column gets its controls beside it.
    OUTPUT_WIDTH = 920

    @property
    def widget(self) -> W.Widget:
        """The ipywidgets box: the controls beside the figure (on its left) when both fit the
        laptop's output area, else in rows above it; every label whole, above its control."""
        if getattr(self, "_widget", None) is None:
            if self.fig is None:
                raise RuntimeError(f"{type(self).__name__}.build() made no figure")
            canvas = self.fig.canvas
            if isinstance(canvas, W.DOMWidget):
                view = canvas
            else:  # non-widget backend (e.g. inline): show a static rendering
                view = W.Output()
                with view:
                    from IPython.display import display
                    display(self.fig)
            items = [_labelled(c, self.CONTROL_WIDTH) for c in self.controls.values()]
            fig_width = self.fig.get_figwidth() * self.fig.dpi
            if fig_width + self.CONTROL_WIDTH + 24 <= self.OUTPUT_WIDTH:
                controls = W.VBox(items, layout=W.Layout(width=f"{self.CONTROL_WIDTH + 8}px",
                                                         min_width=f"{self.CONTROL_WIDTH + 8}px",
                                                         margin="0 12px 0 0"))
                box = W.HBox([controls, view], layout=W.Layout(align_items="flex-start"))
            else:
                controls = W.HBox(items, layout=W.Layout(flex_flow="row wrap", align_items="flex-end",
                                                         grid_gap="0 16px", max_width=f"{self.OUTPUT_WIDTH}px"))
                box = W.VBox([controls, view], layout=W.Layout(align_items="flex-start"))
            if self.title:
                box = W.VBox([W.HTML(f"<b>{self.title}</b>"), box])
            self._widget = box
        return self._widget

    def alt_text(self) -> str:
        """What the panel's picture shows (the alt text of its static rendering)."""
        doc = (type(self).__doc__ or "").strip().splitlines()
        what = self.title or (doc[0].rstrip(".") if doc else type(self).__name__)
        labels = [t for ax in (self.fig.axes if self.fig is not None else [])
                  for t in (ax.get_title(), ax.get_xlabel(), ax.get_ylabel()) if t]
        # (a label laid out above its control keeps its text as the control's tooltip)
        values = ", ".join(f"{getattr(c, 'description', '') or getattr(c, 'tooltip', '') or k} = {self._fmt(c.value)}"
                           for k, c in self.controls.items())
        out = f"Interactive figure: {what}."
        if labels:
            out += " Axes: " + "; ".join(dict.fromkeys(labels)) + "."
        return out + (f" Shown at {values}." if values else "")

    @staticmethod
    def _fmt(v):
        return f"{v:.3g}" if isinstance(v, float) else str(v)

    def _repr_mimebundle_(self, include=None, exclude=None):
        """The live view (JupyterLab shows it) plus a PNG of the figure as it is now, with alt
        text, which static pages (Jupyter Book, nbconvert) show in its place."""
        bundle = dict(self.widget._repr_mimebundle_(include=include, exclude=exclude) or {})
        if self.fig is None:
            return bundle
        import base64
        import io

        buf = io.BytesIO()
        self.fig.savefig(buf, format="png", dpi="figure")
        bundle["image/png"] = base64.b64encode(buf.getvalue()).decode("ascii")
        return bundle, {"image/png": {"alt": self.alt_text()}}


class ScenePanel(Panel):
    """The one widget pattern: a drawing :class:`~gm_core.drawing.toolkit.Scene` (``scene_class``,
    built with the panel's options) owns the figure and its update; the panel pairs it with
    controls (``controls_spec()``).

    ``update`` hands the control values to ``scene.set`` and asks for a redraw; ``naive_update``
    is the scene's clear-and-replot baseline. Attributes the panel does not have are read from
    the scene (``panel.art`` is ``panel.scene.art``), so tests and notebooks can inspect the
    artists and the numbers the scene computed.
    """

    scene_class: type[Scene] | None = None
    scene: Scene
    fig: Figure

    @abstractmethod
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        raise NotImplementedError

    def scene_options(self) -> dict[str, Any]:
        """Keyword arguments for ``scene_class`` (default: the panel's options)."""
        return dict(self.options)

    def __init__(self, **options: Any) -> None:
        super().__init__(**options)
        if self.keyframes is not None:
            # live: the scene may leave to the key frame what need not follow every step (Scene.settle)
            self.scene.settle_later = True

    @override
    def settle(self) -> None:
        self.scene.settle()

    @override
    def build(self) -> None:
        if self.scene_class is None:
            raise NotImplementedError(f"{type(self).__name__} must set scene_class")
        self.scene = self.scene_class(**self.scene_options())
        self.fig = self.scene.fig
        self.controls = self.controls_spec()

    @override
    def update(self, **values: Any) -> None:
        self.scene.set(**values)
        self.after_update(values)
        self.redraw()

    def after_update(self, values: dict[str, Any]) -> None:
        """Hook for control-side effects of a change (e.g. disabling sliders); nothing by default."""

    @override
    def naive_update(self, **values: Any) -> None:
        self.scene.replot(**values)
        self.redraw()

    def __getattr__(self, name: str) -> Any:
        # only called for attributes the panel lacks; never recurse before the scene exists
        if name.startswith("__") or name == "scene":
            raise AttributeError(name)
        scene = self.__dict__.get("scene")
        if scene is None:
            raise AttributeError(f"{type(self).__name__!s} has no attribute {name!r}")
        return getattr(scene, name)


class TablePanel(ScenePanel):
    """A panel whose scene also computes numbers, shown as an HTML table under the figure.

    The scene sets ``table`` (HTML) in ``set``; the panel's ``numbers`` widget (text the browser
    renders, never redrawn by matplotlib) shows it after every update.
    """

    scene: Any

    def __init__(self, **options: Any) -> None:
        self.numbers = W.HTML()
        super().__init__(**options)

    @override
    def after_update(self, values: dict[str, Any]) -> None:
        self.numbers.value = self.scene.table

    @property
    @override
    def widget(self) -> W.Widget:
        """The panel's box with the table of numbers under it."""
        if getattr(self, "_with_numbers", None) is None:
            self._with_numbers = W.VBox([super().widget, self.numbers])
        return self._with_numbers


def _same(control, a, b, exact=False):
    """True if two values of ``control`` are the same slider position (half a step apart at most;
    ``exact``: equal up to float round-off)."""
    try:
        a, b = float(a), float(b)
    except (TypeError, ValueError):
        return a == b
    step = float(getattr(control, "step", 0) or 0)
    tol = 1e-9 * max(1.0, abs(a), abs(b)) if exact or not step else 0.5 * step
    return abs(a - b) <= tol


_LABEL_ABOVE = (W.FloatSlider, W.IntSlider, W.FloatLogSlider, W.SelectionSlider, W.FloatRangeSlider,
                W.IntRangeSlider, W.Dropdown, W.ToggleButtons, W.FloatProgress, W.IntProgress,
                W.BoundedFloatText, W.BoundedIntText, W.FloatText, W.IntText, W.Text, W.RadioButtons)


def _labelled(control: W.Widget, width: int) -> W.Widget:
    """``control`` laid out for the controls column: a description that would squeeze a slider's
    track moves above the control (wrapping if it must, never cut); checkboxes and buttons get
    the width their label needs."""
    from html import escape

    if isinstance(control, W.Checkbox):
        control.indent = False
        control.layout.width = "auto"
        control.layout.max_width = f"{width}px"
        return control
    if isinstance(control, W.Button):
        control.layout.width = "auto"
        return control
    if not isinstance(control, _LABEL_ABOVE):
        return control
    text = control.description
    control.layout.width = f"{width}px"
    if isinstance(control, W.ToggleButtons):
        control.layout.width = "auto"
        control.layout.max_width = "100%"
    if not text:
        return control
    control.description = ""
    control.tooltip = text
    label = W.HTML(f'<div class="gm-control-label" style="white-space: normal; line-height: 1.25; '
                   f'padding-top: 2px">{escape(text)}</div>',
                   layout=W.Layout(width=f"{width}px", margin="2px 0 0 2px"))
    label.add_class("gm-control-label-box")
    # toggle buttons keep their row (as wide as they need); everything else fits the column
    box_width = "auto" if isinstance(control, W.ToggleButtons) else f"{width + 8}px"
    return W.VBox([label, control], layout=W.Layout(width=box_width, overflow="visible"))


def int_slider(value: int, lo: int, hi: int, description: str = "") -> W.IntSlider:
    """An IntSlider with the course's defaults."""
    return W.IntSlider(value=value, min=lo, max=hi, step=1, description=description,
                       continuous_update=True, style={"description_width": "initial"})


def slider(value: float, lo: float, hi: float, step: float = 0.01, description: str = "",
           readout_format: str = ".2f", **kw: Any) -> W.FloatSlider:
    """A FloatSlider with the course's defaults (continuous updates, readable description)."""
    return W.FloatSlider(value=value, min=lo, max=hi, step=step, description=description,
                         readout_format=readout_format, continuous_update=True,
                         style={"description_width": "initial"}, **kw)


def se2_sliders(x: float, y: float, theta: float, names: tuple[str, str, str] = ("x", "y", "theta"),
                lim: float = 2.5, labels: tuple[str, str, str] = ("x", "y", "θ")) -> dict[str, W.FloatSlider]:
    """Three sliders for an SE(2) element (x, y in [-lim, lim], theta in [-pi, pi]), keyed by ``names``."""
    return {names[0]: slider(x, -lim, lim, description=labels[0]),
            names[1]: slider(y, -lim, lim, description=labels[1]),
            names[2]: slider(theta, -np.pi, np.pi, description=labels[2])}


def xi_sliders(vx: float, vy: float, w: float) -> dict[str, W.FloatSlider]:
    """Three sliders for an se(2) velocity (vx, vy, w), each in [-1.5, 1.5]."""
    return {"vx": slider(vx, -1.5, 1.5, description="ξˣ"),
            "vy": slider(vy, -1.5, 1.5, description="ξʸ"),
            "w": slider(w, -1.5, 1.5, description="ξᶿ")}


def show(fig: Figure) -> None:
    """Display a static figure under any backend (the ipympl canvas, or a PNG otherwise)."""
    from IPython.display import display

    canvas = fig.canvas
    if isinstance(canvas, W.DOMWidget):
        display(canvas)
    else:
        display(fig)

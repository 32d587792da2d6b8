"""Panels of notebook 11 (beyond the draft): design a chain, read its geometry on a slice, try a wave
gait, optimise its gait live and watch it swim."""
from __future__ import annotations

from typing import TYPE_CHECKING, Any

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.connection import ROW_LABELS
from gm_core.drawing.link_chain import PHYSICS_LABELS, ChainSliceScene, OptimalGaitScene, WaveGaitScene
from gm_core.drawing.toolkit.primitives import jshtml
from gm_core.geometry import OptimalGait
from gm_core.widgets.base import ScenePanel, int_slider, register, slider

if TYPE_CHECKING:
    from IPython.display import HTML

__all__ = ["ChainSlicePanel", "WaveGaitPanel", "OptimalGaitPanel"]


#: the connection rows as a dropdown shows them (HTML: Unicode superscripts, as the other panels' ξˣ)
_ROW_OPTIONS = [(label.replace("ξx", "ξˣ").replace("ξy", "ξʸ").replace("ξθ", "ξᶿ"), i)
                for i, label in enumerate(ROW_LABELS)]


def _physics_dropdown(value: str = "low_re") -> W.Dropdown:
    label = {v: k for k, v in PHYSICS_LABELS.items()}.get(value, value)
    return W.Dropdown(options=list(PHYSICS_LABELS), value=label, description="physics")


@register
class ChainSlicePanel(ScenePanel):
    """Design a chain (number of links, physics) and read one connection row and its curvature on a
    2-D slice of the shape space spanned by two joints (the other joints straight)."""

    title = "A chain you design, on a slice of its shape space"
    scene_class = ChainSliceScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        o = self.options
        return {
            "links": int_slider(o.get("links", 4), 3, 7, description="links"),
            "physics": _physics_dropdown(o.get("physics", "low_re")),
            "row": W.Dropdown(options=_ROW_OPTIONS, value=o.get("row", 2), description="row"),
            "axis1": int_slider(o.get("axis1", 1), 1, 6, description="slice joint 1"),
            "axis2": int_slider(o.get("axis2", 2), 1, 6, description="slice joint 2"),
        }

    @override
    def update(self, **values: Any) -> None:
        """The slice joints' sliders reach the chain's last joint. A chain made shorter moves a
        slice joint beyond its end onto the last joint; if that put both on one joint, joint 1
        takes the joint before it. A student who picks one joint twice is told on the figure
        (the scene's flags), never silently given another slice."""
        n = int(values.get("links", 4)) - 1
        asked = (int(values.get("axis1", 1)), int(values.get("axis2", 2)))
        axis1, axis2 = min(asked[0], n), min(asked[1], n)
        if axis1 == axis2 and asked[0] != asked[1]:
            axis1 = n - 1 if axis2 == n else axis2 + 1   # clamped onto one joint: keep them apart
        with self.hold():
            for k in ("axis1", "axis2"):
                self.controls[k].max = n
        for k, v in (("axis1", axis1), ("axis2", axis2)):
            if self.controls[k].value != v:
                self.follow(k, v)
        super().update(**{**values, "axis1": axis1, "axis2": axis2})


@register
class WaveGaitPanel(ScenePanel):
    """A travelling wave along a chain (amplitude, phase lag between joints) and one cycle of its motion."""

    title = "A travelling wave along a chain"
    scene_class = WaveGaitScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        o = self.options
        return {
            "links": int_slider(o.get("links", 4), 2, 7, description="links"),
            "physics": _physics_dropdown(o.get("physics", "low_re")),
            "amplitude": slider(o.get("amplitude", 0.8), 0.1, 1.5, description="amplitude (rad)"),
            "lag": slider(o.get("lag", 1.2), 0.0, float(np.pi), description="phase lag (rad)"),
        }


@register
class OptimalGaitPanel(ScenePanel):
    """Design a chain (links, taper, physics, Fourier order), press "optimise" to find its most
    efficient gait (a progress bar counts the optimiser's steps), then read the gait and one cycle
    of its motion. ``panel.run()`` does what the button does (for notebooks and tests);
    ``panel.animation()`` is the gait shown as the course's player, for a cell of its own below
    the panel (panel and player together would not fit a laptop's screen)."""

    title = "Design a chain and optimise its gait"
    scene_class = OptimalGaitScene
    scene: OptimalGaitScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        o = self.options
        return {
            "links": int_slider(o.get("links", 4), 3, 6, description="links"),
            "physics": _physics_dropdown(o.get("physics", "low_re")),
            "taper": slider(o.get("taper", 0.0), 0.0, 0.6, step=0.05, description="taper (tail shorter)"),
            "order": int_slider(o.get("order", 1), 1, 2, description="Fourier order"),
        }

    @override
    def build(self) -> None:
        super().build()
        self.button = W.Button(description="optimise", button_style="primary", icon="play",
                               tooltip="find the most efficient gait of this chain (a few seconds)")
        self.bar = W.IntProgress(value=0, min=0, max=40, layout=W.Layout(width="160px"))
        self.status = W.HTML("")
        self.button.on_click(lambda _: self.run())

    @override
    def after_update(self, values: dict[str, Any]) -> None:
        result = self.scene.result
        self.bar.value = self.bar.max if result is not None else 0
        self.status.value = f"optimised: efficiency {result.efficiency:.4f}" if result is not None else ""

    def run(self) -> OptimalGait:
        """Optimise the design shown with a live progress bar, then draw its best gait. The status
        says "done" only once the picture of the best gait has been sent to the page (drawn now,
        not on the browser's next request). Returns the OptimalGait."""
        self.button.disabled = True
        self.bar.value = 0
        self.status.value = "optimising …"

        def progress(it: int, value: float) -> None:
            self.bar.value = min(it, self.bar.max)
            self.status.value = f"step {it}: efficiency {value:.4f}"

        try:
            res = self.scene.optimize(callback=progress)
            self.bar.value = self.bar.max
            self.status.value = "drawing the best gait …"
            self.draw_now()
        finally:
            self.button.disabled = False
        self.status.value = (f"done: efficiency {res.efficiency:.4f} after {res.nit} steps "
                             "(its animation: the cell below)")
        return res

    def animation(self, n_frames: int = 40, cycles: int = 2) -> HTML:
        """The gait shown (the best one once optimised, else the start wave) as an animation in the
        course's player (:func:`~gm_core.drawing.toolkit.primitives.jshtml`): the output of a cell
        of its own, which plays like every other animation of the course."""
        anim, _, _ = self.scene.animation(n_frames=n_frames, cycles=cycles)
        return jshtml(anim)

    @property
    @override
    def widget(self) -> W.Widget:
        if getattr(self, "_box", None) is None:
            self._box = W.VBox([super().widget, W.HBox([self.button, self.bar, self.status],
                                                       layout=W.Layout(align_items="center", grid_gap="0 10px"))])
        return self._box

"""The locomotion lab's panel (notebook 12): a system of sysplotter's library, a gait and three numbers
(scene of :mod:`gm_core.drawing.catalog`).
"""
from __future__ import annotations

from typing import Any

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.catalog import LabScene, lab_names
from gm_core.drawing.curvature import ROWS
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["LabPanel"]


@register
class LabPanel(ScenePanel):
    """Pick a system by sysplotter's name, shape a gait on its curvature map, read exact g(T), Stokes and ∫ξ dt."""

    title = "Locomotion lab: any chain of sysplotter's library"
    scene_class = LabScene
    scene: LabScene
    # switching systems makes and removes the body's artists: whole redraws, never blitted
    blit = False

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        self.numbers = W.HTML()
        return {"system": W.Dropdown(options=list(lab_names()), value="three_link_lowRe", description="system"),
                "row": W.ToggleButtons(options=[(r, i) for i, r in enumerate(ROWS)], value=0, description="map row",
                                       style={"button_width": "3.5em"}),
                "c1": slider(0.0, -0.8, 0.8, description="centre r₁"),
                "c2": slider(0.0, -0.8, 0.8, description="centre r₂"),
                "a": slider(0.5, 0.05, 0.9, description="size a"),
                "b": slider(0.3, 0.05, 0.9, description="size b"),
                "tilt": slider(0.78, -1.6, 1.6, description="tilt"),
                "phase": slider(0.0, 0.0, 1.0, description="body at t/T")}

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

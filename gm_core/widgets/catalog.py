"""The locomotion lab's panel (notebook 12): a system of sysplotter's library, a gait and three numbers
(scene of :mod:`gm_core.drawing.catalog`).
"""
from __future__ import annotations

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.catalog import LabScene, lab_names
from gm_core.drawing.curvature import ROWS
from gm_core.widgets.base import TablePanel, register, slider

__all__ = ["LabPanel"]


@register
class LabPanel(TablePanel):
    """Pick a system by sysplotter's name, shape a gait on its curvature map, read exact g(T), Stokes and ∫ξ dt."""

    title = "Locomotion lab: any chain of sysplotter's library"
    scene_class = LabScene
    scene: LabScene
    # switching systems makes and removes the body's artists: whole redraws, never blitted
    blit = False

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"system": W.Dropdown(options=list(lab_names()), value="three_link_lowRe", description="system"),
                "row": W.ToggleButtons(options=[(r, i) for i, r in enumerate(ROWS)], value=0, description="map row",
                                       style={"button_width": "3.5em"}),
                "c1": slider(0.0, -0.8, 0.8, description="centre r₁"),
                "c2": slider(0.0, -0.8, 0.8, description="centre r₂"),
                "a": slider(0.5, 0.05, 0.9, description="size a"),
                "b": slider(0.3, 0.05, 0.9, description="size b"),
                "tilt": slider(0.78, -1.6, 1.6, description="tilt"),
                "phase": slider(0.0, 0.0, 1.0, description="body at t/T")}


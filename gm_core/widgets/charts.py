"""Section 1.1 panel: one vector field, point and vector in the Cartesian and the polar chart
(scene of :mod:`gm_core.drawing.charts`).
"""
from __future__ import annotations

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.charts import PlaneChartsScene
from gm_core.fields import FIELDS
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["PlaneChartsPanel"]


@register
class PlaneChartsPanel(ScenePanel):
    """Move the point and turn the vector: the overlap map renames both, and the field, in the polar chart."""

    title = "Two charts of the plane: Cartesian and polar (section 1.1)"
    scene_class = PlaneChartsScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"field": W.Dropdown(options=list(FIELDS), value="spiral sink", description="field"),
                "x": slider(1.5, -2.8, 2.8, step=0.05, description="point x"),
                "y": slider(1.0, -2.8, 2.8, step=0.05, description="point y"),
                "v_angle": slider(60.0, -180.0, 180.0, step=1.0, description="direction of v (°)",
                                  readout_format=".0f"),
                "v_length": slider(1.0, 0.0, 2.0, step=0.05, description="length of v")}

"""Panels of notebook 11 (beyond the draft): design a chain, read its geometry on a slice, try a wave gait."""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from ..drawing.connection import ROW_LABELS
from ..drawing.many_links import PHYSICS_LABELS, ChainSliceScene, WaveGaitScene
from .base import ScenePanel, int_slider, register, slider

__all__ = ["ChainSlicePanel", "WaveGaitPanel"]


def _physics_dropdown(value="low_re"):
    label = {v: k for k, v in PHYSICS_LABELS.items()}.get(value, value)
    return W.Dropdown(options=list(PHYSICS_LABELS), value=label, description="physics")


@register
class ChainSlicePanel(ScenePanel):
    """Design a chain (number of links, physics) and read one connection row and its curvature on a
    2-D slice of the shape space spanned by two joints (the other joints straight)."""

    title = "A chain you design, on a slice of its shape space"
    scene_class = ChainSliceScene

    def controls_spec(self):
        o = self.options
        return {
            "links": int_slider(o.get("links", 4), 3, 7, description="links"),
            "physics": _physics_dropdown(o.get("physics", "low_re")),
            "row": W.Dropdown(options=[(ROW_LABELS[i], i) for i in range(3)], value=o.get("row", 2), description="row"),
            "axis1": int_slider(o.get("axis1", 1), 1, 6, description="slice joint 1"),
            "axis2": int_slider(o.get("axis2", 2), 1, 6, description="slice joint 2"),
        }

    def after_update(self, values):
        n = int(values.get("links", 4)) - 1
        for k in ("axis1", "axis2"):
            self.controls[k].max = n


@register
class WaveGaitPanel(ScenePanel):
    """A travelling wave along a chain (amplitude, phase lag between joints) and one cycle of its motion."""

    title = "A travelling wave along a chain"
    scene_class = WaveGaitScene

    def controls_spec(self):
        o = self.options
        return {
            "links": int_slider(o.get("links", 4), 2, 7, description="links"),
            "physics": _physics_dropdown(o.get("physics", "low_re")),
            "amplitude": slider(o.get("amplitude", 0.8), 0.1, 1.5, description="amplitude (rad)"),
            "lag": slider(o.get("lag", 1.2), 0.0, float(np.pi), description="phase lag (rad)"),
        }

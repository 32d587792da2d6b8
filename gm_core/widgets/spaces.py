"""Section 1.1 panels: paths on the torus, loops, the pole chart
(scenes of :mod:`gm_core.drawing.spaces`).
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.spaces import LoopsScene, PoleChartScene, TorusPathScene
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["TorusPathPanel", "LoopsPanel", "PoleChartPanel"]

PI = float(np.pi)


@register
class TorusPathPanel(ScenePanel):
    """A straight line on the flattened torus is a winding path on the torus (figs 1.5, 1.16)."""

    title = "Torus: flattened view with glued edges"
    scene_class = TorusPathScene
    # The path winds behind the torus's wireframe; only a full 3D draw sorts them by depth.
    blit = False

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"a0": slider(0.5, 0.0, 2 * PI, description="start a₀"),
                "b0": slider(1.0, 0.0, 2 * PI, description="start b₀"),
                "slope": slider(0.5, -3.0, 3.0, description="slope db/da"),
                "turns": slider(2.0, 0.1, 4.0, description="turns in a")}


@register
class LoopsPanel(ScenePanel):
    """Fig. 1.6: shrinking a loop on the sphere works; on the torus it cannot."""

    title = "Loops on the torus and on the sphere (fig. 1.6)"
    scene_class = LoopsScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"s": slider(0.0, 0.0, 1.0, description="shrink s")}


@register
class PoleChartPanel(ScenePanel):
    """Walk towards a pole: the latitude/longitude chart's coordinate speed blows up there."""

    title = "Charts on the sphere and the pole singularity"
    scene_class = PoleChartScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"lat_deg": slider(45.0, -90.0, 90.0, step=0.5, description="latitude φ (°)",
                                  readout_format=".1f"),
                "heading_deg": slider(45.0, 0.0, 180.0, step=1.0, description="heading from north (°)",
                                      readout_format=".0f")}

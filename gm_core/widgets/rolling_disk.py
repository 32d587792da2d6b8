"""Section 3.2 panel: parallel parking, a Lie-bracket motion
(scene of :mod:`gm_core.drawing.rolling_disk`).
"""
from __future__ import annotations

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.rolling_disk import ParallelParkScene
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["ParallelParkPanel"]


@register
class ParallelParkPanel(ScenePanel):
    """A rolling disk parallel-parks by a loop of allowed moves; the integrable constraint (3.viii) cannot.

    Sliders: the drive distance d and the turn angle φ of the loop drive–turn–back–turn back.
    """

    title = "Nonholonomy: parallel parking a rolling disk"
    scene_class = ParallelParkScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"d": slider(0.8, -1.2, 1.2, description="drive distance d"),
                "phi": slider(0.6, -1.5, 1.5, description="turn angle φ")}

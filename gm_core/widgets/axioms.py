"""Section 1.2 panel: group or not? the four axioms tried
(scene of :mod:`gm_core.drawing.axioms`).
"""
from __future__ import annotations

from typing import Any

import ipywidgets as W
from typing_extensions import override

from gm_core.drawing.axioms import CHOICES, GroupOrNotScene, integer_structure
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = ["GroupAxiomsPanel"]


@register
class GroupAxiomsPanel(ScenePanel):
    """Group or not? The axioms (1.ii)-(1.v) on real groups and on (ℤ, ×), (ℝ⁺, +), (ℝ, −), ...,
    with the counterexample that breaks each failing axiom."""

    title = "Group or not? The four axioms, with a counterexample when one fails"
    scene_class = GroupOrNotScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {"structure": W.Dropdown(options=CHOICES, value="(ℤ, ×)", description="set, operation",
                                 style={"description_width": "initial"}),
                "a": slider(2.0, -4.0, 4.0, step=0.5, description="a", readout_format=".1f"),
                "b": slider(3.0, -4.0, 4.0, step=0.5, description="b", readout_format=".1f"),
                "c": slider(-1.0, -4.0, 4.0, step=0.5, description="c", readout_format=".1f")}

    @override
    def update(self, **values: Any) -> None:
        # whole numbers for a set of integers: the sliders step by 1 and a value between
        # integers moves to the nearest one (so (ℤ, ×) never offers a = -0.5)
        integer = integer_structure(values["structure"])
        with self.hold():
            for k in "abc":
                c = self.controls[k]
                c.step, c.readout_format = (1.0, ".0f") if integer else (0.5, ".1f")
                if integer and float(values[k]) != round(float(values[k])):
                    values[k] = float(round(float(values[k])))
                    c.value = values[k]
                    self._exact[k] = values[k]          # the whole number is the value now
                    if k in self._pinned:
                        before, _, t = self._pinned[k]
                        self._pinned[k] = (before, values[k], t)
        super().update(**values)

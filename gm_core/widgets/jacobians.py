"""Section 2.5 panel: a Jacobian assembled link by link
(scene of :mod:`gm_core.drawing.jacobians`).
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.jacobians import JacobianStepScene
from gm_core.widgets.base import ScenePanel, int_slider, register, slider

__all__ = ["JacobianStepPanel"]

PI = float(np.pi)


@register
class JacobianStepPanel(ScenePanel):
    """Step through a chain joint by joint: each joint's velocity carried to the tip, the Jacobian column by column."""

    title = "The Jacobian one column at a time: step k moves joint k alone, (2.33)-(2.37)"
    scene_class = JacobianStepScene
    scene: JacobianStepScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        joints = self.scene.chain.joints
        c = {"step": int_slider(1, 0, len(joints), description="step k")}
        for i, jt in enumerate(joints):
            lo, hi = (-PI, PI) if jt.kind == "revolute" else (0.0, 1.0)
            c[f"q{i + 1}"] = slider(0.4 * (i + 1) if jt.kind == "revolute" else 0.3, lo, hi,
                                    description=f"q{i + 1} ({jt.letter})")
        for i in range(len(joints)):
            c[f"q{i + 1}_dot"] = slider([0.8, 0.6, -1.0, 0.5, 0.5][i % 5], -2.0, 2.0, description=f"q{i + 1} rate")
        return c

"""Chapter 2 panels: arms, mobile chains, generalized body frames and Jacobians
(scenes of :mod:`gm_core.drawing.chains`).
"""
from __future__ import annotations

from typing import Any, ClassVar

import ipywidgets as W
import numpy as np
from typing_extensions import override

from gm_core.drawing.chains import (
    ArmScene,
    BetaFrameScene,
    JacobianMethodsScene,
    MobileChainScene,
    OffsetRPArmScene,
    ThreeLinkVelocityScene,
)
from gm_core.widgets.base import ScenePanel, register, slider

__all__ = [
    "SingleLinkPanel", "RRArmPanel", "RPArmPanel", "OffsetRPArmPanel", "MobileChainPanel",
    "TwoLinkMobilePanel", "ThreeLinkMobilePanel", "BetaFramePanel", "JacobianMethodsPanel",
    "ThreeLinkVelocityPanel",
]

PI = float(np.pi)

_GREEK = {"alpha": "α", "delta": "δ"}
_SUBSCRIPT = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def _joint_label(name: str) -> str:
    """The slider label of a joint value: "alpha2" -> "α₂" (control labels are HTML, where a
    formula is Unicode, as in the other chapters' panels)."""
    stem = name.rstrip("0123456789")
    return _GREEK.get(stem, stem) + name[len(stem):].translate(_SUBSCRIPT)


class _ArmPanel(ScenePanel):
    """A fixed-base arm with one slider per joint and per joint speed; the end effector's velocity arrow."""

    scene_class = ArmScene
    joints: ClassVar[str] = "R"
    lengths: ClassVar[tuple[float, ...]] = (1.0,)
    offsets: ClassVar[tuple[float, ...] | None] = None
    names: ClassVar[tuple[str, ...]] = ("alpha",)
    ranges: ClassVar[tuple[tuple[float, float], ...]] = ((-PI, PI),)
    start: ClassVar[tuple[float, ...]] = (0.6,)
    frames_shown: ClassVar[tuple[str, ...]] = ("f", "h")
    lim: ClassVar[float] = 1.4

    @override
    def scene_options(self) -> dict[str, Any]:
        o = self.options
        return dict(joints=o.get("joints", self.joints), lengths=o.get("lengths", self.lengths),
                    offsets=o.get("offsets", self.offsets), names=self.names, frames_shown=self.frames_shown,
                    lim=o.get("lim", self.lim))

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c = {name: slider(v, lo, hi, description=_joint_label(name))
             for name, (lo, hi), v in zip(self.names, self.ranges, self.start)}
        for name in self.names:
            c[name + "_dot"] = slider(0.5, -2.0, 2.0, description=_joint_label(name) + " rate")
        return c


@register
class SingleLinkPanel(_ArmPanel):
    """One link on a pivot: the proximal frame rotates with alpha, the distal frame follows (2.4); arrow (2.17)."""

    title = "A pivoted link (fig. 2.2): frames g and h, velocity of h from (2.17)"


@register
class RRArmPanel(_ArmPanel):
    """The two-link rotary arm of fig. 2.3 with its end-effector velocity (2.19)."""

    title = "Two-link arm (fig. 2.3): forward kinematics (2.5)-(2.7), end-effector velocity (2.19)"
    joints = "RR"
    lengths = (1.0, 0.8)
    names = ("alpha1", "alpha2")
    ranges = ((-PI, PI), (-PI, PI))
    start = (0.5, 0.8)
    lim = 2.0


@register
class RPArmPanel(_ArmPanel):
    """The rotary-prismatic arm of fig. 2.4: link 2 slides out by delta along link 1, (2.10)-(2.11), (2.45)."""

    title = "Rotary-prismatic arm (fig. 2.4): the dashed gap is the slide δ"
    joints = "RP"
    lengths = (1.0, 0.6)
    names = ("alpha", "delta")
    ranges = ((-PI, PI), (0.0, 1.0))
    start = (0.5, 0.3)
    frames_shown = ("f", "h")
    lim = 2.5


@register
class OffsetRPArmPanel(RPArmPanel):
    """The rotary-prismatic arm with link 2 offset sideways by a (fig. 2.10, exercise 2.2)."""

    title = "Offset rotary-prismatic arm (fig. 2.10): velocity of the end effector"
    scene_class = OffsetRPArmScene
    offsets = (0.3, 0.0)


class MobileChainPanel(ScenePanel):
    """A free-floating chain: pose sliders place the base link's centre, joint sliders set the shape.

    The shared base of the two- and three-link panels (not registered itself; pass ``lengths=...``
    for other chains). Controls: x, y, theta of the base link's medial frame, one joint angle per
    joint, the base link index, and for three links the shape symmetry ("free", "even"
    alpha2 = alpha1, "odd" alpha2 = -alpha1, fig. 2.6).
    """

    title = "Mobile articulated system (figs. 2.5, 2.6, 2.8): base link, shape and symmetry"
    scene_class = MobileChainScene
    scene: MobileChainScene
    default_lengths: ClassVar[tuple[float, ...]] = (1.0, 1.0, 1.0)

    @override
    def scene_options(self) -> dict[str, Any]:
        return dict(lengths=tuple(self.options.get("lengths", self.default_lengths)))

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        n = len(self.options.get("lengths", self.default_lengths))
        c = {"x": slider(0.0, -1.0, 1.0, description="x"), "y": slider(0.0, -1.0, 1.0, description="y"),
             "theta": slider(0.0, -PI, PI, description="θ")}
        for j in range(n - 1):
            c[f"alpha{j + 1}"] = slider([0.6, -0.6, 0.4][j % 3], -2.5, 2.5, description=_joint_label(f"alpha{j + 1}"))
        c["base_link"] = W.IntSlider(value=(n - 1) // 2, min=0, max=n - 1, description="base link")
        if n == 3:
            # each symmetry says what it does to α₂ (fig. 2.6); the values stay "even" and "odd"
            c["shape"] = W.Dropdown(options=[("free", "free"), ("even: α₂ = α₁", "even"), ("odd: α₂ = −α₁", "odd")],
                                    value="free", description="shape")
        c["all_frames"] = W.Checkbox(value=False, description="show f and h frames")
        return c

    @override
    def after_update(self, values: dict[str, Any]) -> None:
        """Under a symmetry the α₂ slider is greyed and shows the α₂ the shape uses (±α₁), so its
        readout never disagrees with the picture; back to "free", α₂ starts from that value and
        the chain does not jump."""
        if "alpha2" in self.controls:
            symmetric = values.get("shape", "free") != "free"
            self.controls["alpha2"].disabled = symmetric
            used = float(self.scene.shape(values)[1])
            if symmetric and values["alpha2"] != used:
                self.follow("alpha2", used)


@register
class TwoLinkMobilePanel(MobileChainPanel):
    """The two-link mobile system of fig. 2.5, configuration space SE(2) x S^1."""

    title = "Two-link mobile system (fig. 2.5): g2 from (2.12)-(2.13)"
    default_lengths = (1.0, 1.0)


@register
class ThreeLinkMobilePanel(MobileChainPanel):
    """The three-link mobile system of fig. 2.8 with even/odd shapes (fig. 2.6)."""

    title = "Three-link mobile system (figs. 2.6, 2.8): sign convention and symmetric shapes"


@register
class BetaFramePanel(ScenePanel):
    """A body frame g = g_2 beta placed by sliders (fig. 2.7) or at the centre of mass (fig. 2.9, ex. 2.3)."""

    title = "Generalized body frame β (figs. 2.7, 2.9)"
    scene_class = BetaFrameScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {
            "alpha1": slider(0.8, -2.5, 2.5, description="α₁"),
            "alpha2": slider(0.8, -2.5, 2.5, description="α₂"),
            "frame": W.Dropdown(options=["sliders", "centre of mass"], value="centre of mass",
                                description="β"),
            "beta_x": slider(0.3, -1.0, 1.0, description="βˣ"),
            "beta_y": slider(0.2, -1.0, 1.0, description="βʸ"),
            "beta_theta": slider(0.0, -PI, PI, description="βᶿ"),
        }

    @override
    def after_update(self, values: dict[str, Any]) -> None:
        for k in ("beta_x", "beta_y", "beta_theta"):
            self.controls[k].disabled = values["frame"] != "sliders"


@register
class JacobianMethodsPanel(ScenePanel):
    """The end-effector velocity of a chain by the three Jacobian methods of section 2.5, live side by side."""

    title = "Three ways to a Jacobian: direct (2.16), world iterative (2.31), body iterative (2.37)"
    scene_class = JacobianMethodsScene
    scene: JacobianMethodsScene
    COLORS: ClassVar[dict[str, str]] = JacobianMethodsScene.COLORS

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        c: dict[str, W.ValueWidget] = {}
        joints = self.scene.chain.joints
        for i, jt in enumerate(joints):
            lo, hi = (-PI, PI) if jt.kind == "revolute" else (0.0, 1.0)
            c[f"q{i + 1}"] = slider(0.4 * (i + 1) if jt.kind == "revolute" else 0.3, lo, hi,
                                    description=f"q{i + 1} ({jt.letter})")
        for i in range(len(joints)):
            c[f"q{i + 1}_dot"] = slider(0.5, -2.0, 2.0, description=f"q{i + 1} rate")
        return c


@register
class ThreeLinkVelocityPanel(ScenePanel):
    """Body velocities of the three links from (xi, alpha_dot) through the corrected (2.57)-(2.59)."""

    title = "Three-link system: link body velocities from ξ and the joint speeds (2.57)-(2.59)"
    scene_class = ThreeLinkVelocityScene

    @override
    def controls_spec(self) -> dict[str, W.ValueWidget]:
        return {
            "alpha1": slider(0.6, -2.5, 2.5, description="α₁"),
            "alpha2": slider(-0.4, -2.5, 2.5, description="α₂"),
            "xi_x": slider(0.5, -1.0, 1.0, description="ξˣ"),
            "xi_y": slider(0.0, -1.0, 1.0, description="ξʸ"),
            "xi_theta": slider(0.0, -1.0, 1.0, description="ξᶿ"),
            "alpha1_dot": slider(0.0, -1.0, 1.0, description="α₁ rate"),
            "alpha2_dot": slider(1.0, -1.0, 1.0, description="α₂ rate"),
        }

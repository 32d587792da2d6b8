"""Chapter 1 panels: the scenes of :mod:`gm_core.drawing.ch1` with sliders.

Every panel is a thin wrapper: ``build`` makes the scene and the sliders, ``update`` asks the
scene to move its artists and calls ``draw_idle``, ``naive_update`` is the clear-and-replot
baseline used by ``benchmarks/widget_latency.py``. The scene is ``panel.scene``; its artists are
what the headless tests in ``tests/test_widgets_ch1.py`` read back.
"""
from __future__ import annotations

import ipywidgets as W
import numpy as np

from ..drawing import ch1 as D
from ..drawing import group_or_not as G
from ..drawing import observer as O
from ..drawing import tangent as T
from .base import ScenePanel, int_slider, register, slider

__all__ = [
    "show", "TorusPathPanel", "LoopsPanel", "PoleChartPanel",
    "GroupAxiomsPanel", "SlideRulePanel", "CircleIsoPanel", "LeftRightActionPanel",
    "ForwardLeftPanel", "BodyPointsPanel",
    "TangentSpacePanel", "VectorFieldPanel", "LiftedScalarPanel", "LiftedSE2Panel", "VelocityPanel", "AdjointPanel",
    "ObserverPanel", "FramesPanel",
    "SurfaceGeodesicsPanel", "HelixPanel", "PuckArcPanel", "RPlusGeodesicPanel", "ExpFourWaysPanel",
]

PI = np.pi


def show(fig):
    """Display a static figure under any backend (the ipympl canvas, or a PNG otherwise)."""
    from IPython.display import display

    canvas = fig.canvas
    if isinstance(canvas, W.DOMWidget):
        display(canvas)
    else:
        display(fig)


# ====================================================================== 1.1 configuration spaces
@register
class TorusPathPanel(ScenePanel):
    """A straight line on the flattened torus is a winding path on the torus (figs 1.5, 1.16)."""

    title = "Torus: flattened view with glued edges"
    scene_class = D.TorusPathScene
    # The path winds behind the torus's wireframe; only a full 3D draw sorts them by depth.
    blit = False

    def controls_spec(self):
        return {"a0": slider(0.5, 0.0, 2 * PI, description="start a₀"),
                "b0": slider(1.0, 0.0, 2 * PI, description="start b₀"),
                "slope": slider(0.5, -3.0, 3.0, description="slope db/da"),
                "turns": slider(2.0, 0.1, 4.0, description="turns in a")}


@register
class LoopsPanel(ScenePanel):
    """Fig. 1.6: shrinking a loop on the sphere works; on the torus it cannot."""

    title = "Loops on the torus and on the sphere (fig. 1.6)"
    scene_class = D.LoopsScene

    def controls_spec(self):
        return {"s": slider(0.0, 0.0, 1.0, description="shrink s")}


@register
class PoleChartPanel(ScenePanel):
    """Walk towards a pole: the latitude/longitude chart's coordinate speed blows up there."""

    title = "Charts on the sphere and the pole singularity"
    scene_class = D.PoleChartScene

    def controls_spec(self):
        return {"lat_deg": slider(45.0, -90.0, 90.0, step=0.5, description="latitude φ (°)",
                                  readout_format=".1f"),
                "heading_deg": slider(45.0, 0.0, 180.0, step=1.0, description="heading from north (°)",
                                      readout_format=".0f")}


# ============================================================================ 1.2-1.3 groups
@register
class GroupAxiomsPanel(ScenePanel):
    """Group or not? The axioms (1.ii)-(1.v) on real groups and on (ℤ, ×), (ℝ⁺, +), (ℝ, −), ...,
    with the counterexample that breaks each failing axiom (``GroupOrNotPanel`` is the same)."""

    title = "Group or not? The four axioms, with a counterexample when one fails"
    scene_class = G.GroupOrNotScene

    def controls_spec(self):
        return {"structure": W.Dropdown(options=G.CHOICES, value="(ℤ, ×)", description="set, operation",
                                 style={"description_width": "initial"}),
                "a": slider(2.0, -4.0, 4.0, step=0.5, description="a", readout_format=".1f"),
                "b": slider(3.0, -4.0, 4.0, step=0.5, description="b", readout_format=".1f"),
                "c": slider(-1.0, -4.0, 4.0, step=0.5, description="c", readout_format=".1f")}

    def update(self, **values):
        # whole numbers for a set of integers: the sliders step by 1 and a value between
        # integers moves to the nearest one (so (ℤ, ×) never offers a = -0.5)
        integer = G.integer_structure(values["structure"])
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


#: the explorer under its descriptive name (the notebooks and tests know it as GroupAxiomsPanel)
GroupOrNotPanel = GroupAxiomsPanel


@register
class SlideRulePanel(ScenePanel):
    """(R+, ×) ↔ (R, +) through log: a slide rule, (1.xii)."""

    title = "A slide rule multiplies by adding logarithms"
    scene_class = D.SlideRuleScene

    def controls_spec(self):
        return {"a": slider(2.0, 1.0, 10.0, description="a"),
                "b": slider(3.0, 1.0, 10.0, description="b")}


@register
class CircleIsoPanel(ScenePanel):
    """(S¹, + mod 1) ↔ SO(2) through S1(1.0).matrix, (1.xiv)-(1.xvi)."""

    title = "Adding on the circle = multiplying rotations"
    scene_class = D.CircleIsoScene

    def controls_spec(self):
        return {"a1": slider(0.2, 0.0, 0.99, description="a₁ (cycles)"),
                "a2": slider(0.35, 0.0, 0.99, description="a₂ (cycles)")}


def _se2_sliders(x, y, theta, names=("x", "y", "theta"), lim=2.5, labels=("x", "y", "θ")):
    return {names[0]: slider(x, -lim, lim, description=labels[0]),
            names[1]: slider(y, -lim, lim, description=labels[1]),
            names[2]: slider(theta, -PI, PI, description=labels[2])}


@register
class LeftRightActionPanel(ScenePanel):
    """Figs. 1.8-1.9: left action h∘g and right action g∘h of SE(2)."""

    title = "SE(2): left action (move by h) vs right action (h relative to g)"
    scene_class = D.LeftRightActionScene

    def controls_spec(self):
        c = _se2_sliders(1.5, 0.5, 0.5, labels=("g: x", "g: y", "g: θ"))
        c.update(_se2_sliders(-1.0, 1.0, 0.9, names=("u", "v", "beta"), labels=("h: u", "h: v", "h: β")))
        return c


@register
class ForwardLeftPanel(ScenePanel):
    """Fig. 1.10: repeating a step in (R²×S¹, +) and in SE(2)."""

    title = "“Forward and to the left”, again and again (fig. 1.10)"
    scene_class = D.ForwardLeftScene

    def controls_spec(self):
        c = _se2_sliders(1.0, 1.0, PI / 2, lim=2.0, labels=("g: x", "g: y", "g: θ"))
        c["n"] = int_slider(2, 1, D.ForwardLeftScene.N_MAX, description="steps n")
        return c


@register
class BodyPointsPanel(ScenePanel):
    """(1.11)-(1.12): a point fixed in the body and its world position."""

    title = "Points on a rigid body"
    scene_class = D.BodyPointsScene

    def controls_spec(self):
        c = _se2_sliders(0.5, 0.3, 0.6, lim=2.0, labels=("g: x", "g: y", "g: θ"))
        c["px"] = slider(0.6, -0.8, 0.8, description="body pₓᵇ")
        c["py"] = slider(0.3, -0.4, 0.4, description="body p_yᵇ")
        return c


# ============================================================================== 1.4-1.5 velocities
@register
class TangentSpacePanel(ScenePanel):
    """Figs 1.11-1.12: velocities are arrows in the tangent space at the moving point."""

    title = "Velocities live in tangent spaces (figs 1.11-1.12)"
    scene_class = T.TangentSpaceScene
    # the 3D view turns with the point: only a full draw sorts the sphere's curve by depth
    blit = False

    def controls_spec(self):
        return {"s": slider(0.8, 0.0, 2 * PI, description="where along the curve s"),
                "speed": slider(1.0, -2.0, 2.0, description="speed ds/dt")}


@register
class VectorFieldPanel(ScenePanel):
    """Figs. 1.13-1.14: integral curves of a vector field from a movable start point."""

    title = "Vector fields and integral curves"
    scene_class = D.VectorFieldScene

    def controls_spec(self):
        return {"field": W.Dropdown(options=list(D.FIELDS), value="spiral sink", description="field"),
                "x0": slider(1.5, -2.9, 2.9, description="start x₀"),
                "y0": slider(1.0, -2.9, 2.9, description="start y₀")}


@register
class LiftedScalarPanel(ScenePanel):
    """(1.22)-(1.25): lifted actions on (R², +) and (R⁺, ×)."""

    title = "Lifted actions carry velocities between tangent spaces"
    scene_class = D.LiftedScalarScene

    def controls_spec(self):
        return {"hx": slider(1.5, -1.0, 3.0, description="R²: hₓ"),
                "hy": slider(1.0, -1.0, 2.5, description="R²: h_y"),
                "h": slider(2.5, 0.2, 6.0, description="R⁺: h")}


@register
class LiftedSE2Panel(ScenePanel):
    """(1.31), (1.37): left and right lifted actions of SE(2) on a moving body."""

    title = "SE(2): T_gL_h keeps the body velocity, T_gR_h keeps the spatial velocity"
    scene_class = D.LiftedSE2Scene

    def controls_spec(self):
        return {"theta": slider(0.3, -PI, PI, description="g: θ"),
                "u": slider(2.0, -1.5, 3.0, description="h: u"),
                "v": slider(1.5, -1.5, 3.0, description="h: v"),
                "beta": slider(1.0, -PI, PI, description="h: β")}


def _xi_sliders(vx, vy, w):
    return {"vx": slider(vx, -1.5, 1.5, description="ξˣ"),
            "vy": slider(vy, -1.5, 1.5, description="ξʸ"),
            "w": slider(w, -1.5, 1.5, description="ξᶿ")}


@register
class VelocityPanel(ScenePanel):
    """Fig. 1.15: world, body and spatial velocity."""

    title = "Four views of one velocity (fig. 1.15)"
    scene_class = D.VelocityScene

    def controls_spec(self):
        c = _se2_sliders(1.2, 0.6, 0.7, lim=2.0, labels=("g: x", "g: y", "g: θ"))
        c.update(_xi_sliders(0.8, 0.3, 0.6))
        return c


@register
class AdjointPanel(ScenePanel):
    """(1.40)-(1.45): the adjoint, checked three ways, live."""

    title = "The adjoint Ad_g = T_gR_g⁻¹ T_eL_g, checked live"
    scene_class = D.AdjointScene

    def controls_spec(self):
        c = _se2_sliders(1.0, -0.5, 0.8, lim=2.5, labels=("g: x", "g: y", "g: θ"))
        c.update(_xi_sliders(0.5, 0.2, 0.7))
        return c


@register
class ObserverPanel(ScenePanel):
    """The adjoint as a change of observer: move h, ξ stays, ξˢ changes; the ICR is one point."""

    title = "Change the observer: the body velocity stays, the spatial velocity changes"
    scene_class = O.ObserverScene

    def controls_spec(self):
        c = _se2_sliders(-1.5, -1.0, 0.0, names=("hx", "hy", "htheta"), lim=2.5,
                         labels=("observer h: x", "observer h: y", "observer h: θ"))
        c.update(_xi_sliders(0.8, 0.3, 0.6))
        return c


@register
class FramesPanel(ScenePanel):
    """The "Frames" box: one reference frame, two coordinate frames, the instantaneous body frame."""

    title = "Reference frame, coordinate frames, and the instantaneous body frame"
    scene_class = O.FramesScene

    def controls_spec(self):
        c = {"t": slider(1.2, 0.0, 6.0, description="time t")}
        c.update(_se2_sliders(-1.8, 1.2, -0.5, names=("bx", "by", "btheta"), lim=2.5,
                              labels=("frame B: x", "frame B: y", "frame B: θ")))
        return c


# ============================================================================== 1.6 geodesics, exp
@register
class SurfaceGeodesicsPanel(ScenePanel):
    """Fig. 1.16: geodesics of the cylinder (loops, helices, lines) and of the sphere (great circles)."""

    title = "Straightest lines on the cylinder and the sphere (fig. 1.16)"
    scene_class = D.SurfaceGeodesicsScene
    # curves wind behind the surfaces' wireframes: only a full 3D draw sorts them by depth
    blit = False

    def controls_spec(self):
        return {"heading_deg": slider(15.0, -90.0, 90.0, step=1.0, description="heading (° up from around)",
                                      readout_format=".0f"),
                "length": slider(3 * PI, 0.1, 4 * PI, description="distance travelled")}


@register
class HelixPanel(ScenePanel):
    """Fig. 1.18: SE(2) geodesic helices and their circular shadows."""

    title = "SE(2) geodesics are helices (fig. 1.18)"
    scene_class = D.HelixScene

    def controls_spec(self):
        return {"thetadot": slider(1.0, -3.0, 3.0, description="dθ/dt (turning rate)")}


@register
class PuckArcPanel(ScenePanel):
    """Fig. 1.19: spinning puck vs SE(2) arc, scrubbed by time."""

    title = "Spinning puck vs SE(2) arc (fig. 1.19)"
    scene_class = D.PuckArcScene

    def controls_spec(self):
        return {"t": slider(1.5, 0.0, 2 * PI, description="time t"),
                "w": slider(1.0, 0.2, 2.0, description="ξᶿ")}


@register
class RPlusGeodesicPanel(ScenePanel):
    """Fig. 1.17: accelerating and decelerating geodesics of (R⁺, ×)."""

    title = "Geodesics of (R⁺, ×) (fig. 1.17)"
    scene_class = D.RPlusGeodesicScene

    def controls_spec(self):
        return {"xi": slider(1.0, -1.5, 1.5, description="ξ")}


@register
class ExpFourWaysPanel(ScenePanel):
    """Section 1.6.4, exercise 1.4d: the exponential map four ways."""

    title = "exp(ξ) on SE(2), four ways"
    scene_class = D.ExpFourWaysScene

    def controls_spec(self):
        return {"thetadot": slider(1.0, -3.0, 3.0, description="dθ/dt in ξ = (1, 0, dθ/dt)"),
                "n": int_slider(8, 1, 64, description="steps / terms n"),
                "side": W.Dropdown(options=["left", "right"], value="left", description="field")}

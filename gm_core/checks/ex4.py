"""Checkers of the curvature exercises 4.1 and 4.2 (book/10, curvature and optimal gaits).

Beyond the draft: the constraint curvature D(-A) of the low-Reynolds swimmer (Hatton & Choset).
Like every chapter, the probes only turn the student's answer into plain data (a number, the
gait sampled at equal time steps); the references (gm_core.geometry, gm_core.systems.motion) and the
judging run in the checking process. What a right answer is lives in
:mod:`gm_core.checks.keys.ex4`. Independent routes are in tests/test_geometry_checks.py.
"""
from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from typing_extensions import override

from gm_core.checks import gait_samples
from gm_core.checks.answers import fmt_value
from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import Exercise
from gm_core.checks.parts import CustomPart, ValuePart

if TYPE_CHECKING:
    from gm_core.systems import LowReSwimmer
    from gm_core.systems.reframed import Reframed
    from gm_core.validation import FloatArray

__all__ = ["ex4_1", "ex4_2", "swimmer", "swimmer_4_1", "SQUARE_4_1", "GAITS_4_1", "TURN_MIN",
           "DRIFT_MAX"]


# ============================================================================ shared set-up
@functools.lru_cache(maxsize=1)
def swimmer() -> LowReSwimmer:
    """The swimmer of both exercises: LowReSwimmer() (links 1, drag ratio 2)."""
    from gm_core.systems import LowReSwimmer

    return LowReSwimmer()


GAITS_4_1 = {"A": "circle of radius 1.0 about (0, 0)", "C": "circle of radius 2.2 about (0, 0)"}
#: The square of shape space over which exercise 4.1's frame is solved (it holds both circles).
SQUARE_4_1 = ((-2.5, 2.5), (-2.5, 2.5))


@functools.lru_cache(maxsize=1)
def swimmer_4_1() -> Reframed:
    """The swimmer of exercise 4.1: LowReSwimmer() in its minimum-perturbation frame over SQUARE_4_1.

    In that frame the curvature map is a faithful picture of the motion (notebook 10, section 4):
    the Stokes estimates of both circles are within 0.01 of the exact displacements.
    """
    from gm_core.geometry import minimum_perturbation_coordinates

    return minimum_perturbation_coordinates(swimmer(), SQUARE_4_1)


# ============================================================================ 4.1
class _AreaSum(ValuePart):
    """4.1(b): the student's own area sum, within 0.5 % of the library's Stokes estimate of gait A
    (a midpoint sum with cells of 0.1 is within 0.45 %)."""

    name, rtol, atol = "b", 0.005, 0.0
    prompt = "The x component of the Stokes estimate for gait A, from your own area sum (a number)"
    expects = "one number (the x component)"
    wrong_size = "your answer has {size} numbers (shape {shape}); hand in only the x component, one number."
    not_finite = ("your number is not finite (NaN or infinite): did a cell of your grid sit on a "
                  "singular shape, or did you divide by zero?")
    hints = ["Evaluate constraint_curvature(s, grid) (s: the exercise's swimmer, in the "
             "minimum-perturbation frame) on a grid of cell centres over the square [-1, 1]^2, "
             "cells of 0.1 or smaller.",
             "Keep the points with a1^2 + a2^2 <= 1, sum their x curvature (row 0) and multiply "
             "by the area of one cell."]

    @override
    def far_message(self, value: float | np.ndarray, expected: npt.ArrayLike) -> str:
        return (f"your number {fmt_value(value)} is not within 0.5 % of the area integral of the x "
                "curvature over the disc of radius 1. Is your grid fine enough (cells of 0.1 or "
                "smaller), did you use the swimmer of this exercise (s, in the minimum-perturbation "
                "frame), keep only the points inside the circle and multiply by the area of one cell?")


ex4_1 = Exercise("4.1", "Which gait moves further? Reading a curvature map", [
    ChoicePart(
        "a", "Which gait moves the low-Re swimmer further per cycle? (Both move it backward, along -x.)",
        {"a": "gait C, the larger circle: it encloses more area",
         "b": "both the same: they are circles with the same centre",
         "c": "gait A, the smaller circle",
         "d": "neither can be read off the curvature map"},
        hints=["Look at the x map of the swimmer (minimum-perturbation frame) with both circles drawn on it.",
               "Net x motion ~ (the x curvature inside the loop, added up with its sign): "
               "red counts one way, blue the other."]),
    _AreaSum(),
    ChoicePart(
        "c", "Why does the larger circle move less?",
        {"a": "larger gaits are run faster, so the swimmer slips more",
         "b": "the Stokes estimate fails for large gaits, so the map cannot tell",
         "c": "the x curvature vanishes everywhere further than 1 from the origin",
         "d": "C's outer ring holds x curvature of the opposite sign, which cancels"},
        hints=["Compare the colours at radius 1 and at radius 2 on the x map."]),
])


# ============================================================================ 4.2
TURN_MIN, DRIFT_MAX = 0.2, 0.02


def _sample_gait(answer: Any) -> FloatArray:
    """Student side of 4.2(a): the gait sampled over one period (:mod:`gm_core.checks.gait_samples`)."""
    return gait_samples.sample(answer, 2, "circle_gait(...)")


ex4_2 = Exercise("4.2", "A gait that turns the swimmer in place", [
    CustomPart(
        "a", f"A gait of the low-Re swimmer that turns it by >= {TURN_MIN} rad per cycle while its "
             f"centre of mass moves <= {DRIFT_MAX}",
        lambda: [_sample_gait],
        hints=["On the theta map, where is the curvature strong and of one sign?",
               "Try small circles centred on the diagonal alpha1 = alpha2 (a C-shaped body on "
               "average).",
               "Scan centres (c, c) and radii with drift_and_turn(s, gait) from gm_core.geometry."],
        kind="gait"),
    ChoicePart(
        "b", "Where on the curvature maps does such a gait sit?",
        {"a": "on strong theta curvature of one sign, away from the x and y lobes",
         "b": "centred on the origin, where every row of the curvature is largest",
         "c": "anywhere at all: the swimmer cannot turn without also moving forward",
         "d": "on the anti-diagonal line alpha1 = -alpha2, through the middle"},
        hints=["Turning comes from the theta map, moving from the x and y maps."]),
])

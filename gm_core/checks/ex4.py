"""Checkers of the curvature exercises 4.1 and 4.2 (book/10, curvature and optimal gaits).

Beyond the draft: the constraint curvature D(-A) of the low-Reynolds swimmer (Hatton & Choset).
Like every chapter, the probes only turn the student's answer into plain data (a number, the
gait sampled at equal time steps); the references (gm_core.geometry, gm_core.systems.motion) and the
judging run in the checking process. Independent routes are in tests/test_geometry_checks.py.
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
from gm_core.checks.parts import CustomPart, Mistake, ValuePart, first_value
from gm_core.checks.sandbox import ProbeOutcome, Wrong

if TYPE_CHECKING:
    from gm_core.systems import LowReSwimmer
    from gm_core.systems.reframed import Reframed
    from gm_core.validation import FloatArray

__all__ = ["ex4_1", "ex4_2", "swimmer", "swimmer_4_1", "SQUARE_4_1", "GAITS_4_1"]


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


@functools.lru_cache(maxsize=1)
def _stokes_A() -> tuple[FloatArray, FloatArray]:
    """(Stokes estimate, exact net displacement) of gait A: the references of 4.1(b)."""
    from gm_core.geometry import stokes_estimate
    from gm_core.systems.gaits import circle_gait
    from gm_core.systems.motion import net_displacement

    g = circle_gait(1.0)
    return stokes_estimate(swimmer_4_1(), g), net_displacement(swimmer_4_1(), g)


# ============================================================================ 4.1
class _AreaSum(ValuePart):
    """4.1(b): the student's own area sum, within 0.5 % of the library's Stokes estimate of gait A
    (a midpoint sum with cells of 0.1 is within 0.45 %; the exact displacement, 0.8 % away in this
    frame, is a mistake of its own)."""

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
    solution_text = ("About -0.155 (stokes_estimate(s, circle_gait(1.0))[0], s the swimmer in the "
                     "minimum-perturbation frame); the exact net x displacement is about -0.154.")
    reference, wrong = -0.15492, [0.15492, -0.15369, 0.0, -0.15492 / 0.01 ** 2, -0.17]

    @override
    def expected_value(self) -> float:
        return float(_stokes_A()[0][0])

    @override
    def known_mistakes(self, expected: npt.ArrayLike) -> list[Mistake]:
        ref = float(np.asarray(expected))
        tol = self.rtol * abs(ref)
        return [Mistake(_stokes_A()[1][0], "that is the exact net displacement (net_displacement); "
                        "this part asks for your own area sum of the x curvature. In this frame the "
                        "two are close (within 1 %), but they are not the same number.", 0.3 * tol),
                Mistake(-ref, "your sign is reversed: a counter-clockwise gait collects +D(-A) over "
                        "the region it encloses, and circle_gait runs counter-clockwise."),
                Mistake(0.0, "your sum is (nearly) zero: that is the y or theta component, or a grid "
                        "whose cells were not restricted to the disc. Sum row x (index 0) inside the "
                        "circle.", 1e-3 * abs(ref))]

    @override
    def success_message(self, value: float | np.ndarray, expected: npt.ArrayLike) -> str:
        return (f"Correct: {fmt_value(value)}; the library's stokes_estimate gives "
                f"{fmt_value(expected)}, and the exact net x displacement in this frame is "
                f"{fmt_value(_stokes_A()[1][0])}.")

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
        "c",
        feedback={"c": "Correct: C encloses more area, but in this frame its outer ring holds x curvature "
                       "of the opposite sign, which cancels part of what the inner disc contributes.",
                  "a": "Area alone is not the point: look at the colours inside C's outer ring.",
                  "b": "Both are centred circles, but what matters is the curvature they enclose.",
                  "d": "The map does tell: to leading order the net x motion is the x curvature "
                       "enclosed."},
        hints=["Look at the x map of the swimmer (minimum-perturbation frame) with both circles drawn on it.",
               "Net x motion ~ (the x curvature inside the loop, added up with its sign): "
               "red counts one way, blue the other."],
        solution_text="c: the smaller circle A."),
    _AreaSum(),
    ChoicePart(
        "c", "Why does the larger circle move less?",
        {"a": "larger gaits are run faster, so the swimmer slips more",
         "b": "the Stokes estimate fails for large gaits, so the map cannot tell",
         "c": "the x curvature vanishes everywhere further than 1 from the origin",
         "d": "C's outer ring holds x curvature of the opposite sign, which cancels"},
        "d",
        feedback={"d": "Correct: in this frame the ring 1 < r < 2.2 adds about +0.037 to the inner "
                       "disc's -0.155, so C's estimate is smaller (-0.118, exact -0.124). In the "
                       "middle-link frame the same ring adds x curvature of the same sign (-0.197): "
                       "there the map would mislead, because for a gait this big the Stokes estimate "
                       "fails (notebook 10, section 4).",
                  "a": "The net displacement of a gait does not depend on its pace (the "
                       "reparameterization argument of section 3.1).",
                  "b": "Not in this frame: here the Stokes estimate of C (-0.118) is within 0.01 of "
                       "the exact value (-0.124), so the map does tell. (In the middle-link frame it "
                       "would be the reason.)",
                  "c": "Look again at the map: the x curvature is far from zero beyond radius 1, "
                       "with strong red lobes on both diagonals."},
        hints=["Compare the colours at radius 1 and at radius 2 on the x map."],
        solution_text="d: in this frame the enclosed curvature changes sign further out."),
])


# ============================================================================ 4.2
TURN_MIN, DRIFT_MAX = 0.2, 0.02


def _sample_gait(answer: Any) -> FloatArray:
    """Student side of 4.2(a): the gait sampled over one period (:mod:`gm_core.checks.gait_samples`)."""
    return gait_samples.sample(answer, 2, "circle_gait(...)")


def _judge_42a(outcomes: list[ProbeOutcome]) -> str:
    from gm_core.geometry import drift_and_turn
    from gm_core.systems.gaits import Gait

    r = gait_samples.grid(first_value(outcomes, "your gait", "the times of one period"), 2)
    if np.max(np.abs(r)) > 2 * np.pi:
        raise Wrong("your gait reaches joint angles beyond 2 pi: the links would pass through each "
                    "other. Keep the loop within about (-3, 3) in each angle.")
    if np.linalg.norm(r[-1] - r[0]) > 1e-6 * max(1.0, float(np.max(np.abs(r)))):
        raise Wrong(f"your gait does not close: r(0) = {fmt_value(r[0])} but r(T) = "
                    f"{fmt_value(r[-1])}. A gait must come back to its first shape after one period.")
    turn, drift = drift_and_turn(swimmer(), Gait.from_samples(r[:-1]))
    if abs(turn) < TURN_MIN:
        raise Wrong(f"it turns by only {turn:+.3f} rad per cycle; at least {TURN_MIN} rad is asked "
                    "for. Which part of the theta map would you enclose?")
    if drift > DRIFT_MAX:
        raise Wrong(f"it turns by {turn:+.3f} rad, but its centre of mass moves {drift:.3f} per cycle "
                    f"(the swimmer is 3 long); at most {DRIFT_MAX} is asked for. Try smaller or "
                    "shifted loops.")
    return f"Correct: it turns by {turn:+.3f} rad while its centre of mass moves only {drift:.4f}."


class _CircleGait:
    """circle_gait(radius, centre), built only when called (keeps the import of this module light)."""

    def __init__(self, radius: float, centre: tuple[float, float] = (0.0, 0.0)) -> None:
        self.radius, self.centre = radius, centre

    def __call__(self, t: npt.ArrayLike) -> FloatArray:
        from gm_core.systems.gaits import circle_gait

        return circle_gait(self.radius, self.centre)(t)

    @override
    def __repr__(self) -> str:
        return f"circle_gait({self.radius}, {self.centre})"


ex4_2 = Exercise("4.2", "A gait that turns the swimmer in place", [
    CustomPart(
        "a", f"A gait of the low-Re swimmer that turns it by >= {TURN_MIN} rad per cycle while its "
             f"centre of mass moves <= {DRIFT_MAX}",
        lambda: [_sample_gait], _judge_42a,
        hints=["On the theta map, where is the curvature strong and of one sign?",
               "Try small circles centred on the diagonal alpha1 = alpha2 (a C-shaped body on "
               "average).",
               "Scan centres (c, c) and radii with drift_and_turn(s, gait) from gm_core.geometry."],
        solution_text="For example circle_gait(0.5, (1.5, 1.5)): about -0.26 rad, drift about 0.006.",
        reference=_CircleGait(0.5, (1.5, 1.5)),
        wrong=[_CircleGait(1.0, (1.5, 1.5)), _CircleGait(0.5), _CircleGait(0.5, (1.5, -1.5)),
               lambda t: np.stack([1.5 + 0.5 * np.cos(2 * np.pi * t), 1.5 + t], -1)],
        kind="gait"),
    ChoicePart(
        "b", "Where on the curvature maps does such a gait sit?",
        {"a": "on strong theta curvature of one sign, away from the x and y lobes",
         "b": "centred on the origin, where every row of the curvature is largest",
         "c": "anywhere at all: the swimmer cannot turn without also moving forward",
         "d": "on the anti-diagonal line alpha1 = -alpha2, through the middle"},
        "a",
        feedback={"a": "Correct: enclose theta curvature of one sign while the x and y curvature "
                       "enclosed cancels.",
                  "b": "A loop centred on the origin encloses theta curvature of both signs: it "
                       "does not turn.",
                  "c": "It can, approximately: look for loops whose enclosed x and y curvature "
                       "cancel.",
                  "d": "By the swimmer's symmetry, such loops do not turn it at all."},
        hints=["Turning comes from the theta map, moving from the x and y maps."],
        solution_text="a."),
])

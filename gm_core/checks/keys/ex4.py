"""The answer keys of chapter 4's exercises (:mod:`gm_core.checks.ex4`): the Stokes estimate of
gait A and the mistakes near it, what a gait that turns in place must do, and the correct options.
The references come from gm_core.geometry and gm_core.systems.motion."""
from __future__ import annotations

import functools
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from gm_core.checks import gait_samples
from gm_core.checks.answer_key import ChoiceKey, JudgeKey, Mistake, ValueKey, provide
from gm_core.checks.answers import fmt_value
from gm_core.checks.ex4 import DRIFT_MAX, TURN_MIN, ex4_1, ex4_2, swimmer, swimmer_4_1
from gm_core.checks.parts import ValuePart, first_value
from gm_core.checks.sandbox import ProbeOutcome, Wrong

if TYPE_CHECKING:
    from collections.abc import Callable

    from gm_core.validation import FloatArray


# ============================================================================ 4.1
@functools.lru_cache(maxsize=1)
def _stokes_A() -> tuple[FloatArray, FloatArray]:
    """(Stokes estimate, exact net displacement) of gait A: the references of 4.1(b)."""
    from gm_core.geometry import stokes_estimate
    from gm_core.systems.gaits import circle_gait
    from gm_core.systems.motion import net_displacement

    g = circle_gait(1.0)
    return stokes_estimate(swimmer_4_1(), g), net_displacement(swimmer_4_1(), g)


def _expected_41b() -> float:
    return float(_stokes_A()[0][0])


def _rtol_41b() -> float:
    part = ex4_1.parts["b"]
    assert isinstance(part, ValuePart)
    return part.rtol


def _mistakes_41b(expected: npt.ArrayLike) -> list[Mistake]:
    """The exact displacement (0.8 % from the Stokes estimate in this frame) is a mistake of its
    own, within 0.3 of the part's tolerance; then a reversed sign and a (nearly) zero sum."""
    ref = float(np.asarray(expected))
    tol = _rtol_41b() * abs(ref)
    return [Mistake(_stokes_A()[1][0], "that is the exact net displacement (net_displacement); "
                    "this part asks for your own area sum of the x curvature. In this frame the "
                    "two are close (within 1 %), but they are not the same number.", 0.3 * tol),
            Mistake(-ref, "your sign is reversed: a counter-clockwise gait collects +D(-A) over "
                    "the region it encloses, and circle_gait runs counter-clockwise."),
            Mistake(0.0, "your sum is (nearly) zero: that is the y or theta component, or a grid "
                    "whose cells were not restricted to the disc. Sum row x (index 0) inside the "
                    "circle.", 1e-3 * abs(ref))]


def _success_41b(value: float | np.ndarray, expected: npt.ArrayLike) -> str:
    return (f"Correct: {fmt_value(value)}; the library's stokes_estimate gives "
            f"{fmt_value(expected)}, and the exact net x displacement in this frame is "
            f"{fmt_value(_stokes_A()[1][0])}.")


provide(
    ex4_1,
    a=ChoiceKey(
        correct="c",
        feedback={"c": "Correct: C encloses more area, but in this frame its outer ring holds x curvature "
                       "of the opposite sign, which cancels part of what the inner disc contributes.",
                  "a": "Area alone is not the point: look at the colours inside C's outer ring.",
                  "b": "Both are centred circles, but what matters is the curvature they enclose.",
                  "d": "The map does tell: to leading order the net x motion is the x curvature "
                       "enclosed."},
        solution_text="c: the smaller circle A."),
    b=ValueKey(
        expected=_expected_41b,
        mistakes=_mistakes_41b,
        success=_success_41b,
        solution_text=("About -0.155 (stokes_estimate(s, circle_gait(1.0))[0], s the swimmer in the "
                       "minimum-perturbation frame); the exact net x displacement is about -0.154."),
        reference=-0.15492,
        wrong=[0.15492, -0.15369, 0.0, -0.15492 / 0.01 ** 2, -0.17]),
    c=ChoiceKey(
        correct="d",
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
        solution_text="d: in this frame the enclosed curvature changes sign further out."),
)


# ============================================================================ 4.2
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


def _circle_gait(radius: float, centre: tuple[float, float] = (0.0, 0.0)) -> gait_samples.LazyGait:
    """circle_gait(radius, centre), built only when called."""
    def make() -> Callable[[npt.ArrayLike], FloatArray]:
        from gm_core.systems.gaits import circle_gait

        return circle_gait(radius, centre)

    return gait_samples.LazyGait(make, f"circle_gait({radius}, {centre})")


provide(
    ex4_2,
    a=JudgeKey(
        judge=_judge_42a,
        solution_text="For example circle_gait(0.5, (1.5, 1.5)): about -0.26 rad, drift about 0.006.",
        reference=_circle_gait(0.5, (1.5, 1.5)),
        wrong=[_circle_gait(1.0, (1.5, 1.5)), _circle_gait(0.5), _circle_gait(0.5, (1.5, -1.5)),
               lambda t: np.stack([1.5 + 0.5 * np.cos(2 * np.pi * t), 1.5 + t], -1)]),
    b=ChoiceKey(
        correct="a",
        feedback={"a": "Correct: enclose theta curvature of one sign while the x and y curvature "
                       "enclosed cancels.",
                  "b": "A loop centred on the origin encloses theta curvature of both signs: it "
                       "does not turn.",
                  "c": "It can, approximately: look for loops whose enclosed x and y curvature "
                       "cancel.",
                  "d": "By the swimmer's symmetry, such loops do not turn it at all."},
        solution_text="a."),
)

"""The answer key of exercise 5.1 (:mod:`gm_core.checks.ex5`): what a good gait does, and examples."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from gm_core.checks import gait_samples
from gm_core.checks.answer_key import ChoiceKey, JudgeKey, provide
from gm_core.checks.answers import fmt_value
from gm_core.checks.ex5 import ANGLE_MAX, DISTANCE_MIN, JOINTS, ex5_1, swimmer_5_1
from gm_core.checks.parts import first_value
from gm_core.checks.sandbox import ProbeOutcome, Wrong

if TYPE_CHECKING:
    from collections.abc import Callable

    from gm_core.validation import FloatArray


def _judge_51a(outcomes: list[ProbeOutcome]) -> str:
    from gm_core.systems.gaits import Gait
    from gm_core.systems.motion import net_displacement

    r = gait_samples.grid(first_value(outcomes, "your gait", "the times of one period"), JOINTS,
                          " (the four-link swimmer has three joints: alpha1, "
                          "alpha2, alpha3)")
    if np.linalg.norm(r[-1] - r[0]) > 1e-6 * max(1.0, float(np.max(np.abs(r)))):
        raise Wrong(f"your gait does not close: r(0) = {fmt_value(r[0])} but r(T) = "
                    f"{fmt_value(r[-1])}. A gait must come back to its first shape after one period.")
    big = float(np.max(np.abs(r)))
    if big > ANGLE_MAX + 1e-9:
        raise Wrong(f"your gait bends a joint by {big:.3f} rad; at most {ANGLE_MAX} rad is allowed (the "
                    "exercise's limit, which keeps the strokes moderate). Make the wave smaller.")
    g = net_displacement(swimmer_5_1(), Gait.from_samples(r[:-1]), steps=512, check=False)
    d = float(np.hypot(g[0], g[1]))
    if d < 1e-3:
        raise Wrong(f"your gait hardly moves the swimmer ({d:.4f} per cycle): all joints in phase (a "
                    "standing wave) or a gait that retraces its path gives no net motion. Let each "
                    "joint lag behind its neighbour.")
    if d < DISTANCE_MIN:
        raise Wrong(f"it moves the swimmer {d:.3f} per cycle; at least {DISTANCE_MIN} is asked for. "
                    "Use larger joint angles (up to the limit) or a different lag between joints.")
    return f"Correct: it moves the swimmer {d:.3f} per cycle (turning {g[2]:+.3f} rad)."


def _wave(amplitude: float, lag: float) -> gait_samples.LazyGait:
    """travelling_wave(3, amplitude, lag), built only when called."""
    def make() -> Callable[[npt.ArrayLike], FloatArray]:
        from gm_core.geometry import travelling_wave

        return travelling_wave(JOINTS, amplitude, lag, period=1.0)

    return gait_samples.LazyGait(make, f"travelling_wave(3, {amplitude}, {lag}, period=1)")


provide(
    ex5_1,
    a=JudgeKey(
        judge=_judge_51a,
        solution_text="For example travelling_wave(3, 1.2, 1.0): about 0.38 per cycle.",
        reference=_wave(1.2, 1.0),
        wrong=[_wave(1.2, 0.0), _wave(0.6, 1.0), _wave(1.5, 1.0), _wave(1.2, 2.8),
               lambda t: np.stack([np.sin(2 * np.pi * t)] * 2, -1)]),
    b=ChoiceKey(
        correct="a",
        feedback={"a": "Correct: a standing wave moves all joints in proportion, a line through shape "
                       "space traced back and forth; only a loop that encloses curvature moves the body.",
                  "b": "Net displacement does not depend on the pace of a gait (the reparametrization "
                       "argument of section 3.1).",
                  "c": "The standing wave uses the same joints.",
                  "d": "Drag is what the swimmer pushes against in both cases; what differs is the loop."},
        solution_text="a."),
)

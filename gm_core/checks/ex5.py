"""Checkers of exercise 5.1 (book/11, many links; beyond the draft): design a four-link swimmer's gait.

The swimmer is :func:`gm_core.geometry.chain_swimmer` (4): four equal links of total length 3,
drag ratio 2, body frame at the centre of mass with the mean orientation. As in every chapter,
the probe only turns the student's answer into plain data (the gait sampled at equal time
steps); the reference (gm_core.systems.motion.net_displacement) and the judging run in the checking
process. Independent routes are in tests/test_checks_many_links.py.
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
from gm_core.checks.parts import CustomPart, first_value
from gm_core.checks.sandbox import ProbeOutcome, Wrong

if TYPE_CHECKING:
    from gm_core.systems.link_chain import LinkChain
    from gm_core.validation import FloatArray

__all__ = ["ex5_1", "swimmer_5_1", "DISTANCE_MIN", "ANGLE_MAX"]

#: Net translation per cycle asked for, and the largest joint angle allowed (the links must not cross).
DISTANCE_MIN, ANGLE_MAX = 0.3, 1.2
_JOINTS = 3


@functools.lru_cache(maxsize=1)
def swimmer_5_1() -> LinkChain:
    """The four-link swimmer of exercise 5.1: chain_swimmer(4)."""
    from gm_core.geometry import chain_swimmer

    return chain_swimmer(4)


def _sample_gait(answer: Any) -> FloatArray:
    """Student side of 5.1(a): the gait sampled over one period (:mod:`gm_core.checks.gait_samples`)."""
    return gait_samples.sample(answer, _JOINTS, "travelling_wave(3, ...)")


def _judge_51a(outcomes: list[ProbeOutcome]) -> str:
    from gm_core.systems.gaits import Gait
    from gm_core.systems.motion import net_displacement

    r = gait_samples.grid(first_value(outcomes, "your gait", "the times of one period"), _JOINTS,
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


class _Wave:
    """travelling_wave(3, amplitude, lag), built only when called (keeps this module's import light)."""

    def __init__(self, amplitude: float, lag: float) -> None:
        self.amplitude, self.lag = amplitude, lag

    def __call__(self, t: npt.ArrayLike) -> FloatArray:
        from gm_core.geometry import travelling_wave

        g = travelling_wave(_JOINTS, self.amplitude, self.lag, period=1.0)
        return g(t)

    @override
    def __repr__(self) -> str:
        return f"travelling_wave(3, {self.amplitude}, {self.lag}, period=1)"


ex5_1 = Exercise("5.1", "Design a four-link swimmer's gait", [
    CustomPart(
        "a", f"A gait of the four-link low-Re swimmer that moves it at least {DISTANCE_MIN} per cycle, "
             f"every joint within +-{ANGLE_MAX} rad",
        lambda: [_sample_gait], _judge_51a,
        hints=["Three joints, one wave: try travelling_wave(3, amplitude, lag) from gm_core.geometry.",
               "A lag of 0 is a standing wave and goes nowhere; a lag near pi neither. Scan lags "
               "between 0.3 and 2 rad.",
               "The distance grows with the amplitude: use the largest allowed, 1.2 rad, and pick "
               "the lag that moves furthest (about 1 rad)."],
        solution_text="For example travelling_wave(3, 1.2, 1.0): about 0.38 per cycle.",
        reference=_Wave(1.2, 1.0),
        wrong=[_Wave(1.2, 0.0), _Wave(0.6, 1.0), _Wave(1.5, 1.0), _Wave(1.2, 2.8),
               lambda t: np.stack([np.sin(2 * np.pi * t)] * 2, -1)],
        kind="gait"),
    ChoicePart(
        "b", "Why does a wave that travels along the body move the swimmer, when a standing wave does not?",
        {"a": "a standing wave retraces the same line in shape space, which encloses no area",
         "b": "a standing wave is too slow: its joints never move fast enough",
         "c": "the travelling wave uses more joints",
         "d": "drag is larger on a travelling wave, so it pushes harder"},
        "a",
        feedback={"a": "Correct: a standing wave moves all joints in proportion, a line through shape "
                       "space traced back and forth; only a loop that encloses curvature moves the body.",
                  "b": "Net displacement does not depend on the pace of a gait (the reparametrization "
                       "argument of section 3.1).",
                  "c": "The standing wave uses the same joints.",
                  "d": "Drag is what the swimmer pushes against in both cases; what differs is the loop."},
        hints=["Draw both gaits in shape space: what does each trace?"],
        solution_text="a."),
])

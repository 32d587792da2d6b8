"""Checkers of exercise 5.1 (book/11, many links; beyond the draft): design a four-link swimmer's gait.

The swimmer is :func:`gm_core.geometry.chain_swimmer` (4): four equal links of total length 3,
drag ratio 2, body frame at the centre of mass with the mean orientation. As in every chapter,
the probe only turns the student's answer into plain data (the gait sampled at equal time
steps); the reference (gm_core.systems.motion.net_displacement) and the judging run in the checking
process. What a right answer is lives in :mod:`gm_core.checks.keys.ex5`. Independent routes are in
tests/test_checks_many_links.py.
"""
from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Any

from gm_core.checks import gait_samples
from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import Exercise
from gm_core.checks.parts import CustomPart

if TYPE_CHECKING:
    from gm_core.systems.link_chain import LinkChain
    from gm_core.validation import FloatArray

__all__ = ["ex5_1", "swimmer_5_1", "DISTANCE_MIN", "ANGLE_MAX", "JOINTS"]

#: Net translation per cycle asked for, and the largest joint angle allowed (the links must not cross).
DISTANCE_MIN, ANGLE_MAX = 0.3, 1.2
JOINTS = 3


@functools.lru_cache(maxsize=1)
def swimmer_5_1() -> LinkChain:
    """The four-link swimmer of exercise 5.1: chain_swimmer(4)."""
    from gm_core.geometry import chain_swimmer

    return chain_swimmer(4)


def _sample_gait(answer: Any) -> FloatArray:
    """Student side of 5.1(a): the gait sampled over one period (:mod:`gm_core.checks.gait_samples`)."""
    return gait_samples.sample(answer, JOINTS, "travelling_wave(3, ...)")


ex5_1 = Exercise("5.1", "Design a four-link swimmer's gait", [
    CustomPart(
        "a", f"A gait of the four-link low-Re swimmer that moves it at least {DISTANCE_MIN} per cycle, "
             f"every joint within +-{ANGLE_MAX} rad",
        lambda: [_sample_gait],
        hints=["Three joints, one wave: try travelling_wave(3, amplitude, lag) from gm_core.geometry.",
               "A lag of 0 is a standing wave and goes nowhere; a lag near pi neither. Scan lags "
               "between 0.3 and 2 rad.",
               "The distance grows with the amplitude: use the largest allowed, 1.2 rad, and pick "
               "the lag that moves furthest (about 1 rad)."],
        kind="gait"),
    ChoicePart(
        "b", "Why does a wave that travels along the body move the swimmer, when a standing wave does not?",
        {"a": "a standing wave retraces the same line in shape space, which encloses no area",
         "b": "a standing wave is too slow: its joints never move fast enough",
         "c": "the travelling wave uses more joints",
         "d": "drag is larger on a travelling wave, so it pushes harder"},
        hints=["Draw both gaits in shape space: what does each trace?"]),
])

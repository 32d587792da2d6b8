"""Exercise 5.1 (book/11, beyond the draft): the right answer, plausible wrong ones, adversarial and
untouched answers, and the reference against an independent route (the sampled trajectory)."""
import sys
import time

import numpy as np

from gm_core import checks
from gm_core.checks import ex5 as ml
from gm_core.checks.store import FAILED, PASSED, UNATTEMPTED
from gm_core.geometry import chain_swimmer, travelling_wave
from gm_core.systems.motion import trajectory


def test_reference_moves_far_enough_by_an_independent_route():
    """The sampled world trajectory (fixed steps, a different route from net_displacement's
    adaptive one) of the reference wave gives the same distance, above the threshold."""
    gait = travelling_wave(3, 1.2, 1.0)
    tr = trajectory(chain_swimmer(4), gait, n_frames=401)
    d = float(np.hypot(*tr.g[-1][:2]))
    assert d > ml.DISTANCE_MIN
    assert ml.ex5_1.a.check(gait, quiet=True).status == PASSED
    assert f"{d:.3f}" in ml.ex5_1.a.check(gait, quiet=True).message


def test_plausible_wrong_gaits_are_told_what_is_wrong():
    part = ml.ex5_1.a
    cases = [
        (travelling_wave(3, 1.2, 0.0), "standing wave"),       # all joints in phase
        (travelling_wave(3, 0.6, 1.0), "at least 0.3"),        # too small
        (travelling_wave(3, 1.5, 1.0), "at most 1.2 rad"),     # over the exercise's limit
        (travelling_wave(3, 1.2, 2.9), "at least 0.3"),        # lag near pi: nearly a standing wave
        (travelling_wave(2, 1.2, 1.0), "three joints"),        # the three-link swimmer's gait
        (lambda t: np.stack([t, t, t], -1), "does not close"),
    ]
    for answer, words in cases:
        v = part.check(answer, quiet=True)
        assert v.status == FAILED and words in v.message, (words, v.message)
    pts = travelling_wave(3, 1.2, 1.0)(np.linspace(0, 2 * np.pi, 64, endpoint=False))
    assert "transpose" in part.check(pts.T, quiet=True).message
    assert part.check(pts, quiet=True).passed and part.check(pts.tolist(), quiet=True).passed
    assert part.check(travelling_wave(3, 1.2, -1.0), quiet=True).passed     # the wave the other way swims back
    assert ml.ex5_1.b.check("a", quiet=True).passed
    for letter in "bcd":
        assert ml.ex5_1.b.check(letter, quiet=True).status == FAILED


def test_untouched_and_junk_answers():
    part = ml.ex5_1.a
    assert part.check(None, quiet=True).status == UNATTEMPTED
    for junk in ("wave", 42, True, {"a": 1}, np.full((10, 3), np.nan), lambda t: np.full(np.shape(t) + (3,), np.inf)):
        v = part.check(junk, quiet=True)
        assert v.status == FAILED and v.message, junk


def test_adversarial_answers_give_a_verdict_quickly_and_cannot_change_the_judge():
    def hang(t):
        while True:
            pass

    class Hostile:
        def __call__(self, t):
            sys.exit(3)

    def cheat(t):
        # tries to make the judge's reference move further; the probe runs in a sandbox
        import gm_core.systems.motion as lo

        lo.net_displacement = lambda *a, **k: np.array([9.0, 0.0, 0.0])
        return travelling_wave(3, 0.6, 1.0, period=1.0)(t)

    checks.set_time_limit(1.0)
    try:
        start = time.monotonic()
        v = ml.ex5_1.a.check(hang, quiet=True)
        assert v.status == FAILED and "longer than" in v.message
        assert time.monotonic() - start < 10
        assert ml.ex5_1.a.check(Hostile(), quiet=True).status == FAILED
    finally:
        checks.set_time_limit(5.0)
    v = ml.ex5_1.a.check(cheat, quiet=True)
    assert v.status == FAILED and "at least 0.3" in v.message
    assert ml.ex5_1.a.check(travelling_wave(3, 1.2, 1.0), quiet=True).status == PASSED


def test_a_negative_lag_swims_the_same_distance_the_other_way():
    """The check-yourself answer of solutions/ex5_1: the wave with lag -lag is the loop run
    backwards (g -> g^-1) and mirrored through the straight shape (conjugation by the reflection
    (x, y, theta) -> (x, -y, -theta)); g(T) has no rotation, so x changes sign and y does not.
    Checked on the sampled trajectory, a route apart from net_displacement's."""
    for lag in (0.5, 1.0, 1.6):
        forward = trajectory(chain_swimmer(4), travelling_wave(3, 1.2, lag), n_frames=401).g[-1]
        back = trajectory(chain_swimmer(4), travelling_wave(3, 1.2, -lag), n_frames=401).g[-1]
        assert abs(forward[2]) < 1e-9 and abs(back[2]) < 1e-9, (lag, forward, back)
        assert abs(forward[0]) > 0.1
        assert np.allclose(back[:2], [-forward[0], forward[1]], rtol=1e-6, atol=1e-9), (lag, forward, back)

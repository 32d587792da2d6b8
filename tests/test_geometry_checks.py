"""The checkers of exercises 4.1 and 4.2 (gm_core.checks.ex4), registered with the checking engine.

The registry-driven tests (test_checks*.py, test_grade.py, test_exercises.py) already run the
reference, the plausible wrong answers, junk and the starter through every part; here: the
verdicts specific to these parts, adversarial answers, and independent routes for the references.
"""
import sys
import time

import numpy as np
import pytest

from gm_core import checks
from gm_core.checks import ex4 as curv
from gm_core.checks.exercise import progress
from gm_core.checks.store import FAILED, PASSED, UNATTEMPTED
from gm_core.geometry import constraint_curvature, drift_and_turn, stokes_estimate
from gm_core.systems.gaits import circle_gait
from gm_core.systems.motion import net_displacement

pytestmark = pytest.mark.usefixtures("clean")


def test_registered_with_the_engine():
    assert checks.ex4_1 is curv.ex4_1 and checks.ex4_2 is curv.ex4_2
    assert {"4.1", "4.2"} <= set(checks.exercise_ids()) and {"4.1", "4.2"} <= set(progress())
    assert [p.kind for p in curv.ex4_1.parts.values()] == ["choice", "number", "choice"]


@pytest.mark.parametrize("part", [curv.ex4_1.a, curv.ex4_1.c, curv.ex4_2.b])
def test_choice_parts_have_feedback_for_every_option(part):
    assert part.check(sorted(part.key.correct)[0], quiet=True).status == PASSED
    for k in part.options:
        if k not in part.key.correct:
            v = part.check(k, quiet=True)
            assert v.status == FAILED and v.message == part.key.feedback[k]
    assert part.check("z", quiet=True).status == UNATTEMPTED       # names no option: not recorded


def test_area_sum_reference_by_an_independent_quadrature():
    """Polar midpoint quadrature of the x curvature over the unit disc (not the library's route)."""
    nr, nt = 200, 256
    r = (np.arange(nr) + 0.5) / nr
    t = (np.arange(nt) + 0.5) * 2 * np.pi / nt
    R, T = np.meshgrid(r, t, indexing="ij")
    P = np.stack([R * np.cos(T), R * np.sin(T)], -1)
    integral = (constraint_curvature(curv.swimmer_4_1(), P)[..., 0] * R).sum() * (1 / nr) * (2 * np.pi / nt)
    assert integral == pytest.approx(stokes_estimate(curv.swimmer_4_1(), circle_gait(1.0))[0], rel=1e-3)
    assert curv.ex4_1.b.check(integral, quiet=True).status == PASSED


@pytest.mark.parametrize("h", [0.1, 0.02])
def test_area_sum_of_a_student_grid_passes(h):
    """The exercise's own recipe (midpoint cells inside the disc) passes with cells of 0.1 or smaller."""
    a = np.arange(-1 + h / 2, 1, h)
    P = np.stack(np.meshgrid(a, a), -1)
    inside = (P ** 2).sum(-1) <= 1.0
    answer = constraint_curvature(curv.swimmer_4_1(), P[inside])[:, 0].sum() * h * h
    assert curv.ex4_1.b.check(answer, quiet=True).passed


def test_exercise_4_1_numbers_in_the_key():
    """The numbers quoted by 4.1's feedback, in both frames (ring = Stokes(C) - Stokes(A))."""
    A, C = circle_gait(1.0), circle_gait(2.2)
    mp, mid = curv.swimmer_4_1(), curv.swimmer()
    sA, sC, eA, eC = (f(mp, g)[0] for f, g in ((stokes_estimate, A), (stokes_estimate, C),
                                               (net_displacement, A), (net_displacement, C)))
    assert round(sC - sA, 3) == 0.037 and round(sA, 3) == -0.155
    assert round(sC, 3) == -0.118 and round(eC, 3) == -0.124 and abs(sC - eC) < 0.01
    assert round(stokes_estimate(mid, C)[0] - stokes_estimate(mid, A)[0], 3) == -0.197
    assert eA < eC < 0                       # both backward; A further: the key of (a)
    assert np.hypot(*net_displacement(mp, A)[:2]) > np.hypot(*net_displacement(mp, C)[:2])
    assert curv.ex4_1.a.key.correct == {"c"} and curv.ex4_1.c.key.correct == {"d"}


def test_area_sum_verdicts():
    ref = stokes_estimate(curv.swimmer_4_1(), circle_gait(1.0))[0]
    exact = net_displacement(curv.swimmer_4_1(), circle_gait(1.0))[0]
    part = curv.ex4_1.b
    assert part.check(ref * 1.004, quiet=True).passed and not part.check(ref * 1.01, quiet=True).passed
    assert part.check(np.float32(ref), quiet=True).passed and part.check(np.array([ref]), quiet=True).passed
    assert "sign" in part.check(-ref, quiet=True).message
    assert "exact net displacement" in part.check(exact, quiet=True).message
    assert "zero" in part.check(0.0, quiet=True).message
    assert "cell" in part.check(ref / 0.01 ** 2, quiet=True).message           # forgot the cell area
    for bad in (ref * 1.1, "big", np.array([ref, 0.0, 0.0]), ref + 0.1j, True, float("nan")):
        assert part.check(bad, quiet=True).status == FAILED, bad
    assert part.check(None, quiet=True).status == UNATTEMPTED


def test_turn_in_place_verdicts():
    part = curv.ex4_2.a
    assert part.check(circle_gait(0.5, (1.5, 1.5)), quiet=True).passed
    assert "centre of mass moves" in part.check(circle_gait(1.0, (1.5, 1.5)), quiet=True).message
    assert "turns by only" in part.check(circle_gait(0.5), quiet=True).message
    assert "does not close" in part.check(lambda t: np.stack([t, t], -1), quiet=True).message
    assert "transpose" in part.check(circle_gait(0.5, (1.5, 1.5))(np.arange(64) / 64).T, quiet=True).message
    assert not part.check(42, quiet=True).passed
    # samples, scalar-only callables and gaits of another period are accepted too
    t = np.linspace(0, 1, 64, endpoint=False)
    pts = np.stack([1.5 + 0.5 * np.cos(2 * np.pi * t), 1.5 + 0.5 * np.sin(2 * np.pi * t)], -1)
    assert part.check(pts, quiet=True).passed and part.check(pts.tolist(), quiet=True).passed
    assert part.check(lambda s: [1.5 + 0.5 * np.cos(2 * np.pi * s), 1.5 + 0.5 * np.sin(2 * np.pi * s)],
                      quiet=True).passed
    assert part.check(circle_gait(0.5, (1.5, 1.5), period=3.0), quiet=True).passed


def test_adversarial_answers_give_a_verdict_quickly():
    def hang(t):
        while True:
            pass

    class Hostile:
        def __float__(self):
            raise SystemExit(3)

        def __array__(self, *a, **k):
            raise GeneratorExit

        def __call__(self, t):
            sys.exit(3)

    checks.set_time_limit(1.0)
    try:
        start = time.monotonic()
        v = curv.ex4_2.a.check(hang, quiet=True)
        assert v.status == FAILED and "longer than" in v.message
        assert time.monotonic() - start < 10
        for part in (curv.ex4_1.b, curv.ex4_2.a):
            v = part.check(Hostile(), quiet=True)
            assert v.status == FAILED and v.message, v
            assert part.check(lambda *a: sys.exit(3), quiet=True).status == FAILED
    finally:
        checks.set_time_limit(5.0)


def test_a_tampered_gait_cannot_forge_the_judge():
    """The probe only samples the gait; drift and turn are computed in the checking process."""
    import gm_core.systems.motion as loc

    def vandal(t):
        loc.net_displacement = lambda *a, **k: np.array([0.0, 0.0, 1.0])   # in the child only
        return circle_gait(0.5)(t)
    assert curv.ex4_2.a.check(vandal, quiet=True).status == FAILED
    assert loc.net_displacement is net_displacement


def test_drift_is_frame_independent():
    """Independent route: the centre of mass computed from the link poses moved by g(T)."""
    from gm_core import SE2
    from gm_core.systems.motion import trajectory

    s = curv.swimmer()
    g = circle_gait(0.5, (1.5, 1.5))
    tr = trajectory(s, g, n_frames=3)
    com = [np.mean(SE2.compose(tr.g[i][None], s.link_poses(tr.r[i]))[:, :2], axis=0) for i in (0, 2)]
    assert drift_and_turn(s, g)[1] == pytest.approx(np.linalg.norm(com[1] - com[0]), abs=1e-9)


def test_sampled_gait_gives_the_same_verdict_numbers():
    g = circle_gait(0.5, (1.5, 1.5))
    from gm_core.systems.gaits import Gait
    sampled = Gait.from_samples(g(np.arange(256) / 256))
    s = curv.swimmer()
    assert np.allclose(drift_and_turn(s, sampled), drift_and_turn(s, g), atol=1e-6)


def test_hint_and_solution_text():
    assert "theta map" in curv.ex4_2.a.hint_text(1)
    assert "solutions/ex4_2.ipynb" in curv.ex4_2.a.solution_text_full()

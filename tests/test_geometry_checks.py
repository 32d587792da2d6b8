"""The checkers of exercises 4.1 and 4.2 (gm_core.checks.ch4): reference passes, wrong fails, starter waits."""
import numpy as np
import pytest

from gm_core.checks import ch4
from gm_core.geometry import stokes_estimate
from gm_core.locomotion import circle_gait


@pytest.mark.parametrize("part", [ch4.ex4_1.a, ch4.ex4_1.c, ch4.ex4_2.b])
def test_choice_parts(part):
    assert part.check(part.reference, quiet=True).status == "passed"
    for w in part.wrong:
        assert part.check(w, quiet=True).status == "failed"
    assert part.check(None, quiet=True).status == "unattempted"
    assert part.check("z", quiet=True).status == "failed"


def test_area_sum_part():
    ref = stokes_estimate(ch4.swimmer(), circle_gait(1.0))[0]
    part = ch4.ex4_1.b
    assert part.check(ref * 1.01, quiet=True).passed
    assert not part.check(-ref, quiet=True).passed          # reversed orientation
    assert not part.check(ref * 1.1, quiet=True).passed
    assert not part.check("big", quiet=True).passed
    assert part.check(None, quiet=True).status == "unattempted"


def test_turn_in_place_part():
    part = ch4.ex4_2.a
    assert part.check(part.reference(), quiet=True).passed
    assert not part.check(circle_gait(1.0, (1.5, 1.5)), quiet=True).passed  # turns but drifts
    assert not part.check(circle_gait(0.5), quiet=True).passed              # does not turn
    assert not part.check(42, quiet=True).passed
    turn, drift = ch4.drift_and_turn(part.reference())
    assert abs(turn) >= 0.2 and drift <= 0.02
    # samples and callables are accepted too
    t = np.linspace(0, 1, 64, endpoint=False)
    pts = np.stack([1.5 + 0.5 * np.cos(2 * np.pi * t), 1.5 + 0.5 * np.sin(2 * np.pi * t)], -1)
    assert part.check(pts, quiet=True).passed


def test_drift_is_frame_independent():
    """Independent route: the centre of mass computed from the link poses moved by g(T) (a pure check of the docstring)."""
    from gm_core import SE2
    from gm_core.locomotion import trajectory

    s = ch4.swimmer()
    g = circle_gait(0.5, (1.5, 1.5))
    tr = trajectory(s, g, n_frames=3)
    com = [np.mean(SE2.compose(tr.g[i][None], s.link_poses(tr.r[i]))[:, :2], axis=0) for i in (0, 2)]
    assert ch4.drift_and_turn(g)[1] == pytest.approx(np.linalg.norm(com[1] - com[0]), abs=1e-9)


def test_hint_and_solution_text():
    assert "theta map" in ch4.ex4_2.a.hint(1)
    assert "solutions/ex4_2.ipynb" in ch4.ex4_2.a.solution()

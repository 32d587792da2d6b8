"""SE(2) exp and log against a 50-digit mpmath reference, at angles where naive formulas fail."""
import mpmath as mp
import numpy as np
import pytest

from gm_core import SE2

mp.mp.dps = 50

ANGLES = [0.0, 1e-300, 1e-12, -1e-12, 1e-8, 1e-6, -1e-6, 0.1, 1.0, -2.5, np.pi / 2,
          np.pi - 1e-9, -(np.pi - 1e-9), np.pi - 1e-15, 3.0]


def exp_reference(vx, vy, w):
    vx, vy, w = mp.mpf(vx), mp.mpf(vy), mp.mpf(w)
    if w == 0:
        return vx, vy, w
    a = mp.sin(w) / w
    b = (1 - mp.cos(w)) / w
    return a * vx - b * vy, b * vx + a * vy, w


def rel_err(got, ref):
    got = [mp.mpf(float(x)) for x in got]
    num = mp.sqrt(sum((g - r) ** 2 for g, r in zip(got, ref)))
    den = mp.sqrt(sum(r ** 2 for r in ref))
    return float(num / den)


@pytest.mark.parametrize("w", ANGLES)
@pytest.mark.parametrize("v", [(1.0, 0.0), (0.3, -2.0), (-1e-3, 5.0)])
def test_exp_relative_accuracy(w, v):
    got = SE2.exp([v[0], v[1], w])
    assert rel_err(got, exp_reference(v[0], v[1], w)) < 4e-16


@pytest.mark.parametrize("w", ANGLES)
@pytest.mark.parametrize("v", [(1.0, 0.0), (0.3, -2.0), (-1e-3, 5.0)])
def test_log_relative_accuracy(w, v):
    # Build g exactly (in 50 digits) from xi, round it to doubles, then compare log(g) with the
    # 50-digit log of that rounded g.
    x, y, t = (float(c) for c in exp_reference(v[0], v[1], w))
    got = SE2.log([x, y, t])
    t_mp = mp.mpf(t)
    h = t_mp / 2
    k = mp.sin(h) / h if t_mp != 0 else mp.mpf(1)
    c, s = mp.cos(h), mp.sin(h)
    ref = ((c * x + s * y) / k, (c * y - s * x) / k, t_mp)
    assert rel_err(got, ref) < 4e-16


def test_log_wraps_theta_to_half_open_interval():
    for t, expected in [(np.pi, np.pi), (-np.pi, np.pi), (3 * np.pi, np.pi), (2 * np.pi, 0.0),
                        (-3 * np.pi / 2, np.pi / 2), (7.0, 7.0 - 2 * np.pi)]:
        assert SE2.log([0.0, 0.0, t])[2] == pytest.approx(expected, abs=1e-15)
    assert SE2.log([0.0, 0.0, 0.5])[2] == 0.5  # exact when already in range


def test_exp_log_roundtrip_near_pi():
    for w in [np.pi - 1e-9, -(np.pi - 1e-9), np.pi]:
        xi = np.array([0.7, -0.2, w])
        back = SE2.log(SE2.exp(xi))
        np.testing.assert_allclose(back[:2], xi[:2], rtol=1e-14)

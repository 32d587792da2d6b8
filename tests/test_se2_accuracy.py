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


# ------------------------------------------------------------------ large angles (issue #11)
BIG = [1e3, -1e3, 12345.678, 1e8, -1e8, 2.0**40 * np.pi, 1e15, -1e15, 1e22, 1e300, -1e300, 1.7e308,
       3 * np.pi, -3 * np.pi, 7.0, np.nextafter(np.pi, 4.0)]


def reduced(theta):
    """theta modulo 2 pi in (-pi, pi], computed exactly enough in mpmath for any double."""
    with mp.workdps(340 + int(mp.log10(abs(mp.mpf(theta)) + 1))):
        t = mp.mpf(theta)
        r = t - 2 * mp.pi * mp.floor(t / (2 * mp.pi) + mp.mpf(1) / 2)
        if r <= -mp.pi:
            r += 2 * mp.pi
        return +r


def ulps_off(got, ref):
    """|got - ref| modulo 2 pi (the doubles nearest -pi and pi are one angle), in ulps of ref."""
    d = mp.mpf(float(got)) - ref
    d -= 2 * mp.pi * mp.nint(d / (2 * mp.pi))
    return float(abs(d) / (mp.mpf(np.spacing(abs(float(ref)))) + mp.mpf(1e-320)))


@pytest.mark.parametrize("theta", BIG)
def test_wrap_angle_is_accurate_to_rounding_for_any_finite_angle(theta):
    from gm_core import wrap_angle
    ref = reduced(theta)
    got = wrap_angle(theta)
    assert -np.pi < got <= np.pi
    assert ulps_off(got, ref) <= 1.0


def test_wrap_angle_keeps_values_in_range_exactly_and_maps_minus_pi_to_pi():
    from gm_core import wrap_angle
    x = np.array([0.0, -0.0, 1e-300, -3.0, np.pi, np.nextafter(-np.pi, 0.0)])
    np.testing.assert_array_equal(wrap_angle(x), x)
    assert wrap_angle(-np.pi) == np.pi
    assert wrap_angle([[7.0]]).shape == (1, 1)


@pytest.mark.parametrize("theta", [1e3, 1e8, 1e15, -1e15, 1e300])
@pytest.mark.parametrize("group", ["SE2", "SO2", "R2xS1", "S1"])
def test_log_of_large_angles_is_accurate_to_rounding(theta, group):
    from gm_core import ALL_GROUPS
    G = ALL_GROUPS[group]
    ref_t = reduced(theta)
    if group in ("SO2", "S1"):
        got = G.log([theta])
        assert ulps_off(got[0], ref_t) <= 1.0
        return
    x, y = 0.7, -1.3
    got = G.log([x, y, theta])
    assert ulps_off(got[2], ref_t) <= 1.0
    if group == "R2xS1":
        assert got[0] == x and got[1] == y
        return
    with mp.workdps(50):
        h = ref_t / 2
        k = mp.sin(h) / h
        c, s = mp.cos(h), mp.sin(h)
        ref = ((c * x + s * y) / k, (c * y - s * x) / k, ref_t)
        assert rel_err(got, ref) < 4e-16

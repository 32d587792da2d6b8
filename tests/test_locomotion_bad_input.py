"""Regression tests for issue 11 in gm_core.systems.motion, gaits, chains and systems: every bad input
refused by name, every accuracy promise kept (or a warning with the estimate)."""
import subprocess
import sys
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_locomotion import reference_displacement  # the solve_ivp route, written once

from gm_core import SE2, SingularShapeError, chains
from gm_core.chains.holonomic import accessible_circle
from gm_core.chains.three_link import three_link_jacobians
from gm_core.geometry.curvature import connection_curl
from gm_core.systems import FloatingSnake, HighReSwimmer, KinematicSnake, LowReSwimmer
from gm_core.systems.connection import metric_from_jacobians, pfaffian_determinant
from gm_core.systems.gaits import Gait, GaitWarning, circle_gait
from gm_core.systems.motion import (
    AccuracyWarning,
    body_velocity,
    check_gait,
    net_displacement,
    trajectory,
)

SNAKE = KinematicSnake()
SAFE = circle_gait(0.8, (0.4, -1.0))


def near_miss(gap):
    """Circle gait passing ``gap`` (in shape-space distance) from the snake's singular line a1 = a2."""
    c = np.array([0.5, -0.4])
    return circle_gait(abs(c[0] - c[1]) / np.sqrt(2) - gap, c)


# ------------------------------------------------------------------ accuracy promises
def test_near_singular_gait_meets_rtol():
    g = near_miss(1e-5)
    d = net_displacement(SNAKE, g)        # no warning: the adaptive steps meet rtol
    ref = reference_displacement(SNAKE, g, rtol=1e-13)
    scale = max(1.0, np.abs(ref).max())
    assert np.abs(d - ref).max() <= 1e-9 * scale, (d, ref)


@pytest.mark.slow
def test_very_near_singular_gait_meets_rtol_or_warns_with_estimate():
    g = near_miss(1e-7)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        d = net_displacement(SNAKE, g)
    ours = [x for x in w if issubclass(x.category, AccuracyWarning)]
    ref = net_displacement(SNAKE, g, steps=2 ** 18, check=False)    # uniform steps, error ~1e-10 here
    err = np.abs(d - ref).max() / max(1.0, np.abs(ref).max())
    if ours:
        msg = str(ours[0].message)
        assert "estimated relative error" in msg
        est = float(msg.split("estimated relative error ")[1].split(" ")[0])
        assert err <= 10 * est
    else:
        assert err <= 1e-9


def test_steps_and_rtol_are_validated():
    for bad, exc in [(0, ValueError), (-3, ValueError), (np.inf, TypeError), (2.5, TypeError), (True, TypeError),
                     ("10", TypeError), (2 ** 40, ValueError)]:
        with pytest.raises(exc, match="steps"):
            net_displacement(SNAKE, SAFE, steps=bad)
    for bad, exc in [(np.nan, ValueError), (0.0, ValueError), (-1e-8, ValueError), (1e-20, ValueError),
                     (2.0, ValueError), ("1e-8", TypeError), (None, TypeError)]:
        with pytest.raises(exc, match="rtol"):
            net_displacement(SNAKE, SAFE, rtol=bad)
    # a plain step count still works and agrees with the adaptive result
    np.testing.assert_allclose(net_displacement(SNAKE, SAFE, steps=4096), net_displacement(SNAKE, SAFE), atol=1e-9)


# ------------------------------------------------------------------ singular gaits
def spike_gait(width=1e-5, t0=0.3):
    """SAFE with a narrow radial spike that crosses the singular line and comes back."""
    c = np.array([0.4, -1.0])

    def r(t):
        t = np.asarray(t, float)
        base = SAFE(t)
        return base + 1.5 * np.exp(-((t - t0) / width) ** 2)[..., None] * (base - c) / 0.8
    return Gait(r, 1.0)


def test_narrow_spike_across_the_singular_line_is_found():
    g = spike_gait()
    assert SNAKE.singularity(g(np.array([0.3])))[0] * SNAKE.singularity(g(np.array([0.0])))[0] < 0
    with pytest.raises(SingularShapeError, match="crosses"):
        check_gait(SNAKE, g)
    with pytest.raises(SingularShapeError, match="singular"):
        net_displacement(SNAKE, g)
    with pytest.raises(SingularShapeError, match="singular"):
        trajectory(SNAKE, g, 11)


def test_integrator_nodes_catch_a_crossing_the_samples_miss():
    # with deliberately sparse samples check_gait misses the spike, but the integrator's nodes do not
    g = spike_gait(width=2e-3)
    check_gait(SNAKE, g, samples=16)
    with pytest.raises(SingularShapeError, match="singular"):
        net_displacement(SNAKE, g, steps=8192)


def test_check_gait_validates_its_arguments():
    with pytest.raises(TypeError, match="system"):
        check_gait("snake", SAFE)
    with pytest.raises(TypeError, match="samples"):
        check_gait(SNAKE, SAFE, samples=100.5)
    with pytest.raises(ValueError, match="samples"):
        check_gait(SNAKE, SAFE, samples=0)


# ------------------------------------------------------------------ closure
def test_open_gaits_are_refused_where_closure_matters():
    open_gait = Gait(lambda t: SAFE(t) + 0.1 * np.asarray(t, float)[..., None], 1.0)
    assert not open_gait.is_closed() and SAFE.is_closed()
    np.testing.assert_allclose(open_gait.closure_gap, [0.1, 0.1], atol=1e-14)
    with pytest.raises(ValueError, match=r"not closed: r\(T\) - r\(0\) = \(0.1, 0.1\)"):
        net_displacement(SNAKE, open_gait)
    with pytest.raises(ValueError, match="not closed"):
        trajectory(SNAKE, open_gait, 11, cycles=2)
    # an open shape path is still fine to integrate once, as documented
    d = net_displacement(SNAKE, open_gait, check=False)
    tr = trajectory(SNAKE, open_gait, 11)
    assert SE2.isclose(tr.g[-1], d, atol=1e-8)


def test_open_samples_warn_naming_the_gap():
    pts = SAFE(np.linspace(0.0, 0.5, 20))          # half a circle
    with pytest.warns(GaitWarning, match="closing segment"):
        Gait.from_samples(pts)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Gait.from_samples(SAFE(np.linspace(0.0, 1.0, 40)[:-1]))   # closed: silent


# ------------------------------------------------------------------ parameters
def test_integer_parameters():
    with pytest.raises(TypeError, match="n must be an integer"):
        accessible_circle(20.7)
    with pytest.raises(TypeError, match="n must be an integer"):
        accessible_circle(np.inf)
    with pytest.raises(ValueError, match="n must be"):
        accessible_circle(1)
    assert accessible_circle(20.0).shape == (20, 3)
    with pytest.raises(ValueError, match="substeps"):
        trajectory(SNAKE, SAFE, 11, substeps=0)
    with pytest.raises(TypeError, match="n_frames"):
        trajectory(SNAKE, SAFE, 10.5)
    with pytest.raises(ValueError, match="cycles"):
        trajectory(SNAKE, SAFE, 11, cycles=0)
    with pytest.raises(ValueError, match="substeps"):
        trajectory(SNAKE, SAFE, 10 ** 6, substeps=10 ** 6)
    with pytest.raises(ValueError, match="rows"):
        metric_from_jacobians([np.zeros((3, 5))], [np.eye(3)], rows=9)


# ------------------------------------------------------------------ errors from inside
def test_errors_name_the_argument():
    np.testing.assert_allclose(SE2.bracket([1, 0, 1], [0, 1, 0]), SE2.vee(
        SE2.hat([1, 0, 1]) @ SE2.hat([0, 1, 0]) - SE2.hat([0, 1, 0]) @ SE2.hat([1, 0, 1])))
    for call in [lambda: body_velocity(None, [0, 0], [0, 0]), lambda: connection_curl("snake", [0, 0]),
                 lambda: net_displacement(object(), SAFE), lambda: trajectory(KinematicSnake, SAFE),
                 lambda: check_gait(None, SAFE)]:
        with pytest.raises(TypeError, match="system"):
            call()
    with pytest.raises(ValueError, match="r and r_dot"):
        body_velocity(SNAKE, np.zeros((3, 2)), np.zeros((4, 2)))
    with pytest.raises(TypeError, match="omega_xi"):
        pfaffian_determinant(None)
    with pytest.raises(ValueError, match="omega_xi"):
        pfaffian_determinant(np.zeros((3, 2)))
    with pytest.raises(TypeError, match="J"):
        chains.world_to_body_jacobian([0, 0, 0], None)
    with pytest.raises(ValueError, match="J must have shape"):
        chains.world_to_body_jacobian([0, 0, 0], np.zeros((2, 4)))
    with pytest.raises(ValueError, match="batch shapes"):
        chains.world_to_body_jacobian(np.zeros((4, 3)), np.zeros((5, 3, 2)))
    with pytest.raises(TypeError, match="jacobians"):
        metric_from_jacobians(None, None)
    with pytest.raises(TypeError, match="inertias"):
        metric_from_jacobians([np.zeros((3, 5))], np.eye(3))
    with pytest.raises(ValueError, match=r"jacobians\[0\]"):
        metric_from_jacobians([np.zeros((3, 5))], [np.eye(2)])
    with pytest.raises(ValueError, match=r"inertias\[1\]"):
        metric_from_jacobians([np.zeros((3, 5))] * 2, [np.eye(3), np.zeros((3, 2))])
    with pytest.raises(ValueError, match="h must be positive"):
        connection_curl(SNAKE, [0.1, 0.2], h=0.0)


# ------------------------------------------------------------------ extreme periods
@pytest.mark.parametrize("period", [1e-200, 1e-8, 1e8, 1e200])
def test_extreme_periods_give_the_same_displacement(period):
    s = LowReSwimmer()
    d1 = net_displacement(s, circle_gait(0.5))
    np.testing.assert_allclose(net_displacement(s, circle_gait(0.5, period=period)), d1, atol=1e-12)
    tr = trajectory(s, circle_gait(0.5, period=period), 5)
    np.testing.assert_allclose(tr.t[-1], period, rtol=1e-15)
    assert SE2.isclose(tr.g[-1], d1, atol=1e-9)
    np.testing.assert_allclose(net_displacement(SNAKE, circle_gait(0.8, (0.4, -1.0), period=period)),
                               net_displacement(SNAKE, SAFE), atol=1e-12)


# ------------------------------------------------------------------ drag_ratio = 1
def test_isotropic_drag_keeps_the_centroid_fixed_while_the_body_frame_moves():
    s = LowReSwimmer((1.0, 0.7, 1.3), drag_ratio=1.0)
    tr = trajectory(s, circle_gait(1.0, (0.3, -0.2)), 41)
    L = np.array(s.lengths)
    centres = SE2.compose(tr.g[:, None, :], s.link_poses(tr.r))[..., :2]   # world link centres
    centroid = np.einsum("i,tij->tj", L, centres) / L.sum()
    np.testing.assert_allclose(centroid, np.broadcast_to(centroid[0], centroid.shape), atol=1e-9)
    assert np.ptp(tr.g[:, 0]) > 0.05 and np.ptp(tr.g[:, 2]) > 0.05     # the middle link moves and turns
    # with anisotropic drag the centroid does move
    tr2 = trajectory(LowReSwimmer((1.0, 0.7, 1.3)), circle_gait(1.0, (0.3, -0.2)), 41)
    c2 = np.einsum("i,tij->tj", L, SE2.compose(tr2.g[:, None, :], s.link_poses(tr2.r))[..., :2]) / L.sum()
    assert np.ptp(c2, axis=0).max() > 1e-3


# ------------------------------------------------------------------ house plan
def test_systems_do_not_import_the_geometry_layer():
    code = ("import sys, gm_core.systems.motion as L; assert not hasattr(L, 'KinematicSnake'); "
            "assert not [m for m in sys.modules if m.startswith('gm_core.geometry')]")
    subprocess.run([sys.executable, "-c", code], check=True)


def test_no_hidden_state_in_systems():
    s = FloatingSnake(frame="com")
    r = np.array([0.4, -0.3])
    s.connection(r)
    assert s.frame == "com"
    for J, Jm in zip(s.middle_link_jacobians(r), three_link_jacobians(r, s.lengths)):
        np.testing.assert_allclose(J, Jm, atol=0)
    assert "connection" not in vars(HighReSwimmer)
    g = circle_gait(0.7, (0.1, 0.2))
    np.testing.assert_allclose(g.amplitude, [0.7, 0.7])
    np.testing.assert_allclose(g.center, [0.1, 0.2])


def test_constant_rate_path_is_a_cheaply_checked_open_path():
    from gm_core.systems import Ackerman
    from gm_core.systems.pacing import constant_rate_path
    p = constant_rate_path([0.0, 0.3], [1.0, 0.2], 2.0)
    np.testing.assert_allclose(p(np.array([0.0, 1.0, 2.0])), [[0, 0.3], [1, 0.5], [2, 0.7]], atol=1e-15)
    np.testing.assert_allclose(p.velocity(np.array([0.5, 1.5])), [[1, 0.2], [1, 0.2]])
    assert p.feature_time == 2.0 and not p.is_closed()
    # Ackerman: xi = (R a1', 0, (R/L) tan(a2) a1'), so theta(T) = sum of tan(a2(t)) a1' dt, exactly integrable
    tr = trajectory(Ackerman(), p, 5)
    theta = (np.log(np.cos(0.3)) - np.log(np.cos(0.7))) / 0.2
    np.testing.assert_allclose(tr.g[-1, 2], theta, rtol=1e-10)
    with pytest.raises(ValueError, match="r0 and r_dot"):
        constant_rate_path([0.0, 0.3], [1.0], 2.0)
    with pytest.raises(ValueError, match="duration"):
        constant_rate_path([0.0], [1.0], 0.0)


@settings(max_examples=8, deadline=None)
@given(st.floats(-1.0, 1.0), st.floats(0.3, 1.5), st.booleans(), st.floats(0.05, 0.999))
def test_random_circle_gaits_meet_the_promised_accuracy(along, across, side, fraction):
    """Circles beside the snake's singular line, some within 1e-3 of it: g(T) within rtol, no warning."""
    u, v = np.array([1.0, 1.0]) / np.sqrt(2), np.array([1.0, -1.0]) / np.sqrt(2)
    d = across if side else -across
    g = circle_gait(fraction * across, along * u + d * v)          # distance to the line: across (1 - fraction)
    with warnings.catch_warnings():
        warnings.simplefilter("error", AccuracyWarning)
        out = net_displacement(SNAKE, g)
    ref = reference_displacement(SNAKE, g, rtol=1e-13)
    assert np.abs(out - ref).max() <= 1e-9 * max(1.0, np.abs(ref).max()), (out, ref)

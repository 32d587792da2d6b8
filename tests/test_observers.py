"""gm_core.manifolds.observers: observers, the ICR and Ad as conjugation, each against an independent route
(matrix products, finite differences of g(t) h^-1, point velocities from first principles)."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import SE2
from gm_core.chains import relative_pose
from gm_core.manifolds.observers import conjugation, icr, observed_velocity, point_in_frame

angles = st.floats(-3.0, 3.0)
coords = st.floats(-3.0, 3.0)
se2 = st.tuples(coords, coords, angles).map(np.array)
xis = st.tuples(st.floats(-2, 2), st.floats(-2, 2), st.floats(-2, 2)).map(np.array)


@settings(max_examples=60, deadline=None)
@given(se2, xis)
def test_ad_is_conjugation(g, xi):
    """hat(Ad_g xi) = G hat(xi) G^-1 with G the homogeneous matrix (scipy-free matrix route)."""
    G = SE2.matrix(g)
    direct = G @ SE2.hat(xi) @ np.linalg.inv(G)
    assert np.allclose(SE2.hat(SE2.Ad(g) @ xi), direct, atol=1e-12)
    conj, hat_ad = conjugation(g, xi)
    assert np.allclose(conj, direct, atol=1e-12) and np.allclose(hat_ad, direct, atol=1e-12)


@settings(max_examples=40, deadline=None)
@given(se2, xis, se2)
def test_observed_velocity_is_the_derivative_of_the_relative_pose(g, xi, h):
    """Finite differences of (h^-1 g(t)) (h^-1 g)^-1 with g(t) = g exp(t xi): the spatial velocity
    seen from h."""
    eps = 1e-6
    Hinv = np.linalg.inv(SE2.matrix(h))
    M0inv = np.linalg.inv(Hinv @ SE2.matrix(g))
    Mp = Hinv @ SE2.matrix(SE2.compose(g, SE2.exp(eps * xi))) @ M0inv
    Mm = Hinv @ SE2.matrix(SE2.compose(g, SE2.exp(-eps * xi))) @ M0inv
    fd = SE2.vee((Mp - Mm) / (2 * eps))
    assert np.allclose(observed_velocity(g, xi, h), fd, atol=1e-6)
    # the observer at the identity sees the book's spatial velocity
    assert np.allclose(observed_velocity(g, xi), SE2.body_to_spatial(g, xi))


@settings(max_examples=60, deadline=None)
@given(xis.filter(lambda x: abs(x[2]) > 1e-3))
def test_icr_has_zero_velocity(xi):
    p, far = icr(xi)
    assert not far
    # velocity of the point p of the plane moving with xi, from first principles: v + w x p
    v = xi[:2] + xi[2] * np.array([-p[1], p[0]])
    assert np.allclose(v, 0.0, atol=1e-9 * (1 + np.abs(p).max()))


def test_icr_is_one_point_whoever_watches():
    g, xi = np.array([1.0, 0.6, 0.6]), np.array([0.8, 0.3, 0.6])
    world = SE2.act_on_points(g, icr(xi)[0])
    for h in (np.zeros(3), np.array([-1.5, -1.0, 0.4]), np.array([2.0, 1.0, -2.5])):
        p_h, far = icr(observed_velocity(g, xi, h))
        assert not far and np.allclose(SE2.act_on_points(h, p_h), world)
        assert np.allclose(point_in_frame(h, world), p_h)


def test_icr_at_infinity_is_flagged_not_inf():
    p, far = icr([1.0, 0.5, 0.0])
    assert far and np.all(np.isfinite(p))
    p, far = icr(np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 2.0]]))
    assert far.tolist() == [True, False] and np.allclose(p[1], [-0.5, 0.0])


def test_relative_pose_and_bad_input():
    g, h = np.array([1.0, 2.0, 0.5]), np.array([-1.0, 0.5, 1.0])
    assert np.allclose(SE2.matrix(relative_pose(g, h)), np.linalg.inv(SE2.matrix(h)) @ SE2.matrix(g))
    with pytest.raises(ValueError, match="xi"):
        icr([1.0, 2.0])
    with pytest.raises(TypeError, match="h"):
        observed_velocity(g, [1, 0, 0], "origin")

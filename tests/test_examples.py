"""The small formulas the pictures need, each against an independent route: the example fields
(gm_core.fields.FIELDS), rigid-body point velocities (gm_core.manifolds.observers), the binomial table
(gm_core.calculus) and the constant-rate drive (gm_core.systems.motion)."""
import math

import numpy as np
import pytest

from gm_core import SE2
from gm_core.calculus import binomial_table
from gm_core.fields import FIELDS
from gm_core.manifolds.observers import icr, point_velocities
from gm_core.systems.motion import drive
from gm_core.systems.pacing import constant_rate_path


def test_fields_are_the_book_examples():
    q = np.array([[0.5, -1.0], [2.0, 0.3]])
    x, y = q[:, 0], q[:, 1]
    assert np.allclose(FIELDS["saddle"](q), np.c_[x, -y])
    assert np.allclose(FIELDS["closed loops"](q), np.c_[-y, x])
    # the spiral sink shrinks |q| at rate 0.25 |q|; the rotation keeps it
    assert np.allclose(np.sum(q * FIELDS["spiral sink"](q), 1), -0.25 * np.sum(q * q, 1))
    assert np.allclose(np.sum(q * FIELDS["closed loops"](q), 1), 0.0)
    assert np.allclose(FIELDS["limit cycle (van der Pol)"](q)[:, 1], (1 - x * x) * y - x)


def test_point_velocities_by_finite_differences_of_the_moving_body():
    g = np.array([0.4, -0.3, 0.8])
    xi = np.array([0.7, 0.2, -0.5])
    g_dot = SE2.body_to_world(g, xi)
    body_pts = np.array([[0.3, 0.1], [-0.5, 0.4], [0.0, 0.0]])
    world = SE2.act_on_points(g, body_pts)
    h = 1e-6
    fd = (SE2.act_on_points(SE2.compose(g, SE2.exp(h * xi)), body_pts)
          - SE2.act_on_points(SE2.compose(g, SE2.exp(-h * xi)), body_pts)) / (2 * h)
    assert np.allclose(point_velocities(g, g_dot, world), fd, atol=1e-8)
    # the one point at rest is the instantaneous centre of rotation (written in world axes)
    c, far = icr(SE2.world_to_spatial(g, g_dot))
    assert not far and np.allclose(point_velocities(g, g_dot, c[None]), 0.0, atol=1e-12)
    with pytest.raises(ValueError, match="g"):
        point_velocities([1.0, 2.0], g_dot, world)


def test_binomial_table_against_math_comb():
    rows = binomial_table(ns=(10, 10000), kmax=4)
    for n, k, c, ratio, inv_fact, draft in rows:
        assert c == math.comb(n, k)
        assert np.isclose(ratio, math.comb(n, k) / n ** k)
        assert np.isclose(draft, n ** k / math.factorial(k))
        if n == 10000:
            assert abs(ratio - inv_fact) < 1e-3
    with pytest.raises(ValueError, match="kmax"):
        binomial_table(kmax=-1)


def test_drive_follows_the_exponential_of_a_constant_body_velocity():
    """A differential-drive car with constant wheel rates has constant body velocity xi, so
    g(T) = exp(T xi) (independent route: scipy's expm of the se(2) matrix)."""
    import scipy.linalg

    from gm_core.systems import DifferentialDrive

    car = DifferentialDrive(wheel_radius=0.3, half_width=0.5)
    rd = np.array([2.0, 3.0])
    traj = drive(car, np.zeros(2), rd, 2.0)
    xi = car.body_velocity(np.zeros(2), rd)
    want = SE2.from_matrix(scipy.linalg.expm(2.0 * SE2.hat(xi)))
    assert SE2.isclose(traj.g[-1], want, atol=1e-8)
    gait = constant_rate_path([0.0, 0.1], [1.0, 0.5], 3.0)
    assert np.allclose(gait(np.array([0.0, 2.0])), [[0.0, 0.1], [2.0, 1.1]])
    with pytest.raises(ValueError, match="duration"):
        constant_rate_path([0.0, 0.0], [1.0, 1.0], 0.0)

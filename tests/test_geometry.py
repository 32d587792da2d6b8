"""Constraint curvature, Stokes estimate and body-velocity integral (gm_core.geometry.curvature)."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import SingularShapeError
from gm_core.geometry import (
    body_velocity_integral,
    connection_derivative,
    constraint_curvature,
    fourier_gait,
    stokes_estimate,
)
from gm_core.systems import Ackerman, DifferentialDrive, FloatingSnake, HighReSwimmer, KinematicSnake, LowReSwimmer
from gm_core.systems.gaits import Gait, circle_gait
from gm_core.systems.motion import net_displacement

REGULAR = [LowReSwimmer(), HighReSwimmer(), FloatingSnake(), FloatingSnake(frame="middle"),
           LowReSwimmer(lengths=(0.5, 1.0, 1.5), drag_ratio=3.0)]


def fd5(system, r, h=1e-3):
    """Fourth-order central differences of the connection (the test's own route)."""
    out = []
    for k in range(2):
        e = np.zeros(2)
        e[k] = h
        A = lambda s: system.connection(r + s * e)  # noqa: E731
        out.append((-A(2) + 8 * A(1) - 8 * A(-1) + A(-2)) / (12 * h))
    return np.stack(out, -1)


@pytest.mark.parametrize("system", [KinematicSnake(), KinematicSnake(lengths=(0.7, 1.0, 1.3)), Ackerman(),
                                    DifferentialDrive(0.3, 0.8)], ids=repr)
def test_closed_form_derivatives_match_differences(system):
    rng = np.random.default_rng(1)
    r = rng.uniform(-1.2, 1.2, (40, 2))
    r = r[np.abs(system.singularity(r)) > 0.05]
    A, dA = connection_derivative(system, r)
    A2, dA_fd = connection_derivative(system, r, method="fd")
    np.testing.assert_allclose(A, system.connection(r), atol=1e-13)
    np.testing.assert_allclose(dA, dA_fd, rtol=1e-6, atol=1e-8)
    np.testing.assert_allclose(dA, fd5(system, r), rtol=1e-5, atol=1e-7)


@pytest.mark.parametrize("system", REGULAR, ids=repr)
def test_difference_derivatives_match_fourth_order(system):
    r = np.random.default_rng(2).uniform(-2, 2, (30, 2))
    A, dA = connection_derivative(system, r)
    np.testing.assert_allclose(A, system.connection(r), rtol=1e-8, atol=1e-9)  # stencil mean, O(h^2)
    np.testing.assert_allclose(dA, fd5(system, r), rtol=1e-6, atol=1e-8)


def test_differential_drive_curvature_is_the_bracket_alone():
    R, w = 0.7, 1.3
    F = constraint_curvature(DifferentialDrive(R, w), np.zeros((4, 2)))
    # A1 = (-R/2, 0, R/2w), A2 = (-R/2, 0, -R/2w): [A1, A2] = (0, -R^2 / 2w, 0) by hand
    np.testing.assert_allclose(F, np.tile([0.0, -R ** 2 / (2 * w), 0.0], (4, 1)), atol=1e-15)


def test_grid_shape_and_nan_at_singular_shapes():
    a = np.linspace(-2, 2, 101)
    grid = np.stack(np.meshgrid(a, a, indexing="ij"), -1)
    F = constraint_curvature(KinematicSnake(), grid)
    assert F.shape == (101, 101, 3)
    assert np.all(np.isnan(F[np.arange(101), np.arange(101)]))  # the line alpha1 = alpha2
    off = ~np.eye(101, dtype=bool)
    assert np.isfinite(F[off]).mean() > 0.99


def ellipse(c, a, b, phase=0.0, cw=False, T=1.0):
    s = -1.0 if cw else 1.0
    w = 2 * np.pi / T
    return Gait(lambda t: np.asarray(c) + np.stack([a * np.cos(w * t + phase), s * b * np.sin(w * t + phase)], -1), T,
                lambda t: np.stack([-a * w * np.sin(w * t + phase), s * b * w * np.cos(w * t + phase)], -1))


def bean(c, size):
    """A non-convex (kidney-shaped) closed curve about c."""
    return fourier_gait([[size, 0.0, 0.3 * size], [0.0, 0.45 * size, 0.0]],
                        [[0.0, 0.0, 0.0], [size, 0.0, 0.25 * size]], c, period=1.0)


GAITS = [circle_gait(0.6, (0.2, -0.4)), ellipse((0.5, 0.1), 0.9, 0.3, 0.4), ellipse((0.0, 0.3), 0.5, 0.8, cw=True),
         bean((-0.3, 0.2), 0.7)]


@pytest.mark.parametrize("system", REGULAR + [DifferentialDrive()], ids=repr)
@pytest.mark.parametrize("gait", GAITS, ids=lambda g: g.name)
def test_theta_row_is_exact(system, gait):
    exact = net_displacement(system, gait)
    assert abs(stokes_estimate(system, gait)[2] - exact[2]) < 1e-8
    assert abs(body_velocity_integral(system, gait)[2] - exact[2]) < 1e-10


def test_theta_row_exact_for_singular_systems_on_one_side():
    for system, gait in [(KinematicSnake(), circle_gait(0.5, (1.2, -0.6))), (KinematicSnake(), bean((-1.0, 0.8), 0.35)),
                         (Ackerman(), ellipse((0.0, 0.2), 1.5, 0.6))]:
        exact = net_displacement(system, gait)
        assert abs(stokes_estimate(system, gait)[2] - exact[2]) < 1e-8


def test_nonconvex_gait_is_really_nonconvex():
    p = bean((0.0, 0.0), 1.0)(np.linspace(0, 1, 400, endpoint=False))
    d1 = np.roll(p, -1, 0) - p
    turn = d1[:, 0] * np.roll(d1, -1, 0)[:, 1] - d1[:, 1] * np.roll(d1, -1, 0)[:, 0]
    assert turn.min() < 0 < turn.max()


def test_orientation_reverses_the_estimate():
    s = LowReSwimmer()
    ccw, cw = ellipse((0.3, 0.2), 0.6, 0.4), ellipse((0.3, 0.2), 0.6, 0.4, cw=True)
    np.testing.assert_allclose(stokes_estimate(s, cw), -stokes_estimate(s, ccw), rtol=1e-10)


@pytest.mark.parametrize("system", [LowReSwimmer(), FloatingSnake(frame="middle"), HighReSwimmer()], ids=repr)
def test_xy_error_falls_as_cube_and_wrong_bracket_sign_as_square(system):
    radii = np.array([0.16, 0.08, 0.04, 0.02])
    err, wrong, naive = [], [], []
    for R in radii:
        g = circle_gait(R, (0.5, -0.3))
        exact = net_displacement(system, g)[:2]
        est = stokes_estimate(system, g)
        bvi = body_velocity_integral(system, g)  # = area integral of -dA alone (Stokes' theorem)
        err.append(np.linalg.norm(est[:2] - exact))
        wrong.append(np.linalg.norm((2 * bvi - est)[:2] - exact))  # -dA - [A1, A2]
        naive.append(np.linalg.norm(bvi[:2] - exact))
    slope = lambda e: np.polyfit(np.log(radii[-2:]), np.log(e[-2:]), 1)[0]  # noqa: E731
    assert 2.8 < slope(err) < 3.3
    assert 1.8 < slope(wrong) < 2.2
    assert 1.8 < slope(naive) < 2.2
    assert err[-1] < 0.05 * wrong[-1]


@settings(max_examples=12, deadline=None)
@given(st.floats(-1.0, 1.0), st.floats(-1.0, 1.0), st.floats(0.05, 0.8), st.floats(0.05, 0.8),
       st.floats(-0.3, 0.3), st.floats(0, 2 * np.pi))
def test_theta_row_exact_for_random_fourier_gaits(c1, c2, ra, rb, k2, ph):
    g = fourier_gait([[ra * np.cos(ph), k2 * ra], [rb * np.sin(ph), 0.0]],
                     [[-ra * np.sin(ph), 0.0], [rb * np.cos(ph), k2 * rb]], (c1, c2), period=1.0)
    s = LowReSwimmer()
    assert abs(stokes_estimate(s, g)[2] - net_displacement(s, g)[2]) < 1e-8


# -- bad input ---------------------------------------------------------------------------------
def test_bad_input():
    s = LowReSwimmer()
    with pytest.raises(TypeError, match="system"):
        constraint_curvature("swimmer", np.zeros(2))
    with pytest.raises(TypeError, match="system"):
        stokes_estimate(object(), circle_gait(0.5))
    with pytest.raises(ValueError, match="r must have shape"):
        constraint_curvature(s, np.zeros(3))
    with pytest.raises(TypeError, match="r must be"):
        constraint_curvature(s, "0, 0")
    with pytest.raises(ValueError, match="method"):
        constraint_curvature(s, np.zeros(2), method="spline")
    with pytest.raises(ValueError, match="shape variables"):
        stokes_estimate(s, Gait(lambda t: np.stack([np.cos(t), np.sin(t), t * 0], -1), 2 * np.pi))
    with pytest.raises(TypeError, match="gait"):
        body_velocity_integral(s, None)
    open_arc = Gait(lambda t: np.stack([np.cos(t), np.sin(t)], -1), np.pi)
    for f in (stokes_estimate, body_velocity_integral):
        with pytest.raises(ValueError, match="gait is not closed"):
            f(s, open_arc)

    class ThreeShapes:
        n_shape, name = 3, "toy"

        def connection(self, r):
            return np.zeros(np.shape(r)[:-1] + (3, 3))

    # three shape variables: the curvature is a 2-form, one component per pair; Stokes needs a slice
    F = constraint_curvature(ThreeShapes(), np.zeros((4, 3)))
    assert F.shape == (4, 3, 3, 3) and np.all(F == 0)
    assert constraint_curvature(ThreeShapes(), np.zeros(3), pair=(0, 2)).shape == (3,)
    with pytest.raises(ValueError, match="2-D shape space.*shape_slice"):
        stokes_estimate(ThreeShapes(), Gait(lambda t: np.stack([np.cos(t), np.sin(t), t * 0], -1), 2 * np.pi))
    with pytest.raises(ValueError, match="pair"):
        constraint_curvature(ThreeShapes(), np.zeros(3), pair=(0, 3))


def test_gait_through_a_singular_shape_is_refused():
    with pytest.raises(SingularShapeError, match="singular"):
        stokes_estimate(KinematicSnake(), circle_gait(0.5, (0.1, 0.0)))
    with pytest.raises(SingularShapeError, match="singular"):
        body_velocity_integral(KinematicSnake(), circle_gait(0.5, (0.1, 0.0)))


# -- fixed resolution (the interactive panels' fast path) --------------------------------------
@pytest.mark.parametrize("gait", GAITS, ids=lambda g: g.name)
def test_fixed_samples_agree_with_refined_and_exact(gait):
    """samples=(64, 12) / samples=256: the same formula once; theta against the exact net rotation."""
    for system in (LowReSwimmer(), HighReSwimmer()):
        fast = stokes_estimate(system, gait, samples=(64, 12), check=False)
        np.testing.assert_allclose(fast, stokes_estimate(system, gait), atol=1e-7)
        assert abs(fast[2] - net_displacement(system, gait)[2]) < 1e-8      # independent route
        bvi = body_velocity_integral(system, gait, samples=256, check=False)
        np.testing.assert_allclose(bvi, body_velocity_integral(system, gait), atol=1e-8)


def test_fixed_samples_bad_input():
    s, g = LowReSwimmer(), circle_gait(0.5)
    for bad in ((64,), (64, 1), 64.0, "64", (True, 8)):
        with pytest.raises(ValueError, match="samples must be"):
            stokes_estimate(s, g, samples=bad)
    for bad in ((64, 8), 1, 2.5):
        with pytest.raises(ValueError, match="samples must be"):
            body_velocity_integral(s, g, samples=bad)
    with pytest.raises(SingularShapeError, match="singular"):
        stokes_estimate(KinematicSnake(), circle_gait(0.5, (0.1, 0.0)), samples=(64, 8))

"""gm_core.geometry.estimates: the numbers of notebook 10's panels, each against an independent route."""
import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from gm_core import SE2, SingularShapeError
from gm_core.geometry import constraint_curvature, minimum_perturbation_coordinates
from gm_core.geometry.estimates import (
    INTERACTIVE,
    curvature_grid,
    displacement_estimates,
    field_rms,
    frames_of,
    row_scaled,
    shaped_gait,
    square_grid,
)
from gm_core.systems import KinematicSnake, LowReSwimmer

SWIMMER = LowReSwimmer()
WINDOW = ((-2.5, 2.5), (-2.5, 2.5))
GAITS = [dict(c1=0.0, c2=0.0, a=1.0, b=0.6, tilt=0.78, bend=0.0),
         dict(c1=0.3, c2=-0.2, a=0.9, b=0.5, tilt=0.4, bend=0.25),
         dict(c1=-0.6, c2=0.5, a=0.4, b=1.2, tilt=-1.2, bend=-0.3)]


# ------------------------------------------------------------------ shaped_gait
@pytest.mark.parametrize("v", GAITS)
def test_shaped_gait_is_the_stated_curve_and_encloses_pi_a_b(v):
    g = shaped_gait(**v)
    t = np.linspace(0, 1, 2001)
    w = 2 * np.pi
    u = v["a"] * np.cos(w * t)
    q = v["b"] * np.sin(w * t) + v["bend"] * np.cos(2 * w * t)
    c, s = np.cos(v["tilt"]), np.sin(v["tilt"])
    want = np.stack([v["c1"] + c * u - s * q, v["c2"] + s * u + c * q], -1)
    np.testing.assert_allclose(g(t), want, atol=1e-12)
    # the velocity against central differences of the curve itself
    h = 1e-6
    np.testing.assert_allclose(g.velocity(t[:50]), (g(t[:50] + h) - g(t[:50] - h)) / (2 * h), atol=1e-6)
    # shoelace area: counter-clockwise, pi a b whatever the bend (the bend term integrates to zero)
    p = g(np.linspace(0, 1, 4000, endpoint=False))
    area = 0.5 * np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1])
    assert area == pytest.approx(np.pi * v["a"] * v["b"], rel=1e-6)


def test_shaped_gait_refuses_bad_sizes():
    with pytest.raises(ValueError, match="a"):
        shaped_gait(a=-1.0)
    with pytest.raises(TypeError, match="tilt"):
        shaped_gait(tilt="steep")


# ------------------------------------------------------------------ the three estimates
def _exact_by_matrix_ode(system, gait):
    """g(T) from the 3 x 3 matrix ODE dG/dt = G hat(xi), solve_ivp (not the library's Magnus steps)."""
    def rhs(t, y):
        G = y.reshape(3, 3)
        r, rd = gait(np.array([t]))[0], gait.velocity(np.array([t]))[0]
        return (G @ SE2.hat(system.body_velocity(r, rd))).ravel()

    sol = solve_ivp(rhs, (0, gait.period), np.eye(3).ravel(), rtol=1e-11, atol=1e-12, method="DOP853")
    return SE2.from_matrix(sol.y[:, -1].reshape(3, 3))


def _bvi_by_quad(system, gait):
    def xi(t, i):
        return system.body_velocity(gait(np.array([t]))[0], gait.velocity(np.array([t]))[0])[i]

    return np.array([quad(xi, 0, gait.period, args=(i,), epsabs=1e-12, limit=200)[0] for i in range(3)])


@pytest.mark.parametrize("v", GAITS[:2])
def test_estimates_against_independent_routes(v):
    gait = shaped_gait(**v)
    est = displacement_estimates(SWIMMER, gait)
    np.testing.assert_allclose(est.exact, _exact_by_matrix_ode(SWIMMER, gait), atol=1e-8)
    np.testing.assert_allclose(est.body_velocity_integral, _bvi_by_quad(SWIMMER, gait), atol=1e-9)
    # theta row of the Stokes estimate is exact; its (x, y) are close for a gait of this size
    assert est.stokes[2] == pytest.approx(est.exact[2], abs=1e-9)
    assert np.abs(est.stokes[:2] - est.exact[:2]).max() < 0.05


def test_stokes_estimate_against_a_polar_area_sum():
    """A circle (bend 0, a = b): the Stokes estimate is the curvature summed over the disc."""
    gait = shaped_gait(0.2, -0.1, 0.8, 0.8, 0.3, 0.0)
    nr, nt = 200, 256
    rho = (np.arange(nr) + 0.5) / nr * 0.8
    phi = (np.arange(nt) + 0.5) / nt * 2 * np.pi
    R, P = np.meshgrid(rho, phi, indexing="ij")
    pts = np.stack([0.2 + R * np.cos(P), -0.1 + R * np.sin(P)], -1)
    area_sum = (constraint_curvature(SWIMMER, pts) * R[..., None]).sum(axis=(0, 1)) * (0.8 / nr) * (2 * np.pi / nt)
    np.testing.assert_allclose(displacement_estimates(SWIMMER, gait).stokes, area_sum, atol=2e-5)


@pytest.mark.parametrize("frame", ["middle link", "centre of mass", "minimum perturbation"])
@pytest.mark.parametrize("v", GAITS)
def test_interactive_resolution_is_within_1e7_of_refined(frame, v):
    system = frames_of(SWIMMER, WINDOW)[frame]
    gait = shaped_gait(**v)
    fast = displacement_estimates(system, gait, interactive=True).as_array()
    slow = displacement_estimates(system, gait).as_array()
    np.testing.assert_allclose(fast, slow, atol=1e-7)
    assert set(INTERACTIVE) == {"exact_steps", "stokes_samples", "bvi_samples"}


def test_estimates_flag_singular_and_out_of_window_gaits():
    with pytest.raises(SingularShapeError):       # crosses the kinematic snake's singular line
        displacement_estimates(KinematicSnake(), shaped_gait(0.0, 0.0, 1.0, 1.0), interactive=True)
    mp = frames_of(SWIMMER, WINDOW)["minimum perturbation"]
    with pytest.raises(SingularShapeError):       # leaves the window the frame is defined on
        displacement_estimates(mp, shaped_gait(1.5, 1.5, 1.5, 1.5), interactive=True)


# ------------------------------------------------------------------ row scaling
def test_row_scaled_keeps_a_vanishing_row_small():
    h = row_scaled([[0.2, 1e-15, -0.1], [0.19, -2e-15, -0.1], [0.1, 0.0, -0.05]])
    np.testing.assert_allclose(h[:, 0], [1.0, 0.95, 0.5])
    assert np.abs(h[:, 1]).max() < 1e-10 and np.allclose(h[:, 2], [-1, -1, -0.5])


@pytest.mark.parametrize("shape", [(3, 3), (1, 3), (4, 2)])
def test_row_scaled_properties(shape):
    rng = np.random.default_rng(sum(shape))
    v = rng.normal(size=shape) * rng.uniform(1e-3, 10, size=shape[1])
    h = row_scaled(v)
    assert np.abs(h).max() <= 1 + 1e-12
    big = np.abs(v).max(axis=0) >= 0.05 * np.abs(v).max()
    np.testing.assert_allclose(np.abs(h).max(axis=0)[big], 1.0)
    np.testing.assert_allclose(np.sign(h), np.sign(v))          # signs kept
    np.testing.assert_allclose(h * np.abs(v).max(axis=0) / np.abs(h).max(axis=0), v)  # one factor per row
    np.testing.assert_array_equal(row_scaled(np.zeros(shape)), np.zeros(shape))


def test_row_scaled_bad_input():
    with pytest.raises(ValueError, match="values"):
        row_scaled([1.0, 2.0])
    with pytest.raises(ValueError, match="floor"):
        row_scaled([[1.0]], floor=2.0)


# ------------------------------------------------------------------ field sizes, frames, caches
def test_field_rms_by_hand_and_the_frames_shrink():
    grid = square_grid(WINDOW, 9)
    A = SWIMMER.connection(grid)
    want = [np.sqrt(np.mean([np.dot(A[j, i, row], A[j, i, row]) for j in range(9) for i in range(9)]))
            for row in range(3)]
    np.testing.assert_allclose(field_rms(SWIMMER, grid), want, rtol=1e-12)
    frames = frames_of(SWIMMER, WINDOW)
    mid, mp = field_rms(frames["middle link"], grid), field_rms(frames["minimum perturbation"], grid)
    assert np.all(mp < mid) and mp[2] < 0.5 * mid[2]


def test_field_rms_skips_singular_shapes():
    snake = KinematicSnake()
    grid = np.array([[0.5, 0.5], [0.3, -0.4], [1.0, -1.0]])   # the first is on the singular line
    A = snake.connection(grid[1:])
    want = np.sqrt(np.mean(np.sum(A ** 2, axis=-1), axis=0))
    np.testing.assert_allclose(field_rms(snake, grid), want)


def test_frames_and_curvature_are_cached_per_system_object():
    frames = frames_of(SWIMMER, WINDOW)
    assert frames_of(SWIMMER, [[-2.5, 2.5], [-2.5, 2.5]]) is frames        # same system, same window
    other = LowReSwimmer(drag_ratio=3.0)
    assert frames_of(other, WINDOW)["middle link"] is other                # never another system's frames
    np.testing.assert_allclose(frames["minimum perturbation"].connection(np.array([0.3, 0.2])),
                               minimum_perturbation_coordinates(SWIMMER, WINDOW).connection(np.array([0.3, 0.2])),
                               atol=1e-12)
    F = curvature_grid(SWIMMER, WINDOW, 11)
    assert curvature_grid(SWIMMER, WINDOW, 11) is F and not F.flags.writeable
    np.testing.assert_allclose(F, constraint_curvature(SWIMMER, square_grid(WINDOW, 11)))
    assert not np.allclose(curvature_grid(other, WINDOW, 11), F)
    with pytest.raises(TypeError):
        frames["middle link"] = other                                      # read-only mapping
    with pytest.raises(ValueError, match="limits"):
        curvature_grid(SWIMMER, ((1.0, -1.0), (0.0, 1.0)), 11)

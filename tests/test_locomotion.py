"""gm_core.systems.motion: Pfaffian/mass-matrix routes, gaits, reconstruction, singular gaits."""
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from gm_core import SE2, SingularShapeError
from gm_core.systems import (
    ALL_SYSTEMS,
    Ackerman,
    DifferentialDrive,
    HighReSwimmer,
    KinematicSnake,
    LowReSwimmer,
)
from gm_core.systems.connection import connection_from_mass_matrix, connection_from_pfaffian, metric_from_jacobians
from gm_core.systems.gaits import Gait, as_gait, circle_gait
from gm_core.systems.motion import body_velocity, check_gait, net_displacement, trajectory

RNG = np.random.default_rng(7)

#: A gait per system that stays away from singular shapes.
GAITS = {
    "DifferentialDrive": circle_gait(1.0, (0.2, -0.4)),
    "Ackerman": circle_gait((2.0, 0.7), (0.0, 0.1)),
    "KinematicSnake": circle_gait(0.8, (0.4, -1.0)),
    "FloatingSnake": circle_gait(1.2, (0.3, 0.2)),
    "LowReSwimmer": circle_gait(1.0, (0.0, 0.0)),
    "HighReSwimmer": circle_gait(1.1, (-0.2, 0.3)),
}


def reference_displacement(system, gait, rtol=1e-12):
    """Independent route: solve_ivp (DOP853) on (x, y, theta) with g_dot = T_e L_g xi, (1.28)."""
    def f(t, g):
        r = gait(np.array([t]))[0]
        rd = gait.velocity(np.array([t]))[0]
        xi = -system.connection(r) @ rd
        c, s = np.cos(g[2]), np.sin(g[2])
        return [c * xi[0] - s * xi[1], s * xi[0] + c * xi[1], xi[2]]
    sol = solve_ivp(f, (0.0, gait.period), np.zeros(3), method="DOP853", rtol=rtol, atol=1e-14)
    return sol.y[:, -1]


# ------------------------------------------------------------------ connection routes
def test_connection_from_pfaffian_solves_the_constraint():
    om = RNG.normal(size=(6, 3, 5))
    A = connection_from_pfaffian(om)
    np.testing.assert_allclose(om[..., :3] @ A, om[..., 3:], atol=1e-12)
    np.testing.assert_allclose(A, np.linalg.solve(om[..., :3], om[..., 3:]), rtol=1e-9, atol=1e-12)
    # xi = -A r_dot satisfies omega [xi; r_dot] = 0, (3.14)-(3.16)
    rd = RNG.normal(size=(6, 2))
    xi = -np.einsum("...ij,...j->...i", A, rd)
    np.testing.assert_allclose(np.einsum("...ij,...j->...i", om, np.concatenate([xi, rd], -1)), 0,
                               atol=1e-12)


def test_connection_from_pfaffian_singular_is_nan_quietly():
    om = RNG.normal(size=(3, 3, 4))
    om[1, 2, :3] = om[1, 0, :3] + om[1, 1, :3]  # dependent body rows
    om[2, :, :3] = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        A = connection_from_pfaffian(om)
    assert np.all(np.isfinite(A[0])) and np.all(np.isnan(A[1])) and np.all(np.isnan(A[2]))


def test_connection_from_pfaffian_bad_shape():
    with pytest.raises(ValueError, match="omega"):
        connection_from_pfaffian(np.zeros((2, 5)))
    with pytest.raises(ValueError, match="omega"):
        connection_from_pfaffian(np.zeros((3, 3)))
    with pytest.raises(TypeError, match="omega"):
        connection_from_pfaffian("omega")


def test_mass_matrix_route_is_zero_momentum():
    B = RNG.normal(size=(4, 5, 5))
    M = B @ np.swapaxes(B, -1, -2) + 5 * np.eye(5)
    A = connection_from_mass_matrix(M)
    rd = RNG.normal(size=(4, 2))
    xi = -np.einsum("...ij,...j->...i", A, rd)
    p = np.einsum("...ij,...j->...i", M[..., :3, :], np.concatenate([xi, rd], -1))
    np.testing.assert_allclose(p, 0, atol=1e-12)
    # (3.40): the off-diagonal block is I_locked A
    np.testing.assert_allclose(M[..., :3, :3] @ A, M[..., :3, 3:], atol=1e-12)
    with pytest.raises(ValueError, match="M"):
        connection_from_mass_matrix(np.zeros((4, 5)))


def test_metric_from_jacobians_diagonal_and_full():
    J = [RNG.normal(size=(2, 3, 5)) for _ in range(3)]
    Ms = [np.diag(RNG.uniform(1, 2, 3)) for _ in range(3)]
    full = sum(np.swapaxes(j, -1, -2) @ m @ j for j, m in zip(J, Ms))
    np.testing.assert_allclose(metric_from_jacobians(J, Ms), full, atol=1e-12)
    np.testing.assert_allclose(metric_from_jacobians(J, Ms, rows=3), full[..., :3, :], atol=1e-12)
    Ms[1] = Ms[1] + 0.1 * (np.ones((3, 3)) - np.eye(3))
    full = sum(np.swapaxes(j, -1, -2) @ m @ j for j, m in zip(J, Ms))
    np.testing.assert_allclose(metric_from_jacobians(J, Ms), full, atol=1e-12)


@settings(max_examples=50, deadline=None)
@given(st.lists(st.floats(-3, 3), min_size=6, max_size=6))
def test_se2_bracket_is_the_matrix_commutator(v):
    x1, x2 = np.array(v[:3]), np.array(v[3:])
    X1, X2 = SE2.hat(x1), SE2.hat(x2)
    np.testing.assert_allclose(SE2.hat(SE2.bracket(x1, x2)), X1 @ X2 - X2 @ X1, atol=1e-12)


def test_body_velocity_function():
    s = KinematicSnake()
    r, rd = np.array([0.5, -0.5]), np.array([1.0, 2.0])
    np.testing.assert_allclose(body_velocity(s, r, rd), -s.connection(r) @ rd)
    np.testing.assert_allclose(s.body_velocity(r, rd), -s.connection(r) @ rd)


# ------------------------------------------------------------------ gaits
def test_circle_gait_formula_and_velocity():
    g = circle_gait(0.5, center=(1.0, -2.0), period=2.0)
    t = np.linspace(0, 2, 9)
    np.testing.assert_allclose(g(t), np.stack([1 + 0.5 * np.cos(np.pi * t), -2 + 0.5 * np.sin(np.pi * t)], -1))
    np.testing.assert_allclose(g.velocity(t), 0.5 * np.pi * np.stack([-np.sin(np.pi * t), np.cos(np.pi * t)], -1),
                               atol=1e-14)
    assert g.period == 2.0 and g.n_shape == 2


def test_callable_gait_velocity_by_differences():
    g = Gait(lambda t: np.stack([np.sin(2 * np.pi * t), np.cos(4 * np.pi * t)], -1))
    t = np.linspace(0, 1, 11)
    exact = np.stack([2 * np.pi * np.cos(2 * np.pi * t), -4 * np.pi * np.sin(4 * np.pi * t)], -1)
    np.testing.assert_allclose(g.velocity(t), exact, atol=1e-10)
    # scalar-only callables work too
    g2 = Gait(lambda t: [np.sin(2 * np.pi * t), np.cos(4 * np.pi * t)])
    np.testing.assert_allclose(g2(t), g(t))


@pytest.mark.parametrize("n_times", [1, 2, 3, 11])
def test_a_callable_returning_shape_by_time_is_read_the_right_way_round(n_times):
    """np.array([cos t, sin t]) gives (n, N), which with N = n = 2 looks like (N, n): the gait
    tells them apart, never silently transposing the shapes."""
    rows = Gait(lambda t: np.array([np.cos(t), 2 * np.sin(t)]))
    by_time = Gait(lambda t: np.stack([np.cos(t), 2 * np.sin(t)], -1))
    scalar = Gait(lambda t: [float(np.cos(t)), float(2 * np.sin(t))])
    t = np.linspace(0.0, 1.0, n_times)
    exact = np.stack([np.cos(t), 2 * np.sin(t)], -1)
    for g in (rows, by_time, scalar):
        np.testing.assert_allclose(g(t), exact, atol=1e-15)
        np.testing.assert_allclose(g.velocity(t), np.stack([-np.sin(t), 2 * np.cos(t)], -1), atol=1e-9)


def test_sampled_gait_is_closed_and_close_to_the_circle():
    tk = np.linspace(0, 1, 65)
    pts = np.stack([0.3 + np.cos(2 * np.pi * tk), np.sin(2 * np.pi * tk)], -1)
    g = Gait.from_samples(pts)
    np.testing.assert_allclose(g(0.0), g(1.0), atol=1e-14)
    np.testing.assert_allclose(g(np.linspace(0, 1, 33)), circle_gait(1.0, (0.3, 0.0))(np.linspace(0, 1, 33)),
                               atol=1e-5)
    assert as_gait(pts).n_shape == 2


def test_bad_gait_input():
    with pytest.raises(ValueError, match="amplitude"):
        circle_gait(0.0)
    with pytest.raises(ValueError, match="amplitude"):
        circle_gait(-1.0)
    with pytest.raises(ValueError, match="center"):
        circle_gait(1.0, center=(0, 0, 0))
    with pytest.raises(ValueError, match="period"):
        circle_gait(1.0, period=0)
    with pytest.raises(TypeError, match="gait"):
        as_gait("circle")
    with pytest.raises(ValueError, match="points"):
        Gait.from_samples(np.zeros((2, 2)))
    with pytest.raises(ValueError, match="shape variables"):
        net_displacement(KinematicSnake(), Gait(lambda t: np.stack([t, t, t], -1)))
    with pytest.raises(TypeError, match="system"):
        net_displacement(object(), circle_gait(1.0))
    with pytest.raises(ValueError, match="n_frames"):
        trajectory(LowReSwimmer(), circle_gait(1.0), n_frames=1)


# ------------------------------------------------------------------ reconstruction
@pytest.mark.parametrize("name", list(GAITS))
def test_net_displacement_matches_tight_solve_ivp(name):
    s, g = ALL_SYSTEMS[name], GAITS[name]
    d = net_displacement(s, g)
    ref = reference_displacement(s, g)
    assert d.shape == (3,)
    scale = max(1.0, np.abs(ref).max())
    assert np.abs(d - ref).max() <= 1e-8 * scale, (d, ref)


def test_net_displacement_of_sampled_gait_matches_solve_ivp():
    s = LowReSwimmer()
    tk = np.linspace(0, 1, 41)[:-1]
    pts = np.stack([np.cos(2 * np.pi * tk) + 0.3 * np.cos(4 * np.pi * tk), np.sin(2 * np.pi * tk)], -1)
    g = Gait.from_samples(pts)
    d = net_displacement(s, g)
    ref = reference_displacement(s, g)
    assert np.abs(d - ref).max() <= 1e-8 * max(1.0, np.abs(ref).max())


@pytest.mark.parametrize("name", ["KinematicSnake", "LowReSwimmer", "HighReSwimmer", "Ackerman"])
def test_reparameterization_invariance(name):
    """Fig. 3.1 / (3.3)-(3.4): the same path at another pacing gives the same displacement."""
    s, g = ALL_SYSTEMS[name], GAITS[name]
    a = 0.6
    tau = lambda t: t - a / (2 * np.pi) * np.sin(2 * np.pi * t)  # noqa: E731, tau' = 1 - a cos > 0
    tau_dot = lambda t: 1 - a * np.cos(2 * np.pi * t)  # noqa: E731
    d0 = net_displacement(s, g)
    d1 = net_displacement(s, g.reparameterized(tau, tau_dot))
    d2 = net_displacement(s, g.reparameterized(tau))  # finite-difference velocity
    np.testing.assert_allclose(d1, d0, atol=1e-9)
    np.testing.assert_allclose(d2, d0, atol=1e-9)
    # and a different period (slower execution) changes nothing either
    slow = circle_gait(g.amplitude, g.center, period=3.0)
    np.testing.assert_allclose(net_displacement(s, slow), d0, atol=1e-9)


def test_reversed_gait_gives_the_inverse_displacement():
    s = HighReSwimmer()
    g = GAITS["HighReSwimmer"]
    rev = Gait(lambda t: g(1.0 - np.asarray(t)), 1.0, lambda t: -g.velocity(1.0 - np.asarray(t)))
    d, dr = net_displacement(s, g), net_displacement(s, rev)
    assert SE2.isclose(SE2.compose(d, dr), np.zeros(3), atol=1e-10)


def test_diff_drive_orientation_is_holonomic():
    """Exercise 3.1: theta = R (alpha2 - alpha1) / (2 w) + const, so closed gaits never turn the car."""
    s = DifferentialDrive(wheel_radius=0.5, half_width=0.8)
    g = circle_gait(1.5, (0.3, -0.1))
    tr = trajectory(s, g, 41)
    r0 = tr.r[0]
    np.testing.assert_allclose(tr.g[:, 2], 0.5 / 1.6 * ((tr.r[:, 1] - r0[1]) - (tr.r[:, 0] - r0[0])), atol=1e-10)
    assert abs(net_displacement(s, g)[2]) < 1e-12


def test_trajectory_frames_and_cycles():
    s, g = KinematicSnake(), GAITS["KinematicSnake"]
    tr = trajectory(s, g, 21, cycles=2, g0=(1.0, 2.0, 0.5))
    assert tr.g.shape == (21, 3) and tr.t.shape == (21,) and tr.r.shape == (21, 2)
    np.testing.assert_allclose(tr.g[0], [1.0, 2.0, 0.5])
    d = net_displacement(s, g)
    assert SE2.isclose(tr.g[10], SE2.compose([1.0, 2.0, 0.5], d), atol=1e-9)
    assert SE2.isclose(tr.g[20], SE2.compose([1.0, 2.0, 0.5], SE2.compose(d, d)), atol=1e-9)
    np.testing.assert_allclose(tr.t[[0, 10, 20]], [0, 1, 2])


# ------------------------------------------------------------------ singular gaits
def test_gait_crossing_singular_line_raises():
    s = KinematicSnake()
    g = circle_gait(0.8, (0.1, -0.05))  # crosses alpha1 = alpha2 twice, not at a sample point
    with pytest.raises(SingularShapeError, match="singular") as e:
        net_displacement(s, g)
    msg = str(e.value)
    assert "t = " in msg and "r = (" in msg
    # the reported shape is on the singular line
    r = [float(v) for v in msg.split("r = (")[1].split(")")[0].split(",")]
    assert abs(r[0] - r[1]) < 1e-8
    with pytest.raises(ValueError):
        trajectory(s, g, 11)


def test_gait_touching_singular_line_raises():
    s = KinematicSnake()
    c = np.array([0.5, -0.4])
    R = abs(c[0] - c[1]) / np.sqrt(2)  # tangent to alpha1 = alpha2
    with pytest.raises(SingularShapeError, match="singular"):
        net_displacement(s, circle_gait(R, c))
    assert np.isfinite(net_displacement(s, circle_gait(R * 0.98, c))).all()  # a near miss is fine
    with pytest.raises(SingularShapeError, match="singular"):
        check_gait(Ackerman(), circle_gait((1.0, np.pi / 2), (0.0, 0.0)))


def test_nonsingular_systems_never_raise():
    """A large gait through every quadrant: no singular shape is reported, and the displacement
    is a finite element that the frame-by-frame trajectory ends on (an independent integration)."""
    for name in ["DifferentialDrive", "FloatingSnake", "LowReSwimmer", "HighReSwimmer"]:
        system, gait = ALL_SYSTEMS[name], circle_gait(2.5, (0.0, 0.0))
        assert not getattr(system, "may_be_singular", False), name
        check_gait(system, gait)
        g = net_displacement(system, gait)
        assert g.shape == (3,) and np.isfinite(g).all(), name
        assert SE2.isclose(trajectory(system, gait, 3).g[-1], g, atol=1e-6), name


def test_connection_curl():
    from gm_core.geometry.curvature import connection_curl
    assert np.allclose(connection_curl(DifferentialDrive(0.3, 0.7), RNG.uniform(-3, 3, (5, 2))), 0)
    s = KinematicSnake((1.0, 0.8, 1.2))
    r = np.array([0.7, -0.6])
    h = 1e-4
    f = s.connection_closed_form
    ref = ((f(r + [h, 0]) - f(r - [h, 0]))[:, 1] - (f(r + [0, h]) - f(r - [0, h]))[:, 0]) / (2 * h)
    np.testing.assert_allclose(connection_curl(s, r), ref, rtol=1e-6, atol=1e-9)
    assert abs(connection_curl(s, r)[0]) > 0.1  # the forward row is not exact


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2 ** 32 - 1))
def test_connection_is_invariant_under_row_operations(seed):
    """Recombining the constraint rows (omega -> M omega, M invertible) describes the same
    constraints, so A must not change; scaling the shape columns scales A's columns."""
    rng = np.random.default_rng(seed)
    om = rng.normal(size=(3, 5))
    M = rng.normal(size=(3, 3))
    if abs(np.linalg.det(om[:, :3])) < 1e-3 or abs(np.linalg.det(M)) < 1e-3:
        return
    A = connection_from_pfaffian(om)
    np.testing.assert_allclose(connection_from_pfaffian(M @ om), A, rtol=1e-6, atol=1e-6 * np.abs(A).max())
    S = np.diag([1.0, 1.0, 1.0, 2.0, -3.0])
    np.testing.assert_allclose(connection_from_pfaffian(om @ S), A * [2.0, -3.0], rtol=1e-9, atol=1e-9 * np.abs(A).max())


def test_displacement_until_matches_trajectory_frames_and_the_pacing_square():
    from gm_core.systems import LowReSwimmer
    from gm_core.systems.gaits import ellipse_gait
    from gm_core.systems.motion import displacement_until
    from gm_core.systems.pacing import sine_pacing

    sw = LowReSwimmer()
    gait = ellipse_gait(1.0, 0.6, 0.4, (0.1, -0.2))
    tr = trajectory(sw, gait, 9)
    for k in (2, 5, 8):
        np.testing.assert_allclose(displacement_until(sw, gait, tr.t[k], steps=512), tr.g[k], atol=1e-9)
    # independent route: solve_ivp of g_dot = T_e L_g xi over [0, t]
    t_end = 0.37
    def f(t, g):
        xi = sw.body_velocity(gait(np.array([t]))[0], gait.velocity(np.array([t]))[0])
        return SE2.body_to_world(g, xi)
    sol = solve_ivp(f, (0.0, t_end), np.zeros(3), method="DOP853", rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(displacement_until(sw, gait, t_end), sol.y[:, -1], atol=1e-9)
    # (3.4): the repaced gait at time t sits where the original was at tau(t)
    tau, tau_dot = sine_pacing(0.7)
    rep = gait.reparameterized(tau, tau_dot)
    for t in (0.2, 0.55, 0.9):
        np.testing.assert_allclose(displacement_until(sw, rep, t, steps=1024),
                                   displacement_until(sw, gait, float(tau(t)), steps=1024), atol=1e-8)
    with pytest.raises(ValueError, match="t must be"):
        displacement_until(sw, gait, 2.0)

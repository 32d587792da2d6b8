"""Chapter 3 checkers: references against Pfaffians, gm_core.systems.motion and gm_core.systems."""
import numpy as np
import pytest
from scipy.integrate import solve_ivp

from gm_core import SE2
from gm_core.checks.ex3 import ex3_1, ex3_3, ex3_4
from gm_core.checks.keys import ex3
from gm_core.systems import Ackerman, DifferentialDrive, HighReSwimmer, LowReSwimmer
from gm_core.systems.connection import connection_from_pfaffian
from gm_core.systems.fluids import ellipse_added_mass

pytestmark = pytest.mark.usefixtures("clean")


def test_differential_drive_heading_by_integration():
    R, w = 0.6, 0.9
    car = DifferentialDrive(wheel_radius=R, half_width=w)
    A = car.connection(np.zeros(2))
    shape = lambda t: np.array([np.sin(3 * t) + t, 2 * np.cos(t) - 2 + t * t])
    shape_dot = lambda t: np.array([3 * np.cos(3 * t) + 1, -2 * np.sin(t) + 2 * t])
    sol = solve_ivp(lambda t, g: SE2.body_to_world(g, -A @ shape_dot(t)), (0, 2), np.zeros(3),
                    rtol=1e-10, atol=1e-12, dense_output=True)
    for t in np.linspace(0, 2, 9):
        a1, a2 = shape(t)
        assert np.isclose(sol.sol(t)[2], ex3._theta_dd(a1, a2, R, w), atol=1e-7)


@pytest.mark.parametrize("drive", ["rear", "front"])
def test_ackerman_connection_satisfies_its_pfaffian(drive):
    ref = ex3.ackerman_rear if drive == "rear" else ex3.ackerman_front
    for alpha, R, L in ex3_3.a.inputs():
        om = ex3.ackerman_pfaffian(alpha, R, L, drive)
        A = ref(alpha, R, L)
        assert np.linalg.matrix_rank(om) == 3
        assert np.allclose(om @ np.vstack([-A, np.eye(2)]), 0)
        assert np.allclose(connection_from_pfaffian(om), A)


def test_rear_drive_matches_the_library_and_the_book():
    for alpha, R, L in ex3_3.a.inputs():
        assert np.allclose(ex3.ackerman_rear(alpha, R, L), Ackerman(R, L).connection(alpha))
    a2 = 0.4
    assert np.allclose(-ex3.ackerman_rear([0, a2], 1, 1), [[1, 0], [0, 0], [np.tan(a2), 0]])  # (3.9)


def test_front_drive_moves_forward_and_pivots_without_singularity():
    xi = -ex3.ackerman_front([0.0, np.pi / 2], 1.0, 2.0) @ np.array([1.0, 0.0])
    assert np.allclose(xi, [0.0, 0.0, 0.5], atol=1e-12)


def test_two_link_jacobians_by_finite_differences():
    rng = np.random.default_rng(7)
    for _ in range(4):
        alpha, adot, xi = rng.uniform(-2, 2), rng.normal(), rng.normal(size=3)
        J = ex3.two_link_jacobians(alpha)

        def link_world(t, i):
            return SE2.compose(SE2.exp(t * xi), ex3.two_link_geometry(alpha + t * adot)[0][i])
        eps = 1e-6
        for i in range(2):
            g_dot = (link_world(eps, i) - link_world(-eps, i)) / (2 * eps)
            assert np.allclose(J[i] @ np.r_[xi, adot], SE2.world_to_body(link_world(0.0, i), g_dot), atol=1e-6)


def test_swimmer_physics_matches_the_three_link_library():
    # the same assembly (sum J^T K J, top rows as Pfaffian) on three links reproduces gm_core.systems
    def three_link(K, r):
        a1, a2 = r
        poses = [np.array([-0.5 - 0.5 * np.cos(a1), 0.5 * np.sin(a1), -a1]), np.zeros(3),
                 np.array([0.5 + 0.5 * np.cos(a2), 0.5 * np.sin(a2), a2])]
        d = [np.array([[0.5 * np.sin(a1), 0], [0.5 * np.cos(a1), 0], [-1, 0]]), np.zeros((3, 2)),
             np.array([[0, -0.5 * np.sin(a2)], [0, 0.5 * np.cos(a2)], [0, 1]])]
        M = sum(J.T @ K @ J for J in [SE2.Ad_inv(p) @ np.hstack([np.eye(3), SE2.right_lifted_action(SE2.inverse(p), p) @ dp])
                                      for p, dp in zip(poses, d)])
        return np.linalg.solve(M[:3, :3], M[:3, 3:])
    r = np.array([0.9, -0.4])
    assert np.allclose(three_link(ex3.low_re_resistance(), r), LowReSwimmer().connection(r))
    assert np.allclose(three_link(ex3.high_re_inertia(), r), HighReSwimmer(body_density=1.0).connection(r))
    a, b = 0.5, 0.05
    assert np.allclose(ex3.high_re_inertia() - np.diag([np.pi * a * b] * 2 + [np.pi * a * b * (a * a + b * b) / 4]),
                       ellipse_added_mass(a, b))


@pytest.mark.parametrize("regime", ["low", "high"])
def test_two_link_swimmer_symmetry_and_scallop(regime):
    A = ex3.low_re_connection if regime == "low" else ex3.high_re_connection
    for alpha in np.linspace(-2.5, 2.5, 11):
        assert np.allclose(A(alpha)[[0, 2]], 0, atol=1e-12)
    assert np.isclose(A(0.0)[1, 0], 0.25)

    def rhs(t, g):
        alpha, adot = 1.1 * np.sin(2 * np.pi * t), 2.2 * np.pi * np.cos(2 * np.pi * t)
        return SE2.body_to_world(g, -A(alpha)[:, 0] * adot)
    sol = solve_ivp(rhs, (0, 1), np.zeros(3), rtol=1e-10, atol=1e-12)
    assert np.allclose(sol.y[:, -1], 0, atol=1e-7)


def test_swimmer_accepts_flat_vectors():
    assert ex3_4.a.check(lambda a: ex3.low_re_connection(a).ravel(), quiet=True).passed
    assert ex3_1.a.check(lambda a1, a2, R, w: R * (a2 - a1) / (2 * w), quiet=True).passed

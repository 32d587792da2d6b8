"""Body-frame changes and minimum-perturbation coordinates (gm_core.geometry.coordinates)."""
import numpy as np
import pytest

from gm_core import SE2, SingularShapeError
from gm_core.geometry import (
    centre_of_mass_coordinates,
    constraint_curvature,
    drift_and_turn,
    minimum_perturbation_coordinates,
    reframe,
    stokes_estimate,
)
from gm_core.systems import FloatingSnake, HighReSwimmer, KinematicSnake, LowReSwimmer
from gm_core.systems.gaits import circle_gait
from gm_core.systems.motion import net_displacement


@pytest.fixture(scope="module")
def low_re():
    s = LowReSwimmer()
    return s, minimum_perturbation_coordinates(s, ((-2.5, 2.5), (-2.5, 2.5)), 33)


def test_theta_row_is_discretely_divergence_free_with_no_boundary_flux(low_re):
    s, mp = low_re
    div = mp.frame.discrete_divergence()
    # the same weak divergence of the original theta row, for scale
    div0 = mp.frame.discrete_divergence(of="base")
    assert np.abs(div0).max() > 1e-3
    assert np.abs(div).max() < 1e-12 * max(1.0, np.abs(div0).max())


def test_frame_interpolates_its_nodes_and_its_jacobian_is_the_derivative_of_its_pose(low_re):
    """The frame's spline passes through the finite-element solution, agrees with FITPACK's own
    evaluation of the same fit (scipy's RectBivariateSpline, one component at a time), and its
    body Jacobian is the central difference of its pose, converted to the body frame."""
    from scipy.interpolate import RectBivariateSpline

    from gm_core.systems.reframed import body_jacobian

    s, mp = low_re
    frame = mp.frame
    nodes = np.stack(np.meshgrid(*frame.nodes, indexing="ij"), -1)
    np.testing.assert_allclose(frame.pose(nodes), frame.beta_nodes, atol=1e-12)
    r = np.random.default_rng(3).uniform(-2.4, 2.4, (4, 5, 2))
    fits = [RectBivariateSpline(*frame.nodes, frame.beta_nodes[..., c], kx=5, ky=5, s=0) for c in range(3)]
    fitpack = [np.stack([f.ev(r[..., 0], r[..., 1], dx=dx, dy=dy) for f in fits], -1)
               for dx, dy in ((0, 0), (1, 0), (0, 1))]
    beta, B = frame.pose_and_jacobian(r)
    assert B.shape == (4, 5, 3, 2)
    np.testing.assert_allclose(beta, fitpack[0], rtol=0, atol=1e-11)
    np.testing.assert_allclose(B, body_jacobian(fitpack[0], np.stack(fitpack[1:], -1)), rtol=0, atol=1e-10)
    np.testing.assert_allclose(beta, frame.pose(r), rtol=0, atol=0)
    np.testing.assert_allclose(B, frame.jacobian(r), rtol=0, atol=0)
    h = 1e-5
    dbeta = np.stack([(frame.pose(r + h * e) - frame.pose(r - h * e)) / (2 * h) for e in np.eye(2)], -1)
    np.testing.assert_allclose(B, body_jacobian(beta, dbeta), atol=1e-8)


def test_divergence_and_normal_flux_by_differences(low_re):
    """Independent route: central differences of the new theta row through the spline connection."""
    s, mp = low_re
    h = 1e-4
    a = np.linspace(-2.0, 2.0, 21)
    r = np.stack(np.meshgrid(a, a, indexing="ij"), -1)

    def div(system):
        d1 = (system.connection(r + [h, 0])[..., 2, 0] - system.connection(r - [h, 0])[..., 2, 0]) / (2 * h)
        d2 = (system.connection(r + [0, h])[..., 2, 1] - system.connection(r - [0, h])[..., 2, 1]) / (2 * h)
        return d1 + d2

    assert np.abs(div(mp)).max() < 0.05 * np.abs(div(s)).max()
    edge = np.linspace(-2.5, 2.5, 41)
    for r_e, k in [(np.stack([np.full(41, 2.5), edge], -1), 0), (np.stack([edge, np.full(41, -2.5)], -1), 1)]:
        flux_new = np.abs(mp.connection(r_e)[:, 2, k]).max()
        flux_old = np.abs(s.connection(r_e)[:, 2, k]).max()
        assert flux_new < 0.05 * flux_old


def test_curvature_transforms_by_the_adjoint(low_re):
    s, mp = low_re
    r = np.random.default_rng(3).uniform(-2, 2, (25, 2))
    F_new = constraint_curvature(mp, r, method="fd")  # differences of the new connection
    np.testing.assert_allclose(constraint_curvature(mp, r), F_new, atol=2e-6)  # the covariant route
    F_old = constraint_curvature(s, r)
    expect = np.einsum("...ij,...j->...i", SE2.Ad_inv(mp.beta(r)), F_old)
    np.testing.assert_allclose(F_new, expect, atol=2e-6)
    np.testing.assert_allclose(F_new[:, 2], F_old[:, 2], atol=2e-6)  # theta row unchanged


def test_net_displacement_is_conjugated(low_re):
    s, mp = low_re
    for g in [circle_gait(1.0, (0.3, 0.2)), circle_gait(0.6, (-0.8, 0.5), period=2.0)]:
        b = mp.beta(g(0.0))
        expect = SE2.compose(SE2.compose(SE2.inverse(b), net_displacement(s, g)), b)
        np.testing.assert_allclose(net_displacement(mp, g), expect, atol=1e-9)


def test_stokes_estimate_improves_over_middle_link(low_re):
    s, mp = low_re
    for R in (0.6, 1.4):
        for c in [(0.0, 0.0), (0.4, -0.5)]:
            g = circle_gait(R, c)
            err_mid = np.abs(stokes_estimate(s, g) - net_displacement(s, g))[:2].max()
            err_mp = np.abs(stokes_estimate(mp, g) - net_displacement(mp, g))[:2].max()
            assert err_mp < err_mid


def test_beta_vanishes_at_reference_and_identity_reframe():
    s = HighReSwimmer()
    mp = minimum_perturbation_coordinates(s, ((-1, 2), (-1, 1)), 9)
    assert mp.beta(mp.frame.reference)[2] == pytest.approx(0.0, abs=1e-12)
    same = reframe(s, lambda r: np.zeros(r.shape[:-1] + (3,)))
    r = np.random.default_rng(0).uniform(-1, 1, (5, 2))
    np.testing.assert_allclose(same.connection(r), s.connection(r), atol=1e-9)


def test_centre_of_mass_frame_of_floating_snake_does_not_move():
    """Zero momentum: the centre of mass stays put, so the (x, y) rows vanish in that frame."""
    fs = FloatingSnake(masses=(1.0, 2.0, 1.5), frame="middle")
    com = centre_of_mass_coordinates(fs)
    r = np.random.default_rng(4).uniform(-2, 2, (20, 2))
    A = com.connection(r)
    assert np.abs(A[..., :2, :]).max() < 1e-8
    # its rotation row is the middle link's, shifted by d(mean orientation)/dr
    w = np.array(fs.masses) / sum(fs.masses)
    np.testing.assert_allclose(A[..., 2, :], fs.connection(r)[..., 2, :] - [-w[0], w[2]], atol=1e-8)


def test_drift_and_turn_from_the_world_positions_of_the_links():
    """Independent route: the weighted mean of the links' world positions at the start and the
    end of a cycle (trajectory's frames), for a swimmer (lengths) and the floating snake."""
    from gm_core.systems.motion import trajectory

    for s, gait in ((LowReSwimmer(), circle_gait(0.5, (1.5, 1.5))), (FloatingSnake(), circle_gait(0.4, (0.3, 0.2)))):
        w = np.asarray(getattr(s, "masses", None) or s.lengths, float)
        tr = trajectory(s, gait, n_frames=3)
        com = [(w / w.sum()) @ SE2.compose(tr.g[i][None], s.link_poses(tr.r[i]))[:, :2] for i in (0, 2)]
        turn, drift = drift_and_turn(s, gait)
        assert drift == pytest.approx(np.linalg.norm(com[1] - com[0]), abs=1e-9)
        assert turn == pytest.approx(SE2.log(tr.g[2])[2], abs=1e-9)
    with pytest.raises(TypeError, match="system"):
        drift_and_turn("snake", circle_gait(0.5))


def test_part_poses_move_with_the_frame(low_re):
    s, mp = low_re
    r = np.array([0.4, -0.7])
    P = mp.part_poses(r)
    np.testing.assert_allclose(SE2.compose(mp.beta(r), P), s.part_poses(r), atol=1e-12)


def test_outside_the_rectangle_is_refused(low_re):
    s, mp = low_re
    assert np.all(np.isnan(mp.connection(np.array([3.0, 0.0]))))
    with pytest.raises(SingularShapeError, match="outside the rectangle"):
        net_displacement(mp, circle_gait(1.0, (2.0, 0.0)))


def test_bad_input():
    s = LowReSwimmer()
    with pytest.raises(ValueError, match="bounds must satisfy lo < hi"):
        minimum_perturbation_coordinates(s, ((1, -1), (-1, 1)))
    with pytest.raises(ValueError, match="bounds must have shape"):
        minimum_perturbation_coordinates(s, (-1, 1))
    for n in (0, 2.5, True, "9"):
        with pytest.raises(ValueError, match="n must be an integer"):
            minimum_perturbation_coordinates(s, n=n)
    with pytest.raises(TypeError, match="system"):
        minimum_perturbation_coordinates("swimmer")
    with pytest.raises(SingularShapeError, match="singular"):
        minimum_perturbation_coordinates(KinematicSnake(), ((-1, 1), (-1, 1)), 9)
    with pytest.raises(TypeError, match="beta"):
        reframe(s, np.zeros(3))


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=25, deadline=None)
@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-3, 3), st.floats(-1, 1), st.floats(-1, 1),
       st.floats(-1, 1))
def test_curvature_is_covariant_under_shape_dependent_frames(r1, r2, th, kx, ky, kt):
    """D(-A~) = Ad_{beta^-1} D(-A) for beta(r) = (kx a1 a2, ky sin a1, th + kt a2), by differences of A~."""
    s = LowReSwimmer()

    def beta(r):
        return np.stack([kx * r[..., 0] * r[..., 1], ky * np.sin(r[..., 0]), th + kt * r[..., 1]], -1)

    other = reframe(s, beta)  # Jacobian of beta by central differences inside Reframed
    r = np.array([r1, r2])
    got = constraint_curvature(other, r, method="fd")
    want = SE2.Ad_inv(beta(r)) @ constraint_curvature(s, r)
    # both routes difference twice (beta's Jacobian inside Reframed, then A~): errors reach ~2e-5
    np.testing.assert_allclose(got, want, atol=5e-5 * max(1.0, np.abs(want).max()))


def test_a_reframed_curvature_is_undefined_where_the_base_s_table_is():
    """The granular swimmer's measured table ends inside its window: there the reframed curvature
    is NaN like the base's (no error), elsewhere Ad_{beta^-1} D(-A)."""
    from gm_core.drawing.catalog import lab_system
    from gm_core.geometry.estimates import square_grid

    base = lab_system("three_link_granular")
    mp = minimum_perturbation_coordinates(base, base.shape_limits, 17)
    r = square_grid(base.shape_limits, 17)
    F0, F = constraint_curvature(base, r), constraint_curvature(mp, r)
    holes = ~np.isfinite(F0).all(-1)
    assert holes.any() and (~holes).any()
    assert np.all(np.isnan(F[holes])) and np.all(np.isfinite(F[~holes]))
    Ad = SE2.Ad_inv(mp.beta(r[~holes]))
    np.testing.assert_allclose(F[~holes], np.array([M @ f for M, f in zip(Ad, F0[~holes])]), atol=1e-13)


def test_a_never_singular_system_reframed_is_singular_only_off_the_window():
    """The frame's edge is the only singular set (checked quickly, without the base's Pfaffian)."""
    swimmer = LowReSwimmer()
    mp = minimum_perturbation_coordinates(swimmer, ((-1.0, 1.0), (-1.0, 1.0)), 9)
    assert mp.may_be_singular and not swimmer.may_be_singular
    r = np.array([[0.0, 0.0], [0.9, -0.9], [1.2, 0.0], [0.0, -1.5]])
    np.testing.assert_array_equal(mp.singularity(r), [1.0, 1.0, 0.0, 0.0])
    np.testing.assert_array_equal(mp.is_singular(r), [False, False, True, True])
    from gm_core.systems.motion import check_gait

    check_gait(mp, circle_gait((0.8, 0.8)))
    with pytest.raises(SingularShapeError):
        check_gait(mp, circle_gait((0.8, 0.8), (0.5, 0.0)))

"""Frames of chapter 2 by independent routes: relative poses (2.iii)-(2.iv), pinned bodies (fig. 2.1),
the velocity of a generalized body frame split into its causes (2.60)-(2.67), and Jacobian columns
carried out along a chain (2.33)-(2.37)."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import SE2, SO2, RPlus
from gm_core import chains as C
from gm_core.chains.holonomic import pin_constraints, pinned_pair
from gm_core.chains.three_link import beta_frame_velocity, com_frame

EPS = 1e-6
seeds = st.integers(0, 2**31 - 1)


# --------------------------------------------------------------------- relative poses (2.iii)
@settings(max_examples=60, deadline=None)
@given(seeds)
def test_relative_pose_is_inverse_times_pose_in_matrices(seed):
    rng = np.random.default_rng(seed)
    g, h = SE2.random(rng, 2)
    # independent route: homogeneous matrices, h^-1 g = inv(H) @ G
    M = np.linalg.inv(SE2.matrix(h)) @ SE2.matrix(g)
    assert SE2.isclose(C.relative_pose(g, h), SE2.from_matrix(M), atol=1e-10)


@settings(max_examples=60, deadline=None)
@given(seeds)
def test_relative_pose_cancellation_rules(seed):
    rng = np.random.default_rng(seed)
    a, b, c = SE2.random(rng, 3)
    # (2.iv): the frame in the middle cancels, g_{b,c} g_{a,b} = g_{a,c}
    chained = SE2.compose(C.relative_pose(b, c), C.relative_pose(a, b))
    assert SE2.isclose(chained, C.relative_pose(a, c), atol=1e-10)
    # the inverse swaps the subscripts: g_{a,b}^-1 = g_{b,a}
    assert SE2.isclose(SE2.inverse(C.relative_pose(a, b)), C.relative_pose(b, a), atol=1e-10)
    # no second subscript means "seen from the origin": g_{a,e} = a
    assert SE2.isclose(C.relative_pose(a, SE2.identity()), a, atol=1e-12)
    # the world pose is recovered from a relative one: b g_{a,b} = a
    assert SE2.isclose(SE2.compose(b, C.relative_pose(a, b)), a, atol=1e-10)


def test_relative_pose_order_matters_and_other_groups():
    rng = np.random.default_rng(1)
    a, b, c = SE2.random(rng, 3)
    wrong = SE2.compose(C.relative_pose(a, b), C.relative_pose(b, c))   # the frames do not meet
    assert not SE2.isclose(wrong, C.relative_pose(a, c), atol=1e-3)
    x, y = np.array([3.0]), np.array([0.5])
    np.testing.assert_allclose(C.relative_pose(x, y, group=RPlus), [6.0])
    np.testing.assert_allclose(C.relative_pose(np.array([0.3]), np.array([1.0]), group=SO2), [-0.7])


def test_relative_pose_bad_input():
    with pytest.raises(ValueError, match="base"):
        C.relative_pose([0, 0, 0], [1, 2])
    with pytest.raises(TypeError, match="g"):
        C.relative_pose("frame", [0, 0, 0])


# --------------------------------------------------------------------- pinned bodies, fig. 2.1
@settings(max_examples=40, deadline=None)
@given(seeds)
def test_pinned_pair_satisfies_the_pin_and_keeps_alpha(seed):
    rng = np.random.default_rng(seed)
    g = SE2.random(rng)
    alpha = rng.uniform(-np.pi, np.pi)
    g1, g2 = pinned_pair(g, alpha)
    np.testing.assert_allclose(pin_constraints(g1, g2), 0.0, atol=1e-12)
    np.testing.assert_allclose(g1, g)
    # independent route: body 2's frame is body 1's frame turned by alpha about the common origin
    R = SE2.matrix(g1)[:2, :2] @ np.array([[np.cos(alpha), -np.sin(alpha)], [np.sin(alpha), np.cos(alpha)]])
    np.testing.assert_allclose(SE2.matrix(g2)[:2, :2], R, atol=1e-12)
    assert SE2.isclose(C.relative_pose(g2, g1), np.array([0.0, 0.0, alpha]), atol=1e-12)


def test_pin_constraints_values_and_batching():
    rng = np.random.default_rng(2)
    g1, g2 = SE2.random(rng, (2, 4))
    f = pin_constraints(g1, g2)
    assert f.shape == (4, 2)
    np.testing.assert_allclose(f, g1[:, :2] - g2[:, :2])
    assert pinned_pair(g1, np.zeros(4)).shape == (4, 2, 3)
    with pytest.raises(ValueError, match="g2"):
        pin_constraints([0, 0, 0], [0, 0])


# ----------------------------------------------------- velocity of a generalized body frame
def _fd_body(g_of_t):
    return SE2.world_to_body(g_of_t(0.0), SE2.difference(g_of_t(EPS), g_of_t(-EPS)) / (2 * EPS))


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-2.5, 2.5), min_size=2, max_size=2),
       st.lists(st.floats(0.3, 2.0), min_size=3, max_size=3), seeds)
def test_beta_frame_velocity_parts_match_finite_differences(alpha, lengths, seed):
    rng = np.random.default_rng(seed)
    alpha = np.array(alpha)
    g0, xi, alpha_dot = SE2.random(rng), rng.uniform(-1, 1, 3), rng.uniform(-1, 1, 2)
    beta, dbeta = com_frame(alpha, lengths)
    parts = beta_frame_velocity(beta, dbeta, xi, alpha_dot)

    def frame(xi_, ad_):   # g(t) = g0 exp(t xi) beta(alpha + t alpha_dot)
        return lambda t: SE2.compose(SE2.compose(g0, SE2.exp(t * xi_)), com_frame(alpha + t * ad_, lengths)[0])

    np.testing.assert_allclose(parts["body"], _fd_body(frame(xi, alpha_dot)), atol=1e-7)
    np.testing.assert_allclose(parts["carried"], _fd_body(frame(xi, 0 * alpha_dot)), atol=1e-7)  # shape frozen
    np.testing.assert_allclose(parts["shape"], _fd_body(frame(0 * xi, alpha_dot)), atol=1e-7)    # base link still
    # (2.61): v_beta is the spatial velocity of beta relative to the base link, beta_dot beta^-1
    b = lambda t: com_frame(alpha + t * alpha_dot, lengths)[0]
    Bdot = (SE2.matrix(b(EPS)) - SE2.matrix(b(-EPS))) / (2 * EPS)
    np.testing.assert_allclose(SE2.hat(parts["v_beta"]), Bdot @ np.linalg.inv(SE2.matrix(b(0.0))), atol=1e-7)


def test_beta_frame_velocity_bad_input():
    beta, dbeta = com_frame([0.3, 0.4])
    with pytest.raises(ValueError, match="alpha_dot"):
        beta_frame_velocity(beta, dbeta, [0, 0, 1], [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="xi_base"):
        beta_frame_velocity(beta, dbeta, [0, 1], [1.0, 2.0])


# ------------------------------------------------------- Jacobian columns carried to the tip
@settings(max_examples=30, deadline=None)
@given(st.integers(1, 5), seeds)
def test_transported_columns_match_every_frame_and_finite_differences(n, seed):
    rng = np.random.default_rng(seed)
    ch = C.Chain(rng.choice(["R", "P"], n), rng.uniform(0.2, 2.0, n), offsets=rng.uniform(-0.5, 0.5, n))
    q = rng.uniform(-3, 3, n)
    frames, cols = C.transported_columns(ch, q)
    body = ch.jacobians(q, method="direct", velocity="body")
    for i in range(n):
        np.testing.assert_allclose(frames[2 * i], ch.frames(q)["f"][i])
        np.testing.assert_allclose(cols[:, 2 * i + 1].T, body["h"][i], atol=1e-10)
        np.testing.assert_allclose(cols[:, 2 * i].T, body["f"][i], atol=1e-10)
    # independent route: finite differences of the end effector, one joint at a time
    J_fd = C.finite_difference_jacobians(ch.end_effector, q)
    np.testing.assert_allclose(SE2.body_to_world(frames[-1], cols[:, -1]).T, J_fd, atol=1e-7)


def test_transported_columns_batch_and_bad_input():
    ch = C.Chain("RPR", (1.0, 0.5, 0.7))
    q = np.random.default_rng(3).uniform(-1, 1, (4, 3))
    frames, cols = C.transported_columns(ch, q)
    assert frames.shape == (4, 6, 3) and cols.shape == (4, 3, 6, 3)
    np.testing.assert_allclose(cols[2], C.transported_columns(ch, q[2])[1])
    assert np.all(cols[:, 2, :4] == 0)          # frames before joint 3 do not move with it
    with pytest.raises(TypeError, match="chain"):
        C.transported_columns(C.MobileChain((1, 1, 1)), [0.1, 0.2])
    with pytest.raises(ValueError, match="alpha"):
        C.transported_columns(ch, [0.1, 0.2])

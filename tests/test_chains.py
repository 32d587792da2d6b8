"""Tests for gm_core.chains: forward kinematics and Jacobians of chapter 2, checked by independent routes."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import SE2
from gm_core import chains as C
from gm_core.chains.arms import (
    rp_arm_body_jacobians,
    rp_arm_frames,
    rr_arm_frames,
    rr_arm_jacobian,
    single_link_frames,
)
from gm_core.chains.holonomic import (
    accessible_circle,
    circle_constraints,
    sample_accessible_manifold,
    sphere_plane_constraints,
)
from gm_core.chains.three_link import (
    com_frame,
    com_frame_jacobians,
    three_link_chain,
    three_link_frames,
    three_link_jacobians,
    three_link_poses,
)

EPS = 1e-6


def fd_body_velocity(pose_fn, g0, alpha, xi, alpha_dot, eps=EPS):
    """Body velocity of pose_fn(g, alpha) along g(t) = g0 exp(t xi), alpha(t) = alpha + t alpha_dot."""
    def at(t):
        return pose_fn(SE2.compose(g0, SE2.exp(t * xi)), alpha + t * alpha_dot)

    g_dot = SE2.difference(at(eps), at(-eps)) / (2 * eps)
    return SE2.world_to_body(at(0.0), g_dot)


# ----------------------------------------------------------------- three-link system, (2.46)-(2.59)
def test_three_link_jacobians_shapes_and_batching():
    rng = np.random.default_rng(0)
    a = rng.uniform(-2, 2, (4, 5, 2))
    J = three_link_jacobians(a, (1.0, 2.0, 0.5))
    assert len(J) == 3
    for Ji in J:
        assert Ji.shape == (4, 5, 3, 5)
    single = three_link_jacobians(a[2, 3], (1.0, 2.0, 0.5))
    for Ji, Si in zip(J, single):
        np.testing.assert_allclose(Ji[2, 3], Si, atol=1e-15)
    np.testing.assert_array_equal(J[1][0, 0], np.hstack([np.eye(3), np.zeros((3, 2))]))  # (2.46)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-3, 3), min_size=2, max_size=2),
       st.lists(st.floats(0.2, 3.0), min_size=3, max_size=3),
       st.integers(0, 2**31 - 1))
def test_three_link_jacobians_match_finite_differences(alpha, lengths, seed):
    rng = np.random.default_rng(seed)
    alpha = np.array(alpha)
    g0 = SE2.random(rng)
    xi = rng.normal(size=3)
    alpha_dot = rng.normal(size=2)
    J = three_link_jacobians(alpha, lengths)
    u = np.concatenate([xi, alpha_dot])
    for i in range(3):
        def pose(g, a, i=i):
            return three_link_frames(a, lengths, g)["g"][..., i, :]

        expected = fd_body_velocity(pose, g0, alpha, xi, alpha_dot)
        np.testing.assert_allclose(J[i] @ u, expected, atol=1e-7)


def test_three_link_sign_convention():
    # alpha1 = rotation of link 2 relative to link 1, so link 1 sits at -alpha1; link 3 at +alpha2 (fig. 2.6)
    fr = three_link_frames([0.3, 0.5], (1.0, 1.0, 1.0))
    np.testing.assert_allclose(fr["g"][..., 2], [-0.3, 0.0, 0.5], atol=1e-15)
    # joints coincide: h1 and f2 at the same point, h2 and f3 at the same point
    np.testing.assert_allclose(fr["h"][0, :2], fr["f"][1, :2], atol=1e-15)
    np.testing.assert_allclose(fr["h"][1, :2], fr["f"][2, :2], atol=1e-15)
    np.testing.assert_allclose(fr["joints"], [fr["f"][1, :2], fr["f"][2, :2]], atol=1e-15)
    # even shape (alpha1 = alpha2, a C): bilateral mirror symmetry about the middle link's y axis, fig 2.6
    fr = three_link_frames([0.7, 0.7], (1.0, 2.0, 1.0))
    np.testing.assert_allclose(fr["g"][0, :2] * [-1, 1], fr["g"][2, :2], atol=1e-14)
    # odd shape (alpha1 = -alpha2, an S): point symmetry about the middle link's centre
    fr = three_link_frames([0.7, -0.7], (1.0, 2.0, 1.0))
    np.testing.assert_allclose(-fr["g"][0, :2], fr["g"][2, :2], atol=1e-14)


def test_three_link_draft_errata():
    alpha, L = np.array([0.4, -0.9]), (1.0, 1.5, 0.8)
    J1, _, J3 = three_link_jacobians(alpha, L)
    np.testing.assert_allclose(J3[2], [0, 0, 1, 0, 1])    # draft (2.59) prints (0, 0, 1, 1, 0)
    np.testing.assert_allclose(J1[2], [0, 0, 1, -1, 0])
    xi = np.array([0.3, -0.2, 0.7])
    u = np.concatenate([xi, [0.5, 0.1]])
    s1 = np.sin(alpha[0])
    right = xi[0] * np.cos(alpha[0]) - (xi[1] - xi[2] * L[1] / 2) * s1
    draft = xi[0] * np.cos(alpha[0]) - (xi[1] + xi[2] * L[1] / 2) * s1   # (2.51) row 1 sign
    assert abs((J1 @ u)[0] - right) < 1e-14
    assert abs((J1 @ u)[0] - draft) > 1e-3


def test_three_link_bad_input():
    with pytest.raises(ValueError, match="alpha"):
        three_link_jacobians([0.1, 0.2, 0.3], (1, 1, 1))
    with pytest.raises(ValueError, match="lengths"):
        three_link_jacobians([0.1, 0.2], (1, 1))
    with pytest.raises(ValueError, match="lengths"):
        three_link_jacobians([0.1, 0.2], (1, -1, 1))
    with pytest.raises(TypeError, match="alpha"):
        three_link_jacobians("ab", (1, 1, 1))


@pytest.mark.parametrize("method", C.METHODS)
def test_three_link_generic_methods_agree_with_closed_form(method):
    rng = np.random.default_rng(3)
    a = rng.uniform(-3, 3, (20, 2))
    L = (0.7, 1.2, 1.9)
    J = three_link_jacobians(a, L)
    Jg = three_link_chain(L).body_jacobians(a, method=method)
    for i in range(3):
        np.testing.assert_allclose(Jg[..., i, :, :], J[i], atol=1e-12)


# ----------------------------------------------------------------- fixed-base chains
chain_strategy = st.integers(1, 5).flatmap(lambda n: st.tuples(
    st.lists(st.sampled_from(["R", "P"]), min_size=n, max_size=n),
    st.lists(st.floats(0.1, 3.0), min_size=n, max_size=n),
    st.lists(st.floats(-1.0, 1.0), min_size=n, max_size=n),
    st.lists(st.floats(-3.0, 3.0), min_size=n, max_size=n),
))


@settings(max_examples=60, deadline=None)
@given(chain_strategy)
def test_three_methods_agree_and_match_finite_differences(spec):
    joints, lengths, offsets, alpha = spec
    ch = C.Chain(joints, lengths, offsets=offsets)
    alpha = np.array(alpha)
    J = {m: ch.jacobians(alpha, method=m) for m in C.METHODS}
    for frame in "fgh":
        for m in ("world", "body"):
            np.testing.assert_allclose(J[m][frame], J["direct"][frame], atol=1e-10)
        fd = C.finite_difference_jacobians(lambda a: ch.frames(a)[frame], alpha)
        np.testing.assert_allclose(J["direct"][frame], fd, atol=1e-7)


@settings(max_examples=30, deadline=None)
@given(st.integers(2, 5), st.integers(0, 2**31 - 1))
def test_mobile_chain_methods_agree_and_match_fd(n_links, seed):
    rng = np.random.default_rng(seed)
    joints = list(rng.choice(["R", "P"], n_links - 1))
    lengths = rng.uniform(0.2, 2.0, n_links)
    base = int(rng.integers(0, n_links))
    ch = C.MobileChain(lengths, joints, base_link=base)
    alpha = rng.uniform(-2, 2, n_links - 1)
    Jb = {m: ch.jacobians(alpha, method=m, velocity="body") for m in C.METHODS}
    for m in ("world", "body"):
        for frame in "fgh":
            np.testing.assert_allclose(Jb[m][frame], Jb["direct"][frame], atol=1e-10)
    g0 = SE2.random(rng)
    u = rng.normal(size=3 + n_links - 1)
    for frame in "fgh":
        expected = fd_body_velocity(lambda g, a: ch.frames(a, g)[frame], g0, alpha, u[:3], u[3:])
        np.testing.assert_allclose(np.einsum("kij,j->ki", Jb["body"][frame], u), expected, atol=1e-7)


def test_forward_kinematics_rr_arm_matches_book():
    a1, a2, l1, l2 = 0.3, -1.1, 1.2, 0.7
    fr = rr_arm_frames([a1, a2], (l1, l2))
    np.testing.assert_allclose(fr[1], [l1 * np.cos(a1), l1 * np.sin(a1), a1])   # (2.4)
    np.testing.assert_allclose(fr[2], [l1 * np.cos(a1), l1 * np.sin(a1), a1 + a2])   # (2.5)
    np.testing.assert_allclose(fr[3], [l1 * np.cos(a1) + l2 * np.cos(a1 + a2),
                                       l1 * np.sin(a1) + l2 * np.sin(a1 + a2), a1 + a2])   # (2.7)
    ch = C.Chain("RR", (l1, l2))
    np.testing.assert_allclose(rr_arm_jacobian([a1, a2], (l1, l2)),
                               C.finite_difference_jacobians(ch.end_effector, np.array([a1, a2])), atol=1e-8)


def test_single_link_and_two_link_mobile_13():
    g, h = single_link_frames(0.4, 2.0)
    np.testing.assert_allclose(h, [2 * np.cos(0.4), 2 * np.sin(0.4), 0.4])   # (2.4)
    a, l1, l2 = 0.8, 1.0, 1.6
    fr = C.MobileChain((l1, l2), base_link=0).frames([a])
    np.testing.assert_allclose(fr["g"][1], [l1 / 2 + l2 / 2 * np.cos(a), l2 / 2 * np.sin(a), a], atol=1e-15)


def test_rp_arm_frames_and_body_jacobians():
    rng = np.random.default_rng(5)
    for offset in (0.0, 0.35):
        alpha, delta = rng.uniform(-2, 2, 6), rng.uniform(0, 1, 6)
        l1, l2 = 1.1, 0.6
        fr = rp_arm_frames(alpha, delta, l1, l2, offset)
        if offset == 0.0:   # (2.10)-(2.11)
            r = l1 + delta
            np.testing.assert_allclose(fr["g2"], np.stack([r * np.cos(alpha), r * np.sin(alpha), alpha], -1))
            r = l1 + delta + l2
            np.testing.assert_allclose(fr["h2"], np.stack([r * np.cos(alpha), r * np.sin(alpha), alpha], -1))
        J = rp_arm_body_jacobians(alpha, delta, l1, l2, offset)
        q = np.stack([alpha, delta], -1)
        # g2' is the link-2 frame momentarily aligned with h1: xi_g2' = xi_h1 + (delta_dot, 0, 0), (2.43)
        np.testing.assert_allclose(J["g2p"], J["h1"] + np.array([[0, 1.0], [0, 0], [0, 0]]))
        for key in ("g1", "h1", "g2", "h2"):
            def pose(x, key=key):
                return rp_arm_frames(x[..., 0], x[..., 1], l1, l2, offset)[key]

            Jw = C.finite_difference_jacobians(pose, q)
            np.testing.assert_allclose(J[key], C.world_to_body_jacobian(fr[key], Jw), atol=1e-8)
        # the generic chain with the same geometry: f2 of Chain("RP") is the book's g2 (2.10)
        ch = C.Chain("RP", (l1, l2), offsets=(offset, 0.0))
        Jc = ch.jacobians(q, velocity="body")
        np.testing.assert_allclose(Jc["f"][..., 1, :, :], J["g2"], atol=1e-12)
        np.testing.assert_allclose(Jc["h"][..., 1, :, :], J["h2"], atol=1e-12)
    Jh = rp_arm_body_jacobians(0.3, 0.2, 1.0, 1.0)["h1"]
    np.testing.assert_allclose(Jh[:, 0], [0, 1.0, 1.0])   # (2.41): (0, l1, 1), not (0, 0, l1)


def test_bad_input_messages():
    with pytest.raises(ValueError, match="joints"):
        C.Chain(["R", "Q"], (1, 1))
    with pytest.raises(ValueError, match="joints"):
        C.Chain("RX", (1, 1))
    with pytest.raises(ValueError, match="lengths"):
        C.Chain("RR", (1, 0))
    with pytest.raises(ValueError, match="lengths"):
        C.Chain("RR", (1, 1, 1))
    ch = C.Chain("RPR", (1, 1, 1))
    with pytest.raises(ValueError, match="alpha"):
        ch.frames([0.1, 0.2])
    with pytest.raises(ValueError, match="alpha"):
        ch.jacobians(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="method"):
        ch.jacobians([0, 0, 0], method="magic")
    with pytest.raises(ValueError, match="base_link"):
        C.MobileChain((1, 1), base_link=3)
    with pytest.raises(ValueError, match="alpha"):
        three_link_frames([0.1], (1, 1, 1))


def test_batched_frames_match_loop():
    rng = np.random.default_rng(7)
    ch = C.Chain("RPRR", (1, 0.5, 0.7, 0.3))
    alpha = rng.normal(size=(3, 4, 4))
    fr = ch.frames(alpha)
    assert fr["h"].shape == (3, 4, 4, 3)
    J = ch.jacobians(alpha)
    assert J["g"].shape == (3, 4, 4, 3, 4)
    np.testing.assert_allclose(ch.frames(alpha[1, 2])["h"], fr["h"][1, 2])
    np.testing.assert_allclose(ch.jacobians(alpha[1, 2])["h"], J["h"][1, 2])


# ----------------------------------------------------------------- generalized body frames, (2.60)-(2.69)
def test_com_frame_matches_definition_and_fd():
    rng = np.random.default_rng(11)
    L = (0.8, 1.0, 1.4)
    alpha = rng.uniform(-2, 2, (8, 2))
    beta, dbeta = com_frame(alpha, L)
    fr = three_link_frames(alpha, L)
    w = np.array(L) / sum(L)
    np.testing.assert_allclose(beta[..., :2], np.einsum("i,...ij->...j", w, fr["g"][..., :2]), atol=1e-14)
    np.testing.assert_allclose(beta[..., 2], np.einsum("i,...i->...", w, fr["g"][..., 2]), atol=1e-14)
    fd = C.finite_difference_jacobians(lambda a: com_frame(a, L)[0][..., None, :], alpha)[..., 0, :, :]
    np.testing.assert_allclose(dbeta, fd, atol=1e-8)


def test_beta_frame_and_links_from_beta_match_fd():
    rng = np.random.default_rng(12)
    L = (1.0, 0.6, 1.3)
    for _ in range(5):
        alpha = rng.uniform(-2, 2, 2)
        g0 = SE2.random(rng)
        xi, ad = rng.normal(size=3), rng.normal(size=2)
        J_com, links = com_frame_jacobians(alpha, L)

        def com_pose(g, a):
            return SE2.compose(g, com_frame(a, L)[0])

        xi_com = fd_body_velocity(com_pose, g0, alpha, xi, ad)
        np.testing.assert_allclose(J_com @ np.concatenate([xi, ad]), xi_com, atol=1e-7)   # (2.62)
        # (2.68): the same motion described by (xi_com, alpha_dot) gives the same link velocities
        J = three_link_jacobians(alpha, L)
        for Ji, Ki in zip(J, links):
            np.testing.assert_allclose(Ki @ np.concatenate([xi_com, ad]), Ji @ np.concatenate([xi, ad]), atol=1e-7)
        # (2.63) and (2.66) expand the same Jacobian
        beta, dbeta = com_frame(alpha, L)
        bx, by, bt = beta
        c, s = np.cos(bt), np.sin(bt)
        A = np.array([[c, s, bx * s - by * c], [-s, c, bx * c + by * s], [0, 0, 1]])
        T = np.array([[1, 0, by], [0, 1, -bx], [0, 0, 1]])
        np.testing.assert_allclose(J_com, np.hstack([A, A @ T @ dbeta]), atol=1e-13)
        TL = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])
        TRe = np.array([[1, 0, -by], [0, 1, bx], [0, 0, 1]])
        np.testing.assert_allclose(J_com, np.hstack([TL @ TRe, TL @ dbeta]), atol=1e-13)


# ----------------------------------------------------------------- holonomic constraints box
def test_accessible_manifold_samples():
    pts = sample_accessible_manifold(circle_constraints, n=100)
    assert len(pts) > 80
    np.testing.assert_allclose(pts[:, 2], 1.0, atol=1e-9)
    np.testing.assert_allclose(np.hypot(pts[:, 0], pts[:, 1]), 1.0, atol=1e-9)
    # exercise 2.1: a sphere about the origin and the plane give the same circle
    pts2 = sample_accessible_manifold(sphere_plane_constraints, n=100, rng=np.random.default_rng(1))
    np.testing.assert_allclose(circle_constraints(pts2), 0.0, atol=1e-8)
    circ = accessible_circle(50)
    np.testing.assert_allclose(circle_constraints(circ), 0.0, atol=1e-14)
    np.testing.assert_allclose(sphere_plane_constraints(circ), 0.0, atol=1e-14)


# ----------------------------------------------------------------- the matrices printed in section 2.5
def test_world_iterative_matrices_of_225_and_229():
    a1, a2, l1, l2 = 0.4, 1.3, 1.2, 0.9
    fr = rr_arm_frames([a1, a2], (l1, l2))
    g1, h1, g2, h2 = fr
    # (2.24)-(2.25): h1_dot = (T_e R_h1)(T_g1 R_g1^-1) g1_dot, with g1_dot = (0, 0, a1_dot)
    M = SE2.right_lifted_action(h1, SE2.identity()) @ SE2.right_lifted_action(SE2.inverse(g1), g1)
    np.testing.assert_allclose(M, [[1, 0, -l1 * np.sin(a1)], [0, 1, l1 * np.cos(a1)], [0, 0, 1]], atol=1e-15)
    # (2.29): the two factors printed for the second link
    A = SE2.right_lifted_action(h2, SE2.identity())
    B = SE2.right_lifted_action(SE2.inverse(g2), g2)
    np.testing.assert_allclose(A[:2, 2], [-(l1 * np.sin(a1) + l2 * np.sin(a1 + a2)), l1 * np.cos(a1) + l2 * np.cos(a1 + a2)])
    np.testing.assert_allclose(B[:2, 2], [l1 * np.sin(a1), -l1 * np.cos(a1)])
    J_g2 = np.array([[-l1 * np.sin(a1), 0], [l1 * np.cos(a1), 0], [1, 1]])   # (2.28)
    np.testing.assert_allclose(A @ B @ J_g2, rr_arm_jacobian([a1, a2], (l1, l2)), atol=1e-14)   # (2.30)


@settings(max_examples=30, deadline=None)
@given(st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3), st.floats(-3, 3))
def test_change_of_basis_box_and_exercise_2_4(x, y, tg, th):
    # Ad_h^-1 Ad_g is a pure rotation by -(th - tg) when g and h share x and y, (2.vi)-(2.viii)
    g, h = np.array([x, y, tg]), np.array([x, y, th])
    d = th - tg
    R = np.array([[np.cos(d), np.sin(d), 0], [-np.sin(d), np.cos(d), 0], [0, 0, 1]])
    np.testing.assert_allclose(SE2.Ad_inv(h) @ SE2.Ad(g), R, atol=1e-12)
    np.testing.assert_allclose(SE2.Ad_inv(SE2.compose(SE2.inverse(g), h)), R, atol=1e-12)


def test_joint_elements():
    assert C.Joint("R") == C.Joint("revolute") and C.Joint("p").kind == "prismatic"
    np.testing.assert_allclose(C.Joint("R").element(0.3), [0, 0, 0.3])
    np.testing.assert_allclose(C.Joint("P").element([0.3, 0.5]), [[0.3, 0, 0], [0.5, 0, 0]])
    # a joint element is exp(q X): the one-parameter subgroup of its axis
    for j in (C.Joint("R"), C.Joint("P")):
        np.testing.assert_allclose(SE2.exp(0.7 * j.axis), j.element(0.7), atol=1e-15)


# ------------------------------------------------------------------ link-centre poses (one copy)
def test_three_link_poses_are_the_chain_product():
    rng = np.random.default_rng(12)
    L = (0.9, 1.3, 0.6)
    a = rng.uniform(-3, 3, (7, 2))
    P = three_link_poses(a, L)
    for k in range(7):
        a1, a2 = a[k]
        g1 = SE2.compose(SE2.compose([-L[1] / 2, 0, 0], [0, 0, -a1]), [-L[0] / 2, 0, 0])   # (2.12), walking back
        g3 = SE2.compose(SE2.compose([L[1] / 2, 0, 0], [0, 0, a2]), [L[2] / 2, 0, 0])
        assert SE2.isclose(P[k], np.stack([g1, np.zeros(3), g3]), atol=1e-14).all()
    # the centre-of-mass frame is the weighted mean of these poses
    beta, _ = com_frame(a, L, weights=(1.0, 2.0, 3.0))
    np.testing.assert_allclose(beta, np.einsum("i,...ij->...j", np.array([1, 2, 3]) / 6, P), atol=1e-15)


def test_three_link_poses_and_sampling_bad_input():
    with pytest.raises(ValueError, match="alpha"):
        three_link_poses([0.1, 0.2, 0.3])
    with pytest.raises(ValueError, match="lengths"):
        three_link_poses([0.1, 0.2], (1, 1))
    with pytest.raises(TypeError, match="alpha"):
        com_frame(None)
    with pytest.raises(TypeError, match="n must be an integer"):
        sample_accessible_manifold(circle_constraints, n=2.5)
    with pytest.raises(ValueError, match="box"):
        sample_accessible_manifold(circle_constraints, box=-1)
    with pytest.raises(TypeError, match="rng"):
        sample_accessible_manifold(circle_constraints, rng=3)

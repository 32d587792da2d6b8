"""Chapter 2 checkers: references against gm_core.chains (three-way Jacobians) and finite differences."""
import numpy as np
import pytest
import sympy as sp
from checkhelpers import assert_check_failed, assert_check_passed

from gm_core import SE2, chains
from gm_core.chains.arms import rp_arm_body_jacobians
from gm_core.chains.three_link import three_link_jacobians
from gm_core.checks.ex2 import ex2_1, ex2_2, ex2_3, ex2_4
from gm_core.checks.keys import ex2 as key2

pytestmark = pytest.mark.usefixtures("clean")


def test_constraint_answers_in_several_forms():
    x, y, z = sp.symbols("x y z", real=True)
    assert_check_passed(ex2_1.a, (x**2 + y**2 + z**2 - 2, z - 1))
    assert_check_passed(ex2_1.a, (sp.sqrt(x**2 + y**2 + z**2) - sp.sqrt(2), 1 - z))
    assert_check_passed(ex2_1.a, (lambda x, y, z: x*x + y*y + z*z - 2, lambda x, y, z: z - 1))
    assert_check_failed(ex2_1.a, (x**2 + y**2 + z**2 - 1, z - 1), mentions="radius 1")
    assert_check_failed(ex2_1.a, (x**2 + y**2 + z**2 - 2, z**2 - 1), mentions="z = -1")
    assert_check_failed(ex2_1.a, (x**2 + y**2 - 1, z - 1))   # first constraint not a sphere


def test_rp_arm_references_against_chains_and_finite_differences():
    for args in ex2_2.a.inputs():
        alpha, delta, l1, l2, a = args
        chain = chains.Chain("RP", [l1, l2], offsets=[a, 0.0])
        q = np.array([alpha, delta])
        assert np.allclose(chain.jacobians(q, method="world")["h"][-1], ex2_2.a.ref(*args))
        assert np.allclose(rp_arm_body_jacobians(*args)["h2"], ex2_2.b.ref(*args))
        eps = 1e-6
        fd = np.stack([(chain.end_effector(q + eps * e) - chain.end_effector(q - eps * e)) / (2 * eps)
                       for e in np.eye(2)], 1)
        assert np.allclose(fd, ex2_2.a.ref(*args), atol=1e-6)


def link_poses(alpha, lengths):
    """Independent route: link-centre poses relative to the middle link, composed in the group."""
    a1, a2 = alpha
    l1, l2, l3 = lengths
    p1 = SE2.compose(SE2.compose([-l2 / 2, 0, 0], [0, 0, -a1]), [-l1 / 2, 0, 0])
    p3 = SE2.compose(SE2.compose([l2 / 2, 0, 0], [0, 0, a2]), [l3 / 2, 0, 0])
    return np.stack([p1, np.zeros(3), p3])


def test_com_frame_references_against_group_compositions():
    for alpha, lengths in ex2_3.a.inputs():
        w = np.asarray(lengths, dtype=float)
        assert np.allclose(key2.com_beta(alpha, lengths), (w[:, None] * link_poses(alpha, lengths)).sum(0) / w.sum())
        eps = 1e-6
        fd = np.stack([(key2.com_beta(alpha + eps * e, lengths) - key2.com_beta(alpha - eps * e, lengths)) / (2 * eps)
                       for e in np.eye(2)], 1)
        assert np.allclose(key2.com_dbeta(alpha, lengths), fd, atol=1e-6)
        J = key2.three_link_body_jacobians(alpha, lengths)
        assert J.shape == (3, 3, 5)
        assert np.allclose(J, np.stack(three_link_jacobians(alpha, lengths)))


def test_com_jacobian_by_finite_differences():
    rng = np.random.default_rng(5)
    for _ in range(5):
        xi, alpha, adot, lengths = rng.normal(size=3), rng.uniform(-1.5, 1.5, 2), rng.normal(size=2), rng.uniform(0.5, 2, 3)

        def pose(t):
            return SE2.compose(SE2.exp(t * xi), key2.com_beta(alpha + t * adot, lengths))
        eps = 1e-6
        g_dot = (pose(eps) - pose(-eps)) / (2 * eps)
        body = SE2.world_to_body(pose(0.0), g_dot)
        assert np.allclose(key2.com_jacobian(alpha, lengths) @ np.r_[xi, adot], body, atol=1e-6)


def test_link_jacobians_in_com_frame_by_finite_differences():
    rng = np.random.default_rng(6)
    for _ in range(3):
        xi, alpha, adot, lengths = rng.normal(size=3), rng.uniform(-1.5, 1.5, 2), rng.normal(size=2), rng.uniform(0.5, 2, 3)

        def link_world(t, i):
            g_com = SE2.exp(t * xi)
            a = alpha + t * adot
            middle = SE2.compose(g_com, SE2.inverse(key2.com_beta(a, lengths)))
            return SE2.compose(middle, link_poses(a, lengths)[i])
        eps = 1e-6
        J = key2.links_from_com(alpha, lengths)
        for i in range(3):
            g_dot = (link_world(eps, i) - link_world(-eps, i)) / (2 * eps)
            assert np.allclose(J[i] @ np.r_[xi, adot], SE2.world_to_body(link_world(0.0, i), g_dot), atol=1e-6)


def test_change_of_basis_reference():
    for x, y, tg, th in ex2_4.a.inputs():
        assert np.allclose(ex2_4.a.ref(x, y, tg, th), SE2.Ad_inv([x, y, th]) @ SE2.Ad([x, y, tg]))
    X, Y, TG, TH = sp.symbols("x y theta_g theta_h", real=True)
    d = TH - TG
    M = sp.Matrix([[sp.cos(d), sp.sin(d), 0], [-sp.sin(d), sp.cos(d), 0], [0, 0, 1]])
    assert_check_passed(ex2_4.a, M)
    assert "wrong way" in ex2_4.a.check(M.T, quiet=True).message
    assert ex2_4.a.key.reference_factory is not None          # the sympy reference, built when asked
    assert_check_passed(ex2_4.a, ex2_4.a.reference)


def test_links_answer_as_a_tuple_of_three():
    f = lambda al, le: tuple(key2.links_from_com(al, le))
    assert_check_passed(ex2_3.c, f)


def test_hint_2_of_2_2b_states_where_h2_sits_as_the_frames_say():
    """The hint names h2's pose seen from the rotary joint's frame g1: (l1 + delta + l2, a, 0)."""
    assert "(l1 + delta + l2, a, 0)" in ex2_2.b.hint_text(2)
    al, de, l1, l2, a = 0.7, 0.3, 1.1, 0.8, 0.25
    g1 = np.array([0.0, 0.0, al])
    h2 = SE2.compose(SE2.compose(g1, [l1, a, 0.0]), [de + l2, 0.0, 0.0])
    np.testing.assert_allclose(SE2.compose(SE2.inverse(g1), h2), [l1 + de + l2, a, 0.0], atol=1e-15)

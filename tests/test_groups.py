"""Property tests written once and run over every group of chapter 1 (jaxlie-style).

Each law is checked through a route independent of the closed forms in gm_core.groups: the
matrix representation and matrix products, scipy's expm/logm, and central finite differences of
the group operation for the lifted actions (1.20)-(1.21).
"""
import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import ALL_GROUPS, SE2, RPlus
from gm_core.groups import matvec

GROUPS = list(ALL_GROUPS.items())
ids = [name for name, _ in GROUPS]
seeds = st.integers(min_value=0, max_value=2**32 - 1)
settings.register_profile("course", max_examples=40, deadline=None)
settings.load_profile("course")


def elements(G, seed, n=4):
    return G.random(np.random.default_rng(seed), n)


def algebra(G, seed, n=4, scale=2.0):
    return np.random.default_rng(seed + 1).normal(scale=scale, size=(n, G.dim))


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_compose_matches_matrix_product(name, G, seed):
    g, h = elements(G, seed), elements(G, seed + 7)
    np.testing.assert_allclose(G.matrix(G.compose(g, h)), G.matrix(g) @ G.matrix(h), atol=1e-12)


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_associativity(name, G, seed):
    a, b, c = elements(G, seed), elements(G, seed + 1), elements(G, seed + 2)
    lhs = G.compose(a, G.compose(b, c))
    rhs = G.compose(G.compose(a, b), c)
    assert G.isclose(lhs, rhs, atol=1e-10).all()


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_identity_and_inverse(name, G, seed):
    g = elements(G, seed)
    e = G.identity((4,))
    assert G.isclose(G.compose(e, g), g).all() and G.isclose(G.compose(g, e), g).all()
    assert G.isclose(G.compose(g, G.inverse(g)), e, atol=1e-10).all()
    assert G.isclose(G.compose(G.inverse(g), g), e, atol=1e-10).all()
    np.testing.assert_allclose(G.matrix(G.inverse(g)), np.linalg.inv(G.matrix(g)), atol=1e-10)


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_exp_matches_expm_and_log_inverts(name, G, seed):
    xi = algebra(G, seed)
    np.testing.assert_allclose(G.matrix(G.exp(xi)), scipy.linalg.expm(G.hat(xi)), atol=1e-10)
    g = elements(G, seed)
    assert G.isclose(G.exp(G.log(g)), g, atol=1e-10).all()
    # log is the principal logarithm: it agrees with scipy's logm.
    for gi, li in zip(g, G.log(g)):
        np.testing.assert_allclose(G.hat(li), np.real(scipy.linalg.logm(G.matrix(gi))), atol=1e-8)


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_hat_vee_roundtrip(name, G, seed):
    xi = algebra(G, seed)
    np.testing.assert_allclose(G.vee(G.hat(xi)), xi, atol=1e-14)


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_lifted_actions_match_finite_differences(name, G, seed):
    g, h = elements(G, seed), elements(G, seed + 3)
    np.testing.assert_allclose(G.left_lifted_action(h, g), G.numerical_left_lifted_action(h, g), atol=1e-7)
    np.testing.assert_allclose(G.right_lifted_action(h, g), G.numerical_right_lifted_action(h, g), atol=1e-7)


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_adjoint_is_product_of_lifted_actions(name, G, seed):
    """Ad_g = T_g R_{g^-1} T_e L_g, book (1.40); Ad_g^-1 = T_g L_{g^-1} T_e R_g, book (1.41)."""
    g = elements(G, seed)
    e = G.identity()
    via_lifted = G.right_lifted_action(G.inverse(g), g) @ G.left_lifted_action(g, e)
    np.testing.assert_allclose(G.Ad(g), via_lifted, atol=1e-12)
    via_lifted_inv = G.left_lifted_action(G.inverse(g), g) @ G.right_lifted_action(g, e)
    np.testing.assert_allclose(G.Ad_inv(g), via_lifted_inv, atol=1e-12)
    np.testing.assert_allclose(G.Ad(g) @ G.Ad_inv(g), np.broadcast_to(np.eye(G.dim), G.Ad(g).shape), atol=1e-12)


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_adjoint_conjugates_algebra(name, G, seed):
    """Ad_g xi = (g xi^ g^-1)^vee: the matrix route to (1.43)."""
    g, xi = elements(G, seed), algebra(G, seed)
    Gm = G.matrix(g)
    conj = G.vee(Gm @ G.hat(xi) @ np.linalg.inv(Gm))
    np.testing.assert_allclose(matvec(G.Ad(g), xi), conj, atol=1e-10)


@pytest.mark.parametrize("name,G", GROUPS, ids=ids)
@given(seed=seeds)
def test_velocity_conversions_roundtrip_and_match_matrix_route(name, G, seed):
    g, xi = elements(G, seed), algebra(G, seed)
    g_dot = G.body_to_world(g, xi)
    np.testing.assert_allclose(G.world_to_body(g, g_dot), xi, atol=1e-10)
    xi_s = G.world_to_spatial(g, g_dot)
    np.testing.assert_allclose(G.spatial_to_world(g, xi_s), g_dot, atol=1e-10)
    np.testing.assert_allclose(G.body_to_spatial(g, xi), xi_s, atol=1e-10)
    np.testing.assert_allclose(G.spatial_to_body(g, xi_s), xi, atol=1e-10)
    # Matrix route: g^-1 g_dot = xi^ (body), g_dot g^-1 = xi_s^ (spatial), cf. (1.52).
    Gm = G.matrix(g)
    dG = np.stack([(G.matrix(g + 1e-6 * g_dot) - G.matrix(g - 1e-6 * g_dot)) / 2e-6], 0)[0]
    np.testing.assert_allclose(G.vee(np.linalg.inv(Gm) @ dG), xi, atol=1e-6)
    np.testing.assert_allclose(G.vee(dG @ np.linalg.inv(Gm)), xi_s, atol=1e-6)


def test_batching_and_broadcasting():
    rng = np.random.default_rng(0)
    g = SE2.random(rng, (5, 4))
    h = SE2.random(rng, (4,))
    out = SE2.compose(g, h)
    assert out.shape == (5, 4, 3)
    for i in range(5):
        for j in range(4):
            np.testing.assert_allclose(out[i, j], SE2.compose(g[i, j], h[j]), atol=1e-15)
    assert SE2.Ad(g).shape == (5, 4, 3, 3)
    assert SE2.left_lifted_action(h, g).shape == (5, 4, 3, 3)
    assert SE2.identity((2, 3)).shape == (2, 3, 3)
    assert RPlus.left_lifted_action([[2.0]], [[3.0], [4.0]]).shape == (2, 1, 1)


def test_book_examples():
    # Fig. 1.10: g = (1, 1, pi/2), h = g o g = (0, 2, pi) in SE(2) but (2, 2, pi) in R2xS1.
    from gm_core import R2xS1
    g = np.array([1.0, 1.0, np.pi / 2])
    assert SE2.isclose(SE2.compose(g, g), [0.0, 2.0, np.pi])
    assert R2xS1.isclose(R2xS1.compose(g, g), [2.0, 2.0, np.pi])
    # (1.24): on (R+, x), T_g L_h = h.
    assert RPlus.left_lifted_action([3.0], [5.0])[0, 0] == 3.0
    # (1.12): the point (1, 0) of a body at (1, 2, pi/2) sits at (1, 3).
    np.testing.assert_allclose(SE2.act_on_points([1.0, 2.0, np.pi / 2], [1.0, 0.0]), [1.0, 3.0], atol=1e-15)

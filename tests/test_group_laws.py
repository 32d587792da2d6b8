"""Lie-group laws written once and run over every group of ALL_GROUPS and several batch shapes
(jaxlie's ``general_group_test`` pattern).

``@over_groups`` and ``@over_shapes`` parametrize a hypothesis test over every group and over the
batch shapes ``()``, ``(1,)`` and ``(3, 1, 2, 1)``; the strategies draw algebra vectors from
floats and reach elements through exp (surjective for every group of the course). Every law is
checked through a route independent of the closed forms in gm_core.groups: the matrix
representation (matrix products and inverses, the matrix commutator, scipy's expm and logm) and
central finite differences (of the group operation for the lifted actions (1.20)-(1.21), of
Ad along exp(t xi) for the bracket, of the matrix along g_dot for the velocities).
"""
import math

import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import ALL_GROUPS, S1, SE2, LieGroup, R2xS1, RPlus
from gm_core.groups import MAX_RN_DIM, Rn, matvec

LAWS = settings(max_examples=15, deadline=None)   # per test and shape: no global profile is loaded here

SHAPES = [(), (1,), (3, 1, 2, 1)]
over_groups = pytest.mark.parametrize("G", list(ALL_GROUPS.values()), ids=list(ALL_GROUPS))
over_shapes = pytest.mark.parametrize("shape", SHAPES, ids=["scalar", "one", "3x1x2x1"])


@st.composite
def algebra(draw, G, shape, scale=3.0, principal=False):
    """Algebra vectors ``shape + (tangent_dim,)``; ``principal`` keeps periodic parts inside
    (-k/2, k/2), and the whole vector inside the ball |xi| < ``G.principal_radius`` when the
    group declares one, so that log(exp(xi)) = xi."""
    n = math.prod(shape) * G.tangent_dim
    u = np.array(draw(st.lists(st.floats(-1.0, 1.0), min_size=n, max_size=n))).reshape(shape + (G.tangent_dim,))
    out = scale * u
    if principal and G.principal_radius is not None:
        out = 0.98 * G.principal_radius * u / math.sqrt(G.tangent_dim)      # |u| <= sqrt(dim)
    for j, p in enumerate(G.periods):
        if p is not None and principal:
            out[..., j] = 0.49 * p * u[..., j]
    return out


def elements(G, shape):
    return algebra(G, shape).map(G.exp)


def batched(A, shape, m):
    """The (m x m) matrices of ``A`` with the batch ``shape`` (assert it), flattened to a list."""
    assert A.shape == shape + (m, m)
    return A.reshape(-1, m, m)


def vee_of_commutator(G, a, b):
    A, B = G.hat(a), G.hat(b)
    return G.vee(A @ B - B @ A)


def law(f):
    """A law: over every group, every batch shape and hypothesis-drawn data."""
    return over_groups(over_shapes(LAWS(given(data=st.data())(f))))


# ------------------------------------------------------------------ group axioms
@law
def test_compose_is_the_matrix_product(G, shape, data):
    g, h = data.draw(elements(G, shape)), data.draw(elements(G, shape))
    gh = G.compose(g, h)
    assert gh.shape == shape + (G.param_dim,)
    np.testing.assert_allclose(G.matrix(gh), G.matrix(g) @ G.matrix(h), atol=1e-12)


@law
def test_associativity(G, shape, data):
    a, b, c = (data.draw(elements(G, shape)) for _ in range(3))
    assert G.isclose(G.compose(a, G.compose(b, c)), G.compose(G.compose(a, b), c), atol=1e-9).all()


@law
def test_identity_and_inverse(G, shape, data):
    g = data.draw(elements(G, shape))
    e = G.identity(shape)
    assert G.isclose(G.compose(e, g), g, atol=1e-12).all()
    assert G.isclose(G.compose(g, e), g, atol=1e-12).all()
    assert G.isclose(G.compose(g, G.inverse(g)), e, atol=1e-9).all()
    assert G.isclose(G.compose(G.inverse(g), g), e, atol=1e-9).all()
    np.testing.assert_allclose(G.matrix(G.inverse(g)), np.linalg.inv(G.matrix(g)), atol=1e-9)


# ------------------------------------------------------------------ exp, log, hat, vee
@law
def test_exp_is_expm_and_log_is_logm(G, shape, data):
    xi = data.draw(algebra(G, shape))
    m = G.matrix_size
    for X, E in zip(batched(G.hat(xi), shape, m), batched(G.matrix(G.exp(xi)), shape, m)):
        np.testing.assert_allclose(E, scipy.linalg.expm(X), atol=1e-10)
    g = G.exp(data.draw(algebra(G, shape, principal=True)))   # off the branch cut of log
    # log is the principal logarithm: it agrees with scipy's logm.
    for L, M in zip(batched(G.hat(G.log(g)), shape, m), batched(G.matrix(g), shape, m)):
        # scipy's norm estimator inside logm divides by exact zeros of some exact rotations
        # (numpy warns); its result is what is checked here
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            logm = scipy.linalg.logm(M)
        np.testing.assert_allclose(L, np.real(logm), atol=1e-8)


@law
def test_exp_log_round_trip(G, shape, data):
    g = data.draw(elements(G, shape))
    assert G.isclose(G.exp(G.log(g)), g, atol=1e-9).all()
    xi = data.draw(algebra(G, shape, principal=True))
    np.testing.assert_allclose(G.log(G.exp(xi)), xi, atol=1e-9)


@law
def test_hat_vee_round_trip(G, shape, data):
    xi = data.draw(algebra(G, shape))
    assert G.hat(xi).shape == shape + (G.matrix_size, G.matrix_size)
    np.testing.assert_allclose(G.vee(G.hat(xi)), xi, rtol=1e-15, atol=1e-15)


# ------------------------------------------------------------------ lifted actions and Ad
@law
def test_lifted_actions_are_finite_differences_of_the_operation(G, shape, data):
    g, h = data.draw(elements(G, shape)), data.draw(elements(G, shape))
    np.testing.assert_allclose(G.left_lifted_action(h, g), G.numerical_left_lifted_action(h, g), atol=1e-7)
    np.testing.assert_allclose(G.right_lifted_action(h, g), G.numerical_right_lifted_action(h, g), atol=1e-7)


@law
def test_adjoint_is_the_product_of_lifted_actions(G, shape, data):
    """Ad_g = T_g R_{g^-1} T_e L_g, book (1.40); Ad_g^-1 = T_g L_{g^-1} T_e R_g, book (1.41)."""
    g = data.draw(elements(G, shape))
    e = G.identity(shape)
    ginv = G.inverse(g)
    np.testing.assert_allclose(G.Ad(g), G.right_lifted_action(ginv, g) @ G.left_lifted_action(g, e), atol=1e-12)
    np.testing.assert_allclose(G.Ad_inv(g), G.left_lifted_action(ginv, g) @ G.right_lifted_action(g, e), atol=1e-12)
    np.testing.assert_allclose(G.Ad(g) @ G.Ad_inv(g), np.broadcast_to(np.eye(G.dim), G.Ad(g).shape), atol=1e-12)


@law
def test_adjoint_conjugates_the_algebra(G, shape, data):
    """Ad_g xi = (g xi^ g^-1)^vee: the matrix route to (1.43)."""
    g, xi = data.draw(elements(G, shape)), data.draw(algebra(G, shape))
    M = G.matrix(g)
    np.testing.assert_allclose(matvec(G.Ad(g), xi), G.vee(M @ G.hat(xi) @ np.linalg.inv(M)), atol=1e-10)


@law
def test_adjoint_is_a_homomorphism(G, shape, data):
    g, h = data.draw(elements(G, shape)), data.draw(elements(G, shape))
    np.testing.assert_allclose(G.Ad(G.compose(g, h)), G.Ad(g) @ G.Ad(h), atol=1e-9)
    np.testing.assert_allclose(G.Ad(G.inverse(g)), np.linalg.inv(G.Ad(g)), atol=1e-9)


@law
def test_velocity_conversions_round_trip_and_match_the_matrix_route(G, shape, data):
    g, xi = data.draw(elements(G, shape)), data.draw(algebra(G, shape))
    g_dot = G.body_to_world(g, xi)
    np.testing.assert_allclose(G.world_to_body(g, g_dot), xi, atol=1e-10)
    xi_s = G.world_to_spatial(g, g_dot)
    np.testing.assert_allclose(G.spatial_to_world(g, xi_s), g_dot, atol=1e-10)
    np.testing.assert_allclose(G.body_to_spatial(g, xi), xi_s, atol=1e-10)
    np.testing.assert_allclose(G.spatial_to_body(g, xi_s), xi, atol=1e-10)
    # Matrix route: g^-1 g_dot = xi^ (body), g_dot g^-1 = xi_s^ (spatial), cf. (1.52).
    M, h = G.matrix(g), 1e-6
    dM = (G.matrix(g + h * g_dot) - G.matrix(g - h * g_dot)) / (2 * h)
    np.testing.assert_allclose(G.vee(np.linalg.inv(M) @ dM), xi, atol=1e-6)
    np.testing.assert_allclose(G.vee(dM @ np.linalg.inv(M)), xi_s, atol=1e-6)


# ------------------------------------------------------------------ bracket and ad
@law
def test_bracket_is_antisymmetric_and_satisfies_jacobi(G, shape, data):
    x, y, z = (data.draw(algebra(G, shape)) for _ in range(3))
    np.testing.assert_allclose(G.bracket(x, y), -G.bracket(y, x), atol=1e-12)
    np.testing.assert_array_equal(G.bracket(x, x), 0.0)
    jacobi = (G.bracket(x, G.bracket(y, z)) + G.bracket(y, G.bracket(z, x))
              + G.bracket(z, G.bracket(x, y)))
    np.testing.assert_allclose(jacobi, 0.0, atol=1e-10)


@law
def test_bracket_and_ad_equal_the_matrix_commutator(G, shape, data):
    x, y = data.draw(algebra(G, shape)), data.draw(algebra(G, shape))
    ref = vee_of_commutator(G, x, y)
    np.testing.assert_allclose(G.bracket(x, y), ref, atol=1e-12)
    np.testing.assert_allclose(matvec(G.ad(x), y), ref, atol=1e-12)


@law
def test_bracket_is_the_derivative_of_Ad_along_exp(G, shape, data):
    """[xi, eta] = d/dt Ad(exp(t xi)) eta at t = 0, by central differences."""
    xi, eta = data.draw(algebra(G, shape, scale=1.0)), data.draw(algebra(G, shape, scale=1.0))
    h = 1e-5

    def Ad_eta(t):
        return matvec(G.Ad(G.exp(t * xi)), eta)

    np.testing.assert_allclose(G.bracket(xi, eta), (Ad_eta(h) - Ad_eta(-h)) / (2 * h), atol=1e-8)


# ------------------------------------------------------------------ declared interface
@over_groups
def test_declared_dimensions_match_the_arrays(G):
    assert G.identity().shape == (G.param_dim,)
    assert G.identity((2, 4)).shape == (2, 4, G.param_dim)
    xi = np.zeros(G.tangent_dim)
    m = G.matrix_size
    assert G.hat(xi).shape == (m, m)
    assert G.matrix(G.identity()).shape == (m, m)
    assert G.Ad(G.identity()).shape == (G.tangent_dim, G.tangent_dim)
    assert G.ad(xi).shape == (G.tangent_dim, G.tangent_dim)
    assert G.dim == G.param_dim == G.tangent_dim
    assert len(G.coords) == len(G.periods) == G.param_dim
    assert G.angular == tuple(p is not None for p in G.periods)
    assert isinstance(G.label, str) and G.label


def test_lie_group_is_abstract():
    with pytest.raises(TypeError):
        LieGroup()

    class Half(LieGroup):                     # forgets most of the interface
        name, coords, periods, param_dim, tangent_dim, matrix_size = "H", ("x",), (None,), 1, 1, 2

        def compose(self, g, h):
            return g + h

    with pytest.raises(TypeError, match="abstract"):
        Half()


def test_rn_dimensions_are_bounded():
    assert Rn(MAX_RN_DIM).param_dim == MAX_RN_DIM
    with pytest.raises(ValueError, match="n must be a positive integer"):
        Rn(MAX_RN_DIM + 1)


@over_groups
def test_contains_and_project(G):
    g = G.random(np.random.default_rng(1), 5)
    p = G.project(g)
    assert G.contains(p).all() and G.isclose(p, g).all()
    assert not G.contains(np.full(G.param_dim, np.nan))
    assert G.contains(np.zeros((4, 0, G.param_dim))).shape == (4, 0)


def test_membership_is_group_specific():
    assert list(RPlus.contains([[2.0], [0.0], [-1.0]])) == [True, False, False]
    C = S1(1.0)
    assert list(C.contains([[0.0], [0.999], [1.0], [-0.2]])) == [True, True, False, False]
    np.testing.assert_allclose(C.project([[1.25], [-0.25]]), [[0.25], [0.75]])
    assert SE2.contains([1e10, -3.0, 40.0])


# ------------------------------------------------------------------ broadcasting and the book
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
    g = np.array([1.0, 1.0, np.pi / 2])
    assert SE2.isclose(SE2.compose(g, g), [0.0, 2.0, np.pi])
    assert R2xS1.isclose(R2xS1.compose(g, g), [2.0, 2.0, np.pi])
    # (1.24): on (R+, x), T_g L_h = h.
    assert RPlus.left_lifted_action([3.0], [5.0])[0, 0] == 3.0
    # (1.12): the point (1, 0) of a body at (1, 2, pi/2) sits at (1, 3).
    np.testing.assert_allclose(SE2.act_on_points([1.0, 2.0, np.pi / 2], [1.0, 0.0]), [1.0, 3.0], atol=1e-15)


def test_se2_bracket_on_the_basis():
    ex, ey, ew = np.eye(3)
    np.testing.assert_array_equal(SE2.bracket(ex, ey), 0.0)
    np.testing.assert_array_equal(SE2.bracket(ew, ex), ey)        # rotating a translation
    np.testing.assert_array_equal(SE2.bracket(ew, ey), -ex)

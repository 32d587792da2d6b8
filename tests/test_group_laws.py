"""Lie-group laws written once and run over every group of ALL_GROUPS (jaxlie's pattern).

``@over_groups`` parametrizes a hypothesis test over every group; the strategies draw algebra
vectors from floats and reach elements through exp (surjective for every group of the course).
The routes checked here are independent of the closed forms: matrix products and inverses, the
matrix commutator, and central finite differences of Ad along exp(t xi).
"""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import ALL_GROUPS, S1, SE2, LieGroup, RPlus
from gm_core.groups import MAX_RN_DIM, Rn

LAWS = settings(max_examples=25, deadline=None)   # per test: no global profile is loaded here

BATCH = 3
over_groups = pytest.mark.parametrize("G", list(ALL_GROUPS.values()), ids=list(ALL_GROUPS))


@st.composite
def algebra(draw, G, scale=3.0, principal=False):
    """A batch (BATCH, tangent_dim) of algebra vectors; ``principal`` keeps periodic parts inside
    (-k/2, k/2) so that log(exp(xi)) = xi."""
    u = np.array(draw(st.lists(st.floats(-1.0, 1.0), min_size=BATCH * G.tangent_dim,
                               max_size=BATCH * G.tangent_dim))).reshape(BATCH, G.tangent_dim)
    out = scale * u
    for j, p in enumerate(G.periods):
        if p is not None and principal:
            out[:, j] = 0.49 * p * u[:, j]
    return out


def elements(G):
    return algebra(G).map(G.exp)


def vee_of_commutator(G, a, b):
    A, B = G.hat(a), G.hat(b)
    return G.vee(A @ B - B @ A)


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


# ------------------------------------------------------------------ group axioms
@over_groups
@LAWS
@given(data=st.data())
def test_associativity(G, data):
    a, b, c = (data.draw(elements(G)) for _ in range(3))
    assert G.isclose(G.compose(a, G.compose(b, c)), G.compose(G.compose(a, b), c), atol=1e-9).all()


@over_groups
@LAWS
@given(data=st.data())
def test_identity_and_inverse(G, data):
    g = data.draw(elements(G))
    e = G.identity((BATCH,))
    assert G.isclose(G.compose(e, g), g, atol=1e-12).all()
    assert G.isclose(G.compose(g, e), g, atol=1e-12).all()
    assert G.isclose(G.compose(g, G.inverse(g)), e, atol=1e-9).all()
    assert G.isclose(G.compose(G.inverse(g), g), e, atol=1e-9).all()
    np.testing.assert_allclose(G.matrix(G.inverse(g)), np.linalg.inv(G.matrix(g)), atol=1e-9)


@over_groups
@LAWS
@given(data=st.data())
def test_exp_log_round_trip(G, data):
    g = data.draw(elements(G))
    assert G.isclose(G.exp(G.log(g)), g, atol=1e-9).all()
    xi = data.draw(algebra(G, principal=True))
    np.testing.assert_allclose(G.log(G.exp(xi)), xi, atol=1e-9)


@over_groups
@LAWS
@given(data=st.data())
def test_hat_vee_round_trip(G, data):
    xi = data.draw(algebra(G))
    np.testing.assert_allclose(G.vee(G.hat(xi)), xi, rtol=1e-15, atol=1e-15)


@over_groups
@LAWS
@given(data=st.data())
def test_adjoint_is_a_homomorphism(G, data):
    g, h = data.draw(elements(G)), data.draw(elements(G))
    np.testing.assert_allclose(G.Ad(G.compose(g, h)), G.Ad(g) @ G.Ad(h), atol=1e-9)
    np.testing.assert_allclose(G.Ad(G.inverse(g)), np.linalg.inv(G.Ad(g)), atol=1e-9)


# ------------------------------------------------------------------ bracket and ad
@over_groups
@LAWS
@given(data=st.data())
def test_bracket_is_antisymmetric_and_satisfies_jacobi(G, data):
    x, y, z = (data.draw(algebra(G)) for _ in range(3))
    np.testing.assert_allclose(G.bracket(x, y), -G.bracket(y, x), atol=1e-12)
    np.testing.assert_array_equal(G.bracket(x, x), 0.0)
    jacobi = (G.bracket(x, G.bracket(y, z)) + G.bracket(y, G.bracket(z, x))
              + G.bracket(z, G.bracket(x, y)))
    np.testing.assert_allclose(jacobi, 0.0, atol=1e-10)


@over_groups
@LAWS
@given(data=st.data())
def test_bracket_and_ad_equal_the_matrix_commutator(G, data):
    x, y = data.draw(algebra(G)), data.draw(algebra(G))
    ref = vee_of_commutator(G, x, y)
    np.testing.assert_allclose(G.bracket(x, y), ref, atol=1e-12)
    np.testing.assert_allclose(np.einsum("...ij,...j->...i", G.ad(x), y), ref, atol=1e-12)


@over_groups
@LAWS
@given(data=st.data())
def test_bracket_is_the_derivative_of_Ad_along_exp(G, data):
    """[xi, eta] = d/dt Ad(exp(t xi)) eta at t = 0, by central differences."""
    xi, eta = data.draw(algebra(G, scale=1.0)), data.draw(algebra(G, scale=1.0))
    h = 1e-5

    def Ad_eta(t):
        return np.einsum("...ij,...j->...i", G.Ad(G.exp(t * xi)), eta)

    fd = (Ad_eta(h) - Ad_eta(-h)) / (2 * h)
    np.testing.assert_allclose(G.bracket(xi, eta), fd, atol=1e-8)


def test_se2_bracket_on_the_basis():
    ex, ey, ew = np.eye(3)
    np.testing.assert_array_equal(SE2.bracket(ex, ey), 0.0)
    np.testing.assert_array_equal(SE2.bracket(ew, ex), ey)        # rotating a translation
    np.testing.assert_array_equal(SE2.bracket(ew, ey), -ex)

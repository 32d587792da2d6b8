"""gm_core.axioms: the axiom residuals and membership test, over every group, checked against
direct computations (matrix products for associativity, known non-elements)."""
import numpy as np
import pytest

from gm_core import ALL_GROUPS, RPlus, SE2, S1
from gm_core.axioms import AXIOMS, axiom_residuals, is_element, powers, scaled


@pytest.mark.parametrize("name", list(ALL_GROUPS))
def test_every_group_satisfies_the_axioms(name):
    G = ALL_GROUPS[name]
    r = axiom_residuals(G, np.random.default_rng(1), n=30)
    assert r["closure"]
    assert max(r[a] for a in AXIOMS) < 1e-9
    big = axiom_residuals(G, np.random.default_rng(2), n=30, scale=4.0)
    assert big["closure"] and max(big[a] for a in AXIOMS) < 1e-8


@pytest.mark.parametrize("name", list(ALL_GROUPS))
def test_associativity_residual_equals_matrix_route(name):
    """Independent route: associativity of the matrix product, mapped back with from_matrix."""
    G = ALL_GROUPS[name]
    rng = np.random.default_rng(5)
    g1, g2, g3 = (G.random(rng, 10) for _ in range(3))
    M = G.matrix(g1) @ G.matrix(g2) @ G.matrix(g3)
    assert np.all(G.isclose(G.from_matrix(M), G.compose(G.compose(g1, g2), g3), atol=1e-9))


def test_membership_without_asking_which_group():
    assert is_element(RPlus, np.array([[2.0], [0.5]]))
    assert not is_element(RPlus, np.array([[-1.0]]))           # (R+, x) has no negative numbers
    assert not is_element(RPlus, np.array([[0.0]]))
    assert not is_element(SE2, np.array([1.0, np.nan, 0.0]))   # not finite
    assert not is_element(SE2, np.array([1.0, 2.0]))           # wrong number of coordinates
    assert is_element(SE2, SE2.random(np.random.default_rng(0), 5))
    assert is_element(S1(1.0), np.array([0.25]))
    with pytest.raises(TypeError, match="G must be one of gm_core's Lie groups"):
        is_element("SE2", np.zeros(3))


def test_scaled_moves_along_the_one_parameter_subgroup():
    g = np.array([3.0])
    assert np.allclose(scaled(RPlus, g, 2.0), 9.0)             # exp(2 log 3) = 3^2
    xi = np.array([0.3, -0.2, 0.4])
    g = SE2.exp(xi)
    assert np.allclose(scaled(SE2, g, 3.0), SE2.exp(3 * xi))
    # half of g composed with itself is g
    h = scaled(SE2, g, 0.5)
    assert SE2.isclose(SE2.compose(h, h), g)


def test_powers_match_matrix_powers():
    g = np.array([1.0, 1.0, np.pi / 2])
    P = powers(SE2, g, 4)
    assert P.shape == (5, 3)
    for k in range(5):
        assert SE2.isclose(SE2.from_matrix(np.linalg.matrix_power(SE2.matrix(g), k)), P[k])
    with pytest.raises(ValueError, match="n must be a non-negative integer"):
        powers(SE2, g, -1)

"""The scale-shift group R+ x| R: the author's own numbers, the affine-map meaning, and exp/log
against 50-digit mpmath and scipy's expm/logm.

The reference values below were produced by running the author's code
(rlhatton/GeometryOfMotionCodebase, ``geomotion/`` and the ``S275``/``S280``/``S500``/``S550``
constructions of the scale-shift group) on the inputs named in each comment; they come from an
independent implementation (numdifftools Jacobians, scipy's expm/logm, solve_ivp flows). The
group laws shared by every group (associativity, lifted actions by finite differences, Ad,
bracket, ...) run over this group in tests/test_group_laws.py.
"""
import mpmath as mp
import numpy as np
import pytest
import scipy.linalg

from gm_core import ScaleShift as G
from gm_core import calculus as C
from gm_core import fields as F
from gm_core.groups import matvec

G1, G2, G3 = [3.0, -1.0], [0.5, 1.5], [1.5, 3.5]      # the elements of E275 and E285


# ------------------------------------------------------------------ the author's numbers
def test_composition_and_inverse_match_the_author():
    # E275_scale_shift_composition_examples.py: g1 * g2 and g2 * g1 with S275's scale_shift_action.
    np.testing.assert_array_equal(G.compose(G1, G2), [1.5, 3.5])
    np.testing.assert_array_equal(G.compose(G2, G1), [1.5, 1.0])
    # S275's scale_shift_inverse of g1 = [3, -1] and g2 = [.5, 1.5].
    np.testing.assert_allclose(G.inverse(G1), [0.3333333333333333, 0.3333333333333333], rtol=1e-16)
    np.testing.assert_array_equal(G.inverse(G2), [2.0, -3.0])
    # E285_scale_shift_inverse_composition_examples.py (S280 representation group): g3 * g2.inverse
    # and g1.inverse * g3 with g3 = [1.5, 3.5].
    np.testing.assert_allclose(G.compose(G3, G.inverse(G2)), [3.0, -1.0], rtol=1e-15)
    np.testing.assert_allclose(G.compose(G.inverse(G1), G3), [0.5, 1.4999999999999998], rtol=1e-15)
    # S280's scale_shift_rep of g3.
    np.testing.assert_array_equal(G.matrix(G3), [[1.5, 3.5], [0.0, 1.0]])
    # geomotion/group.py commutator(g1, g2) = g1 g2 g1^-1 g2^-1 (E295).
    c = G.compose(G.compose(G1, G2), G.compose(G.inverse(G1), G.inverse(G2)))
    np.testing.assert_allclose(c, [1.0, 2.5], rtol=1e-15)


def test_lifted_actions_match_the_author():
    # geomotion/liegroup.py: h * v (TL, numdifftools Jacobian of L_h) and v * h (TR) for the unit
    # vectors v of the tangent space at g = [0.8, -0.6] (S500), h = [1.5, 1.0]; columns below.
    h, g = [1.5, 1.0], [0.8, -0.6]
    author_TL = np.array([[1.4999999999999998, 0.0], [0.0, 1.4999999999999996]])
    author_TR = np.array([[1.4999999999999998, 0.0], [0.9999999999999998, 0.9999999999999998]])
    np.testing.assert_allclose(G.left_lifted_action(h, g), author_TL, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(G.right_lifted_action(h, g), author_TR, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("xi, author_Ad, author_Ad_inv", [
    # E615_scale_shift_adjoint_fields_rep.py: g.Ad(g_circ) and g.Ad_inv(g_circ), g = [1.5, 1] (S550).
    ([1.0, 0.5], [0.9999999999999999, -0.24999999999999994], [1.0, 1.0]),
    ([1.0, -0.25], [0.9999999999999999, -1.3749999999999998], [1.0, 0.5]),
    ([0.3, -2.0], [0.3, -3.3], [0.3, -1.1333333333333333]),
])
def test_adjoint_matches_the_author(xi, author_Ad, author_Ad_inv):
    g = [1.5, 1.0]
    np.testing.assert_allclose(matvec(G.Ad(g), xi), author_Ad, rtol=1e-14, atol=1e-14)
    np.testing.assert_allclose(matvec(G.Ad_inv(g), xi), author_Ad_inv, rtol=1e-14, atol=1e-14)


@pytest.mark.parametrize("xi, author_exp", [
    # E660_scale_shift_exponentiation_rep.py: Lie_alg_vector(xi).exp_L (scipy expm, S550); exp_R
    # printed the same numbers.
    ([1.0, 1.0], [2.7182818284590446, 1.7182818284590446]),
    ([-0.7, 2.0], [0.4965853037914095, 1.4383277034531154]),
    ([1e-6, 0.4], [1.0000010000005, 0.4000002000000666]),
    ([0.0, 1.5], [1.0, 1.4999999999999996]),
])
def test_exp_matches_the_author(xi, author_exp):
    np.testing.assert_allclose(G.exp(xi), author_exp, rtol=1e-15)


@pytest.mark.parametrize("g, author_log", [
    # geomotion/representationliegroup.py: element(g).log (scipy logm, S550).
    ([2.718281828459045, 1.718281828459045], [1.0000000000000002, 1.0000000000000002]),
    ([0.5, -1.0], [-0.6931471805599454, -1.3862943611198908]),
    ([3.0, 2.0], [1.09861228866811, 1.0986122886681098]),
])
def test_log_matches_the_author(g, author_log):
    np.testing.assert_allclose(G.log(g), author_log, rtol=1e-15)


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("xi, author_flow", [
    # E650_scale_shift_exponentiation.py: Lie_alg_vector(xi).exp_L / exp_R of S500, the author's
    # solve_ivp flows of the generator fields from e to t = 1 (its default tolerances, ~1e-5).
    ([1.0, 1.0], [2.718297588748846, 1.7182975887488472]),
    ([-0.7, 2.0], [0.4965859559837855, 1.4383258400463268]),
])
def test_geodesics_from_identity_match_the_authors_flows(side, xi, author_flow):
    closed = F.group_geodesic(G, xi, [1.0], side=side)[0]
    np.testing.assert_allclose(closed, author_flow, rtol=2e-5)
    np.testing.assert_allclose(closed, G.exp(xi), rtol=1e-15)


# ------------------------------------------------------------------ the affine-map meaning
def test_matrix_acts_on_the_line_as_x_to_ax_plus_b():
    rng = np.random.default_rng(3)
    g, h = G.random(rng, 6), G.random(rng, 6)
    x = rng.uniform(-5.0, 5.0, 6)
    line = np.stack([x, np.ones(6)], -1)
    a, b = g[:, 0], g[:, 1]
    np.testing.assert_allclose(matvec(G.matrix(g), line), np.stack([a * x + b, np.ones(6)], -1), rtol=1e-15)
    # compose is the composition of maps: (g o h)(x) = g(h(x))
    gh = G.compose(g, h)
    hx = h[:, 0] * x + h[:, 1]
    np.testing.assert_allclose(gh[:, 0] * x + gh[:, 1], a * hx + b, rtol=1e-13, atol=1e-13)
    # the inverse undoes the map
    gi = G.inverse(g)
    np.testing.assert_allclose(gi[:, 0] * (a * x + b) + gi[:, 1], x, rtol=1e-13, atol=1e-13)


def test_identity_is_the_identity_map():
    np.testing.assert_array_equal(G.identity(), [1.0, 0.0])
    np.testing.assert_array_equal(G.matrix(G.identity()), np.eye(2))


def test_closed_forms_written_out():
    """T_g L_h = a_h I, T_g R_h = [[a_h, 0], [b_h, 1]], Ad_g = [[1, 0], [-b, a]], [xi1, xi2] = (0, u1 v2 - u2 v1)."""
    h, g = np.array([2.0, -3.0]), np.array([0.25, 7.0])
    np.testing.assert_array_equal(G.left_lifted_action(h, g), [[2.0, 0.0], [0.0, 2.0]])
    np.testing.assert_array_equal(G.right_lifted_action(h, g), [[2.0, 0.0], [-3.0, 1.0]])
    np.testing.assert_array_equal(G.Ad(g), [[1.0, 0.0], [-7.0, 0.25]])
    np.testing.assert_array_equal(G.Ad_inv(g), [[1.0, 0.0], [28.0, 4.0]])
    np.testing.assert_array_equal(G.bracket([1.0, 0.0], [0.0, 1.0]), [0.0, 1.0])   # scaling a shift
    np.testing.assert_array_equal(G.hat([2.0, 3.0]), [[2.0, 3.0], [0.0, 0.0]])
    # the same lifted actions by central differences of the group operation (1.20)-(1.21)
    np.testing.assert_allclose(G.left_lifted_action(h, g), G.numerical_left_lifted_action(h, g), atol=1e-8)
    np.testing.assert_allclose(G.right_lifted_action(h, g), G.numerical_right_lifted_action(h, g), atol=1e-8)


# ------------------------------------------------------------------ exp and log to rounding
U = [0.0, 5e-324, 1e-300, 1e-12, -1e-12, 1e-8, 1e-6, -1e-6, 0.1, 1.0, -2.5, 30.0, -30.0, 700.0]


def rel_err(got, ref):
    got = [mp.mpf(float(x)) for x in got]
    return float(mp.sqrt(sum((g - r) ** 2 for g, r in zip(got, ref))) / mp.sqrt(sum(r ** 2 for r in ref)))


def exp_reference(u, v):
    u, v = mp.mpf(u), mp.mpf(v)
    return mp.exp(u), (v if u == 0 else v * mp.expm1(u) / u)


@pytest.mark.parametrize("u", U)
@pytest.mark.parametrize("v", [1.0, -2.5, 1e-3])
def test_exp_is_accurate_to_rounding(u, v):
    with mp.workdps(50):
        ref = exp_reference(u, v)
        got = G.exp([u, v])
        assert float(abs(mp.mpf(float(got[0])) - ref[0]) / ref[0]) < 2.3e-16
        assert float(abs(mp.mpf(float(got[1])) - ref[1]) / abs(ref[1])) < 5e-16


@pytest.mark.parametrize("a", [1.0, 1 + 2.0 ** -52, 1 - 2.0 ** -53, 1 + 1e-12, 1 - 1e-9, 0.5, 2.0, 1e-300,
                               1e-6, 3.7, 1e8, 1e300])
@pytest.mark.parametrize("b", [1.0, -2.5, 1e-3])
def test_log_is_accurate_to_rounding(a, b):
    with mp.workdps(50):
        A, B = mp.mpf(a), mp.mpf(b)
        ref = (mp.log(A), B if A == 1 else B * mp.log(A) / (A - 1))
        got = G.log([a, b])
        if a != 1.0:
            assert float(abs(mp.mpf(float(got[0])) - ref[0]) / abs(ref[0])) < 2.3e-16
        else:
            assert got[0] == 0.0
        assert float(abs(mp.mpf(float(got[1])) - ref[1]) / abs(ref[1])) < 5e-16


@pytest.mark.parametrize("u", [0.0, 1e-12, -1e-6, 0.3, -1.7, 3.0])
def test_exp_and_log_are_expm_and_logm(u):
    xi = np.array([u, -0.8])
    E = G.matrix(G.exp(xi))
    # scipy's Pade expm is itself off by ~6e-14 relative at u = 3 (mpmath above is the tight check)
    np.testing.assert_allclose(E, scipy.linalg.expm(G.hat(xi)), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(G.hat(G.log(G.exp(xi))), np.real(scipy.linalg.logm(E)), rtol=1e-12, atol=1e-13)
    np.testing.assert_allclose(G.log(G.exp(xi)), xi, rtol=1e-14, atol=1e-15)


def test_exp_is_the_product_integral():
    """exp(xi) as lim (I + xi^/n)^n, (1.49), by the course's own product integral, and by Taylor."""
    xi = np.array([0.9, -1.3])
    four = C.exp_four_ways(G, xi, [4000])
    for m, h in four.items():
        assert np.all(G.isclose(h.elements, G.exp(xi), atol=5e-3 if m in ("euler", "product") else 1e-13)), m


# ------------------------------------------------------------------ membership and bad input
def test_non_positive_scale_is_refused_by_name():
    with pytest.raises(ValueError, match=r"^h must have a positive scale"):
        G.compose([1.0, 0.0], [0.0, 1.0])
    with pytest.raises(ValueError, match=r"^g must have a positive scale"):
        G.log([-1.0, 0.0])
    assert list(G.contains([[2.0, -1.0], [0.0, 1.0], [-1.0, 0.0]])) == [True, False, False]


@pytest.mark.parametrize("M, words", [
    ([[2.0, 1.0], [0.5, 1.0]], "bottom row"),
    ([[2.0, 1.0], [0.0, 2.0]], "bottom row"),
    ([[-2.0, 1.0], [0.0, 1.0]], "positive scale"),
    ([[0.0, 1.0], [0.0, 1.0]], "positive scale"),
])
def test_from_matrix_refuses_non_group_matrices(M, words):
    with pytest.raises(ValueError, match=rf"^G .*{words}"):
        G.from_matrix(M)


def test_vee_refuses_a_non_algebra_matrix():
    with pytest.raises(ValueError, match=r"^X must be a scale-shift algebra matrix"):
        G.vee([[1.0, 2.0], [0.0, 1.0]])


def test_overflow_is_an_error_naming_the_argument():
    with pytest.raises(ValueError, match=r"^xi is out of range"):
        G.exp([800.0, 1.0])
    with pytest.raises(ValueError, match=r"^xi is out of range"):
        G.exp([-800.0, 1.0])
    with pytest.raises(ValueError, match=r"^g and h are out of range"):
        G.compose([1e200, 0.0], [1e200, 0.0])


def test_random_elements_have_positive_scale():
    g = G.random(np.random.default_rng(0), (50,), scale=3.0)
    assert g.shape == (50, 2) and np.all(G.contains(g))
    assert np.all(np.abs(np.log(g[:, 0])) < 3.0) and np.all(np.abs(g[:, 1]) < 9.0)
    with pytest.raises(ValueError, match="scale"):
        G.random(0, 3, scale=1e5)


def test_euler_overshoot_is_returned_not_refused():
    # left Euler steps g + dt T_e L_g xi = (a (1 + dt u), b + dt a v), written out by hand
    h = C.exp_euler(G, [-3.0, 1.0], [1, 2])
    np.testing.assert_allclose(h.elements, [[-2.0, 1.0], [0.25, 0.5 + (-0.5) * 0.5]])

"""Bad input gets a TypeError/ValueError that names the argument, never an IndexError or a silent broadcast."""
import numpy as np
import pytest

from gm_core import ALL_GROUPS, R2, S1, SE2, SO2, R2xS1, Rn, RPlus, matvec, wrap_angle


@pytest.mark.parametrize("bad,exc,words", [
    ("abc", TypeError, "g must be a numeric array"),
    (None, TypeError, "g must be a numeric array"),
    ([1.0, 2.0], ValueError, "shape (..., 3)"),
    ([1.0, 2.0, 3.0, 4.0], ValueError, "shape (..., 3)"),
    (np.zeros((5, 4)), ValueError, "got shape (5, 4)"),
    ([1.0, np.nan, 0.0], ValueError, "NaN"),
    ([1.0, np.inf, 0.0], ValueError, "NaN or infinite"),
    ([["a", "b", "c"]], TypeError, "g must be a numeric array"),
    ({"x": 1}, TypeError, "g must be"),
])
def test_se2_element_errors_name_argument(bad, exc, words):
    with pytest.raises(exc) as info:
        SE2.inverse(bad)
    assert words in str(info.value)


def test_second_argument_is_named():
    with pytest.raises(ValueError, match=r"^h must have shape"):
        SE2.compose([0, 0, 0], [1, 2])
    with pytest.raises(ValueError, match=r"^xi must have shape"):
        SE2.exp([1, 2])
    with pytest.raises(ValueError, match=r"^g_dot must have shape"):
        SE2.world_to_body([0, 0, 0], [1, 2, 3, 4])


def test_no_silent_broadcast_of_mismatched_batches():
    with pytest.raises(ValueError):
        SE2.compose(np.zeros((4, 3)), np.zeros((5, 3)))


@pytest.mark.parametrize("G", list(ALL_GROUPS.values()), ids=list(ALL_GROUPS))
def test_every_group_rejects_wrong_shapes_and_strings(G):
    wrong = np.zeros(G.dim + 1)
    for fn in (G.inverse, G.exp, G.log, G.matrix, G.Ad):
        with pytest.raises(ValueError, match="must have shape"):
            fn(wrong)
        with pytest.raises(TypeError):
            fn("1")
    with pytest.raises(ValueError, match="must have shape"):
        G.from_matrix(np.eye(G.matrix_size + 1))


def test_rplus_rejects_non_positive():
    with pytest.raises(ValueError, match="positive"):
        RPlus.compose([2.0], [-1.0])
    with pytest.raises(ValueError, match="positive"):
        RPlus.log([0.0])


@pytest.mark.parametrize("G", [
    np.diag([2.0, 1.0, 1.0]),                                   # scaling
    np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),  # shear
    np.diag([1.0, -1.0, 1.0]),                                  # reflection (det -1)
    np.array([[1.0, 0.0, 1.0], [0.0, 1.0, 2.0], [0.3, 0.0, 1.0]]),  # bad last row
])
def test_from_matrix_rejects_non_rigid(G):
    with pytest.raises(ValueError, match="G "):
        SE2.from_matrix(G)
    if not np.allclose(G[:2, :2], np.eye(2)):
        with pytest.raises(ValueError, match="not a rotation"):
            SO2.from_matrix(G[:2, :2])


def test_vee_rejects_non_algebra_matrix():
    with pytest.raises(ValueError, match="se\\(2\\)"):
        SE2.vee(np.eye(3))
    with pytest.raises(ValueError, match="skew"):
        SO2.vee(np.eye(2))


def test_constructor_arguments():
    with pytest.raises(ValueError, match="n must be a positive integer"):
        Rn(0)
    with pytest.raises(ValueError, match="period must be a positive number"):
        S1(-1.0)


def test_matrix_arguments_named():
    with pytest.raises(ValueError, match=r"^G must have shape \(\.\.\., 3, 3\)"):
        SE2.from_matrix(np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"^X must have shape"):
        SE2.vee(np.zeros(3))


# ------------------------------------------------------------------ issue #11 reproducers
def test_complex_input_is_refused_by_name():
    for bad in (np.array([1 + 1j, 0, 0.5]), [1 + 1j, 0, 0.5], [np.complex128(1), 0, 0]):
        with pytest.raises(TypeError, match=r"^xi .*complex"):
            SE2.exp(bad)
    with pytest.raises(TypeError, match=r"^theta .*complex"):
        wrap_angle(1j)
    with pytest.raises(TypeError, match=r"^h .*complex"):
        SE2.compose([0, 0, 0], np.zeros(3, complex))


def test_booleans_are_not_numbers():
    with pytest.raises(TypeError, match=r"^g .*boolean"):
        SE2.inverse(np.array([True, False, True]))


@pytest.mark.parametrize("G", list(ALL_GROUPS.values()), ids=list(ALL_GROUPS))
def test_difference_and_isclose_validate(G):
    g = G.identity()
    with pytest.raises(ValueError, match=r"^h must have shape"):
        G.isclose(g, np.zeros(G.param_dim + 1))
    with pytest.raises(ValueError, match=r"^h must have shape"):
        G.difference(g, np.zeros(G.param_dim + 1))
    with pytest.raises(TypeError, match=r"^h must be"):
        G.isclose(g, None)
    with pytest.raises(ValueError, match=r"^g .*NaN"):
        G.difference(np.full(G.param_dim, np.nan), g)
    with pytest.raises(ValueError, match="atol"):
        G.isclose(g, g, atol=-1.0)
    with pytest.raises(ValueError, match=r"g \(batch shape \(4,\)\) and h \(batch shape \(5,\)\)"):
        G.isclose(G.identity(4), G.identity(5))


def test_se2_isclose_reproducers():
    with pytest.raises(ValueError, match="^h"):
        SE2.isclose([0, 0, 0], [0])
    with pytest.raises(TypeError, match="^h"):
        SE2.isclose([0, 0, 0], None)
    assert SE2.isclose([0, 0, 0], [0, 0, 2 * np.pi])
    assert not SE2.isclose([0, 0, 1e8], [0, 0, 1e8 + 1e-6], atol=1e-9)


def test_wrap_angle_refuses_non_numbers():
    for bad in (None, "1.0", [1, "a"]):
        with pytest.raises(TypeError, match="^theta"):
            wrap_angle(bad)
    with pytest.raises(ValueError, match="^theta"):
        wrap_angle(np.nan)


def test_integer_parameters_are_checked_with_bounds():
    with pytest.raises(ValueError, match="at most"):
        Rn(10**12)
    with pytest.raises(TypeError, match="^n must be"):
        Rn(2.5)
    with pytest.raises(TypeError, match="^period"):
        S1("abc")
    with pytest.raises(ValueError, match="^period"):
        S1(np.inf)
    with pytest.raises(ValueError, match="^batch_shape"):
        SE2.identity(batch_shape=-1)
    with pytest.raises(TypeError, match="^batch_shape"):
        SE2.identity(batch_shape="3")
    with pytest.raises(ValueError, match="^batch_shape"):
        SE2.identity(batch_shape=(10**5, 10**5))
    with pytest.raises(ValueError, match="^size"):
        SE2.random(np.random.default_rng(0), -2)
    with pytest.raises(TypeError, match="^rng"):
        SE2.random("seed")


def test_from_matrix_uses_an_absolute_tolerance():
    with pytest.raises(ValueError, match="^G is not a rotation"):
        SE2.from_matrix(np.diag([1.000004, 1.000004, 1.0]))
    with pytest.raises(ValueError, match="^G is not a rotation"):
        SO2.from_matrix(np.diag([1.000004, 1.000004]))
    garbage = R2xS1.matrix([1.0, 2.0, 0.3])
    garbage[0, 4] = 7.0
    with pytest.raises(ValueError, match="^G must be block-diagonal"):
        R2xS1.from_matrix(garbage)
    np.testing.assert_allclose(R2xS1.from_matrix(R2xS1.matrix([1.0, 2.0, 0.3])), [1.0, 2.0, 0.3])
    T = R2.matrix([1.0, 2.0])
    T[0, 0] = 1.000004
    with pytest.raises(ValueError, match="^G must be a translation"):
        R2.from_matrix(T)


def test_mismatched_batches_name_the_arguments():
    with pytest.raises(ValueError, match=r"^g \(batch shape \(4,\)\) and h \(batch shape \(5,\)\)"):
        SE2.compose(np.zeros((4, 3)), np.zeros((5, 3)))
    with pytest.raises(ValueError, match=r"^g .* and g_dot "):
        SE2.world_to_body(np.zeros((4, 3)), np.zeros((5, 3)))
    with pytest.raises(ValueError, match=r"^xi1 .* and xi2 "):
        SE2.bracket(np.zeros((4, 3)), np.zeros((5, 3)))
    with pytest.raises(ValueError, match=r"^g .* and p "):
        SE2.act_on_points(np.zeros((4, 3)), np.zeros((5, 2)))
    with pytest.raises(ValueError, match=r"^M .* and v "):
        matvec(np.zeros((4, 3, 3)), np.zeros((5, 3)))
    with pytest.raises(ValueError, match=r"^M has 3 columns"):
        matvec(np.zeros((3, 3)), np.zeros(2))


def test_lists_work_for_bracket():
    np.testing.assert_array_equal(SE2.bracket([0, 0, 1], [1, 0, 0]), [0.0, 1.0, 0.0])


def test_se2_helix_straight_case_with_a_start():
    from gm_core.fields import se2_helix
    h = se2_helix([1, 0, 0], g0=[1, 2, 0.3])
    assert h.straight and h.radius == np.inf and np.isnan(h.centre).all()
    h = se2_helix([[1, 0, 0], [1, 0, 1]], g0=[1, 2, 0.3])
    np.testing.assert_allclose(h.centre[1], SE2.act_on_points([1, 2, 0.3], [0.0, 1.0]))
    assert se2_helix([1, 0, 0], side="right", g0=[1, 2, 0.3]).radius == np.inf
    with pytest.raises(ValueError, match=r"^xi .* and g0 "):
        se2_helix(np.ones((4, 3)), g0=np.zeros((5, 3)))


def test_calculus_and_fields_counts_and_options():
    from gm_core import calculus as C
    from gm_core import fields as F
    with pytest.raises(ValueError, match="^n must be an integer"):
        C.exp_euler(SE2, [1, 0, 1], 10**9)
    with pytest.raises(ValueError, match="^n must be an integer"):
        C.product_integral(1.0, 0, 1, 0)
    with pytest.raises(ValueError, match="^k must be an integer"):
        C.binomial_terms(10, 10**6)
    with pytest.raises(ValueError, match="^side must be one of"):
        C.exp_product(SE2, [1, 0, 1], 4, side="middle")
    with pytest.raises(TypeError, match="unknown keyword.*tolerance"):
        F.integral_curve(F.left_invariant_field(SE2, [1, 0, 1]), [0, 0, 0], (0, 1), tolerance=1e-3)
    with pytest.raises(ValueError, match="^num"):
        F.se2_helix([1, 0, 1]).circle_points(0)
    with pytest.raises(ValueError, match="^method"):
        F.group_geodesic(SE2, [1, 0, 1], [0, 1], method="rk4")
    with pytest.raises(TypeError, match="^X\\(q, t\\) .*complex"):
        F.VectorField(lambda q, t: q * 1j, 2)([1.0, 2.0])
    with pytest.raises(ValueError, match="^dim"):
        F.VectorField(lambda q, t: q, 10**9)

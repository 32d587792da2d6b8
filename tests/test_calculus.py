"""Tests for gm_core.calculus: product integral, quotient derivative, exp four ways (ex. 1.4d).

Every result is checked by a route independent of the code under test: scipy.linalg.expm,
scipy's ODE solver, analytic derivatives, numpy's polynomial powers, transposition identities.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from gm_core import ALL_GROUPS, SE2, RPlus, SingularShapeError
from gm_core import calculus as C

HYP = settings(max_examples=30, deadline=None)
finite = st.floats(-2.5, 2.5, allow_nan=False, allow_infinity=False)


def se2_xi():
    return st.tuples(finite, finite, finite).map(np.array)


# ------------------------------------------------------------------------- product integral
def test_product_integral_constant_matrix_tends_to_expm_like_one_over_n():
    A = SE2.hat([1.0, 0.5, 2.0])
    errs = []
    for n in (100, 200, 400, 800):
        P = C.product_integral(A, 0.0, 1.0, n)
        errs.append(np.linalg.norm(P - expm(A)))
    errs = np.array(errs)
    ratios = errs[:-1] / errs[1:]
    assert np.allclose(ratios, 2.0, atol=0.05)          # first order, (1.49)
    assert errs[-1] < 5e-3


def test_product_integral_general_matrix_and_interval():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(4, 4))
    P = C.product_integral(A, -1.0, 0.5, 20000, side="left")
    assert np.allclose(P, expm(1.5 * A), rtol=1e-3, atol=1e-3)
    # reversed interval: product integral from b to a inverts it (to first order in 1/n)
    Q = C.product_integral(A, 0.5, -1.0, 20000)
    assert np.allclose(P @ Q, np.eye(4), atol=2e-3)


def test_product_integral_scalar_function_matches_exp_of_integral():
    # prod (1 + v dx) -> exp(int v): v(x) = 2x on [0, 1] gives e.
    vals = [C.product_integral(lambda x: 2 * x, 0.0, 1.0, n) for n in (1000, 2000)]
    assert isinstance(vals[0], float)
    assert abs(vals[1] - math.e) < 2e-3
    assert abs(vals[1] - math.e) < abs(vals[0] - math.e)


@pytest.mark.parametrize("side", ["left", "right"])
def test_product_integral_solves_the_matrix_ode(side):
    """Right product integral solves F' = F v (1.xxx); the left one solves F' = v F (1.xxix)."""
    def v(x):
        return SE2.hat([np.cos(3 * x), x, 1.0 + np.sin(x)])

    def rhs(x, y):
        F = y.reshape(3, 3)
        return (F @ v(x) if side == "right" else v(x) @ F).ravel()

    ref = solve_ivp(rhs, (0.0, 1.5), np.eye(3).ravel(), rtol=1e-11, atol=1e-12).y[:, -1].reshape(3, 3)
    P1 = C.product_integral(v, 0.0, 1.5, 1500, side=side, point="mid")
    P2 = C.product_integral(v, 0.0, 1.5, 3000, side=side, point="mid")
    e1, e2 = np.linalg.norm(P1 - ref), np.linalg.norm(P2 - ref)
    assert e2 < 2e-3 and 1.7 < e1 / e2 < 2.3


def test_left_and_right_product_integrals_differ_and_are_related_by_transpose():
    def v(x):
        return np.array([[0.0, x], [1.0, 0.3]])

    left = C.product_integral(v, 0.0, 1.0, 50, side="left")
    right = C.product_integral(v, 0.0, 1.0, 50, side="right")
    right_T = C.product_integral(lambda x: v(x).T, 0.0, 1.0, 50, side="right")
    assert not np.allclose(left, right, atol=1e-4)
    assert np.allclose(left, right_T.T, atol=1e-12)


def test_product_integral_history_and_sampling_points():
    seen = []
    run = C.product_integral(lambda x: seen.append(x) or np.array([[x]]), 1.0, 2.0, 4,
                             history=True, point="start")
    assert np.allclose(seen, [1.0, 1.25, 1.5, 1.75])
    x, prods = run
    assert np.allclose(x, [1.0, 1.25, 1.5, 1.75, 2.0])
    assert prods.shape == (5, 1, 1) and np.allclose(prods[0], 1.0)
    expected = np.cumprod([1.0] + [1 + s * 0.25 for s in seen])
    assert np.allclose(prods[:, 0, 0], expected)
    assert np.allclose(run.final, prods[-1])
    ends = []
    C.product_integral(lambda x: ends.append(x) or 0.0, 0.0, 1.0, 4)   # default (1.xxi): x_k = k dx
    assert np.allclose(ends, [0.25, 0.5, 0.75, 1.0])
    scal = C.product_integral(0.5, 0.0, 1.0, 3, history=True)
    assert scal.products.shape == (4,) and np.isclose(scal.final, (1 + 0.5 / 3) ** 3)


def test_product_integral_history_matches_final_for_batched_constant():
    A = np.stack([SE2.hat([1.0, 0.0, w]) for w in (0.5, 1.0, 2.0)])
    final = C.product_integral(A, 0.0, 1.0, 64)
    run = C.product_integral(A, 0.0, 1.0, 64, history=True)
    assert final.shape == (3, 3, 3)
    assert np.allclose(run.final, final, atol=1e-13)


# ------------------------------------------------------------------------- quotient derivative
def _trajectory(t):
    return np.array([t ** 2, np.sin(t), 0.5 * t ** 3 - t])


def _trajectory_dot(t):
    return np.array([2 * t, np.cos(t), 1.5 * t ** 2 - 1.0])


@pytest.mark.parametrize("t", [0.0, 0.7, -1.3])
def test_quotient_derivatives_are_body_and_spatial_velocities(t):
    F = lambda s: SE2.matrix(_trajectory(s))  # noqa: E731
    g, gd = _trajectory(t), _trajectory_dot(t)
    # body velocity by the rotation formula (1.26), spatial by xi_s = Ad_g xi with (1.43) entries
    c, s = np.cos(g[2]), np.sin(g[2])
    xi = np.array([c * gd[0] + s * gd[1], -s * gd[0] + c * gd[1], gd[2]])
    xi_s = np.array([gd[0] + g[1] * gd[2], gd[1] - g[0] * gd[2], gd[2]])
    vR = C.quotient_derivative(F, t, side="right")
    vL = C.quotient_derivative(F, t, side="left")
    assert np.allclose(vR, SE2.hat(xi), atol=1e-8)
    assert np.allclose(vL, SE2.hat(xi_s), atol=1e-8)
    vRq = C.quotient_derivative(F, t, side="right", method="quotient")
    assert np.allclose(vRq, SE2.hat(xi), atol=1e-6)


def test_quotient_derivative_of_matrix_exponential_and_scalars():
    rng = np.random.default_rng(3)
    A = rng.normal(size=(3, 3))
    for side in ("left", "right"):
        assert np.allclose(C.quotient_derivative(lambda x: expm(x * A), 0.4, side), A, atol=1e-8)
    # scalar: d/dx exp(x^2) / exp(x^2) = 2x, and an array of x
    assert abs(C.quotient_derivative(lambda x: np.exp(x ** 2), 0.8) - 1.6) < 1e-8
    vals = C.quotient_derivative(lambda x: np.exp(x ** 2), np.array([0.0, 1.0, 2.0]), side="left")
    assert np.allclose(vals, [0.0, 2.0, 4.0], atol=1e-7)
    # the forward quotient (1.xxviii) is first order in h: halving h halves the error
    e = [abs(C.quotient_derivative(lambda x: np.exp(x ** 2), 1.0, h=h, method="quotient") - 2.0)
         for h in (1e-3, 5e-4)]
    assert 1.8 < e[0] / e[1] < 2.2


def test_quotient_derivative_inverts_product_integral():
    # v_R of the running right product integral of v recovers v (the two are inverse operations)
    def v(x):
        return SE2.hat([1.0, x, np.cos(x)])

    def F(x):
        return C.product_integral(v, 0.0, x, 4000, point="mid") if x != 0 else np.eye(3)

    assert np.allclose(C.quotient_derivative(F, 0.6, h=1e-2), v(0.6), atol=1e-3)


def test_quotient_derivative_singular_raises():
    with pytest.raises(SingularShapeError, match="singular"):
        C.quotient_derivative(lambda x: np.array([[x, 0.0], [0.0, 1.0]]) * 0.0, 1.0)


# ------------------------------------------------------------------------- exp four ways
@pytest.mark.parametrize("name", sorted(ALL_GROUPS))
def test_closed_form_matches_expm_of_hat_for_every_group(name):
    G = ALL_GROUPS[name]
    xi = np.linspace(0.4, 1.1, G.dim)
    h = C.exp_closed_form(G, xi, [1, 10])
    assert np.allclose(h.exact_matrix, expm(G.hat(xi)), atol=1e-12)
    assert np.all(h.error == 0.0)


@pytest.mark.parametrize("thetadot", [0.5, 1.0, 2.0, 4.0])
@pytest.mark.parametrize("side", ["left", "right"])
def test_se2_euler_and_product_converge_first_order(thetadot, side):
    xi = [1.0, 0.0, thetadot]
    ns = [64, 128, 256, 512]
    ref = expm(SE2.hat(xi))
    for method in ("euler", "product"):
        h = C.exp_history(SE2, xi, ns, method, side)
        err_ref = np.linalg.norm(h.matrices - ref, axis=(-2, -1))
        assert np.allclose(h.error, err_ref, rtol=1e-6, atol=1e-14)
        assert 0.9 < h.order() < 1.1, (method, h.error)
        assert np.all(np.diff(h.error) < 0)
        # first order: error * n settles to a constant
        assert np.allclose(h.error * h.n, (h.error * h.n)[-1], rtol=0.1)


@pytest.mark.parametrize("thetadot", [0.5, 2.0, 4.0])
def test_taylor_converges_faster_than_any_power(thetadot):
    xi = [1.0, 0.0, thetadot]
    h = C.exp_taylor(SE2, xi, range(1, 40))
    ref = expm(SE2.hat(xi))
    assert np.linalg.norm(h.matrices[-1] - ref) < 1e-12
    # error after n terms is bounded by the tail |A|^n/n! e^|A| (super-exponential decay)
    a = np.linalg.norm(SE2.hat(xi), 2)
    bound = np.array([a ** n / math.factorial(n) * math.exp(a) for n in h.n])
    assert np.all(h.error <= bound * 3 + 1e-13)
    # successive error ratios shrink like |A|/n
    big = h.error > 1e-13
    r = h.error[big][1:] / h.error[big][:-1]
    assert r[-1] < 0.5 * r[len(r) // 2] or r[-1] < 0.2
    # the fitted algebraic order grows with the range of n: not a power law
    assert C.convergence_order(h.n[10:25], h.error[10:25]) > 2 * C.convergence_order(h.n[:10], h.error[:10])


def test_rplus_euler_equals_product_and_both_tend_to_e():
    ns = [1, 10, 100, 1000]
    eu = C.exp_euler(RPlus, [1.0], ns)
    pr = C.exp_product(RPlus, [1.0], ns)
    assert np.allclose(eu.matrices, pr.matrices, rtol=1e-12)
    assert np.allclose(eu.elements[:, 0], [(1 + 1 / n) ** n for n in ns], rtol=1e-12)
    assert abs(pr.matrices[-1, 0, 0] - math.e) < 2e-3
    assert 0.95 < C.convergence_order(pr.n[1:], pr.error[1:]) < 1.05
    ta = C.exp_taylor(RPlus, [1.0], 20)
    assert abs(ta.elements[0, 0] - math.e) < 1e-15 * 10


def test_rplus_euler_follows_the_lifted_action_and_may_overshoot():
    # independent route: step g += dt * T_e L_g xi with the group's own lifted action (1.24)
    g, e = RPlus.identity(), RPlus.identity()
    for _ in range(25):
        g = g + (1 / 25) * (RPlus.left_lifted_action(g, e) @ np.array([0.7]))
    assert np.isclose(C.exp_euler(RPlus, [0.7], 25).elements[0, 0], g[0], rtol=1e-13)
    # too few steps for a fast decay overshoot below zero, out of (R+, x): reported, not rejected
    h = C.exp_euler(RPlus, [-3.0], [1, 2, 4, 64])
    assert np.allclose(h.elements[:, 0], [-2.0, 0.25, 1 / 256, (1 - 3 / 64) ** 64])
    assert h.error[0] > 2 and h.error[-1] < 5e-3
    assert np.allclose(h.path(1).elements[:, 0], [1.0, -2.0])


@pytest.mark.parametrize("name", sorted(ALL_GROUPS))
@pytest.mark.parametrize("side", ["left", "right"])
def test_four_ways_agree_on_every_group(name, side):
    G = ALL_GROUPS[name]
    xi = np.linspace(0.3, 0.8, G.dim)
    four = C.exp_four_ways(G, xi, [2000], side=side)
    assert set(four) == set(C.EXP_METHODS)
    for m, h in four.items():
        tol = 1e-12 if m in ("closed", "taylor") else 5e-3
        assert np.all(G.isclose(h.elements, h.exact, atol=tol)), (m, h.element_error)


def test_euler_paths_differ_by_side_but_reach_the_same_element():
    xi = np.array([1.0, 0.0, 2.0])
    left = C.exp_euler(SE2, xi, 50, "left").path()
    right = C.exp_euler(SE2, xi, 50, "right").path()
    assert left.matrices.shape == (51, 3, 3) and left.elements.shape == (51, 3)
    assert np.allclose(left.s, np.arange(51) / 50)
    # the theta coordinate is exact on both sides (T_e L_g and T_e R_g leave it alone) ...
    assert np.allclose(left.elements[:, 2], 2.0 * left.s)
    assert np.allclose(right.elements[:, 2], 2.0 * right.s)
    # ... but the xy intermediate values differ. Left Euler takes equal steps turning by w dt each
    # time: the vertices of a regular polygon, on a circle of radius dt / (2 sin(w dt / 2)) through
    # the origin. Right Euler is explicit Euler of a rotation about the fixed centre (0, 1/w): each
    # step multiplies the distance from it by sqrt(1 + (w dt)^2), an outward spiral.
    assert np.max(np.abs(left.elements[:, :2] - right.elements[:, :2])) > 1e-2
    dt, w = 1 / 50, 2.0
    rho = dt / (2 * np.sin(w * dt / 2))
    c_left = np.array([dt / 2, np.sqrt(rho ** 2 - (dt / 2) ** 2)])
    assert np.allclose(np.linalg.norm(left.elements[:, :2] - c_left, axis=-1), rho, atol=1e-12)
    r_right = np.linalg.norm(right.elements[:, :2] - [0.0, 0.5], axis=-1)
    assert np.allclose(r_right, 0.5 * (1 + (w * dt) ** 2) ** (np.arange(51) / 2), atol=1e-12)
    for p in (left, right):
        assert np.all(p.error[1:] > 0) and p.error[-1] < 0.05
        assert np.allclose(p.reference, SE2.matrix(SE2.exp(p.s[:, None] * xi)))


def test_product_paths_are_the_same_for_both_sides_and_follow_the_geodesic():
    xi = np.array([1.0, 0.0, 1.5])
    pl = C.exp_product(SE2, xi, 40, "left").path()
    pr = C.exp_product(SE2, xi, 40, "right").path()
    assert np.allclose(pl.matrices, pr.matrices, atol=1e-13)   # powers of one matrix commute
    # the k-th running product (I + A/n)^k approximates exp(k/n A): error <= O(1/n) along the way
    assert np.max(pl.error) < 0.05
    # the running products are not group matrices: the rotation block grows by (1 + (w/n)^2)^(k/2)
    det = np.linalg.det(pl.matrices[-1][:2, :2])
    assert np.isclose(det, (1 + (1.5 / 40) ** 2) ** 40)
    # but the nearest-element angle is k * atan(w/n), a slight undershoot of the exact k w / n
    assert np.allclose(pl.elements[:, 2], np.arange(41) * np.arctan(1.5 / 40))


def test_taylor_and_closed_paths():
    xi = np.array([1.0, -0.5, 2.0])
    tp = C.exp_taylor(SE2, xi, 25).path()
    assert np.allclose(tp.s, np.arange(26))
    assert np.allclose(tp.matrices[0], 0.0) and np.allclose(tp.matrices[1], np.eye(3))
    assert np.allclose(tp.matrices[2], np.eye(3) + SE2.hat(xi))
    assert tp.error[-1] < 1e-12
    cp = C.exp_closed_form(SE2, xi, 8).path()
    assert np.allclose(cp.elements, SE2.exp(cp.s[:, None] * xi))


def test_se2_exp_study_shapes_and_orders():
    study = C.se2_exp_study([0.5, 3.0], n=[32, 64, 128])
    assert set(study) == {"left", "right"}
    for side, methods in study.items():
        assert set(methods) == set(C.EXP_METHODS)
        for h, w in zip(methods["euler"], [0.5, 3.0]):
            assert np.allclose(h.xi, [1.0, 0.0, w]) and h.side == side
            assert 0.9 < h.order() < 1.1
        # faster rotation, bigger error for the same n (first-order constant grows with |w|)
        assert methods["product"][1].error[-1] > methods["product"][0].error[-1]
    with pytest.raises(ValueError, match="thetadots"):
        C.se2_exp_study(np.ones((2, 2)))


@HYP
@given(se2_xi())
def test_taylor_series_equals_closed_form_property(xi):
    h = C.exp_taylor(SE2, xi, 45)
    assert np.all(SE2.isclose(h.elements, SE2.exp(xi), atol=1e-9))


@HYP
@given(se2_xi(), st.sampled_from(["left", "right"]))
def test_euler_error_halves_when_steps_double_property(xi, side):
    h = C.exp_euler(SE2, xi, [200, 400], side)
    if h.error[0] < 1e-10:          # pure rotations / translations are integrated exactly
        assert h.error[1] < 1e-10
    else:
        assert 1.6 < h.error[0] / h.error[1] < 2.4


@pytest.mark.parametrize("name", sorted(ALL_GROUPS))
def test_element_from_matrix_round_trips_group_matrices(name):
    G = ALL_GROUPS[name]
    g = G.random(np.random.default_rng(5), 7)
    assert np.all(G.isclose(C.element_from_matrix(G, G.matrix(g)), g, atol=1e-12))


def test_element_from_matrix_takes_nearest_rotation_angle():
    M = 1.7 * SE2.matrix([0.3, -0.2, 2.5])
    M[2] = [0.0, 0.0, 1.0]
    M[:2, 2] = [0.3, -0.2]
    assert np.allclose(C.element_from_matrix(SE2, M), [0.3, -0.2, 2.5])


# ------------------------------------------------------------------------- binomial (errata 1.50-1.51)
def test_binomial_coefficients_match_polynomial_expansion_not_the_draft():
    n = 7
    coeffs = np.polynomial.polynomial.polypow([1, 1], n)      # coefficients of (1 + y)^n
    for k in range(n + 1):
        c, ratio = C.binomial_terms(n, k)
        assert c == round(coeffs[k])
        assert np.isclose(ratio, coeffs[k] / n ** k)
    assert C.binomial_terms(7, 3)[0] != 7 ** 3 / math.factorial(3)   # the draft's n^k/k!
    # C(n, k)/n^k -> 1/k! as n grows, which is what makes (1.51) hold
    assert abs(C.binomial_terms(10 ** 6, 3)[1] - 1 / 6) < 1e-6


# ------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("call, exc, word", [
    (lambda: C.product_integral("A", 0, 1, 10), TypeError, "v"),
    (lambda: C.product_integral(np.ones((2, 3)), 0, 1, 10), ValueError, "square"),
    (lambda: C.product_integral(np.eye(2), "a", 1, 10), TypeError, "a"),
    (lambda: C.product_integral(np.eye(2), 0, [1, 2], 10), ValueError, "b"),
    (lambda: C.product_integral(np.eye(2), 0, 1, 0), ValueError, "n"),
    (lambda: C.product_integral(np.eye(2), 0, 1, 2.5), TypeError, "n"),
    (lambda: C.product_integral(np.eye(2), 0, 1, 10, side="up"), ValueError, "side"),
    (lambda: C.product_integral(np.eye(2), 0, 1, 10, point="left"), ValueError, "point"),
    (lambda: C.product_integral(lambda x: None, 0, 1, 10), TypeError, "v(x)"),
    (lambda: C.product_integral(np.eye(2) * np.nan, 0, 1, 10), ValueError, "NaN"),
    (lambda: C.quotient_derivative(np.eye(2), 0.0), TypeError, "F"),
    (lambda: C.quotient_derivative(lambda x: np.eye(2), "x"), TypeError, "x"),
    (lambda: C.quotient_derivative(lambda x: np.eye(2), 0.0, h=-1.0), ValueError, "h"),
    (lambda: C.quotient_derivative(lambda x: np.eye(2), 0.0, side=1), ValueError, "side"),
    (lambda: C.quotient_derivative(lambda x: np.eye(2), 0.0, method="x"), ValueError, "method"),
    (lambda: C.exp_euler("SE2", [1, 0, 1], 10), TypeError, "group"),
    (lambda: C.exp_euler(SE2, [1, 0], 10), ValueError, "xi"),
    (lambda: C.exp_euler(SE2, "xi", 10), TypeError, "xi"),
    (lambda: C.exp_euler(SE2, [[1, 0, 1]], 10), ValueError, "xi"),
    (lambda: C.exp_taylor(SE2, [1, 0, 1], [1, 0]), ValueError, "n"),
    (lambda: C.exp_taylor(SE2, [1, 0, 1], None), TypeError, "n"),
    (lambda: C.exp_product(SE2, [1, 0, 1], 10, side="middle"), ValueError, "side"),
    (lambda: C.exp_history(SE2, [1, 0, 1], 10, method="rk4"), ValueError, "method"),
    (lambda: C.exp_history(SE2, [1, 0, 1], 10).path(0), ValueError, "n"),
    (lambda: C.binomial_terms(3, 4), ValueError, "k"),
    (lambda: C.convergence_order([1, 2], [0.0, 0.0]), ValueError, "two"),
    (lambda: C.element_from_matrix(SE2, np.eye(2)), ValueError, "M"),
])
def test_bad_input_names_the_argument(call, exc, word):
    with pytest.raises(exc, match=__import__("re").escape(word)):
        call()

"""Chapter 1 checkers: the references agree with independent routes, and the answer forms a student
may reasonably use (sympy expressions, functions, matrices) are accepted."""
import numpy as np
import pytest
import sympy as sp
from checkhelpers import assert_check_failed, assert_check_passed
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from gm_core import SE2
from gm_core.checks.ex1 import ex1_2, ex1_3, ex1_4, ex1_5
from gm_core.checks.keys.ex1 import EXP_METHODS, _exp_ref, helix_ref

pytestmark = pytest.mark.usefixtures("clean")


def test_exp_reference_matches_expm_on_checker_inputs():
    for (xi,) in ex1_4.a.inputs():
        G = expm(SE2.hat(xi))
        assert SE2.isclose(SE2.from_matrix(G), _exp_ref(xi), atol=1e-10)


def test_exp_reference_is_the_flow_of_both_invariant_fields():
    xi = np.array([0.7, -0.4, 2.3])
    for field in (lambda t, g: SE2.body_to_world(g, xi), lambda t, g: SE2.spatial_to_world(g, xi)):
        sol = solve_ivp(field, (0, 1), np.zeros(3), rtol=1e-11, atol=1e-12)
        assert SE2.isclose(sol.y[:, -1], _exp_ref(xi), atol=1e-8)


def test_helix_reference_against_the_sampled_path():
    for (xi,) in ex1_4.c.inputs():
        w = xi[2]
        period = 2 * np.pi / abs(w)
        t = np.linspace(0, period, 4001)
        path = np.array([SE2.exp(s * xi) for s in t])
        pitch, diameter, arclength = helix_ref(xi)
        assert np.isclose(path[-1, 2] - path[0, 2], pitch)
        span = np.max(np.linalg.norm(path[:, None, :2] - path[None, ::40, :2], axis=-1))
        assert np.isclose(span, diameter, rtol=1e-3, atol=1e-9)
        unit = np.array([SE2.exp(s * xi) for s in np.linspace(0, 1, 4001)])
        assert np.isclose(np.sum(np.linalg.norm(np.diff(unit[:, :2], axis=0), axis=1)), arclength, rtol=1e-5)


def test_reference_methods_converge_at_the_expected_rates():
    xi = np.array([1.0, 0.0, 2.0])
    exact = _exp_ref(xi)

    def err(f, n):
        out = np.asarray(f(xi, n))
        if out.shape == (3, 3):
            out = np.array([out[0, 2], out[1, 2], np.arctan2(out[1, 0], out[0, 0])])
        return np.linalg.norm(SE2.difference(out, exact))

    for name in ("euler_left", "euler_right", "product"):
        assert 0.4 < err(EXP_METHODS[name], 400) / err(EXP_METHODS[name], 200) < 0.6
    assert err(EXP_METHODS["taylor"], 25) < 1e-12


def test_lifted_action_references_match_finite_differences():
    rng = np.random.default_rng(0)
    for (g,) in ex1_3.b.components[0][1].inputs():
        refs = [key.ref for key in ex1_3.b.key.components]
        e = SE2.identity()
        assert np.allclose(refs[0](g), SE2.numerical_left_lifted_action(SE2.inverse(g), g), atol=1e-6)
        assert np.allclose(refs[1](g), SE2.numerical_left_lifted_action(g, e), atol=1e-6)
        assert np.allclose(refs[2](g), SE2.numerical_right_lifted_action(SE2.inverse(g), g), atol=1e-6)
        assert np.allclose(refs[3](g), SE2.numerical_right_lifted_action(g, e), atol=1e-6)
        assert np.allclose(refs[0](g) @ refs[1](g), np.eye(3)) and np.allclose(refs[2](g) @ refs[3](g), np.eye(3))
    h, g = np.exp(rng.normal(size=2)), np.exp(rng.normal(size=2))
    eps = 1e-6
    fd = np.stack([(h * (g + eps * e) - h * (g - eps * e)) / (2 * eps) for e in np.eye(2)], 1)
    assert np.allclose(ex1_2.b.ref(h, g), fd)


def test_sympy_answers_are_accepted():
    g1, g2, h1, h2 = sp.symbols("g1 g2 h1 h2", positive=True)
    assert_check_passed(ex1_2.a, sp.Matrix([h1 * g1, h2 * g2]))
    assert_check_passed(ex1_2.b, sp.diag(h1, h2))
    assert_check_failed(ex1_2.b, sp.diag(g1, g2))
    x, y, th = sp.symbols("x y theta", real=True)
    c, s = sp.cos(th), sp.sin(th)
    se2 = (sp.Matrix([[c, s, 0], [-s, c, 0], [0, 0, 1]]), sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]]),
           sp.Matrix([[1, 0, y], [0, 1, -x], [0, 0, 1]]), sp.Matrix([[1, 0, -y], [0, 1, x], [0, 0, 1]]))
    assert_check_passed(ex1_3.b, se2)
    g = sp.Symbol("g", positive=True)
    assert_check_passed(ex1_3.a, (1 / g, g, 1 / g, g))
    vx, vy, w = sp.symbols("vx vy w", real=True)
    closed = sp.Matrix([(vx * sp.sin(w) - vy * (1 - sp.cos(w))) / w,
                        (vx * (1 - sp.cos(w)) + vy * sp.sin(w)) / w, w])
    assert_check_passed(ex1_4.a, closed)


def test_matrix_answers_and_wrapped_angles_are_accepted():
    assert_check_passed(ex1_4.a, lambda xi: expm(SE2.hat(xi)))
    assert_check_passed(ex1_4.b, lambda xi: SE2.exp(xi) + np.array([0, 0, 2 * np.pi]))
    assert_check_passed(ex1_2.a, lambda h, g: np.diag(h) @ np.diag(g))
    assert_check_failed(ex1_2.a, lambda h, g: np.ones((2, 2)), mentions="off-diagonal")


def test_euler_that_does_not_converge_is_explained():
    bad = dict(EXP_METHODS, euler_right=lambda xi, n: EXP_METHODS["euler_right"](xi, 7))
    assert_check_failed(ex1_4.d, bad, mentions="euler_right")


def test_slide_rule_offset_part():
    assert_check_passed(ex1_5.b, np.log10)
    assert "natural logarithm" in ex1_5.b.check(np.log, quiet=True).message

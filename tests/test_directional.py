"""The directional-linearity box's four examples (gm_core.systems.directional): properties and replays."""
import numpy as np
import pytest
import sympy as sp

from gm_core.systems.directional import PATH_SCALE, RATE_MAPS, rate_map, rate_map_properties, replay

A, B, C, D = list(RATE_MAPS)


def test_which_example_has_which_property():
    props = {k: rate_map_properties(k) for k in RATE_MAPS}
    tol = 1e-12
    assert props[A]["scaling (3.ii)"] < tol and props[A]["odd (3.iii)"] < tol and props[A]["additive (3.iv)"] > 0.1
    assert all(v < tol for v in props[B].values())
    assert props[C]["scaling (3.ii)"] > 0.1 and props[C]["odd (3.iii)"] < tol
    assert props[D]["scaling (3.ii)"] < tol and props[D]["odd (3.iii)"] > 0.1


def test_rate_maps_against_sympy_homogeneity():
    a1, a2, k = sp.symbols("a1 a2 k", positive=True)
    exprs = {A: (a1 ** 3 + a2 ** 3) / (a1 ** 2 + a2 ** 2), C: (a1 ** 3 + a2 ** 3) / sp.sqrt(a1 ** 2 + a2 ** 2)}
    degree = {A: 1, C: 2}
    for name, e in exprs.items():
        assert sp.simplify(e.subs({a1: k * a1, a2: k * a2}, simultaneous=True) - k ** degree[name] * e) == 0
        f = sp.lambdify((a1, a2), e)
        assert np.isclose(rate_map(name)(np.array([0.7, 1.3])), f(0.7, 1.3))


@pytest.mark.parametrize("name", list(RATE_MAPS))
def test_replay_at_another_pace_and_backwards(name):
    s, x1 = replay(name, 1.0)
    _, x3 = replay(name, 3.0)
    _, xb = replay(name, 1.0, reverse=True, x0=x1[-1])
    pace_invariant = np.allclose(x3, x1, atol=1e-12)
    retraces = np.allclose(xb[::-1], x1, atol=1e-12)
    assert pace_invariant == (name != C)
    assert retraces == (name != D)          # odd maps retrace (c too, at the same pace)
    if name == C:
        np.testing.assert_allclose(x3, 3 * x1, atol=1e-12)      # degree 2: three times as far
    # the linear example integrates exactly: x = b(r(s) - r(0))
    if name == B:
        r_end = PATH_SCALE * np.array([np.cos(1.5 * np.pi), 0.6 * np.sin(1.5 * np.pi)])
        assert np.isclose(x1[-1], rate_map(B)(r_end - np.array([PATH_SCALE, 0.0])), atol=1e-12)


def test_bad_names_and_paces():
    with pytest.raises(ValueError, match="name"):
        rate_map("(e)")
    with pytest.raises(ValueError, match="pace"):
        replay(A, pace=-1.0)

"""gm_core.systems.fluids: added mass (closed form and boundary method) and resistive-force drag.

Independent routes: the published closed forms for an ellipse (Lamb section 72, Newman table 4.2)
and their circle and flat-plate limits; sympy integration of the resistive-force law along a link.
"""
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import SE2
from gm_core.systems.fluids import added_mass_bem, drag_wrench, ellipse_added_mass, slender_link_drag


# ------------------------------------------------------------------ added mass
@pytest.mark.parametrize("a, b", [(1.0, 0.4), (1.0, 0.1), (2.0, 1.5), (0.4, 1.0), (0.1, 1.0), (0.7, 0.7)])
def test_boundary_method_matches_the_ellipse_closed_form(a, b):
    rho = 1.3
    M = added_mass_bem(a, b, rho)
    exact = np.diag([np.pi * rho * b ** 2, np.pi * rho * a ** 2, np.pi * rho * (a ** 2 - b ** 2) ** 2 / 8])
    np.testing.assert_allclose(np.diag(M), np.diag(exact), rtol=1e-8, atol=1e-9)
    # the motions decouple for a body symmetric about both axes
    np.testing.assert_allclose(M - np.diag(np.diag(M)), 0, atol=1e-9)
    np.testing.assert_allclose(ellipse_added_mass(a, b, rho), exact, rtol=1e-15)


def test_circle_limit_and_flat_plate_limit():
    # a circle of radius a displaces its own area of fluid: pi rho a^2 each way, nothing when turning
    M = added_mass_bem(0.8, 0.8, 2.0)
    np.testing.assert_allclose(np.diag(M), [np.pi * 2.0 * 0.64, np.pi * 2.0 * 0.64, 0.0], atol=1e-10)
    # a nearly circular ellipse tends to the same numbers continuously
    np.testing.assert_allclose(np.diag(added_mass_bem(0.8, 0.8 * (1 - 1e-6), 2.0)), np.diag(M), atol=1e-5)
    # flat plate of half-width a moving broadside: pi rho a^2 (and pi rho a^4 / 8 turning), Newman table 4.2
    np.testing.assert_allclose(np.diag(ellipse_added_mass(1.5, 0.0)), [0.0, np.pi * 1.5 ** 2, np.pi * 1.5 ** 4 / 8])
    np.testing.assert_allclose(np.diag(added_mass_bem(1.0, 0.05, n=1200, m=600)),
                               np.diag(ellipse_added_mass(1.0, 0.05)), rtol=1e-8)


def test_added_mass_scales_with_density_and_size():
    M1 = added_mass_bem(1.0, 0.3)
    # lengths doubled: translation entries x4 (area), rotation x16; density halved
    np.testing.assert_allclose(np.diag(added_mass_bem(2.0, 0.6, 0.5)), np.diag(M1) * 0.5 * np.array([4, 4, 16]),
                               rtol=1e-10)


def test_added_mass_bad_input():
    with pytest.raises(ValueError, match="a must be"):
        ellipse_added_mass(-1, np.nan)
    with pytest.raises(ValueError, match="b contains NaN"):
        ellipse_added_mass(1, np.nan)
    with pytest.raises(ValueError, match="fluid_density"):
        ellipse_added_mass(1, 0.5, -1.0)
    with pytest.raises(TypeError, match="a must be"):
        ellipse_added_mass("1", 0.5)
    with pytest.raises(ValueError, match="b must be positive"):
        added_mass_bem(1.0, 0.0)
    with pytest.raises(ValueError, match="n must be"):
        added_mass_bem(1.0, 0.5, n=3)
    with pytest.raises(TypeError, match="m must be"):
        added_mass_bem(1.0, 0.5, m=2.5)
    with pytest.raises(ValueError, match="must not exceed"):
        added_mass_bem(1.0, 0.5, n=100, m=200)
    with pytest.raises(ValueError, match="a and b must be numbers"):
        ellipse_added_mass([1.0, 2.0], 0.5)


# ------------------------------------------------------------------ resistive-force drag
def _sympy_link_wrench(pose, vel, length, k):
    """(F_x, F_y, M about the origin) on one link, by exact integration of the drag law."""
    s = sp.symbols("s", real=True)
    x, y, th = [sp.nsimplify(v) for v in pose]
    vx, vy, w = [sp.nsimplify(v) for v in vel]
    t = sp.Matrix([sp.cos(th), sp.sin(th)])
    n = sp.Matrix([-sp.sin(th), sp.cos(th)])
    v = sp.Matrix([vx, vy]) + w * s * n
    f = -(v.dot(t)) * t - sp.nsimplify(k) * (v.dot(n)) * n
    p = sp.Matrix([x, y]) + s * t
    half = sp.nsimplify(length) / 2
    Fx = sp.integrate(f[0], (s, -half, half))
    Fy = sp.integrate(f[1], (s, -half, half))
    M = sp.integrate(p[0] * f[1] - p[1] * f[0], (s, -half, half))
    return np.array([float(sp.N(e, 30)) for e in (Fx, Fy, M)])


@settings(max_examples=15, deadline=None)
@given(st.lists(st.floats(-2, 2), min_size=6, max_size=6), st.floats(0.2, 2.0), st.floats(0.5, 4.0))
def test_drag_quadrature_is_the_exact_integral(v, length, k):
    pose, vel = np.array(v[:3]), np.array(v[3:])
    got = drag_wrench(pose[None], vel[None], [length], k)
    np.testing.assert_allclose(got, _sympy_link_wrench(pose, vel, length, k), rtol=1e-10, atol=1e-10)


def test_drag_of_a_link_in_its_own_frame_is_the_closed_form_matrix():
    rng = np.random.default_rng(5)
    for length, k in [(1.0, 2.0), (0.3, 1.0), (2.5, 3.7)]:
        xi = rng.normal(size=3)
        np.testing.assert_allclose(drag_wrench(np.zeros((1, 3)), xi[None], [length], k, nodes=2),
                                   -slender_link_drag(length, k) @ xi, atol=1e-13)


def test_drag_wrench_batches_and_moves_with_the_frame():
    rng = np.random.default_rng(6)
    P, V = rng.normal(size=(4, 3, 3)), rng.normal(size=(4, 3, 3))
    L = [1.0, 0.7, 1.3]
    W = drag_wrench(P, V, L, 2.0)
    assert W.shape == (4, 3)
    np.testing.assert_allclose(W[2], drag_wrench(P[2], V[2], L, 2.0), atol=1e-14)
    # the same motion seen from a rotated and shifted frame: force rotates, moment moves
    h = np.array([0.4, -1.1, 0.8])
    Ph = SE2.compose(h, P[0])
    Vh = np.concatenate([SE2.act_on_points(np.array([0, 0, h[2]]), V[0, :, :2]), V[0, :, 2:]], -1)
    Wh = drag_wrench(Ph, Vh, L, 2.0)
    F = SE2.act_on_points(np.array([0, 0, h[2]]), W[0, :2])
    np.testing.assert_allclose(Wh[:2], F, atol=1e-12)
    np.testing.assert_allclose(Wh[2], W[0, 2] + h[0] * F[1] - h[1] * F[0], atol=1e-12)


def test_drag_wrench_bad_input():
    with pytest.raises(ValueError, match="lengths"):
        drag_wrench(np.zeros((3, 3)), np.zeros((3, 3)), [1.0, 1.0])
    with pytest.raises(ValueError, match="poses and velocities"):
        drag_wrench(np.zeros((3, 3)), np.zeros((2, 3)), [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="poses must have shape"):
        drag_wrench(np.zeros(3), np.zeros(3), [1.0])
    with pytest.raises(TypeError, match="velocities"):
        drag_wrench(np.zeros((1, 3)), None, [1.0])
    with pytest.raises(ValueError, match="nodes"):
        drag_wrench(np.zeros((1, 3)), np.zeros((1, 3)), [1.0], nodes=0)
    with pytest.raises(ValueError, match="drag_ratio"):
        drag_wrench(np.zeros((1, 3)), np.zeros((1, 3)), [1.0], drag_ratio=0.0)

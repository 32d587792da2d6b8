"""Tests for gm_core.fields: vector fields, integral curves, invariant fields and geodesics.

Independent routes: closed-form solutions of linear ODEs (scipy.linalg.expm), matrix forms of the
invariant fields (g xi^ and xi_s^ g, checked by finite differences of matrices), distances of
sampled points from the predicted circles, numerical arclength, and scipy's ODE solver.
"""
from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.linalg import expm

from gm_core import ALL_GROUPS, SE2, R2xS1, RPlus
from gm_core import fields as F
from gm_core.groups import matvec

HYP = settings(max_examples=25, deadline=None)
coord = st.floats(-2.0, 2.0, allow_nan=False, allow_infinity=False)
se2_xi = st.tuples(coord, coord, coord).map(np.array)


# ------------------------------------------------------------------------- VectorField
def test_vector_field_call_batches_and_checks_shape():
    X = F.VectorField(lambda q, t: np.stack([-q[..., 1], q[..., 0]], -1) * (1 + t), 2, name="rot")
    q = np.array([[1.0, 0.0], [0.0, 2.0]])
    assert np.allclose(X(q, 1.0), [[0.0, 2.0], [-4.0, 0.0]])
    assert X([1.0, 0.0]).shape == (2,)
    bad = F.VectorField(lambda q, t: q[..., :1], 2, name="bad")
    with pytest.raises(ValueError, match="bad"):
        bad(q)


def test_vector_field_not_vectorized_and_on_grid():
    calls = []

    def f(q, t):
        calls.append(q.shape)
        return np.array([q[1], -q[0] + t])

    X = F.VectorField(f, 2, vectorized=False)
    xs, ys = np.linspace(-1, 1, 4), np.linspace(0, 2, 3)
    Xg, Yg, U, V = X.on_grid(xs, ys, t=0.5)
    assert Xg.shape == (3, 4) and U.shape == (3, 4)
    assert set(calls) == {(2,)} and len(calls) == 12
    assert np.allclose(U, Yg) and np.allclose(V, -Xg + 0.5)


def test_on_grid_slice_of_se2_field():
    X = F.left_invariant_field(SE2, [1.0, 0.0, 0.3])
    xs, ths = np.linspace(-1, 1, 5), np.linspace(-np.pi, np.pi, 4)
    Xg, Tg, U, W = X.on_grid(xs, ths, axes=(0, 2), at=[0.0, 7.0, 0.0])
    # x-component of T_e L_g xi is cos(theta) for xi = (1, 0, w); theta-component is w
    assert np.allclose(U, np.cos(Tg)) and np.allclose(W, 0.3)
    with pytest.raises(ValueError, match="axes"):
        X.on_grid(xs, ths, axes=(0, 0))


# ------------------------------------------------------------------------- integral curves
def test_integral_curve_of_linear_field_matches_expm():
    A = np.array([[0.0, 1.0, 0.0], [-2.0, -0.1, 0.3], [0.5, 0.0, -0.4]])
    X = F.VectorField(lambda q, t: matvec(A, q), 3)
    q0 = np.array([1.0, -0.5, 0.2])
    t = np.linspace(0, 3, 7)
    ts, qs = F.integral_curve(X, q0, (0, 3), t_eval=t)
    assert np.allclose(ts, t)
    ref = np.stack([expm(s * A) @ q0 for s in t])
    assert np.allclose(qs, ref, atol=1e-9)


def test_integral_curve_time_dependent_batched_and_backwards():
    X = F.VectorField(lambda q, t: np.broadcast_to(np.array([t, 1.0]), q.shape), 2)
    q0 = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, -1.0]])
    curve = F.integral_curve(X, q0, (0.0, 2.0), t_eval=[0.0, 1.0, 2.0])
    assert curve.q.shape == (3, 3, 2)
    assert np.allclose(curve.q[-1], q0 + [2.0, 2.0])      # int_0^2 t dt = 2
    back = F.integral_curve(X, [0.0, 0.0], (2.0, 0.0), t_eval=[2.0, 0.0])
    assert np.allclose(back.q[-1], [-2.0, -2.0])
    # a plain callable works when q0 fixes the dimension
    t, q = F.integral_curve(lambda q, t: -q, [1.0], (0.0, 1.0), t_eval=[1.0])
    assert np.allclose(q[-1], np.exp(-1.0), atol=1e-10)


def test_integral_curves_do_not_cross_and_solver_failure_is_reported():
    # two curves of a time-invariant field keep their order (uniqueness, section 1.4.1)
    X = F.VectorField(lambda q, t: np.sin(q), 1)
    _, q = F.integral_curve(X, [[0.5], [0.6]], (0, 5), t_eval=np.linspace(0, 5, 50))
    assert np.all(q[:, 1, 0] > q[:, 0, 0])
    blow_up = F.VectorField(lambda q, t: q ** 2, 1, name="blow")
    with pytest.raises(RuntimeError, match="blow"):
        F.integral_curve(blow_up, [1.0], (0.0, 2.0))


# ------------------------------------------------------------------------- invariant fields
@pytest.mark.parametrize("name", sorted(ALL_GROUPS))
def test_invariant_fields_are_lifted_actions_by_finite_differences(name):
    G = ALL_GROUPS[name]
    rng = np.random.default_rng(11)
    g = G.random(rng, 4)
    xi = rng.normal(size=G.dim)
    e = G.identity()
    XL = F.left_invariant_field(G, xi)(g)
    XR = F.right_invariant_field(G, xi)(g)
    assert np.allclose(XL, matvec(G.numerical_left_lifted_action(g, e), xi), atol=1e-7)
    assert np.allclose(XR, matvec(G.numerical_right_lifted_action(g, e), xi), atol=1e-7)


@pytest.mark.parametrize("name", ["SE2", "RPlus", "R2xS1", "SO2", "R2"])
def test_invariant_fields_in_matrix_form(name):
    """d/dt matrix(g) equals matrix(g) xi^ on X_L and xi_s^ matrix(g) on X_R, cf. (1.xxix)-(1.xxx)."""
    G = ALL_GROUPS[name]
    rng = np.random.default_rng(2)
    g = G.random(rng)
    xi = rng.normal(size=G.dim)
    h = 1e-6
    for field, expected in ((F.left_invariant_field(G, xi), G.matrix(g) @ G.hat(xi)),
                            (F.right_invariant_field(G, xi), G.hat(xi) @ G.matrix(g))):
        v = field(g)
        dM = (G.matrix(g + h * v) - G.matrix(g - h * v)) / (2 * h)
        assert np.allclose(dM, expected, atol=1e-7)


# ------------------------------------------------------------------------- geodesics
@pytest.mark.parametrize("name", sorted(ALL_GROUPS))
@pytest.mark.parametrize("side", ["left", "right"])
def test_group_geodesic_closed_form_matches_solve_ivp(name, side):
    G = ALL_GROUPS[name]
    rng = np.random.default_rng(7)
    xi = rng.uniform(-1.0, 1.0, G.dim)
    g0 = G.random(rng)
    t = np.array([-1.0, -0.3, 0.0, 0.4, 1.0, 2.5])
    closed = F.group_geodesic(G, xi, t, side=side, g0=g0)
    solved = F.group_geodesic(G, xi, t, side=side, g0=g0, method="integrate")
    assert closed.shape == (6, G.dim)
    assert np.all(G.isclose(closed, solved, atol=1e-8)), np.abs(G.difference(closed, solved)).max()
    assert np.all(G.isclose(closed[2], g0, atol=1e-14))


@pytest.mark.parametrize("side", ["left", "right"])
def test_se2_geodesic_matrices_are_expm(side):
    xi = np.array([0.7, -0.2, 1.3])
    g0 = np.array([1.0, 2.0, 0.5])
    t = np.linspace(0, 2, 5)
    g = F.group_geodesic(SE2, xi, t, side, g0)
    G0 = SE2.matrix(g0)
    for s, gi in zip(t, g):
        E = expm(s * SE2.hat(xi))
        assert np.allclose(SE2.matrix(gi), G0 @ E if side == "left" else E @ G0, atol=1e-12)


def test_left_and_right_geodesics_from_identity_coincide_but_not_elsewhere():
    xi = np.array([1.0, 0.5, 2.0])
    t = np.linspace(0, 1, 9)
    assert np.allclose(F.group_geodesic(SE2, xi, t, "left"), F.group_geodesic(SE2, xi, t, "right"))
    g0 = np.array([1.0, 0.0, 1.0])
    assert not np.allclose(F.group_geodesic(SE2, xi, t, "left", g0),
                           F.group_geodesic(SE2, xi, t, "right", g0))
    # body velocity is constant along the left geodesic, spatial velocity along the right one
    dt = 1e-6
    for side, convert in (("left", SE2.world_to_body), ("right", SE2.world_to_spatial)):
        gp = F.group_geodesic(SE2, xi, t + dt, side, g0)
        gm = F.group_geodesic(SE2, xi, t - dt, side, g0)
        g = F.group_geodesic(SE2, xi, t, side, g0)
        assert np.allclose(convert(g, (gp - gm) / (2 * dt)), xi, atol=1e-7)


def test_group_geodesic_keeps_the_shape_of_t():
    g = F.group_geodesic(SE2, [1, 0, 1], np.zeros((2, 3)))
    assert g.shape == (2, 3, 3)
    assert F.group_geodesic(RPlus, [0.5], 2.0).shape == (1,)


# ------------------------------------------------------------------------- SE(2) helices (ex. 1.4c)
@HYP
@given(se2_xi)
def test_helix_circle_contains_sampled_geodesic_points(xi):
    assume(abs(xi[2]) > 0.05 and np.hypot(xi[0], xi[1]) > 0.05)
    geo = F.se2_helix(xi)
    t = np.linspace(0, 2 * np.pi / abs(xi[2]), 41)
    g = F.group_geodesic(SE2, xi, t)
    d = np.linalg.norm(g[:, :2] - geo.centre, axis=-1)
    assert np.allclose(d, geo.radius, rtol=1e-9, atol=1e-9)
    assert np.isclose(np.linalg.norm(geo.centre), geo.radius)           # passes through the origin
    assert abs(np.dot(geo.centre, xi[:2])) < 1e-9 * (1 + geo.radius)     # tangent there to (vx, vy)
    # after one period the xy point is back at the start and theta rose by the pitch
    assert np.allclose(g[-1, :2], 0.0, atol=1e-9 * (1 + geo.radius))
    assert np.isclose(g[-1, 2] - g[0, 2], geo.pitch)
    assert np.isclose(geo.diameter, 2 * np.hypot(xi[0], xi[1]) / abs(xi[2]))


@HYP
@given(se2_xi)
def test_helix_arclength_and_slope_by_sampling(xi):
    assume(np.hypot(xi[0], xi[1]) > 0.05)
    geo = F.se2_helix(xi)
    t = np.linspace(0, 1, 4001)
    g = F.group_geodesic(SE2, xi, t)
    s = np.sum(np.linalg.norm(np.diff(g[:, :2], axis=0), axis=-1))     # polyline length
    assert np.isclose(s, geo.arclength, rtol=1e-6)
    assert np.isclose((g[-1, 2] - g[0, 2]) / s, geo.slope, rtol=1e-6, atol=1e-9)
    assert np.isclose(geo.turns, xi[2] / (2 * np.pi))
    if abs(xi[2]) > 0.05:
        assert np.isclose(geo.arclength_per_turn, 2 * np.pi * geo.radius)


@pytest.mark.parametrize("side", ["left", "right"])
def test_helix_circle_moves_with_g0(side):
    xi = np.array([0.8, -0.3, 1.7])
    g0 = np.array([1.5, -0.5, 2.0])
    geo = F.se2_helix(xi, side=side, g0=g0)
    g = F.group_geodesic(SE2, xi, np.linspace(0, 4, 30), side, g0)
    assert np.allclose(np.linalg.norm(g[:, :2] - geo.centre, axis=-1), geo.radius, atol=1e-10)
    if side == "right":   # spatial velocity: the centre is the fixed world point (-vy, vx)/w
        assert np.allclose(geo.centre, [0.3 / 1.7, 0.8 / 1.7])


def test_helix_straight_line_and_batch():
    geo = F.se2_helix([[1.0, 0.0, 0.0], [1.0, 0.0, 2.0]])
    assert list(geo.straight) == [True, False]
    assert np.isinf(geo.radius[0]) and np.isnan(geo.centre[0]).all()
    assert np.allclose(geo.centre[1], [0.0, 0.5]) and geo.pitch[0] == 0.0
    pts = geo.circle_points(16)
    assert pts.shape == (2, 16, 2) and np.isnan(pts[0]).all()
    assert np.allclose(np.linalg.norm(pts[1] - geo.centre[1], axis=-1), 0.5)


def test_se2_helices_family_of_fig_1_18():
    thetadot = np.array([-2.0, -0.5, 0.5, 1.0, 2.0])
    t = np.linspace(0, 3, 50)
    paths, geo = F.se2_helices(thetadot, t)
    assert paths.shape == (5, 50, 3)
    assert np.allclose(geo.centre, np.stack([np.zeros(5), 1 / thetadot], -1))
    d = np.linalg.norm(paths[..., :2] - geo.centre[:, None, :], axis=-1)
    assert np.allclose(d, np.abs(1 / thetadot)[:, None], atol=1e-12)
    assert np.allclose(paths[:, :, 2], thetadot[:, None] * t)            # theta = thetadot t


# ------------------------------------------------------------------------- fig. 1.19 and fig. 1.17
def test_puck_vs_arc_fig_1_19():
    t = np.linspace(0, 2 * np.pi, 101)
    res = F.puck_vs_arc(t)
    # the puck: straight line x = y = t while theta = t; independent route: solve its field
    assert np.allclose(res.puck, np.stack([t, t, t], -1))
    solved = F.group_geodesic(R2xS1, [1, 1, 1], t, method="integrate")
    assert np.allclose(res.puck, solved, atol=1e-9)
    # the SE(2) arc: circle of radius sqrt(2) around (-1, 1) through the origin
    assert np.allclose(np.linalg.norm(res.arc[:, :2] - [-1.0, 1.0], axis=-1), np.sqrt(2))
    assert np.allclose(res.arc_body_velocity, [1.0, 1.0, 1.0])
    # the puck's body velocity rotates: (1, 1) seen from a frame at angle t; forward part changes sign
    c, s = np.cos(t), np.sin(t)
    assert np.allclose(res.puck_body_velocity[:, 0], c + s)
    assert np.allclose(res.puck_body_velocity[:, 1], c - s)
    assert res.puck_body_velocity[:, 0].min() < -1 and res.puck_body_velocity[:, 0].max() > 1


def test_rplus_geodesics_fig_1_17():
    xi = np.array([-1.0, -0.3, 0.3, 1.0])
    t = np.linspace(0, 2, 21)
    g, gdot = F.rplus_geodesics(xi, t, g0=2.0)
    assert g.shape == (4, 21)
    for k, x in enumerate(xi):   # independent route: integrate the left-invariant field g_dot = g xi
        _, q = F.integral_curve(F.left_invariant_field(RPlus, [x]), [2.0], (0, 2), t_eval=t)
        assert np.allclose(g[k], q[:, 0], rtol=1e-9)
    speed = np.abs(gdot)
    assert np.all(np.diff(speed[xi > 0], axis=-1) > 0)     # accelerating
    assert np.all(np.diff(speed[xi < 0], axis=-1) < 0)     # decelerating
    ratio = g[:, 10:] / g[:, :-10]                          # equal times, equal ratios (1.48)
    assert np.allclose(ratio, ratio[:, :1])


# ------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("call, exc, word", [
    (lambda: F.VectorField("f", 2), TypeError, "func"),
    (lambda: F.VectorField(lambda q, t: q, 0), ValueError, "dim"),
    (lambda: F.VectorField(lambda q, t: q, 2)([1.0, 2.0, 3.0]), ValueError, "q"),
    (lambda: F.VectorField(lambda q, t: q, 2)("q"), TypeError, "q"),
    (lambda: F.VectorField(lambda q, t: q, 2)([1.0, 2.0], t=[0, 1]), ValueError, "t"),
    (lambda: F.VectorField(lambda q, t: q, 2).on_grid([[1.0]]), ValueError, "axes_values[0]"),
    (lambda: F.integral_curve(3.0, [1.0], (0, 1)), TypeError, "field"),
    (lambda: F.integral_curve(lambda q, t: q, None, (0, 1)), TypeError, "q0"),
    (lambda: F.integral_curve(lambda q, t: q, [1.0], (0, 0)), ValueError, "t_span"),
    (lambda: F.integral_curve(lambda q, t: q, [1.0], (0, 1, 2)), ValueError, "t_span"),
    (lambda: F.integral_curve(lambda q, t: q, [1.0], (0, 1), t_eval=[2.0]), ValueError, "t_eval"),
    (lambda: F.left_invariant_field("SE2", [1, 0, 0]), TypeError, "group"),
    (lambda: F.left_invariant_field(SE2, [1, 0]), ValueError, "xi"),
    (lambda: F.right_invariant_field(SE2, [1, np.nan, 0]), ValueError, "xi_s"),
    (lambda: F.group_geodesic(SE2, [1, 0, 1], [0, 1], side="top"), ValueError, "side"),
    (lambda: F.group_geodesic(SE2, [1, 0, 1], "t"), TypeError, "t"),
    (lambda: F.group_geodesic(SE2, [1, 0, 1], [0, 1], g0=[1, 2]), ValueError, "g0"),
    (lambda: F.group_geodesic(RPlus, [1], [0, 1], g0=[-1.0]), ValueError, "g0"),
    (lambda: F.group_geodesic(SE2, [1, 0, 1], [0, 1], method="rk4"), ValueError, "method"),
    (lambda: F.group_geodesic(SE2, [[1, 0, 1]], [0, 1]), ValueError, "xi"),
    (lambda: F.se2_helix([1, 0]), ValueError, "xi"),
    (lambda: F.se2_helix([1, 0, 1], side="x"), ValueError, "side"),
    (lambda: F.se2_helices("fast", [0, 1]), TypeError, "thetadot"),
    (lambda: F.puck_vs_arc([0, 1], xi=[1, 1]), ValueError, "xi"),
    (lambda: F.rplus_geodesics([1.0], [0, 1], g0=-2.0), ValueError, "g0"),
])
def test_bad_input_names_the_argument(call, exc, word):
    with pytest.raises(exc, match=re.escape(word)):
        call()

"""Extensible continuum bodies (gm_core.chains.continuum), checked by independent routes and the author's numbers."""
import json
from pathlib import Path

import numpy as np
import pytest
import scipy.integrate
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import SE2
from gm_core import chains as C
from gm_core.chains.continuum import ContinuumBody
from gm_core.systems.slender_body import SlenderBody, segment_modes, serpenoid_modes

REFERENCE = json.loads((Path(__file__).parent / "data" / "author_reference.json").read_text(encoding="utf-8"))
TWO_PI = 2 * np.pi


def _serpenoid_and_wave():
    """The author's E727 stretch wave -cos(4 pi s) with serpenoid curvature, on s in [0, 1]."""
    return ContinuumBody([lambda s: np.cos(TWO_PI * s), lambda s: np.sin(TWO_PI * s)],
                         [lambda s: -np.cos(2 * TWO_PI * s)])


# ----------------------------------------------------------------- the author's numbers
def _authors_body(kind):
    if kind == "constant":
        return ContinuumBody([1.0])
    if kind == "e727":
        return ContinuumBody(stretch_modes=[lambda s: -np.cos(2 * TWO_PI * s)])
    return _serpenoid_and_wave()


@pytest.mark.parametrize("case", REFERENCE["continuum"], ids=lambda c: c["kind"])
def test_backbone_matches_the_authors_numbers(case):
    body = _authors_body(case["kind"])
    np.testing.assert_allclose(body.frames(case["shape"], case["s"]), case["poses"], atol=1e-10)


# ----------------------------------------------------------------- closed forms
@pytest.mark.parametrize("kappa, sigma", [(0.0, 0.0), (1e-9, 0.0), (2.3, 0.0), (-1.7, 0.4), (0.8, -0.3), (6.0, 1.5)])
def test_constant_curvature_and_stretch_is_the_exponential(kappa, sigma):
    body = ContinuumBody([1.0], [1.0], length=1.3)
    s = np.linspace(0.0, 1.3, 9)
    h = np.array([1 + sigma, 0.0, kappa])
    expected = np.array([scipy.linalg.expm(si * SE2.hat(h)) for si in s])
    np.testing.assert_allclose(SE2.matrix(body.frames([kappa, sigma], s)), expected, atol=3e-15)


def test_e727_stretch_in_closed_form():
    body = ContinuumBody(stretch_modes=[lambda s: -np.cos(2 * TWO_PI * s)])
    s = np.linspace(0.0, 1.0, 13)
    for eps in (0.3, 1.0):
        x = s - eps * np.sin(2 * TWO_PI * s) / (2 * TWO_PI)
        np.testing.assert_allclose(body.frames([eps], s), np.stack([x, 0 * s, 0 * s], -1), atol=1e-15)


def test_constant_curvature_jacobian_in_closed_form():
    """d/d kappa of exp(s (1 + sigma, 0, kappa)) and d/d sigma, differentiated symbolically by hand."""
    body = ContinuumBody([1.0], [1.0])
    kappa, sigma = 1.7, 0.25
    s = np.linspace(0.05, 1.0, 6)
    lam, th = 1 + sigma, kappa * s
    x, y = lam * np.sin(th) / kappa, lam * (1 - np.cos(th)) / kappa
    dx_dk = lam * (s * np.cos(th) * kappa - np.sin(th)) / kappa**2
    dy_dk = lam * (s * np.sin(th) * kappa - (1 - np.cos(th))) / kappa**2
    expected = np.stack([np.stack([dx_dk, x / lam], -1), np.stack([dy_dk, y / lam], -1),
                         np.stack([s, 0 * s], -1)], -2)
    np.testing.assert_allclose(body.jacobians([kappa, sigma], s), expected, atol=1e-14)


# ----------------------------------------------------------------- Jacobians by finite differences
@settings(max_examples=20, deadline=None)
@given(st.lists(st.floats(-4, 4), min_size=3, max_size=3), st.sampled_from(["world", "body"]))
def test_jacobians_match_finite_differences(r, velocity):
    body = _serpenoid_and_wave()
    s = np.linspace(0.0, 1.0, 7)
    r = np.array(r) * [1.0, 1.0, 0.2]
    g, J = body.frames_and_jacobians(r, s, velocity=velocity)
    fd = C.finite_difference_jacobians(lambda x: body.frames(x, s), r)
    if velocity == "body":
        fd = C.world_to_body_jacobian(g, fd)
    np.testing.assert_allclose(J, fd, atol=1e-8)


def test_an_ode_solver_agrees():
    """The flow g' = g h(s) by scipy's DOP853 on the homogeneous matrix (no closed form used)."""
    body = _serpenoid_and_wave()
    r = np.array([3.0, -1.2, 0.5])

    def rhs(s, y):
        k = r[0] * np.cos(TWO_PI * s) + r[1] * np.sin(TWO_PI * s)
        h = np.array([1 - r[2] * np.cos(2 * TWO_PI * s), 0.0, k])
        return (y.reshape(3, 3) @ SE2.hat(h)).ravel()

    s = np.linspace(0.0, 1.0, 6)
    sol = scipy.integrate.solve_ivp(rhs, (0, 1), np.eye(3).ravel(), method="DOP853", t_eval=s, rtol=1e-13, atol=1e-13)
    expected = SE2.from_matrix(sol.y.T.reshape(-1, 3, 3))
    np.testing.assert_allclose(body.frames(r, s), expected, atol=1e-10)


# ----------------------------------------------------------------- zero stretch: the existing inextensible models
def test_zero_stretch_is_the_slender_body_backbone():
    """SlenderBody's quadrature poses (middle frame) equal the body's frames seen from its middle."""
    modes, _ = serpenoid_modes(1.0)
    ours = ContinuumBody(list(modes), [lambda s: -np.cos(2 * TWO_PI * s)])
    slender = SlenderBody(1.0, "serpenoid")
    r = np.array([2.5, -1.0])
    s, _, poses, dposes = slender.quadrature_poses(r)
    g = ours.frames([*r, 0.0], np.concatenate([s, [0.5]]))
    np.testing.assert_allclose(C.relative_pose(g[:-1], g[-1]), poses, atol=1e-12)
    # the shape derivatives of the middle-frame poses: SlenderBody's own against differences of ours
    def from_middle(x):
        g = ours.frames([*x, 0.0], np.concatenate([s, [0.5]]))
        return C.relative_pose(g[:-1], g[-1])

    np.testing.assert_allclose(C.finite_difference_jacobians(from_middle, r), dposes, atol=1e-8)


def test_piecewise_constant_curvature_is_a_chain_of_bends():
    """Three bends of the chain module and a body with three constant-curvature pieces: same frames and Jacobians."""
    bounds = [0.0, 0.3, 0.7, 1.0]
    modes = segment_modes(bounds)[0]
    body = ContinuumBody(list(modes), breaks=bounds[1:-1])
    chain = C.Chain("BBB", np.diff(bounds))
    kappa = np.array([1.5, -2.0, 0.7])
    h = chain.frames(kappa)["h"]
    g, J = body.frames_and_jacobians(kappa, bounds[1:])
    np.testing.assert_allclose(g, h, atol=1e-14)
    np.testing.assert_allclose(J, chain.jacobians(kappa, method="body", velocity="world")["h"], atol=1e-13)


def test_batched_shapes_match_loop():
    body = _serpenoid_and_wave()
    r = np.random.default_rng(1).uniform(-2, 2, (2, 3, 3))
    s = [0.0, 0.4, 1.0]
    g, J = body.frames_and_jacobians(r, s)
    assert g.shape == (2, 3, 3, 3) and J.shape == (2, 3, 3, 3, 3)
    for idx in np.ndindex(2, 3):
        g1, J1 = body.frames_and_jacobians(r[idx], s)
        np.testing.assert_allclose(g[idx], g1, atol=1e-15)
        np.testing.assert_allclose(J[idx], J1, atol=1e-15)


def test_curvature_and_stretch_values():
    body = _serpenoid_and_wave()
    s = np.array([0.0, 0.25, 0.6])
    r = [1.5, -0.5, 0.3]
    np.testing.assert_allclose(body.curvature(r, s), 1.5 * np.cos(TWO_PI * s) - 0.5 * np.sin(TWO_PI * s))
    np.testing.assert_allclose(body.stretch(r, s), -0.3 * np.cos(2 * TWO_PI * s))


def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="at least one shape mode"):
        ContinuumBody()
    with pytest.raises(TypeError, match="curvature_modes"):
        ContinuumBody("cos")
    with pytest.raises(TypeError, match=r"stretch_modes\[0\]"):
        ContinuumBody([1.0], ["x"])
    body = ContinuumBody([1.0], [1.0])
    with pytest.raises(ValueError, match="r"):
        body.frames([1.0])
    with pytest.raises(ValueError, match="s must be"):
        body.frames([1.0, 0.0], [1.5])
    with pytest.raises(ValueError, match="velocity"):
        body.jacobians([1.0, 0.0], velocity="spatial")
    with pytest.raises(ValueError, match="breaks"):
        ContinuumBody([1.0], breaks=[1.0])
    with pytest.raises(ValueError, match="mode 0"):
        ContinuumBody([lambda s: np.full_like(s, np.nan)]).frames([1.0])

"""Arc and bend joints and curved links of gm_core.chains.Chain, checked by independent routes and the author's numbers."""
import json
from pathlib import Path

import mpmath
import numpy as np
import pytest
import scipy.linalg
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core import SE2
from gm_core import chains as C
from gm_core.chains.chain import _bend_coefficients

REFERENCE = json.loads((Path(__file__).parent / "data" / "author_reference.json").read_text(encoding="utf-8"))


def _fd(chain, alpha, frame):
    return C.finite_difference_jacobians(lambda a: chain.frames(a)[frame], alpha)


# ----------------------------------------------------------------- the author's E702 chain
@pytest.mark.parametrize("case", REFERENCE["chains"], ids=lambda c: f"arc{c['arc_joint_curvature']}-{c['alpha'][0]}")
def test_arc_chain_matches_the_authors_numbers(case):
    chain = C.Chain(["R", "R", C.Joint("arc", curvature=case["arc_joint_curvature"]), "R"], [1, 1, 1, 1],
                    curvatures=[0, 0, case["arc_link_curvature"], 0])
    frames = chain.frames(case["alpha"])
    for name in "fgh":
        np.testing.assert_allclose(frames[name], case[name], atol=1e-13, err_msg=name)


def test_e702_as_the_author_wrote_it():
    chain = C.Chain("RRAR", [1, 1, 1, 1], curvatures=[0, 0, 1, 0])
    assert chain.joints[2] == C.Joint("arc", curvature=1.0)
    g = chain.frames([1, -0.5, 0.25, 1])["g"]
    # the arc link's medial frame: its proximal frame times exp((1, 0, 1) / 2)
    f3 = chain.frames([1, -0.5, 0.25, 1])["f"][2]
    expected = SE2.from_matrix(SE2.matrix(f3) @ scipy.linalg.expm(SE2.hat([0.5, 0.0, 0.5])))
    np.testing.assert_allclose(g[2], expected, atol=1e-14)


# ----------------------------------------------------------------- Jacobians vs finite differences
JOINT_SETS = ["RBAR", "BB", "PAB", "ABRP", "B"]


@settings(max_examples=25, deadline=None)
@given(st.sampled_from(JOINT_SETS), st.integers(0, 2**31 - 1))
def test_jacobians_three_methods_match_finite_differences(letters, seed):
    rng = np.random.default_rng(seed)
    n = len(letters)
    joints = [C.Joint("arc", curvature=rng.uniform(-2, 2)) if ch == "A" else ch for ch in letters]
    curv = [0.0 if ch == "B" else rng.uniform(-1.5, 1.5) for ch in letters]
    chain = C.Chain(joints, rng.uniform(0.3, 1.5, n), curvatures=curv, base=rng.uniform(-1, 1, 3))
    alpha = rng.uniform(-2, 2, n)
    for method in C.METHODS:
        for velocity in ("world", "body"):
            J = chain.jacobians(alpha, method=method, velocity=velocity)
            for name in "fgh":
                fd = _fd(chain, alpha, name)
                if velocity == "body":
                    fd = C.world_to_body_jacobian(chain.frames(alpha)[name], fd)
                np.testing.assert_allclose(J[name], fd, atol=2e-8, err_msg=f"{method} {velocity} {name}")


def test_mobile_chain_with_arc_joints_matches_finite_differences():
    rng = np.random.default_rng(4)
    for base_link in range(4):
        chain = C.MobileChain([1.0, 0.6, 1.2, 0.8], joints=["A", C.Joint("arc", curvature=-1.3), "R"], base_link=base_link)
        alpha, g = rng.uniform(-1, 1, 3), rng.uniform(-1, 1, 3)
        J = chain.jacobians(alpha, g, method="body")
        J2 = chain.jacobians(alpha, g, method="direct")
        for name in "fgh":
            fd = C.finite_difference_jacobians(lambda a: chain.frames(a, g)[name], alpha)
            np.testing.assert_allclose(J[name][..., 3:], fd, atol=2e-8)
            np.testing.assert_allclose(J2[name], J[name], atol=1e-12)


# ----------------------------------------------------------------- limits and closed forms
def test_bend_at_zero_curvature_is_a_straight_link():
    straight = C.Chain("RR", [0.7, 1.3]).frames([0.4, 0.0])
    bent = C.Chain("RB", [0.7, 1.3]).frames([0.4, 0.0])
    for name in "fgh":
        np.testing.assert_allclose(bent[name], straight[name], atol=1e-15)
    # near zero, the tip swings sideways at l^2 / 2 per unit curvature, (l^2/2) kappa to first order
    for kappa in (1e-12, 1e-8):
        tip = C.Chain("B", [1.3]).end_effector([kappa])
        np.testing.assert_allclose(tip, [1.3, 1.3**2 / 2 * kappa, 1.3 * kappa], rtol=1e-7, atol=1e-300)


def test_bend_is_a_circular_arc():
    L, kappa = 1.4, 2.2
    frames = C.Chain("B", [L]).frames([kappa])
    for name, t in (("g", 0.5), ("h", 1.0)):
        th = kappa * L * t
        np.testing.assert_allclose(frames[name][0], [np.sin(th) / kappa, (1 - np.cos(th)) / kappa, th], atol=1e-15)


def test_arc_joint_tends_to_a_prismatic_joint_and_curved_link_to_a_straight_one():
    alpha = [0.3, 0.8, -0.4]
    near = C.Chain(["R", C.Joint("arc", curvature=1e-10), "R"], [1, 1, 1], curvatures=[1e-10, 0, 0]).frames(alpha)
    flat = C.Chain("RPR", [1, 1, 1]).frames(alpha)
    for name in "fgh":
        np.testing.assert_allclose(near[name], flat[name], atol=1e-9)


@pytest.mark.parametrize("theta", [1e-300, 1e-12, 1e-6, 0.3, 0.999999, 1.0, 1.000001, 2.5, np.pi - 1e-9, 7.0, -0.7, -3.0])
def test_bend_coefficients_match_high_precision(theta):
    a, b = _bend_coefficients(np.array(theta))
    with mpmath.workdps(700):  # enough digits for theta - sin theta at theta = 1e-300
        t = mpmath.mpf(theta)
        a_ref = (t - mpmath.sin(t)) / t**2
        b_ref = (1 - mpmath.cos(t)) / t**2
    assert abs(a - float(a_ref)) <= 4e-16 * abs(float(a_ref)) + 1e-320
    assert abs(b - float(b_ref)) <= 4e-16 * abs(float(b_ref))


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_bend_twist_is_the_body_derivative_of_the_element(sign):
    joint, L, eps = C.Joint("bend"), 0.9, 1e-6
    for q in (0.0, 1e-7, 0.6, -2.4):
        E = joint.element(q, sign, L)
        dE = SE2.difference(joint.element(q + eps, sign, L), joint.element(q - eps, sign, L)) / (2 * eps)
        np.testing.assert_allclose(joint.twist(q, sign, L), SE2.world_to_body(E, dE), atol=1e-9)


def test_backbone_samples_the_links():
    chain = C.Chain("RBA", [1.0, 0.8, 1.1], curvatures=[0.5, 0.0, -1.0])
    alpha = np.array([[0.3, 1.2, 0.4], [-0.2, -0.7, 0.1]])
    bb = chain.backbone(alpha, 5)
    fr = chain.frames(alpha)
    assert bb.shape == (2, 3, 5, 3)
    np.testing.assert_allclose(bb[..., 0, :], fr["f"], atol=1e-14)
    np.testing.assert_allclose(bb[..., 2, :], fr["g"], atol=1e-14)
    np.testing.assert_allclose(bb[..., 4, :], fr["h"], atol=1e-14)


def test_batched_arc_chain_matches_loop():
    chain = C.Chain("BAR", [1.0, 0.5, 0.7])
    alpha = np.random.default_rng(2).uniform(-1, 1, (3, 2, 3))
    J = chain.jacobians(alpha, method="world")["h"]
    for idx in np.ndindex(3, 2):
        np.testing.assert_allclose(J[idx], chain.jacobians(alpha[idx], method="world")["h"], atol=1e-15)


# ----------------------------------------------------------------- bad input
def test_bad_input_names_the_argument():
    with pytest.raises(ValueError, match="curvature must be a finite number"):
        C.Joint("arc", curvature="x")
    with pytest.raises(ValueError, match="curvature: only an arc joint"):
        C.Joint("R", curvature=1.0)
    with pytest.raises(ValueError, match="offsets, curvatures"):
        C.Chain("B", [1.0], offsets=[0.1])
    with pytest.raises(ValueError, match="curvatures"):
        C.Chain("RR", [1.0, 1.0], curvatures=[1.0])
    with pytest.raises(ValueError, match="joints: a mobile chain"):
        C.MobileChain([1.0, 1.0], joints="B")
    with pytest.raises(ValueError, match="bend joint"):
        C.transported_columns(C.Chain("RB", [1.0, 1.0]), [0.1, 0.2])
    with pytest.raises(TypeError, match="length must be a positive number"):
        C.Joint("bend").element(0.3)
    with pytest.raises(ValueError, match="no axis"):
        _ = C.Joint("B").axis
    with pytest.raises(ValueError, match="n must"):
        C.Chain("B", [1.0]).backbone([0.2], n=1)

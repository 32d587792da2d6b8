"""The answer keys of chapter 2's exercises (:mod:`gm_core.checks.ex2`): the references, the
known mistakes and their messages, the judge of 2.1 and the solution texts.

The three-link references call gm_core.chains (one copy of every formula); the independent
routes (finite differences, the group layer) are in tests/test_checks_ch2.py.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from gm_core.chains.three_link import com_frame, com_frame_jacobians, three_link_jacobians
from gm_core.checks.answer_key import FunctionKey, JudgeKey, provide
from gm_core.checks.answers import fmt_value
from gm_core.checks.ex2 import R2, ex2_1, ex2_2, ex2_3, ex2_4, points
from gm_core.checks.parts import outcome_error
from gm_core.checks.sandbox import ProbeOutcome, Wrong
from gm_core.groups import SE2

if TYPE_CHECKING:
    import sympy

    from gm_core.validation import FloatArray

__all__ = ["com_beta", "com_dbeta", "three_link_body_jacobians", "com_jacobian", "links_from_com"]

#: A function of 2.2 (a reference or a known mistake).
_ArrayFunction = Callable[..., npt.ArrayLike]


# ============================================================================ 2.1
def _zeros_along(values: npt.ArrayLike, scale: float) -> list[int]:
    """Indices along a sampled curve where the function crosses or (nearly) touches zero."""
    v = np.asarray(values)
    tol = 1e-7 * scale
    idx = {int(i) for i in np.flatnonzero(np.abs(v) <= tol)}
    idx |= {i for i in range(len(v) - 1) if v[i] * v[i + 1] < 0}
    a = np.abs(v)
    idx |= {i for i in range(1, len(v) - 1) if a[i] <= a[i - 1] and a[i] <= a[i + 1] and a[i] < 1e-2 * scale}
    return sorted(idx)


def _judge_2_1(outcomes: list[ProbeOutcome]) -> str:
    for o in outcomes:
        if o["k"] != "ok":
            outcome_error(o, "your constraint", "a point p")
    G = points()
    f1, f2 = (np.array(outcomes[i]["v"], dtype=float) for i in (0, 1))
    if f1.shape != G["p1"].shape or f2.shape != G["p2"].shape:
        raise Wrong("the check could not evaluate your constraints at every point.")
    f1[G["p1"]], f2[G["p2"]] = f1.copy(), f2.copy()   # back from the order they were visited in
    g_f1, g_f2, g_sphere, g_dirs, g_radii = G["f1"], G["f2"], G["sphere"], G["dirs"], G["radii"]
    g_circle, g_lats, g_zs, g_lons, g_mz, g_mlons = G["circle"], G["lats"], G["zs"], G["lons"], G["mz"], G["mlons"]
    for vals, pts, label in ((f1, g_f1, "f1"), (f2, g_f2, "f2")):
        bad = np.flatnonzero(~np.isfinite(vals))
        if bad.size:
            raise Wrong(f"{label} gives NaN or inf at p = {fmt_value(np.round(pts[bad[0]], 3))}.")
    scale1 = max(1.0, float(np.median(np.abs(f1))))
    sphere, rays = f1[:len(g_sphere)], f1[len(g_sphere):].reshape(len(g_dirs), len(g_radii))
    if np.any(np.abs(sphere) > 1e-7 * scale1):
        for r in (1.0, 2.0):
            k = int(np.argmin(np.abs(g_radii - r)))
            if np.all(np.abs(rays[:, k]) < 1e-2 * scale1) and np.all(np.abs(rays[:, k]) <= np.abs(rays).min(axis=1) + 1e-12):
                raise Wrong(f"f1 vanishes on a sphere of radius {r:g}; the circle x^2 + y^2 = 1, "
                            "z = 1 is not on that sphere, so the two constraints would have no "
                            "common solutions there.")
        raise Wrong("f1 does not vanish everywhere on one sphere centred at (0, 0, 0) through the "
                    "circle; the exercise asks for a first constraint that fixes the distance from "
                    "the origin.")
    for ray in rays:
        for i in _zeros_along(ray, scale1):
            if abs(g_radii[i] - R2) > 0.03 and not (i + 1 < len(g_radii) and g_radii[i] < R2 < g_radii[i + 1]):
                raise Wrong(f"f1 also vanishes near distance {g_radii[i]:.3g} from the origin, so its "
                            "zero set is more than one sphere.")
    scale2 = max(1.0, float(np.median(np.abs(f2))))
    circle = f2[:len(g_circle)]
    if np.any(np.abs(circle) > 1e-7 * scale2):
        p = g_circle[int(np.argmax(np.abs(circle)))]
        raise Wrong(f"f2 does not vanish at the circle point {fmt_value(np.round(p, 3))}, so the "
                    "accessible manifold misses part of the circle.")
    lats = f2[len(g_circle):len(g_circle) + len(g_lats)].reshape(len(g_zs), len(g_lons))
    for z, row in zip(g_zs, lats):
        if np.all(np.abs(row) <= 1e-7 * scale2):
            raise Wrong(f"f2 also vanishes on the whole circle z = {z:.3g} of the same sphere, so "
                        "the accessible manifold would be more than one circle.")
        loop = np.append(row, row[0])
        hits = _zeros_along(loop, scale2)
        if hits:
            t = g_lons[hits[0] % len(g_lons)]
            p = np.array([np.sqrt(2 - z * z) * np.cos(t), np.sqrt(2 - z * z) * np.sin(t), z])
            raise Wrong(f"f2 also vanishes near {fmt_value(np.round(p, 3))}, a point of the sphere "
                        "off the circle, so the accessible manifold is larger than the circle.")
    mer = f2[len(g_circle) + len(g_lats):].reshape(len(g_mlons), len(g_mz))
    for t, col in zip(g_mlons, mer):
        for i in _zeros_along(col, scale2):
            z = g_mz[i]
            if abs(z - 1.0) > 0.04 and not (i + 1 < len(g_mz) and g_mz[i] < 1.0 < g_mz[i + 1]):
                p = np.array([np.sqrt(max(2 - z * z, 0)) * np.cos(t), np.sqrt(max(2 - z * z, 0)) * np.sin(t), z])
                raise Wrong(f"f2 also vanishes near {fmt_value(np.round(p, 3))}, a point of the "
                            "sphere off the circle, so the accessible manifold is larger than the circle.")
    return ("Correct: f1 = 0 is the sphere of radius sqrt(2) about the origin, and on it f2 = 0 cuts "
            "out exactly the circle x^2 + y^2 = 1, z = 1.")


provide(
    ex2_1,
    a=JudgeKey(
        judge=_judge_2_1,
        solution_text="f1 = x^2 + y^2 + z^2 - 2 (the sphere of radius sqrt 2) and f2 = z - 1.",
        reference=(lambda p: p[0] ** 2 + p[1] ** 2 + p[2] ** 2 - 2.0, lambda p: p[2] - 1.0),
        wrong=[(lambda p: p[0] ** 2 + p[1] ** 2 + p[2] ** 2 - 2.0, lambda p: p[0] ** 2 + p[1] ** 2 - 1.0)]),
)


# ============================================================================ 2.2
def _rp_world(alpha: float, delta: float, l1: float, l2: float, a: float) -> FloatArray:
    L = l1 + delta + l2
    c, s = np.cos(alpha), np.sin(alpha)
    return np.array([[-L * s - a * c, c], [L * c - a * s, s], [1.0, 0.0]])


def _rp_body(alpha: float, delta: float, l1: float, l2: float, a: float) -> FloatArray:
    L = l1 + delta + l2
    return np.array([[-a, 1.0], [L, 0.0], [1.0, 0.0]])


def _swapcols(f: Callable[..., FloatArray]) -> Callable[..., FloatArray]:
    return lambda *args: f(*args)[:, ::-1]


def _no_offset(f: _ArrayFunction) -> _ArrayFunction:
    return lambda alpha, delta, l1, l2, a: f(alpha, delta, l1, l2, 0.0)


def _flip_offset(f: _ArrayFunction) -> _ArrayFunction:
    return lambda alpha, delta, l1, l2, a: f(alpha, delta, l1, l2, -a)


def _rp_mistakes(ref: Callable[..., FloatArray], other: _ArrayFunction, other_msg: str,
                 flip_msg: str) -> list[tuple[_ArrayFunction, str]]:
    """The mistakes tried for either Jacobian of exercise 2.2: the other part's answer, the
    offset dropped or flipped, the columns swapped."""
    return [(other, other_msg),
            (_no_offset(ref), "your Jacobian ignores the lateral offset a."),
            (_flip_offset(ref), flip_msg),
            (_swapcols(ref), "your columns are in the order (delta_dot, alpha_dot); use (alpha_dot, delta_dot).")]


provide(
    ex2_2,
    a=FunctionKey(
        ref=_rp_world,
        mistakes=_rp_mistakes(_rp_world, _rp_body, "that is the body-velocity Jacobian (part b); part a "
                              "asks for the world velocity h2_dot.",
                              "the offset terms have the wrong sign: the offset is along +y of link 1's "
                              "distal frame."),
        solution_text="With L = l1 + delta + l2: J = [[-L sin(alpha) - a cos(alpha), cos(alpha)], "
                      "[L cos(alpha) - a sin(alpha), sin(alpha)], [1, 0]]."),
    b=FunctionKey(
        ref=_rp_body,
        mistakes=_rp_mistakes(_rp_body, _rp_world, "that is the world-velocity Jacobian (part a); part b "
                              "asks for the body velocity of h2, expressed in h2's own frame.",
                              "the offset term has the wrong sign: a point offset by +a to the left moves "
                              "backwards (-x) when the arm turns counterclockwise."),
        solution_text="J_b = [[-a, 1], [l1 + delta + l2, 0], [1, 0]]; it equals T_{h2} L_{h2^-1} "
                      "times the world Jacobian of part a."),
)


# ============================================================================ 2.3
def com_beta(alpha: npt.ArrayLike, lengths: npt.ArrayLike, weights: npt.ArrayLike | None = None) -> FloatArray:
    """beta(alpha): the length-weighted CoM / mean-orientation frame, (3,); ex. 2.3a (gm_core.chains)."""
    return com_frame(alpha, lengths, weights)[0]


def com_dbeta(alpha: npt.ArrayLike, lengths: npt.ArrayLike) -> FloatArray:
    """d beta / d alpha (3, 2) of the CoM frame (gm_core.chains)."""
    return com_frame(alpha, lengths)[1]


def three_link_body_jacobians(alpha: npt.ArrayLike, lengths: npt.ArrayLike) -> FloatArray:
    """Adapter: gm_core.chains.three_link.three_link_jacobians stacked into one (3, 3, 5) array."""
    return np.stack(three_link_jacobians(alpha, lengths))


def com_jacobian(alpha: npt.ArrayLike, lengths: npt.ArrayLike) -> FloatArray:
    """Body Jacobian (3, 5) of the CoM frame, (2.62) (gm_core.chains)."""
    return com_frame_jacobians(alpha, lengths)[0]


def links_from_com(alpha: npt.ArrayLike, lengths: npt.ArrayLike) -> FloatArray:
    """Link body Jacobians (3, 3, 5) with the CoM frame as body frame, (2.68) (gm_core.chains)."""
    return np.stack(com_frame_jacobians(alpha, lengths)[1])


def _com_dbeta_only(al: npt.ArrayLike, le: npt.ArrayLike) -> FloatArray:
    beta, dbeta = com_frame(al, le)
    return np.hstack([SE2.Ad_inv(beta), dbeta])


provide(
    ex2_3,
    a=FunctionKey(
        ref=com_beta,
        mistakes=[(lambda al, le: com_beta(al, le, np.ones(3)),
                   "you used the plain (unweighted) mean; with uniform mass per unit length each "
                   "link's weight is its length (the prompt fixes this convention)."),
                  (lambda al, le: com_beta(al, le) * np.array([1, 1, 0]),
                   "your orientation is 0: the frame's angle is the weighted mean of the link "
                   "angles (-alpha1, 0, alpha2).")],
        solution_text="beta = (sum_i l_i p_i) / (l1 + l2 + l3) with p1 = (-l2/2 - l1/2 cos a1, "
                      "l1/2 sin a1, -a1), p2 = 0, p3 = (l2/2 + l3/2 cos a2, l3/2 sin a2, a2)."),
    b=FunctionKey(
        ref=com_jacobian,
        mistakes=[(_com_dbeta_only,
                   "your shape columns are d beta / d alpha itself; the velocity of the frame "
                   "relative to the middle link must be carried to the frame with T_beta R_beta^-1 "
                   "and Ad_beta^-1, (2.61)-(2.62)."),
                  (lambda al, le: np.hstack([SE2.Ad(com_beta(al, le)), com_jacobian(al, le)[:, 3:]]),
                   "your first three columns use Ad_beta where Ad_beta^-1 belongs (2.60).")],
        solution_text="J_com = Ad_beta^-1 [ I_3 | T_beta R_beta^-1 d beta/d alpha ]."),
    c=FunctionKey(
        ref=links_from_com,
        mistakes=[(three_link_body_jacobians, "these are the link Jacobians with the middle link as "
                   "body frame, (2.57)-(2.59); re-express them with xi_middle = Ad_beta xi_com - v_beta "
                   "(2.68).")],
        solution_text="J_i_new = J_i P with P = [[Ad_beta, -T_beta R_beta^-1 dbeta], [0, I]] and J_i "
                      "the middle-link Jacobians (2.57)-(2.59), whose printed third row of (2.59) "
                      "should read (0, 0, 1, 0, 1)."),
)


# ============================================================================ 2.4
def _cob(x: float, y: float, tg: float, th: float) -> FloatArray:
    d = th - tg
    c, s = np.cos(d), np.sin(d)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def _cob_sympy() -> sympy.Matrix:
    import sympy as sp
    tg, th = sp.symbols("theta_g theta_h", real=True)
    d = th - tg
    return sp.Matrix([[sp.cos(d), sp.sin(d), 0], [-sp.sin(d), sp.cos(d), 0], [0, 0, 1]])


provide(
    ex2_4,
    a=FunctionKey(
        ref=_cob,
        mistakes=[(lambda x, y, tg, th: _cob(x, y, tg, th).T,
                   "your rotation goes the wrong way: components in h's frame are those in g's frame "
                   "turned by -(theta_h - theta_g), compare (2.vi)."),
                  (lambda x, y, tg, th: SE2.Ad([x, y, tg]) @ SE2.Ad_inv([x, y, th]),
                   "you multiplied in the other order, Ad_g Ad_h^-1; the change of basis is "
                   "Ad_h^-1 Ad_g (2.viii).")],
        solution_text="Ad_h^-1 Ad_g = [[cos d, sin d, 0], [-sin d, cos d, 0], [0, 0, 1]] with d = "
                      "theta_h - theta_g: the rotation (2.vi), independent of x and y.",
        reference_factory=_cob_sympy),
)

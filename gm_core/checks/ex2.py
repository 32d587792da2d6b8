"""Checkers for the chapter 2 exercises (2.1-2.4): constraints, Jacobians, body frames.

The three-link references call gm_core.chains (one copy of every formula); the independent
routes (finite differences, the group layer) are in tests/test_checks_ch2.py.
"""
from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
from typing_extensions import override

from gm_core.chains.three_link import com_frame, com_frame_jacobians, three_link_jacobians
from gm_core.checks import channel
from gm_core.checks.answers import (
    describe,
    fmt_value,
    is_starter,
    is_sympy,
    sympy_function,
    to_numbers,
)
from gm_core.checks.choice import ChoicePart  # noqa: F401 - kept for chapter modules that add choices
from gm_core.checks.exercise import Exercise
from gm_core.checks.parts import CustomPart, FunctionPart, outcome_error, probe_rng, rng_inputs
from gm_core.checks.sandbox import Probe, ProbeOutcome, Unattempted, Wrong
from gm_core.groups import SE2

if TYPE_CHECKING:
    import sympy

    from gm_core.validation import FloatArray

#: A function of 2.2 (a reference or a known mistake).
_ArrayFunction = Callable[..., npt.ArrayLike]

# ============================================================================ 2.1
_R2 = np.sqrt(2.0)


def _scalar_fn(f: Any, label: str) -> Callable[[FloatArray], Any]:
    """Student side: a constraint given as f(p), f(x, y, z), f(x, y, z=0), f(*p), a sympy
    expression in x, y, z or an equation Eq(lhs, rhs) (read as lhs - rhs)."""
    if is_starter(f):
        raise Unattempted()
    if is_sympy(f):
        import sympy as sp
        expr = f.lhs - f.rhs if isinstance(f, sp.Equality) else f
        if hasattr(expr, "free_symbols"):
            g = sympy_function(expr, ("x", "y", "z"), None, label)
            if g is not None:          # always: expr has free symbols
                return lambda p: g(p[0], p[1], p[2])
    if not callable(f):
        raise Wrong(f"{label} is {describe(f)}; a function of the point p = (x, y, z) (or a sympy "
                    "expression in x, y, z) was expected.")
    try:
        params = list(inspect.signature(f).parameters.values())
        positional = [q for q in params if q.kind in (q.POSITIONAL_ONLY, q.POSITIONAL_OR_KEYWORD)]
        spread = any(q.kind == q.VAR_POSITIONAL for q in params) or len(positional) >= 3
    except (TypeError, ValueError):
        spread = False
    if spread:
        return lambda p: f(p[0], p[1], p[2])
    return f


def _pair(answer: Any) -> Sequence[Any]:
    if is_starter(answer):
        raise Unattempted()
    if not isinstance(answer, (tuple, list)) or len(answer) != 2:
        raise Wrong(f"your answer is {describe(answer)}; give a pair (f1, f2) of constraint functions.")
    if all(is_starter(a) for a in answer):
        raise Unattempted()
    for label, a in zip(("f1", "f2"), answer):
        if is_starter(a):
            raise Wrong(f"{label} is still None; give both constraint functions.")
    return answer


def _values(answer: Any, i: int, points: FloatArray) -> FloatArray:
    """Student side: f_i at every point (NaN where it gives no single number)."""
    label = ("f1", "f2")[i]
    f = _scalar_fn(_pair(answer)[i], label)
    out = np.full(len(points), np.nan)
    for j, p in enumerate(points):
        v = f(np.array(p))
        if is_starter(v):
            if j == 0:
                raise Unattempted(f"{label} still returns None.")
            raise Wrong(f"{label} returned None at p = {fmt_value(p)} (a branch without return?).")
        arr = to_numbers(v, f"the value of {label} at p = {fmt_value(np.round(p, 3))}")
        if arr.size != 1:
            raise Wrong(f"{label} should return one number (a constraint function is scalar); it "
                        f"returned shape {arr.shape}.")
        out[j] = float(arr.reshape(()))
    return out


def _unit(rng: np.random.Generator, n: int) -> FloatArray:
    u = rng.normal(size=(n, 3))
    return u / np.linalg.norm(u, axis=1, keepdims=True)


@functools.lru_cache(maxsize=4)
def _grid(salt: int | None) -> dict[str, FloatArray]:
    """The points where 2.1's constraints are sampled: a sphere of random points, rays along random
    directions (and the poles), the circle, latitude rings and meridians of the sphere. In the
    student's kernel always the same; when grading, the random directions, the rings' longitudes,
    the meridians and the radii along the rays are drawn from this run's salt (``salt``)."""
    rng = probe_rng(21)
    sphere = _R2 * _unit(rng, 30)
    dirs = np.vstack([_unit(rng, 6), [[0, 0, 1.0], [0, 0, -1.0]]])
    radii = np.linspace(0.05, 4.0, 240)
    lon0, mer0, z0 = 0.0, 0.3, 0.0
    if salt is not None:
        radii = radii + rng.uniform(0.0, radii[1] - radii[0])
        lon0 = rng.uniform(0.0, 2 * np.pi / 48)
        mer0 = rng.uniform(0.0, 2 * np.pi / 8)
        z0 = rng.uniform(-0.02, 0.02)
    rays = (dirs[:, None, :] * radii[None, :, None]).reshape(-1, 3)
    circle = np.array([[np.cos(t), np.sin(t), 1.0]
                       for t in lon0 + np.linspace(0, 2 * np.pi, 24, endpoint=False)])
    zs = np.array([z for z in np.linspace(-1.4, 1.4, 57) + z0 if abs(z - 1.0) > 0.04])
    lons = lon0 + np.linspace(0, 2 * np.pi, 48, endpoint=False)
    lats = np.array([[np.sqrt(2 - z * z) * np.cos(t), np.sqrt(2 - z * z) * np.sin(t), z]
                     for z in zs for t in lons])
    mz = np.linspace(-_R2, _R2, 121)
    mlons = np.linspace(0, 2 * np.pi, 8, endpoint=False) + mer0
    meridians = np.array([[np.sqrt(max(2 - z * z, 0)) * np.cos(t), np.sqrt(max(2 - z * z, 0)) * np.sin(t), z]
                          for t in mlons for z in mz])
    f1, f2 = np.vstack([sphere, rays]), np.vstack([circle, lats, meridians])
    # when grading the points are also visited in an order of this run's own
    p1 = rng.permutation(len(f1)) if salt is not None else np.arange(len(f1))
    p2 = rng.permutation(len(f2)) if salt is not None else np.arange(len(f2))
    return {"sphere": sphere, "dirs": dirs, "radii": radii, "circle": circle, "zs": zs,
            "lons": lons, "lats": lats, "mz": mz, "mlons": mlons, "meridians": meridians,
            "f1": f1, "f2": f2, "p1": p1, "p2": p2}


def _points() -> dict[str, FloatArray]:
    return _grid(channel.probe_salt())


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
    G = _points()
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
            if abs(g_radii[i] - _R2) > 0.03 and not (i + 1 < len(g_radii) and g_radii[i] < _R2 < g_radii[i + 1]):
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


def _probes_2_1() -> list[Probe]:
    G = _points()
    return [lambda ans: _values(ans, 0, G["f1"][G["p1"]]), lambda ans: _values(ans, 1, G["f2"][G["p2"]])]


ex2_1 = Exercise("2.1", "Holonomic constraints: the circle as a sphere cut by a second constraint", [
    CustomPart(
        "a", "A pair (f1, f2): f1 fixes the distance from the origin, f1 = f2 = 0 is the circle "
             "x^2 + y^2 = 1 on the plane z = 1", _probes_2_1, _judge_2_1,
        hints=["Which sphere about the origin contains the circle? Compute the distance from the "
               "origin of the point (1, 0, 1).",
               "On that sphere, which second condition keeps the circle and throws away everything "
               "else? Beware of conditions that also hold on a second circle.",
               "x^2 + y^2 = 1 holds on the sphere at z = +1 and at z = -1."],
        solution_text="f1 = x^2 + y^2 + z^2 - 2 (the sphere of radius sqrt 2) and f2 = z - 1.",
        reference=(lambda p: p[0] ** 2 + p[1] ** 2 + p[2] ** 2 - 2.0, lambda p: p[2] - 1.0),
        wrong=[(lambda p: p[0] ** 2 + p[1] ** 2 + p[2] ** 2 - 2.0, lambda p: p[0] ** 2 + p[1] ** 2 - 1.0)],
        starter=(None, None)),
])


# ============================================================================ 2.2
def _rp_world(alpha: float, delta: float, l1: float, l2: float, a: float) -> FloatArray:
    L = l1 + delta + l2
    c, s = np.cos(alpha), np.sin(alpha)
    return np.array([[-L * s - a * c, c], [L * c - a * s, s], [1.0, 0.0]])


def _rp_body(alpha: float, delta: float, l1: float, l2: float, a: float) -> FloatArray:
    L = l1 + delta + l2
    return np.array([[-a, 1.0], [L, 0.0], [1.0, 0.0]])


def _rp_make(rng: np.random.Generator) -> tuple[float, float, float, float, float]:
    return (float(rng.uniform(-np.pi, np.pi)), float(rng.uniform(0, 1)), float(rng.uniform(0.5, 2)),
            float(rng.uniform(0.5, 2)), float(rng.uniform(-0.6, 0.6)))


_rp_inputs = rng_inputs(22, 6, _rp_make, edges=[(0.3, 0.4, 1.0, 1.0, 0.0), (0.0, 0.0, 1.0, 1.0, 0.5),
                                                (2.5, 0.7, 1.5, 0.5, -0.3)])
_RP_NAMES = ("alpha", "delta", "l1", "l2", "a")


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


ex2_2 = Exercise("2.2", "Jacobian of the offset rotary-prismatic arm", [
    FunctionPart(
        "a", "J(alpha, delta, l1, l2, a): world-velocity Jacobian of the end effector h2 (absolute "
             "positions, iterating (2.31)); columns (alpha_dot, delta_dot)",
        ref=_rp_world, inputs=_rp_inputs, arg_names=_RP_NAMES, shape=(3, 2),
        mistakes=_rp_mistakes(_rp_world, _rp_body, "that is the body-velocity Jacobian (part b); part a "
                              "asks for the world velocity h2_dot.",
                              "the offset terms have the wrong sign: the offset is along +y of link 1's "
                              "distal frame."),
        hints=["Start from g1_dot = (0, 0, alpha_dot) and carry the velocity to the end of link 1 "
               "with the right lifted action, (2.24).",
               "The prismatic joint adds (delta_dot cos alpha, delta_dot sin alpha, 0) in world "
               "coordinates, since it slides along link 1's x axis.",
               "Check: with a = 0 your answer must reduce to the world form of (2.45)."],
        solution_text="With L = l1 + delta + l2: J = [[-L sin(alpha) - a cos(alpha), cos(alpha)], "
                      "[L cos(alpha) - a sin(alpha), sin(alpha)], [1, 0]]."),
    FunctionPart(
        "b", "J_b(alpha, delta, l1, l2, a): body-velocity Jacobian of h2 (relative positions, "
             "(2.37)); columns (alpha_dot, delta_dot)",
        ref=_rp_body, inputs=_rp_inputs, arg_names=_RP_NAMES, shape=(3, 2),
        mistakes=_rp_mistakes(_rp_body, _rp_world, "that is the world-velocity Jacobian (part a); part b "
                              "asks for the body velocity of h2, expressed in h2's own frame.",
                              "the offset term has the wrong sign: a point offset by +a to the left moves "
                              "backwards (-x) when the arm turns counterclockwise."),
        hints=["Follow (2.38)-(2.45): body velocities, with Ad^-1 of each frame relative to the "
               "previous one.",
               "The only new ingredient is the offset. Seen from the rotary joint's frame g1 (at the "
               "joint, turning with link 1), h2 sits at (l1 + delta + l2, a, 0): everything along the "
               "links adds up in x, the offset a is sideways.",
               "Ad^-1 of (x, y, 0) is [[1, 0, -y], [0, 1, x], [0, 0, 1]]."],
        solution_text="J_b = [[-a, 1], [l1 + delta + l2, 0], [1, 0]]; it equals T_{h2} L_{h2^-1} "
                      "times the world Jacobian of part a."),
])


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


def _tl_make(rng: np.random.Generator) -> tuple[FloatArray, FloatArray]:
    lengths = rng.uniform(0.5, 2.0, 3) if rng.uniform() < 0.6 else np.ones(3)
    return (rng.uniform(-1.6, 1.6, 2), lengths)


_tl_inputs = rng_inputs(23, 6, _tl_make, edges=[(np.zeros(2), np.ones(3)),
                                                (np.array([0.7, -0.4]), np.array([1.0, 2.0, 0.5]))])


def _links_post(out: Any, args: tuple[Any, ...]) -> Any:
    """Accept a (3, 3, 5) array or a sequence of three (3, 5) matrices."""
    if isinstance(out, (list, tuple)) and len(out) == 3:
        return np.stack([to_numbers(o, "each link Jacobian") for o in out])
    return out


ex2_3 = Exercise("2.3", "Three-link system: the centre-of-mass / mean-orientation body frame", [
    FunctionPart(
        "a", "beta(alpha, lengths): the CoM frame relative to the middle link, (x, y, theta)",
        ref=com_beta, inputs=_tl_inputs, arg_names=("alpha", "lengths"), shape=(3,),
        mistakes=[(lambda al, le: com_beta(al, le, np.ones(3)),
                   "you used the plain (unweighted) mean; with uniform mass per unit length each "
                   "link's weight is its length (the prompt fixes this convention)."),
                  (lambda al, le: com_beta(al, le) * np.array([1, 1, 0]),
                   "your orientation is 0: the frame's angle is the weighted mean of the link "
                   "angles (-alpha1, 0, alpha2).")],
        hints=["Write the pose of each link's centre relative to the middle link, e.g. link 3 is "
               "(l2/2, 0, 0) then a turn by alpha2 then (l3/2, 0, 0).",
               "Link 1 is turned by -alpha1 relative to link 2 (the sign convention of Figure 2.6).",
               "Average positions and angles with weights l1, l2, l3."],
        solution_text="beta = (sum_i l_i p_i) / (l1 + l2 + l3) with p1 = (-l2/2 - l1/2 cos a1, "
                      "l1/2 sin a1, -a1), p2 = 0, p3 = (l2/2 + l3/2 cos a2, l3/2 sin a2, a2)."),
    FunctionPart(
        "b", "J_com(alpha, lengths): body Jacobian (3 x 5) of the CoM frame, columns (xi, alpha_dot) "
             "of the middle link",
        ref=com_jacobian, inputs=_tl_inputs, arg_names=("alpha", "lengths"), shape=(3, 5),
        mistakes=[(_com_dbeta_only,
                   "your shape columns are d beta / d alpha itself; the velocity of the frame "
                   "relative to the middle link must be carried to the frame with T_beta R_beta^-1 "
                   "and Ad_beta^-1, (2.61)-(2.62)."),
                  (lambda al, le: np.hstack([SE2.Ad(com_beta(al, le)), com_jacobian(al, le)[:, 3:]]),
                   "your first three columns use Ad_beta where Ad_beta^-1 belongs (2.60).")],
        hints=["Use (2.62): xi_g = Ad_beta^-1 (xi + T_beta R_beta^-1 (d beta / d alpha) alpha_dot).",
               "Or the compact form (2.66): rotate by T_beta L_beta^-1 the sum T_e R_beta xi + "
               "(d beta / d alpha) alpha_dot.",
               "A finite-difference check: move the middle link along exp(t xi), change alpha by "
               "t alpha_dot, and differentiate the pose of the CoM frame."],
        solution_text="J_com = Ad_beta^-1 [ I_3 | T_beta R_beta^-1 d beta/d alpha ]."),
    FunctionPart(
        "c", "links(alpha, lengths): the three link body Jacobians (3, 3, 5) with the CoM frame as "
             "system body frame, columns (xi_com, alpha_dot)",
        ref=links_from_com, inputs=_tl_inputs, arg_names=("alpha", "lengths"), shape=(3, 3, 5),
        postprocess=_links_post,
        mistakes=[(three_link_body_jacobians, "these are the link Jacobians with the middle link as "
                   "body frame, (2.57)-(2.59); re-express them with xi_middle = Ad_beta xi_com - v_beta "
                   "(2.68).")],
        hints=["Invert (2.60): the middle link's body velocity is Ad_beta xi_com - v_beta, (2.68).",
               "Substitute it into the middle-link Jacobians: J_i_new = J_i_old P with "
               "P = [[Ad_beta, -T_beta R_beta^-1 d beta/d alpha], [0, I_2]].",
               "Self-test: with the same P, J_com P must be [I_3 | 0], since the CoM frame's body "
               "velocity is then xi_com itself."],
        solution_text="J_i_new = J_i P with P = [[Ad_beta, -T_beta R_beta^-1 dbeta], [0, I]] and J_i "
                      "the middle-link Jacobians (2.57)-(2.59), whose printed third row of (2.59) "
                      "should read (0, 0, 1, 0, 1)."),
])


# ============================================================================ 2.4
def _cob(x: float, y: float, tg: float, th: float) -> FloatArray:
    d = th - tg
    c, s = np.cos(d), np.sin(d)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


class ShowThatPart(FunctionPart):
    """A symbolic "show that" answer: a sympy object, numerically right, from which the symbols
    ``eliminated`` have dropped out (the property the exercise shows)."""

    kind: str = "show"

    def __init__(self, *a: Any, eliminated: Sequence[str] = (),
                 reference_factory: Callable[[], Any] | None = None, **kw: Any) -> None:
        self._reference_factory = reference_factory
        super().__init__(*a, **kw)
        self.eliminated = tuple(eliminated)

    @property
    @override
    def reference(self) -> Any:
        """A correct answer (built with sympy on first use, so importing stays light)."""
        if self._reference_factory is not None:
            return self._reference_factory()
        return self._reference

    @reference.setter
    def reference(self, value: Any) -> None:
        self._reference = value

    def _symbols(self, answer: Any) -> list[str]:
        if is_starter(answer):
            raise Unattempted()
        if not (is_sympy(answer) or isinstance(answer, (list, tuple))):
            raise Wrong(f"your answer is {describe(answer)}; this part shows a property, so give the "
                        "simplified sympy matrix (a function would hide the simplification).")
        return sorted({str(x) for x in getattr(_as_matrix(answer), "free_symbols", ())})

    @override
    def probes(self) -> list[Probe]:
        return [self._symbols, *super().probes()]

    @override
    def judge(self, outcomes: list[ProbeOutcome]) -> str:
        if not outcomes:
            raise Wrong("the check could not evaluate your answer.")
        if outcomes[0]["k"] != "ok":
            outcome_error(outcomes[0], "your answer", "")
        message = super().judge(outcomes[1:])
        left = [s for s in outcomes[0]["v"] if s in self.eliminated]
        if left:
            raise Wrong(f"your matrix has the right values but still contains {', '.join(left)}: "
                        "simplify it (sp.simplify) so that they drop out; that is what the exercise "
                        "shows.")
        return message


def _cob_sympy() -> sympy.Matrix:
    import sympy as sp
    tg, th = sp.symbols("theta_g theta_h", real=True)
    d = th - tg
    return sp.Matrix([[sp.cos(d), sp.sin(d), 0], [-sp.sin(d), sp.cos(d), 0], [0, 0, 1]])


def _as_matrix(answer: Any) -> Any:
    import sympy as sp
    return sp.Matrix(answer) if isinstance(answer, (list, tuple)) else answer


ex2_4 = Exercise("2.4", "Ad_h^-1 Ad_g with equal positions is a rotation (change of basis)", [
    ShowThatPart(
        "a", "The product Ad_h^-1 Ad_g for g = (x, y, theta_g), h = (x, y, theta_h), as a simplified "
             "sympy matrix in x, y, theta_g, theta_h", eliminated=("x", "y"),
        ref=_cob, arg_names=("x", "y", "theta_g", "theta_h"), shape=(3, 3),
        inputs=rng_inputs(24, 6, lambda rng: tuple(rng.uniform(-3, 3, 4)),
                          edges=[(0.0, 0.0, 0.0, 0.0), (2.0, -1.0, 0.3, 0.3), (1.0, 1.0, 0.0, np.pi)]),
        mistakes=[(lambda x, y, tg, th: _cob(x, y, tg, th).T,
                   "your rotation goes the wrong way: components in h's frame are those in g's frame "
                   "turned by -(theta_h - theta_g), compare (2.vi)."),
                  (lambda x, y, tg, th: SE2.Ad([x, y, tg]) @ SE2.Ad_inv([x, y, th]),
                   "you multiplied in the other order, Ad_g Ad_h^-1; the change of basis is "
                   "Ad_h^-1 Ad_g (2.viii).")],
        hints=["Write Ad_g from (1.43) and Ad_h^-1 from (1.45) with the same x and y.",
               "Multiply and simplify with trigonometric identities (sympy: simplify or trigsimp).",
               "The translation entries cancel; the 2x2 block is a rotation by theta_g - theta_h."],
        solution_text="Ad_h^-1 Ad_g = [[cos d, sin d, 0], [-sin d, cos d, 0], [0, 0, 1]] with d = "
                      "theta_h - theta_g: the rotation (2.vi), independent of x and y.",
        reference_factory=_cob_sympy),
])

__all__ = ["ex2_1", "ex2_2", "ex2_3", "ex2_4"]

"""Checkers for the chapter 2 exercises (2.1-2.4): constraints, Jacobians, body frames.

The probes only turn the student's answers into plain data; what a right answer is (references,
mistakes, the judge of 2.1) lives in :mod:`gm_core.checks.keys.ex2`, whose three-link references
call gm_core.chains (one copy of every formula). The independent routes (finite differences, the
group layer) are in tests/test_checks_ch2.py.
"""
from __future__ import annotations

import functools
import inspect
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from typing_extensions import override

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

if TYPE_CHECKING:
    from gm_core.validation import FloatArray

# ============================================================================ 2.1
#: The radius of the sphere on which 2.1's constraints are sampled.
R2 = np.sqrt(2.0)


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
    sphere = R2 * _unit(rng, 30)
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
    mz = np.linspace(-R2, R2, 121)
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


def points() -> dict[str, FloatArray]:
    """The points where 2.1's constraints are sampled (this run's, :func:`_grid`), by name."""
    return _grid(channel.probe_salt())


def _probes_2_1() -> list[Probe]:
    G = points()
    return [lambda ans: _values(ans, 0, G["f1"][G["p1"]]), lambda ans: _values(ans, 1, G["f2"][G["p2"]])]


ex2_1 = Exercise("2.1", "Holonomic constraints: the circle as a sphere cut by a second constraint", [
    CustomPart(
        "a", "A pair (f1, f2): f1 fixes the distance from the origin, f1 = f2 = 0 is the circle "
             "x^2 + y^2 = 1 on the plane z = 1", _probes_2_1,
        hints=["Which sphere about the origin contains the circle? Compute the distance from the "
               "origin of the point (1, 0, 1).",
               "On that sphere, which second condition keeps the circle and throws away everything "
               "else? Beware of conditions that also hold on a second circle.",
               "x^2 + y^2 = 1 holds on the sphere at z = +1 and at z = -1."],
        starter=(None, None)),
])


# ============================================================================ 2.2
def _rp_make(rng: np.random.Generator) -> tuple[float, float, float, float, float]:
    return (float(rng.uniform(-np.pi, np.pi)), float(rng.uniform(0, 1)), float(rng.uniform(0.5, 2)),
            float(rng.uniform(0.5, 2)), float(rng.uniform(-0.6, 0.6)))


_rp_inputs = rng_inputs(22, 6, _rp_make, edges=[(0.3, 0.4, 1.0, 1.0, 0.0), (0.0, 0.0, 1.0, 1.0, 0.5),
                                                (2.5, 0.7, 1.5, 0.5, -0.3)])
_RP_NAMES = ("alpha", "delta", "l1", "l2", "a")


ex2_2 = Exercise("2.2", "Jacobian of the offset rotary-prismatic arm", [
    FunctionPart(
        "a", "J(alpha, delta, l1, l2, a): world-velocity Jacobian of the end effector h2 (absolute "
             "positions, iterating (2.31)); columns (alpha_dot, delta_dot)",
        inputs=_rp_inputs, arg_names=_RP_NAMES, shape=(3, 2),
        hints=["Start from g1_dot = (0, 0, alpha_dot) and carry the velocity to the end of link 1 "
               "with the right lifted action, (2.24).",
               "The prismatic joint adds (delta_dot cos alpha, delta_dot sin alpha, 0) in world "
               "coordinates, since it slides along link 1's x axis.",
               "Check: with a = 0 your answer must reduce to the world form of (2.45)."]),
    FunctionPart(
        "b", "J_b(alpha, delta, l1, l2, a): body-velocity Jacobian of h2 (relative positions, "
             "(2.37)); columns (alpha_dot, delta_dot)",
        inputs=_rp_inputs, arg_names=_RP_NAMES, shape=(3, 2),
        hints=["Follow (2.38)-(2.45): body velocities, with Ad^-1 of each frame relative to the "
               "previous one.",
               "The only new ingredient is the offset. Seen from the rotary joint's frame g1 (at the "
               "joint, turning with link 1), h2 sits at (l1 + delta + l2, a, 0): everything along the "
               "links adds up in x, the offset a is sideways.",
               "Ad^-1 of (x, y, 0) is [[1, 0, -y], [0, 1, x], [0, 0, 1]]."]),
])


# ============================================================================ 2.3
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
        inputs=_tl_inputs, arg_names=("alpha", "lengths"), shape=(3,),
        hints=["Write the pose of each link's centre relative to the middle link, e.g. link 3 is "
               "(l2/2, 0, 0) then a turn by alpha2 then (l3/2, 0, 0).",
               "Link 1 is turned by -alpha1 relative to link 2 (the sign convention of Figure 2.6).",
               "Average positions and angles with weights l1, l2, l3."]),
    FunctionPart(
        "b", "J_com(alpha, lengths): body Jacobian (3 x 5) of the CoM frame, columns (xi, alpha_dot) "
             "of the middle link",
        inputs=_tl_inputs, arg_names=("alpha", "lengths"), shape=(3, 5),
        hints=["Use (2.62): xi_g = Ad_beta^-1 (xi + T_beta R_beta^-1 (d beta / d alpha) alpha_dot).",
               "Or the compact form (2.66): rotate by T_beta L_beta^-1 the sum T_e R_beta xi + "
               "(d beta / d alpha) alpha_dot.",
               "A finite-difference check: move the middle link along exp(t xi), change alpha by "
               "t alpha_dot, and differentiate the pose of the CoM frame."]),
    FunctionPart(
        "c", "links(alpha, lengths): the three link body Jacobians (3, 3, 5) with the CoM frame as "
             "system body frame, columns (xi_com, alpha_dot)",
        inputs=_tl_inputs, arg_names=("alpha", "lengths"), shape=(3, 3, 5),
        postprocess=_links_post,
        hints=["Invert (2.60): the middle link's body velocity is Ad_beta xi_com - v_beta, (2.68).",
               "Substitute it into the middle-link Jacobians: J_i_new = J_i_old P with "
               "P = [[Ad_beta, -T_beta R_beta^-1 d beta/d alpha], [0, I_2]].",
               "Self-test: with the same P, J_com P must be [I_3 | 0], since the CoM frame's body "
               "velocity is then xi_com itself."]),
])


# ============================================================================ 2.4
class ShowThatPart(FunctionPart):
    """A symbolic "show that" answer: a sympy object, numerically right, from which the symbols
    ``eliminated`` have dropped out (the property the exercise shows)."""

    kind: str = "show"

    def __init__(self, *a: Any, eliminated: Sequence[str] = (), **kw: Any) -> None:
        super().__init__(*a, **kw)
        self.eliminated = tuple(eliminated)

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


def _as_matrix(answer: Any) -> Any:
    import sympy as sp
    return sp.Matrix(answer) if isinstance(answer, (list, tuple)) else answer


ex2_4 = Exercise("2.4", "Ad_h^-1 Ad_g with equal positions is a rotation (change of basis)", [
    ShowThatPart(
        "a", "The product Ad_h^-1 Ad_g for g = (x, y, theta_g), h = (x, y, theta_h), as a simplified "
             "sympy matrix in x, y, theta_g, theta_h", eliminated=("x", "y"),
        arg_names=("x", "y", "theta_g", "theta_h"), shape=(3, 3),
        inputs=rng_inputs(24, 6, lambda rng: tuple(rng.uniform(-3, 3, 4)),
                          edges=[(0.0, 0.0, 0.0, 0.0), (2.0, -1.0, 0.3, 0.3), (1.0, 1.0, 0.0, np.pi)]),
        hints=["Write Ad_g from (1.43) and Ad_h^-1 from (1.45) with the same x and y.",
               "Multiply and simplify with trigonometric identities (sympy: simplify or trigsimp).",
               "The translation entries cancel; the 2x2 block is a rotation by theta_g - theta_h."]),
])

__all__ = ["ex2_1", "ex2_2", "ex2_3", "ex2_4", "R2", "points"]

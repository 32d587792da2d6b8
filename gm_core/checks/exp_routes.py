"""Exercise 1.4's machinery: SE(2) exp references, the four numerical routes of 1.4(d) and
their judge. Used by ex1.py (split off to keep each file readable in one sitting)."""
from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from gm_core.checks.answers import fmt_value, is_starter, match_shape, to_numbers
from gm_core.checks.parts import FunctionPart, first_value, outcome_error, probe_rng, rng_inputs, salted
from gm_core.checks.sandbox import Probe, ProbeOutcome, Unattempted, Wrong
from gm_core.groups import SE2, wrap_angle

if TYPE_CHECKING:
    from gm_core.validation import FloatArray

#: A route of 1.4(d): ``f(xi, n)``, exp(xi) after n steps, as (x, y, theta) or a 3 x 3 matrix.
Route = Callable[[npt.ArrayLike, int], npt.ArrayLike]


def _se2_vec(out: Any, args: object, nan_ok: bool = True) -> FloatArray:
    """Accept (x, y, theta) or a 3x3 homogeneous matrix; wrap the angle to (-pi, pi]."""
    arr = to_numbers(out, "the value your function returned")
    if arr.shape == (3, 3):
        arr = np.array([arr[0, 2], arr[1, 2], np.arctan2(arr[1, 0], arr[0, 0])])
    arr = match_shape(arr, (3,), "the value your function returned")
    return np.array([arr[0], arr[1], wrap_angle(arr[2])])


def _exp_ref(xi: npt.ArrayLike) -> FloatArray:
    e = SE2.exp(np.asarray(xi, dtype=float))
    return np.array([e[0], e[1], wrap_angle(e[2])])


_XI_EDGES = [(np.array(v, dtype=float),) for v in (
    [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 1e-9], [0.0, 1.0, np.pi], [1.0, 0.0, 2 * np.pi],
    [0.3, -0.2, -1.5], [1.0, 0.0, 1e-5], [0.0, 0.0, 2.0])]
_xi_inputs = rng_inputs(14, 6, lambda rng: (rng.uniform(-3, 3, 3),), edges=_XI_EDGES)


def _exp_wrong_sign(xi: npt.ArrayLike) -> FloatArray:
    vx, vy, w = np.asarray(xi, dtype=float)
    return _exp_ref([vx, vy, w]) * np.array([1, 1, 1]) if w == 0 else _exp_ref(
        [vx, vy, -w]) * np.array([1, 1, -1])


_EXP_MISTAKES = [
    (lambda xi: np.array([xi[0], xi[1], wrap_angle(xi[2])]),
     "your function returns xi itself: that is the exponential of the additive group (R^2 x S^1, +), "
     "the straight-line 'hockey puck' path of Figure 1.19, not the SE(2) arc."),
    (_exp_wrong_sign, "the arc bends the wrong way: with a positive rotational velocity the path "
     "curves to the left of its initial direction."),
]


def exp_part(name: str, side: str) -> FunctionPart:
    """Part (a) or (b) of 1.4: the closed-form exp of the ``side`` ("left" or "right") field."""
    field = "left-invariant field X_L(g) = T_e L_g xi, (1.46)" if side == "left" else \
        "right-invariant field X_R(g) = T_e R_g xi, (1.47)"
    return FunctionPart(
        name, f"Closed-form {side} exponential exp(xi) as a function of xi = (vx, vy, w)",
        ref=_exp_ref, inputs=_xi_inputs, arg_names=("xi",), shape=(3,), postprocess=_se2_vec,
        rtol=1e-6, atol=1e-7, sympy_names=("vx", "vy", "w"), angles=(2,),
        sympy_args=lambda xi: (xi[0], xi[1], xi[2]), sympy_ok=lambda xi: abs(xi[2]) > 1e-3,
        mistakes=_EXP_MISTAKES,
        hints=[f"Write the flow of the {field} as three ODEs for x, y and theta, starting at e.",
               "theta(t) = w t comes first; the other two equations then have explicit right-hand "
               "sides (left field) or form a linear system x' = vx - w y, y' = vy + w x (right field).",
               "Integrate to t = 1. Your formula divides by w: treat w = 0 (a straight line) "
               "separately, or use sin(w)/w and (1 - cos w)/w written to avoid 0/0."],
        solution_text="exp(vx, vy, w) = ((vx sin w - vy (1 - cos w))/w, (vx (1 - cos w) + vy sin w)/w, "
                      "w), with the limit (vx, vy, 0) at w = 0. Both fields give the same point.",
        wrong=[lambda xi: np.asarray(xi)])


def helix_ref(xi: npt.ArrayLike) -> FloatArray:
    """(pitch, diameter, xy arclength) of the helix exp(t xi), t in [0, 1]: the reference of 1.4(c)."""
    vx, vy, w = np.asarray(xi, dtype=float)
    v = np.hypot(vx, vy)
    return np.array([2 * np.pi * np.sign(w), 2 * v / abs(w), v])


def helix_inputs() -> Iterator[tuple[FloatArray]]:
    """The arguments 1.4(c) is checked on: three edge cases, then five seeded random xi."""
    yield (np.array([1.0, 0.0, 1.0]),)
    yield (np.array([0.0, 0.0, 2.0]),)
    yield (np.array([1.0, 1.0, -0.5]),)
    rng = probe_rng(15)
    for _ in range(5):
        w = rng.choice([-1, 1]) * rng.uniform(0.2, 4)
        yield (np.array([rng.uniform(-2, 2), rng.uniform(-2, 2), w]),)


_D_KEYS = ("euler_left", "euler_right", "product", "taylor")
_D_NAMES = {"euler_left": "Euler on the left-invariant field", "euler_right": "Euler on the "
            "right-invariant field", "product": "the cumulative product (I + xi^/n)^n",
            "taylor": "the Taylor sum over k < n"}
_D_XIS = (np.array([1.0, 0.0, 0.5]), np.array([0.3, -0.7, 2.0]), np.array([1.0, 0.5, -4.0]))
_D_NS = {"euler_left": (1, 2, 7, 40), "euler_right": (1, 2, 7, 40), "product": (1, 2, 7, 40),
         "taylor": (1, 2, 5, 12, 30)}


def _d_calls() -> list[tuple[str, FloatArray, int]]:
    """The (route, xi, n) calls of 1.4(d): in the student's kernel always the three xis above; when
    grading, the first of them and two drawn from this run's salt (one turning each way)."""
    xis = _D_XIS
    if salted():
        rng = probe_rng(17)
        xis = (_D_XIS[0],) + tuple(np.array([*rng.uniform(-1.5, 1.5, 2), sign * rng.uniform(0.3, 4.0)])
                                   for sign in (1.0, -1.0))
    return [(k, xi, n) for k in _D_KEYS for xi in xis for n in _D_NS[k]]


def _d_structure(answer: Any) -> str:
    """Student side: which entries of the dict are given."""
    if is_starter(answer):
        raise Unattempted()
    if not isinstance(answer, dict) or not answer:
        raise Wrong("give a dict {'euler_left': f, 'euler_right': f, 'product': f, 'taylor': f} of "
                    "functions f(xi, n).")
    missing = [k for k in _D_KEYS if k not in answer]
    if missing:
        raise Wrong(f"your dict has no entry for {', '.join(repr(k) for k in missing)}.")
    if all(is_starter(answer[k]) for k in _D_KEYS):
        raise Unattempted()
    for k in _D_KEYS:
        if is_starter(answer[k]):
            raise Wrong(f"the entry {k!r} is still None.")
        if not callable(answer[k]):
            raise Wrong(f"answer[{k!r}] is not a function f(xi, n).")
    return "ok"


def _d_call(answer: Any, k: str, xi: npt.ArrayLike, n: int) -> FloatArray | None:
    out = answer[k](np.array(xi), int(n))
    if is_starter(out):
        return None
    return _se2_vec(out, None, nan_ok=True)


def routes_probes() -> list[Probe]:
    """The probes of 1.4(d): the dict's structure, then every (route, xi, n) call."""
    def call(c: tuple[str, FloatArray, int]) -> Probe:
        return lambda ans: _d_call(ans, *c)
    return [_d_structure, *(call(c) for c in _d_calls())]


def _d_close(got: npt.ArrayLike, want: npt.ArrayLike) -> bool:
    d = np.asarray(got, dtype=float) - np.asarray(want, dtype=float)
    if np.isfinite(d[2]):   # a NaN or infinite difference stays so, and fails
        d[2] = wrap_angle(d[2])
    return bool(np.all(np.abs(d) <= 1e-9 + 1e-7 * np.abs(want)))


def _d_vec(f: Route, xi: npt.ArrayLike, n: int) -> FloatArray:
    return _se2_vec(f(xi, n), None)


#: wrong routes a student may hand in for each key, with the message each deserves
def _d_mistakes(k: str) -> list[tuple[Route, str]]:
    out: list[tuple[Route, str]] = [
        (EXP_METHODS[o], f"answer[{k!r}] computes {_D_NAMES[o]}, not {_D_NAMES[k]}.") for o in _D_KEYS if o != k]
    out.append((lambda xi, n: SE2.exp(xi), f"answer[{k!r}] returns the exact exponential for every "
                "n; implement the n-step method itself so that its convergence can be seen."))
    if k == "taylor":
        out.append((lambda xi, n: _taylor(xi, n + 1), "answer['taylor'] sums n + 1 terms (k = 0 ... "
                    "n); the prompt asks for the terms k < n."))
    else:
        def more_steps(xi: npt.ArrayLike, n: int) -> npt.ArrayLike:
            return EXP_METHODS[k](xi, n + 1) if k == "product" else _euler(xi, n + 1, k.split("_")[1])
        out.append((more_steps, f"answer[{k!r}] takes n + 1 steps; take n steps of size 1/n."))
    return out


def routes_judge(outcomes: list[ProbeOutcome]) -> str:
    """The judge of 1.4(d): every route matches its reference step for step, or a message says
    which route is wrong and, for a known mistake, how."""
    first_value(outcomes, "your dict", "")
    calls = _d_calls()
    if len(outcomes) != len(calls) + 1:
        raise Wrong("the check could not evaluate every route.")
    results = dict(zip(range(len(calls)), outcomes[1:]))
    by_key: dict[str, list[tuple[FloatArray, int, FloatArray]]] = {k: [] for k in _D_KEYS}
    for i, (k, xi, n) in enumerate(calls):
        o = results[i]
        label = f"xi = {fmt_value(xi)}, n = {n}"
        if o["k"] != "ok":
            outcome_error(o, f"answer[{k!r}]", label)
        if o["v"] is None:
            raise Unattempted(f"answer[{k!r}] still returns None for {label}.") if all(
                results[j]["k"] == "ok" and results[j]["v"] is None
                for j, c in enumerate(calls) if c[0] == k) else Wrong(
                f"answer[{k!r}] returned None for {label} (a branch without return?).")
        got = np.asarray(o["v"], dtype=float)
        if got.shape != (3,) or not np.all(np.isfinite(got)):
            raise Wrong(f"answer[{k!r}] returned NaN or infinite entries for {label}.")
        by_key[k].append((xi, n, got))
    for k in _D_KEYS:
        bad = [(xi, n) for xi, n, got in by_key[k] if not _d_close(got, _d_vec(EXP_METHODS[k], xi, n))]
        if not bad:
            continue
        for f, msg in _d_mistakes(k):
            if all(_d_close(got, _d_vec(f, xi, n)) for xi, n, got in by_key[k]):
                raise Wrong(msg)
        xi, n = bad[0]
        raise Wrong(f"answer[{k!r}] gives a different value for xi = {fmt_value(xi)}, n = {n}: it "
                    f"should be {_D_NAMES[k]} with n steps (or terms), starting at e. Try n = 1 by hand.")
    return ("Correct: all four routes match, step for step. Both Euler flows and the cumulative "
            "product converge at first order (error ~ 1/n), the Taylor sum factorially fast.")


def _euler(xi: npt.ArrayLike, n: int, side: str) -> FloatArray:
    xi = np.asarray(xi, dtype=float)
    g = np.zeros(3)
    for _ in range(int(n)):
        if side == "left":
            g = g + SE2.body_to_world(g, xi) / n
        else:
            g = g + SE2.spatial_to_world(g, xi) / n
    return g


def _product(xi: npt.ArrayLike, n: int) -> FloatArray:
    return np.linalg.matrix_power(np.eye(3) + SE2.hat(np.asarray(xi, dtype=float)) / n, int(n))


def _taylor(xi: npt.ArrayLike, n: int) -> FloatArray:
    X = SE2.hat(np.asarray(xi, dtype=float))
    total, term = np.zeros((3, 3)), np.eye(3)
    for k in range(int(n)):
        total = total + term
        term = term @ X / (k + 1)
    return total


#: Reference implementations of the four routes of exercise 1.4d (also used by the tests).
EXP_METHODS: dict[str, Route] = {"euler_left": lambda xi, n: _euler(xi, n, "left"),
               "euler_right": lambda xi, n: _euler(xi, n, "right"),
               "product": _product, "taylor": _taylor}



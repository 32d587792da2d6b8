"""Exercise 1.4's student side: the closed-form exp parts (a, b), the helix's inputs (c) and the
probes of the four numerical routes (d). Used by ex1.py (split off to keep each file readable in
one sitting). Their answer keys (the SE(2) exp and helix references, the routes' reference
implementations, the mistakes and the routes' judge) are in :mod:`gm_core.checks.keys.ex1`."""
from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from gm_core.checks.answers import is_starter, match_shape, to_numbers
from gm_core.checks.parts import FunctionPart, probe_rng, rng_inputs, salted
from gm_core.checks.sandbox import Probe, Unattempted, Wrong
from gm_core.groups import wrap_angle

if TYPE_CHECKING:
    from gm_core.validation import FloatArray

__all__ = ["Route", "se2_vec", "exp_part", "helix_inputs", "ROUTES", "route_calls", "routes_probes"]

#: A route of 1.4(d): ``f(xi, n)``, exp(xi) after n steps, as (x, y, theta) or a 3 x 3 matrix.
Route = Callable[[npt.ArrayLike, int], npt.ArrayLike]


def se2_vec(out: Any, args: object, nan_ok: bool = True) -> FloatArray:
    """Accept (x, y, theta) or a 3x3 homogeneous matrix; wrap the angle to (-pi, pi]."""
    arr = to_numbers(out, "the value your function returned")
    if arr.shape == (3, 3):
        arr = np.array([arr[0, 2], arr[1, 2], np.arctan2(arr[1, 0], arr[0, 0])])
    arr = match_shape(arr, (3,), "the value your function returned")
    return np.array([arr[0], arr[1], wrap_angle(arr[2])])


_XI_EDGES = [(np.array(v, dtype=float),) for v in (
    [1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 1e-9], [0.0, 1.0, np.pi], [1.0, 0.0, 2 * np.pi],
    [0.3, -0.2, -1.5], [1.0, 0.0, 1e-5], [0.0, 0.0, 2.0])]
_xi_inputs = rng_inputs(14, 6, lambda rng: (rng.uniform(-3, 3, 3),), edges=_XI_EDGES)


def exp_part(name: str, side: str) -> FunctionPart:
    """Part (a) or (b) of 1.4: the closed-form exp of the ``side`` ("left" or "right") field."""
    field = "left-invariant field X_L(g) = T_e L_g xi, (1.46)" if side == "left" else \
        "right-invariant field X_R(g) = T_e R_g xi, (1.47)"
    return FunctionPart(
        name, f"Closed-form {side} exponential exp(xi) as a function of xi = (vx, vy, w)",
        inputs=_xi_inputs, arg_names=("xi",), shape=(3,), postprocess=se2_vec,
        rtol=1e-6, atol=1e-7, sympy_names=("vx", "vy", "w"), angles=(2,),
        sympy_args=lambda xi: (xi[0], xi[1], xi[2]), sympy_ok=lambda xi: abs(xi[2]) > 1e-3,
        hints=[f"Write the flow of the {field} as three ODEs for x, y and theta, starting at e.",
               "theta(t) = w t comes first; the other two equations then have explicit right-hand "
               "sides (left field) or form a linear system x' = vx - w y, y' = vy + w x (right field).",
               "Integrate to t = 1. Your formula divides by w: treat w = 0 (a straight line) "
               "separately, or use sin(w)/w and (1 - cos w)/w written to avoid 0/0."])


def helix_inputs() -> Iterator[tuple[FloatArray]]:
    """The arguments 1.4(c) is checked on: three edge cases, then five seeded random xi."""
    yield (np.array([1.0, 0.0, 1.0]),)
    yield (np.array([0.0, 0.0, 2.0]),)
    yield (np.array([1.0, 1.0, -0.5]),)
    rng = probe_rng(15)
    for _ in range(5):
        w = rng.choice([-1, 1]) * rng.uniform(0.2, 4)
        yield (np.array([rng.uniform(-2, 2), rng.uniform(-2, 2), w]),)


#: The entries of 1.4(d)'s dict, one route each.
ROUTES = ("euler_left", "euler_right", "product", "taylor")
_D_XIS = (np.array([1.0, 0.0, 0.5]), np.array([0.3, -0.7, 2.0]), np.array([1.0, 0.5, -4.0]))
_D_NS = {"euler_left": (1, 2, 7, 40), "euler_right": (1, 2, 7, 40), "product": (1, 2, 7, 40),
         "taylor": (1, 2, 5, 12, 30)}


def route_calls() -> list[tuple[str, FloatArray, int]]:
    """The (route, xi, n) calls of 1.4(d): in the student's kernel always the three xis above; when
    grading, the first of them and two drawn from this run's salt (one turning each way)."""
    xis = _D_XIS
    if salted():
        rng = probe_rng(17)
        xis = (_D_XIS[0],) + tuple(np.array([*rng.uniform(-1.5, 1.5, 2), sign * rng.uniform(0.3, 4.0)])
                                   for sign in (1.0, -1.0))
    return [(k, xi, n) for k in ROUTES for xi in xis for n in _D_NS[k]]


def _d_structure(answer: Any) -> str:
    """Student side: which entries of the dict are given."""
    if is_starter(answer):
        raise Unattempted()
    if not isinstance(answer, dict) or not answer:
        raise Wrong("give a dict {'euler_left': f, 'euler_right': f, 'product': f, 'taylor': f} of "
                    "functions f(xi, n).")
    missing = [k for k in ROUTES if k not in answer]
    if missing:
        raise Wrong(f"your dict has no entry for {', '.join(repr(k) for k in missing)}.")
    if all(is_starter(answer[k]) for k in ROUTES):
        raise Unattempted()
    for k in ROUTES:
        if is_starter(answer[k]):
            raise Wrong(f"the entry {k!r} is still None.")
        if not callable(answer[k]):
            raise Wrong(f"answer[{k!r}] is not a function f(xi, n).")
    return "ok"


def _d_call(answer: Any, k: str, xi: npt.ArrayLike, n: int) -> FloatArray | None:
    out = answer[k](np.array(xi), int(n))
    if is_starter(out):
        return None
    return se2_vec(out, None, nan_ok=True)


def routes_probes() -> list[Probe]:
    """The probes of 1.4(d): the dict's structure, then every (route, xi, n) call."""
    def call(c: tuple[str, FloatArray, int]) -> Probe:
        return lambda ans: _d_call(ans, *c)
    return [_d_structure, *(call(c) for c in route_calls())]

"""The exponential map computed four ways, section 1.6.4 and exercise 1.4d (numpy only).

Closed form, Taylor partial sums (1.51), cumulative products (I + A/n)^n (1.49) and Euler steps
along the invariant field (1.46)-(1.47); re-exported by :mod:`gm_core.calculus`, whose docstring
explains ``side``.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from gm_core.calculus.arguments import (
    SIDES,
    check_n_list,
    check_scalar,
    check_side,
    check_steps,
    check_xi,
)
from gm_core.calculus.products import element_from_matrix
from gm_core.groups import SE2, LieGroup, check_group
from gm_core.validation import FloatArray, as_array, check_option

__all__ = ["ExpHistory", "ExpPath", "exp_closed_form", "exp_taylor", "exp_product", "exp_euler",
           "exp_four_ways", "exp_history", "convergence_order", "se2_exp_study", "EXP_METHODS",
           "DEFAULT_N"]

EXP_METHODS = ("closed", "taylor", "product", "euler")
DEFAULT_N = tuple(2 ** k for k in range(11))


# ---------------------------------------------------------------------------------- exp four ways
@dataclass(frozen=True)
class ExpPath:
    """Intermediate values of one evaluation of exp(xi) with ``n`` steps (or terms).

    ``s[j]`` is the parameter of the j-th value: the time j/n along the flow for ``"euler"``,
    ``"product"`` and ``"closed"`` (so the values approximate points exp(s xi) of the geodesic),
    and the number of Taylor terms j for ``"taylor"`` (partial sums, which are *not* points of the
    geodesic). ``matrices`` has shape (n+1, k, k), ``elements`` (n+1, dim) (via
    :func:`element_from_matrix` for values that are not exact group matrices), ``reference`` is
    the closed form at the same parameters (exp(s xi); for Taylor the final exp(xi) repeated).
    """

    method: str
    side: str
    n: int
    s: np.ndarray
    matrices: np.ndarray
    elements: np.ndarray
    reference: np.ndarray

    @property
    def error(self) -> FloatArray:
        """Frobenius distance of each intermediate matrix from the closed-form matrix at s."""
        return np.linalg.norm(self.matrices - self.reference, axis=(-2, -1))


@dataclass(frozen=True)
class ExpHistory:
    """Convergence history of one way of computing exp(xi) on ``group``.

    ``n`` (m,) are the numbers of steps (Euler, product) or of series terms (Taylor);
    ``matrices`` (m, k, k) the estimate of the matrix exp(xi^) for each n; ``elements`` (m, dim)
    their group coordinates; ``exact`` / ``exact_matrix`` the closed form (``group.exp``);
    ``error`` (m,) the Frobenius norm of ``matrices - exact_matrix``. ``path(n)`` returns the
    intermediate values of a single evaluation, for plotting.
    """

    method: str
    side: str
    group: LieGroup
    xi: np.ndarray
    n: np.ndarray
    matrices: np.ndarray
    exact: np.ndarray
    exact_matrix: np.ndarray
    error: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "error", _frobenius(self.matrices - self.exact_matrix))

    @property
    def elements(self) -> FloatArray:
        return element_from_matrix(self.group, self.matrices)

    @property
    def element_error(self) -> FloatArray:
        """Coordinate error (angles wrapped), shape (m, dim)."""
        return self.group.difference(self.elements, self.exact)

    def order(self, floor: float = 1e-13) -> float:
        """Fitted algebraic convergence order p in error ~ C n^-p (see :func:`convergence_order`)."""
        return convergence_order(self.n, self.error, floor=floor)

    def path(self, n: int | None = None) -> ExpPath:
        """Intermediate values of the evaluation with ``n`` steps/terms (default: the largest n)."""
        n = int(self.n[-1]) if n is None else check_steps(n, "n")
        return _PATHS[self.method](self.group, self.xi, n, self.side)


def _frobenius(D):
    """Frobenius norms over the last two axes, scaled so that entries near 1e300 do not overflow."""
    big = np.max(np.abs(D), axis=(-2, -1), keepdims=True)
    safe = np.where(big > 0, big, 1.0)
    return np.linalg.norm(D / safe, axis=(-2, -1)) * big[..., 0, 0]


def convergence_order(n: ArrayLike, error: ArrayLike, floor: float = 1e-13) -> float:
    """Least-squares slope p of log(error) = c - p log(n), ignoring errors below ``floor``.

    Euler and (I + A/n)^n give p close to 1; a Taylor series converges faster than any power, so
    its fitted p keeps growing with the range of n used.
    """
    n = as_array(n, "n")
    error = as_array(error, "error")
    if n.shape != error.shape or n.ndim != 1:
        raise ValueError(f"n and error must be 1-D arrays of one length; got {n.shape} and {error.shape}")
    floor = check_scalar(floor, "floor")
    if floor < 0:
        raise ValueError(f"floor must be a non-negative error level; got {floor!r}")
    if np.any(error < 0) or np.any(n <= 0):
        raise ValueError("n must be positive and error non-negative (errors are norms)")
    keep = error > floor
    if len(np.unique(n[keep])) < 2:
        raise ValueError("n and error must hold at least two different n with errors above floor "
                         "to fit a convergence order")
    slope = np.polyfit(np.log(n[keep]), np.log(error[keep]), 1)[0]
    return float(-slope)


def _euler_states(group, xi, n, side):
    """States g_0 = e, g_{j+1} = g_j + (1/n) T_e{L,R}_{g_j} xi, j < n; shape (n+1, dim).

    Each step is the group's :meth:`~gm_core.groups.LieGroup.euler_step`. On (R+, x) the lifted
    actions are multiplication by g, (1.24)-(1.25), so the steps are g_{j+1} = g_j (1 + xi/n):
    exactly the cumulative product (1.49). With n <= -xi a step overshoots to g <= 0, outside the
    group; those values are returned as they are (they show the failure of too few steps).
    """
    dt = 1.0 / n
    g = group.identity()
    out = np.empty((n + 1, group.param_dim))
    out[0] = g
    for j in range(n):
        g = group.euler_step(g, xi, dt, side)
        out[j + 1] = g
    return out


def _euler_finals(group, xi, ns, side):
    """The last Euler state g_n of :func:`_euler_states` for every n in ``ns`` (ascending), shape
    (len(ns), dim): all of them stepped together, max(ns) batched steps. A step of time 1/n along
    xi is a step of time 1 along xi/n (the step is linear in dt xi); a state whose n steps are
    done stays as it is."""
    steps = xi[None, :] / ns[:, None]
    g = np.repeat(group.identity()[None, :], len(ns), axis=0)
    for j in range(int(ns[-1])):
        live = j < ns
        g[live] = group.euler_step(g[live], steps[live], 1.0, side)
    return g


def _state_matrices(group, G):
    """Matrices of Euler states, which may lie outside the group (see :func:`_euler_states`)."""
    return group.coordinate_matrix(G)


def _taylor_sums(A, n):
    """Partial sums S_0 = 0, S_j = sum_{k<j} A^k/k! for j = 1..n; shape (n+1, k, k)."""
    size = A.shape[-1]
    out = np.empty((n + 1, size, size))
    out[0] = 0.0
    term = np.eye(size)
    total = np.zeros((size, size))
    for j in range(1, n + 1):
        total = total + term
        out[j] = total
        term = term @ A / j
    return out


def _running_products(A, n, side):
    step = np.eye(A.shape[-1]) + A / n
    out = np.empty((n + 1,) + A.shape)
    P = np.eye(A.shape[-1])
    out[0] = P
    for j in range(n):
        P = P @ step if side == "left" else step @ P
        out[j + 1] = P
    return out


def _geodesic_matrices(group, xi, s):
    return group.matrix(group.exp(s[:, None] * xi))


def _path_closed(group, xi, n, side):
    s = np.arange(n + 1) / n
    M = _geodesic_matrices(group, xi, s)
    return ExpPath("closed", side, n, s, M, element_from_matrix(group, M), M)


def _path_euler(group, xi, n, side):
    s = np.arange(n + 1) / n
    G = _euler_states(group, xi, n, side)
    return ExpPath("euler", side, n, s, _state_matrices(group, G), G, _geodesic_matrices(group, xi, s))


def _path_product(group, xi, n, side):
    s = np.arange(n + 1) / n
    M = _running_products(group.hat(xi), n, side)
    return ExpPath("product", side, n, s, M, element_from_matrix(group, M),
                   _geodesic_matrices(group, xi, s))


def _path_taylor(group, xi, n, side):
    S = _taylor_sums(group.hat(xi), n)
    ref = np.broadcast_to(group.matrix(group.exp(xi)), S.shape).copy()
    return ExpPath("taylor", side, n, np.arange(n + 1, dtype=float), S,
                   element_from_matrix(group, S), ref)


_PATHS = {"closed": _path_closed, "euler": _path_euler, "product": _path_product,
          "taylor": _path_taylor}


def exp_history(group: LieGroup, xi: ArrayLike, n: ArrayLike = DEFAULT_N, method: str = "product",
                side: str = "left") -> ExpHistory:
    """Estimates of exp(xi) on ``group`` for each n in ``n`` by one of :data:`EXP_METHODS`.

    ``method``: ``"closed"`` (``group.exp``, error 0), ``"taylor"`` (first n terms of (1.51)),
    ``"product"`` ((I + xi^/n)^n, (1.49)), ``"euler"`` (n forward-Euler steps of unit total time
    along the ``side``-invariant field, (1.46) or (1.47), in the group's own coordinates).
    ``xi`` is a single Lie-algebra vector (a body velocity for ``side="left"``, a spatial velocity
    for ``side="right"``). Returns an :class:`ExpHistory`.
    """
    group = check_group(group)
    xi = check_xi(group, xi)
    ns = check_n_list(n)
    side = check_side(side)
    method = check_option(method, "method", EXP_METHODS)
    exact = group.exp(xi)
    exact_matrix = group.matrix(exact)
    A = group.hat(xi)
    with np.errstate(over="ignore", invalid="ignore"):
        if method == "closed":
            mats = np.broadcast_to(exact_matrix, (len(ns),) + exact_matrix.shape).copy()
        elif method == "taylor":
            mats = _taylor_sums(A, int(ns[-1]))[ns]
        elif method == "product":
            eye = np.eye(A.shape[-1])
            mats = np.stack([np.linalg.matrix_power(eye + A / m, int(m)) for m in ns])
        else:
            mats = _state_matrices(group, _euler_finals(group, xi, ns, side))
        error = _frobenius(mats - exact_matrix)
    if not (np.all(np.isfinite(mats)) and np.all(np.isfinite(error))):
        raise ValueError(f"xi is too large for method {method!r} with n up to {int(ns[-1])}: the "
                         f"estimates of exp(xi) overflow a float")
    return ExpHistory(method=method, side=side, group=group, xi=xi, n=ns, matrices=mats,
                      exact=exact, exact_matrix=exact_matrix)


def exp_closed_form(group: LieGroup, xi: ArrayLike, n: ArrayLike = DEFAULT_N, side: str = "left") -> ExpHistory:
    """The closed-form reference ``group.exp(xi)`` as an :class:`ExpHistory` (error 0); ex. 1.4a/b."""
    return exp_history(group, xi, n, "closed", side)


def exp_taylor(group: LieGroup, xi: ArrayLike, n: ArrayLike = DEFAULT_N, side: str = "left") -> ExpHistory:
    """Partial sums sum_{k<n} xi^^k / k! of the matrix series (1.51); error falls like |xi|^n / n!."""
    return exp_history(group, xi, n, "taylor", side)


def exp_product(group: LieGroup, xi: ArrayLike, n: ArrayLike = DEFAULT_N, side: str = "left") -> ExpHistory:
    """Cumulative products (I + xi^/n)^n of (1.49); error ~ 1/n. ``side`` orders the path factors."""
    return exp_history(group, xi, n, "product", side)


def exp_euler(group: LieGroup, xi: ArrayLike, n: ArrayLike = DEFAULT_N, side: str = "left") -> ExpHistory:
    """n forward-Euler steps of g_dot = T_e L_g xi (``"left"``, (1.46)) or T_e R_g xi (``"right"``,
    (1.47)) from the identity over unit time; error ~ 1/n."""
    return exp_history(group, xi, n, "euler", side)


def exp_four_ways(group: LieGroup, xi: ArrayLike, n: ArrayLike = DEFAULT_N,
                  side: str = "left") -> dict[str, ExpHistory]:
    """``{"closed", "taylor", "product", "euler"} -> ExpHistory`` for one xi: exercise 1.4d."""
    return {m: exp_history(group, xi, n, m, side) for m in EXP_METHODS}



def se2_exp_study(thetadots: ArrayLike = (0.5, 1.0, 2.0, 4.0), n: ArrayLike = DEFAULT_N, speed: float = 1.0
                  ) -> dict[str, dict[str, list[ExpHistory]]]:
    """Exercise 1.4d in one call: every method and side for xi = (speed, 0, thetadot).

    Returns ``{side: {method: [ExpHistory for each thetadot]}}`` with sides ``"left"`` and
    ``"right"`` and methods :data:`EXP_METHODS`, all on SE(2) with the same ``n``. The fitted
    orders (``h.order()``) are about 1 for Euler and cumulative products; Taylor errors fall faster
    than any power of n, and more slowly (in n) the larger |thetadot| is.
    """
    td = as_array(thetadots, "thetadots", what=" (rotation rates)")
    if td.ndim > 1:
        raise ValueError(f"thetadots must be a number or a 1-D array; got shape {td.shape}")
    speed = check_scalar(speed, "speed")
    check_n_list(n)
    xis = [np.array([speed, 0.0, w]) for w in np.atleast_1d(td)]
    try:
        return {side: {m: [exp_history(SE2, xi, n, m, side) for xi in xis] for m in EXP_METHODS}
                for side in SIDES}
    except ValueError as exc:
        raise ValueError(f"thetadots and speed are too large: {exc}") from None

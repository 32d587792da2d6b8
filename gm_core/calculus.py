"""Multiplicative calculus and the exponential map computed four ways (numpy + scipy only).

This module is the numeric side of the book's *Multiplicative Calculus* box ((1.xx)-(1.xxxii)) and
of section 1.6.4 / exercise 1.4d:

==========================  ==========================================================  =============
function                    what it computes                                            book
==========================  ==========================================================  =============
product_integral            prod (I + v(x_k) dx), left or right ordering, with history  (1.xxi), (1.xxiv), (1.xxvi)-(1.xxvii)
quotient_derivative         v_L = F' F^-1 or v_R = F^-1 F', by central differences      (1.xxv), (1.xxviii)-(1.xxx)
exp_closed_form             the group's closed-form exp (reference)                    section 1.6.4, ex. 1.4a/b
exp_taylor                  partial sums  sum_{k<n} A^k / k!                            (1.51)
exp_product                 cumulative product (I + A/n)^n                              (1.49)
exp_euler                   n Euler steps along the invariant field of xi               (1.46), (1.47)
exp_four_ways               all four at once, as a dict                                 ex. 1.4d
se2_exp_study               every method and side for xi = (1, 0, thetadot), several rates  ex. 1.4d
==========================  ==========================================================  =============

Left and right
--------------
``side`` in the exponential functions names the *invariant vector field* being followed, as in
``gm_core.fields``: ``"left"`` is the left-invariant field g_dot = T_e L_g xi of a body velocity xi,
(1.46); ``"right"`` is the right-invariant field g_dot = T_e R_g xi_s of a spatial velocity xi_s,
(1.47). In matrix form the left-invariant flow is g_dot = g xi^, so its Euler / cumulative-product
steps append new factors on the right: that is the *right* product integral (1.xxvi)-(1.xxvii).
Conversely the right-invariant flow g_dot = xi_s^ g is the *left* product integral (1.xxiv). The
function :func:`product_integral` uses the product-integral names (its ``side`` says where new
factors go). From the identity both exponential flows reach the same element exp(xi); the
intermediate values of the Euler integration differ (see :meth:`ExpHistory.path`), while the
cumulative products of a constant matrix coincide (powers of one matrix commute). (Exercise 1.4a/b
as drafted pair the body velocity xi with the right-invariant field and xi_s with the left one,
the reverse of (1.46)-(1.47); this module follows (1.46)-(1.47).)

The binomial step between (1.50) and (1.51) needs the coefficient C(n, k) = n! / (k! (n - k)!);
the draft prints n^k / k!, which is only its large-n limit (see :func:`binomial_terms`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._validate import SingularShapeError, as_array, check_int, check_option
from .groups import SE2, LieGroup, check_group

__all__ = [
    "product_integral", "RunningProduct", "quotient_derivative",
    "ExpHistory", "ExpPath", "exp_closed_form", "exp_taylor", "exp_product", "exp_euler",
    "exp_four_ways", "exp_history", "convergence_order", "binomial_terms", "element_from_matrix",
    "se2_exp_study", "EXP_METHODS",
]

EXP_METHODS = ("closed", "taylor", "product", "euler")
_SIDES = ("left", "right")
DEFAULT_N = tuple(2 ** k for k in range(11))


# ---------------------------------------------------------------------------------- checking
def _check_side(side, name="side"):
    return check_option(side, name, _SIDES)


#: Largest number of steps, factors or series terms accepted (a Python loop runs over them).
MAX_STEPS = 10**5


def _check_int(n, name, minimum=1, maximum=MAX_STEPS):
    return check_int(n, name, minimum=minimum, maximum=maximum)


def _check_n_list(n, name="n"):
    """An int or a sequence of ints >= 1, returned as a sorted 1-D int array without repeats."""
    if isinstance(n, (str, bytes)) or n is None:
        raise TypeError(f"{name} must be a positive integer or a sequence of them; got {n!r}")
    if np.ndim(n) == 0:
        return np.array([_check_int(n, name)], dtype=int)
    vals = [_check_int(v, name) for v in np.asarray(n, dtype=object).ravel()]
    if not vals:
        raise ValueError(f"{name} must contain at least one positive integer; got an empty sequence")
    return np.unique(np.array(vals, dtype=int))


def _check_scalar(x, name):
    arr = as_array(x, name, what=" (a single real number)")
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a single real number; got shape {arr.shape}")
    return float(arr)


def _check_xi(group, xi, name="xi"):
    xi = as_array(xi, name, (group.dim,), what=f", a Lie-algebra vector of {group.name}")
    if xi.ndim != 1:
        raise ValueError(f"{name} must be a single vector of shape ({group.dim},); got shape {xi.shape}")
    return xi


def _matrix_value(value, name):
    """``value`` as a float array of shape (..., k, k), plus a flag saying it was a scalar."""
    arr = as_array(value, name, what=" (a number or a square matrix)")
    if arr.ndim == 0:
        return arr.reshape(1, 1), True
    if arr.ndim < 2 or arr.shape[-1] != arr.shape[-2]:
        raise ValueError(f"{name} must be a number or a square matrix (..., k, k); got shape {arr.shape}")
    return arr, False


# ---------------------------------------------------------------------------------- product integral
@dataclass(frozen=True)
class RunningProduct:
    """Running products of a product integral.

    ``x[j]`` (j = 0..n) is the end of the j-th subinterval, ``products[j]`` the product of the
    first j factors (``products[0]`` is I), so ``products[j]`` approximates F(x_j)/F(a) in the
    sense of (1.xxi); ``final`` is ``products[-1]``. Scalars come back as arrays of shape (n+1,).
    """

    x: np.ndarray
    products: np.ndarray
    side: str

    @property
    def final(self):
        return self.products[-1]

    def __iter__(self):
        yield self.x
        yield self.products


def product_integral(v, a, b, n, side="right", *, point="end", history=False):
    """Product integral of ``v`` from ``a`` to ``b`` with ``n`` factors (I + v(x_k) dx).

    Parameters
    ----------
    v : callable or array
        The quotient derivative: a function ``x -> (k, k) matrix`` (or ``x -> number``), or a
        constant matrix / number. Batched matrices ``(..., k, k)`` are multiplied batch-wise.
    a, b : float
        Interval ends; dx = (b - a) / n (b < a is allowed and gives dx < 0).
    n : int
        Number of factors (subintervals), >= 1.
    side : {"right", "left"}
        ``"right"``: new factors are appended on the right, (I + v(x_1) dx)(I + v(x_2) dx)...,
        the right product integral (1.xxvi)-(1.xxvii). ``"left"``: each new factor multiplies
        the running total from the left, ...(I + v(x_2) dx)(I + v(x_1) dx), the left product
        integral (1.xxiv).
    point : {"end", "start", "mid"}
        Where v is sampled in each subinterval: x_k = a + k dx for k = 1..n as in (1.xx)-(1.xxi)
        (``"end"``, default), a + (k - 1) dx (``"start"``), or the midpoint.
    history : bool
        If true return a :class:`RunningProduct` with every running product; otherwise the final
        product only (a ``(k, k)`` array, or a float for scalar ``v``).

    For a constant matrix A on [0, 1] this is (I + A/n)^n, which tends to expm(A), (1.49).
    """
    a = _check_scalar(a, "a")
    b = _check_scalar(b, "b")
    n = _check_int(n, "n")
    side = _check_side(side)
    point = check_option(point, "point", ("end", "start", "mid"))
    if not isinstance(history, (bool, np.bool_)):
        raise TypeError(f"history must be True or False; got {history!r:.40}")
    with np.errstate(over="ignore"):
        dx = (b - a) / n
    if not np.isfinite(dx):
        raise ValueError(f"a and b are too far apart: b - a overflows a float (a={a:g}, b={b:g})")
    offset = {"end": 1.0, "start": 0.0, "mid": 0.5}[point]
    nodes = a + (np.arange(n) + offset) * dx
    ends = a + np.arange(n + 1) * dx

    if callable(v):
        def factor_value(k):
            return _matrix_value(v(float(nodes[k])), "v(x)")
        V0, scalar = factor_value(0)
        constant = None
    else:
        V0, scalar = _matrix_value(v, "v")
        constant = V0
    size = V0.shape[-1]
    eye = np.eye(size)

    def compute():
        if constant is not None and not history:
            out = np.linalg.matrix_power(eye + constant * dx, n)
            return float(out[0, 0]) if scalar else out

        P = np.broadcast_to(eye, V0.shape).copy()
        running = [P] if history else None
        for k in range(n):
            if constant is not None:
                Vk = constant
            elif k == 0:
                Vk = V0
            else:
                Vk, _ = factor_value(k)
                if Vk.shape[-1] != size:
                    raise ValueError(
                        f"v(x) must keep one matrix size; got {size}x{size} at x={nodes[0]:g} and "
                        f"shape {Vk.shape} at x={nodes[k]:g}"
                    )
            step = eye + Vk * dx
            P = P @ step if side == "right" else step @ P
            if history:
                running.append(P)
        if history:
            prods = np.stack(running)
            if scalar:
                prods = prods[..., 0, 0]
            return RunningProduct(x=ends, products=prods, side=side)
        if scalar:
            return float(P[0, 0])
        return P

    with np.errstate(over="ignore", invalid="ignore"):
        result = compute()
    values = result.products if history else result
    if not np.all(np.isfinite(values)):
        raise ValueError(f"the product overflowed: the factors (I + v dx) with v and dx = (b - a)/n = "
                         f"{dx:g} are too large; shrink v or the interval [a, b], or raise n")
    return result


# ---------------------------------------------------------------------------------- quotient derivative
def _default_step(x, method):
    scale = max(1.0, abs(x))
    eps = np.finfo(float).eps
    return (eps ** (1 / 3) if method == "central" else eps ** 0.5) * scale


def quotient_derivative(F, x, side="right", h=None, *, method="central"):
    """Numerical quotient derivative of a matrix-valued (or positive scalar) function F at x.

    ``side="right"``: v_R(x) = F(x)^-1 F'(x), the right quotient derivative (1.xxviii), (1.xxx);
    for a group trajectory F(t) = matrix(g(t)) this is the body velocity in matrix form (1.52).
    ``side="left"``: v_L(x) = F'(x) F(x)^-1, the left quotient derivative (1.xxv), (1.xxix); for a
    group trajectory it is the spatial velocity in matrix form.

    ``method="central"`` (default) differentiates F by central differences, O(h^2), and multiplies
    by F(x)^-1 as in (1.xxix)-(1.xxx). ``method="quotient"`` uses the one-sided quotients of
    (1.xxv)/(1.xxviii) literally, (F(x)^-1 F(x + h) - I)/h, which is O(h). ``h`` defaults to
    eps^(1/3) max(1, |x|) (central) or eps^(1/2) max(1, |x|) (quotient).

    ``x`` may be a number (returns ``(k, k)``, or a float for scalar F) or a 1-D array (returns a
    stack). Raises :class:`gm_core.SingularShapeError` if F(x) is not invertible.
    """
    if not callable(F):
        raise TypeError(f"F must be a callable x -> matrix; got {type(F).__name__}")
    side = _check_side(side)
    method = check_option(method, "method", ("central", "quotient"))
    xs = as_array(x, "x", what=" (a number or a 1-D array of numbers)")
    if xs.ndim > 1 or xs.size == 0:
        raise ValueError(f"x must be a number or a non-empty 1-D array; got shape {xs.shape}")
    if h is not None:
        h_val = _check_scalar(h, "h")
        if h_val <= 0:
            raise ValueError(f"h must be a positive step size; got {h!r}")

    def one(x0):
        step = h_val if h is not None else _default_step(x0, method)
        Fx, scalar = _matrix_value(F(x0), "F(x)")
        try:
            Finv = np.linalg.inv(Fx)
        except np.linalg.LinAlgError:
            raise SingularShapeError(
                f"F(x) is singular at x={x0:g}: the quotient derivative needs an invertible value"
            ) from None
        if not np.all(np.isfinite(Finv)):
            raise SingularShapeError(f"F(x) is singular at x={x0:g}: its inverse is not finite")
        Fp, _ = _matrix_value(F(x0 + step), "F(x)")
        if method == "central":
            Fm, _ = _matrix_value(F(x0 - step), "F(x)")
            dF = (Fp - Fm) / (2.0 * step)
            out = Finv @ dF if side == "right" else dF @ Finv
        else:
            eye = np.eye(Fx.shape[-1])
            out = ((Finv @ Fp) if side == "right" else (Fp @ Finv)) - eye
            out = out / step
        return (out[..., 0, 0] if out.ndim > 2 else float(out[0, 0])) if scalar else out

    if xs.ndim == 0:
        return one(float(xs))
    return np.stack([np.asarray(one(float(x0))) for x0 in xs])


# ---------------------------------------------------------------------------------- matrices <-> elements
def element_from_matrix(group, M):
    """Coordinates of the group element nearest a (possibly non-group) matrix ``M``.

    Truncated Taylor sums and the products (I + A/n)^k are not exactly group matrices (their
    rotation blocks are scaled). This reads the translation columns as they are and the angle of
    a 2x2 block [[a, -b], [b, a]] + (anything symmetric) as atan2 of its rotational part, which is
    the angle of the nearest rotation (polar decomposition). Exact group matrices round-trip.
    For (R+, x) the single entry is returned unchecked (a partial sum can be negative). The
    reading is the group's own :meth:`~gm_core.groups.LieGroup.nearest_element`.
    """
    return check_group(group).nearest_element(M)


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
    def error(self):
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

    def __post_init__(self):
        object.__setattr__(self, "error", _frobenius(self.matrices - self.exact_matrix))

    @property
    def elements(self):
        return element_from_matrix(self.group, self.matrices)

    @property
    def element_error(self):
        """Coordinate error (angles wrapped), shape (m, dim)."""
        return self.group.difference(self.elements, self.exact)

    def order(self, floor=1e-13):
        """Fitted algebraic convergence order p in error ~ C n^-p (see :func:`convergence_order`)."""
        return convergence_order(self.n, self.error, floor=floor)

    def path(self, n=None):
        """Intermediate values of the evaluation with ``n`` steps/terms (default: the largest n)."""
        n = int(self.n[-1]) if n is None else _check_int(n, "n")
        return _PATHS[self.method](self.group, self.xi, n, self.side)


def _frobenius(D):
    """Frobenius norms over the last two axes, scaled so that entries near 1e300 do not overflow."""
    big = np.max(np.abs(D), axis=(-2, -1), keepdims=True)
    safe = np.where(big > 0, big, 1.0)
    return np.linalg.norm(D / safe, axis=(-2, -1)) * big[..., 0, 0]


def convergence_order(n, error, floor=1e-13):
    """Least-squares slope p of log(error) = c - p log(n), ignoring errors below ``floor``.

    Euler and (I + A/n)^n give p close to 1; a Taylor series converges faster than any power, so
    its fitted p keeps growing with the range of n used.
    """
    n = as_array(n, "n")
    error = as_array(error, "error")
    if n.shape != error.shape or n.ndim != 1:
        raise ValueError(f"n and error must be 1-D arrays of one length; got {n.shape} and {error.shape}")
    floor = _check_scalar(floor, "floor")
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


def binomial_terms(n, k):
    """The binomial coefficient C(n, k) = n!/(k!(n-k)!) used between (1.50) and (1.51).

    Returns ``(C(n, k), C(n, k) / n^k)``: the second tends to 1/k! as n -> infinity, which is why
    each term of the binomial expansion of (I + A/n)^n tends to A^k/k!. (The draft's
    coefficient n^k / k! is the large-n approximation of C(n, k), not equal to it.)
    """
    n = _check_int(n, "n", minimum=0, maximum=10**9)
    k = _check_int(k, "k", minimum=0, maximum=1000)
    if k > n:
        raise ValueError(f"k must be between 0 and n={n}; got {k}")
    c = math.comb(n, k)
    return c, c / n ** k if n else 1.0


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


def exp_history(group, xi, n=DEFAULT_N, method="product", side="left"):
    """Estimates of exp(xi) on ``group`` for each n in ``n`` by one of :data:`EXP_METHODS`.

    ``method``: ``"closed"`` (``group.exp``, error 0), ``"taylor"`` (first n terms of (1.51)),
    ``"product"`` ((I + xi^/n)^n, (1.49)), ``"euler"`` (n forward-Euler steps of unit total time
    along the ``side``-invariant field, (1.46) or (1.47), in the group's own coordinates).
    ``xi`` is a single Lie-algebra vector (a body velocity for ``side="left"``, a spatial velocity
    for ``side="right"``). Returns an :class:`ExpHistory`.
    """
    group = check_group(group)
    xi = _check_xi(group, xi)
    ns = _check_n_list(n)
    side = _check_side(side)
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
            mats = _state_matrices(group, np.stack([_euler_states(group, xi, int(m), side)[-1] for m in ns]))
        error = _frobenius(mats - exact_matrix)
    if not (np.all(np.isfinite(mats)) and np.all(np.isfinite(error))):
        raise ValueError(f"xi is too large for method {method!r} with n up to {int(ns[-1])}: the "
                         f"estimates of exp(xi) overflow a float")
    return ExpHistory(method=method, side=side, group=group, xi=xi, n=ns, matrices=mats,
                      exact=exact, exact_matrix=exact_matrix)


def exp_closed_form(group, xi, n=DEFAULT_N, side="left"):
    """The closed-form reference ``group.exp(xi)`` as an :class:`ExpHistory` (error 0); ex. 1.4a/b."""
    return exp_history(group, xi, n, "closed", side)


def exp_taylor(group, xi, n=DEFAULT_N, side="left"):
    """Partial sums sum_{k<n} xi^^k / k! of the matrix series (1.51); error falls like |xi|^n / n!."""
    return exp_history(group, xi, n, "taylor", side)


def exp_product(group, xi, n=DEFAULT_N, side="left"):
    """Cumulative products (I + xi^/n)^n of (1.49); error ~ 1/n. ``side`` orders the path factors."""
    return exp_history(group, xi, n, "product", side)


def exp_euler(group, xi, n=DEFAULT_N, side="left"):
    """n forward-Euler steps of g_dot = T_e L_g xi (``"left"``, (1.46)) or T_e R_g xi (``"right"``,
    (1.47)) from the identity over unit time; error ~ 1/n."""
    return exp_history(group, xi, n, "euler", side)


def exp_four_ways(group, xi, n=DEFAULT_N, side="left"):
    """``{"closed", "taylor", "product", "euler"} -> ExpHistory`` for one xi: exercise 1.4d."""
    return {m: exp_history(group, xi, n, m, side) for m in EXP_METHODS}



def se2_exp_study(thetadots=(0.5, 1.0, 2.0, 4.0), n=DEFAULT_N, speed=1.0):
    """Exercise 1.4d in one call: every method and side for xi = (speed, 0, thetadot).

    Returns ``{side: {method: [ExpHistory for each thetadot]}}`` with sides ``"left"`` and
    ``"right"`` and methods :data:`EXP_METHODS`, all on SE(2) with the same ``n``. The fitted
    orders (``h.order()``) are about 1 for Euler and cumulative products; Taylor errors fall faster
    than any power of n, and more slowly (in n) the larger |thetadot| is.
    """
    td = as_array(thetadots, "thetadots", what=" (rotation rates)")
    if td.ndim > 1:
        raise ValueError(f"thetadots must be a number or a 1-D array; got shape {td.shape}")
    speed = _check_scalar(speed, "speed")
    _check_n_list(n)
    xis = [np.array([speed, 0.0, w]) for w in np.atleast_1d(td)]
    try:
        return {side: {m: [exp_history(SE2, xi, n, m, side) for xi in xis] for m in EXP_METHODS}
                for side in _SIDES}
    except ValueError as exc:
        raise ValueError(f"thetadots and speed are too large: {exc}") from None

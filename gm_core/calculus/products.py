"""Product integrals, quotient derivatives and the binomial step of the *Multiplicative Calculus*
box ((1.xx)-(1.xxxii)) and (1.50)-(1.51) (numpy only). Re-exported by :mod:`gm_core.calculus`."""
from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import Literal, overload

import numpy as np
from numpy.typing import ArrayLike

from gm_core.calculus.arguments import check_scalar, check_side, check_steps, matrix_value
from gm_core.groups import LieGroup, check_group
from gm_core.validation import FloatArray, SingularShapeError, as_array, check_option

__all__ = ["product_integral", "RunningProduct", "quotient_derivative", "element_from_matrix",
           "binomial_terms", "binomial_table"]


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
    def final(self) -> FloatArray | float:
        return self.products[-1]

    def __iter__(self) -> Iterator[np.ndarray]:
        yield self.x
        yield self.products


#: What :func:`product_integral` and :func:`quotient_derivative` integrate or differentiate: a
#: function ``x -> (k, k) matrix`` (or ``x -> number``), or (for a product integral) a constant.
MatrixFunction = Callable[[float], ArrayLike]


@overload
def product_integral(v: MatrixFunction | ArrayLike, a: float, b: float, n: int, side: str = ..., *,
                     point: str = ..., history: Literal[False] = ...) -> FloatArray | float: ...
@overload
def product_integral(v: MatrixFunction | ArrayLike, a: float, b: float, n: int, side: str = ..., *,
                     point: str = ..., history: Literal[True]) -> RunningProduct: ...
@overload
def product_integral(v: MatrixFunction | ArrayLike, a: float, b: float, n: int, side: str = ..., *,
                     point: str = ..., history: bool) -> FloatArray | float | RunningProduct: ...
def product_integral(v: MatrixFunction | ArrayLike, a: float, b: float, n: int, side: str = "right", *,
                     point: str = "end", history: bool = False) -> FloatArray | float | RunningProduct:
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
    a = check_scalar(a, "a")
    b = check_scalar(b, "b")
    n = check_steps(n, "n")
    side = check_side(side)
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
            return matrix_value(v(float(nodes[k])), "v(x)")
        V0, scalar = factor_value(0)
        constant = None
    else:
        V0, scalar = matrix_value(v, "v")
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


def quotient_derivative(F: MatrixFunction, x: ArrayLike, side: str = "right", h: float | None = None, *,
                        method: str = "central") -> FloatArray | float:
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
    side = check_side(side)
    method = check_option(method, "method", ("central", "quotient"))
    xs = as_array(x, "x", what=" (a number or a 1-D array of numbers)")
    if xs.ndim > 1 or xs.size == 0:
        raise ValueError(f"x must be a number or a non-empty 1-D array; got shape {xs.shape}")
    if h is not None:
        h_val = check_scalar(h, "h")
        if h_val <= 0:
            raise ValueError(f"h must be a positive step size; got {h!r}")

    def one(x0):
        step = h_val if h is not None else _default_step(x0, method)
        Fx, scalar = matrix_value(F(x0), "F(x)")
        try:
            Finv = np.linalg.inv(Fx)
        except np.linalg.LinAlgError:
            raise SingularShapeError(
                f"F(x) is singular at x={x0:g}: the quotient derivative needs an invertible value"
            ) from None
        if not np.all(np.isfinite(Finv)):
            raise SingularShapeError(f"F(x) is singular at x={x0:g}: its inverse is not finite")
        Fp, _ = matrix_value(F(x0 + step), "F(x)")
        if method == "central":
            Fm, _ = matrix_value(F(x0 - step), "F(x)")
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
def element_from_matrix(group: LieGroup, M: ArrayLike) -> FloatArray:
    """Coordinates of the group element nearest a (possibly non-group) matrix ``M``.

    Truncated Taylor sums and the products (I + A/n)^k are not exactly group matrices (their
    rotation blocks are scaled). This reads the translation columns as they are and the angle of
    a 2x2 block [[a, -b], [b, a]] + (anything symmetric) as atan2 of its rotational part, which is
    the angle of the nearest rotation (polar decomposition). Exact group matrices round-trip.
    For (R+, x) the single entry is returned unchecked (a partial sum can be negative). The
    reading is the group's own :meth:`~gm_core.groups.LieGroup.nearest_element`.
    """
    return check_group(group).nearest_element(M)


def binomial_terms(n: int, k: int) -> tuple[int, float]:
    """The binomial coefficient C(n, k) = n!/(k!(n-k)!) used between (1.50) and (1.51).

    Returns ``(C(n, k), C(n, k) / n^k)``: the second tends to 1/k! as n -> infinity, which is why
    each term of the binomial expansion of (I + A/n)^n tends to A^k/k!. (The draft's
    coefficient n^k / k! is the large-n approximation of C(n, k), not equal to it.)
    """
    n = check_steps(n, "n", minimum=0, maximum=10**9)
    k = check_steps(k, "k", minimum=0, maximum=1000)
    if k > n:
        raise ValueError(f"k must be between 0 and n={n}; got {k}")
    c = math.comb(n, k)
    return c, c / n ** k if n else 1.0


def binomial_table(ns: Iterable[int] = (5, 10, 100, 1000), kmax: int = 5
                   ) -> list[tuple[int, int, int, float, float, float]]:
    """Rows (n, k, C(n,k), C(n,k)/n^k, 1/k!, n^k/k!) showing why (I + A/n)^n -> sum A^k/k!.

    Uses :func:`binomial_terms`; the last column is the draft's coefficient in (1.50), which is
    *not* C(n, k).
    """
    kmax = check_steps(kmax, "kmax", minimum=0, maximum=1000)
    rows = []
    for n in ns:
        for k in range(kmax + 1):
            c, ratio = binomial_terms(n, k)
            rows.append((n, k, c, ratio, 1.0 / math.factorial(k), n ** k / math.factorial(k)))
    return rows

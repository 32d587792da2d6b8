"""Gaits as Fourier series and their optimisation (numpy/scipy only), after Ramasamy & Hatton (2019).

A Fourier gait moves each joint as ``r_j(t) = c_j + sum_k a_jk cos(k w t) + b_jk sin(k w t)``,
``w = 2 pi / T``. :func:`optimize_gait` maximises the net translation ``|(x, y) of g(T)|`` or the
efficiency (translation per unit path length in the cost metric) over the coefficients with
scipy's L-BFGS-B and an exact gradient of the discretised problem's continuous adjoint:

    delta g(T) = g(T) * int_0^T Ad_{g(T)^-1 g(t)} delta xi(t) dt,
    delta xi = -(dA/dr . delta r) r_dot - A delta r_dot,

(the variation of ``g_dot = g xi``), and for the path length
``delta L = int (r_dot^T M delta r_dot + 1/2 r_dot^T (dM . delta r) r_dot) / |r_dot|_M dt``.
tests/test_geometry_optimal.py compares this gradient with finite differences.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.geometry.curvature import connection_derivative
from gm_core.geometry.metrics import metric_function, path_length
from gm_core.groups import SE2, matvec
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.gaits import Gait, GaitLike, as_gait
from gm_core.systems.minimum_perturbation import MAX_DIMENSION, MinimumPerturbationFrame, too_many_dimensions
from gm_core.systems.motion import check_gait, check_system, net_displacement, trajectory
from gm_core.systems.reframed import Reframed
from gm_core.validation import (
    FloatArray,
    SingularShapeError,
    as_array,
    check_int,
    check_option,
    positive_number,
    real_number,
)

__all__ = ["FourierGait", "fourier_gait", "fourier_fit", "travelling_wave", "optimize_gait", "OptimalGait", "gait_objective"]

#: Trial gaits must keep this fraction of the minimum-perturbation rectangle's width from its edges.
EDGE_MARGIN = 1e-3

#: Cost returned for trial gaits that reach a singular shape (a finite wall the line search backs off from).
_REJECT = 1e3


class FourierGait(Gait):
    """A :class:`Gait` given by Fourier coefficients: ``center (n,)``, ``a, b (n, order)`` (cos, sin)."""

    def __init__(self, a: ArrayLike, b: ArrayLike, center: ArrayLike, period: float,
                 name: str = "Fourier gait") -> None:
        a, b, center = np.asarray(a, dtype=float), np.asarray(b, dtype=float), np.asarray(center, dtype=float)
        self.a, self.b, self.center = a, b, center
        self.order = a.shape[1]
        k = np.arange(1, self.order + 1)
        w = 2 * np.pi / period
        self._k, self._w = k, w

        def shape(t):
            kt = w * np.asarray(t, dtype=float)[..., None] * k
            return center + np.cos(kt) @ a.T + np.sin(kt) @ b.T

        def vel(t):
            kt = w * np.asarray(t, dtype=float)[..., None] * k
            return (np.cos(kt) * (w * k)) @ b.T - (np.sin(kt) * (w * k)) @ a.T

        super().__init__(shape, period, vel, name=name)

    @property
    def parameters(self) -> FloatArray:
        """Flat coefficient vector ``[center, a.ravel(), b.ravel()]``, length n (1 + 2 order)."""
        return np.concatenate([self.center, self.a.ravel(), self.b.ravel()])

    @classmethod
    def from_parameters(cls, p: ArrayLike, n_shape: int, order: int, period: float = 2 * np.pi,
                        name: str = "Fourier gait") -> FourierGait:
        p = np.asarray(p, dtype=float)
        n, K = n_shape, order
        return cls(p[n:n + n * K].reshape(n, K), p[n + n * K:].reshape(n, K), p[:n].copy(), float(period), name)

    def basis(self, t: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Per-joint basis values and time derivatives at t (N,): two arrays (1 + 2 order, N)."""
        kt = self._w * np.asarray(t, dtype=float)[None, :] * self._k[:, None]
        wk = (self._w * self._k)[:, None]
        phi = np.vstack([np.ones((1, kt.shape[1])), np.cos(kt), np.sin(kt)])
        dphi = np.vstack([np.zeros((1, kt.shape[1])), -wk * np.sin(kt), wk * np.cos(kt)])
        return phi, dphi


def fourier_gait(a: ArrayLike, b: ArrayLike | None = None, center: ArrayLike | None = None, *,
                 period: float = 2 * np.pi, name: str = "Fourier gait") -> FourierGait:
    """A closed gait whose joints are truncated Fourier series (any order, any centre).

    ``a``: cosine coefficients (n, order) (``a[j, k-1]`` multiplies cos(k w t) in joint j);
    ``b``: sine coefficients, same shape (zeros if None); ``center``: (n,) (zeros if None);
    ``period`` T, with w = 2 pi / T. The velocity is exact.
    """
    a = as_array(a, "a")
    if a.ndim != 2 or a.shape[1] < 1:
        raise ValueError(f"a must have shape (n_shape, order) with order >= 1; got shape {a.shape}")
    b = np.zeros_like(a) if b is None else as_array(b, "b", a.shape[-1:], what=" (same shape as a)")
    if b.shape != a.shape:
        raise ValueError(f"b must have the same shape as a {a.shape}; got shape {b.shape}")
    center = np.zeros(a.shape[0]) if center is None else as_array(center, "center", (a.shape[0],))
    if center.ndim != 1:
        raise ValueError(f"center must have shape ({a.shape[0]},); got shape {center.shape}")
    T = positive_number(period, "period")
    return FourierGait(a.copy(), b.copy(), center.copy(), T, name)


def fourier_fit(gait: GaitLike, order: int, *, samples: int = 256) -> FourierGait:
    """The truncated Fourier series of ``gait`` (``order`` harmonics, same period and centre) as a :class:`FourierGait`.

    The coefficients are the discrete Fourier transform of ``samples`` shapes at equal time steps
    (``a_k = 2 Re X_k / N``, ``b_k = -2 Im X_k / N``, centre ``X_0 / N``), so a Fourier gait of at
    most ``order`` harmonics is returned to round-off; a spline drawn through clicked points gets
    the smooth loop nearest to it, a start for :func:`optimize_gait`.
    """
    gait = as_gait(gait)
    order = check_int(order, "order", 1, 64)
    samples = check_int(samples, "samples", 2 * order + 1, 65536, what=" (more than twice the order)")
    T = gait.period
    X = np.fft.rfft(gait(np.arange(samples) * (T / samples)), axis=0) / samples   # (samples // 2 + 1, n)
    return fourier_gait(2 * X[1:order + 1].real.T, -2 * X[1:order + 1].imag.T, X[0].real, period=T,
                        name=f"{gait.name} (Fourier order {order})")


def travelling_wave(n_joints: int, amplitude: float = 0.8, lag: float = np.pi / 2, *,
                    period: float = 2 * np.pi) -> FourierGait:
    """The travelling wave ``alpha_j(t) = A sin(w t - (j - 1) lag)`` in joints j = 1..n (a Fourier gait of order 1).

    Each joint lags its neighbour towards the head by ``lag``: the wave runs from link 1
    towards link N. ``amplitude`` A > 0 (rad), w = 2 pi / ``period``.
    """
    n = check_int(n_joints, "n_joints", minimum=1, maximum=200, what=" (the number of joints)")
    A = positive_number(amplitude, "amplitude")
    lag = real_number(lag, "lag", what=" (the phase lag between joints, rad)")
    j = np.arange(n)
    return fourier_gait((-A * np.sin(j * lag))[:, None], (A * np.cos(j * lag))[:, None], period=period,
                        name=f"travelling wave: amplitude {A:.2f}, lag {lag:.2f} rad")


# ---------------------------------------------------------------------------------------------
# Objective and its gradient
# ---------------------------------------------------------------------------------------------
def _metric_derivative(Mf, r):
    """M (N, n, n) and dM (N, n, n, n) by central differences (dM[..., k] = dM/dr_k)."""
    n = r.shape[-1]
    h = 6e-6 * np.maximum(1.0, np.abs(r))
    offs = np.zeros((2 * n,) + r.shape)
    for k in range(n):
        offs[2 * k, :, k], offs[2 * k + 1, :, k] = h[:, k], -h[:, k]
    vals = np.asarray(Mf(r[None] + offs))
    dM = np.stack([(vals[2 * k] - vals[2 * k + 1]) / (2 * h[:, k, None, None]) for k in range(n)], -1)
    return vals.mean(axis=0), dM


def _check_intervals(intervals):
    n = check_int(intervals, "intervals", minimum=8, maximum=2**20, what=" (even)")
    if n % 2:
        raise ValueError(f"intervals must be an even integer >= 8; got {intervals!r}")
    return n


def gait_objective(system: LocomotionSystem, gait: GaitLike, objective: str = "displacement", *, intervals: int = 512,
                   metric: Any = None, gradient: bool = True) -> tuple[float, FloatArray | None, dict[str, Any]]:
    """Objective value and gradient with respect to ``gait.parameters`` (to be *maximised*).

    ``objective``: ``"displacement"`` (|(x, y) of g(T)|) or ``"efficiency"`` (that over the path
    length in the cost metric). Uses ``intervals`` equal time steps (even), two Magnus steps each.
    Returns ``(value, grad or None, info)`` with info = dict(g=g(T), length=L or None).
    """
    if not isinstance(gait, FourierGait):
        raise TypeError(f"gait must be a FourierGait (from fourier_gait); got {type(gait).__name__}")
    objective = check_option(objective, "objective", ("displacement", "efficiency"))
    N = _check_intervals(intervals)
    T = gait.period
    tr = trajectory(system, gait, n_frames=N + 1, substeps=2, check=False)
    gT = tr.g[-1]
    if not np.all(np.isfinite(gT)):
        raise SingularShapeError(f"the gait reaches a singular shape of {system.name}")
    d = float(np.hypot(gT[0], gT[1]))
    value, L = d, None
    t = tr.t
    if objective == "efficiency":
        Mf = metric_function(system, metric)
        v = gait.velocity(t[:-1])
        if gradient:
            M, dM = _metric_derivative(Mf, tr.r[:-1])
        else:
            M = Mf(tr.r[:-1])
        sp = np.sqrt(np.maximum(np.einsum("ti,tij,tj->t", v, M, v), 1e-300))
        L = float(sp.sum() * T / N)
        value = d / L
    if not gradient:
        return value, None, dict(g=gT, length=L)
    n = system.n_shape
    A, dA = connection_derivative(system, tr.r)
    if not (np.all(np.isfinite(A)) and np.all(np.isfinite(dA))):   # g(T) is, but the gait grazes an edge
        raise SingularShapeError(f"the gait reaches the edge of the shapes where {system.name} is defined")
    rd = gait.velocity(t)
    Ad = SE2.Ad(SE2.compose(SE2.inverse(gT), tr.g))  # (N+1, 3, 3)
    w = np.full(N + 1, 2.0)
    w[1::2] = 4.0
    w[0] = w[-1] = 1.0
    w *= T / (3 * N)  # Simpson
    phi, dphi = gait.basis(t)  # (P, N+1)
    grads = []
    for j in range(n):
        K = -matvec(Ad, np.einsum("tik,tk->ti", dA[..., j], rd)) * w[:, None]
        Lc = -matvec(Ad, A[..., j]) * w[:, None]
        eta = phi @ K + dphi @ Lc  # (P, 3)
        c, s = np.cos(gT[2]), np.sin(gT[2])
        dxy = np.stack([c * eta[:, 0] - s * eta[:, 1], s * eta[:, 0] + c * eta[:, 1]], -1)
        grads.append(dxy @ gT[:2] / max(d, 1e-300))
    grad_d = _to_parameter_order(grads, gait.order)
    if objective == "displacement":
        return value, grad_d, dict(g=gT, length=None)
    phi0, dphi0 = phi[:, :-1], dphi[:, :-1]
    Mv = matvec(M, v)
    gl = []
    for j in range(n):
        quad = 0.5 * np.einsum("ti,tik,tk->t", v, dM[..., j], v)
        gl.append((phi0 @ (quad / sp) + dphi0 @ (Mv[:, j] / sp)) * T / N)
    grad_L = _to_parameter_order(gl, gait.order)
    assert L is not None                                 # the efficiency objective measured the length
    return value, grad_d / L - d / L ** 2 * grad_L, dict(g=gT, length=L)


def _to_parameter_order(per_joint, order):
    """Reorder per-joint gradients [(1 + 2K,)] * n into the flat [center, a.ravel(), b.ravel()] layout."""
    G = np.array(per_joint)  # (n, 1 + 2K)
    return np.concatenate([G[:, 0], G[:, 1:1 + order].ravel(), G[:, 1 + order:].ravel()])


# ---------------------------------------------------------------------------------------------
# Optimisation
# ---------------------------------------------------------------------------------------------
@dataclass
class OptimalGait:
    """Result of :func:`optimize_gait`."""

    gait: FourierGait
    objective: str
    displacement: float
    net_displacement: np.ndarray
    path_length: float | None
    efficiency: float | None
    history: list = field(default_factory=list)
    success: bool = True
    message: str = ""
    nit: int = 0

    @override
    def __repr__(self) -> str:
        eff = "n/a" if self.efficiency is None else f"{self.efficiency:.5f}"
        return (f"OptimalGait({self.objective}: displacement {self.displacement:.5f}, efficiency {eff}, "
                f"{self.nit} iterations)")


def _start_gait(system, order, start, period):
    n = system.n_shape
    if start is None:
        a = np.zeros((n, order))
        b = np.zeros((n, order))
        a[0, 0] = 1.0
        b[1 % n, 0] = 1.0
        return fourier_gait(a, b, period=period, name="start: circle")
    if isinstance(start, FourierGait):
        if start.n_shape != n:
            raise ValueError(f"start has {start.n_shape} shape variables but {system.name} has {n}")
        K = max(order, start.order)
        a = np.zeros((n, K))
        b = np.zeros((n, K))
        a[:, :start.order], b[:, :start.order] = start.a, start.b
        return fourier_gait(a[:, :order] if K > order else a, b[:, :order] if K > order else b,
                            start.center, period=start.period, name="start")
    raise TypeError(f"start must be None (a circle) or a FourierGait from fourier_gait(); got {type(start).__name__}")


def optimize_gait(system: LocomotionSystem, objective: str = "displacement", order: int = 3, start: Any = None, *,
                  coordinates: str = "minimum perturbation", bounds: Any = None, metric: Any = None,
                  period: float = 2 * np.pi, maxiter: int = 200, gtol: float = 1e-7, intervals: int = 512,
                  callback: Callable[[int, float], Any] | None = None, singular_margin: float = 1e-3) -> OptimalGait:
    """Fourier gait (of ``order`` harmonics per joint) maximising ``objective``; an :class:`OptimalGait`.

    ``objective``: ``"displacement"`` (|(x, y) of g(T)|) or ``"efficiency"`` (that per unit
    path length in the cost metric); ``start``: None (the unit circle about the origin) or a
    :class:`FourierGait`; ``callback(iteration, value)`` is called after each iteration (for
    progress displays). L-BFGS on the exact adjoint gradient of :func:`gait_objective`.

    A gait that rotates the body moves its frame along an arc, so how far "the swimmer" got
    depends on which body frame is measured. As in sysplotter, the translation is measured in
    the minimum-perturbation frame over ``bounds`` (default ``system.shape_limits``), which also
    confines the gait to that rectangle; ``coordinates="given"`` measures it in the system's
    own frame instead. The start gait must stay clear of singular shapes (else
    SingularShapeError); trial gaits that come within ``singular_margin`` of one (in the scaled
    determinant of :meth:`singularity`) or come within :data:`EDGE_MARGIN` of the rectangle's
    width of its edge are rejected (a cost wall the line search backs off from), and the result
    is checked again.
    """
    from scipy.optimize import minimize

    from gm_core.geometry.coordinates import minimum_perturbation_coordinates

    check_system(system)
    if coordinates not in ("minimum perturbation", "given"):
        raise ValueError(f"coordinates must be 'minimum perturbation' or 'given'; got {coordinates!r}")
    already = (isinstance(system, Reframed) and isinstance(system.frame, MinimumPerturbationFrame)
               or getattr(system, "frame", None) == "minimum perturbation")
    if coordinates == "minimum perturbation" and not already:
        if system.n_shape > MAX_DIMENSION:
            raise ValueError(too_many_dimensions("coordinates='minimum perturbation'", system.name, system.n_shape)
                             + "; or pass coordinates='given' to measure in the system's own frame")
        system = minimum_perturbation_coordinates(system, bounds)
    if objective not in ("displacement", "efficiency"):
        raise ValueError(f"objective must be 'displacement' or 'efficiency'; got {objective!r}")
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or order < 1:
        raise ValueError(f"order must be a positive integer; got {order!r}")
    if isinstance(maxiter, bool) or not isinstance(maxiter, (int, np.integer)) or maxiter < 1:
        raise ValueError(f"maxiter must be a positive integer; got {maxiter!r}")
    _check_intervals(intervals)
    if objective == "efficiency":
        metric_function(system, metric)  # fails early if the system has no metric
    g0 = _start_gait(system, int(order), start, period)
    check_gait(system, g0)
    n, K, T = system.n_shape, g0.order, g0.period
    singular_ok = not getattr(system, "may_be_singular", False)
    frame = getattr(system, "frame", None)
    box = np.array(frame.bounds) if isinstance(frame, MinimumPerturbationFrame) else None
    if box is not None:   # the rectangle less a margin far wider than a curve bulges between samples
        box = box + EDGE_MARGIN * (box[:, 1:] - box[:, :1]) * np.array([1.0, -1.0])

    def make(p):
        return FourierGait.from_parameters(p, n, K, T)

    def fun(p):
        gait = make(p)
        if box is not None:
            r = gait(np.linspace(0, T, 4 * intervals + 1))
            if np.any(r < box[:, 0]) or np.any(r > box[:, 1]):
                return _REJECT, np.zeros_like(p)
        if not singular_ok:
            dd = system.singularity(gait(np.linspace(0, T, 4 * intervals + 1)))
            if np.any(np.abs(dd) < singular_margin) or np.any(np.sign(dd) != np.sign(dd[0])):
                return _REJECT, np.zeros_like(p)
        try:
            val, grad, _ = gait_objective(system, gait, objective, intervals=intervals, metric=metric)
        except SingularShapeError:    # a trial gait outside the rectangle, or through a singular shape
            return _REJECT, np.zeros_like(p)
        return -val, -grad

    history = []

    def cb(xk):
        val = -fun(xk)[0]
        history.append(float(val))
        if callback is not None:
            callback(len(history), float(val))

    p0 = g0.parameters
    history.append(float(-fun(p0)[0]))
    res = minimize(fun, p0, jac=True, method="L-BFGS-B", callback=cb,
                   options=dict(maxiter=int(maxiter), gtol=gtol, ftol=1e-13, maxls=40))
    best = make(res.x)
    best.name = f"optimal gait ({objective}, order {K})"
    check_gait(system, best)
    g = net_displacement(system, best, check=False)
    d = float(np.hypot(g[0], g[1]))
    L = eff = None
    try:
        L = path_length(system, best, metric=metric, check=False)
        eff = d / L
    except TypeError:
        if objective == "efficiency":
            raise
    return OptimalGait(best, objective, d, g, L, eff, history, bool(res.success), str(res.message), int(res.nit))

"""Passive spring/damper joints: drive some joints and the rest follow by second-order shape dynamics (numpy/scipy only).

A system that conserves zero momentum (a high-Reynolds swimmer started from rest, a floating chain)
moves kinematically, ``xi = -A(r) r_dot`` (3.10), whatever its shape does; its shape obeys Lagrange's
equations for the kinetic energy left once the momentum constraint is used, ``KE = 1/2 r_dot^T M(r) r_dot``
with ``M = [-A; I]^T M_sys [-A; I]`` the reduced mass metric of (3.39)-(3.40) (the system's
``shape_metric``, twice the kinetic energy):

    M(r) r_ddot + C(r, r_dot) = tau,    C_i = G_ijk r_dot_j r_dot_k,
    G_ijk = 1/2 (dM_ij/dr_k + dM_ik/dr_j - dM_jk/dr_i)     (Christoffel symbols of the first kind).

A passive joint p carries a spring and a damper, ``tau_p = -k r_p - b r_dot_p``; a driven joint d follows
a prescribed ``r_d(t)`` and its torque ``tau_d`` is whatever the equation asks. :class:`PassiveJoints`
solves the passive rows for ``r_ddot_p``, integrates them (scipy's DOP853, rtol 1e-10) from rest at
r_p = 0 for ``cycles`` periods to settle on the limit cycle, then one more period, from which it reports
the shapes, the driven torque, ``g(T)`` by the course's Magnus integrator
(:func:`~gm_core.systems.motion.net_displacement`), the work ``int tau_d . r_dot_d dt``, the torque cost
``int |tau_d|^2 dt`` and the energy the dampers dissipate. ``dM/dr`` is taken by fourth-order central
differences (step 1e-3), whose error (~1e-12 relative) is far below the integrator's.

The model is that of sysplotter's ``simulate2DPassiveSwimmer.m`` (file ``three_link_passive``: joint 1
passive, k = 0.074, b = 0.01, joint 2 driven), with these differences. sysplotter wraps joint angles to
[-pi, pi] before reading its interpolated tables; the course evaluates the metric at the shape itself
(the chain's metric is 2 pi-periodic in each joint, so the two agree). sysplotter integrates the world
pose (x, y, theta) inside its ode45 (default tolerances, RelTol 1e-3) and reports ``displ = |(x, y)|``;
the course reports the whole SE(2) element g(T). sysplotter's ``cost`` is the work ``int tau_2 r_dot_2 dt``
(named :attr:`PassiveGait.work` here); the torque-squared cost is :attr:`PassiveGait.torque_squared`.
sysplotter's energy rows (``addEnergies``) put the spring on the driven joint r2; the spring is on r1.
Its metric has the pi/8 defect of ``Inertia_link.m`` (:mod:`gm_core.systems.catalog`); the course's has not.
With that defect put back, ``tests/test_passive.py`` reproduces sysplotter's own run in Octave
(``tools/sysplotter_reference.py --passive``, stored in ``sysplotter_passive.json``) to the accuracy of its ode45.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp

from gm_core.systems.gaits import Gait
from gm_core.systems.motion import net_displacement
from gm_core.validation import FloatArray, as_array, check_int, positive_number

__all__ = ["PassiveJoints", "PassiveGait", "christoffel_symbols", "METRIC_STEP", "ODE_RTOL"]

#: Step of the fourth-order central differences of the metric, dM/dr (relative to max(1, |r|)).
METRIC_STEP = 1e-3
#: Relative tolerance of the shape integration (scipy's DOP853; absolute tolerance 1e-12).
ODE_RTOL = 1e-10
_ODE_ATOL = 1e-12
_FD4 = ((1, 8.0 / 12.0), (2, -1.0 / 12.0))


def christoffel_symbols(dM: ArrayLike) -> FloatArray:
    """Christoffel symbols of the first kind G (..., n, n, n), ``G[..., i, j, k] = 1/2 (dM_ij/dr_k + dM_ik/dr_j - dM_jk/dr_i)``.

    ``dM`` (..., n, n, n) with ``dM[..., i, j, k] = dM_ij / dr_k``; the Coriolis and centrifugal
    terms of ``M r_ddot + C = tau`` are ``C_i = G_ijk r_dot_j r_dot_k``.
    """
    dM = as_array(dM, "dM")
    if dM.ndim < 3 or not dM.shape[-1] == dM.shape[-2] == dM.shape[-3]:
        raise ValueError(f"dM must have shape (..., n, n, n) (dM[..., i, j, k] = dM_ij/dr_k); got shape {dM.shape}")
    return 0.5 * (dM + np.swapaxes(dM, -1, -2) - np.moveaxis(dM, -1, -3))


@dataclass(frozen=True)
class PassiveGait:
    """One period of a passive-joint gait on its limit cycle (after the settling periods).

    ``times`` (N,) from 0 to T (time since the period began), ``shape`` and ``shape_velocity`` (N, n) (every
    joint, passive and driven), ``torque`` (N, n_driven) at the driven joints; ``displacement`` g(T) (3,)
    from g(0) = e, by :func:`~gm_core.systems.motion.net_displacement`; ``work`` = int tau_d . r_dot_d dt
    (sysplotter's ``cost``), ``torque_squared`` = int |tau_d|^2 dt, ``dissipated`` = int b |r_dot_p|^2 dt over
    the period; ``gait`` the period's shape path as a :class:`~gm_core.systems.gaits.Gait` (open by the
    passive joints' residual drift, so give ``check=False`` to the reconstruction functions).
    """

    times: np.ndarray
    shape: np.ndarray
    shape_velocity: np.ndarray
    torque: np.ndarray
    displacement: np.ndarray
    work: float
    torque_squared: float
    dissipated: float
    gait: Gait


def _is_fourier(gait: Any) -> bool:
    """True for a Fourier gait (:class:`gm_core.geometry.optimal.FourierGait`, read by its coefficients)."""
    return isinstance(gait, Gait) and all(isinstance(getattr(gait, c, None), np.ndarray) for c in ("a", "b", "center"))


class PassiveJoints:
    """A system whose joints ``passive`` carry springs and dampers while the others are driven.

    ``system``: any system with an inertial ``shape_metric(r)`` (a high-Re chain, a floating snake;
    :func:`gm_core.systems.catalog.passive_model` for sysplotter's file), or give ``metric``, a callable
    r (..., n) -> M (..., n, n), to use another. ``passive``: joint indices from 0; ``stiffness`` k and
    ``damping`` b: one number or one per passive joint in that order, non-negative (the defaults are
    sysplotter's ``three_link_passive``: joint 1, k = 0.074, b = 0.01). The other joints are ``driven``.
    """

    def __init__(self, system: Any, passive: Sequence[int] = (0,), stiffness: ArrayLike = 0.074,
                 damping: ArrayLike = 0.01, *, metric: Callable[[Any], Any] | None = None) -> None:
        n = getattr(system, "n_shape", None)
        if not isinstance(n, int) or not callable(getattr(system, "connection", None)):
            raise TypeError(f"system must be a locomotion system (with n_shape and connection(r)); got {system!r:.80}")
        if metric is None:
            metric = getattr(system, "shape_metric", None)
        if not callable(metric):
            raise TypeError(f"metric must be a callable r -> M(r) (n, n) or None; got {type(metric).__name__}")
        if isinstance(passive, (int, np.integer)):
            passive = (int(passive),)
        if not isinstance(passive, (tuple, list)) or not passive:
            raise TypeError(f"passive must be a non-empty tuple of joint indices; got {passive!r}")
        idx = [check_int(p, "passive", minimum=0, what=" (joint indices from 0)") for p in passive]
        if max(idx) >= n:
            raise ValueError(f"passive must index the {n} shape variables of {getattr(system, 'name', 'the system')} "
                             f"(0 to {n - 1}); got {tuple(passive)}")
        if len(set(idx)) != len(idx) or len(idx) == n:
            raise ValueError(f"passive must name distinct joints and leave at least one driven; got {tuple(passive)}")
        self.system, self.metric, self.n_shape = system, metric, n
        self.passive = tuple(idx)
        self.driven = tuple(i for i in range(n) if i not in self.passive)
        self.stiffness = self._per_joint(stiffness, "stiffness")
        self.damping = self._per_joint(damping, "damping")

    def _per_joint(self, value: ArrayLike, name: str) -> FloatArray:
        if isinstance(value, (bool, np.bool_)) or value is None:
            raise TypeError(f"{name} must be a non-negative number or one per passive joint; got {value!r}")
        arr = as_array(value, name, what=" (one number or one per passive joint)")
        if arr.ndim > 1 or (arr.ndim == 1 and arr.size != len(self.passive)):
            raise ValueError(f"{name} must be one number or {len(self.passive)} (one per passive joint); got shape {arr.shape}")
        if np.any(arr < 0):
            raise ValueError(f"{name} must be non-negative; got {value!r}")
        return np.broadcast_to(arr, (len(self.passive),)).astype(float)

    # -- the shape dynamics ---------------------------------------------------------------------------
    def metric_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(M (..., n, n), dM (..., n, n, n))`` with ``dM[..., i, j, k] = dM_ij/dr_k`` (fourth-order central differences)."""
        return self._derivative(as_array(r, "r", (self.n_shape,)))

    def _derivative(self, r: FloatArray) -> tuple[FloatArray, FloatArray]:
        n = self.n_shape
        h = METRIC_STEP * np.maximum(1.0, np.abs(r))
        offsets = np.zeros((4 * n + 1,) + r.shape)
        for k in range(n):
            for m, (s, _) in enumerate(_FD4):
                offsets[4 * k + 2 * m + 1, ..., k] = s * h[..., k]
                offsets[4 * k + 2 * m + 2, ..., k] = -s * h[..., k]
        vals = np.asarray(self.metric(r[None] + offsets), dtype=float)
        dM = np.stack([sum(w * (vals[4 * k + 2 * m + 1] - vals[4 * k + 2 * m + 2]) for m, (_, w) in enumerate(_FD4))
                       / h[..., k, None, None] for k in range(n)], -1)
        return vals[0], dM

    def coriolis(self, r: ArrayLike, r_dot: ArrayLike) -> FloatArray:
        """Coriolis and centrifugal terms C(r, r_dot) (..., n) of ``M r_ddot + C = tau``: ``C_i = G_ijk r_dot_j r_dot_k``."""
        v = as_array(r_dot, "r_dot", (self.n_shape,))
        _, dM = self.metric_derivative(r)
        return np.einsum("...ijk,...j,...k->...i", christoffel_symbols(dM), v, v)

    def _step(self, r: FloatArray, v: FloatArray, a_d: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Passive accelerations and driven torques at one state (joint arrays (n,), a_d (n_driven,))."""
        p, d = list(self.passive), list(self.driven)
        M, dM = self._derivative(r)
        C = np.einsum("ijk,j,k->i", christoffel_symbols(dM), v, v)
        tau_p = -self.stiffness * r[p] - self.damping * v[p]
        a_p = np.linalg.solve(M[np.ix_(p, p)], tau_p - M[np.ix_(p, d)] @ a_d - C[p])
        acc = np.empty(self.n_shape)
        acc[p], acc[d] = a_p, a_d
        return a_p, M[d] @ acc + C[d]

    # -- simulation ---------------------------------------------------------------------------------------
    def _driven(self, driven: Any, period: Any) -> tuple[Gait, Callable[[float], FloatArray], float]:
        """The driven joints as a Gait (for arrays of times), t -> rows (r, r_dot, r_ddot) (3, n_driven) at one time, T."""
        if _is_fourier(driven):
            T = driven.period if period is None else positive_number(period, "period")
            if abs(T - driven.period) > 1e-12 * driven.period:
                raise ValueError(f"period must match the Fourier gait's period {driven.period:g} (or be None); got {period!r}")
            shape, a, b, centre = driven, driven.a, driven.b, driven.center
            wk = 2 * np.pi / T * np.arange(1, a.shape[1] + 1)

            def state(t: float) -> FloatArray:
                c, s = np.cos(wk * t), np.sin(wk * t)
                return np.stack([centre + a @ c + b @ s, b @ (wk * c) - a @ (wk * s), -a @ (wk ** 2 * c) - b @ (wk ** 2 * s)])
        elif isinstance(driven, (tuple, list)) and len(driven) == 3:
            if not all(callable(f) for f in driven):
                raise TypeError("driven must be a FourierGait or three callables (r(t), r_dot(t), r_ddot(t)); "
                                f"got {[type(f).__name__ for f in driven]}")
            if period is None:
                raise ValueError("period must be given (a positive number) when driven is three callables")
            T = positive_number(period, "period")
            shape, funcs = Gait(driven[0], T, driven[1], name="driven joints"), tuple(driven)

            def state(t: float) -> FloatArray:
                rows = [np.atleast_1d(np.asarray(f(t), dtype=float)) for f in funcs]
                if len({row.shape for row in rows}) != 1:
                    raise ValueError(f"driven: r(t), r_dot(t) and r_ddot(t) must have one shape; got {[row.shape for row in rows]}")
                return np.stack(rows)
        else:
            raise TypeError(f"driven must be a FourierGait (gm_core.geometry.optimal.fourier_gait) or three callables "
                            f"(r(t), r_dot(t), r_ddot(t)); got {type(driven).__name__}")
        nd = len(self.driven)
        if shape.n_shape != nd or state(0.0).shape != (3, nd):
            raise ValueError(f"driven must move the {nd} driven joint(s) {self.driven}; it has {shape.n_shape} component(s)")
        return shape, state, T

    def simulate(self, driven: Any, period: float | None = None, cycles: int = 5, samples: int = 201) -> PassiveGait:
        """The period after ``cycles`` settling periods from rest (r_p = r_dot_p = 0), as a :class:`PassiveGait`.

        ``driven``: the driven joints' motion, a :class:`~gm_core.geometry.optimal.FourierGait` with one
        component per driven joint (``period`` then defaults to its own), or three callables t -> r_d(t),
        r_dot_d(t), r_ddot_d(t) with ``period`` T. ``samples`` equally spaced times over the last period.
        """
        shape, state, T = self._driven(driven, period)
        cycles = check_int(cycles, "cycles", minimum=0, maximum=10 ** 4, what=" (settling periods before the one reported)")
        samples = check_int(samples, "samples", minimum=2, maximum=10 ** 6, what=" (times over the last period)")
        p, d, npas = list(self.passive), list(self.driven), len(self.passive)

        def torque_and_rates(t: float, y: FloatArray) -> tuple[FloatArray, FloatArray]:
            (r_d, v_d, a_d), r, v = state(t), np.empty(self.n_shape), np.empty(self.n_shape)
            r[p], v[p], r[d], v[d] = y[:npas], y[npas:2 * npas], r_d, v_d
            a_p, tau_d = self._step(r, v, a_d)
            return tau_d, np.concatenate([v[p], a_p, [tau_d @ v[d], tau_d @ tau_d, float(self.damping @ v[p] ** 2)]])

        def rhs(t: float, y: FloatArray) -> FloatArray:
            return torque_and_rates(t, y)[1]

        y0 = np.zeros(2 * npas + 3)
        if cycles:
            y0 = solve_ivp(rhs, (0.0, cycles * T), y0, method="DOP853", rtol=ODE_RTOL, atol=_ODE_ATOL).y[:, -1]
            y0[2 * npas:] = 0.0
        sol = solve_ivp(rhs, (0.0, T), y0, method="DOP853", rtol=ODE_RTOL, atol=_ODE_ATOL, dense_output=True)
        if not sol.success:
            raise RuntimeError(f"the shape integration failed: {sol.message}")
        dense = sol.sol

        def full(t: Any, what: int) -> FloatArray:
            t = np.asarray(t, dtype=float)
            out = np.empty(t.shape + (self.n_shape,))
            out[..., p] = np.moveaxis(dense(t.reshape(-1))[what * npas:(what + 1) * npas], 0, -1).reshape(t.shape + (npas,))
            out[..., d] = shape(t) if what == 0 else shape.velocity(t)
            return out

        gait = Gait(lambda t: full(t, 0), T, lambda t: full(t, 1), name="passive gait (last period)")
        times = np.linspace(0.0, T, samples)
        r, v = full(times, 0), full(times, 1)
        y = dense(times)
        torque = np.array([torque_and_rates(times[i], y[:, i])[0] for i in range(samples)])
        g = net_displacement(self.system, gait, check=False, rtol=1e-9)
        work, tsq, diss = (float(x) for x in sol.y[2 * npas:, -1])
        return PassiveGait(times, r, v, torque, g, work, tsq, diss, gait)

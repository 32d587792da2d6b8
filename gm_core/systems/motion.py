"""Kinematic locomotion (chapter 3): local connections, singular gaits and reconstruction (numpy/scipy only).

A symmetric linear-kinematic locomotor moves with body velocity ``xi = -A(r) r_dot`` (3.10),
where ``A`` is the *local connection*. This module holds the parts shared by every system in
:mod:`gm_core.systems` (which import it; it never imports them):

* :func:`check_system` (the one validator of systems at the boundary; a
  :class:`CheckedSystem` was checked when built and is trusted), :func:`body_velocity`;
* :func:`fd_connection_derivative`, :func:`curvature_form`: the connection's
  derivative (one difference routine), its curvature 2-form and curl;
* :func:`check_gait`: does a gait meet a singular shape?
* :func:`net_displacement`, :func:`trajectory`: reconstruction of the position trajectory by
  integrating ``g_dot = T_e L_g xi`` with a fourth-order Magnus (Lie-group) integrator built on
  the position group's ``exp``, so every step stays exactly in the group: SE(2), or the group a
  system names as its ``position_group`` (SO(3) for a body turning in space, :func:`position_group`).

The routes to the connection (:func:`connection_from_pfaffian`, (3.11)-(3.17);
:func:`connection_from_mass_matrix` and :func:`metric_from_jacobians`, (3.39)-(3.40)) live in
:mod:`gm_core.systems.connection`, the gaits (:class:`Gait`, :func:`circle_gait`, :func:`as_gait`) in
:mod:`gm_core.systems.gaits`.

Conventions: a shape ``r`` is an array ``(..., n)``; a connection is ``(..., 3, n)``; the body
velocity is ``(xi^x, xi^y, xi^theta)``. At a *singular* shape (``det omega_xi = 0``) the local
connection does not exist: ``connection`` returns NaN there quietly, and integrating a gait that
reaches such a shape raises :class:`gm_core.SingularShapeError`. A *system* is any object with
``n_shape``, ``name``, ``connection(r)`` and, if ``may_be_singular``, ``singularity(r)``.
"""
from __future__ import annotations

import math
import numbers
import warnings
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups import SE2, LieGroup, matvec
from gm_core.systems.gaits import Gait, GaitLike, as_gait
from gm_core.systems.pacing import constant_rate_path
from gm_core.validation import FloatArray, SingularShapeError, as_array, check_int, positive_number, real_number

__all__ = [
    "CheckedSystem", "SystemLike", "validate_system", "check_system", "trusted_dimension", "body_velocity",
    "fd_connection_derivative", "curvature_form",
    "exterior_derivative", "FD_STEP", "check_gait", "net_displacement", "trajectory", "displacement_until",
    "Trajectory", "drive", "AccuracyWarning",
]


class AccuracyWarning(UserWarning):
    """A result was returned without meeting its requested tolerance; the message gives the estimate."""


class CheckedSystem:
    """Base of the systems checked once, when they are built (every :class:`gm_core.systems.LocomotionSystem`).

    :func:`check_system` returns at once for an instance, and the functions of :mod:`gm_core.systems`
    and :mod:`gm_core.geometry` read its ``n_shape`` without checking it again
    (:func:`trusted_dimension`); any other object is checked by :func:`check_system` wherever it
    enters.
    """

    name: str
    n_shape: int


class SystemLike(Protocol):
    """What the functions of this module use of a system (every :class:`CheckedSystem`
    and any object shaped like one): a ``name``, ``n_shape`` and ``connection(r)``, and
    ``singularity(r)`` where the system ``may_be_singular``."""

    name: str
    n_shape: int

    def connection(self, r: ArrayLike) -> FloatArray: ...

    def singularity(self, r: ArrayLike) -> FloatArray: ...


def validate_system(system: Any, name: str = "system") -> int:
    """n_shape of ``system`` after checking it looks like a locomotion system (TypeError naming ``name``).

    The full check, whatever ``system`` is: an object with an integer ``n_shape`` >= 1 and a
    callable ``connection(r)``; one that ``may_be_singular`` must also have ``singularity(r)``.
    A :class:`gm_core.systems.LocomotionSystem` runs it once, when it is built.
    """
    n = getattr(system, "n_shape", None)
    if (isinstance(system, (str, bytes, type)) or not isinstance(n, numbers.Integral) or isinstance(n, bool)
            or n < 1 or not callable(getattr(system, "connection", None))):
        raise TypeError(f"{name} must be a locomotion system (e.g. gm_core.systems.KinematicSnake()) with "
                        f"n_shape and connection(r); got {system!r:.80}")
    if getattr(system, "may_be_singular", False) and not callable(getattr(system, "singularity", None)):
        raise TypeError(f"{name} {system!r:.60} may be singular but has no singularity(r) method")
    return int(n)


def check_system(system: Any, name: str = "system") -> int:
    """n_shape of ``system`` after checking it looks like a locomotion system (TypeError naming ``name``).

    The one validator of systems at the boundary: a :class:`CheckedSystem` (every
    :class:`gm_core.systems.LocomotionSystem`, checked when it was built) is trusted and its
    ``n_shape`` returned at once; any other object, shaped like a system or not, gets the full
    check of :func:`validate_system`.
    """
    if isinstance(system, CheckedSystem):
        return system.n_shape
    return validate_system(system, name)


def trusted_dimension(system: Any, name: str = "system") -> int:
    """n_shape of ``system`` inside the library: read directly from a :class:`CheckedSystem`
    (checked once, when it was built), else :func:`check_system` (a duck-typed system, checked
    wherever it enters). Public functions call this, so that a system handed from one to another
    is not checked again at every step."""
    if isinstance(system, CheckedSystem):
        return system.n_shape
    return check_system(system, name)


# ---------------------------------------------------------------------------------------------
# Body velocity, the connection's derivative, curl and curvature
# ---------------------------------------------------------------------------------------------
def body_velocity(system: SystemLike, r: ArrayLike, r_dot: ArrayLike) -> FloatArray:
    """Body velocity ``xi = -A(r) r_dot`` (..., 3) of ``system`` at shape r moving at r_dot, (3.10)."""
    n = trusted_dimension(system)
    r = as_array(r, "r", (n,), what=f" (a shape of {system.name})")
    r_dot = as_array(r_dot, "r_dot", (n,), what=f" (a shape velocity of {system.name})")
    try:
        np.broadcast_shapes(r.shape, r_dot.shape)
    except ValueError:
        raise ValueError(f"r and r_dot have incompatible batch shapes {r.shape[:-1]} and {r_dot.shape[:-1]}") from None
    A = system.connection(r)
    if not np.all(np.isfinite(A)):
        raise SingularShapeError(f"r reaches a singular shape of {system.name} "
                                 f"({getattr(system, 'singular_description', 'det omega_xi = 0')}): "
                                 f"the local connection does not exist there")
    return -matvec(A, r_dot)


#: Relative central-difference step for connection derivatives (about eps**(1/3)).
FD_STEP = 6e-6


def fd_connection_derivative(system: SystemLike, r: ArrayLike, step: float = FD_STEP) -> tuple[FloatArray, FloatArray]:
    """``(A (..., 3, n), dA (..., 3, n, n))`` by central differences, ``dA[..., i, j, k] = d A_ij / d r_k``.

    The one difference route to the connection's derivative (systems without a closed form use
    it through :meth:`LocomotionSystem.connection_derivative`). The step is ``step`` relative to
    ``max(1, |r|)``; A itself is the mean of the stencil values (error O(h^2), about 1e-11), all
    2n stencil points in one batched call.
    """
    n = trusted_dimension(system)
    r = as_array(r, "r", (n,), what=f" (a shape of {system.name})")
    step = positive_number(step, "h")
    h = step * np.maximum(1.0, np.abs(r))
    offsets = np.zeros((2 * n,) + r.shape)
    for k in range(n):
        offsets[2 * k, ..., k] = h[..., k]
        offsets[2 * k + 1, ..., k] = -h[..., k]
    vals = system.connection(r[None] + offsets)  # (2n, ..., 3, n)
    dA = np.stack([(vals[2 * k] - vals[2 * k + 1]) / (2 * h[..., k, None, None]) for k in range(n)], -1)
    return np.asarray(vals.mean(axis=0), dtype=float), dA


def exterior_derivative(dA: ArrayLike) -> FloatArray:
    """``dA_j/dr_i - dA_i/dr_j`` (..., 3, n, n) from dA (..., 3, n, n) (index order of :func:`fd_connection_derivative`)."""
    dA = np.asarray(dA, dtype=float)
    return np.swapaxes(dA, -1, -2) - dA


def position_group(system: Any) -> LieGroup:
    """The Lie group a system's position lives in: its ``position_group`` attribute, SE(2) if it has none.

    It must have a three-dimensional algebra (the three rows of the connection); TypeError otherwise.
    """
    G = getattr(system, "position_group", SE2)
    if not isinstance(G, LieGroup) or G.tangent_dim != 3 or G.param_dim != 3:
        raise TypeError(f"system.position_group must be a gm_core Lie group with three coordinates and a "
                        f"three-dimensional algebra (SE2, SO3); got {G!r:.60}")
    return G


def curvature_form(A: ArrayLike, dA: ArrayLike, group: LieGroup = SE2) -> FloatArray:
    """Constraint curvature 2-form D(-A) (..., 3, n, n) from A (..., 3, n) and its derivative dA (..., 3, n, n).

    ``F[..., :, i, j] = -(d_i A_j - d_j A_i) + [A_i, A_j]`` (Hatton & Choset 2015, with the book's
    sign xi = -A r_dot), antisymmetric in (i, j): one algebra component per pair of shape
    directions, the bracket that of ``group`` (se(2) by default). NaN where A or dA is not finite.
    """
    A = np.asarray(A, dtype=float)
    ext = exterior_derivative(dA)
    ok = np.asarray(np.isfinite(A).all(axis=(-1, -2)) & np.isfinite(ext).all(axis=(-1, -2, -3)))
    if not ok.all():  # singular shapes: NaN out, and keep NaN away from the bracket's input check
        A = np.where(ok[..., None, None], A, 0.0)
        ext = np.where(ok[..., None, None, None], ext, np.nan)
    X = np.moveaxis(A, -2, -1)                                      # (..., n, 3): the columns A_i
    br = group.bracket(X[..., :, None, :], X[..., None, :, :])        # (..., n, n, 3)
    return -ext + np.moveaxis(br, -1, -3)


# ---------------------------------------------------------------------------------------------
# Singular shapes along a gait
# ---------------------------------------------------------------------------------------------
#: |scaled det omega_xi| at or below this along a gait counts as reaching a singular shape.
GAIT_SINGULAR_TOL = 1e-9
#: check_gait's sample count for a gait whose feature time is unknown (any plain callable).
DENSE_SAMPLES = 2 ** 16
#: At least this many samples per gait, and this many per feature time.
MIN_SAMPLES, SAMPLES_PER_FEATURE = 4096, 64
_MAX_SAMPLES = 2 ** 24
_CHUNK = 8192


def _check_shapes(system, gait):
    n = trusted_dimension(system)
    if gait.n_shape != n:
        raise ValueError(f"gait has {gait.n_shape} shape variables but {system.name} has {n}")


def _singular_error(system, gait, s, how):
    T = gait.period
    r = gait(np.array([s * T]))[0]
    return SingularShapeError(
        f"the gait {how} a singular shape of {system.name} at t = {s * T:.6g} (of period {T:g}), "
        f"r = ({', '.join(f'{v:.6g}' for v in r)}): there det(omega_xi) = 0 and the local "
        f"connection does not exist ({getattr(system, 'singular_description', 'singular shape')})")


def _det_at(system, gait, s):
    return float(system.singularity(gait(np.array([s * gait.period])))[0])


def _scan(system, gait, s, d):
    """Raise SingularShapeError if d, sampled at normalized times s, reaches zero or changes sign."""
    order = np.argsort(s, kind="stable")
    s, d = s[order], d[order]
    small = ~(np.abs(d) > GAIT_SINGULAR_TOL)  # NaN counts as singular too
    if np.any(small):
        raise _singular_error(system, gait, s[np.argmax(small)], "reaches")
    cross = np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0]
    if cross.size:
        from scipy.optimize import brentq

        i = cross[0]
        raise _singular_error(system, gait, brentq(lambda x: _det_at(system, gait, x), s[i], s[i + 1],
                                                   xtol=1e-15), "crosses")


def check_gait(system: SystemLike, gait: GaitLike, *, samples: int | None = None) -> None:
    """Raise SingularShapeError if the gait crosses or touches a singular shape of ``system``.

    Samples the scaled ``det omega_xi`` (``system.singularity``, never zero at regular shapes) at
    ``samples + 1`` equally spaced times over one period, looks for sign changes and zeros, and
    refines near-zero local minima of its magnitude (bounded scalar minimisation) to catch
    touching points; the error names the time and shape where it happens.

    What is guaranteed: every crossing during which the gait stays on the other side of the
    singular set for longer than the sample spacing T / samples is found, and so is every
    touching point whose neighbourhood shows as a local minimum among the samples. The default
    spacing follows the gait's ``feature_time``: 64 samples per feature (at least 4096 per
    period) for circles and splines, ``DENSE_SAMPLES`` = 65536 for plain callables, whose
    features could be arbitrarily narrow. An excursion shorter than the spacing can escape this
    check; :func:`net_displacement` and :func:`trajectory` also watch the sign of the
    determinant at every node of their integrators (which refine where the motion is fast).
    """
    gait = as_gait(gait)
    _check_shapes(system, gait)
    if not getattr(system, "may_be_singular", False):
        return
    T = gait.period
    if samples is None:
        per = 1 if gait.feature_time is None else math.ceil(T / gait.feature_time)
        samples = DENSE_SAMPLES if gait.feature_time is None else max(MIN_SAMPLES, SAMPLES_PER_FEATURE * per)
        samples = min(samples, _MAX_SAMPLES)
    else:
        samples = check_int(samples, "samples", minimum=16, maximum=_MAX_SAMPLES, what=" (times sampled per period)")
    s = np.linspace(0.0, 1.0, samples + 1)
    d = np.concatenate([system.singularity(gait(s[i:i + _CHUNK] * T)) for i in range(0, s.size, _CHUNK)])
    _scan(system, gait, s, d)
    a = np.abs(d)
    idx = np.nonzero((a[1:-1] <= a[:-2]) & (a[1:-1] <= a[2:]))[0] + 1
    # Refine only the minima that could plausibly hide a touching point (the 32 smallest).
    cand = idx[a[idx] < 1e-2]
    if cand.size:
        from scipy.optimize import minimize_scalar

        cand = cand[np.argsort(a[cand])[:32]]
        f = lambda x: abs(_det_at(system, gait, x))  # noqa: E731
        for i in cand:
            res = minimize_scalar(f, bounds=(s[i - 1], s[i + 1]), method="bounded", options={"xatol": 1e-14})
            if res.fun <= GAIT_SINGULAR_TOL:
                raise _singular_error(system, gait, res.x, "touches")


# ---------------------------------------------------------------------------------------------
# Reconstruction
# ---------------------------------------------------------------------------------------------
_G1 = 0.5 - math.sqrt(3) / 6
_G2 = 0.5 + math.sqrt(3) / 6
_MAGNUS_C = math.sqrt(3) / 12
#: Largest number of Magnus steps an integration may take.
MAX_STEPS = 2 ** 22


def _increments(system, gait, lo, hi, with_det=False):
    """Fourth-order Magnus steps Omega_k (k, 3) over normalized times [lo_k, hi_k] (t = s T).

    Works in normalized time s = t / T, where the body velocity is ``T xi = -A(r) (T r_dot)``,
    so neither tiny nor huge periods overflow. Also returns the Gauss nodes (2k,) and, when
    ``with_det``, the scaled det omega_xi at them (else None).
    """
    T = gait.period
    h = hi - lo
    sq = np.concatenate([lo + _G1 * h, lo + _G2 * h])
    r = gait(sq * T)
    xi = -matvec(system.connection(r), gait.velocity(sq * T) * T)
    finite = np.all(np.isfinite(xi), axis=-1)
    if not np.all(finite):
        bad = np.nonzero(~finite)[0]
        raise _singular_error(system, gait, float(sq[bad[np.argmin(sq[bad])]]), "reaches")
    k = lo.size
    x1, x2 = xi[:k], xi[k:]
    hh = h[:, None]
    om = hh / 2 * (x1 + x2) + _MAGNUS_C * hh ** 2 * position_group(system).bracket(x1, x2)
    return om, sq, (system.singularity(r) if with_det else None)


def _product(G, E):
    """g = E_0 E_1 ... E_{N-1} for elements E (N, 3) of the group G, by pairwise (tree) reduction."""
    while E.shape[0] > 1:
        if E.shape[0] % 2:
            E = np.vstack([E, G.identity((1,))])
        E = G.compose(E[0::2], E[1::2])
    return E[0]


def _cumulative(G, E):
    """Prefix products P_k = E_0 ... E_k (N, 3) in G, by a Hillis-Steele scan (log2 N vectorized steps)."""
    P = E.copy()
    d = 1
    while d < P.shape[0]:
        P[d:] = G.compose(P[:-d], P[d:])
        d *= 2
    return P


def _steps_for(gait, steps):
    """Number of steps: a multiple of the knot count so steps never straddle a spline knot."""
    if gait.knots is not None:
        k = len(gait.knots) - 1
        return k * max(1, -(-steps // k))
    return steps


def _adaptive(system, gait, rtol, with_det):
    """g(T) by Magnus steps, refined where step doubling shows the largest local errors.

    Each interval [lo, hi] is integrated by one step (E_full) and by two half steps (E_a E_b,
    which is kept and is about 16 times more accurate); e = |E_a E_b - E_full| estimates its
    local error. A local error delta moves g(T) by Ad of the remaining motion applied to delta,
    so ``est = (1 + 2 max |translation so far|) * sum(e) / 15`` bounds the global error to first
    order. While est > rtol * max(1, |g(T)|), every interval whose e exceeds its equal share of
    that budget is split in two (its halves become the children's one-step results, so a split
    costs four new steps). Refinement stops early when four rounds fail to halve the error (the
    integrand is then noisy at that level, as near a singular shape where A is computed with
    cancellation). Returns (g, est / scale, met).
    """
    G = position_group(system)
    n0 = _steps_for(gait, 512)
    edges = np.linspace(0.0, 1.0, n0 + 1)
    lo, hi = edges[:-1], edges[1:]
    mid = 0.5 * (lo + hi)
    om, sq, d = _increments(system, gait, np.concatenate([lo, lo, mid]), np.concatenate([hi, mid, hi]), with_det)
    E = G.exp(om)
    full, Ea, Eb = E[:n0], E[n0:2 * n0], E[2 * n0:]
    nodes_s, nodes_d = [sq], [d]
    used, history = 3 * n0, []
    while True:
        if with_det:
            _scan(system, gait, np.concatenate(nodes_s), np.concatenate(nodes_d))
        two = G.compose(Ea, Eb)
        e = np.max(np.abs(G.difference(two, full)), axis=-1)
        P = _cumulative(G, two)
        g = P[-1]
        scale = max(1.0, float(np.max(np.abs(g))))
        budget = 15 * rtol * scale / (1.0 + 2.0 * float(np.max(np.abs(P[:, :2]))))
        total = float(np.sum(e))
        history.append(total)
        if total <= budget or used >= MAX_STEPS:
            return g, total / budget * rtol, total <= budget
        if len(history) > 4 and min(history[-4:]) > 0.5 * min(history[:-4]):
            # four rounds of splitting without halving the error: the integrand itself is only
            # known to this accuracy (rounding in A near a singular shape), so stop here
            return g, total / budget * rtol, False
        split = np.nonzero((e > budget / e.size) & (hi - lo > 2.0 ** -44))[0]
        if split.size == 0 or used + 4 * split.size > MAX_STEPS:
            return g, total / budget * rtol, False
        # children [lo, mid] and [mid, hi] of every split interval; their one-step results are Ea, Eb
        m = 0.5 * (lo[split] + hi[split])
        c_lo, c_hi = np.concatenate([lo[split], m]), np.concatenate([m, hi[split]])
        c_full = np.concatenate([Ea[split], Eb[split]])
        c_mid = 0.5 * (c_lo + c_hi)
        om, sq, d = _increments(system, gait, np.concatenate([c_lo, c_mid]), np.concatenate([c_mid, c_hi]), with_det)
        used += om.shape[0]
        nodes_s.append(sq)
        nodes_d.append(d)
        Ec = G.exp(om)
        k = c_lo.size
        keep = np.ones(lo.size, bool)
        keep[split] = False
        lo, hi = np.concatenate([lo[keep], c_lo]), np.concatenate([hi[keep], c_hi])
        full = np.concatenate([full[keep], c_full])
        Ea, Eb = np.concatenate([Ea[keep], Ec[:k]]), np.concatenate([Eb[keep], Ec[k:]])
        order = np.argsort(lo, kind="stable")
        lo, hi, full, Ea, Eb = lo[order], hi[order], full[order], Ea[order], Eb[order]


def net_displacement(system: SystemLike, gait: GaitLike, *, steps: int | None = None, check: bool = True,
                     rtol: float = 1e-10) -> FloatArray:
    """Net displacement g(T) (3,) over one period of ``gait``, starting from g(0) = e.

    Integrates the reconstruction equation g_dot = T_e L_g xi with xi = -A(r) r_dot (3.10)
    by fourth-order Magnus steps ``g <- g exp(Omega)`` (each exactly in SE(2)). By default the
    steps adapt (step doubling, see ``_adaptive``; they crowd where the gait passes close to a
    singular shape and the body turns fast) until the estimated error is below ``rtol``
    relative to ``max(1, |g(T)|)``; if that cannot be reached (more than ``MAX_STEPS`` steps, or
    refinement stops reducing the error) the best result is returned with an
    :class:`AccuracyWarning` giving the estimate. ``steps=N`` takes
    N equal steps instead, with no error estimate.

    With ``check=True`` (the default) the gait must be closed (r(T) = r(0), else ValueError
    naming the gap) and must not meet a singular shape: :func:`check_gait` runs first, and the
    sign of det omega_xi is watched at every node of the integrator; either raises
    SingularShapeError. With ``check=False`` none of this is done: any shape path over [0, T] is
    integrated, and the only guarantee is that a node where the connection does not exist
    (NaN/inf) raises SingularShapeError; a path that crosses the singular set between nodes
    gives a finite number that means nothing.
    """
    gait = as_gait(gait)
    _check_shapes(system, gait)
    if not isinstance(check, (bool, np.bool_)):
        raise TypeError(f"check must be True or False; got {check!r}")
    if isinstance(rtol, bool):
        raise TypeError(f"rtol must be a number; got {rtol!r}")
    rtol = real_number(rtol, "rtol", " (a relative tolerance)")
    if not 1e-14 <= float(rtol) < 1:
        raise ValueError(f"rtol must be a relative tolerance in [1e-14, 1) (double precision cannot "
                         f"do better than ~1e-14); got {rtol!r}")
    if steps is not None:
        steps = check_int(steps, "steps", minimum=1, maximum=MAX_STEPS, what=" (equal Magnus steps per period)")
    with_det = bool(check) and bool(getattr(system, "may_be_singular", False))
    if check:
        gait.require_closed("net_displacement (pass check=False to integrate an open shape path over [0, T])")
        check_gait(system, gait)
    if steps is not None:
        edges = np.linspace(0.0, 1.0, _steps_for(gait, steps) + 1)
        om, sq, d = _increments(system, gait, edges[:-1], edges[1:], with_det)
        if with_det:
            _scan(system, gait, sq, d)
        G = position_group(system)
        return _product(G, G.exp(om))
    g, est, met = _adaptive(system, gait, float(rtol), with_det)
    if not met:
        warnings.warn(f"net_displacement did not meet rtol = {rtol:g}: estimated relative error {est:.2g} "
                      "(refining the steps stopped helping; is the gait very close to a singular shape?)",
                      AccuracyWarning, stacklevel=2)
    return g


@dataclass
class Trajectory:
    """Sampled reconstruction: times t (N,), positions g (N, 3) with g[0] = g0, shapes r (N, n)."""

    t: np.ndarray
    g: np.ndarray
    r: np.ndarray


def trajectory(system: SystemLike, gait: GaitLike, n_frames: int = 101, *, cycles: int = 1, g0: ArrayLike = (0.0, 0.0, 0.0),
               substeps: int | None = None, check: bool = True) -> Trajectory:
    """Position trajectory g(t) at ``n_frames`` equally spaced times over ``cycles`` periods.

    For animations: frames are spaced evenly in time from 0 to ``cycles * T`` inclusive. Between
    frames the same fourth-order Magnus integrator as :func:`net_displacement` takes ``substeps``
    equal steps (enough for ~4096 steps per period by default); there is no error control. An
    open shape path is fine for one cycle; repeating it (``cycles > 1``) needs a closed gait.
    ``check`` as for :func:`net_displacement` (singular shapes; closure is not required).
    """
    gait = as_gait(gait)
    _check_shapes(system, gait)
    n_frames = check_int(n_frames, "n_frames", minimum=2, maximum=10 ** 6, what=" (frames to return)")
    cycles = check_int(cycles, "cycles", minimum=1, maximum=10 ** 4, what=" (periods to integrate)")
    g0 = as_array(g0, "g0", (3,), what=" (the starting position (x, y, theta))")
    if g0.ndim != 1:
        raise ValueError(f"g0 must be one pose (3,); got shape {g0.shape}")
    intervals = n_frames - 1
    if substeps is None:
        substeps = max(1, -(-4096 * cycles // intervals))
    else:
        substeps = check_int(substeps, "substeps", minimum=1, maximum=10 ** 6, what=" (Magnus steps between frames)")
    if intervals * substeps > MAX_STEPS:
        raise ValueError(f"n_frames - 1 = {intervals} times substeps = {substeps} is more than "
                         f"{MAX_STEPS} integration steps; use fewer frames or substeps")
    if cycles > 1:
        gait.require_closed(f"trajectory with cycles = {cycles}")
    with_det = bool(check) and bool(getattr(system, "may_be_singular", False))
    if check:
        check_gait(system, gait)
    t = np.linspace(0.0, cycles * gait.period, n_frames)
    edges = np.linspace(0.0, float(cycles), intervals * substeps + 1)
    om, sq, d = _increments(system, gait, edges[:-1], edges[1:], with_det)
    if with_det:
        _scan(system, gait, sq, d)
    G = position_group(system)
    P = _cumulative(G, G.exp(om))[substeps - 1::substeps]
    g = np.vstack([g0[None], G.compose(g0, P)])
    return Trajectory(t=t, g=g, r=gait(t))


def displacement_until(system: SystemLike, gait: GaitLike, t: ArrayLike, *, steps: int | None = 256,
                       g0: ArrayLike = (0.0, 0.0, 0.0)) -> FloatArray:
    """Position g(t) (3,) after the first ``t`` time units of ``gait``, from g(0) = g0.

    Takes ``steps`` equal fourth-order Magnus steps over [0, t] (no error control; the gait
    need not be closed, and t may be any time in (0, T]). The shape path is checked for singular
    shapes at the integrator's nodes only. For the pacing square of fig. 3.1: the position after
    time t of a repaced gait equals that after time tau(t) of the original, (3.4).
    """
    gait = as_gait(gait)
    _check_shapes(system, gait)
    t = positive_number(t, "t")
    if t > gait.period * (1 + 1e-12):
        raise ValueError(f"t must be in (0, T] with T = {gait.period:g} the gait's period; got {t!r}")
    steps = check_int(steps, "steps", minimum=1, maximum=MAX_STEPS, what=" (equal Magnus steps)")
    g0 = as_array(g0, "g0", (3,), what=" (the starting position (x, y, theta))")
    part = Gait(gait, period=min(t, gait.period), velocity=gait.velocity, name=gait.name)
    edges = np.linspace(0.0, 1.0, steps + 1)
    om, sq, d = _increments(system, part, edges[:-1], edges[1:], bool(getattr(system, "may_be_singular", False)))
    if d is not None:
        _scan(system, part, sq, d)
    G = position_group(system)
    return G.compose(g0, _product(G, G.exp(om)))


def drive(system: SystemLike, r0: ArrayLike, r_dot: ArrayLike, duration: float, n_frames: int = 81) -> Trajectory:
    """Trajectory of ``system`` when its shape moves at the constant rate r_dot from r0 for ``duration``.

    The shape path is :func:`gm_core.systems.pacing.constant_rate_path` (open, not a gait); returns a
    :class:`Trajectory` starting at the identity; raises SingularShapeError if the shape path
    reaches a singular shape.
    """
    return trajectory(system, constant_rate_path(r0, r_dot, duration), n_frames, substeps=16)

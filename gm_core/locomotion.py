"""Kinematic locomotion (chapter 3): local connections, gaits and reconstruction (numpy/scipy only).

A symmetric linear-kinematic locomotor moves with body velocity ``xi = -A(r) r_dot`` (3.10),
where ``A`` is the *local connection*. This module holds the parts shared by every system in
:mod:`gm_core.systems`:

* :func:`connection_from_pfaffian`: ``A = omega_xi^-1 omega_r`` from a three-row Pfaffian
  ``0 = omega_xi xi + omega_r r_dot`` (3.11)-(3.17);
* :func:`connection_from_mass_matrix` and :func:`metric_from_jacobians`: the route for
  momentum-conserving systems, where the mass matrix has the block form (3.39)-(3.40);
* :class:`Gait`, :func:`circle_gait`: closed shape trajectories, from formulas or samples;
* :func:`net_displacement`, :func:`trajectory`: reconstruction of the position trajectory by
  integrating ``g_dot = T_e L_g xi`` with a fourth-order Magnus (Lie-group) integrator built on
  ``SE2.exp``, so every step stays exactly in SE(2).

Conventions: a shape ``r`` is an array ``(..., n)``; a connection is ``(..., 3, n)``; the body
velocity is ``(xi^x, xi^y, xi^theta)``. At a *singular* shape (``det omega_xi = 0``) the local
connection does not exist: ``connection`` returns NaN there quietly, and integrating a gait that
reaches such a shape raises :class:`gm_core.SingularShapeError`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._validate import SingularShapeError, as_array, check_positive
from .groups import SE2, matvec

__all__ = [
    "connection_from_pfaffian", "connection_from_mass_matrix", "metric_from_jacobians",
    "pfaffian_determinant", "body_velocity", "connection_curl", "Gait", "circle_gait", "as_gait", "check_gait",
    "net_displacement", "trajectory", "Trajectory", "se2_bracket", "SingularShapeError",
]

#: A Pfaffian whose body block has |det| below this fraction of its Hadamard bound is singular.
SINGULAR_TOL = 1e-12


# ---------------------------------------------------------------------------------------------
# Pfaffian and mass-matrix routes to the local connection
# ---------------------------------------------------------------------------------------------
def _cofactors3(m):
    """Adjugate (..., 3, 3) and determinant (...) of 3x3 matrices, elementwise (fast for big batches)."""
    a, b, c = m[..., 0, 0], m[..., 0, 1], m[..., 0, 2]
    d, e, f = m[..., 1, 0], m[..., 1, 1], m[..., 1, 2]
    g, h, i = m[..., 2, 0], m[..., 2, 1], m[..., 2, 2]
    adj = np.empty(m.shape)
    adj[..., 0, 0] = e * i - f * h
    adj[..., 0, 1] = c * h - b * i
    adj[..., 0, 2] = b * f - c * e
    adj[..., 1, 0] = f * g - d * i
    adj[..., 1, 1] = a * i - c * g
    adj[..., 1, 2] = c * d - a * f
    adj[..., 2, 0] = d * h - e * g
    adj[..., 2, 1] = b * g - a * h
    adj[..., 2, 2] = a * e - b * d
    det = a * adj[..., 0, 0] + b * adj[..., 1, 0] + c * adj[..., 2, 0]
    return adj, det


def _hadamard(m):
    return np.prod(np.sqrt(np.einsum("...ij,...ij->...i", m, m)), axis=-1)


def pfaffian_determinant(omega_xi):
    """Scaled determinant of the body block ``omega_xi (..., 3, 3)``: det / prod(row norms).

    The scaling (Hadamard's bound) makes the number dimensionless and in [-1, 1], so one
    tolerance decides "singular" for every system and every choice of units.
    """
    omega_xi = np.asarray(omega_xi, dtype=float)
    if omega_xi.shape[-2:] == (3, 3):
        det = _cofactors3(omega_xi)[1]
    else:
        det = np.linalg.det(omega_xi)
    norms = _hadamard(omega_xi)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(norms > 0, det / np.where(norms > 0, norms, 1.0), 0.0)


def connection_from_pfaffian(omega, *, n_position=3):
    """Local connection ``A = omega_xi^-1 omega_r`` (..., 3, n) from a Pfaffian (..., 3, 3 + n), (3.17).

    The Pfaffian's first three columns multiply the body velocity xi and the rest multiply the
    shape velocity, as in (3.13). With this A the reconstruction equation is ``xi = -A r_dot``
    (3.10). Where ``omega_xi`` is singular the result is NaN (no warning): see
    :func:`pfaffian_determinant`.
    """
    omega = as_array(omega, "omega", allow_nan=True)
    if omega.ndim < 2 or omega.shape[-2] != n_position or omega.shape[-1] <= n_position:
        raise ValueError(f"omega must have shape (..., {n_position}, {n_position} + n) with n >= 1 "
                         f"shape columns; got shape {omega.shape}")
    w_xi = omega[..., :n_position]
    w_r = omega[..., n_position:]
    if n_position == 3:
        adj, det = _cofactors3(w_xi)
        norms = _hadamard(w_xi)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            ok = np.abs(det) > SINGULAR_TOL * norms  # False for NaN too
            A = (adj @ w_r) / np.where(ok, det, np.nan)[..., None, None]
        return A
    bad = ~(np.abs(pfaffian_determinant(w_xi)) > SINGULAR_TOL)  # also catches NaN
    if np.any(bad):
        w_xi = np.where(bad[..., None, None], np.eye(n_position), w_xi)
    A = np.linalg.solve(w_xi, w_r)
    if np.any(bad):
        A[bad] = np.nan
    return A


def metric_from_jacobians(jacobians, inertias, *, rows=None):
    """Sum of ``J_i^T M_i J_i``: the (3 + n) x (3 + n) mass (or drag) matrix of a chain, (3.39), (3.47).

    ``jacobians``: sequence of ``(..., 3, 3 + n)`` link Jacobians mapping ``(xi, r_dot)`` to each
    link's body velocity; ``inertias``: matching sequence of ``(3, 3)`` link matrices (mass and
    inertia, or drag coefficients) written in each link's own frame. ``rows=k`` returns only the
    first k rows (k = 3 gives the momentum or force Pfaffian), which is cheaper.
    """
    J = np.concatenate([np.asarray(j, dtype=float) for j in jacobians], axis=-2)
    M = np.zeros((J.shape[-2], J.shape[-2]))
    k = 0
    for Mi in inertias:
        Mi = np.asarray(Mi, dtype=float)
        M[k:k + Mi.shape[0], k:k + Mi.shape[0]] = Mi
        k += Mi.shape[0]
    left = J if rows is None else J[..., :rows]
    if np.count_nonzero(M - np.diag(np.diag(M))) == 0:
        return np.swapaxes(left * np.diag(M)[:, None], -1, -2) @ J
    return np.swapaxes(left, -1, -2) @ (M @ J)


def connection_from_mass_matrix(M, *, n_position=3):
    """Local connection ``A = I^-1 (I A)`` (..., 3, n) read off a mass matrix (..., 3 + n, 3 + n), (3.40).

    For a system whose Lagrangian is its kinetic energy ``1/2 [xi r_dot] M [xi r_dot]^T`` (3.39),
    the body momentum is ``I xi + (I A) r_dot`` with ``I`` the top-left (locked) block, so zero
    momentum gives ``xi = -A r_dot``. The top three rows of ``M`` are therefore a Pfaffian.
    """
    M = as_array(M, "M", allow_nan=True)
    if M.ndim < 2 or M.shape[-1] != M.shape[-2] or M.shape[-1] <= n_position:
        raise ValueError(f"M must be a square (..., 3 + n, 3 + n) mass matrix; got shape {M.shape}")
    return connection_from_pfaffian(M[..., :n_position, :], n_position=n_position)


def body_velocity(system, r, r_dot):
    """Body velocity ``xi = -A(r) r_dot`` (..., 3) of ``system`` at shape r moving at r_dot, (3.10)."""
    n = system.n_shape
    r = as_array(r, "r", (n,), what=f" (a shape of {system.name})")
    r_dot = as_array(r_dot, "r_dot", (n,), what=f" (a shape velocity of {system.name})")
    return -matvec(system.connection(r), r_dot)


def connection_curl(system, r, h=1e-5):
    """Scalar curl (..., 3) of each connection row over a 2-D shape space, by central differences.

    For row i, ``d A_i2 / d alpha1 - d A_i1 / d alpha2``. It vanishes where the row is locally
    the gradient of a function of shape (an exact one-form, box on one-forms (3.xvii)); only then
    does a global contour plot of that row make sense.
    """
    r = as_array(r, "r", (2,), what=" (a point of a 2-D shape space)")
    e1, e2 = np.array([h, 0.0]), np.array([0.0, h])
    dA1 = (system.connection(r + e1) - system.connection(r - e1)) / (2 * h)
    dA2 = (system.connection(r + e2) - system.connection(r - e2)) / (2 * h)
    return dA1[..., :, 1] - dA2[..., :, 0]


def se2_bracket(xi1, xi2):
    """Lie bracket [xi1, xi2] (..., 3) of se(2) vectors; kept name for :meth:`SE2.bracket`."""
    return SE2.bracket(xi1, xi2)


# ---------------------------------------------------------------------------------------------
# Gaits
# ---------------------------------------------------------------------------------------------
# Eighth-order central difference weights for f'(t) with offsets 1..4.
_FD8 = np.array([4 / 5, -1 / 5, 4 / 105, -1 / 280])


class Gait:
    """A closed shape trajectory ``t -> r(t)`` of period T, with its shape velocity.

    Build one from a callable (``Gait(lambda t: ..., period=T)``), optionally with an exact
    ``velocity`` callable (otherwise an eighth-order central difference is used), or from a
    sampled closed path with :meth:`from_samples` (periodic cubic spline through the samples at
    equal time steps). Callables should accept an array of times ``(N,)`` and return ``(N, n)``;
    scalar-only callables also work, more slowly.
    """

    def __init__(self, shape, period=1.0, velocity=None, *, name="gait", knots=None):
        if not callable(shape):
            raise TypeError(f"shape must be a callable t -> r(t); got {type(shape).__name__} "
                            "(use Gait.from_samples for an array of points)")
        if velocity is not None and not callable(velocity):
            raise TypeError(f"velocity must be a callable t -> r_dot(t) or None; got {type(velocity).__name__}")
        self.period = float(check_positive(period, "period"))
        self._shape = shape
        self._velocity = velocity
        self.name = name
        self.knots = None if knots is None else np.asarray(knots, dtype=float)
        r0 = self._eval(self._shape, np.array([0.0]))
        self.n_shape = r0.shape[-1]

    @staticmethod
    def _eval(f, t):
        t = np.asarray(t, dtype=float)
        flat = t.reshape(-1)
        try:
            out = np.asarray(f(flat), dtype=float)
        except Exception:  # noqa: BLE001 - scalar-only callables
            out = None
        if out is None or out.ndim != 2 or out.shape[0] != flat.size:
            out = np.array([np.atleast_1d(np.asarray(f(float(s)), dtype=float)) for s in flat])
        if not np.all(np.isfinite(out)):
            raise ValueError("the gait returned NaN or infinite shapes; every shape must be finite")
        return out.reshape(t.shape + out.shape[-1:])

    def __call__(self, t):
        """Shape r(t), ``(..., n)`` for times ``(...)``."""
        return self._eval(self._shape, t)

    def velocity(self, t):
        """Shape velocity r_dot(t), ``(..., n)``: exact if given, else an 8th-order central difference."""
        if self._velocity is not None:
            return self._eval(self._velocity, t)
        t = np.asarray(t, dtype=float)
        h = 1e-3 * self.period
        out = 0.0
        for k, w in enumerate(_FD8, start=1):
            out = out + w * (self(t + k * h) - self(t - k * h))
        return out / h

    @classmethod
    def from_samples(cls, points, period=1.0, *, name="sampled gait"):
        """A gait through the closed path ``points (K, n)`` visited at equal time steps.

        The path is closed automatically (a last point equal to the first is dropped) and
        interpolated by a periodic cubic spline, whose derivative gives the shape velocity.
        """
        from scipy.interpolate import CubicSpline

        pts = as_array(points, "points")
        if pts.ndim != 2 or pts.shape[0] < 3 or pts.shape[1] < 1:
            raise ValueError(f"points must have shape (K, n) with K >= 3 samples of a closed path; "
                             f"got shape {pts.shape}")
        if np.allclose(pts[0], pts[-1]):
            pts = pts[:-1]
        if pts.shape[0] < 3:
            raise ValueError("points must contain at least 3 distinct samples of a closed path")
        T = float(check_positive(period, "period"))
        K = pts.shape[0]
        tk = np.linspace(0.0, T, K + 1)
        spline = CubicSpline(tk, np.vstack([pts, pts[:1]]), bc_type="periodic", axis=0)
        d = spline.derivative()
        return cls(lambda t: spline(np.mod(t, T)), T, lambda t: d(np.mod(t, T)), name=name,
                   knots=tk)

    def reparameterized(self, tau, tau_dot=None, *, name=None):
        """The same path with a new pacing: ``r'(t) = r(tau(t))``, for a map tau of [0, T] onto itself.

        ``tau`` must be increasing with tau(0) = 0 and tau(T) = T; ``tau_dot`` is its derivative
        (optional). This is the time reparameterization of (3.3).
        """
        if not callable(tau):
            raise TypeError("tau must be a callable t -> tau(t)")
        T = self.period
        if not (abs(float(tau(0.0))) < 1e-12 and abs(float(tau(T)) - T) < 1e-12 * max(T, 1.0)):
            raise ValueError("tau must map [0, T] onto itself with tau(0) = 0 and tau(T) = T")
        base = self
        if tau_dot is None:
            vel = None
        else:
            def vel(t):
                t = np.asarray(t, dtype=float)
                return base.velocity(tau(t)) * np.asarray(tau_dot(t), dtype=float)[..., None]
        return Gait(lambda t: base(tau(np.asarray(t, dtype=float))), T, vel,
                    name=name or f"{self.name} (repaced)")

    def __repr__(self):
        return f"Gait({self.name!r}, period={self.period:g}, n_shape={self.n_shape})"


def circle_gait(amplitude, center=(0.0, 0.0), period=1.0):
    """Circular gait ``r(t) = c + R (cos 2 pi t / T, sin 2 pi t / T)`` in a 2-D shape space.

    ``amplitude`` is the radius R (a positive number, or two positive semi-axes for an ellipse);
    ``center`` is c; the circle is traversed counterclockwise once per ``period``.
    """
    R = check_positive(amplitude, "amplitude")
    if R.ndim > 1 or R.size not in (1, 2):
        raise ValueError(f"amplitude must be a number or a pair of semi-axes; got shape {R.shape}")
    R = np.broadcast_to(R, (2,)).astype(float)
    c = as_array(center, "center", (2,), what=" (the gait's centre in shape space)")
    if c.ndim != 1:
        raise ValueError(f"center must have shape (2,); got shape {c.shape}")
    T = float(check_positive(period, "period"))
    w = 2 * np.pi / T

    def shape(t):
        t = np.asarray(t, dtype=float)
        return c + R * np.stack([np.cos(w * t), np.sin(w * t)], -1)

    def vel(t):
        t = np.asarray(t, dtype=float)
        return w * R * np.stack([-np.sin(w * t), np.cos(w * t)], -1)

    g = Gait(shape, T, vel, name=f"circle R={R[0]:g} about ({c[0]:g}, {c[1]:g})")
    g.amplitude, g.center = R, c
    return g


def as_gait(gait, period=1.0):
    """A :class:`Gait` from a Gait, a callable ``t -> r`` (period ``period``) or samples ``(K, n)``."""
    if isinstance(gait, Gait):
        return gait
    if callable(gait):
        return Gait(gait, period)
    if gait is None or isinstance(gait, (str, bytes)):
        raise TypeError(f"gait must be a Gait, a callable t -> r(t) or an array of shapes; got {gait!r}")
    return Gait.from_samples(gait, period)


# ---------------------------------------------------------------------------------------------
# Singular shapes along a gait
# ---------------------------------------------------------------------------------------------
GAIT_SINGULAR_TOL = 1e-9


def check_gait(system, gait, *, samples=4096):
    """Raise SingularShapeError if the gait crosses or touches a singular shape of ``system``.

    Samples ``system.singularity(r(t))`` (the scaled det omega_xi, never zero at regular shapes),
    looks for sign changes and for near-zero local minima of its magnitude (refined with a
    bounded scalar minimisation), and names the time and shape where it happens.
    """
    gait = as_gait(gait)
    if getattr(system, "singularity", None) is None or not system.may_be_singular:
        return
    T = gait.period
    t = np.linspace(0.0, T, samples + 1)
    d = system.singularity(gait(t))

    def fail(ti, how):
        r = gait(np.array([ti]))[0]
        raise SingularShapeError(
            f"the gait {how} a singular shape of {system.name} at t = {ti:.6g} (of period {T:g}), "
            f"r = ({', '.join(f'{v:.6g}' for v in r)}): there det(omega_xi) = 0 and the local "
            f"connection does not exist ({system.singular_description})")

    small = np.abs(d) <= GAIT_SINGULAR_TOL
    if np.any(small):
        fail(t[np.argmax(small)], "reaches")
    cross = np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0]
    if cross.size:
        from scipy.optimize import brentq

        i = cross[0]
        f = lambda s: float(system.singularity(gait(np.array([s])))[0])  # noqa: E731
        fail(brentq(f, t[i], t[i + 1], xtol=1e-14), "crosses")
    a = np.abs(d)
    idx = np.nonzero((a[1:-1] <= a[:-2]) & (a[1:-1] <= a[2:]))[0] + 1
    # Refine only the minima that could plausibly hide a touching point.
    cand = idx[a[idx] < 1e-2]
    if cand.size:
        from scipy.optimize import minimize_scalar

        f = lambda s: abs(float(system.singularity(gait(np.array([s])))[0]))  # noqa: E731
        for i in cand:
            res = minimize_scalar(f, bounds=(t[i - 1], t[i + 1]), method="bounded",
                                  options={"xatol": 1e-13 * max(T, 1.0)})
            if res.fun <= GAIT_SINGULAR_TOL:
                fail(res.x, "touches")


# ---------------------------------------------------------------------------------------------
# Reconstruction
# ---------------------------------------------------------------------------------------------
_G1 = 0.5 - math.sqrt(3) / 6
_G2 = 0.5 + math.sqrt(3) / 6
_MAGNUS_C = math.sqrt(3) / 12


def _increments(system, gait, t0, t1, steps):
    """Fourth-order Magnus steps Omega_k (steps, 3) on [t0, t1] for g_dot = g xi^ (left-invariant)."""
    edges = np.linspace(t0, t1, steps + 1)
    h = np.diff(edges)
    tq = np.concatenate([edges[:-1] + _G1 * h, edges[:-1] + _G2 * h])
    r = gait(tq)
    rd = gait.velocity(tq)
    xi = -matvec(system.connection(r), rd)
    if not np.all(np.isfinite(xi)):
        bad = np.nonzero(~np.all(np.isfinite(xi), axis=-1))[0][0]
        rb = r[bad]
        raise SingularShapeError(
            f"the gait reaches a singular shape of {system.name} near t = {tq[bad]:.6g}, "
            f"r = ({', '.join(f'{v:.6g}' for v in rb)}): the local connection does not exist there")
    x1, x2 = xi[:steps], xi[steps:]
    hh = h[:, None]
    return hh / 2 * (x1 + x2) + _MAGNUS_C * hh ** 2 * se2_bracket(x1, x2)


def _product(E):
    """g = E_0 E_1 ... E_{N-1} for SE(2) elements E (N, 3), by pairwise (tree) reduction."""
    while E.shape[0] > 1:
        if E.shape[0] % 2:
            E = np.vstack([E, np.zeros((1, 3))])
        E = SE2.compose(E[0::2], E[1::2])
    return E[0]


def _cumulative(E):
    """Prefix products P_k = E_0 ... E_k (N, 3), by a Hillis-Steele scan (log2 N vectorized steps)."""
    P = E.copy()
    d = 1
    while d < P.shape[0]:
        P[d:] = SE2.compose(P[:-d], P[d:])
        d *= 2
    return P


def _steps_for(gait, steps):
    """Number of steps: a multiple of the knot count so steps never straddle a spline knot."""
    if gait.knots is not None:
        k = len(gait.knots) - 1
        return k * max(1, -(-steps // k))
    return steps


def net_displacement(system, gait, *, steps=None, check=True, rtol=1e-10):
    """Net displacement g(T) (3,) over one period of ``gait``, starting from g(0) = e.

    Integrates the reconstruction equation g_dot = T_e L_g xi with xi = -A(r) r_dot (3.10)
    by fourth-order Magnus steps ``g <- g exp(Omega)`` (each exactly in SE(2)); the number of
    steps doubles from 1024 until two successive results agree to ``rtol`` (relative to the
    size of the motion), which in practice gives 1e-10 or better. Raises SingularShapeError
    when the gait crosses or touches a singular shape (see :func:`check_gait`).
    """
    gait = as_gait(gait)
    _check_system_gait(system, gait)
    if check:
        check_gait(system, gait)
    T = gait.period
    if steps is not None:
        n = _steps_for(gait, int(steps))
        return _product(SE2.exp(_increments(system, gait, 0.0, T, n)))
    n = _steps_for(gait, 1024)
    prev = _product(SE2.exp(_increments(system, gait, 0.0, T, n)))
    while True:
        n *= 2
        cur = _product(SE2.exp(_increments(system, gait, 0.0, T, n)))
        scale = max(1.0, float(np.max(np.abs(cur))))
        err = float(np.max(np.abs(cur - prev)))
        if err <= rtol * scale or n >= 2 ** 18:
            return cur
        prev = cur


@dataclass
class Trajectory:
    """Sampled reconstruction: times t (N,), positions g (N, 3) with g[0] = g0, shapes r (N, n)."""

    t: np.ndarray
    g: np.ndarray
    r: np.ndarray


def trajectory(system, gait, n_frames=101, *, cycles=1, g0=(0.0, 0.0, 0.0), substeps=None, check=True):
    """Position trajectory g(t) at ``n_frames`` equally spaced times over ``cycles`` periods.

    For animations: frames are spaced evenly in time from 0 to ``cycles * T`` inclusive. Between
    frames the same fourth-order Magnus integrator as :func:`net_displacement` takes ``substeps``
    steps (enough for ~4096 steps per period by default).
    """
    gait = as_gait(gait)
    _check_system_gait(system, gait)
    if isinstance(n_frames, bool) or int(n_frames) != n_frames or n_frames < 2:
        raise ValueError(f"n_frames must be an integer >= 2; got {n_frames!r}")
    if isinstance(cycles, bool) or int(cycles) != cycles or cycles < 1:
        raise ValueError(f"cycles must be a positive integer; got {cycles!r}")
    g0 = as_array(g0, "g0", (3,), what=" (the starting position (x, y, theta))")
    if check:
        check_gait(system, gait)
    n_frames, cycles = int(n_frames), int(cycles)
    T = gait.period
    t = np.linspace(0.0, cycles * T, n_frames)
    intervals = n_frames - 1
    if substeps is None:
        substeps = max(1, -(-4096 * cycles // intervals))
    E = SE2.exp(_increments(system, gait, 0.0, cycles * T, intervals * int(substeps)))
    P = _cumulative(E)[int(substeps) - 1::int(substeps)]
    g = np.vstack([g0[None], SE2.compose(g0, P)])
    return Trajectory(t=t, g=g, r=gait(t))


def _check_system_gait(system, gait):
    n = getattr(system, "n_shape", None)
    if n is None or not hasattr(system, "connection"):
        raise TypeError(f"system must be a locomotion system with connection(r); got {system!r}")
    if gait.n_shape != n:
        raise ValueError(f"gait has {gait.n_shape} shape variables but {system.name} has {n}")


def __getattr__(name):
    # The systems are importable from here too: ``from gm_core.locomotion import KinematicSnake``.
    from . import systems

    if name in systems.__all__:
        return getattr(systems, name)
    raise AttributeError(f"module 'gm_core.locomotion' has no attribute {name!r}")

"""Constraint curvature, the Stokes estimate and the body-velocity integral (numpy/scipy only).

Convention (book (3.10)): ``xi = -A(r) r_dot``, A of shape (..., 3, 2) with columns
``A_1, A_2`` (se(2) vectors). Over one cycle of a small gait the net displacement is, to
leading order (Hatton & Choset 2011, 2015),

    log g(T) ~ integral over the enclosed area of  D(-A) = -(d_1 A_2 - d_2 A_1) + [A_1, A_2],

the first term from Stokes' theorem applied to the body-velocity integral ``-oint A dr`` and the
second from the second-order Magnus term of ``g_dot = g xi``. ``[.,.]`` is the group's
``SE2.bracket``. The theta row is exact (SE(2)'s rotation part is abelian); the (x, y) rows
have an error of third order in the size of the gait.

Derivatives of A: the system's ``connection_derivative`` method (exact for the systems whose
connection has a closed form, otherwise second-order central differences with a step near the
optimum eps**(1/3), tested against exact derivatives in tests/test_geometry.py). For more than
two shape variables the curvature is a 2-form with a component per pair of shape directions;
Stokes estimates are for gaits in a 2-D slice (:func:`gm_core.systems.shape_slice`).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups import matvec
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.gaits import Gait, GaitLike, as_gait
from gm_core.systems.motion import (
    FD_STEP,
    check_gait,
    curvature_form,
    exterior_derivative,
    fd_connection_derivative,
    position_group,
    trusted_dimension,
)
from gm_core.validation import FloatArray, SingularShapeError, as_array, check_int, positive_number

__all__ = ["constraint_curvature", "connection_derivative", "connection_curl", "stokes_estimate",
           "body_velocity_integral", "closed_gait", "require_planar"]


def require_planar(system: LocomotionSystem, what: str = "curvature maps and Stokes estimates") -> LocomotionSystem:
    """``system`` after checking it has a 2-D shape space (ValueError pointing to :func:`shape_slice` if not)."""
    n = trusted_dimension(system)
    if n != 2:
        raise ValueError(f"system must have a 2-D shape space for {what}; {getattr(system, 'name', system)} has "
                         f"n_shape = {n}: take a 2-D slice with gm_core.systems.shape_slice(system, through, axes)")
    return system


def connection_derivative(system: LocomotionSystem, r: ArrayLike, *, method: str = "auto",
                          h: float | None = None) -> tuple[FloatArray, FloatArray]:
    """Connection and its shape derivative: ``(A (..., 3, n), dA (..., 3, n, n))``, ``dA[..., i, j, k] = d A_ij / d r_k``.

    ``method="auto"`` asks the system (its ``connection_derivative``: a closed form for the
    differential drive, Ackerman car and kinematic snake, else central differences);
    ``"fd"`` forces central differences (:func:`gm_core.systems.motion.fd_connection_derivative`) with
    relative step ``h`` (default :data:`gm_core.systems.motion.FD_STEP`). The one place that chooses.
    """
    n = trusted_dimension(system)
    r = as_array(r, "r", (n,), what=f" (a shape of {system.name})")
    if method not in ("auto", "fd"):
        raise ValueError(f"method must be 'auto' or 'fd'; got {method!r}")
    if h is not None:
        h = positive_number(h, "h")
        if method == "auto":
            method = "fd"
    if method == "auto" and isinstance(system, LocomotionSystem):
        return system.connection_derivative(r)
    return fd_connection_derivative(system, r, FD_STEP if h is None else h)


def connection_curl(system: LocomotionSystem, r: ArrayLike, h: float | None = None) -> FloatArray:
    """Scalar curl (..., 3) of each connection row over a 2-D shape space.

    For row i, ``d A_i2 / d alpha1 - d A_i1 / d alpha2``, from :func:`connection_derivative`
    (the system's closed form where there is one), or central differences with relative step
    ``h`` if given. It vanishes where the row is locally the gradient of a function of shape (an
    exact one-form, box on one-forms (3.xvii)); only then does a global contour plot of that row
    make sense.
    """
    if trusted_dimension(system) != 2:
        raise ValueError(f"system must have a 2-D shape space for a scalar curl; {system.name} has "
                         f"{system.n_shape} shape variables")
    r = as_array(r, "r", (2,), what=" (a point of a 2-D shape space)")
    dA = connection_derivative(system, r, h=h)[1]
    return exterior_derivative(dA)[..., 0, 1]


def constraint_curvature(system: LocomotionSystem, r: ArrayLike, *, method: str = "auto",
                         pair: tuple[int, int] | None = None) -> FloatArray:
    """Constraint curvature D(-A) at shapes r: ``F_ij = -(d_i A_j - d_j A_i) + [A_i, A_j]``.

    For a 2-D shape space the one component F_12, (..., 3); for n shape variables the 2-form
    (..., 3, n, n) (antisymmetric: one se(2) component per pair of shape directions), or with
    ``pair=(i, j)`` (0-based) that component alone, (..., 3). Its integral over the area a
    counter-clockwise gait encloses in a 2-D slice is the leading-order net displacement
    (Hatton & Choset 2015); rows are (x, y, theta) in the body frame. NaN at singular shapes.
    ``method="auto"`` asks the system (a frame change acts by Ad_{beta^-1}, gauge covariance);
    ``"fd"`` differentiates the connection by central differences.
    """
    n = trusted_dimension(system)
    r = as_array(r, "r", (n,), what=f" (a shape of {system.name})")
    if method not in ("auto", "fd"):
        raise ValueError(f"method must be 'auto' or 'fd'; got {method!r}")
    if pair is not None:
        if np.ndim(pair) != 1 or len(pair) != 2:
            raise ValueError(f"pair must be two shape indices (i, j); got {pair!r}")
        i, j = (check_int(k, "pair", minimum=0, maximum=n - 1, what=f" (shape indices 0..{n - 1})") for k in pair)
    if method == "auto" and isinstance(system, LocomotionSystem):
        F = system.constraint_curvature(r)
        if n == 2:
            F = F[..., None, None] * np.array([[0.0, 1.0], [-1.0, 0.0]])
    else:
        F = curvature_form(*fd_connection_derivative(system, r), group=position_group(system))
    if pair is not None:
        return F[..., i, j]
    return F[..., 0, 1] if n == 2 else F


# ---------------------------------------------------------------------------------------------
# Area and loop integrals over a gait
# ---------------------------------------------------------------------------------------------
def _centroid(p):
    """Area centroid of the closed polygon p (N, 2) (vertex mean if the area is ~0)."""
    x, y = p[:, 0], p[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = cross.sum() / 2
    scale = np.ptp(p, axis=0).prod()
    if abs(area) <= 1e-9 * max(scale, 1e-300):
        return p.mean(axis=0)
    return np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6 * area)


def _stokes_once(system, gait, nt, ns, center, method):
    T = gait.period
    t = np.arange(nt) * (T / nt)
    p = gait(t)
    v = gait.velocity(t)
    s, w = np.polynomial.legendre.leggauss(ns)
    s, w = (s + 1) / 2, w / 2
    q = center + s[:, None, None] * (p - center)[None]  # (ns, nt, 2)
    F = constraint_curvature(system, q, method=method)  # (ns, nt, 3)
    if not np.all(np.isfinite(F)):
        i, j = np.argwhere(~np.isfinite(F).all(-1))[0]
        raise SingularShapeError(
            f"the curvature of {system.name} is singular at r = ({q[i, j, 0]:.6g}, {q[i, j, 1]:.6g}) "
            "inside the gait: the area integral is undefined there")
    radial = np.einsum("s,s,sti->ti", w, s, F)  # int_0^1 F(c + s (p - c)) s ds
    d = p - center
    cross = d[:, 0] * v[:, 1] - d[:, 1] * v[:, 0]
    return (radial * cross[:, None]).sum(axis=0) * (T / nt)


def _check_rtol(rtol):
    r = positive_number(rtol, "rtol", what=" (a relative tolerance)")
    if not 1e-15 <= r < 1:
        raise ValueError(f"rtol must be a relative tolerance in [1e-15, 1); got {rtol!r}")
    return r


def stokes_estimate(system: LocomotionSystem, gait: GaitLike, *, rtol: float = 1e-11, method: str = "auto",
                    check: bool = True, samples: int | None = None) -> FloatArray:
    """Area integral (3,) of the constraint curvature over the region the gait encloses.

    The region is counted with its winding number, so a clockwise gait gives the negative
    (it moves the other way) and a non-convex simple gait is fine. Computed with the radial
    (Poincare-lemma) primitive of the curvature about the gait's area centroid c:
    ``oint (int_0^1 F(c + s (r - c)) s ds) (r - c) x r_dot dt``, trapezoidal in t (periodic)
    and Gauss-Legendre in s, refined until two results agree to ``rtol``. The theta row
    equals the exact net rotation; (x, y) are the leading-order estimate of g(T).

    ``samples=(nt, ns)`` evaluates the same formula once at that fixed resolution instead of
    refining (for interactive use: ``(64, 12)`` costs a few ms and, for gaits with a few Fourier
    harmonics, agrees with the refined value to 1e-7 or better; tests/test_geometry.py checks it).
    """
    require_planar(system)
    gait = closed_gait(gait, system)
    rtol = _check_rtol(rtol)
    if check:
        check_gait(system, gait)
    center = _centroid(gait(np.linspace(0, gait.period, 1024, endpoint=False)))
    if samples is not None:
        nt, ns = _fixed_samples(samples, 2)
        return _stokes_once(system, gait, nt, ns, center, method)
    nt, ns = 256, 16
    prev = _stokes_once(system, gait, nt, ns, center, method)
    while True:
        nt, ns = 2 * nt, ns + 8
        cur = _stokes_once(system, gait, nt, ns, center, method)
        if np.max(np.abs(cur - prev)) <= rtol * max(1.0, np.max(np.abs(cur))) or nt >= 2 ** 12:
            return cur
        prev = cur


def body_velocity_integral(system: LocomotionSystem, gait: GaitLike, *, rtol: float = 1e-12, check: bool = True,
                           samples: int | None = None) -> FloatArray:
    """The naive estimate (3,): ``int_0^T xi dt = -oint A(r) dr`` (ignores the Lie bracket).

    Trapezoidal rule over the period (spectrally accurate for smooth periodic gaits), doubled
    until two results agree to ``rtol``; ``samples=n`` uses n equal time steps once instead.
    """
    trusted_dimension(system)
    gait = closed_gait(gait, system)
    if check:
        check_gait(system, gait)
    rtol = _check_rtol(rtol)
    T = gait.period

    def once(n):
        t = np.arange(n) * (T / n)
        xi = -matvec(system.connection(gait(t)), gait.velocity(t))
        if not np.all(np.isfinite(xi)):
            raise SingularShapeError(f"the gait reaches a singular shape of {system.name}")
        return xi.sum(axis=0) * (T / n)

    if samples is not None:
        return once(_fixed_samples(samples, 1)[0])
    n = 512
    prev = once(n)
    while True:
        n *= 2
        cur = once(n)
        if np.max(np.abs(cur - prev)) <= rtol * max(1.0, np.max(np.abs(cur))) or n >= 2 ** 17:
            return cur
        prev = cur


def _fixed_samples(samples, count):
    """``samples`` as ``count`` integers >= 2 (one int is accepted for count 1)."""
    vals = np.atleast_1d(np.asarray(samples, dtype=object))
    if vals.shape != (count,) or not all(isinstance(v, (int, np.integer)) and not isinstance(v, bool)
                                         and v >= 2 for v in vals):
        want = "an integer >= 2" if count == 1 else f"{count} integers >= 2, e.g. (64, 8)"
        raise ValueError(f"samples must be {want}; got {samples!r}")
    return [int(v) for v in vals]


def closed_gait(gait: GaitLike, system: LocomotionSystem | None = None, name: str = "gait") -> Gait:
    """``gait`` as a :class:`Gait` after checking it is closed (r(T) = r(0)) and matches ``system``."""
    gait = as_gait(gait)
    p0, p1 = gait(np.array([0.0, gait.period]))
    if np.max(np.abs(p1 - p0)) > 1e-8 * max(1.0, float(np.max(np.abs(p0)))):
        raise ValueError(f"{name} is not closed: r(0) = {np.round(p0, 6).tolist()} but r(T) = "
                         f"{np.round(p1, 6).tolist()} (T = {gait.period:g}); a gait must return to its start")
    if system is not None:
        _match(system, gait)
    return gait


def _match(system, gait):
    if gait.n_shape != system.n_shape:
        raise ValueError(f"gait has {gait.n_shape} shape variables but {system.name} has {system.n_shape}")

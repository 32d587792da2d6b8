"""Routes to the local connection of chapter 3: from a Pfaffian or from a mass matrix (numpy only).

* :func:`connection_from_pfaffian`: ``A = omega_xi^-1 omega_r`` from a three-row Pfaffian
  ``0 = omega_xi xi + omega_r r_dot`` (3.11)-(3.17); NaN (quietly) where omega_xi is singular;
* :func:`pfaffian_determinant`: the scaled det omega_xi that decides "singular";
* :func:`metric_from_jacobians` and :func:`connection_from_mass_matrix`: the route for systems
  defined by a balance over links (momentum, drag), whose matrix has the block form (3.39)-(3.40).

:mod:`gm_core.systems.motion` re-exports every name here.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.validation import FloatArray, as_array, check_int

__all__ = ["SINGULAR_TOL", "pfaffian_determinant", "connection_from_pfaffian", "metric_from_jacobians",
           "connection_from_mass_matrix", "shape_space_metric"]

#: A Pfaffian whose body block has |det| below this fraction of its Hadamard bound is singular.
SINGULAR_TOL = 1e-12


def _cofactors3(m):
    """Adjugate (..., 3, 3) and determinant (...) of 3x3 matrices, elementwise (fast for big batches;
    the adjugate keeps the memory layout of ``m``, so batch-last input gives contiguous rows)."""
    a, b, c = m[..., 0, 0], m[..., 0, 1], m[..., 0, 2]
    d, e, f = m[..., 1, 0], m[..., 1, 1], m[..., 1, 2]
    g, h, i = m[..., 2, 0], m[..., 2, 1], m[..., 2, 2]
    adj = np.empty_like(m, dtype=float)
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


def pfaffian_determinant(omega_xi: ArrayLike) -> FloatArray:
    """Scaled determinant of the body block ``omega_xi (..., 3, 3)``: det / prod(row norms).

    The scaling (Hadamard's bound) makes the number dimensionless and in [-1, 1], so one
    tolerance decides "singular" for every system and every choice of units.
    """
    omega_xi = as_array(omega_xi, "omega_xi", what=" (square body blocks (..., k, k) of Pfaffians)",
                        allow_nan=True)
    if omega_xi.ndim < 2 or omega_xi.shape[-1] != omega_xi.shape[-2] or omega_xi.shape[-1] == 0:
        raise ValueError(f"omega_xi must be square matrices (..., k, k), the body block of a Pfaffian; "
                         f"got shape {omega_xi.shape}")
    # the ratio det / prod(row norms) does not change when a row is scaled: scale each row by its
    # largest entry first, so that entries near 1e300 do not overflow
    with np.errstate(invalid="ignore", divide="ignore"):                     # NaN in, NaN out
        big = np.max(np.abs(omega_xi), axis=-1, keepdims=True)
        omega_xi = omega_xi / np.where(big > 0, big, 1.0)
        det = _cofactors3(omega_xi)[1] if omega_xi.shape[-2:] == (3, 3) else np.linalg.det(omega_xi)
        norms = _hadamard(omega_xi)
        # a zero row is singular (0); a NaN entry stays NaN (the caller counts it as singular)
        return np.where(norms > 0, det / np.where(norms > 0, norms, 1.0), np.where(np.isnan(norms), np.nan, 0.0))


def connection_from_pfaffian(omega: ArrayLike, *, n_position: int = 3) -> FloatArray:
    """Local connection ``A = omega_xi^-1 omega_r`` (..., 3, n) from a Pfaffian (..., 3, 3 + n), (3.17).

    The Pfaffian's first three columns multiply the body velocity xi and the rest multiply the
    shape velocity, as in (3.13). With this A the reconstruction equation is ``xi = -A r_dot``
    (3.10). Where ``omega_xi`` is singular the result is NaN (no warning): see
    :func:`pfaffian_determinant`.
    """
    n_position = check_int(n_position, "n_position", minimum=1, maximum=64, what=" (rows of the Pfaffian)")
    omega = as_array(omega, "omega", allow_nan=True)
    if omega.ndim < 2 or omega.shape[-2] != n_position or omega.shape[-1] <= n_position:
        raise ValueError(f"omega must have shape (..., {n_position}, {n_position} + n) with n >= 1 "
                         f"shape columns; got shape {omega.shape}")
    w_xi = omega[..., :n_position]
    w_r = omega[..., n_position:]
    if n_position == 3:
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):   # NaN in, NaN out
            adj, det = _cofactors3(w_xi)
            norms = _hadamard(w_xi)
            ok = np.abs(det) > SINGULAR_TOL * norms  # False for NaN too
            A = (adj @ w_r) / np.where(ok, det, np.nan)[..., None, None]
        return A
    bad = ~(np.abs(pfaffian_determinant(w_xi)) > SINGULAR_TOL)  # also catches NaN
    if np.any(bad):
        w_xi = np.where(bad[..., None, None], np.eye(n_position), w_xi)
    A = np.linalg.solve(w_xi, w_r)
    if np.any(bad):
        A[bad] = np.nan
    return np.asarray(A, dtype=float)


def metric_from_jacobians(jacobians: ArrayLike, inertias: ArrayLike, *,
                          rows: tuple[int, ...] | None = None) -> FloatArray:
    """Sum of ``J_i^T M_i J_i``: the (3 + n) x (3 + n) mass (or drag) matrix of a chain, (3.39), (3.47).

    ``jacobians``: sequence of ``(..., 3, 3 + n)`` link Jacobians mapping ``(xi, r_dot)`` to each
    link's body velocity; ``inertias``: matching sequence of ``(3, 3)`` link matrices (mass and
    inertia, or drag coefficients) written in each link's own frame. ``rows=k`` returns only the
    first k rows (k = 3 gives the momentum or force Pfaffian), which is cheaper.
    """
    if isinstance(jacobians, np.ndarray) or not isinstance(jacobians, (list, tuple)) or not jacobians:
        raise TypeError(f"jacobians must be a non-empty list or tuple of link Jacobians (..., 3, 3 + n); "
                        f"got {type(jacobians).__name__}")
    if isinstance(inertias, np.ndarray) or not isinstance(inertias, (list, tuple)) or len(inertias) != len(jacobians):
        raise TypeError(f"inertias must be a list or tuple of {len(jacobians)} square link matrices, one per "
                        f"Jacobian; got {type(inertias).__name__}"
                        + (f" of length {len(inertias)}" if isinstance(inertias, (list, tuple)) else ""))
    Js, Ms = [], []
    for i, (j, Mi) in enumerate(zip(jacobians, inertias)):
        Mi = as_array(Mi, f"inertias[{i}]")
        if Mi.ndim != 2 or Mi.shape[0] != Mi.shape[1]:
            raise ValueError(f"inertias[{i}] must be a square (k, k) link matrix; got shape {Mi.shape}")
        j = as_array(j, f"jacobians[{i}]", allow_nan=True)
        if j.ndim < 2 or j.shape[-2] != Mi.shape[0] or j.shape[-1] != np.shape(jacobians[0])[-1]:
            raise ValueError(f"jacobians[{i}] must have shape (..., {Mi.shape[0]}, m) with the same m for every "
                             f"link (rows matching inertias[{i}]); got shape {j.shape}")
        Js.append(j)
        Ms.append(Mi)
    try:
        batch = np.broadcast_shapes(*(j.shape[:-2] for j in Js))
    except ValueError:
        raise ValueError(f"jacobians have incompatible batch shapes {[j.shape[:-2] for j in Js]}") from None
    J = np.concatenate([np.broadcast_to(j, batch + j.shape[-2:]) for j in Js], axis=-2)
    M = np.zeros((J.shape[-2], J.shape[-2]))
    k = 0
    for Mi in Ms:
        M[k:k + Mi.shape[0], k:k + Mi.shape[0]] = Mi
        k += Mi.shape[0]
    if rows is not None:
        rows = check_int(rows, "rows", minimum=1, maximum=J.shape[-1], what=" (how many rows of the matrix to return)")
    left = J if rows is None else J[..., :rows]
    if np.count_nonzero(M - np.diag(np.diag(M))) == 0:
        return np.swapaxes(left * np.diag(M)[:, None], -1, -2) @ J
    return np.swapaxes(left, -1, -2) @ (M @ J)


def connection_from_mass_matrix(M: ArrayLike, *, n_position: int = 3) -> FloatArray:
    """Local connection ``A = I^-1 (I A)`` (..., 3, n) read off a mass matrix (..., 3 + n, 3 + n), (3.40).

    For a system whose Lagrangian is its kinetic energy ``1/2 [xi r_dot] M [xi r_dot]^T`` (3.39),
    the body momentum is ``I xi + (I A) r_dot`` with ``I`` the top-left (locked) block, so zero
    momentum gives ``xi = -A r_dot``. The top three rows of ``M`` are therefore a Pfaffian.
    """
    n_position = check_int(n_position, "n_position", minimum=1, maximum=64, what=" (rows of the locked inertia)")
    M = as_array(M, "M", allow_nan=True)
    if M.ndim < 2 or M.shape[-1] != M.shape[-2] or M.shape[-1] <= n_position:
        raise ValueError(f"M must be a square (..., 3 + n, 3 + n) mass matrix; got shape {M.shape}")
    return connection_from_pfaffian(M[..., :n_position, :], n_position=n_position)


def shape_space_metric(D: ArrayLike, A: ArrayLike) -> FloatArray:
    """Cost metric on shape space ``M = [-A; I]^T D [-A; I]`` (..., n, n), symmetrised.

    ``D`` (..., 3 + n, 3 + n) is a drag or mass matrix on the full velocity (xi, r_dot) and ``A``
    (..., 3, n) the connection in the same body frame; substituting xi = -A r_dot (3.10) gives the
    power dissipated (low Re) or twice the kinetic energy (floating, high Re) as r_dot^T M r_dot
    (the metric of Hatton and co-workers). It does not depend on the choice of body frame.
    """
    A, D = np.asarray(A, dtype=float), np.asarray(D, dtype=float)
    n = A.shape[-1]
    P = np.concatenate([-A, np.broadcast_to(np.eye(n), A.shape[:-2] + (n, n))], axis=-2)
    M = np.swapaxes(P, -1, -2) @ D @ P
    return (M + np.swapaxes(M, -1, -2)) / 2

"""Batch-last kernels of revolute chains of any length: link poses and body Jacobians in closed form.

numpy only. The public, validated entry points are :func:`link_chain_poses` and
:func:`link_chain_jacobians` (batch-first, ``(..., N, 3)``); the kernels under them are public
too, so that the locomotion systems (:class:`gm_core.systems.LinkChain`, the kinematic snake) and
the three-link chain (:mod:`gm_core.chains.three_link`) share one copy. Kernels do not validate:
callers pass arrays that :func:`chain_arguments` (or their own checks) have already checked.

The batch-last layout. A chain has ``N`` links and ``n = N - 1`` revolute joints; a batch of
``M`` shapes is flattened (:func:`flatten_batch`) and put *last*, so that every numpy operation
runs on long contiguous rows:

=======================  ===============================================================
argument / result        shape
=======================  ===============================================================
``alpha`` (batch-first)  ``(..., n)``; :func:`flatten_batch` gives ``a (n, M)`` and ``...``
``a``                    ``(n, M)`` joint angles, or ``(n,)`` for one shape (no batch axis:
                         every array below then loses its last axis ``M``)
``L``                    ``(N,)`` positive link lengths
``P`` (poses)            ``(x, y, theta, cos theta, sin theta)``, each ``(N, M)``
``B`` (shape Jacobians)  ``(Bx, By, Btheta)``: ``Bx, By (N, n, M)``, ``Btheta (N, n, 1)``
``beta`` (body frame)    ``(x, y, theta, cos theta, sin theta)``, each ``(M,)``
``Bb`` (its Jacobian)    ``(Bx, By, Btheta)``, each ``(n, M)``
``Q`` (links in body)    ``(x, y, theta, cos theta, sin theta)``, each ``(N, M)``
``J`` (link Jacobians)   ``(len(rows), 3 + n, N, M)``: rows x, y, theta of each link's map
                         from ``(xi, alpha_dot)`` to its body velocity
:func:`joint_turns`      ``(N, n) + (1,) * (ndim - 1)``, read-only
=======================  ===============================================================

Frames: link ``base`` (0-based) is the kernels' reference link, its centre frame at the origin;
link i + 1 is turned by ``alpha_i`` relative to link i (chapter 2's convention, fig. 2.8).
"""
from __future__ import annotations

import functools
from collections.abc import Sized
from typing import cast

import numpy as np
from numpy.typing import ArrayLike

from gm_core.validation import FloatArray, as_array, check_lengths

__all__ = [
    "chain_arguments", "flatten_batch", "chain_poses_T", "joint_turns", "chain_jacobians_T",
    "with_trig", "middle_frame_kernel", "link_chain_poses", "link_chain_jacobians",
]

#: ``(x, y, theta, cos theta, sin theta)``, each ``(N, M)`` (or ``(M,)`` for a body frame).
Pose5 = tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]
#: ``(Bx, By, Btheta)``: body Jacobians of poses, batch-last.
Jac3 = tuple[FloatArray, FloatArray, FloatArray]


def chain_arguments(alpha: ArrayLike, lengths: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Validated ``(alpha (..., N - 1), L (N,))`` for an N-link chain (N >= 2), naming a bad argument."""
    if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or len(cast(Sized, lengths)) < 2:
        raise ValueError(f"lengths must be a sequence of N >= 2 positive link lengths; got {lengths!r}")
    L = check_lengths(lengths, len(cast(Sized, lengths)))
    alpha = as_array(alpha, "alpha", (L.size - 1,), what=f" (the {L.size - 1} joint angles of a {L.size}-link chain)")
    return alpha, L


def flatten_batch(alpha: FloatArray) -> tuple[FloatArray, tuple[int, ...]]:
    """alpha (..., n) -> (n, M) with the batch flattened last (contiguous rows), and the batch shape."""
    return np.ascontiguousarray(alpha.reshape(-1, alpha.shape[-1]).T), alpha.shape[:-1]


def chain_poses_T(a: FloatArray, L: FloatArray, base: int = 0) -> tuple[Pose5, Jac3]:
    """The batch-last kernel of :func:`link_chain_poses`: joint angles ``a (n, M)``, lengths ``L (N,)``.

    Returns ``(P, B)`` with ``P = (x, y, theta, cos theta, sin theta)``, each ``(N, M)``, the link
    centres in the centre frame of link ``base + 1`` (0-based ``base``, default link 1), and
    ``B = (Bx, By, Btheta)``, ``Bx, By (N, n, M)``, ``Btheta (N, n, 1)``, their body Jacobians with
    that link held still: joint j turns the links beyond it (i > j >= base) by +1 about the
    joint, and, seen from a later base link, the links before it (i <= j < base) by -1. The
    chain is walked out from the base link both ways (headings by the addition formulas, 2 n
    transcendental calls per shape; running sums link by link, as a cumsum over the short first
    axis is ten times slower on batch-last rows). Batch-last arrays keep every operation on long
    contiguous rows (the fast layout for many shapes at once). ``a`` may also be ``(n,)``, one shape
    without a batch axis: the running sums then go on scalars and every array loses its last axis.
    """
    N, n = L.size, L.size - 1
    th = np.empty((N,) + a.shape[1:])
    c, s, px, py = np.empty_like(th), np.empty_like(th), np.empty_like(th), np.empty_like(th)
    qx, qy = np.empty_like(a), np.empty_like(a)                # the joints, in the same frame
    ca, sa = np.cos(a), np.sin(a)
    th[base], c[base], s[base], px[base], py[base] = 0.0, 1.0, 0.0, 0.0, 0.0
    for i in range(base, n):                                   # beyond the base: turn by +alpha_i
        if i == base:
            th[i + 1], c[i + 1], s[i + 1] = a[i], ca[i], sa[i]
        else:
            th[i + 1] = th[i] + a[i]
            c[i + 1] = c[i] * ca[i] - s[i] * sa[i]
            s[i + 1] = s[i] * ca[i] + c[i] * sa[i]
    for i in range(base - 1, -1, -1):                          # before it: turn by -alpha_i
        if i == base - 1:
            th[i], c[i], s[i] = -a[i], ca[i], -sa[i]
        else:
            th[i] = th[i + 1] - a[i]
            c[i] = c[i + 1] * ca[i] + s[i + 1] * sa[i]
            s[i] = s[i + 1] * ca[i] - c[i + 1] * sa[i]
    half = (L / 2).reshape((N,) + (1,) * (th.ndim - 1))
    sx, sy = half * c, half * s
    for j in range(base, n):                                   # joint j, between links j and j + 1
        qx[j] = px[j] + sx[j]
        qy[j] = py[j] + sy[j]
        px[j + 1] = qx[j] + sx[j + 1]
        py[j + 1] = qy[j] + sy[j + 1]
    for j in range(base - 1, -1, -1):
        qx[j] = px[j + 1] - sx[j + 1]
        qy[j] = py[j + 1] - sy[j + 1]
        px[j] = qx[j] - sx[j]
        py[j] = qy[j] - sy[j]
    turns = joint_turns(N, base, th.ndim)                     # (N, n, 1): +1, -1 or 0
    dx = qy[None] - py[:, None]                                # d p_x,i / d alpha_j = -(p_y,i - q_y,j) turns_ij
    dy = px[:, None] - qx[None]
    dx *= turns
    dy *= turns
    cc, ss = c[:, None], s[:, None]
    Bx, By = cc * dx, cc * dy                                  # in place from here: fewer big temporaries
    dx *= ss
    dy *= ss
    Bx += dy
    By -= dx
    return (px, py, th, c, s), (Bx, By, turns)


@functools.cache
def joint_turns(N: int, base: int, ndim: int) -> FloatArray:
    """The read-only (N, N - 1) table of d theta_i / d alpha_j with link ``base`` held still: +1 for
    i > j >= base, -1 for i <= j < base, else 0; with ``ndim - 1`` trailing axes of length 1."""
    i, j = np.arange(N)[:, None], np.arange(N - 1)[None, :]
    turns = ((i > j) & (j >= base)).astype(float) - ((i <= j) & (j < base))
    turns = turns.reshape((N, N - 1) + (1,) * (ndim - 1))
    turns.flags.writeable = False
    return turns


def chain_jacobians_T(P: Pose5, B: Jac3, beta: Pose5 | None = None, Bb: Jac3 | None = None,
                      rows: tuple[int, ...] = (0, 1, 2)) -> tuple[Pose5, FloatArray]:
    """The batch-last kernel of :func:`link_chain_jacobians`: ``P, B`` from :func:`chain_poses_T`,
    the body frame ``beta = (x, y, theta, cos theta, sin theta)`` (each (M,)) relative to the
    kernel's base link and its body Jacobian ``Bb = (Bx, By, Btheta)`` (each (n, M)); ``None``
    for both when the body frame is the base link itself (nothing to re-express). Returns
    ``(Q, J)``: ``Q`` the links in the body frame as (x, y, theta, cos theta, sin theta) (each
    (N, M)), and ``J (len(rows), 3 + n, N, M)``, the requested rows (0 = x, 1 = y, 2 = theta) and
    every column of each link's Jacobian from (xi, alpha_dot) to its body velocity.
    """
    (px, py, th, cp, sp), (B0, B1, B2) = P, B
    if beta is None:
        x, y, t, c, sn = P
    else:
        bx, by, bt, cb, sb = beta
        dx, dy = px - bx, py - by
        x, y, t = cb * dx + sb * dy, cb * dy - sb * dx, th - bt
        c, sn = cp * cb + sp * sb, sp * cb - cp * sb          # cos, sin of theta_i - theta_beta
    n = B0.shape[1]
    J = np.empty((len(rows), 3 + n) + px.shape)
    cc, ss = c[:, None], sn[:, None]
    if Bb is not None:
        X, Y, T = (b[None] for b in Bb)                   # Ad_{P_i^-1} Ad_beta = Ad_{Q_i^-1}
    for k, row in enumerate(rows):                        # Ad_{Q^-1} = [[c, s, e1], [-s, c, e2], [0, 0, 1]]
        shape_cols = np.swapaxes(J[k, 3:], 0, 1)          # (N, n, M), written in place
        if row == 0:
            e1 = sn * x - c * y
            J[k, 0], J[k, 1], J[k, 2] = c, sn, e1
            if Bb is None:
                shape_cols[...] = B0
            else:
                np.multiply(cc, X, out=shape_cols)
                shape_cols += ss * Y
                shape_cols += e1[:, None] * T
                np.subtract(B0, shape_cols, out=shape_cols)
        elif row == 1:
            e2 = c * x + sn * y
            J[k, 0], J[k, 1], J[k, 2] = -sn, c, e2
            if Bb is None:
                shape_cols[...] = B1
            else:
                np.multiply(cc, Y, out=shape_cols)
                shape_cols -= ss * X
                shape_cols += e2[:, None] * T
                np.subtract(B1, shape_cols, out=shape_cols)
        else:
            J[k, 0], J[k, 1], J[k, 2] = 0.0, 0.0, 1.0
            if Bb is None:
                shape_cols[...] = B2
            else:
                np.subtract(B2, T, out=shape_cols)
    return (x, y, t, c, sn), J


def with_trig(x: FloatArray, y: FloatArray, t: FloatArray) -> Pose5:
    """A batch-last pose (x, y, theta) with its cosine and sine, as the kernels take it."""
    return x, y, t, np.cos(t), np.sin(t)


def middle_frame_kernel(a: FloatArray, L: FloatArray, rows: tuple[int, ...]) -> tuple[Pose5, FloatArray]:
    """The links and Jacobians of a chain in its second link's frame (the middle of three):
    :func:`chain_poses_T` walked out from link 1 (0-based) and :func:`chain_jacobians_T` with no
    re-expression. ``a (n, M)`` validated, flattened joint angles, ``L (N,)``; returns ``(Q, J)``
    in the layout of the module docstring."""
    return chain_jacobians_T(*chain_poses_T(a, L, base=1), rows=rows)


def link_chain_poses(alpha: ArrayLike, lengths: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Link-centre poses ``(..., N, 3)`` of an N-link chain in link 1's centre frame and their body Jacobians.

    The chain of fig. 2.8 with any number of links: link i + 1 is turned by alpha_i relative to
    link i (chapter 2's convention), each link frame sits at its centre with x along the link
    towards link N. Returns ``(P, B)``: ``P (..., N, 3)`` the poses relative to link 1 and
    ``B (..., N, 3, N - 1)`` the body-velocity Jacobians of those relative poses,
    ``P_i^-1 dP_i = B_i dalpha`` (link 1 held still). A joint j turns every link beyond it about
    the joint: ``d p_i / d alpha_j = perp(p_i - q_j)`` for i > j, ``d theta_i / d alpha_j = 1``.
    """
    alpha, L = chain_arguments(alpha, lengths)
    a, batch = flatten_batch(alpha)
    (px, py, th, _, _), (B0, B1, B2) = chain_poses_T(a, L)
    N, n = L.size, L.size - 1
    P = np.stack([px, py, th]).T.reshape(batch + (N, 3))
    B = np.stack([B0, B1, np.broadcast_to(B2, B0.shape)]).transpose(3, 1, 0, 2).reshape(batch + (N, 3, n))
    return P, B


def link_chain_jacobians(P: ArrayLike, B: ArrayLike, beta: ArrayLike,
                         B_beta: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Link Jacobians ``(..., N, 3, 3 + n)`` mapping (xi, alpha_dot) to each link's body velocity.

    ``P, B`` from :func:`link_chain_poses`; the body frame sits at ``beta (..., 3)`` relative to
    link 1 with body-velocity Jacobian ``B_beta (..., 3, n)``. With Q_i = beta^-1 P_i (link i in
    the body frame), ``xi_i = Ad_{Q_i^-1} xi + (B_i - Ad_{P_i^-1} Ad_beta B_beta) alpha_dot``
    (body velocities of products and inverses, section 1.5; (2.68) for any number of links).
    Returns ``(Q (..., N, 3), J (..., N, 3, 3 + n))``.
    """
    P, B = np.asarray(P, dtype=float), np.asarray(B, dtype=float)
    beta, B_beta = np.asarray(beta, dtype=float), np.asarray(B_beta, dtype=float)
    n = B.shape[-1]
    batch = np.broadcast_shapes(P.shape[:-2], B.shape[:-3], beta.shape[:-1], B_beta.shape[:-2])
    N = P.shape[-2]
    P = np.broadcast_to(P, batch + P.shape[-2:]).reshape(-1, N, 3)
    B = np.broadcast_to(B, batch + B.shape[-3:]).reshape(-1, N, 3, n)
    beta = np.broadcast_to(beta, batch + (3,)).reshape(-1, 3).T
    Bb = np.broadcast_to(B_beta, batch + (3, n)).reshape(-1, 3, n).transpose(1, 2, 0)
    PT = with_trig(*(P[..., k].T for k in range(3)))
    BT = (B[:, :, 0].transpose(1, 2, 0), B[:, :, 1].transpose(1, 2, 0), B[:, :, 2].transpose(1, 2, 0))
    (x, y, t, _, _), J = chain_jacobians_T(PT, BT, with_trig(*beta), (Bb[0], Bb[1], Bb[2]))
    Q = np.stack([x, y, t]).T.reshape(batch + (N, 3))
    return Q, J.transpose(3, 2, 0, 1).reshape(batch + (N, 3, 3 + n))

"""Batch-last kernels of revolute chains of any length (book section 2.5; beyond the draft for N > 3).

One copy of the link-centre poses and body Jacobians of an N-link planar chain, used by the
three-link chain of chapter 2 (:mod:`gm_core.chains.three_link`), the locomoting chains
(:class:`gm_core.systems.LinkChain`, the kinematic snake) and their checkers.

**Layout.** The kernels take and return *batch-last* arrays: the M shapes of a batch sit on the
last axis, so every operation runs along long contiguous rows. For a chain of N links and
n = N - 1 joints:

* joint angles ``a``: ``(n, M)`` (or ``(n,)`` for one shape: every result then loses its last axis);
  :func:`batch_last` turns the usual ``(..., n)`` into ``(n, M)`` and returns the batch shape;
* link lengths ``L``: ``(N,)``;
* poses ``P = (x, y, theta, cos theta, sin theta)``: five arrays ``(N, M)``, the link centres in the
  centre frame of the base link;
* pose Jacobians ``B = (Bx, By, Btheta)``: ``Bx, By (N, n, M)`` and ``Btheta (N, n, 1)`` (the
  read-only table of :func:`joint_turns`);
* a body frame ``beta = (x, y, theta, cos, sin)`` (each ``(M,)``) with Jacobian
  ``Bb = (Bx, By, Btheta)`` (each ``(n, M)``);
* link Jacobians ``J``: ``(rows, 3 + n, N, M)``, columns (xi, alpha_dot), rows 0 = x, 1 = y, 2 = theta.

:func:`link_chain_poses` and :func:`link_chain_jacobians` are the same computations in the usual
batch-first layout, with their arguments validated. numpy only.
"""
from __future__ import annotations

import functools

import numpy as np

from gm_core.validation import as_array, check_lengths

__all__ = [
    "batch_last", "chain_arguments", "chain_poses_batch_last", "chain_jacobians_batch_last", "joint_turns",
    "with_trig", "middle_frame_kernel", "link_chain_poses", "link_chain_jacobians",
]


def chain_arguments(alpha, lengths):
    """``(alpha, L)`` validated: joint angles ``(..., N - 1)`` and N >= 2 positive link lengths ``L (N,)``."""
    if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or len(lengths) < 2:
        raise ValueError(f"lengths must be a sequence of N >= 2 positive link lengths; got {lengths!r}")
    L = check_lengths(lengths, len(lengths))
    alpha = as_array(alpha, "alpha", (L.size - 1,), what=f" (the {L.size - 1} joint angles of a {L.size}-link chain)")
    return alpha, L


def batch_last(alpha):
    """alpha (..., n) -> (n, M) with the batch flattened last (contiguous rows), and the batch shape."""
    return np.ascontiguousarray(alpha.reshape(-1, alpha.shape[-1]).T), alpha.shape[:-1]


def chain_poses_batch_last(a, L, base=0):
    """Link-centre poses and their body Jacobians, batch-last (the kernel of :func:`link_chain_poses`): joint angles ``a (n, M)``, lengths ``L (N,)``.

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
def joint_turns(N, base, ndim):
    """The read-only (N, N - 1) table of d theta_i / d alpha_j with link ``base`` held still: +1 for
    i > j >= base, -1 for i <= j < base, else 0; with ``ndim - 1`` trailing axes of length 1."""
    i, j = np.arange(N)[:, None], np.arange(N - 1)[None, :]
    turns = ((i > j) & (j >= base)).astype(float) - ((i <= j) & (j < base))
    turns = turns.reshape((N, N - 1) + (1,) * (ndim - 1))
    turns.flags.writeable = False
    return turns


def chain_jacobians_batch_last(P, B, beta=None, Bb=None, rows=(0, 1, 2)):
    """The batch-last kernel of :func:`link_chain_jacobians`: ``P, B`` from :func:`chain_poses_batch_last`,
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


def with_trig(x, y, t):
    """A batch-last pose (x, y, theta) with its cosine and sine, as the kernels take it."""
    return x, y, t, np.cos(t), np.sin(t)


def link_chain_poses(alpha, lengths):
    """Link-centre poses ``(..., N, 3)`` of an N-link chain in link 1's centre frame and their body Jacobians.

    The chain of fig. 2.8 with any number of links: link i + 1 is turned by alpha_i relative to
    link i (chapter 2's convention), each link frame sits at its centre with x along the link
    towards link N. Returns ``(P, B)``: ``P (..., N, 3)`` the poses relative to link 1 and
    ``B (..., N, 3, N - 1)`` the body-velocity Jacobians of those relative poses,
    ``P_i^-1 dP_i = B_i dalpha`` (link 1 held still). A joint j turns every link beyond it about
    the joint: ``d p_i / d alpha_j = perp(p_i - q_j)`` for i > j, ``d theta_i / d alpha_j = 1``.
    """
    alpha, L = chain_arguments(alpha, lengths)
    a, batch = batch_last(alpha)
    (px, py, th, _, _), (B0, B1, B2) = chain_poses_batch_last(a, L)
    N, n = L.size, L.size - 1
    P = np.stack([px, py, th]).T.reshape(batch + (N, 3))
    B = np.stack([B0, B1, np.broadcast_to(B2, B0.shape)]).transpose(3, 1, 0, 2).reshape(batch + (N, 3, n))
    return P, B


def link_chain_jacobians(P, B, beta, B_beta):
    """Link Jacobians ``(..., N, 3, 3 + n)`` mapping (xi, alpha_dot) to each link's body velocity.

    ``P, B`` from :func:`link_chain_poses`; the body frame sits at ``beta (..., 3)`` relative to
    link 1 with body-velocity Jacobian ``B_beta (..., 3, n)``. With Q_i = beta^-1 P_i (link i in
    the body frame), ``xi_i = Ad_{Q_i^-1} xi + (B_i - Ad_{P_i^-1} Ad_beta B_beta) alpha_dot``
    (body velocities of products and inverses, section 1.5; (2.68) for any number of links).
    Returns ``(Q (..., N, 3), J (..., N, 3, 3 + n))``.
    """
    n = B.shape[-1]
    batch = np.broadcast_shapes(P.shape[:-2], B.shape[:-3], beta.shape[:-1], B_beta.shape[:-2])
    N = P.shape[-2]
    P = np.broadcast_to(P, batch + P.shape[-2:]).reshape(-1, N, 3)
    B = np.broadcast_to(B, batch + B.shape[-3:]).reshape(-1, N, 3, n)
    beta = np.broadcast_to(beta, batch + (3,)).reshape(-1, 3).T
    Bb = np.broadcast_to(B_beta, batch + (3, n)).reshape(-1, 3, n).transpose(1, 2, 0)
    PT = with_trig(*(P[..., k].T for k in range(3)))
    BT = tuple(B[:, :, k].transpose(1, 2, 0) for k in range(3))
    (x, y, t, _, _), J = chain_jacobians_batch_last(PT, BT, with_trig(*beta), tuple(Bb))
    Q = np.stack([x, y, t]).T.reshape(batch + (N, 3))
    return Q, J.transpose(3, 2, 0, 1).reshape(batch + (N, 3, 3 + n))


def middle_frame_kernel(a, L, rows):
    """:func:`middle_frame_T` on validated, flattened joint angles ``a (2, M)`` and lengths ``L (3,)``:
    the chain kernels walked out from the middle link (their base), so nothing is re-expressed."""
    return chain_jacobians_batch_last(*chain_poses_batch_last(a, L, base=1), rows=rows)

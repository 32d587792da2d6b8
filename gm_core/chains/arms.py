"""The book's fixed-base arms (chapter 2): the pivoted link, the two-link (RR) arm and the
rotary-prismatic (RP) arm, (2.3)-(2.45), each in closed form and written once.

numpy only. The general machinery they are instances of (joints, :class:`~gm_core.chains.Chain`,
Jacobians three ways) is :mod:`gm_core.chains`; tests check every closed form against it.
Shapes: configurations ``alpha: (..., n_joints)``; poses ``(..., 3)`` = (x, y, theta); Jacobians
``(..., 3, m)``.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.chains.chain import Chain
from gm_core.groups import SE2
from gm_core.validation import FloatArray, as_array, check_lengths, positive_number, real_number

__all__ = [
    "single_link_frames", "rr_arm_frames", "rr_arm_jacobian", "rp_arm_frames",
    "rp_arm_body_jacobians",
]


def single_link_frames(alpha: ArrayLike, length: float = 1.0) -> tuple[FloatArray, FloatArray]:
    """Proximal and distal poses (g, h), each ``(..., 3)``, of the pivoted link of fig. 2.2; book (2.3)-(2.4)."""
    alpha = as_array(alpha, "alpha")
    L = positive_number(length, "length")
    g = np.stack(np.broadcast_arrays(0.0 * alpha, 0.0 * alpha, alpha), -1)
    return g, SE2.compose(g, np.array([L, 0.0, 0.0]))


def rr_arm_frames(alpha: ArrayLike, lengths: ArrayLike = (1.0, 1.0)) -> FloatArray:
    """Poses ``(..., 4, 3)`` of g1, h1, g2, h2 of the two-link arm of fig. 2.3; book (2.5)-(2.7)."""
    ch = Chain("RR", lengths)
    fr = ch.frames(alpha)
    return np.stack([fr["f"][..., 0, :], fr["h"][..., 0, :], fr["f"][..., 1, :], fr["h"][..., 1, :]], -2)


def rr_arm_jacobian(alpha: ArrayLike, lengths: ArrayLike = (1.0, 1.0)) -> FloatArray:
    """World-velocity Jacobian ``(..., 3, 2)`` of the two-link arm's end effector h2, closed form; book (2.19), (2.30)."""
    alpha = as_array(alpha, "alpha", (2,), what=" (alpha1, alpha2)")
    l1, l2 = check_lengths(lengths, 2)
    a1, a12 = alpha[..., 0], alpha[..., 0] + alpha[..., 1]
    J = np.zeros(alpha.shape[:-1] + (3, 2))
    J[..., 0, 0] = -(l1 * np.sin(a1) + l2 * np.sin(a12))
    J[..., 0, 1] = -l2 * np.sin(a12)
    J[..., 1, 0] = l1 * np.cos(a1) + l2 * np.cos(a12)
    J[..., 1, 1] = l2 * np.cos(a12)
    J[..., 2, :] = 1.0
    return J


def _rp_args(alpha, delta, l1, l2, offset):
    alpha = as_array(alpha, "alpha")
    delta = as_array(delta, "delta")
    l1 = positive_number(l1, "l1")
    l2 = positive_number(l2, "l2")
    a = real_number(offset, "offset")
    alpha, delta = np.broadcast_arrays(alpha, delta)
    return alpha, delta, l1, l2, a


def rp_arm_frames(alpha: ArrayLike, delta: ArrayLike, l1: float = 1.0, l2: float = 1.0,
                  offset: float = 0.0) -> dict[str, FloatArray]:
    """Poses of g1, h1, g2', g2, h2, dict of ``(..., 3)``, for the rotary-prismatic arm of figs. 2.4 and 2.10; book (2.10)-(2.11).

    g1 is the rotating frame at the pivot, h1 = g1 (l1, offset, 0) the end of link 1 (``offset`` is
    the lateral offset a of fig. 2.10; 0 for fig. 2.4), g2' the frame of link 2 aligned with h1,
    g2 = g2' (delta, 0, 0) and h2 = g2' (delta + l2, 0, 0).
    """
    alpha, delta, l1, l2, a = _rp_args(alpha, delta, l1, l2, offset)
    z = np.zeros_like(alpha)
    g1 = np.stack([z, z, alpha], -1)
    h1 = SE2.compose(g1, np.array([l1, a, 0.0]))
    g2 = SE2.compose(h1, np.stack([delta, z, z], -1))
    h2 = SE2.compose(h1, np.stack([delta + l2, z, z], -1))
    return {"g1": g1, "h1": h1, "g2p": h1.copy(), "g2": g2, "h2": h2}


def rp_arm_body_jacobians(alpha: ArrayLike, delta: ArrayLike, l1: float = 1.0, l2: float = 1.0,
                          offset: float = 0.0) -> dict[str, FloatArray]:
    """Body-velocity Jacobians wrt (alpha_dot, delta_dot), dict of ``(..., 3, 2)``; book (2.40)-(2.45), exercise 2.2.

    Keys g1, h1, g2p, g2, h2 as in :func:`rp_arm_frames`. With lateral offset a (fig. 2.10) the
    distal frame of link 1 also moves backwards along its own x axis at -a alpha_dot.
    """
    alpha, delta, l1, l2, a = _rp_args(alpha, delta, l1, l2, offset)

    def J(col_a, col_d):
        out = np.zeros(alpha.shape + (3, 2))
        out[..., :, 0] = np.stack(np.broadcast_arrays(*col_a), -1)
        out[..., :, 1] = col_d
        return out

    zero = np.zeros_like(alpha)
    return {
        "g1": J((zero, zero, zero + 1.0), (0.0, 0.0, 0.0)),                     # (2.40)
        "h1": J((zero - a, zero + l1, zero + 1.0), (0.0, 0.0, 0.0)),            # (2.41)
        "g2p": J((zero - a, zero + l1, zero + 1.0), (1.0, 0.0, 0.0)),           # (2.43)
        "g2": J((zero - a, l1 + delta, zero + 1.0), (1.0, 0.0, 0.0)),           # (2.44)
        "h2": J((zero - a, l1 + delta + l2, zero + 1.0), (1.0, 0.0, 0.0)),      # (2.45)
    }

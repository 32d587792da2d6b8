"""The three-link mobile chain of chapter 2 and its generalized body frames.

numpy only. Link-centre poses :func:`three_link_poses` and body-velocity Jacobians
:func:`three_link_jacobians` (2.46)-(2.59), used by every three-link locomotor in
:mod:`gm_core.systems` and by the exercise checkers; generalized body frames (2.60)-(2.69) and the
centre-of-mass frame of exercise 2.3. The general machinery (:class:`~gm_core.chains.MobileChain`)
is :mod:`gm_core.chains`. Shapes: configurations ``alpha: (..., 2)``; poses ``(..., 3)``;
Jacobians ``(..., 3, 5)``.
"""
from __future__ import annotations

from collections.abc import Sequence, Sized
from typing import cast

import numpy as np
from numpy.typing import ArrayLike

from gm_core.chains.chain import MobileChain
from gm_core.chains.kernels import Pose5, flatten_batch, middle_frame_kernel
from gm_core.groups import SE2, matvec
from gm_core.validation import FloatArray, as_array, batch_shape, check_lengths

__all__ = [
    "three_link_chain", "three_link_frames", "three_link_poses", "three_link_jacobians",
    "beta_frame_velocity", "beta_frame_jacobian", "links_from_beta_frame", "com_frame",
    "com_frame_jacobians",
]


def three_link_chain(lengths: ArrayLike) -> MobileChain:
    """The three-link mobile system of fig. 2.8 with the middle link as body frame (a :class:`MobileChain`)."""
    if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or len(cast(Sized, lengths)) != 3:
        raise ValueError(f"lengths must be a length-3 sequence of positive link lengths; got {lengths!r}")
    return MobileChain(lengths, base_link=1)


def three_link_frames(alpha: ArrayLike, lengths: ArrayLike = (1.0, 1.0, 1.0),
                      g: ArrayLike | None = None) -> dict[str, FloatArray]:
    """Poses of the three links' f, g, h frames and the two joints, with link 2's centre at g; book (2.12), fig. 2.8.

    alpha: ``(..., 2)``, alpha1 = rotation of link 2 relative to link 1, alpha2 = rotation of link 3
    relative to link 2 (fig. 2.6). g: ``(..., 3)``, default e. Returns a dict with "f", "g", "h"
    of shape ``(..., 3, 3)`` (link index on axis -2) and "joints" ``(..., 2, 2)``, the joint positions.
    """
    fr = three_link_chain(lengths).frames(alpha, g)
    fr["joints"] = fr["h"][..., :2, :2].copy()
    return fr


def _three_link_lengths(lengths):
    if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or len(lengths) != 3:
        raise ValueError(f"lengths must be a length-3 sequence of positive link lengths; got {lengths!r}")
    return check_lengths(lengths, 3)


def middle_frame_T(alpha: ArrayLike, lengths: ArrayLike,
                   rows: tuple[int, ...] = (0, 1, 2)) -> tuple[tuple[int, ...], Pose5, FloatArray]:
    """``(batch, (x, y, theta, cos, sin), J)``: the link poses (each (3, M)) and Jacobians J (rows, 5, 3, M) in the
    middle link's frame, batch-last (:func:`gm_core.chains.kernels.middle_frame_kernel`); ``batch`` the shape M was flattened from."""
    alpha = as_array(alpha, "alpha", (2,), what=" (alpha1, alpha2)")
    a, batch = flatten_batch(alpha)
    return (batch,) + middle_frame_kernel(a, np.asarray(_three_link_lengths(lengths)), rows)


def _middle_frame(alpha, lengths):
    """(Q, J): the link poses (..., 3, 3) and Jacobians (..., 3, 3, 5) in the middle link's frame."""
    batch, (x, y, t, _, _), J = middle_frame_T(alpha, lengths)
    return np.stack([x, y, t]).T.reshape(batch + (3, 3)), J.transpose(3, 2, 0, 1).reshape(batch + (3, 3, 5))


def three_link_poses(alpha: ArrayLike, lengths: ArrayLike = (1.0, 1.0, 1.0)) -> FloatArray:
    """Poses ``(..., 3, 3)`` of the three link centres g1, g2, g3 in the middle link's frame; book (2.12), fig. 2.8.

    The chain product ``g1 = (-l2/2, 0, 0) exp(-alpha1) (-l1/2, 0, 0)``, ``g2 = e``,
    ``g3 = (l2/2, 0, 0) exp(alpha2) (l3/2, 0, 0)`` (the link index is on axis -2): link 1 sits at
    heading -alpha1, link 3 at +alpha2. alpha: ``(..., 2)``. The N-link chain of
    :func:`gm_core.chains.link_chain_poses` seen from its middle link (one copy for every N).
    """
    return _middle_frame(alpha, lengths)[0]


def three_link_jacobians(alpha: ArrayLike,
                         lengths: ArrayLike = (1.0, 1.0, 1.0)) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Body-velocity Jacobians (J1, J2, J3) of the three links, each ``(..., 3, 5)``; book (2.57)-(2.59), corrected.

    Each maps (xi_x, xi_y, xi_theta, alpha1_dot, alpha2_dot) -- the body velocity of the middle link
    and the joint speeds -- to the body velocity of link i's centre frame g_i. alpha: ``(..., 2)``
    with the sign convention of fig. 2.6 (link 1 sits at -alpha1 relative to link 2, link 3 at
    +alpha2); lengths: three positive numbers. Computed as :func:`gm_core.chains.link_chain_jacobians`
    with the middle link as body frame; ``tests/test_chains_three_link.py`` checks it against the
    closed form (2.57)-(2.59). Corrections to the draft (see book/90-errata): row 1 of (2.51) has
    -(xi_y - xi_theta l2/2) sin(alpha1); (2.56) needs the third row xi_theta + alpha2_dot, so
    row 3 of (2.59) is (0, 0, 1, 0, 1).
    """
    J = _middle_frame(alpha, lengths)[1]
    return J[..., 0, :, :], J[..., 1, :, :], J[..., 2, :, :]


# ------------------------------------------------------------------ generalized body frames
def _beta_args(beta, dbeta):
    beta = as_array(beta, "beta", (3,), what=" (pose of the frame relative to the base link)")
    dbeta = as_array(dbeta, "dbeta", (3, np.shape(dbeta)[-1] if np.ndim(dbeta) >= 2 else 0),
                     what=" (d beta / d alpha)")
    batch_shape(("beta", beta, 1), ("dbeta", dbeta, 2))
    return beta, dbeta


def _v_beta_matrix(beta, dbeta):
    """The map alpha_dot -> v_beta = T_beta R_{beta^-1} (d beta / d alpha) alpha_dot, ``(..., 3, n)``; book (2.61)."""
    return SE2.right_lifted_action(SE2.inverse(beta), beta) @ dbeta


def beta_frame_velocity(beta: ArrayLike, dbeta: ArrayLike, xi_base: ArrayLike,
                        alpha_dot: ArrayLike) -> dict[str, FloatArray]:
    """The body velocity of the frame g = g_base beta(alpha), split into its two causes; book (2.60)-(2.62), (2.67).

    Returns a dict of ``(..., 3)`` arrays:

    * ``"carried"`` = Ad_beta^-1 xi_base: the velocity g would have if it were welded to the
      base link (the base link's motion, seen at g and in g's axes);
    * ``"shape"`` = Ad_beta^-1 v_beta = T_beta L_{beta^-1} beta_dot: g sliding and turning
      relative to the base link because the shape changes;
    * ``"body"`` = carried + shape, the body velocity xi_g of (2.62);
    * ``"v_beta"`` = T_beta R_{beta^-1} beta_dot, the velocity of (2.61) (expressed at the base
      link, as a spatial velocity of beta).

    beta ``(..., 3)``, dbeta = d beta / d alpha ``(..., 3, n)``, xi_base ``(..., 3)`` the base link's
    body velocity, alpha_dot ``(..., n)``. The columns are those of :func:`beta_frame_jacobian`.
    """
    beta, dbeta = _beta_args(beta, dbeta)
    n = dbeta.shape[-1]
    xi_base = as_array(xi_base, "xi_base", (3,), what=" (body velocity of the base link)")
    alpha_dot = as_array(alpha_dot, "alpha_dot", (n,), what=f" (one shape rate per column of dbeta: {n})")
    J = beta_frame_jacobian(beta, dbeta)
    carried = matvec(J[..., :, :3], xi_base)
    shape = matvec(J[..., :, 3:], alpha_dot)
    return {"carried": carried, "shape": shape, "body": carried + shape,
            "v_beta": matvec(_v_beta_matrix(beta, dbeta), alpha_dot)}


def beta_frame_jacobian(beta: ArrayLike, dbeta: ArrayLike) -> FloatArray:
    """Body-velocity Jacobian ``(..., 3, 3 + n)`` of the frame g = g_base beta(alpha); book (2.60)-(2.67).

    Maps (xi_base, alpha_dot) to xi_g = Ad_beta^-1 (xi_base + T_beta R_{beta^-1} dbeta alpha_dot).
    beta: ``(..., 3)``, dbeta = d beta / d alpha: ``(..., 3, n)``.
    """
    beta, dbeta = _beta_args(beta, dbeta)
    n = dbeta.shape[-1]
    batch = np.broadcast_shapes(beta.shape[:-1], dbeta.shape[:-2])
    M = np.zeros(batch + (3, 3 + n))
    M[..., :, :3] = np.eye(3)
    M[..., :, 3:] = _v_beta_matrix(beta, dbeta)
    return SE2.Ad_inv(beta) @ M


def links_from_beta_frame(jacobians: Sequence[ArrayLike], beta: ArrayLike, dbeta: ArrayLike) -> list[FloatArray]:
    """Link Jacobians re-expressed with the frame g = g_base beta as body frame: list of ``(..., 3, 3 + n)``; book (2.68).

    ``jacobians`` are Jacobians wrt (xi_base, alpha_dot) (e.g. from :func:`three_link_jacobians`);
    the result maps (xi_g, alpha_dot) using xi_base = Ad_beta xi_g - T_beta R_{beta^-1} dbeta alpha_dot.
    """
    beta, dbeta = _beta_args(beta, dbeta)
    n = dbeta.shape[-1]
    batch = np.broadcast_shapes(beta.shape[:-1], dbeta.shape[:-2])
    M = np.zeros(batch + (3 + n, 3 + n))
    M[..., :3, :3] = SE2.Ad(beta)
    M[..., :3, 3:] = -_v_beta_matrix(beta, dbeta)
    M[..., 3:, 3:] = np.eye(n)
    if not isinstance(jacobians, (list, tuple)) or not jacobians:
        raise TypeError(f"jacobians must be a non-empty list or tuple of Jacobians (..., 3, 3 + n); "
                        f"got {type(jacobians).__name__}")
    Js = [as_array(J, f"jacobians[{i}]", (3, 3 + n), what=f" (dbeta has n = {n} columns)")
          for i, J in enumerate(jacobians)]
    return [J @ M for J in Js]


def com_frame(alpha: ArrayLike, lengths: ArrayLike = (1.0, 1.0, 1.0),
              weights: ArrayLike | None = None) -> tuple[FloatArray, FloatArray]:
    """The centre-of-mass / mean-orientation frame beta(alpha) ``(..., 3)`` and d beta/d alpha ``(..., 3, 2)``; exercise 2.3a, (2.69).

    beta is the pose relative to the middle link of the three-link system: position the weighted
    mean of the link centres, orientation the weighted mean of the link orientations (-alpha1, 0,
    alpha2). ``weights`` default to the link lengths (uniform mass per unit length); pass
    ``(1, 1, 1)`` for the plain mean. This is the course's one "centre of mass" frame
    (``LinkChain(..., frame="com")`` for any number of links).
    """
    Q, J = _middle_frame(alpha, lengths)
    w = np.array(_three_link_lengths(lengths)) if weights is None else check_lengths(weights, 3, "weights")
    w = w / w.sum()
    # d(x_i, y_i)/d alpha = R(theta_i) (shape columns of J_i, rows x, y); d theta_i/d alpha = row theta
    c, s = np.cos(Q[..., 2])[..., None], np.sin(Q[..., 2])[..., None]
    Jr = J[..., 3:]
    dP = np.stack([c * Jr[..., 0, :] - s * Jr[..., 1, :], s * Jr[..., 0, :] + c * Jr[..., 1, :], Jr[..., 2, :]], -2)
    return np.einsum("i,...ij->...j", w, Q), np.einsum("i,...ijk->...jk", w, dP)


def com_frame_jacobians(alpha: ArrayLike, lengths: ArrayLike = (1.0, 1.0, 1.0),
                        weights: ArrayLike | None = None) -> tuple[FloatArray, tuple[FloatArray, ...]]:
    """Jacobian of the centre-of-mass frame and the three link Jacobians seen from it; exercise 2.3b-c.

    Returns ``(J_com, (J1, J2, J3))``: J_com ``(..., 3, 5)`` maps (xi_middle, alpha_dot) to the
    body velocity of the frame (2.62); J_i ``(..., 3, 5)`` map (xi_com, alpha_dot) to link i's body
    velocity (2.68).
    """
    beta, dbeta = com_frame(alpha, lengths, weights)
    J_com = beta_frame_jacobian(beta, dbeta)
    return J_com, tuple(links_from_beta_frame(three_link_jacobians(alpha, lengths), beta, dbeta))

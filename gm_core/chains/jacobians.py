"""Jacobians of chains and frames (book section 2.5): changes between world and body Jacobians,
finite differences, relative poses and the column-by-column (one joint at a time) transport of (2.33)-(2.37).

numpy only. Shapes as in :mod:`gm_core.chains.chain`: poses ``(..., 3)``, Jacobians ``(..., 3, m)``.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups import SE2
from gm_core.groups.base import LieGroup
from gm_core.validation import FloatArray, as_array, positive_number

__all__ = [
    "finite_difference_jacobians", "relative_pose", "world_to_body_jacobian",
    "body_to_world_jacobian",
]


def world_to_body_jacobian(g: ArrayLike, J: ArrayLike) -> FloatArray:
    """Body-velocity Jacobian ``T_g L_{g^-1} J`` from a world-velocity one; g: (..., 3), J: (..., 3, m); book (1.32)."""
    g = as_array(g, "g", (3,), what=" (the pose the Jacobian is taken at)")
    J = as_array(J, "J", what=" (a world-velocity Jacobian (..., 3, m))")
    if J.ndim < 2 or J.shape[-2] != 3:
        raise ValueError(f"J must have shape (..., 3, m) (a world-velocity Jacobian); got shape {J.shape}")
    try:
        np.broadcast_shapes(g.shape[:-1], J.shape[:-2])
    except ValueError:
        raise ValueError(f"g and J have incompatible batch shapes {g.shape[:-1]} and {J.shape[:-2]}") from None
    return SE2.left_lifted_action(SE2.inverse(g), g) @ J


def body_to_world_jacobian(g: ArrayLike, J: ArrayLike) -> FloatArray:
    return SE2.left_lifted_action(g, SE2.identity()) @ np.asarray(J, dtype=float)


# ------------------------------------------------------------------------ finite differences
def finite_difference_jacobians(fk: Callable[[FloatArray], ArrayLike], alpha: ArrayLike,
                                eps: float = 1e-6) -> FloatArray:
    """World-velocity Jacobian ``(..., k, 3, n)`` of poses ``fk(alpha): (..., k, 3)`` by central differences.

    An independent route to (2.16): angles are differenced modulo 2 pi. ``alpha: (..., n)``.
    """
    if not callable(fk):
        raise TypeError(f"fk must be a function alpha (..., n) -> poses (..., k, 3); got {type(fk).__name__}")
    alpha = np.atleast_1d(as_array(alpha, "alpha"))
    if alpha.shape[-1] == 0:
        raise ValueError(f"alpha must have at least one joint angle; got shape {alpha.shape}")
    eps = positive_number(eps, "eps", what=" (a finite-difference step)")
    if eps >= 1:
        raise ValueError(f"eps must be a small step in (0, 1); got {eps!r}")
    cols = []
    for j in range(alpha.shape[-1]):
        d = np.zeros(alpha.shape)
        d[..., j] = eps
        cols.append(SE2.difference(fk(alpha + d), fk(alpha - d)) / (2 * eps))
    return np.stack(cols, axis=-1)


# ------------------------------------------------------------------------ relative poses
def relative_pose(g: ArrayLike, base: ArrayLike, group: LieGroup = SE2) -> FloatArray:
    """The pose ``base^-1 g`` of frame g seen from frame ``base``, ``(..., dim)``; book (2.iii), g_{1,h} = h^-1 g_1.

    With this notation poses chain by cancelling the frame in the middle, box "A note on
    notation" (2.iv): ``compose(relative_pose(b, c), relative_pose(a, b)) == relative_pose(a, c)``
    (the pose of b seen from c, then a seen from b, is a seen from c), and
    ``inverse(relative_pose(a, b)) == relative_pose(b, a)``. ``group`` is any
    :class:`~gm_core.groups.LieGroup` (default SE(2)); g, base: ``(..., group.dim)``.
    """
    dim = group.dim
    g = as_array(g, "g", (dim,), what=f" (an element of {group.name})")
    base = as_array(base, "base", (dim,), what=f" (an element of {group.name}: the frame g is seen from)")
    return group.compose(group.inverse(base), g)



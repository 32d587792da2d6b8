"""A system restricted to an affine subspace of its shapes: slices of shape space and shape maps (numpy only).

If the shape is driven only along ``r = r0 + S q`` (S an (n, m) matrix), the restricted system
has shape q and, by the chain rule, connection ``A_q(q) = A(r0 + S q) S``, Pfaffian
``[omega_xi, omega_r S]``, cost metric ``S^T M S`` and curvature the pull-back of the 2-form,
``F_q,ab = sum_ij S_ia S_jb F_ij`` (curvature commutes with pull-back). Two uses:

* :func:`shape_slice`: a two-dimensional slice through a shape ``r0`` along two shape
  directions of a many-link chain, on which every two-dimensional tool of the course works
  (connection fields, curvature maps, Stokes estimates of gaits lying in the slice);
* a chain whose joint angles sample a continuous curvature (``S`` maps mode amplitudes to joint
  angles), compared with the continuous body in :mod:`gm_core.systems.slender_body`.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.systems.base import LocomotionSystem, SystemPart
from gm_core.systems.motion import trusted_dimension
from gm_core.validation import BoolArray, FloatArray, as_array, check_int

__all__ = ["AffineRestriction", "shape_slice"]


class AffineRestriction(LocomotionSystem):
    """``base`` with its shape confined to ``r = offset + matrix @ q``; shape q (m,)."""

    def __init__(self, base: LocomotionSystem, matrix: ArrayLike, offset: ArrayLike | None = None, *,
                 shape_names: Sequence[str] | None = None, shape_limits: Any = None, name: str | None = None) -> None:
        n = trusted_dimension(base, "base")
        S = as_array(matrix, "matrix", what=f" (an (n, m) map from the new shapes to the {n} shapes of {base.name})")
        if S.ndim != 2 or S.shape[0] != n or S.shape[1] < 1:
            raise ValueError(f"matrix must have shape ({n}, m) with m >= 1; got shape {S.shape}")
        r0 = np.zeros(n) if offset is None else as_array(offset, "offset", (n,), what=f" (a shape of {base.name})")
        if r0.ndim != 1:
            raise ValueError(f"offset must be one shape ({n},); got shape {r0.shape}")
        self.base_system, self.matrix, self.offset = base, S.copy(), r0.copy()
        self.n_shape = S.shape[1]
        self.shape_names = tuple(shape_names) if shape_names is not None else tuple(f"q{k + 1}" for k in range(self.n_shape))
        self.shape_limits = tuple(shape_limits) if shape_limits is not None else ((-np.pi, np.pi),) * self.n_shape
        self.may_be_singular = base.may_be_singular
        setattr(self, "position_group", base.position_group)  # noqa: B010 (a ClassVar elsewhere): a rotor body still turns in SO(3)
        self.singular_description = base.singular_description
        self.name = name or f"{base.name} (restricted)"

    def full_shape(self, q: ArrayLike) -> FloatArray:
        """The base system's shape (..., n) at restricted shapes q (..., m)."""
        q = self._shape(q, "q")
        return self.offset + q @ self.matrix.T

    @override
    def connection(self, r: ArrayLike) -> FloatArray:
        return self.base_system.connection(self.full_shape(r)) @ self.matrix

    def _base_has_closed_form(self):
        return type(self.base_system).connection_derivative is not LocomotionSystem.connection_derivative

    @override
    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(A_q, dA_q): the base's closed form pulled back, else central differences of
        :meth:`connection` along the m directions of the restriction (not the base's n)."""
        if not self._base_has_closed_form():
            return super().connection_derivative(r)
        A, dA = self.base_system.connection_derivative(self.full_shape(r))
        S = self.matrix
        return A @ S, np.einsum("...ijk,ja,kb->...iab", dA, S, S)

    @override
    def constraint_curvature(self, r: ArrayLike) -> FloatArray:
        """The pull-back of the base's curvature 2-form, ``F_q,ab = S_ia S_jb F_ij``; computed as the
        curvature of the restricted connection (the same thing: curvature commutes with pull-back),
        which needs differences along the m directions only, unless the base has a closed-form
        derivative or is itself two-dimensional (then its own curvature is pulled back)."""
        if not self._base_has_closed_form() and self.base_system.n_shape > self.n_shape:
            return super().constraint_curvature(r)
        F = self.base_system.constraint_curvature(self.full_shape(r))
        S = self.matrix
        if self.base_system.n_shape == 2:        # F is the (1, 2) component: F_ij = F eps_ij
            F = F[..., None, None] * np.array([[0.0, 1.0], [-1.0, 0.0]])
        F = np.einsum("...kij,ia,jb->...kab", F, S, S)
        return F[..., 0, 1] if self.n_shape == 2 else F

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        om = self.base_system.pfaffian(self.full_shape(r))
        return np.concatenate([om[..., :3], om[..., 3:] @ self.matrix], -1)

    @override
    def shape_metric(self, r: ArrayLike) -> FloatArray:
        M = self.base_system.shape_metric(self.full_shape(r))
        return self.matrix.T @ M @ self.matrix

    @override
    def singularity(self, r: ArrayLike) -> FloatArray:
        return self.base_system.singularity(self.full_shape(r))

    @override
    def is_singular(self, r: ArrayLike) -> BoolArray:
        return self.base_system.is_singular(self.full_shape(r))

    @override
    def parts(self) -> list[SystemPart]:
        return self.base_system.parts()

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        return self.base_system.part_poses(self.full_shape(r))

    def link_poses(self, r: ArrayLike) -> FloatArray:
        return cast(Any, self.base_system).link_poses(self.full_shape(r))

    def link_weights(self) -> FloatArray:
        return cast(Any, self.base_system).link_weights()

    @override
    def __repr__(self) -> str:
        return f"AffineRestriction({self.base_system!r}, matrix shape {self.matrix.shape})"


def shape_slice(system: LocomotionSystem, through: ArrayLike | None = None, axes: Any = (0, 1), *,
                limits: Any = None) -> AffineRestriction:
    """The two-dimensional slice of ``system``'s shape space through ``through`` along ``axes``.

    ``axes``: a pair of shape indices (i, j) (0-based): then the slice's shapes are (r_i, r_j)
    themselves and the other shape variables stay at their values in ``through`` (default the
    straight shape, zeros); or an (n, 2) matrix of two directions u, v: then r = through + a u + b v.
    The result is a system with two shape variables (an :class:`AffineRestriction`); a gait
    drawn in it is a gait of the full system lying in the slice.
    """
    n = trusted_dimension(system)
    r0 = np.zeros(n) if through is None else as_array(through, "through", (n,), what=f" (a shape of {system.name})")
    if r0.ndim != 1:
        raise ValueError(f"through must be one shape ({n},); got shape {r0.shape}")
    if np.ndim(axes) == 1 and len(axes) == 2 and all(isinstance(a, (int, np.integer)) and not isinstance(a, bool)
                                                    for a in axes):
        i, j = (check_int(a, "axes", minimum=0, maximum=n - 1, what=f" (shape indices 0..{n - 1})") for a in axes)
        if i == j:
            raise ValueError(f"axes must name two different shape variables; got {axes!r}")
        S = np.zeros((n, 2))
        S[i, 0] = S[j, 1] = 1.0
        r0 = r0.copy()
        r0[[i, j]] = 0.0
        names = (system.shape_names[i], system.shape_names[j])
        lim = limits or (system.shape_limits[i], system.shape_limits[j])
        fixed = ", ".join(f"{system.shape_names[k]}={r0[k]:.2g}" for k in range(n) if k not in (i, j))
        label = f"{system.name}: slice ({names[0]}, {names[1]})" + (f" at {fixed}" if fixed else "")
    else:
        S = as_array(axes, "axes", (2,), what=" (two shape indices, or an (n, 2) matrix of two directions)")
        if S.shape != (n, 2):
            raise ValueError(f"axes must be two shape indices or an ({n}, 2) matrix of directions; got {axes!r:.60}")
        if abs(np.linalg.det(S.T @ S)) < 1e-12:
            raise ValueError("axes: the two directions must be linearly independent")
        names, lim = ("a", "b"), limits or ((-np.pi, np.pi),) * 2
        label = f"{system.name}: slice through the plane of two directions"
    return AffineRestriction(system, S, r0, shape_names=names, shape_limits=lim, name=label)

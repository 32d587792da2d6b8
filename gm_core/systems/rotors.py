"""A rigid body in space turned by the rotors it carries (reaction wheels), on SO(3) (numpy only).

Beyond the draft, whose locomotors all move in the plane: the body's position is its orientation,
an element of SO(3) (:data:`gm_core.groups.SO3`, rotation-vector coordinates), its body velocity
is its angular velocity omega in its own frame, and its shape is the angles r_k of n rotors
relative to the body. Rotor k spins about the body-fixed unit axis a_k with axial moment of
inertia J_k; I is the inertia tensor of the whole (body and rotors) about its centre of mass.
Started at rest, the angular momentum stays zero:

    I omega + sum_k J_k a_k r_dot_k = 0,

the Pfaffian ``[I, J_1 a_1 ... J_n a_n]``, so ``omega = -A r_dot`` with ``A = I^-1 [J_k a_k]``
(3.10), constant: a satellite turns itself by spinning its wheels. Two rotors about different
axes driven round a closed cycle leave a net rotation (the bracket of so(3) at work), which
:func:`gm_core.systems.motion.net_displacement` integrates in SO(3). sysplotter's
``twin_rotor`` file is the case of two rotors on one axis, opposite ways, with J_k / I_zz = 1
(:mod:`gm_core.systems.catalog`).
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import SO3, LieGroup
from gm_core.systems.base import LocomotionSystem, SystemPart
from gm_core.validation import FloatArray, as_array

__all__ = ["Rotors"]


class Rotors(LocomotionSystem):
    """A body in space with rotors about body-fixed axes; shape = the rotor angles. See the module docstring."""

    position_group: ClassVar[LieGroup] = SO3
    row_names = ("omega_x", "omega_y", "omega_z")
    may_be_singular = False

    def __init__(self, axes: ArrayLike = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)), rotor_inertias: ArrayLike | None = None,
                 inertia: ArrayLike = ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)), *, name: str = "body with rotors") -> None:
        a = as_array(axes, "axes", (3,), what=" (one body-fixed rotor axis per row, (n, 3))")
        if a.ndim != 2 or not 1 <= a.shape[0] <= 64:
            raise ValueError(f"axes must have shape (n, 3) with 1 <= n <= 64 rotors; got shape {a.shape}")
        norms = np.linalg.norm(a, axis=-1)
        if np.any(norms < 1e-12) or np.any(norms > 1e12):
            raise ValueError("axes must be nonzero vectors (each rotor's axis; they are normalised)")
        n = a.shape[0]
        J = np.ones(n) if rotor_inertias is None else as_array(rotor_inertias, "rotor_inertias", what=" (one per rotor)")
        if J.shape != (n,) or np.any(J <= 0) or np.any(J > 1e12):
            raise ValueError(f"rotor_inertias must be {n} positive numbers (at most 1e12), one per rotor; got {J!r:.60}")
        inertia_matrix = as_array(inertia, "inertia", what=" (the 3 x 3 inertia tensor of the whole)")
        if inertia_matrix.shape != (3, 3) or not np.allclose(inertia_matrix, inertia_matrix.T, rtol=0, atol=1e-12 * np.abs(inertia_matrix).max()):
            raise ValueError(f"inertia must be a symmetric 3 x 3 matrix; got shape {inertia_matrix.shape}")
        if np.linalg.eigvalsh(inertia_matrix).min() <= 0:
            raise ValueError("inertia must be positive definite (an inertia tensor)")
        self.axes = a / norms[:, None]
        self.rotor_inertias = J.copy()
        self.inertia = inertia_matrix.copy()
        self.n_shape = n
        self.shape_names = tuple(f"rotor {k + 1}" for k in range(n))
        self.shape_limits = ((-np.pi, np.pi),) * n
        self.name = name
        self._A = np.linalg.solve(self.inertia, (self.rotor_inertias[:, None] * self.axes).T)       # (3, n)

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """``[I, J_1 a_1 ... J_n a_n]`` (..., 3, 3 + n): zero angular momentum."""
        r = self._shape(r)
        om = np.hstack([self.inertia, (self.rotor_inertias[:, None] * self.axes).T])
        return np.broadcast_to(om, r.shape[:-1] + om.shape).copy()

    @override
    def connection(self, r: ArrayLike) -> FloatArray:
        """The constant A = I^-1 [J_k a_k] (..., 3, n)."""
        r = self._shape(r)
        return np.broadcast_to(self._A, r.shape[:-1] + self._A.shape).copy()

    @override
    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(A, 0)``: the connection is constant."""
        A = self.connection(r)
        return A, np.zeros(A.shape + (self.n_shape,))

    @override
    def parts(self) -> list[SystemPart]:
        """None: the drawing layer draws bodies in the plane; this one turns in space."""
        return []

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        return np.zeros(self._shape(r).shape[:-1] + (0, 3))

    @override
    def __repr__(self) -> str:
        return f"Rotors(axes={self.axes.tolist()}, rotor_inertias={self.rotor_inertias.tolist()})"

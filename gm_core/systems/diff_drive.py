"""Differential-drive car, book section 3.2, (3.18)-(3.29) and fig. 3.3."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.systems.base import LocomotionSystem, SystemPart, rectangle_outline
from gm_core.validation import FloatArray, positive_number

__all__ = ["DifferentialDrive"]


class DifferentialDrive(LocomotionSystem):
    """Two independently driven wheels on one axle; shape r = (alpha1, alpha2), the wheel angles.

    Body frame at the centre of the axle, x forward. Wheel 1 is at +half_width (left of the
    heading), wheel 2 at -half_width, as in (3.20). Rolling without slipping or sliding (3.18)
    gives the Pfaffian (3.26) and the constant connection (3.29):
    ``xi = R/2 (a1' + a2', 0, (a2' - a1') / w)``.
    """

    name = "differential-drive car"
    shape_names = ("alpha1", "alpha2")

    def __init__(self, wheel_radius: float = 1.0, half_width: float = 1.0) -> None:
        self.wheel_radius = positive_number(wheel_radius, "wheel_radius")
        self.half_width = positive_number(half_width, "half_width")

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian (..., 3, 5) of (3.26): no slip at each wheel, no sideways slide."""
        r = self._shape(r)
        R, w = self.wheel_radius, self.half_width
        om = np.array([[1.0, 0.0, -w, -R, 0.0],
                       [1.0, 0.0, w, 0.0, -R],
                       [0.0, 1.0, 0.0, 0.0, 0.0]])
        return np.broadcast_to(om, r.shape[:-1] + (3, 5)).copy()

    @override
    def connection(self, r: ArrayLike) -> FloatArray:
        """Constant local connection (..., 3, 2), (3.29): [[-R/2, -R/2], [0, 0], [R/2w, -R/2w]]."""
        r = self._shape(r)
        R, w = self.wheel_radius, self.half_width
        A = np.array([[-R / 2, -R / 2], [0.0, 0.0], [R / (2 * w), -R / (2 * w)]])
        return np.broadcast_to(A, r.shape[:-1] + (3, 2)).copy()

    @override
    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(A (..., 3, 2), dA (..., 3, 2, 2))`` with ``dA[..., i, j, k] = d A_ij / d r_k``: zero, A is constant."""
        A = self.connection(r)
        return A, np.zeros(A.shape + (2,))

    @override
    def parts(self) -> list[SystemPart]:
        R, w = self.wheel_radius, self.half_width
        return [SystemPart("chassis", rectangle_outline(1.6 * w, 1.4 * w), "chassis"),
                SystemPart("wheel 1", rectangle_outline(2 * R, 0.25 * w), "wheel"),
                SystemPart("wheel 2", rectangle_outline(2 * R, 0.25 * w), "wheel")]

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        r = self._shape(r)
        w = self.half_width
        P = np.array([[-0.3 * w, 0.0, 0.0], [0.0, w, 0.0], [0.0, -w, 0.0]])
        return np.broadcast_to(P, r.shape[:-1] + (3, 3)).copy()

    @override
    def __repr__(self) -> str:
        return f"DifferentialDrive(wheel_radius={self.wheel_radius:g}, half_width={self.half_width:g})"

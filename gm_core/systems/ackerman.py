"""Ackerman-steered car as a kinematic bicycle, book (3.9) and exercise 3.3a."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.systems.base import LocomotionSystem, SystemPart, rectangle_outline
from gm_core.validation import FloatArray, positive_number

__all__ = ["Ackerman"]


class Ackerman(LocomotionSystem):
    """Rear-wheel-drive kinematic bicycle; shape r = (alpha1, alpha2) = (rear wheel angle, steering angle).

    Body frame at the centre of the rear axle, x forward; the steered front wheel sits at
    (wheelbase, 0) turned by alpha2. Constraints: the rear wheel rolls without slipping
    (xi^x = R a1') or sliding (xi^y = 0), and the front wheel does not slide sideways
    (-sin a2 xi^x + cos a2 (xi^y + L xi^theta) = 0). Hence
    ``xi = (R a1', 0, (R/L) tan(a2) a1')``, which is (3.9) with R = L = 1. At a2 = +-pi/2 the
    front wheel stands across the car and the connection does not exist (NaN).
    """

    name = "Ackerman car (kinematic bicycle)"
    shape_names = ("alpha1", "alpha2")
    may_be_singular = True
    singular_description = "the steering angle is +-pi/2, front wheel perpendicular to the car"
    shape_limits = ((-np.pi, np.pi), (-1.3, 1.3))

    def __init__(self, wheel_radius: float = 1.0, wheelbase: float = 1.0) -> None:
        self.wheel_radius = positive_number(wheel_radius, "wheel_radius")
        self.wheelbase = positive_number(wheelbase, "wheelbase")

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian (..., 3, 5): rear no-slip, rear no-slide, front no-slide."""
        r = self._shape(r)
        R, L = self.wheel_radius, self.wheelbase
        a2 = r[..., 1]
        om = np.zeros(r.shape[:-1] + (3, 5))
        om[..., 0, 0] = 1.0
        om[..., 0, 3] = -R
        om[..., 1, 1] = 1.0
        om[..., 2, 0] = -np.sin(a2)
        om[..., 2, 1] = np.cos(a2)
        om[..., 2, 2] = L * np.cos(a2)
        return om

    @override
    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(A (..., 3, 2), dA (..., 3, 2, 2))`` with ``dA[..., i, j, k] = d A_ij / d r_k``; NaN where A is.

        Only A_theta,1 = -(R/L) tan(a2) depends on the shape: d/d a2 = -(R/L) / cos(a2)^2.
        """
        r = self._shape(r)
        A = self.connection(r)
        R, L = self.wheel_radius, self.wheelbase
        dA = np.zeros(A.shape + (2,))
        with np.errstate(divide="ignore", invalid="ignore"):
            dA[..., 2, 0, 1] = -(R / L) / np.cos(r[..., 1]) ** 2
        dA[~np.isfinite(A).all(axis=(-1, -2))] = np.nan
        return A, dA

    @override
    def parts(self) -> list[SystemPart]:
        R, L = self.wheel_radius, self.wheelbase
        return [SystemPart("chassis", rectangle_outline(1.3 * L, 0.45 * L), "chassis"),
                SystemPart("rear wheel", rectangle_outline(min(2 * R, 0.4 * L), 0.12 * L), "wheel"),
                SystemPart("front wheel", rectangle_outline(min(2 * R, 0.4 * L), 0.12 * L), "wheel")]

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        r = self._shape(r)
        L = self.wheelbase
        P = np.zeros(r.shape[:-1] + (3, 3))
        P[..., 0, 0] = L / 2
        P[..., 2, 0] = L
        P[..., 2, 2] = r[..., 1]
        return P

    @override
    def __repr__(self) -> str:
        return f"Ackerman(wheel_radius={self.wheel_radius:g}, wheelbase={self.wheelbase:g})"

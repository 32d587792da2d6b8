"""The interface shared by every locomotion system of chapter 3 (numpy only).

A system knows its Pfaffian ``omega(r)`` (..., 3, 3 + n) (3.11)-(3.13) and so its local
connection ``A(r) = omega_xi^-1 omega_r`` (3.17), with body velocity ``xi = -A(r) r_dot`` (3.10).
For the drawing layer it also lists its rigid parts (:class:`SystemPart`, an outline in the part's own
frame) and where they sit in the system's body frame at a shape (:meth:`part_poses`).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.systems.connection import SINGULAR_TOL, connection_from_pfaffian, pfaffian_determinant
from gm_core.systems.motion import body_velocity, curvature_form, fd_connection_derivative
from gm_core.validation import BoolArray, FloatArray, as_array

__all__ = ["LocomotionSystem", "SystemPart", "ellipse_outline", "rectangle_outline"]


@dataclass(frozen=True)
class SystemPart:
    """A rigid part for drawing: ``outline (k, 2)`` in its own frame; ``kind`` is a style hint."""

    name: str
    outline: np.ndarray
    kind: str = "link"


def rectangle_outline(length: float, width: float) -> FloatArray:
    """Outline (4, 2) of a length x width rectangle centred on its frame, long side along x."""
    a, b = length / 2, width / 2
    return np.array([[-a, -b], [a, -b], [a, b], [-a, b]], dtype=float)


def ellipse_outline(a: float, b: float, n: int = 48) -> FloatArray:
    """Outline (n, 2) of an ellipse with semi-axes a (along x) and b, centred on its frame."""
    s = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.stack([a * np.cos(s), b * np.sin(s)], -1)


class LocomotionSystem:
    """A symmetric linear-kinematic locomotor on SE(2) with an n-dimensional shape space."""

    name = "system"
    n_shape = 2
    shape_names: tuple = ("alpha1", "alpha2")
    #: True when det(omega_xi) can vanish, so gaits must be checked for singular shapes.
    may_be_singular = False
    singular_description = "never singular"
    #: Suggested shape-space window for plots, ((lo1, hi1), (lo2, hi2)).
    shape_limits = ((-np.pi, np.pi), (-np.pi, np.pi))
    #: Row labels of the connection: body x (longitudinal), y (lateral), theta (rotation).
    row_names = ("x", "y", "theta")

    # -- to implement -----------------------------------------------------------------------
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian ``omega(r)`` (..., 3, 3 + n): ``omega [xi; r_dot] = 0`` on allowed motions."""
        raise NotImplementedError

    def parts(self) -> list[SystemPart]:
        """The rigid parts to draw (list of :class:`SystemPart`)."""
        raise NotImplementedError

    def part_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., P, 3) of the parts relative to the system body frame at shape r."""
        raise NotImplementedError

    # -- shared -----------------------------------------------------------------------------
    def _shape(self, r, name="r"):
        names = ", ".join(self.shape_names)
        return as_array(r, name, (self.n_shape,), what=f" (the shape ({names}) of {self.name})")

    def connection(self, r: ArrayLike) -> FloatArray:
        """Local connection A(r) (..., 3, n) with xi = -A r_dot, (3.10), (3.17); NaN at singular shapes."""
        return connection_from_pfaffian(self.pfaffian(r))

    def body_velocity(self, r: ArrayLike, r_dot: ArrayLike) -> FloatArray:
        """Body velocity xi = -A(r) r_dot (..., 3), book (3.10)."""
        return body_velocity(self, r, r_dot)

    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(A (..., 3, n), dA (..., 3, n, n))``, ``dA[..., i, j, k] = d A_ij / d r_k``.

        Central differences (:func:`gm_core.systems.motion.fd_connection_derivative`) unless a system
        has a closed form and overrides this.
        """
        return fd_connection_derivative(self, r)

    def constraint_curvature(self, r: ArrayLike) -> FloatArray:
        """Constraint curvature D(-A): (..., 3) for a 2-D shape space, else the 2-form (..., 3, n, n).

        ``F_ij = -(d_i A_j - d_j A_i) + [A_i, A_j]`` (:func:`gm_core.systems.motion.curvature_form`);
        for two shape variables the one component F_12 is returned as (..., 3). NaN at singular shapes.
        """
        F = curvature_form(*self.connection_derivative(r))
        return F[..., 0, 1] if self.n_shape == 2 else F

    def shape_metric(self, r: ArrayLike) -> FloatArray:
        """Cost metric on shape space (..., n, n); systems without a physical cost refuse (TypeError)."""
        raise TypeError(f"system {self.name!r} has no physical cost metric (no drag or mass matrix); "
                        "pass metric='euclidean' or a callable r -> M(r)")

    def body_frames(self, bounds: Any = None, *, n: int | None = None, centre_of_mass: bool = True,
                    minimum_perturbation: bool = True) -> dict[str, LocomotionSystem]:
        """The body frames this system can be seen from, {name: system}, its own first.

        This one alone unless a system offers more: systems made of links add, when asked, their
        centre of mass with the mean link orientation (``centre_of_mass``) and Hatton's
        minimum-perturbation frame over ``bounds`` with ``n`` nodes per axis
        (``minimum_perturbation``); a system whose physics defines several frames (the floating
        snake) always lists them.
        """
        return {"own frame": self}

    def singularity(self, r: ArrayLike) -> FloatArray:
        """Scaled det(omega_xi) (...,) in [-1, 1]; zero exactly at singular shapes."""
        return pfaffian_determinant(self.pfaffian(r)[..., :3])

    def is_singular(self, r: ArrayLike) -> BoolArray:
        """Boolean (...,): True where the local connection does not exist (det omega_xi = 0)."""
        return ~(np.abs(self.singularity(r)) > SINGULAR_TOL)

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"

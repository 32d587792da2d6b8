"""The interface shared by every locomotion system of chapter 3 (numpy only).

A system knows its Pfaffian ``omega(r)`` (..., 3, 3 + n) (3.11)-(3.13) and so its local
connection ``A(r) = omega_xi^-1 omega_r`` (3.17), with body velocity ``xi = -A(r) r_dot`` (3.10).
For the drawing layer it also lists its rigid parts (:class:`SystemPart`, an outline in the part's own
frame) and where they sit in the system's body frame at a shape (:meth:`part_poses`).
"""
from __future__ import annotations

from abc import ABCMeta, abstractmethod
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import SE2, LieGroup
from gm_core.systems.connection import (
    SINGULAR_TOL,
    connection_from_pfaffian,
    pfaffian_determinant,
    shape_space_metric,
)
from gm_core.systems.motion import (
    CheckedSystem,
    body_velocity,
    curvature_form,
    fd_connection_derivative,
    validate_system,
)
from gm_core.validation import BoolArray, FloatArray, as_array

__all__ = ["LocomotionSystem", "BalancedSystem", "SystemPart", "SystemMeta", "ellipse_outline", "rectangle_outline"]


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


class SystemMeta(ABCMeta):
    """The metaclass of :class:`LocomotionSystem`: a system is checked once, when it is built.

    After ``__init__`` returns, :func:`gm_core.systems.motion.validate_system` checks the new
    instance (an integer ``n_shape`` >= 1, a callable ``connection``, ``singularity`` if it
    ``may_be_singular``) and its ``shape_names`` and ``shape_limits`` have one entry per shape
    variable (TypeError or ValueError naming the class). From then on
    :func:`~gm_core.systems.motion.check_system` trusts the instance and returns at once.
    """

    @override
    def __call__(cls, *args: Any, **kwargs: Any) -> Any:
        system = super().__call__(*args, **kwargs)
        n = validate_system(system, f"{cls.__name__}(...)")
        for attr in ("shape_names", "shape_limits"):
            value = getattr(system, attr)
            if len(value) != n:
                raise ValueError(f"{cls.__name__}(...): {attr} has {len(value)} entries for {n} shape variables")
        return system


class LocomotionSystem(CheckedSystem, metaclass=SystemMeta):
    """A symmetric linear-kinematic locomotor on SE(2) with an n-dimensional shape space.

    An abstract base class: a system gives its Pfaffian (:meth:`pfaffian`) and its rigid parts for
    drawing (:meth:`parts`, :meth:`part_poses`); everything else has a default built on them.
    It is checked once when it is built (:class:`SystemMeta`).
    """

    name: str = "system"
    #: The group the position lives in: SE(2) for every locomotor in the plane (SO(3) for a body
    #: turning in space); gaits are integrated in it and the curvature takes its bracket.
    position_group: ClassVar[LieGroup] = SE2
    #: Dimension of the position group (the rows of the connection), the same for every system.
    n_position: ClassVar[int] = 3
    #: Dimension n of the shape space (fixed per class for most systems, set per instance for chains).
    n_shape: int = 2
    shape_names: tuple[str, ...] = ("alpha1", "alpha2")
    #: True when det(omega_xi) can vanish, so gaits must be checked for singular shapes.
    may_be_singular: bool = False
    singular_description: str = "never singular"
    #: Suggested shape-space window for plots, ((lo1, hi1), (lo2, hi2)).
    shape_limits: tuple[tuple[float, float], ...] = ((-np.pi, np.pi), (-np.pi, np.pi))
    #: Row labels of the connection: body x (longitudinal), y (lateral), theta (rotation).
    row_names: tuple[str, ...] = ("x", "y", "theta")

    # -- to implement -----------------------------------------------------------------------
    @abstractmethod
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian ``omega(r)`` (..., 3, 3 + n): ``omega [xi; r_dot] = 0`` on allowed motions."""

    @abstractmethod
    def parts(self) -> list[SystemPart]:
        """The rigid parts to draw (list of :class:`SystemPart`)."""

    @abstractmethod
    def part_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., P, 3) of the parts relative to the system body frame at shape r."""

    # -- shared -----------------------------------------------------------------------------
    def _shape(self, r: ArrayLike, name: str = "r") -> FloatArray:
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
        F = curvature_form(*self.connection_derivative(r), group=self.position_group)
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

    @override
    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


class BalancedSystem(LocomotionSystem):
    """A system whose constraint is a balance: zero net drag wrench, or zero momentum from rest.

    It gives its system matrix ``metric(r)`` (..., 3 + n, 3 + n) on (xi, r_dot), ``sum J^T M J`` over
    its parts, (3.39), (3.47); everything else is written once here: the Pfaffian is its top three
    rows (the net wrench or momentum), the connection follows from it (3.40), and the cost metric on
    shape space is ``[-A; I]^T M [-A; I]`` (the power dissipated, or twice the kinetic energy).
    A subclass may override :meth:`pfaffian` with a cheaper route to the same rows.
    """

    @abstractmethod
    def metric(self, r: ArrayLike) -> FloatArray:
        """System matrix (..., 3 + n, 3 + n) on (xi, r_dot): drag or mass matrix."""

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian (..., 3, 3 + n): the top rows of :meth:`metric` (total wrench or momentum = 0)."""
        return self.metric(r)[..., :3, :]

    @override
    def connection(self, r: ArrayLike) -> FloatArray:
        """Local connection (..., 3, n): xi = -A r_dot (3.10) from the Pfaffian, (3.40)."""
        return connection_from_pfaffian(self.pfaffian(r))

    @override
    def shape_metric(self, r: ArrayLike) -> FloatArray:
        """Cost metric on shape space M(r) = [-A; I]^T D [-A; I] (..., n, n) (power or twice kinetic energy)."""
        D = self.metric(r)
        return shape_space_metric(D, connection_from_pfaffian(D[..., :3, :]))

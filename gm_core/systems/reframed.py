"""Body frames as objects, and a system seen from another body frame, by composition (numpy only).

If the new body frame sits at ``beta(r)`` (an SE(2) pose, (..., 3)) relative to a system's body
frame, the new position is ``g~ = g beta(r)`` and its body velocity is
``xi~ = Ad_{beta^-1} xi + beta^-1 beta_dot`` (the velocity conversions of section 1.5), so with
``xi = -A r_dot`` (3.10) the connection seen from the new frame is

    A~(r) = Ad_{beta^-1} A(r) - B_beta(r),      B_beta = T_beta L_{beta^-1} d beta / dr,

(``B_beta`` is the body-velocity Jacobian of beta). The curvature transforms as
``D(-A~) = Ad_{beta^-1} D(-A)`` and net displacements as ``g~(T) = beta(r0)^-1 g(T) beta(r0)``.

* :class:`BodyFrame`: a frame ``beta(r)`` with its body Jacobian and the shapes where it is defined;
* :class:`PoseFrame`: one from a callable (Jacobian given or by central differences);
* :class:`Reframed`: a system seen from a :class:`BodyFrame`: a real system type (connection,
  curvature, parts, metric, singular set), built from the base system and the frame.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import SE2
from gm_core.systems.base import LocomotionSystem, SystemPart
from gm_core.systems.motion import trusted_dimension
from gm_core.validation import BoolArray, FloatArray

__all__ = ["BodyFrame", "PoseFrame", "CentreOfMassFrame", "Reframed", "body_jacobian"]


def body_jacobian(beta: ArrayLike, dbeta: ArrayLike) -> FloatArray:
    """Body-velocity Jacobian ``(..., 3, n)`` of a pose ``beta (..., 3)`` from ``d beta / dr (..., 3, n)``:
    ``[R(-theta) d(x, y)/dr; d theta/dr]`` (T_beta L_{beta^-1} applied to each column)."""
    beta, dbeta = np.asarray(beta, dtype=float), np.asarray(dbeta, dtype=float)
    c, s = np.cos(beta[..., 2])[..., None], np.sin(beta[..., 2])[..., None]
    out = np.empty(np.broadcast_shapes(beta.shape[:-1], dbeta.shape[:-2]) + dbeta.shape[-2:])
    out[..., 0, :] = c * dbeta[..., 0, :] + s * dbeta[..., 1, :]
    out[..., 1, :] = -s * dbeta[..., 0, :] + c * dbeta[..., 1, :]
    out[..., 2, :] = dbeta[..., 2, :]
    return out


class BodyFrame:
    """A choice of body frame: its pose ``beta(r)`` relative to a system's own body frame.

    Subclasses give :meth:`pose` and :meth:`jacobian` (the body-velocity Jacobian B_beta) and, if
    the frame is defined only on part of shape space, :meth:`contains` and ``domain_description``.
    """

    name = "body frame"
    domain_description = ""

    def pose(self, r: ArrayLike) -> FloatArray:
        """Pose (..., 3) of the frame relative to the base system's body frame."""
        raise NotImplementedError

    def jacobian(self, r: ArrayLike) -> FloatArray:
        """Body-velocity Jacobian B_beta (..., 3, n): beta^-1 beta_dot = B_beta r_dot."""
        raise NotImplementedError

    def pose_and_jacobian(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(pose(r), jacobian(r))``: what a connection needs; a frame whose Jacobian is built
        from its pose overrides this to compute the pose once."""
        return self.pose(r), self.jacobian(r)

    def contains(self, r: ArrayLike) -> BoolArray:
        """Boolean (...,): where the frame is defined (everywhere unless a subclass says otherwise)."""
        return np.ones(np.shape(r)[:-1], dtype=bool)


class PoseFrame(BodyFrame):
    """A frame from a callable ``beta(r) -> (..., 3)``; ``jacobian(r) = d beta/dr (..., 3, n)`` or central differences."""

    def __init__(self, beta: Callable[[Any], ArrayLike],
                 jacobian: Callable[[Any], ArrayLike] | None = None, n_shape: int | None = None,
                 name: str = "other frame") -> None:
        if not callable(beta):
            raise TypeError(f"beta must be a callable r -> (..., 3) pose; got {type(beta).__name__}")
        if jacobian is not None and not callable(jacobian):
            raise TypeError(f"jacobian must be a callable r -> (..., 3, n) or None; got {type(jacobian).__name__}")
        self._beta, self._jac, self.name = beta, jacobian, name

    @override
    def pose(self, r: ArrayLike) -> FloatArray:
        return np.asarray(self._beta(r), dtype=float)

    def derivative(self, r: ArrayLike) -> FloatArray:
        """d beta / d r (..., 3, n): the given callable, else central differences (step 1e-6)."""
        if self._jac is not None:
            return np.asarray(self._jac(r), dtype=float)
        r = np.asarray(r, dtype=float)
        h, n = 1e-6, r.shape[-1]
        cols = [(self.pose(r + h * e) - self.pose(r - h * e)) / (2 * h) for e in np.eye(n)]
        return np.stack(cols, -1)

    @override
    def jacobian(self, r: ArrayLike) -> FloatArray:
        return self.pose_and_jacobian(r)[1]

    @override
    def pose_and_jacobian(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        beta = self.pose(r)
        return beta, body_jacobian(beta, self.derivative(r))


class CentreOfMassFrame(PoseFrame):
    """The centre of mass of a system made of links, with the weighted mean link orientation.

    Pose: ``sum_i w_i P_i(r)`` over the link poses in the system's body frame, with weights
    ``system.link_weights()`` (masses, else lengths); its Jacobian by central differences.
    Hatton & Choset (2011) show this frame is close to the minimum-perturbation one for
    three-link swimmers.
    """

    def __init__(self, system: LocomotionSystem) -> None:
        weights = getattr(system, "link_weights", None)
        if not callable(weights) or not callable(getattr(system, "link_poses", None)):
            raise TypeError(f"system must be made of links (link_poses(r) and link_weights()); got {system!r:.80}")
        w = np.asarray(weights(), dtype=float)
        links = cast(Any, system)                  # made of links: checked above
        super().__init__(lambda r: np.einsum("i,...ij->...j", w, links.link_poses(r)), name="centre of mass")


class Reframed(LocomotionSystem):
    """``base`` seen from the body frame ``frame`` (a :class:`BodyFrame`).

    Works wherever a system does (connection, net_displacement, curvature, metrics, drawing):
    its parts are the base's, placed with ``beta^-1 * base.part_poses(r)``; where the frame is
    not defined the connection is NaN and the shape counts as singular.
    """

    def __init__(self, base: LocomotionSystem, frame: BodyFrame, name: str | None = None) -> None:
        trusted_dimension(base, "base")
        if not isinstance(frame, BodyFrame):
            raise TypeError(f"frame must be a gm_core.systems.BodyFrame; got {type(frame).__name__}")
        self.base_system, self.frame = base, frame
        self.n_shape = base.n_shape
        self.shape_names = base.shape_names
        self.shape_limits = getattr(frame, "bounds", None) or base.shape_limits
        partial = type(frame).contains is not BodyFrame.contains
        self.may_be_singular = base.may_be_singular or partial
        self.singular_description = (frame.domain_description if partial and not base.may_be_singular
                                     else base.singular_description)
        self.name = name or f"{base.name} ({frame.name})"

    def beta(self, r: ArrayLike) -> FloatArray:
        """Pose (..., 3) of the new body frame in the base system's body frame."""
        return self.frame.pose(self._shape(r))

    @override
    def connection(self, r: ArrayLike) -> FloatArray:
        """A~ = Ad_{beta^-1} A - B_beta, (..., 3, n); NaN where the frame is undefined."""
        r = self._shape(r)
        beta, B = self.frame.pose_and_jacobian(r)
        A = SE2.Ad_inv(beta) @ self.base_system.connection(r) - B
        return self._mask(r, A, 2)

    @override
    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(A~, dA~) by central differences of :meth:`connection` (the frame's Jacobian is smooth)."""
        from gm_core.systems.motion import fd_connection_derivative

        return fd_connection_derivative(self, r)

    @override
    def constraint_curvature(self, r: ArrayLike) -> FloatArray:
        """D(-A~) = Ad_{beta^-1} D(-A) (gauge covariance: no second derivative of beta is needed)."""
        r = self._shape(r)
        F = self.base_system.constraint_curvature(r)
        b = self.frame.pose(r)
        # einsum, not matvec: a base curvature that is NaN (outside a measured table) stays NaN here
        F = np.einsum("...ij,...j->...i" if self.n_shape == 2 else "...ij,...jkl->...ikl", SE2.Ad_inv(b), F)
        return self._mask(r, F, 1 if self.n_shape == 2 else 3)

    def _mask(self, r, X, tail):
        inside = self.frame.contains(r)
        if np.all(inside):
            return X
        return np.where(inside.reshape(inside.shape + (1,) * tail), X, np.nan)

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian (..., 3, 3 + n) in the new frame: ``omega [xi; r_dot]`` with xi = Ad_beta (xi~ - B_beta r_dot)
        (the body velocity of g~ = g beta is xi~ = Ad_{beta^-1} xi + B_beta r_dot)."""
        r = self._shape(r)
        om = self.base_system.pfaffian(r)
        b, B = self.frame.pose_and_jacobian(r)
        Ad = SE2.Ad(b)
        out = np.empty(np.broadcast_shapes(om.shape, Ad.shape[:-2] + om.shape[-2:]))
        out[..., :3] = om[..., :3] @ Ad
        out[..., 3:] = om[..., 3:] - om[..., :3] @ Ad @ B
        return self._mask(r, out, 2)

    @override
    def shape_metric(self, r: ArrayLike) -> FloatArray:
        """The cost metric on shape space (..., n, n): the base's (it does not depend on the body frame)."""
        return self.base_system.shape_metric(r)

    @override
    def singularity(self, r: ArrayLike) -> FloatArray:
        r = self._shape(r)
        inside = self.frame.contains(r)
        if not self.base_system.may_be_singular:   # only the frame's edge: skip the base's costly Pfaffian
            return inside.astype(float)
        return np.where(inside, self.base_system.singularity(r), 0.0)

    @override
    def is_singular(self, r: ArrayLike) -> BoolArray:
        r = self._shape(r)
        return ~self.frame.contains(r) | self.base_system.is_singular(r)

    @override
    def parts(self) -> list[SystemPart]:
        return self.base_system.parts()

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        r = self._shape(r)
        return SE2.compose(SE2.inverse(self.frame.pose(r))[..., None, :], self.base_system.part_poses(r))

    def link_poses(self, r: ArrayLike) -> FloatArray:
        """Link poses (..., N, 3) in the new frame (for systems made of links)."""
        r = self._shape(r)
        return SE2.compose(SE2.inverse(self.frame.pose(r))[..., None, :], cast(Any, self.base_system).link_poses(r))

    def link_weights(self) -> FloatArray:
        return cast(Any, self.base_system).link_weights()

    @override
    def body_frames(self, bounds: Any = None, *, n: int | None = None, centre_of_mass: bool = True,
                    minimum_perturbation: bool = True) -> dict[str, LocomotionSystem]:
        return self.base_system.body_frames(bounds, n=n, centre_of_mass=centre_of_mass,
                                            minimum_perturbation=minimum_perturbation)

    @override
    def __repr__(self) -> str:
        return f"Reframed({self.base_system!r}, {self.frame.name!r})"


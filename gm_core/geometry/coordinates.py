"""Choice of body frame: centre-of-mass and Hatton's minimum-perturbation coordinates of a system.

The frame machinery is in :mod:`gm_core.systems.reframed` (a :class:`~gm_core.systems.Reframed`
system is the base system seen from a :class:`~gm_core.systems.BodyFrame`, built by
composition) and the finite-element solver of the minimum-perturbation frame, for a box of
any dimension, in :mod:`gm_core.systems.minimum_perturbation`. Here are the functions the
notebooks call: :func:`reframe`, :func:`centre_of_mass`, :func:`centre_of_mass_coordinates`,
:func:`drift_and_turn`, :func:`minimum_perturbation_coordinates`.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups import SE2
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.gaits import GaitLike, as_gait
from gm_core.systems.minimum_perturbation import MinimumPerturbationFrame
from gm_core.systems.motion import net_displacement, trusted_dimension
from gm_core.systems.reframed import CentreOfMassFrame, PoseFrame, Reframed
from gm_core.validation import FloatArray

__all__ = ["reframe", "centre_of_mass", "centre_of_mass_coordinates", "drift_and_turn",
           "minimum_perturbation_coordinates"]


def reframe(system: LocomotionSystem, beta: Callable[[Any], ArrayLike],
            jacobian: Callable[[Any], ArrayLike] | None = None, name: str | None = None) -> Reframed:
    """``system`` seen from the body frame at ``beta(r)`` (..., 3): a :class:`Reframed` system.

    ``jacobian(r)`` = d beta / dr (..., 3, n), or None for central differences.
    """
    trusted_dimension(system)
    frame = PoseFrame(beta, jacobian, name="other frame")
    return Reframed(system, frame, name=name)


def centre_of_mass(system: LocomotionSystem, r: ArrayLike) -> FloatArray:
    """Weighted mean ``(..., 3)`` of the link poses of a ``system`` made of links at shapes ``r``,
    in its body frame: (x, y) the centre of mass, theta the mean link orientation.

    Links are weighted by ``system.link_weights()``: mass for the floating snake, else length
    (uniform slender links, as for the swimmers).
    """
    trusted_dimension(system)
    return CentreOfMassFrame(system).pose(r)


def centre_of_mass_coordinates(system: LocomotionSystem) -> Reframed:
    """A ``system`` made of links seen from its centre of mass with the mean link orientation
    (:class:`~gm_core.systems.CentreOfMassFrame`)."""
    trusted_dimension(system)
    return Reframed(system, CentreOfMassFrame(system), name=f"{system.name} (centre of mass, mean orientation)")


def drift_and_turn(system: LocomotionSystem, gait: GaitLike) -> tuple[float, float]:
    """(net turn angle, distance moved by the centre of mass) over one cycle of ``gait``.

    The shape is the same at the start and the end of a cycle, so the centre of mass sits at the
    same point c of the body frame; the net displacement g(T) carries it from c to g(T) c. Both
    numbers are independent of the choice of body frame.
    """
    trusted_dimension(system)
    CentreOfMassFrame(system)
    gait = as_gait(gait)
    gT = net_displacement(system, gait)
    c = centre_of_mass(system, gait(np.array([0.0]))[0])[:2]
    return float(gT[2]), float(np.linalg.norm(SE2.act_on_points(gT, c) - c))


def minimum_perturbation_coordinates(system: LocomotionSystem, bounds: Any = None, n: int | None = None, *,
                                     reference: ArrayLike | None = None) -> Reframed:
    """Hatton's minimum-perturbation body frame of ``system`` over the box ``bounds``: a :class:`Reframed` system.

    Minimises ``int |A~_theta|^2`` (a Neumann-Poisson problem: A~_theta divergence-free with no
    flux through the boundary), then ``int |A~_x|^2 + |A~_y|^2`` given beta_theta, with
    multilinear finite elements on ``n`` nodes per axis (default 33 in two dimensions, 13 in
    three, 9 in four) and 2 Gauss points per axis and cell. ``bounds``: one (lo, hi) per shape
    variable, default the system's ``shape_limits``; ``reference``: the shape where beta = 0
    (default the origin if inside, else the centre). The result is a system: ``.frame`` is the
    :class:`~gm_core.systems.MinimumPerturbationFrame` (bounds, nodes, beta_nodes, reference,
    discrete_divergence), ``.beta(r)`` its pose; outside the box its connection is NaN. Raises
    SingularShapeError if the box contains singular shapes and ValueError, with the node count,
    if the grid is too large to be feasible (see ``MAX_NODES``).
    """
    frame = MinimumPerturbationFrame.fit(system, bounds, n, reference=reference)
    return Reframed(system, frame, name=f"{system.name} (minimum perturbation)")



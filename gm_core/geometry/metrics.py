"""Cost metrics on shape space, path length and efficiency of gaits (numpy only).

For a system whose motions cost energy through a symmetric matrix on the full velocity
``(xi, r_dot)`` -- the drag matrix of the low-Reynolds swimmer (power dissipated) or the mass
matrix of the floating snake and the high-Reynolds swimmer (kinetic energy) -- the cost seen on
shape space alone follows by substituting the constraint ``xi = -A(r) r_dot`` (3.10):

    M(r) = [-A; I]^T  D(r)  [-A; I]       (n x n),

the metric used by Hatton and co-workers (sysplotter: drag per unit length 1 along a link and
``drag_ratio`` across it, so each link contributes diag(L, k L, k L^3 / 12)).
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.geometry.curvature import closed_gait
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.gaits import GaitLike
from gm_core.systems.motion import check_gait, net_displacement, trusted_dimension
from gm_core.validation import FloatArray, as_array

__all__ = ["dissipation_metric", "path_length", "efficiency", "metric_function"]


def dissipation_metric(system: LocomotionSystem, r: ArrayLike) -> FloatArray:
    """Shape-space cost metric M(r) (..., n, n) = [-A; I]^T D [-A; I] (power or kinetic energy).

    ``D`` is the system's drag matrix (low Re: the power is ``r_dot^T M r_dot``) or its mass
    matrix (floating snake, high Re: twice the kinetic energy): the system's ``shape_metric``
    (:func:`gm_core.systems.connection.shape_space_metric`). It does not depend on the choice of body
    frame, so a system seen from other coordinates gives its base's. TypeError for a system
    with no physical cost.
    """
    n = trusted_dimension(system)
    r = as_array(r, "r", (n,), what=f" (a shape of {system.name})")
    if not isinstance(system, LocomotionSystem):
        raise TypeError(f"system {getattr(system, 'name', system)!r} has no physical cost metric; pass "
                        "metric='euclidean' or a callable r -> M(r)")
    return system.shape_metric(r)


def metric_function(system: LocomotionSystem, metric: Any = None) -> Callable[[Any], FloatArray]:
    """A callable r -> M(r) (..., n, n): the system's own metric (None), the identity ('euclidean'), or ``metric``."""
    if metric is None:
        dissipation_metric(system, np.zeros(system.n_shape))      # fails early if there is none
        return lambda r: dissipation_metric(system, r)
    if isinstance(metric, str):
        if metric != "euclidean":
            raise ValueError(f"metric must be None, 'euclidean' or a callable r -> M(r); got {metric!r}")
        n = system.n_shape
        return lambda r: np.broadcast_to(np.eye(n), np.shape(r)[:-1] + (n, n))
    if not callable(metric):
        raise TypeError(f"metric must be None, 'euclidean' or a callable r -> M(r); got {type(metric).__name__}")
    return metric


def path_length(system: LocomotionSystem, gait: GaitLike, *, metric: Any = None, samples: int | None = None,
                check: bool = True) -> float:
    """Length (float) of the gait in the cost metric: ``int_0^T sqrt(r_dot^T M(r) r_dot) dt``.

    ``metric=None`` uses :func:`dissipation_metric`; ``'euclidean'`` the identity. Trapezoidal
    rule over the period (spectral for smooth periodic gaits): 4096 samples unless given.
    """
    trusted_dimension(system)
    gait = closed_gait(gait, system)
    Mf = metric_function(system, metric)
    if check:
        check_gait(system, gait)
    n = 4096 if samples is None else int(samples)
    if n < 8:
        raise ValueError(f"samples must be an integer >= 8; got {samples!r}")
    t = np.arange(n) * (gait.period / n)
    v = gait.velocity(t)
    M = Mf(gait(t))
    speed2 = np.einsum("ti,tij,tj->t", v, M, v)
    return float(np.sqrt(np.maximum(speed2, 0.0)).sum() * gait.period / n)


def efficiency(system: LocomotionSystem, gait: GaitLike, *, metric: Any = None, check: bool = True,
               samples: int | None = None, displacement: ArrayLike | None = None) -> float:
    """Efficiency (float): translation ``|(x, y) of g(T)|`` per unit path length in the cost metric.

    ``samples`` as for :func:`path_length`. ``displacement``: g(T) (3,) when it is already known
    (the last pose of a :func:`~gm_core.systems.motion.trajectory` a live panel draws), instead of
    :func:`~gm_core.systems.motion.net_displacement`.
    """
    trusted_dimension(system)
    gait = closed_gait(gait, system)
    L = path_length(system, gait, metric=metric, check=check, samples=samples)
    if displacement is None:
        g = net_displacement(system, gait, check=False)
    else:
        g = as_array(displacement, "displacement", (3,), what=" (the net displacement g(T) = (x, y, theta))")
    return float(np.hypot(g[0], g[1]) / L)

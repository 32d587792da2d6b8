"""Pacing (book section 3.1): a change of pace along a shape path, and paths run at a constant rate.

Kinematic locomotion does not care how fast a path is run (fig. 3.1's commuting square): these are
the re-timings the pacing panel and :func:`gm_core.systems.motion.drive` use. numpy only.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.systems.gaits import Gait
from gm_core.validation import as_array, positive_number, real_number

__all__ = [
    "constant_rate_path", "sine_pacing",
]


def sine_pacing(a: float, period: float = 1.0) -> tuple[Callable[[Any], Any], Callable[[Any], Any]]:
    """(tau, tau_dot): the pacing ``tau(t) = t - a T/(2 pi) sin(2 pi t / T)`` of [0, T] onto itself.

    Increasing for |a| < 1 (its rate 1 - a cos(2 pi t / T) stays positive); a > 0 lingers near
    t = 0 and T and hurries through the middle. For :meth:`Gait.reparameterized`, (3.3).
    """
    a = real_number(a, "a", what=" (the pacing's unevenness)")
    if not abs(a) < 1:
        raise ValueError(f"a must satisfy |a| < 1 so that the pacing is increasing; got {a!r}")
    T = positive_number(period, "period")

    def tau(t):
        t = np.asarray(t, float)
        return t - a * T / (2 * np.pi) * np.sin(2 * np.pi * t / T)

    def tau_dot(t):
        return 1 - a * np.cos(2 * np.pi * np.asarray(t, float) / T)

    return tau, tau_dot


def constant_rate_path(r0: ArrayLike, r_dot: ArrayLike, duration: float, *, name: str = "constant rate") -> Gait:
    """The open shape path ``r(t) = r0 + t r_dot`` for 0 <= t <= duration, as a :class:`Gait`.

    For driving a system at a constant shape rate (e.g. both wheels of a car turning steadily)
    with :func:`gm_core.systems.motion.trajectory`. Its feature time is the whole duration (a straight
    line has no narrow features), so singularity checks need only a few thousand samples.
    """
    r0 = as_array(r0, "r0", what=" (the starting shape)")
    r_dot = as_array(r_dot, "r_dot", what=" (the constant shape velocity)")
    if r0.ndim != 1 or r_dot.shape != r0.shape or r0.size < 1:
        raise ValueError(f"r0 and r_dot must be vectors of the same length n >= 1; got shapes "
                         f"{r0.shape} and {r_dot.shape}")
    T = positive_number(duration, "duration")
    if T * float(np.max(np.abs(r_dot))) > 1e100 or float(np.max(np.abs(r0))) > 1e100:
        raise ValueError(f"r0 and duration * r_dot must stay below 1e100 (shapes are angles and lengths); "
                         f"got |r0| up to {float(np.max(np.abs(r0))):g} and duration * |r_dot| up to "
                         f"{T * float(np.max(np.abs(r_dot))):g}")
    return Gait(lambda t: r0 + np.asarray(t, float)[..., None] * r_dot, T,
                lambda t: np.broadcast_to(r_dot, np.shape(t) + r_dot.shape), name=name, feature_time=T)

"""Small formulas the course's pictures need, moved out of the drawing layer (numpy only).

Provisional home: each belongs next to its topic and may move there (the names stay importable
from here and from the drawing modules that used them).

name               what it is                                                 belongs in
-----------------  ---------------------------------------------------------  -------------
FIELDS             the example vector fields of figs. 1.13-1.14              fields
point_velocities   world velocities of points on a rigid body (1.28)          groups (SE2)
binomial_table     why (I + A/n)^n -> sum A^k/k!, the coefficients of (1.50)  calculus
constant_rate_gait a shape path r0 + t r_dot (not closed) as a Gait            locomotion
drive              trajectory when the shape moves at a constant rate         locomotion
"""
from __future__ import annotations

from math import factorial

import numpy as np

from ._validate import as_array, check_positive

__all__ = ["FIELDS", "point_velocities", "binomial_table", "constant_rate_gait", "drive"]


# -------------------------------------------------------------------- example vector fields
def _spiral(q, t=0.0):
    x, y = q[..., 0], q[..., 1]
    return np.stack([-0.25 * x - y, x - 0.25 * y], -1)


def _saddle(q, t=0.0):
    return np.stack([q[..., 0], -q[..., 1]], -1)


def _rotation(q, t=0.0):
    return np.stack([-q[..., 1], q[..., 0]], -1)


def _van_der_pol(q, t=0.0):
    x, y = q[..., 0], q[..., 1]
    return np.stack([y, (1.0 - x * x) * y - x], -1)


#: The example vector fields of figs. 1.13-1.14, as functions ``(q (..., 2), t) -> q_dot``.
FIELDS = {"spiral sink": _spiral, "saddle": _saddle, "closed loops": _rotation,
          "limit cycle (van der Pol)": _van_der_pol}


# ------------------------------------------------------------------------ rigid-body points
def point_velocities(g, g_dot, points):
    """World velocities ``(..., k, 2)`` of world points ``(..., k, 2)`` carried by a body at g.

    The body's pose is ``g (..., 3)`` and its world velocity ``g_dot (..., 3)``; a point p moves
    with v(p) = (x_dot, y_dot) + theta_dot J (p - (x, y)), J the quarter turn, (1.28).
    """
    g = as_array(g, "g", (3,), what=" (x, y, theta) of SE(2)")
    g_dot = as_array(g_dot, "g_dot", (3,), what=" (world velocity)")
    r = as_array(points, "points", (2,), what=" (world points)") - g[..., None, :2]
    return g_dot[..., None, :2] + g_dot[..., None, 2:3] * np.stack([-r[..., 1], r[..., 0]], -1)


# ------------------------------------------------------------------------- binomial table
def binomial_table(ns=(5, 10, 100, 1000), kmax=5):
    """Rows (n, k, C(n,k), C(n,k)/n^k, 1/k!, n^k/k!) showing why (I + A/n)^n -> sum A^k/k!.

    Uses :func:`gm_core.calculus.binomial_terms`; the last column is the draft's coefficient in
    (1.50), which is *not* C(n, k).
    """
    from .calculus import binomial_terms

    if isinstance(kmax, bool) or int(kmax) != kmax or kmax < 0:
        raise ValueError(f"kmax must be a non-negative integer; got {kmax!r}")
    rows = []
    for n in ns:
        for k in range(int(kmax) + 1):
            c, ratio = binomial_terms(n, k)
            rows.append((n, k, c, ratio, 1.0 / factorial(k), n ** k / factorial(k)))
    return rows


# --------------------------------------------------------------------- constant-rate shapes
def constant_rate_gait(r0, r_dot, duration):
    """The open shape path r(t) = r0 + t r_dot as a Gait; the same as :func:`gm_core.gaits.constant_rate_path`."""
    from .gaits import constant_rate_path

    return constant_rate_path(r0, r_dot, duration)


def drive(system, r0, r_dot, duration, n_frames=81):
    """Trajectory of ``system`` when its shape moves at the constant rate r_dot from r0 for ``duration``.

    Returns a :class:`gm_core.locomotion.Trajectory` starting at the identity; raises
    SingularShapeError if the shape path reaches a singular shape.
    """
    from .locomotion import trajectory

    return trajectory(system, constant_rate_gait(r0, r_dot, duration), n_frames, substeps=16)

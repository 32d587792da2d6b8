"""Frames and observers on SE(2) (book section 1.5, the "Frames" box and (1.38)-(1.45)).

numpy only. The body velocity of a rigid body does not depend on who watches it; its spatial
velocity does: an observer whose coordinate frame sits at ``h`` sees the body at ``h^-1 g`` and
so measures ``xi^s_h = Ad_{h^-1 g} xi``. The instantaneous centre of rotation (ICR) is the one
point of the moving plane with zero velocity; written in any frame it is the same point.

name                   what it is                                                      book
---------------------  --------------------------------------------------------------  --------------
observed_velocity      xi^s seen by the observer at h: Ad_{h^-1 g} xi                    (1.40)-(1.43)
icr                    (-v_y / w, v_x / w) for xi = (v_x, v_y, w), flagged at w = 0      sec. 1.5
point_in_frame         coordinates of a world point in the frame g (g^-1 p)             (1.12)
conjugation            g xi^ g^-1 and (Ad_g xi)^: Ad as conjugation, for display         (1.40)
point_velocities       world velocities of world points carried by a moving body       (1.28)
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.chains.jacobians import relative_pose
from gm_core.groups import SE2, matvec
from gm_core.validation import BoolArray, FloatArray, as_array, batch_shape, positive_number

__all__ = ["observed_velocity", "icr", "point_in_frame", "conjugation",
           "point_velocities"]


def _se2(g, name):
    return as_array(g, name, (3,), what=" (an SE(2) element (x, y, theta))")


def observed_velocity(g: ArrayLike, xi: ArrayLike, h: ArrayLike = (0.0, 0.0, 0.0)) -> FloatArray:
    """Spatial velocity ``(..., 3)`` of a body at ``g`` with body velocity ``xi``, measured by an
    observer whose coordinate frame is at ``h``: Ad_{h^-1 g} xi, (1.43).

    With ``h = e`` this is the book's spatial velocity xi^s = Ad_g xi. The body velocity xi is
    the same for every observer; the spatial velocity is the velocity of the body point that is
    momentarily over the observer's origin, written in the observer's axes.
    """
    g, h = _se2(g, "g"), _se2(h, "h")
    xi = as_array(xi, "xi", (3,), what=" (a body velocity (v_x, v_y, omega))")
    batch_shape(("g", g, 1), ("xi", xi, 1), ("h", h, 1))
    return matvec(SE2.Ad(relative_pose(g, h)), xi)


def icr(xi: ArrayLike, tol: float = 1e-9) -> tuple[FloatArray, BoolArray]:
    """Instantaneous centre of rotation of the velocity ``xi = (v_x, v_y, w)``, in the frame
    ``xi`` is written in: ``(point (..., 2), at_infinity (...,) bool)``.

    A point p of the moving plane has velocity (v_x - w p_y, v_y + w p_x) (the translation plus
    w times the lever arm turned a quarter turn), which vanishes at p = (-v_y / w, v_x / w).
    When |w| <= tol there is no such point (pure translation: the centre is "at infinity") and
    the point returned is 0 with ``at_infinity`` True; never inf or NaN.
    """
    xi = as_array(xi, "xi", (3,), what=" (a velocity (v_x, v_y, omega))")
    tol = positive_number(tol, "tol", allow_zero=True, what=" (the turning rate below which the centre is at infinity)")
    w = xi[..., 2]
    far = np.abs(w) <= tol
    safe = np.where(far, 1.0, w)
    p = np.stack([-xi[..., 1] / safe, xi[..., 0] / safe], -1)
    p = np.where(far[..., None], 0.0, p) + 0.0          # + 0.0 turns -0.0 into 0.0 for readouts
    return p, far


def point_in_frame(g: ArrayLike, p: ArrayLike) -> FloatArray:
    """Coordinates ``(..., 2)`` of the world point ``p`` in the frame at ``g`` (inverse of (1.12))."""
    p = as_array(p, "p", (2,), what=" (a point (x, y))")
    return SE2.act_on_points(SE2.inverse(_se2(g, "g")), p)


def conjugation(g: ArrayLike, xi: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Ad as conjugation, for display: ``(g xi^ g^-1, (Ad_g xi)^)``, two ``(..., 3, 3)`` matrices
    that agree (the first from matrix products, the second from the closed form (1.43))."""
    g = _se2(g, "g")
    xi = as_array(xi, "xi", (3,), what=" (a Lie-algebra element (v_x, v_y, omega))")
    batch_shape(("g", g, 1), ("xi", xi, 1))
    M = SE2.matrix(g)
    return M @ SE2.hat(xi) @ np.linalg.inv(M), SE2.hat(matvec(SE2.Ad(g), xi))


def point_velocities(g: ArrayLike, g_dot: ArrayLike, points: ArrayLike) -> FloatArray:
    """World velocities ``(..., k, 2)`` of world points ``(..., k, 2)`` carried by a body at g.

    The body's pose is ``g (..., 3)`` and its world velocity ``g_dot (..., 3)``; a point p moves
    with v(p) = (x_dot, y_dot) + theta_dot J (p - (x, y)), J the quarter turn, (1.28). The one
    point with v = 0 is the body's :func:`icr` (written in world axes).
    """
    g = _se2(g, "g")
    g_dot = as_array(g_dot, "g_dot", (3,), what=" (world velocity)")
    r = as_array(points, "points", (2,), what=" (world points)") - g[..., None, :2]
    return g_dot[..., None, :2] + g_dot[..., None, 2:3] * np.stack([-r[..., 1], r[..., 0]], -1)

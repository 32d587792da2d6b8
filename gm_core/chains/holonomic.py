"""Holonomic constraints of chapter 2: two pinned bodies (fig. 2.1) and the accessible manifold
of box (2.i)-(2.ii), exercise 2.1. numpy only.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups import SE2
from gm_core.validation import FloatArray, as_array, batch_shape, check_int, positive_number

__all__ = [
    "pin_constraints", "pinned_pair", "circle_constraints", "sphere_plane_constraints",
    "sample_accessible_manifold", "accessible_circle",
]


def pin_constraints(g1: ArrayLike, g2: ArrayLike) -> FloatArray:
    """Constraint values ``(..., 2)`` of two bodies pinned at their frame origins: (x1 - x2, y1 - y2); fig. 2.1.

    g1, g2: poses ``(..., 3)``. The pair is a configuration of the pinned system exactly where
    both values vanish; the two constraints take SE(2) x SE(2) (six numbers) down to the
    four-dimensional accessible manifold SE(2) x S^1 (section 2.1).
    """
    g1 = as_array(g1, "g1", (3,), what=" (pose of body 1)")
    g2 = as_array(g2, "g2", (3,), what=" (pose of body 2)")
    batch_shape(("g1", g1, 1), ("g2", g2, 1))
    return g1[..., :2] - g2[..., :2]


def pinned_pair(g: ArrayLike, alpha: ArrayLike) -> FloatArray:
    """Poses ``(..., 2, 3)`` of two bodies pinned at their frame origins, from (g, alpha) in SE(2) x S^1; fig. 2.1.

    Body 1 is at g; body 2 shares its origin and is turned by alpha relative to it, g2 = g exp(alpha)
    (the coordinates on the accessible manifold: no constraint needs enforcing).
    """
    g = as_array(g, "g", (3,), what=" (pose of body 1)")
    alpha = as_array(alpha, "alpha", what=" (angle of body 2 relative to body 1)")
    batch_shape(("g", g, 1), ("alpha", alpha, 0))
    g, alpha = np.broadcast_arrays(g, alpha[..., None])
    turn = np.zeros(g.shape)
    turn[..., 2] = alpha[..., 0]
    return np.stack([g, SE2.compose(g, turn)], axis=-2)


def circle_constraints(p: ArrayLike) -> FloatArray:
    """Constraint values ``(..., 2)``: f1 = z - 1 and f2 = sqrt(x^2 + y^2) - 1; book (2.i)-(2.ii). p: ``(..., 3)``."""
    p = as_array(p, "p", (3,), what=" (points x, y, z)")
    return np.stack([p[..., 2] - 1.0, np.hypot(p[..., 0], p[..., 1]) - 1.0], -1)


def sphere_plane_constraints(p: ArrayLike) -> FloatArray:
    """Constraint values ``(..., 2)``: distance from the origin sqrt(2) and z = 1 (exercise 2.1: same manifold). p: ``(..., 3)``."""
    p = as_array(p, "p", (3,), what=" (points x, y, z)")
    return np.stack([np.hypot(np.hypot(p[..., 0], p[..., 1]), p[..., 2]) - np.sqrt(2.0), p[..., 2] - 1.0], -1)


def sample_accessible_manifold(constraints: Callable[[FloatArray], FloatArray], n: int = 200,
                               rng: np.random.Generator | None = None, box: float = 2.0, dim: int = 3, iters: int = 50,
                               tol: float = 1e-12) -> FloatArray:
    """Points ``(k, dim)`` on the zero set of ``constraints`` (the accessible manifold), book box (2.i)-(2.ii).

    Random points in ``[-box, box]^dim`` are projected onto ``constraints(p) = 0`` by Gauss-Newton
    steps with a numerical Jacobian; points that do not converge (or hit a singularity) are dropped.
    """
    if not callable(constraints):
        raise TypeError("constraints must be a function p (..., dim) -> values (..., k)")
    n = check_int(n, "n", minimum=1, maximum=10 ** 7, what=" (the number of random starting points)")
    dim = check_int(dim, "dim", minimum=1, maximum=1000, what=" (the dimension of the ambient space)")
    iters = check_int(iters, "iters", minimum=1, maximum=10 ** 6, what=" (Gauss-Newton iterations)")
    box = positive_number(box, "box")
    tol = positive_number(tol, "tol")
    if rng is None:
        rng = np.random.default_rng(0)
    elif not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy Generator (np.random.default_rng(seed)) or None; got {rng!r}")
    p = rng.uniform(-box, box, (n, dim))
    eps = 1e-7
    for _ in range(iters):
        f = constraints(p)
        J = np.stack([(constraints(p + eps * e) - constraints(p - eps * e)) / (2 * eps) for e in np.eye(dim)], -1)
        step = np.einsum("nij,nj->ni", np.linalg.pinv(J), f)
        p = p - step
        if np.all(np.abs(f) < tol):
            break
    ok = np.all(np.abs(constraints(p)) < 1e-9, axis=-1) & np.all(np.isfinite(p), axis=-1)
    return p[ok]


def accessible_circle(n: int = 100) -> FloatArray:
    """Points ``(n, 3)`` of the accessible manifold of (2.i)-(2.ii): the unit circle in the plane z = 1."""
    n = check_int(n, "n", minimum=2, maximum=10 ** 7, what=" (the number of points)")
    t = np.linspace(0.0, 2 * np.pi, n)
    return np.stack([np.cos(t), np.sin(t), np.ones_like(t)], -1)

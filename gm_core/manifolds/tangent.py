"""Tangent spaces and geodesics on the course's surfaces (book section 1.4): the velocity of a point
moving on a circle or a sphere, the sphere's tangent basis, great circles and the cylinder's helices.

numpy only; the embeddings themselves are :mod:`gm_core.manifolds.spaces`.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.manifolds.spaces import broadcast_pair, cylinder_xyz
from gm_core.validation import FloatArray, as_array, batch_shape, positive_number, real_number

__all__ = [
    "circle_point_velocity", "cylinder_geodesic", "great_circle", "sphere_tangent_basis",
    "sphere_velocity",
]


# ------------------------------------------------------------------ tangent spaces (figs 1.11-1.12)
def circle_point_velocity(a: ArrayLike, a_dot: ArrayLike = 1.0, radius: float = 1.0
                          ) -> tuple[FloatArray, FloatArray]:
    """Position and velocity ``(..., 2)`` of a point at angle ``a`` on a circle of ``radius``,
    turning at rate ``a_dot``: p = r (cos a, sin a), v = r a_dot (-sin a, cos a), which lies on
    the tangent line at p (v . p = 0), fig. 1.11."""
    a = as_array(a, "a")
    a_dot = as_array(a_dot, "a_dot")
    radius = positive_number(radius, "radius")
    batch_shape(("a", a, 0), ("a_dot", a_dot, 0))
    a, a_dot = np.broadcast_arrays(a, a_dot)
    c, s = np.cos(a), np.sin(a)
    return radius * np.stack([c, s], -1), (radius * a_dot)[..., None] * np.stack([-s, c], -1)


def sphere_tangent_basis(lat: ArrayLike, lon: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Unit vectors ``(east, north)``, each ``(..., 3)``, spanning the tangent plane of the
    sphere at latitude ``lat``, longitude ``lon`` (fig. 1.12): east = d/dlon of
    :func:`sphere_xyz` divided by cos(lat), north = d/dlat. At a pole "east" and "north" lose
    their meaning (east is still returned, a unit vector of that plane, for lon given)."""
    lat, lon = broadcast_pair(lat, lon, "lat", "lon")
    east = np.stack([-np.sin(lon), np.cos(lon), np.zeros_like(lon)], -1)
    north = np.stack([-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)], -1)
    return east, north


def sphere_velocity(lat: ArrayLike, lon: ArrayLike, lat_dot: ArrayLike, lon_dot: ArrayLike,
                    radius: float = 1.0) -> FloatArray:
    """Velocity ``(..., 3)`` in T_pS^2 of a point moving with coordinate rates ``lat_dot``,
    ``lon_dot``: r (cos(lat) lon_dot east + lat_dot north), the chain rule on :func:`sphere_xyz`."""
    east, north = sphere_tangent_basis(lat, lon)
    lat = as_array(lat, "lat")
    lat_dot = as_array(lat_dot, "lat_dot")
    lon_dot = as_array(lon_dot, "lon_dot")
    radius = positive_number(radius, "radius")
    return radius * ((np.cos(lat) * lon_dot)[..., None] * east + lat_dot[..., None] * north)


# -------------------------------------------------------------------------- geodesics (fig. 1.16)
def great_circle(p: ArrayLike, v: ArrayLike, t: ArrayLike, radius: float = 1.0, tol: float = 1e-9
                 ) -> tuple[FloatArray, FloatArray]:
    """Points and velocities ``(len(t), 3)`` of the sphere's geodesic that starts at ``p`` (on the
    sphere of ``radius``) with tangent velocity ``v``: with speed c = |v| and unit direction u,
    p(t) = p cos(c t / r) + r u sin(c t / r), a great circle run at constant speed, fig. 1.16.

    ``p`` off the sphere or ``v`` not tangent (p . v != 0) is a ValueError.
    """
    p = as_array(p, "p", (3,), what=" (a point on the sphere)")
    v = as_array(v, "v", (3,), what=" (a tangent velocity)")
    for name, x in (("p", p), ("v", v)):
        if x.ndim != 1:
            raise ValueError(f"{name} must be a single vector (3,); got shape {x.shape}")
    t = as_array(t, "t")
    radius = positive_number(radius, "radius")
    norm_p, c = (float(np.hypot(np.hypot(x[0], x[1]), x[2])) for x in (p, v))   # no overflow
    if abs(norm_p - radius) > tol * radius:
        raise ValueError(f"p must lie on the sphere of radius {radius}; |p| = {norm_p:.6g}")
    if abs(p @ (v / max(c, 1.0))) > tol * radius:
        raise ValueError(f"v must be tangent to the sphere at p (p . v = 0); got p . v = {p @ v:.3g}")
    if c == 0.0:
        return np.broadcast_to(p, t.shape + (3,)).copy(), np.zeros(t.shape + (3,))
    u = v / c
    k = (c / radius) * t[..., None]
    return p * np.cos(k) + radius * u * np.sin(k), c * (u * np.cos(k) - p / radius * np.sin(k))


def cylinder_geodesic(s0: float, a0: float, s_dot: float, a_dot: float, t: ArrayLike,
                      radius: float = 1.0) -> FloatArray:
    """Points ``(len(t), 3)`` of the cylinder's geodesic from height ``s0``, angle ``a0`` with
    constant rates ``s_dot``, ``a_dot``: unrolled, the cylinder is flat, so a geodesic is a
    straight line in (r a, s) -- a loop (s_dot = 0), an axial line (a_dot = 0) or a helix,
    fig. 1.16. Speed sqrt(s_dot^2 + (r a_dot)^2)."""
    t = as_array(t, "t")
    s0, a0, s_dot, a_dot = (real_number(x, n) for x, n in
                            ((s0, "s0"), (a0, "a0"), (s_dot, "s_dot"), (a_dot, "a_dot")))
    return cylinder_xyz(s0 + s_dot * t, a0 + a_dot * t, radius)

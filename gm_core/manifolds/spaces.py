"""Surfaces and charts of section 1.1: embeddings of the cylinder, torus and sphere, the
latitude/longitude chart's coordinate speed, a polar chart, and cutting a path at the seams of a
flattened (periodic) square.

numpy only; the drawing layer (gm_core.drawing.spaces) plots what these functions return.

name                  what it is                                                       book
--------------------  ---------------------------------------------------------------  --------
cylinder_xyz          R^1 x S^1 in 3D: height s, angle a                              fig. 1.4
torus_xyz             S^1 x S^1 in 3D: a round the hole, b round the tube             fig. 1.5
sphere_xyz            S^2 at latitude / longitude                                      fig. 1.6
wrap_segments         a path on the flat torus/cylinder cut where it crosses a seam    fig. 1.5
chart_speed           (dlat/dt, dlon/dt) of a unit-speed walker; inf at the poles      sec. 1.1
polar_chart_velocity  the same walker in the polar chart of the northern half          sec. 1.1
circle_point_velocity a point moving on a circle and its velocity on the tangent line   fig. 1.11
sphere_tangent_basis  east and north unit vectors spanning the tangent plane T_pS^2     fig. 1.12
sphere_velocity       velocity in T_pS^2 of a walker with rates (dlat/dt, dlon/dt)     fig. 1.12
great_circle          geodesic of the sphere from p with velocity v (exact formula)    fig. 1.16
cylinder_geodesic     geodesic of the cylinder: a helix, a loop or an axial line       fig. 1.16
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups.base import TWO_PI
from gm_core.validation import FloatArray, as_array, batch_shape, positive_number

__all__ = [
    "broadcast_pair",
    "cylinder_xyz", "torus_xyz", "sphere_xyz", "wrap_segments", "chart_speed",
    "polar_chart_velocity",
]


def broadcast_pair(u: ArrayLike, v: ArrayLike, nu: str, nv: str) -> tuple[FloatArray, FloatArray]:
    """``u`` and ``v`` (named ``nu``, ``nv`` in errors) as float arrays of one broadcast shape."""
    u = as_array(u, nu)
    v = as_array(v, nv)
    batch_shape((nu, u, 0), (nv, v, 0))
    bu, bv = np.broadcast_arrays(u, v)
    return bu, bv


def cylinder_xyz(s: ArrayLike, a: ArrayLike, radius: float = 1.0) -> FloatArray:
    """Points ``(..., 3)`` of the cylinder R^1 x S^1 of ``radius``: height ``s``, angle ``a``."""
    s, a = broadcast_pair(s, a, "s", "a")
    radius = positive_number(radius, "radius")
    return np.stack([radius * np.cos(a), radius * np.sin(a), s], -1)


def torus_xyz(a: ArrayLike, b: ArrayLike, R: float = 2.0, r: float = 0.7) -> FloatArray:
    """Points ``(..., 3)`` of the torus S^1 x S^1: ``a`` round the hole, ``b`` round the tube.

    ``R`` is the distance from the centre to the tube's centre line, ``r`` the tube radius
    (``R > r > 0`` for an embedded torus).
    """
    a, b = broadcast_pair(a, b, "a", "b")
    R = positive_number(R, "R")
    r = positive_number(r, "r")
    if r >= R:
        raise ValueError(f"the tube radius r must be smaller than R; got r = {r}, R = {R}")
    rho = R + r * np.cos(b)
    return np.stack([rho * np.cos(a), rho * np.sin(a), r * np.sin(b)], -1)


def sphere_xyz(lat: ArrayLike, lon: ArrayLike, radius: float = 1.0) -> FloatArray:
    """Point ``(..., 3)`` of the sphere S^2 of ``radius`` at latitude ``lat``, longitude ``lon`` (rad)."""
    lat, lon = broadcast_pair(lat, lon, "lat", "lon")
    radius = positive_number(radius, "radius")
    c = np.cos(lat)
    return radius * np.stack([c * np.cos(lon), c * np.sin(lon), np.sin(lat)], -1)


def wrap_segments(a: ArrayLike, b: ArrayLike, period_a: float = TWO_PI, period_b: float = TWO_PI
                  ) -> list[FloatArray]:
    """Cut a path (a(t), b(t)) into pieces inside the square [0, pa) x [0, pb) of a flat torus.

    Returns a list of ``(k, 2)`` arrays, one per visit of the square (pieces of a single point
    are dropped), so the path can be drawn on the flattened view without joining its exit point
    to its re-entry point. A period of 0 means "not periodic" in that coordinate (the cylinder's
    height).
    """
    a = as_array(a, "a")
    b = as_array(b, "b")
    if a.ndim != 1 or a.shape != b.shape:
        raise ValueError(f"a and b must be 1-D arrays of equal length; got shapes {a.shape} and {b.shape}")
    pa = positive_number(period_a, "period_a", allow_zero=True)
    pb = positive_number(period_b, "period_b", allow_zero=True)
    ia = np.floor(a / pa) if pa else np.zeros_like(a)
    ib = np.floor(b / pb) if pb else np.zeros_like(b)
    cuts = np.flatnonzero((np.diff(ia) != 0) | (np.diff(ib) != 0)) + 1
    pts = np.stack([a - ia * pa, b - ib * pb], -1)
    return [seg for seg in np.split(pts, cuts) if len(seg) > 1]


def chart_speed(lat: ArrayLike, heading: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Coordinate speed ``(dlat/dt, dlon/dt)`` of a unit-speed walker at latitude ``lat`` (rad).

    ``heading`` is measured from north towards east. On the unit sphere the walker's velocity
    has north component cos(heading) and east component sin(heading); the east component is
    cos(lat) * dlon/dt, so ``dlon = sin(heading) / cos(lat)``: it is ``inf`` at the poles, where
    the chart fails (the caller flags it instead of plotting).
    """
    lat = as_array(lat, "lat", what=" (latitude in radians)")
    heading = as_array(heading, "heading", what=" (radians from north)")
    batch_shape(("lat", lat, 0), ("heading", heading, 0))
    lat, heading = np.broadcast_arrays(lat, heading)
    c = np.cos(lat)
    dlat = np.cos(heading)
    pole = np.abs(c) <= 1e-12
    dlon = np.where(pole, np.inf, np.sin(heading) / np.where(pole, 1.0, c))
    return dlat, dlon


def polar_chart_velocity(lat: ArrayLike, lon: ArrayLike, heading: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Position ``(X, Y)`` and velocity ``(dX, dY)`` of the walker of :func:`chart_speed` in the
    polar chart X = cos(lat) cos(lon), Y = cos(lat) sin(lon) of the northern half.

    Unlike the latitude/longitude chart this one is smooth at the north pole: the velocity stays
    finite (its length is the walker's unit speed times |sin(lat)| along the meridian).
    Returns two arrays ``(..., 2)``.
    """
    lat = as_array(lat, "lat")
    lon = as_array(lon, "lon")
    heading = as_array(heading, "heading")
    batch_shape(("lat", lat, 0), ("lon", lon, 0), ("heading", heading, 0))
    lat, lon, heading = np.broadcast_arrays(lat, lon, heading)
    dlat = np.cos(heading)
    c, s = np.cos(lat), np.sin(lat)
    # d/dt (cos lat cos lon, cos lat sin lon) with cos(lat) dlon/dt = sin(heading) (no 1/cos lat)
    east = np.sin(heading)
    dX = -s * dlat * np.cos(lon) - east * np.sin(lon)
    dY = -s * dlat * np.sin(lon) + east * np.cos(lon)
    pos = np.stack([c * np.cos(lon), c * np.sin(lon)], -1)
    return pos, np.stack([dX, dY], -1)



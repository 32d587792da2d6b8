"""Configuration spaces and observers (book chapter 1), numpy only.

* :mod:`.spaces`: embeddings and charts of the circle, cylinder, torus and sphere (section 1.1);
* :mod:`.charts`: charts and their transition maps acting on points, vectors and fields (section 1.1);
* :mod:`.tangent`: tangent vectors and geodesics on them (section 1.4);
* :mod:`.observers`: velocities seen from moving frames (section 1.5).
"""
from __future__ import annotations

from gm_core.manifolds.charts import (
    CARTESIAN,
    CHARTS,
    LATITUDE_LONGITUDE,
    POLAR,
    STEREOGRAPHIC_NORTH,
    STEREOGRAPHIC_SOUTH,
    Cartesian,
    Chart,
    LatitudeLongitude,
    Polar,
    Stereographic,
    in_overlap,
    transition_field,
    transition_jacobian,
    transition_path,
    transition_point,
    transition_vector,
)
from gm_core.manifolds.observers import (
    conjugation,
    icr,
    observed_velocity,
    point_in_frame,
    point_velocities,
)
from gm_core.manifolds.spaces import (
    broadcast_pair,
    chart_speed,
    cylinder_xyz,
    polar_chart_velocity,
    sphere_xyz,
    torus_xyz,
    wrap_segments,
)
from gm_core.manifolds.tangent import (
    circle_point_velocity,
    cylinder_geodesic,
    great_circle,
    sphere_tangent_basis,
    sphere_velocity,
)

__all__ = [
    "broadcast_pair", "cylinder_xyz", "torus_xyz", "sphere_xyz", "wrap_segments", "chart_speed",
    "polar_chart_velocity", "circle_point_velocity", "cylinder_geodesic", "great_circle",
    "sphere_tangent_basis", "sphere_velocity", "observed_velocity", "icr", "point_in_frame",
    "conjugation", "point_velocities",
    "Chart", "Cartesian", "Polar", "LatitudeLongitude", "Stereographic", "CARTESIAN", "POLAR",
    "LATITUDE_LONGITUDE", "STEREOGRAPHIC_NORTH", "STEREOGRAPHIC_SOUTH", "CHARTS", "transition_point",
    "transition_jacobian", "transition_vector", "transition_field", "in_overlap", "transition_path",
]

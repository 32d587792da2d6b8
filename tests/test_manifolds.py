"""gm_core.manifolds: embeddings, the chart speed of a walker and seam cutting, each checked by
an independent route (implicit equations, finite differences on the sphere, brute-force walks)."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core.manifolds import (chart_speed, cylinder_xyz, polar_chart_velocity, sphere_xyz, torus_xyz,
                               wrap_segments)

angles = st.floats(-10.0, 10.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(angles, angles)
def test_embeddings_satisfy_their_implicit_equations(u, v):
    x, y, z = torus_xyz(u, v, R=2.0, r=0.7)
    assert np.isclose((np.hypot(x, y) - 2.0) ** 2 + z ** 2, 0.7 ** 2)
    x, y, z = sphere_xyz(u, v, radius=1.6)
    assert np.isclose(x * x + y * y + z * z, 1.6 ** 2)
    x, y, z = cylinder_xyz(u, v, radius=0.5)
    assert np.isclose(x * x + y * y, 0.25) and np.isclose(z, u)


def test_embeddings_are_periodic_and_broadcast():
    a = np.linspace(0, 1, 5)[:, None]
    b = np.linspace(0, 2, 3)[None, :]
    P = torus_xyz(a, b)
    assert P.shape == (5, 3, 3)
    assert np.allclose(torus_xyz(a + 2 * np.pi, b - 2 * np.pi), P)
    assert np.allclose(sphere_xyz(np.pi / 2, [0.0, 1.0, 2.0]), [[0, 0, 1]] * 3, atol=1e-15)  # one north pole


def test_bad_input_names_the_argument():
    with pytest.raises(TypeError, match="a"):
        torus_xyz("x", 1.0)
    with pytest.raises(ValueError, match="r must be smaller than R"):
        torus_xyz(0.0, 0.0, R=1.0, r=2.0)
    with pytest.raises(ValueError, match="radius"):
        sphere_xyz(0.0, 0.0, radius=-1.0)
    with pytest.raises(ValueError, match="equal length"):
        wrap_segments([0.0, 1.0], [0.0])


@pytest.mark.parametrize("lat,heading", [(0.3, 0.7), (-1.2, 2.0), (1.5, 0.1), (0.0, np.pi / 2)])
def test_chart_speed_against_finite_differences_of_a_walk_on_the_sphere(lat, heading):
    """Walk a short great-circle step on the unit sphere from (lat, 0) with the given heading and
    read its latitude/longitude back: the coordinate rates must match chart_speed."""
    p = sphere_xyz(lat, 0.0)
    north = np.array([-np.sin(lat), 0.0, np.cos(lat)])
    east = np.array([0.0, 1.0, 0.0])
    v = np.cos(heading) * north + np.sin(heading) * east

    def coords(h):
        q = np.cos(h) * p + np.sin(h) * v          # unit-speed great circle
        return np.array([np.arcsin(q[2]), np.arctan2(q[1], q[0])])

    h = 1e-6
    fd = (coords(h) - coords(-h)) / (2 * h)
    dlat, dlon = chart_speed(lat, heading)
    assert np.allclose([dlat, dlon], fd, rtol=1e-6, atol=1e-8)


def test_chart_speed_is_infinite_only_at_the_poles():
    dlat, dlon = chart_speed(np.array([np.pi / 2, -np.pi / 2, 1.0]), 0.5)
    assert np.isinf(dlon[:2]).all() and np.isfinite(dlon[2])
    assert np.allclose(dlat, np.cos(0.5))


@pytest.mark.parametrize("lat,lon,heading", [(0.4, 0.3, 1.0), (1.5707, 2.0, 0.3), (0.9, -1.0, 2.5)])
def test_polar_chart_velocity_against_finite_differences(lat, lon, heading):
    dlat, dlon = chart_speed(lat, heading)

    def pos(t):
        la, lo = lat + t * dlat, lon + t * dlon
        return np.array([np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo)])

    h = 1e-6
    p, v = polar_chart_velocity(lat, lon, heading)
    assert np.allclose(p, pos(0.0))
    assert np.allclose(v, (pos(h) - pos(-h)) / (2 * h), atol=1e-6)
    # at the pole itself the polar chart's velocity stays finite
    _, v_pole = polar_chart_velocity(np.pi / 2, 0.0, heading)
    assert np.all(np.isfinite(v_pole)) and np.isclose(np.hypot(*v_pole), 1.0)


def test_wrap_segments_against_a_brute_force_walk():
    t = np.linspace(0, 3 * 2 * np.pi, 700)
    a, b = t + 0.3, 2.0 / 3.0 * t + 1.0
    segs = wrap_segments(a, b)
    pts = np.concatenate(segs)
    assert pts.min() >= 0 and pts.max() < 2 * np.pi
    # brute force: count the seam crossings of the unwrapped path; one piece per visit
    crossings = np.count_nonzero(np.diff(np.floor(a / (2 * np.pi))) != 0) + \
        np.count_nonzero(np.diff(np.floor(b / (2 * np.pi))) != 0)
    assert len(segs) == crossings + 1
    # every point is kept (the path's points are the pieces' points, mod 2 pi)
    assert len(pts) == len(t)
    assert np.allclose(np.sort(pts[:, 0]), np.sort(np.mod(a, 2 * np.pi)))
    # period 0: no wrapping in that coordinate (the cylinder's height)
    segs = wrap_segments(a, 10 * b, 2 * np.pi, 0)
    assert np.allclose(np.concatenate(segs)[:, 1], 10 * b)

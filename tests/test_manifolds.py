"""gm_core.manifolds: embeddings, the chart speed of a walker and seam cutting, each checked by
an independent route (implicit equations, finite differences on the sphere, brute-force walks)."""
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from gm_core.manifolds import chart_speed, cylinder_xyz, polar_chart_velocity, sphere_xyz, torus_xyz, wrap_segments

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


# ------------------------------------------------- tangent spaces (figs 1.11-1.12), geodesics (1.16)
from gm_core.manifolds import (  # noqa: E402
    circle_point_velocity,
    cylinder_geodesic,
    great_circle,
    sphere_tangent_basis,
    sphere_velocity,
)


def _fd(f, t, h=1e-6):
    return (f(t + h) - f(t - h)) / (2 * h)


def test_circle_velocity_is_tangent_and_is_the_derivative():
    a = np.linspace(0, 6, 13)
    p, v = circle_point_velocity(a, 1.7, radius=2.0)
    assert np.allclose(np.sum(p * v, -1), 0.0)                        # on the tangent line
    fd = _fd(lambda t: circle_point_velocity(1.7 * t, 0.0, radius=2.0)[0], a / 1.7)
    assert np.allclose(v, fd, atol=1e-6)
    assert np.allclose(np.linalg.norm(v, axis=-1), 2.0 * 1.7)


def test_sphere_tangent_basis_against_finite_differences():
    lat, lon = np.meshgrid(np.linspace(-1.4, 1.4, 7), np.linspace(-3, 3, 9))
    east, north = sphere_tangent_basis(lat, lon)
    d_lon = _fd(lambda x: sphere_xyz(lat, x), lon)
    d_lat = _fd(lambda x: sphere_xyz(x, lon), lat)
    assert np.allclose(east * np.cos(lat)[..., None], d_lon, atol=1e-6)
    assert np.allclose(north, d_lat, atol=1e-6)
    p = sphere_xyz(lat, lon)
    for u in (east, north):                                             # unit, tangent, orthogonal
        assert np.allclose(np.linalg.norm(u, axis=-1), 1.0) and np.allclose(np.sum(u * p, -1), 0.0)
    assert np.allclose(np.sum(east * north, -1), 0.0)


def test_sphere_velocity_is_the_chain_rule():
    t = np.linspace(0, 5, 11)

    def curve(t):
        return sphere_xyz(0.6 * np.sin(t), t, radius=1.5)

    v = sphere_velocity(0.6 * np.sin(t), t, 0.6 * np.cos(t), 1.0, radius=1.5)
    assert np.allclose(v, _fd(curve, t), atol=1e-6)
    assert np.allclose(np.sum(v * curve(t), -1), 0.0)


def test_great_circle_is_a_geodesic():
    """Constant speed, acceleration normal to the sphere (no tangential part), and it stays in
    the plane through the centre spanned by p and v: the exact great circle."""
    rng = np.random.default_rng(4)
    for _ in range(5):
        r = rng.uniform(0.5, 2.0)
        p = sphere_xyz(rng.uniform(-1.4, 1.4), rng.uniform(-3, 3), radius=r)
        e, n = sphere_tangent_basis(np.arcsin(p[2] / r), np.arctan2(p[1], p[0]))
        v = rng.normal() * e + rng.normal() * n
        t = np.linspace(0, 4, 41)
        P, V = great_circle(p, v, t, radius=r)
        assert np.allclose(np.linalg.norm(P, axis=-1), r)                               # on the sphere
        assert np.allclose(np.linalg.norm(V, axis=-1), np.linalg.norm(v))               # constant speed
        assert np.allclose(V, _fd(lambda s: great_circle(p, v, s, radius=r)[0], t), atol=1e-6)
        h = 1e-4
        acc = (great_circle(p, v, t + h, radius=r)[0] - 2 * P + great_circle(p, v, t - h, radius=r)[0]) / h ** 2
        tangential = acc - np.sum(acc * P, -1, keepdims=True) * P / r ** 2
        assert np.max(np.abs(tangential)) < 1e-5                                          # geodesic equation
        normal = np.cross(p, v)
        assert np.allclose(P @ normal, 0.0, atol=1e-9)                                    # plane through 0
        ang = np.arccos(np.clip(P @ p / r ** 2, -1, 1))                                   # arc length = speed t
        k = np.linalg.norm(v) * t / r
        assert np.allclose(ang, np.where(k % (2 * np.pi) <= np.pi, k % (2 * np.pi), 2 * np.pi - k % (2 * np.pi)),
                           atol=1e-6)


def test_great_circle_refuses_bad_starts():
    with pytest.raises(ValueError, match="p must lie on the sphere"):
        great_circle([1.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0])
    with pytest.raises(ValueError, match="v must be tangent"):
        great_circle([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0])


@pytest.mark.parametrize("s_dot, a_dot", [(0.0, 1.0), (1.0, 0.0), (0.4, 1.3), (-0.7, -0.5)])
def test_cylinder_geodesic_constant_speed_zero_tangential_acceleration(s_dot, a_dot):
    r = 1.3
    t = np.linspace(0, 5, 31)
    P = cylinder_geodesic(0.2, 0.4, s_dot, a_dot, t, radius=r)
    V = _fd(lambda s: cylinder_geodesic(0.2, 0.4, s_dot, a_dot, s, radius=r), t)
    assert np.allclose(np.linalg.norm(V, axis=-1), np.hypot(s_dot, r * a_dot), atol=1e-6)
    h = 1e-4
    acc = (cylinder_geodesic(0.2, 0.4, s_dot, a_dot, t + h, radius=r) - 2 * P
           + cylinder_geodesic(0.2, 0.4, s_dot, a_dot, t - h, radius=r)) / h ** 2
    radial = np.stack([P[:, 0], P[:, 1], 0 * t], -1) / r                     # the surface normal
    tangential = acc - np.sum(acc * radial, -1, keepdims=True) * radial
    assert np.max(np.abs(tangential)) < 1e-5
    assert np.allclose(np.hypot(P[:, 0], P[:, 1]), r)

"""gm_core.manifolds.charts: charts and their transitions on points, vectors and fields, each checked
by an independent route (sympy Jacobians, central differences, round trips, integral curves solved
in both charts) and against the numbers of the author's own code (rlhatton/GeometryOfMotionCodebase)."""
import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from gm_core.fields import FIELDS, VectorField, integral_curve
from gm_core.manifolds import (
    CARTESIAN,
    CHARTS,
    LATITUDE_LONGITUDE,
    POLAR,
    STEREOGRAPHIC_NORTH,
    STEREOGRAPHIC_SOUTH,
    in_overlap,
    transition_field,
    transition_jacobian,
    transition_path,
    transition_point,
    transition_vector,
)

PLANE = [CARTESIAN, POLAR]
SPHERE = [LATITUDE_LONGITUDE, STEREOGRAPHIC_NORTH, STEREOGRAPHIC_SOUTH]
PAIRS = [(a, b) for group in (PLANE, SPHERE) for a in group for b in group if a is not b]
PAIR_IDS = [f"{a.name}->{b.name}" for a, b in PAIRS]


def sample(chart, n, seed):
    """Coordinates in ``chart`` of n random points that every chart of its manifold covers."""
    rng = np.random.default_rng(seed)
    if chart.manifold == "plane":
        r = rng.uniform(0.2, 3.0, n)
        th = rng.uniform(-3.0, 3.0, n)
        p = np.stack([r * np.cos(th), r * np.sin(th)], -1)
    else:
        lat = rng.uniform(-1.4, 1.4, n)
        lon = rng.uniform(-3.0, 3.0, n)
        p = np.stack([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)], -1)
    return chart.from_manifold(p)


# --------------------------------------------------------------------------------- points
@pytest.mark.parametrize("chart1, chart2", PAIRS, ids=PAIR_IDS)
def test_round_trip_is_the_identity(chart1, chart2):
    q1 = sample(chart1, 50, 1)
    q2 = transition_point(q1, chart1, chart2)
    assert np.allclose(transition_point(q2, chart2, chart1), q1, rtol=1e-12, atol=1e-12)
    assert np.allclose(chart2.to_manifold(q2), chart1.to_manifold(q1), atol=1e-14)


def test_known_points():
    assert np.allclose(transition_point([0.0, 2.0], CARTESIAN, POLAR), [2.0, np.pi / 2])
    assert np.allclose(transition_point([2.0, -np.pi / 2], POLAR, CARTESIAN), [0.0, -2.0], atol=1e-15)
    # the equator is the unit circle in both stereographic charts; the north pole's image in the south chart is 0
    assert np.allclose(transition_point([0.0, 1.0], LATITUDE_LONGITUDE, STEREOGRAPHIC_NORTH), [np.cos(1.0), np.sin(1.0)])
    assert np.allclose(STEREOGRAPHIC_SOUTH.from_manifold([0.0, 0.0, 1.0]), [0.0, 0.0])


@settings(max_examples=60, deadline=None)
@given(st.tuples(st.floats(-5, 5), st.floats(-5, 5)).filter(lambda q: np.hypot(*q) > 1e-3))
def test_stereographic_transition_is_the_inversion(q):
    q = np.array(q)
    assert np.allclose(transition_point(q, STEREOGRAPHIC_NORTH, STEREOGRAPHIC_SOUTH), q / (q @ q), rtol=1e-10)
    with pytest.raises(ValueError, match="q1 = .*south pole"):
        transition_point([0.0, 0.0], STEREOGRAPHIC_NORTH, STEREOGRAPHIC_SOUTH)


# ---------------------------------------------------------------------------- Jacobians
def _sympy_jacobians():
    """Jacobians of four overlap maps derived symbolically from the charts' textbook formulas."""
    x, y, r, th, u, v, lat, lon = sp.symbols("x y r theta u v lat lon", real=True)
    cart_to_polar = sp.Matrix([sp.sqrt(x**2 + y**2), sp.atan2(y, x)]).jacobian([x, y])
    polar_to_cart = sp.Matrix([r * sp.cos(th), r * sp.sin(th)]).jacobian([r, th])
    X, Y, Z = sp.cos(lat) * sp.cos(lon), sp.cos(lat) * sp.sin(lon), sp.sin(lat)
    latlon_to_north = sp.Matrix([X / (1 - Z), Y / (1 - Z)]).jacobian([lat, lon])
    north_to_south = sp.Matrix([u / (u**2 + v**2), v / (u**2 + v**2)]).jacobian([u, v])
    return {
        (CARTESIAN, POLAR): sp.lambdify((x, y), cart_to_polar),
        (POLAR, CARTESIAN): sp.lambdify((r, th), polar_to_cart),
        (LATITUDE_LONGITUDE, STEREOGRAPHIC_NORTH): sp.lambdify((lat, lon), latlon_to_north),
        (STEREOGRAPHIC_NORTH, STEREOGRAPHIC_SOUTH): sp.lambdify((u, v), north_to_south),
    }


SYMPY = _sympy_jacobians()


@pytest.mark.parametrize("pair", list(SYMPY), ids=lambda p: f"{p[0].name}->{p[1].name}")
def test_transition_jacobian_matches_sympy(pair):
    chart1, chart2 = pair
    q1 = sample(chart1, 20, 2)
    J = transition_jacobian(q1, chart1, chart2)
    for q, Jq in zip(q1, J):
        assert np.allclose(Jq, np.array(SYMPY[pair](*q), float), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("chart1, chart2", PAIRS, ids=PAIR_IDS)
def test_transition_jacobian_matches_central_differences(chart1, chart2):
    q1 = sample(chart1, 10, 3)
    J = transition_jacobian(q1, chart1, chart2)
    h = 1e-6
    for i in range(chart1.dim):
        e = np.zeros(chart1.dim)
        e[i] = h
        fd = (transition_point(q1 + e, chart1, chart2) - transition_point(q1 - e, chart1, chart2)) / (2 * h)
        assert np.allclose(J[..., :, i], fd, rtol=1e-6, atol=1e-6)


@pytest.mark.parametrize("chart1, chart2", PAIRS, ids=PAIR_IDS)
def test_jacobians_of_the_two_directions_are_inverse(chart1, chart2):
    q1 = sample(chart1, 20, 4)
    q2 = transition_point(q1, chart1, chart2)
    assert np.allclose(transition_jacobian(q2, chart2, chart1) @ transition_jacobian(q1, chart1, chart2), np.eye(2),
                       atol=1e-10)


@pytest.mark.parametrize("chart", [POLAR, *SPHERE], ids=lambda c: c.name)
def test_coordinate_basis_vectors_are_velocities_of_the_point(chart):
    """Column i of d phi^-1/dq is the velocity of the point as q_i grows (central differences)."""
    q = sample(chart, 10, 5)
    J = chart.jacobian_to_manifold(q)
    h = 1e-6
    for i in range(2):
        e = np.zeros(2)
        e[i] = h
        assert np.allclose(J[..., i], (chart.to_manifold(q + e) - chart.to_manifold(q - e)) / (2 * h), atol=1e-8)


# ------------------------------------------------------------------------------ vectors
@pytest.mark.parametrize("chart1, chart2", PAIRS, ids=PAIR_IDS)
def test_a_vector_is_the_velocity_of_a_curve_in_both_charts(chart1, chart2):
    """v2 = J v1 is the chart-2 velocity of the curve q1 + t v1: a difference quotient of its image."""
    q1 = sample(chart1, 10, 6)
    v1 = np.random.default_rng(7).normal(size=q1.shape)
    q2, v2 = transition_vector(q1, v1, chart1, chart2)
    h = 1e-6
    fd = (transition_point(q1 + h * v1, chart1, chart2) - transition_point(q1 - h * v1, chart1, chart2)) / (2 * h)
    assert np.allclose(v2, fd, rtol=1e-6, atol=1e-6)
    assert np.allclose(q2, transition_point(q1, chart1, chart2))


def test_the_author_s_points_and_vectors():
    # rlhatton/GeometryOfMotionCodebase @049bfdf, Chapter_1_Examples/E105_Cartesian_Polar_Transition.py,
    # run from a temp copy: (3, 3) -> polar [4.242640687119285, 0.7853981633974483] -> back [3, 2.9999999999999996]
    q2 = transition_point([3.0, 3.0], CARTESIAN, POLAR)
    assert np.allclose(q2, [4.242640687119285, 0.7853981633974483], rtol=1e-15)
    assert np.allclose(transition_point(q2, POLAR, CARTESIAN), [3.0, 2.9999999999999996], rtol=1e-15)
    # Chapter_2_Examples/E405_velocity_cartesian_polar.py (his Jacobian is numdifftools' numerical one):
    # v = (0, 1) at (2, 0) -> polar [0, 0.4999999999999999] at [2, 0]
    q, v = transition_vector([2.0, 0.0], [0.0, 1.0], CARTESIAN, POLAR)
    assert np.allclose(q, [2.0, 0.0]) and np.allclose(v, [0.0, 0.4999999999999999], atol=1e-13)
    # v = (1, 1) at (1, 1) -> polar [1.4142135623731054, -9.99e-16] at [1.4142135623730951, 0.7853981633974483]
    q, v = transition_vector([1.0, 1.0], [1.0, 1.0], CARTESIAN, POLAR)
    assert np.allclose(q, [1.4142135623730951, 0.7853981633974483], rtol=1e-15)
    assert np.allclose(v, [1.4142135623731054, -9.9920072216264089e-16], atol=1e-13)


# ------------------------------------------------------------------------------- fields
def test_the_author_s_outward_field_is_radial_in_the_polar_chart():
    # Chapter_2_Examples/E423_vector_field_cartesian_polar_transition_commutative_test.py: the outward field
    # X(x, y) = (x, y) read in the polar chart, at polar points (2, pi/4), (1, 2), (sqrt 5, atan2(-1, 2)), gave
    # [2.0000000000000666, -1.08e-14], [0.99999999999997435, -4.5e-15], [2.2360679774993546, -1.5e-14] (numerical Jacobian)
    X2 = transition_field(lambda q, t: q, CARTESIAN, POLAR)
    q2 = np.array([[2.0, np.pi / 4], [1.0, 2.0], [np.sqrt(5.0), np.arctan2(-1.0, 2.0)]])
    his = np.array([[2.0000000000000666, -1.0758620304397857e-14], [0.99999999999997435, -4.5180218003571935e-15],
                    [2.2360679774993546, -1.5321077739827160e-14]])
    assert np.allclose(X2(q2), his, atol=1e-12)
    assert np.allclose(X2(q2), np.stack([q2[:, 0], 0 * q2[:, 0]], -1), atol=1e-14)   # exactly (r, 0)


def test_the_author_s_saddle_flow_in_two_charts():
    # Chapter_2_Examples/E425_vector_field_flow.py: the saddle field (y, x) from (-1.5, 1.8) for t in [0, 2.5].
    # With his solve_ivp defaults (RK45, rtol 1e-3) he gets the Cartesian end [1.691840034865145, 1.9630429122118134]
    # and the polar end [2.6365997514762016, 0.8594588970767959] (r 1.7 % long: the loose default tolerance); the
    # same call with rtol=1e-10, atol=1e-12 passed to his integrate gives [2.5913857853084497, 0.859380307289322].
    def saddle(q, t):
        return np.stack([q[..., 1], q[..., 0]], -1)

    q0 = np.array([-1.5, 1.8])
    _, qc = integral_curve(VectorField(saddle, 2), q0, (0.0, 2.5))
    _, qp = integral_curve(transition_field(saddle, CARTESIAN, POLAR), transition_point(q0, CARTESIAN, POLAR), (0.0, 2.5))
    assert np.allclose(qc[-1], [1.691840034865145, 1.9630429122118134], atol=2e-3)
    assert np.allclose(qp[-1], [2.6365997514762016, 0.8594588970767959], rtol=0.02)
    assert np.allclose(qp[-1], [2.5913857853084497, 0.859380307289322], rtol=1e-8)
    exact = 0.15 * np.exp(2.5) * np.array([1, 1]) + 1.65 * np.exp(-2.5) * np.array([-1, 1])   # x+y, x-y decouple
    assert np.allclose(qc[-1], exact, rtol=1e-9)
    assert np.allclose(transition_point(qp[-1], POLAR, CARTESIAN), exact, rtol=1e-8)
    # his second flow, from (-1.8, 1.5), crosses the ray y = 0, x < 0 (his polar angle ends at 3.85 > pi):
    # our polar chart does not cover that ray, and the transitioned field refuses to go there
    with pytest.raises(ValueError, match="q "):
        integral_curve(transition_field(saddle, CARTESIAN, POLAR), transition_point([-1.8, 1.5], CARTESIAN, POLAR),
                       (0.0, 2.5))


@pytest.mark.parametrize("name", sorted(FIELDS))
def test_an_integral_curve_maps_to_the_integral_curve_in_the_other_chart(name):
    """gamma_2 = phi_2 o phi_1^-1 o gamma_1: solve in Cartesian, map, and solve the transitioned field in polar."""
    q0 = np.array([0.9, 0.6])
    t = np.linspace(0.0, 0.8, 9)
    _, c1 = integral_curve(VectorField(FIELDS[name], 2), q0, (0.0, 0.8), t_eval=t)
    X2 = transition_field(FIELDS[name], CARTESIAN, POLAR)
    # an independent solver on the chart-2 field: scipy's solve_ivp directly, LSODA
    sol = solve_ivp(lambda s, q: X2(q, s), (0.0, 0.8), transition_point(q0, CARTESIAN, POLAR), t_eval=t,
                    method="LSODA", rtol=1e-11, atol=1e-12)
    assert np.allclose(sol.y.T, transition_point(c1, CARTESIAN, POLAR), rtol=1e-7, atol=1e-8)


def test_a_rotation_of_the_sphere_is_a_rotation_of_the_stereographic_plane():
    """Spinning about the z axis is lon_dot = 1 in latitude/longitude and (u, v) -> (-v, u) in either
    stereographic chart (the projection commutes with rotations about the axis through its pole)."""
    spin = transition_field(lambda q, t: np.stack([0 * q[..., 0], 1 + 0 * q[..., 1]], -1), LATITUDE_LONGITUDE,
                            STEREOGRAPHIC_NORTH)
    q = sample(STEREOGRAPHIC_NORTH, 20, 8)
    assert np.allclose(spin(q), np.stack([-q[:, 1], q[:, 0]], -1), atol=1e-12)
    again = transition_field(spin, STEREOGRAPHIC_NORTH, STEREOGRAPHIC_SOUTH)
    q = sample(STEREOGRAPHIC_SOUTH, 20, 9)
    assert np.allclose(again(q), np.stack([-q[:, 1], q[:, 0]], -1), atol=1e-12)


@pytest.mark.parametrize("chart2", [STEREOGRAPHIC_NORTH, STEREOGRAPHIC_SOUTH], ids=lambda c: c.name)
def test_an_integral_curve_on_the_sphere_maps_to_the_one_in_a_stereographic_chart(chart2):
    """A field given in latitude/longitude, solved there and in a stereographic chart; both compared
    as points of the sphere with the curve solved in R^3 for the field's embedded velocity."""
    def X_latlon(q, t):
        return np.stack([0.4 * np.cos(q[..., 0]) * np.cos(q[..., 1]), 1.0 + 0 * q[..., 1]], -1)

    q0 = np.array([0.3, -1.0])
    t = np.linspace(0.0, 1.5, 7)
    _, c1 = integral_curve(VectorField(X_latlon, 2), q0, (0.0, 1.5), t_eval=t)
    _, c2 = integral_curve(transition_field(X_latlon, LATITUDE_LONGITUDE, chart2),
                           transition_point(q0, LATITUDE_LONGITUDE, chart2), (0.0, 1.5), t_eval=t)
    assert np.allclose(chart2.to_manifold(c2), LATITUDE_LONGITUDE.to_manifold(c1), atol=1e-8)

    def xyz_rhs(s, p):   # the same field as a velocity in R^3, through textbook lat/lon formulas
        lat, lon = np.arcsin(p[2]), np.arctan2(p[1], p[0])
        dlat, dlon = X_latlon(np.array([lat, lon]), s)
        north = [-np.sin(lat) * np.cos(lon), -np.sin(lat) * np.sin(lon), np.cos(lat)]
        east = [-np.sin(lon), np.cos(lon), 0.0]
        return dlat * np.array(north) + np.cos(lat) * dlon * np.array(east)

    p0 = [np.cos(0.3) * np.cos(-1.0), np.cos(0.3) * np.sin(-1.0), np.sin(0.3)]
    sol = solve_ivp(xyz_rhs, (0.0, 1.5), p0, t_eval=t, rtol=1e-11, atol=1e-12)
    assert np.allclose(chart2.to_manifold(c2), sol.y.T, atol=1e-8)


def test_a_field_transitioned_there_and_back_is_the_field():
    X1 = VectorField(FIELDS["limit cycle (van der Pol)"], 2)
    back = transition_field(transition_field(X1, CARTESIAN, POLAR), POLAR, CARTESIAN)
    q = sample(CARTESIAN, 30, 10)
    assert np.allclose(back(q), X1(q), atol=1e-12)


# ------------------------------------------------------------------------------- paths
def test_a_path_is_cut_where_it_crosses_the_polar_ray():
    line = np.stack([np.full(41, -1.0), np.linspace(-1, 1, 41)], -1)     # crosses the ray at (-1, 0)
    pieces = transition_path(line, CARTESIAN, POLAR)
    assert len(pieces) == 2
    assert all(np.all(np.sign(p[:, 1]) == np.sign(p[0, 1])) for p in pieces)   # theta keeps one sign in each
    assert sum(len(p) for p in pieces) == 40                                   # only (-1, 0) itself is dropped
    smooth = np.stack([np.full(41, 1.0), np.linspace(-1, 1, 41)], -1)
    (piece,) = transition_path(smooth, CARTESIAN, POLAR)
    assert np.allclose(piece, transition_point(smooth, CARTESIAN, POLAR))
    step = np.stack([np.full(4, -1.0), [-0.5, -0.1, 0.1, 0.5]], -1)            # jumps over the ray between samples
    assert [len(p) for p in transition_path(step, CARTESIAN, POLAR)] == [2, 2]


# --------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("bad", [[-1.0, 0.0], [0.0, 0.0], [-3.0, -0.0]])
def test_polar_refuses_the_ray_and_the_origin(bad):
    with pytest.raises(ValueError, match=r"q1 = .* outside the overlap.*ray y = 0, x <= 0"):
        transition_point(bad, CARTESIAN, POLAR)
    with pytest.raises(ValueError, match=r"p = .*outside the domain of the polar chart"):
        POLAR.from_manifold(bad)
    assert not in_overlap(bad, CARTESIAN, POLAR)


@pytest.mark.parametrize("bad", [[0.0, 1.0], [-1.0, 1.0], [1.0, np.pi], [1.0, -np.pi], [1.0, 4.0]])
def test_polar_refuses_coordinates_outside_its_image(bad):
    with pytest.raises(ValueError, match=r"q1 = .*outside the polar chart"):
        transition_point(bad, POLAR, CARTESIAN)
    with pytest.raises(ValueError, match=r"v1"):
        transition_vector([1.0, 0.0], [1.0, 2.0, 3.0], POLAR, CARTESIAN)


def test_sphere_charts_refuse_their_missing_points():
    with pytest.raises(ValueError, match=r"q1 = .*outside the overlap.*north pole"):
        transition_point([0.0, 0.0], STEREOGRAPHIC_SOUTH, STEREOGRAPHIC_NORTH)   # the north pole
    with pytest.raises(ValueError, match=r"q1 = .*latitude/longitude"):
        transition_point([-1.0, 0.0], STEREOGRAPHIC_NORTH, LATITUDE_LONGITUDE)   # (-1, 0, 0), on the cut
    assert not in_overlap([-1.0, 0.0], STEREOGRAPHIC_NORTH, LATITUDE_LONGITUDE)
    with pytest.raises(ValueError, match=r"p must lie on the sphere"):
        LATITUDE_LONGITUDE.from_manifold([1.0, 1.0, 0.0])
    with pytest.raises(ValueError, match=r"q1 = .*outside the latitude/longitude chart"):
        transition_point([2.0, 0.0], LATITUDE_LONGITUDE, STEREOGRAPHIC_NORTH)


def test_charts_of_different_manifolds_and_non_charts_are_refused():
    with pytest.raises(ValueError, match="chart1 and chart2 must cover one manifold"):
        transition_point([1.0, 0.0], CARTESIAN, STEREOGRAPHIC_NORTH)
    with pytest.raises(TypeError, match="chart2 must be a Chart"):
        transition_point([1.0, 0.0], CARTESIAN, "polar")
    with pytest.raises(TypeError, match="field must be a VectorField"):
        transition_field(3.0, CARTESIAN, POLAR)
    with pytest.raises(ValueError, match="field must have dimension 2"):
        transition_field(VectorField(lambda q, t: q, 3), CARTESIAN, POLAR)
    with pytest.raises(ValueError, match=r"q = .*outside the polar chart"):
        transition_field(FIELDS["saddle"], CARTESIAN, POLAR)([1.0, np.pi])
    with pytest.raises(ValueError, match="pole must be 'north' or 'south'"):
        type(STEREOGRAPHIC_NORTH)("east")
    assert set(CHARTS.values()) >= {CARTESIAN, POLAR, LATITUDE_LONGITUDE, STEREOGRAPHIC_NORTH, STEREOGRAPHIC_SOUTH}

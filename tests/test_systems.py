"""The six locomotion systems of chapter 3, each checked against an independent route.

* Pfaffian -> connection: re-derived here with sympy from the world positions of wheels and
  link centres (never from gm_core's Jacobians), then lambdified;
* momentum-conserving systems: zero total momentum checked with finite differences of the
  links' world poses, and the mass matrix checked against the kinetic energy;
* low-Reynolds swimmer: the distributed drag integrated by quadrature along every link sums to
  zero force and moment;
* kinematic snake: the link-centre lateral velocities from gm_core.chains.three_link_jacobians
  vanish;
* the system laws (``@system_law``, jaxlie's ``general_group_test`` pattern, like
  tests/test_group_laws.py): what holds for every locomotion system, written once and run over
  every system of ALL_SYSTEMS plus LinkChain variants, a Reframed system, a SlenderBody and a
  modal chain with inert links from sysplotter's catalog, at
  the batch shapes (), (1,) and (3, 1, 2). A system added to ALL_SYSTEMS gets every law.
"""
import warnings

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

import gm_core
from gm_core import SE2, SingularShapeError
from gm_core.chains import MobileChain
from gm_core.chains.three_link import three_link_jacobians, three_link_poses
from gm_core.systems import (
    ALL_SYSTEMS,
    Ackerman,
    DifferentialDrive,
    FloatingSnake,
    HighReSwimmer,
    InteractingChain,
    KinematicSnake,
    LinkChain,
    LowReSwimmer,
    Reframed,
    SlenderBody,
    TapeMeasure,
    catalog,
)
from gm_core.systems.base import LocomotionSystem, SystemPart, rectangle_outline
from gm_core.systems.connection import connection_from_mass_matrix, connection_from_pfaffian
from gm_core.systems.fluids import ellipse_added_mass
from gm_core.systems.motion import check_system, curvature_form, fd_connection_derivative, validate_system
from gm_core.systems.reframed import CentreOfMassFrame

RNG = np.random.default_rng(20261122)


def regular_shapes(system, n=40, rng=RNG):
    """Random shapes away from singular ones."""
    lo = np.array([l for l, _ in system.shape_limits])
    hi = np.array([h for _, h in system.shape_limits])
    r = rng.uniform(lo, hi, (4 * n, 2))
    keep = np.abs(system.singularity(r)) > 0.05
    return r[keep][:n]


# ------------------------------------------------------------------ sympy routes (independent)
a1, a2 = sp.symbols("alpha1 alpha2", real=True)
X, Y, TH = sp.symbols("x y theta", real=True)
Q = [X, Y, TH, a1, a2]
QD = sp.symbols("xd yd thd a1d a2d", real=True)
XI = sp.symbols("xix xiy xith", real=True)
# world velocity = R(theta) (xi_x, xi_y), theta_dot = xi_theta: write every constraint in (xi, r_dot)
TO_BODY = {QD[0]: sp.cos(TH) * XI[0] - sp.sin(TH) * XI[1],
           QD[1]: sp.sin(TH) * XI[0] + sp.cos(TH) * XI[1], QD[2]: XI[2]}


def _ddt(f):
    return sum(sp.diff(f, q) * qd for q, qd in zip(Q, QD))


def _world_point(px, py):
    return (X + sp.cos(TH) * px - sp.sin(TH) * py, Y + sp.sin(TH) * px + sp.cos(TH) * py)


def _pfaffian_rows(constraints):
    vel = list(XI) + [QD[3], QD[4]]
    rows = [sp.expand(c.subs(TO_BODY)) for c in constraints]
    return sp.Matrix([[sp.diff(c, v) for v in vel] for c in rows])


def _lambdified_connection(W):
    Wx, Wr = W[:, :3], W[:, 3:]
    f = sp.lambdify((X, Y, TH, a1, a2), [Wx, Wr], "numpy")

    def A(r):
        out = []
        for s in np.atleast_2d(r):
            wx, wr = f(0.3, -0.2, 0.7, s[0], s[1])  # any position: the result must not depend on it
            out.append(np.linalg.solve(np.array(wx, float), np.array(wr, float)))
        return np.array(out)
    return A


def sympy_wheel_constraint(px, py, heading, R=None, angle=None):
    """No-slide (and, with R, no-slip) of a wheel at body point (px, py) pointing along heading."""
    wx, wy = _world_point(px, py)
    vx, vy = _ddt(wx), _ddt(wy)
    h = TH + heading
    along = sp.cos(h) * vx + sp.sin(h) * vy
    across = -sp.sin(h) * vx + sp.cos(h) * vy
    out = [across]
    if R is not None:
        out.insert(0, along - R * _ddt(angle))
    return out


def test_diff_drive_matches_sympy_derivation_and_book_3_8():
    R, w = 0.7, 1.3
    cons = (sympy_wheel_constraint(0, w, 0, R, a1)[:1] + sympy_wheel_constraint(0, -w, 0, R, a2)[:1]
            + sympy_wheel_constraint(0, w, 0))
    A_ref = _lambdified_connection(_pfaffian_rows(cons))
    s = DifferentialDrive(wheel_radius=R, half_width=w)
    r = RNG.uniform(-3, 3, (5, 2))
    np.testing.assert_allclose(s.connection(r), A_ref(r), atol=1e-13)
    np.testing.assert_allclose(connection_from_pfaffian(s.pfaffian(r)), s.connection(r), atol=1e-13)
    # (3.8): R = 2, w = 1 gives xi = [[1, 1], [0, 0], [-1, 1]] r_dot
    np.testing.assert_allclose(-DifferentialDrive(2.0, 1.0).connection([0.0, 0.0]),
                               [[1, 1], [0, 0], [-1, 1]], atol=1e-15)
    # wheel 1 is on the left: driving it alone turns the car clockwise (to the right)
    assert s.body_velocity([0, 0], [1, 0])[2] < 0


def test_ackerman_matches_sympy_bicycle_and_book_3_9():
    R, L = 0.4, 1.7
    cons = (sympy_wheel_constraint(0, 0, 0, R, a1) + sympy_wheel_constraint(L, 0, a2))
    A_ref = _lambdified_connection(_pfaffian_rows(cons))
    s = Ackerman(wheel_radius=R, wheelbase=L)
    r = regular_shapes(s, 20)
    np.testing.assert_allclose(s.connection(r), A_ref(r), atol=1e-12)
    xi = s.body_velocity(r, np.tile([1.0, 0.3], (len(r), 1)))
    np.testing.assert_allclose(xi[:, 0], R)
    np.testing.assert_allclose(xi[:, 1], 0, atol=1e-14)
    np.testing.assert_allclose(xi[:, 2], R / L * np.tan(r[:, 1]), rtol=1e-12)
    # (3.9) is the R = L = 1 case
    np.testing.assert_allclose(-Ackerman().connection([0.2, 0.5]), [[1, 0], [0, 0], [np.tan(0.5), 0]],
                               atol=1e-15)


def _sympy_link_centres(l1, l2, l3):
    """Link-centre positions and headings in the middle frame, derived directly from the geometry."""
    # walk from the middle link centre along the chain: link 1 is turned by -alpha1, link 3 by alpha2
    p1 = (-l2 / 2 - l1 / 2 * sp.cos(-a1), -l1 / 2 * sp.sin(-a1), -a1)
    p3 = (l2 / 2 + l3 / 2 * sp.cos(a2), l3 / 2 * sp.sin(a2), a2)
    return [p1, (0, 0, 0), p3]


def test_kinematic_snake_matches_sympy_no_slide_derivation():
    L = (0.8, 1.1, 1.4)
    cons = []
    for px, py, h in _sympy_link_centres(*[sp.nsimplify(v) for v in L]):
        cons += sympy_wheel_constraint(px, py, h)
    A_ref = _lambdified_connection(_pfaffian_rows(cons))
    s = KinematicSnake(L)
    r = regular_shapes(s, 25)
    np.testing.assert_allclose(s.connection(r), A_ref(r), rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(s.connection(r), s.connection_closed_form(r), rtol=1e-10, atol=1e-12)


def test_kinematic_snake_link_centres_do_not_slide():
    s = KinematicSnake((1.0, 0.7, 1.2))
    r = regular_shapes(s, 30)
    r_dot = RNG.normal(size=r.shape)
    xi = s.body_velocity(r, r_dot)
    v = np.concatenate([xi, r_dot], -1)
    for J in three_link_jacobians(r, s.lengths):
        lateral = np.einsum("...j,...j->...", J[..., 1, :], v)
        np.testing.assert_allclose(lateral, 0, atol=1e-11)
    assert np.all(np.abs(xi[:, 1]) < 1e-12)  # the middle link cannot slide either


def world_link_poses(system, g, r):
    """World poses (..., 3, 3) of the link centres (body frame of the system at g)."""
    return SE2.compose(np.asarray(g)[..., None, :], system.link_poses(r))


def fd_link_body_velocities(system, r, r_dot, g=(0.4, -0.3, 0.9), h=1e-6):
    """Link body velocities by central differences of world poses along xi = -A r_dot."""
    g = np.asarray(g, float)
    xi = system.body_velocity(r, r_dot)
    gp, gm = SE2.compose(g, SE2.exp(h * xi)), SE2.compose(g, SE2.exp(-h * xi))
    Pp = world_link_poses(system, gp, r + h * r_dot)
    Pm = world_link_poses(system, gm, r - h * r_dot)
    P0 = world_link_poses(system, g, r)
    world_vel = (Pp - Pm) / (2 * h)
    return P0, world_vel, np.stack([SE2.world_to_body(P0[i], world_vel[i]) for i in range(3)])


def test_three_link_jacobians_agree_with_finite_differences_and_the_frame_graph():
    L = (0.9, 1.2, 0.6)
    r = RNG.uniform(-3, 3, (20, 2))
    Jc = three_link_jacobians(r, L)
    # independent route: the generic chain machinery (product of joint and link elements)
    chain = MobileChain(L, base_link=1)
    Jg = chain.body_jacobians(r, method="direct")
    for i in range(3):
        np.testing.assert_allclose(Jc[i], Jg[..., i, :, :], atol=1e-12)
    assert SE2.isclose(three_link_poses(r, L), chain.frames(r)["g"], atol=1e-12).all()
    h = 1e-6
    for k in range(5):
        v = np.zeros(5)
        v[k] = 1.0
        g0 = np.zeros(3)
        gp, gm = SE2.exp(h * v[:3]), SE2.exp(-h * v[:3])
        Pp = SE2.compose(gp[None], three_link_poses(r + h * v[3:], L))
        Pm = SE2.compose(gm[None], three_link_poses(r - h * v[3:], L))
        P0 = SE2.compose(g0[None], three_link_poses(r, L))
        for i in range(3):
            xi_fd = SE2.world_to_body(P0[:, i], (Pp[:, i] - Pm[:, i]) / (2 * h))
            np.testing.assert_allclose(Jc[i][..., k], xi_fd, atol=1e-8)


@pytest.mark.parametrize("frame", ["com", "middle"])
def test_floating_snake_conserves_zero_momentum(frame):
    s = FloatingSnake((1.0, 0.8, 1.3), masses=(1.0, 2.0, 0.5), inertias=(0.2, 0.1, 0.3), frame=frame)
    r = RNG.uniform(-2.5, 2.5, (10, 2))
    for ri in r:
        rd = RNG.normal(size=2)
        P0, V, _ = fd_link_body_velocities(s, ri, rd)
        m = np.array(s.masses)
        lin = (m[:, None] * V[:, :2]).sum(0)
        ang = (np.array(s.inertias) * V[:, 2] + m * (P0[:, 0] * V[:, 1] - P0[:, 1] * V[:, 0])).sum()
        np.testing.assert_allclose(lin, 0, atol=1e-8)
        np.testing.assert_allclose(ang, 0, atol=1e-8)


def test_floating_snake_mass_matrix_is_the_kinetic_energy():
    s = FloatingSnake((1.0, 0.8, 1.3), masses=(1.0, 2.0, 0.5), inertias=(0.2, 0.1, 0.3), frame="com")
    g, h = np.array([0.1, 0.2, 0.3]), 1e-6
    for ri in RNG.uniform(-2.5, 2.5, (5, 2)):
        v = RNG.normal(size=5)
        Pp = world_link_poses(s, SE2.compose(g, SE2.exp(h * v[:3])), ri + h * v[3:])
        Pm = world_link_poses(s, SE2.compose(g, SE2.exp(-h * v[:3])), ri - h * v[3:])
        V = (Pp - Pm) / (2 * h)
        ke = 0.5 * sum(m * (V[i, 0] ** 2 + V[i, 1] ** 2) + I * V[i, 2] ** 2
                       for i, (m, I) in enumerate(zip(s.masses, s.inertias)))
        assert np.isclose(0.5 * v @ s.mass_matrix(ri) @ v, ke, rtol=1e-7)
        np.testing.assert_allclose(connection_from_mass_matrix(s.mass_matrix(ri)), s.connection(ri), atol=1e-12)


def test_floating_snake_com_frame_and_corrected_3_38():
    s = FloatingSnake()  # unit links, unit masses, slender rods I = 1/12, COM frame
    r = RNG.uniform(-3, 3, (50, 2))
    A = s.connection(r)
    np.testing.assert_allclose(A[:, :2], 0, atol=1e-14)  # the centre of mass does not move
    c1, c2, c12 = np.cos(r[:, 0]), np.cos(r[:, 1]), np.cos(r[:, 0] + r[:, 1])
    D = 13 + 6 * (c1 + c2) + 2 * c12
    np.testing.assert_allclose(A[:, 2, 0], -(3 + 3 * c1 + c12) / D, rtol=1e-12)
    np.testing.assert_allclose(A[:, 2, 1], (3 + 3 * c2 + c12) / D, rtol=1e-12)
    # the rotation row does not depend on the frame's position
    np.testing.assert_allclose(FloatingSnake(frame="middle").connection(r)[:, 2], A[:, 2], atol=1e-13)


def test_low_re_swimmer_distributed_drag_balances():
    k = 2.5
    s = LowReSwimmer((0.9, 1.2, 0.7), drag_ratio=k)
    nodes, weights = np.polynomial.legendre.leggauss(6)  # exact for the quadratic moment integrand
    for ri in RNG.uniform(-2.5, 2.5, (8, 2)):
        rd = RNG.normal(size=2)
        P0, V, _ = fd_link_body_velocities(s, ri, rd)
        F = np.zeros(2)
        M = 0.0
        for i, l in enumerate(s.lengths):
            x, y, th = P0[i]
            t_hat = np.array([np.cos(th), np.sin(th)])
            n_hat = np.array([-np.sin(th), np.cos(th)])
            for sq, wq in zip(nodes * l / 2, weights * l / 2):
                p = np.array([x, y]) + sq * t_hat
                v = V[i, :2] + V[i, 2] * sq * n_hat  # rigid-body velocity of the point
                f = -(v @ t_hat) * t_hat - k * (v @ n_hat) * n_hat
                F += wq * f
                M += wq * (p[0] * f[1] - p[1] * f[0])
        np.testing.assert_allclose(F, 0, atol=1e-8)
        np.testing.assert_allclose(M, 0, atol=1e-8)


def test_low_re_swimmer_matches_corrected_3_44_for_equal_links():
    """(3.44) with L the half-length, plus the middle link's own drag that the draft omits."""
    Lh, k = 0.5, 2.0
    s = LowReSwimmer((2 * Lh,) * 3, drag_ratio=k)
    r = np.array([0.7, -0.4])
    om = s.pfaffian(r)
    J1, J2, J3 = three_link_jacobians(r, s.lengths)
    D = np.diag([2 * Lh * 1.0, 2 * Lh * k, 2 / 3 * k * Lh ** 3])  # (3.41)-(3.43), longitudinal = 1
    c1, s1, c2, s2 = np.cos(r[0]), np.sin(r[0]), np.cos(r[1]), np.sin(r[1])
    T1 = np.array([[c1, s1, 0], [-s1, c1, 0], [Lh * s1, -Lh * (1 + c1), 1]])  # (3.44) as printed
    T3 = np.array([[c2, -s2, 0], [s2, c2, 0], [Lh * s2, Lh * (1 + c2), 1]])
    F = T1 @ D @ J1 + D @ J2 + T3 @ D @ J3
    np.testing.assert_allclose(om, F, atol=1e-14)
    F_draft = T1 @ D @ J1 + T3 @ D @ J3
    assert not np.allclose(connection_from_pfaffian(F_draft), s.connection(r), atol=1e-3)


def test_slender_link_drag_is_the_drafts_3_41_to_3_43_at_drag_ratio_2():
    """Notebook 11's statement: the draft's (3.41)-(3.43), with its overall constant k_d and
    half-length L, are diag(l, k l, k l^3/12) with l = 2 L and k = 2, times k_d / 2."""
    from gm_core.systems.fluids import slender_link_drag
    for L, k_d in [(0.5, 1.0), (0.25, 3.0), (1.3, 0.7)]:
        ell, xi = sp.symbols("ell xi")
        draft = [sp.integrate(sp.Rational(1, 2) * k_d * xi, (ell, -L, L)) / xi,     # (3.41)
                 sp.integrate(k_d * xi, (ell, -L, L)) / xi,                        # (3.42)
                 sp.integrate(k_d * ell * ell * xi, (ell, -L, L)) / xi]            # (3.43)
        np.testing.assert_allclose(np.diag([float(d) for d in draft]),
                                   k_d / 2 * slender_link_drag(2 * L, 2.0), rtol=1e-12)


def test_ellipse_added_mass_and_high_re_momentum():
    a, b, rho = 0.5, 0.05, 1.3
    Ma = ellipse_added_mass(a, b, rho)
    np.testing.assert_allclose(np.diag(Ma), [np.pi * rho * b ** 2, np.pi * rho * a ** 2,
                                             np.pi * rho * (a ** 2 - b ** 2) ** 2 / 8])
    # a flat plate (b = 0) rotating: pi rho a^4 / 8, the classic strip result
    assert np.isclose(ellipse_added_mass(1.0, 0.0)[2, 2], np.pi / 8)
    s = HighReSwimmer((1.0, 1.3, 0.8), aspect_ratio=6.0, fluid_density=rho, body_density=0.7)
    Ms = s.link_matrices()
    for ri in RNG.uniform(-2.5, 2.5, (8, 2)):
        rd = RNG.normal(size=2)
        P0, V, Vb = fd_link_body_velocities(s, ri, rd)
        # spatial (world-frame) momentum of each link: linear R_i (M xi_i), angular M_th w + x x p
        lin = np.zeros(2)
        ang = 0.0
        for i in range(3):
            pb = Ms[i] @ Vb[i]
            th = P0[i, 2]
            pw = np.array([np.cos(th) * pb[0] - np.sin(th) * pb[1], np.sin(th) * pb[0] + np.cos(th) * pb[1]])
            lin += pw
            ang += pb[2] + P0[i, 0] * pw[1] - P0[i, 1] * pw[0]
        np.testing.assert_allclose(lin, 0, atol=1e-8)
        np.testing.assert_allclose(ang, 0, atol=1e-8)


def test_high_re_body_density_only_adds_body_inertia():
    r = np.array([0.5, 1.0])
    base = HighReSwimmer(body_density=0.0).connection(r)
    heavy = HighReSwimmer(body_density=5.0).connection(r)
    assert not np.allclose(base, heavy)
    a, b = 0.5, 0.05
    m = 5.0 * np.pi * a * b
    np.testing.assert_allclose(HighReSwimmer(body_density=5.0).link_matrices()[0] -
                               HighReSwimmer().link_matrices()[0],
                               np.diag([m, m, m * (a * a + b * b) / 4]), atol=1e-15)


# ------------------------------------------------------------------ shared behaviour
@pytest.mark.parametrize("name", list(ALL_SYSTEMS))
def test_connection_is_batched(name):
    s = ALL_SYSTEMS[name]
    r = regular_shapes(s, 12).reshape(3, 4, 2)
    A = s.connection(r)
    assert A.shape == (3, 4, 3, 2)
    for idx in np.ndindex(3, 4):
        np.testing.assert_allclose(A[idx], s.connection(r[idx]), rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(A, connection_from_pfaffian(s.pfaffian(r)), rtol=1e-10, atol=1e-12)
    assert s.connection(r[0, 0]).shape == (3, 2)
    assert s.part_poses(r).shape == (3, 4, len(s.parts()), 3)


@pytest.mark.parametrize("name", list(ALL_SYSTEMS))
def test_connection_matches_finite_difference_of_the_constraint(name):
    """A r_dot must be the xi that zeroes the Pfaffian; check omega [xi; r_dot] = 0 directly."""
    s = ALL_SYSTEMS[name]
    r = regular_shapes(s, 10)
    rd = RNG.normal(size=r.shape)
    xi = s.body_velocity(r, rd)
    resid = np.einsum("...ij,...j->...i", s.pfaffian(r), np.concatenate([xi, rd], -1))
    np.testing.assert_allclose(resid, 0, atol=1e-10)


def test_singular_shapes_give_nan_quietly():
    ks = KinematicSnake()
    t = np.linspace(-3, 3, 7)
    diag = np.stack([t, t], -1)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        A = ks.connection(diag)
        A2 = Ackerman().connection([[0.0, np.pi / 2], [0.0, -np.pi / 2]])
    assert np.all(np.isnan(A)) and np.all(np.isnan(A2))
    assert np.all(ks.is_singular(diag))
    assert not np.any(ks.is_singular(diag + [0.0, 0.3]))
    assert np.all(np.isfinite(ks.connection(diag + [0.0, 0.3])))
    # unequal links: singular where the closed form's D vanishes, not on the diagonal
    s = KinematicSnake((1.0, 1.0, 2.0))
    assert not s.is_singular([0.5, 0.5])
    a = 0.8  # D = 2 sin a1 - sin a2 + sin(a1 - a2) vanishes at a1 = 0 only if sin a2 = sin(-a2): a2 = 0
    assert s.is_singular([0.0, 0.0]) and not s.is_singular([0.0, a])
    for name in ["DifferentialDrive", "FloatingSnake", "LowReSwimmer", "HighReSwimmer"]:
        assert np.all(np.isfinite(ALL_SYSTEMS[name].connection(RNG.uniform(-3, 3, (50, 2)))))


def test_singular_error_is_a_value_error():
    assert issubclass(SingularShapeError, ValueError)
    assert gm_core.SingularShapeError is SingularShapeError


@pytest.mark.parametrize("make, arg", [
    (lambda v: KinematicSnake(lengths=v), "lengths"),
    (lambda v: FloatingSnake(lengths=v), "lengths"),
    (lambda v: LowReSwimmer(lengths=v), "lengths"),
    (lambda v: HighReSwimmer(lengths=v), "lengths"),
    (lambda v: FloatingSnake(masses=v), "masses"),
    (lambda v: FloatingSnake(inertias=v), "inertias"),
])
def test_bad_three_link_parameters(make, arg):
    for bad in [(1.0, 0.0, 1.0), (1.0, -1.0, 1.0)]:
        with pytest.raises(ValueError, match=arg):
            make(bad)
    with pytest.raises(ValueError, match=arg):
        make((1.0, 1.0))
    with pytest.raises(ValueError, match=arg):
        make((1.0, np.nan, 1.0))


@pytest.mark.parametrize("make, arg", [
    (lambda v: DifferentialDrive(wheel_radius=v), "wheel_radius"),
    (lambda v: DifferentialDrive(half_width=v), "half_width"),
    (lambda v: Ackerman(wheel_radius=v), "wheel_radius"),
    (lambda v: Ackerman(wheelbase=v), "wheelbase"),
    (lambda v: LowReSwimmer(drag_ratio=v), "drag_ratio"),
    (lambda v: HighReSwimmer(aspect_ratio=v), "aspect_ratio"),
    (lambda v: HighReSwimmer(fluid_density=v), "fluid_density"),
])
def test_bad_scalar_parameters(make, arg):
    for bad in [0.0, -1.0]:
        with pytest.raises(ValueError, match=arg):
            make(bad)
    with pytest.raises(TypeError, match=arg):
        make("big")


def test_other_bad_parameters():
    with pytest.raises(ValueError, match="aspect_ratio"):
        HighReSwimmer(aspect_ratio=0.5)
    with pytest.raises(ValueError, match="body_density"):
        HighReSwimmer(body_density=-1.0)
    with pytest.raises(ValueError, match="frame"):
        FloatingSnake(frame="head")


@pytest.mark.parametrize("name", list(ALL_SYSTEMS))
def test_bad_shapes_name_the_argument(name):
    s = ALL_SYSTEMS[name]
    with pytest.raises(ValueError, match="r"):
        s.connection([0.1, 0.2, 0.3])
    with pytest.raises(ValueError, match=r"\br\b"):
        s.connection(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="NaN"):
        s.connection([np.nan, 0.0])
    with pytest.raises(TypeError, match=r"\br\b"):
        s.connection("shape")
    with pytest.raises(ValueError, match="r_dot"):
        s.body_velocity([0.1, 0.2], [1.0])


# ------------------------------------------------------------------ nonholonomy: rolling disk vs (3.viii)
def test_rolling_disk_moves_obey_the_no_slide_constraint():
    from gm_core.systems.rolling_disk import disk_constraint_world, disk_moves_path, parallel_park_moves

    t, g = disk_moves_path(parallel_park_moves(0.7, 0.9), n_per_move=200)
    # world velocity by finite differences inside each move: no sideways component (3.v)
    gd = np.gradient(g, t, axis=0)
    inner = np.ones(len(t), bool)
    inner[::200] = False
    inner[1::200] = False
    inner[-1] = False
    assert np.max(np.abs(disk_constraint_world(g[inner], gd[inner]))) < 1e-4


def test_parallel_parking_moves_the_disk_sideways_exactly_as_the_group_commutator():
    from gm_core.systems.rolling_disk import disk_moves_path, parallel_park_displacement, parallel_park_moves

    d, phi = 0.8, 0.5
    net = parallel_park_displacement(d, phi)
    # elementary geometry: forward d, turn, back d along the turned heading, turn back
    np.testing.assert_allclose(net, [d * (1 - np.cos(phi)), -d * np.sin(phi), 0.0], atol=1e-14)
    _, g = disk_moves_path(parallel_park_moves(d, phi))
    np.testing.assert_allclose(g[-1], net, atol=1e-12)
    assert abs(net[1]) > 0.3     # a sideways displacement the velocity constraint forbids instantaneously


@pytest.mark.parametrize("eps", [0.2, 0.1, 0.05])
def test_small_parking_loops_match_the_area_times_lie_bracket(eps):
    from scipy.linalg import expm, logm

    from gm_core.systems.rolling_disk import DISK_DRIVE, DISK_TURN, bracket_estimate, parallel_park_displacement

    d, phi = 1.3 * eps, 0.8 * eps
    net = parallel_park_displacement(d, phi)
    est = bracket_estimate(d, phi)
    # independent route: matrix exponentials and the matrix commutator of the hat matrices
    X, Y = SE2.hat(DISK_DRIVE), SE2.hat(DISK_TURN)
    M = expm(d * X) @ expm(phi * Y) @ expm(-d * X) @ expm(-phi * Y)
    np.testing.assert_allclose(SE2.matrix(net), M, atol=1e-14)
    np.testing.assert_allclose(SE2.hat(est), d * phi * (X @ Y - Y @ X), atol=1e-15)
    # the estimate is right to third order in the loop size: log(net) - area [X, Y] = O(eps^3)
    err = np.max(np.abs(np.real(logm(M)) - SE2.hat(est)))
    assert err < 2.0 * eps ** 3
    assert abs(est[1]) > 0.9 * (d * phi) and np.isclose(net[1], est[1], rtol=3 * eps)


def test_radial_constraint_loop_returns_exactly_to_the_start_on_its_circle():
    from gm_core.systems.rolling_disk import radial_loop_moves, radial_point_path

    q0 = (0.6, 0.8)
    for a, b in [(0.9, 0.4), (0.05, 0.02), (2.5, -1.7)]:
        q = radial_point_path(radial_loop_moves(a, b), q0)
        np.testing.assert_allclose(q[-1], q0, atol=1e-14)
        np.testing.assert_allclose(np.hypot(q[:, 0], q[:, 1]), 1.0, atol=1e-14)   # the level set (3.ix)
        # allowed velocities: x x' + y y' = 0 (3.viii), by central differences along the path
        # (inside each move, where the steps on both sides are equal)
        dq = (q[2:] - q[:-2]) / 2
        inner = np.arange(1, len(q) - 1) % 25 != 0
        assert np.max(np.abs(np.einsum("ij,ij->i", q[1:-1], dq)[inner])) < 1e-12


def test_rolling_disk_bad_input_names_the_argument():
    from gm_core.systems.rolling_disk import disk_moves_path, parallel_park_moves, radial_point_path

    with pytest.raises(ValueError, match="moves"):
        disk_moves_path([[1.0, 0.0, -1.0]])
    with pytest.raises(TypeError, match="d"):
        parallel_park_moves("far", 0.3)
    with pytest.raises(ValueError, match="q0"):
        radial_point_path([[1.0, 0.5]], q0=(0.0, 0.0))


# ------------------------------------------------------------------ the system laws
#: Every system the laws run over: ALL_SYSTEMS, then chains of four links under each physics, a
#: system seen from another body frame and the continuous slender body. (A tabulated connection is
#: only piecewise smooth, so the derivative laws do not hold across its cells; tests/test_catalog.py.)
LAW_SYSTEMS = {
    **ALL_SYSTEMS,
    "LinkChain(4, low_re)": LinkChain((1.0, 0.8, 1.2, 1.0), "low_re"),
    "LinkChain(4, high_re)": LinkChain((1.0, 0.8, 1.2, 1.0), "high_re"),
    "LinkChain(4, floating)": LinkChain((1.0, 0.8, 1.2, 1.0), "floating", masses=(1.0, 2.0, 1.0, 0.5)),
    "Reframed(LowReSwimmer, centre of mass)": Reframed(LowReSwimmer(), CentreOfMassFrame(LowReSwimmer())),
    "SlenderBody": SlenderBody(),
    "LinkChain(4, low_re, tail)": LinkChain((1.0, 0.8, 1.2, 1.0), "low_re", frame="tail"),
    "catalog: flapper_highRe": catalog.load("flapper_highRe"),
    "InteractingChain(3, 16 panels)": InteractingChain((1.0, 0.8, 1.2), separation=0.1, body_density=1.0, panels=16),
    "catalog: symmetricTapeMeasure": catalog.load("symmetricTapeMeasure"),
    "TapeMeasure(symmetric=False)": TapeMeasure(symmetric=False),
}
LAW_SHAPES = [(), (1,), (3, 1, 2)]
SYSTEM_LAWS = settings(max_examples=4, deadline=None)


def law_shapes(system, shape, rng, margin=0.1):
    """Shapes ``shape + (n,)`` drawn in the middle 70 % of the system's window, away from singular
    shapes (scaled |det omega_xi| > ``margin``)."""
    lo, hi = (np.array(v, dtype=float) for v in zip(*system.shape_limits))
    mid, half = (lo + hi) / 2, 0.35 * (hi - lo)
    out = np.empty(shape + (system.n_shape,))
    for idx in np.ndindex(*shape):
        for _ in range(1000):
            r = mid + half * rng.uniform(-1.0, 1.0, system.n_shape)
            if abs(float(system.singularity(r))) > margin:
                out[idx] = r
                break
        else:
            raise AssertionError(f"no regular shape found for {system!r}")
    return out


def system_law(f):
    """A law ``f(system, shape, rng)`` that every locomotion system obeys, as a test over every system
    of LAW_SYSTEMS, every batch shape of LAW_SHAPES and hypothesis-drawn seeds; the law itself stays
    reachable as ``test.law`` (to show a broken system fails it)."""
    def test(name, shape, seed):
        f(LAW_SYSTEMS[name], shape, np.random.default_rng(seed))

    test.__name__, test.__qualname__, test.__doc__ = f.__name__, f.__qualname__, f.__doc__
    test = given(seed=st.integers(0, 2 ** 32 - 1))(test)
    test = SYSTEM_LAWS(test)
    test = pytest.mark.parametrize("shape", LAW_SHAPES, ids=["scalar", "one", "3x1x2"])(test)
    test = pytest.mark.parametrize("name", list(LAW_SYSTEMS))(test)
    test.law = f
    return test


def central_difference(system, r, h=1e-3):
    """d A / d r_k (..., 3, n, n) by the five-point stencil (error O(h^4)), independent of
    gm_core's differences (fd_connection_derivative: two points, a relative step of 6e-6)."""
    cols = []
    for e in np.eye(system.n_shape):
        step = h * e
        A = [system.connection(r + c * step) for c in (2, 1, -1, -2)]
        cols.append((-A[0] + 8 * A[1] - 8 * A[2] + A[3]) / (12 * h))
    return np.stack(cols, -1)


@system_law
def test_law_shapes_of_every_map(system, shape, rng):
    """connection (..., 3, n), pfaffian (..., 3, 3 + n), singularity and is_singular (...),
    part poses (..., P, 3), body velocity (..., 3), connection derivative (..., 3, n, n); the
    batched call agrees with the calls one shape at a time."""
    n = system.n_shape
    r = law_shapes(system, shape, rng)
    A = system.connection(r)
    assert A.shape == shape + (3, n)
    assert system.pfaffian(r).shape == shape + (3, 3 + n)
    assert system.singularity(r).shape == shape and system.is_singular(r).shape == shape
    assert system.part_poses(r).shape == shape + (len(system.parts()), 3)
    assert system.body_velocity(r, np.ones(shape + (n,))).shape == shape + (3,)
    dA = system.connection_derivative(r)[1]
    assert dA.shape == shape + (3, n, n)
    for idx in np.ndindex(*shape):
        np.testing.assert_allclose(A[idx], system.connection(r[idx]), rtol=1e-12, atol=1e-13)
    assert np.all(np.isfinite(A)) and not np.any(system.is_singular(r))


@system_law
def test_law_the_pfaffian_annihilates_allowed_motions(system, shape, rng):
    """omega(r) [xi; r_dot] = 0 with xi = -A(r) r_dot, (3.10)-(3.17): the connection solves the
    constraint (and is the connection read off the Pfaffian)."""
    r = law_shapes(system, shape, rng)
    rd = rng.normal(size=r.shape)
    A = system.connection(r)
    xi = -np.einsum("...ij,...j->...i", A, rd)
    om = system.pfaffian(r)
    resid = np.einsum("...ij,...j->...i", om, np.concatenate([xi, rd], -1))
    scale = 1.0 + np.abs(om).max() * (1.0 + np.abs(rd).max())
    np.testing.assert_allclose(resid, 0.0, atol=1e-10 * scale)
    np.testing.assert_allclose(A, connection_from_pfaffian(om), rtol=1e-9, atol=1e-11)


@system_law
def test_law_body_velocity_is_minus_a_r_dot(system, shape, rng):
    """body_velocity(r, r_dot) = -A(r) r_dot, (3.10): linear in r_dot (scaling, odd symmetry and
    additivity, the box "Directional linearity")."""
    r = law_shapes(system, shape, rng)
    rd, rd2 = rng.normal(size=r.shape), rng.normal(size=r.shape)
    xi = system.body_velocity(r, rd)
    np.testing.assert_allclose(xi, -np.einsum("...ij,...j->...i", system.connection(r), rd), rtol=1e-12, atol=1e-13)
    atol = 1e-11 * (1.0 + np.abs(xi).max())
    np.testing.assert_allclose(system.body_velocity(r, -2.5 * rd), -2.5 * xi, rtol=1e-11, atol=atol)
    np.testing.assert_allclose(system.body_velocity(r, rd + rd2), xi + system.body_velocity(r, rd2), atol=atol)


@system_law
def test_law_connection_derivative_matches_an_independent_difference(system, shape, rng):
    """fd_connection_derivative (two points, relative step 6e-6) and the system's own
    connection_derivative (closed form where it has one) both match a five-point central
    difference of the connection; A comes back with them."""
    r = law_shapes(system, shape, rng)
    ref = central_difference(system, r)
    atol = 1e-5 * (1.0 + np.abs(ref).max())
    for A, dA in (fd_connection_derivative(system, r), system.connection_derivative(r)):
        np.testing.assert_allclose(dA, ref, atol=atol)
        A0 = system.connection(r)   # the same A by another evaluation order: rounding relative to |A|
        np.testing.assert_allclose(A, A0, rtol=1e-8, atol=1e-9 * (1.0 + np.abs(A0).max()))


@system_law
def test_law_the_curvature_form_is_antisymmetric(system, shape, rng):
    """F_ij = -(d_i A_j - d_j A_i) + [A_i, A_j] is antisymmetric in (i, j), so zero on the
    diagonal, and constraint_curvature returns it (its (1, 2) component for two shape variables)."""
    r = law_shapes(system, shape, rng)
    F = curvature_form(*system.connection_derivative(r))
    n = system.n_shape
    assert F.shape == shape + (3, n, n)
    np.testing.assert_allclose(F, -np.swapaxes(F, -1, -2), atol=1e-12 * (1.0 + np.abs(F).max()))
    D = system.constraint_curvature(r)
    expected = F[..., 0, 1] if n == 2 else F
    assert D.shape == expected.shape
    # two routes: closed forms or the gauge covariance D(-A~) = Ad_{beta^-1} D(-A) against differences
    # of A~; a frame whose Jacobian is itself differenced (the centre of mass) leaves ~1e-5 of noise
    np.testing.assert_allclose(D, expected, rtol=1e-5, atol=5e-5 * (1.0 + np.abs(F).max()))


@system_law
def test_law_a_system_describes_itself(system, shape, rng):
    """Names and windows for every shape variable, drawable parts, a scaled determinant in
    [-1, 1], and a system checked once when built: check_system trusts it."""
    n = system.n_shape
    assert isinstance(system, LocomotionSystem) and isinstance(system.name, str) and system.name
    assert len(system.shape_names) == n and len(system.shape_limits) == n
    assert all(lo < hi for lo, hi in system.shape_limits)
    assert len(system.row_names) == system.n_position == 3
    for part in system.parts():
        assert isinstance(part, SystemPart) and part.outline.ndim == 2 and part.outline.shape[1] == 2
    d = system.singularity(law_shapes(system, shape, rng))
    assert np.all(np.abs(d) <= 1.0 + 1e-12)
    assert check_system(system) == validate_system(system) == n


class _SignSlip(DifferentialDrive):
    """Deliberately broken: its connection has the wrong sign (xi = +A r_dot), so it disagrees
    with its own Pfaffian."""

    def connection(self, r):
        return -super().connection(r)


class _FrozenDerivative(Ackerman):
    """Deliberately broken: it claims a closed-form connection derivative of zero, but steering
    changes its connection."""

    def connection_derivative(self, r):
        A = self.connection(r)
        return A, np.zeros(A.shape + (2,))


class _Quadratic(DifferentialDrive):
    """Deliberately broken: its body velocity grows with the square of the shape velocity."""

    def body_velocity(self, r, r_dot):
        return super().body_velocity(r, r_dot) * np.abs(np.asarray(r_dot, dtype=float)[..., :1])


def test_a_broken_system_fails_the_laws():
    """The laws can fail: each broken system passes for its healthy parent and fails the law it breaks."""
    for law, healthy, broken in [
            (test_law_the_pfaffian_annihilates_allowed_motions.law, DifferentialDrive(), _SignSlip()),
            (test_law_connection_derivative_matches_an_independent_difference.law, Ackerman(), _FrozenDerivative()),
            (test_law_body_velocity_is_minus_a_r_dot.law, DifferentialDrive(), _Quadratic())]:
        law(healthy, (3, 1, 2), np.random.default_rng(1))
        with pytest.raises(AssertionError):
            law(broken, (3, 1, 2), np.random.default_rng(1))


def test_a_system_is_checked_once_when_built():
    """LocomotionSystem is abstract, and a subclass instance that is not a system (no integer
    n_shape >= 1, or names that do not match it) is refused when it is built, naming the class."""
    class NoParts(LocomotionSystem):
        def pfaffian(self, r):
            return np.zeros(np.shape(r)[:-1] + (3, 5))

    with pytest.raises(TypeError, match="abstract"):
        NoParts()
    with pytest.raises(TypeError, match="abstract"):
        LocomotionSystem()

    class Flat(NoParts):
        def parts(self):
            return [SystemPart("body", rectangle_outline(1.0, 0.5))]

        def part_poses(self, r):
            return np.zeros(np.shape(r)[:-1] + (1, 3))

    Flat()
    with pytest.raises(TypeError, match=r"Zero\(\.\.\.\) must be a locomotion system"):
        type("Zero", (Flat,), {"n_shape": 0})()
    with pytest.raises(ValueError, match="shape_names has 3 entries for 2"):
        type("Named", (Flat,), {"shape_names": ("a", "b", "c")})()


"""sysplotter's system library by name (gm_core.systems.catalog) against sysplotter's own code.

The reference values are sysplotter's: its own MATLAB code run in GNU Octave on each of its
system files by ``tools/sysplotter_reference.py`` and stored in
``gm_core/systems/sysplotter_reference.json`` (so these tests need no Octave). Where sysplotter is
right the catalog agrees to ``CLOSED_FORM_RTOL`` (1e-8, relative); where it is wrong (the pi/8 of
the rotational added mass) the catalog gives the right value, checked here by an independent
route (a boundary-element computation of the added mass), and putting sysplotter's defect back
into the catalog reproduces sysplotter's numbers to the same 1e-8: the defect is the whole
difference.
"""
import numpy as np
import pytest

from gm_core import SO3
from gm_core.systems import AffineRestriction, InteractingChain, LinkChain, Rotors, catalog, panel_method
from gm_core.systems.fluids import added_mass_bem, ellipse_added_mass
from gm_core.systems.gaits import circle_gait
from gm_core.systems.motion import fd_connection_derivative, net_displacement, trajectory
from gm_core.systems.panel_method import interacting_added_mass
from gm_core.systems.tabulated import TabulatedConnection

FILES = catalog.sysplotter_files()
LOADABLE = catalog.names()
REFERENCE = catalog.reference()
#: The loadable files sysplotter itself can evaluate (all but asymmetricTapeMeasure): those with values to compare.
CHECKED = tuple(n for n in LOADABLE if not REFERENCE["files"][n].get("error"))


def test_the_catalog_lists_every_one_of_sysplotters_41_files():
    """Every file Octave was run on (every sysf_*.m of sysplotter) is in the table, and no other."""
    assert len(FILES) == 41
    assert set(FILES) == set(REFERENCE["files"])
    assert set(LOADABLE) <= set(FILES)
    assert len(LOADABLE) >= 27
    for entry in FILES.values():
        assert entry.loadable == (entry.missing == ""), entry.name
        assert entry.model and len(entry.grid_range) >= 1


@pytest.mark.parametrize("name", CHECKED)
def test_a_loaded_system_is_in_the_files_shape_coordinates(name):
    """The file's number of shape variables, its window, finite connection and symmetric metric."""
    system = catalog.load(name)
    ref = catalog.reference(name)
    assert ref["error"] == ""
    n = ref["shapes"].shape[1]
    assert system.n_shape == n == len(FILES[name].grid_range)
    A, M = catalog.sysplotter_view(system, ref["shapes"])
    assert A.shape == (len(ref["shapes"]), 3, n) and np.all(np.isfinite(A))
    assert (M is None) == (ref["metric"] is None)
    if M is not None:
        np.testing.assert_allclose(M, np.swapaxes(M, -1, -2), atol=1e-15 * np.abs(M).max())


def _relative(mine, theirs):
    return np.abs(mine - theirs).max() / np.abs(theirs).max()


@pytest.mark.parametrize("name", [n for n in CHECKED if not FILES[n].differs and FILES[n].rtol == catalog.CLOSED_FORM_RTOL])
def test_where_sysplotter_is_right_the_catalog_agrees_to_1e8(name):
    system = catalog.load(name)
    ref = catalog.reference(name)
    A, M = catalog.sysplotter_view(system, ref["shapes"])
    assert _relative(A, ref["A"]) <= catalog.CLOSED_FORM_RTOL
    if M is not None:
        assert _relative(M, ref["metric"]) <= catalog.CLOSED_FORM_RTOL


@pytest.mark.parametrize("name", [n for n in LOADABLE if FILES[n].differs == catalog.PI_OVER_8])
def test_where_sysplotter_lacks_pi_over_8_the_catalog_differs_by_exactly_that(name):
    """The catalog differs from sysplotter (by more than rounding), and with sysplotter's
    rotational added mass put back it agrees to 1e-8."""
    assert FILES[name].differs == catalog.PI_OVER_8
    system = catalog.load(name)
    ref = catalog.reference(name)
    A, M = catalog.sysplotter_view(system, ref["shapes"])
    differences = [_relative(A, ref["A"])] + ([] if M is None else [_relative(M, ref["metric"])])
    assert max(differences) > 1e-4
    theirs = catalog.with_sysplotter_added_mass(system)
    assert _relative(theirs.connection(ref["shapes"]), ref["A"]) <= catalog.CLOSED_FORM_RTOL
    if FILES[name].metric == "physical":
        M2 = FILES[name].metric_scale * theirs.shape_metric(ref["shapes"])
        assert _relative(M2, ref["metric"]) <= catalog.CLOSED_FORM_RTOL


def test_the_catalogs_added_mass_is_the_boundary_element_value_not_sysplotters():
    """The rotational added mass of the catalog's ellipse links (ar 0.1) against a boundary-element
    solution of the potential flow: pi/8 rho (a^2 - b^2)^2, not sysplotter's rho (a^2 - b^2)^2."""
    chain = catalog.load("four_link_HighRe")
    a, b = chain.semi_axes()[0]
    bem = added_mass_bem(a, b, 1.0)
    body = np.pi * a * b * (a ** 2 + b ** 2) / 4                 # the link's own inertia (density 1)
    mine = chain.link_matrices()[0][2, 2] - body
    theirs = catalog.with_sysplotter_added_mass(chain).link_matrices()[0][2, 2] - body
    assert abs(mine - bem[2, 2]) <= 1e-3 * bem[2, 2]
    assert abs(theirs - bem[2, 2]) > 0.5 * bem[2, 2]
    np.testing.assert_allclose(theirs, (a ** 2 - b ** 2) ** 2, rtol=1e-14)


def test_the_parity_table_has_a_row_for_every_file_and_a_reason_for_every_difference():
    rows = catalog.parity()
    assert [r.name for r in rows] == list(FILES)
    by_status = {}
    for r in rows:
        by_status.setdefault(r.status, []).append(r.name)
        if r.status == "agrees":
            assert max(r.A_difference, r.M_difference) <= FILES[r.name].rtol, r.name
        elif r.status == "corrected":
            assert r.as_sysplotter <= FILES[r.name].rtol and r.reason, r.name
        else:
            assert r.reason, r.name
    assert by_status["sysplotter cannot run it"] == ["asymmetricTapeMeasure"]
    assert len(by_status["agrees"]) + len(by_status["corrected"]) == len(CHECKED) == len(LOADABLE) - 1


def test_modal_files_map_their_modes_to_joint_angles_as_the_file_does():
    """Spot checks of the mode matrices against the files' own loops."""
    cc = catalog.load("two_mode_CC")
    assert isinstance(cc, AffineRestriction)
    np.testing.assert_array_equal(cc.matrix[:10, 0], 1 / 40)
    np.testing.assert_array_equal(cc.matrix[10:, 1], 1 / 40)
    assert cc.matrix[:10, 1].any() == cc.matrix[10:, 0].any() == False  # noqa: E712
    serp = catalog.load("two_mode_serpenoid")
    i = np.arange(1, 20)
    np.testing.assert_allclose(serp.matrix, np.stack([np.cos(i / 20 * 2 * np.pi), np.sin(i / 20 * 2 * np.pi)], -1))
    fish = catalog.load("fishTail_HighRe_tapered")
    assert fish.matrix.shape == (29, 2) and fish.matrix[19, 0] == 1 and not fish.matrix[20:].any()
    flap = catalog.load("flapper_highRe")
    assert isinstance(flap.base_system, LinkChain)
    np.testing.assert_array_equal(flap.base_system.link_diagonals[1], 0.0)


def test_the_tail_frame_is_the_first_links_centre():
    chain = LinkChain((1.0, 0.5, 2.0, 1.0), "low_re")
    tail = chain.with_frame("tail")
    r = np.array([0.3, -0.7, 1.1])
    np.testing.assert_allclose(tail.link_poses(r)[0], 0.0, atol=1e-15)
    # the same motion seen from two frames: link 1's world velocity must agree
    r_dot = np.array([0.2, 0.5, -0.4])
    xi_tail = tail.body_velocity(r, r_dot)
    J = chain.link_jacobians(r)[0]                       # link 1's body velocity from (xi_middle, r_dot)
    v1 = J @ np.concatenate([chain.body_velocity(r, r_dot), r_dot])
    np.testing.assert_allclose(xi_tail, v1, atol=1e-12)


def test_bad_names_and_systems_are_refused_by_name():
    with pytest.raises(ValueError, match="three_link_lowRe"):
        catalog.load("three_link_lowre")
    with pytest.raises(ValueError, match="name 'nonsense'"):
        catalog.load("nonsense")
    with pytest.raises(TypeError, match="name must be"):
        catalog.load(3)
    assert catalog.load("sysf_three_link_lowRe.m").n_shape == 2
    with pytest.raises(TypeError, match="system must be a system made by"):
        catalog.sysplotter_view(LinkChain(), [0.1, 0.2])
    with pytest.raises(TypeError, match="high-Re"):
        catalog.with_sysplotter_added_mass(catalog.load("three_link_lowRe"))
    with pytest.raises(ValueError, match="link_diagonals"):
        LinkChain((1, 1, 1), link_diagonals=[[1, 1, 1], [0, 0, 0], [-1, 0, 0]])
    with pytest.raises(ValueError, match="link_diagonals"):
        LinkChain((1, 1, 1), link_diagonals=[[1, 1, 1], [0, 0, 0]])


# ------------------------------------------------------------------ tabulated connections
def _chain_table(n=9, half=1.5):
    """The three-link low-Re swimmer's connection on an n x n grid: a table with the symmetries exactly."""
    chain = LinkChain((1, 1, 1), "low_re")
    g = np.linspace(-half, half, n)
    R = np.stack(np.meshgrid(g, g, indexing="ij"), -1)
    return chain, g, np.moveaxis(chain.connection(R), (0, 1), (2, 3))      # (3, 2, n, n)


def test_a_table_is_exact_at_its_nodes_and_bilinear_between_them():
    chain, g, T = _chain_table()
    tab = TabulatedConnection((g, g), T)
    R = np.stack(np.meshgrid(g, g, indexing="ij"), -1)
    np.testing.assert_array_equal(np.moveaxis(tab.connection(R), (0, 1), (2, 3)), T)
    # bilinear: a table of a function linear in each variable is reproduced everywhere inside
    lin = np.einsum("ij,a,b->ijab", np.arange(6.0).reshape(3, 2), 1 + g, 2 - g)
    r = np.array([[0.31, -0.77], [1.49, 1.2]])
    expect = np.arange(6.0).reshape(3, 2) * ((1 + r[:, 0]) * (2 - r[:, 1]))[:, None, None]
    np.testing.assert_allclose(TabulatedConnection((g, g), lin).connection(r), expect, rtol=1e-14)
    # and it converges to the chain it samples as the grid is refined (second order)
    r = np.array([0.4, -1.1])
    errors = [np.abs(TabulatedConnection((h, h), U).connection(r) - chain.connection(r)).max()
              for _, h, U in (_chain_table(n) for n in (11, 21, 41))]
    assert errors[2] < errors[1] < errors[0] and errors[1] / errors[2] > 3


def test_the_three_link_symmetries_hold_for_a_three_link_swimmer_and_average_noise_away():
    """The four lookups of sysplotter's '3link' average agree for a true three-link swimmer, so
    averaging changes nothing at the nodes; noise that breaks the symmetry is averaged down."""
    chain, g, T = _chain_table()
    tab = TabulatedConnection((g, g), T, symmetry="three link")
    R = np.stack(np.meshgrid(g, g, indexing="ij"), -1)
    np.testing.assert_allclose(tab.connection(R), chain.connection(R), atol=1e-15)
    noise = np.random.default_rng(3).normal(0, 1e-2, T.shape)
    raw = TabulatedConnection((g, g), T + noise).connection(R) - chain.connection(R)
    averaged = TabulatedConnection((g, g), T + noise, symmetry="three link").connection(R) - chain.connection(R)
    assert np.sqrt(np.mean(averaged ** 2)) < 0.6 * np.sqrt(np.mean(raw ** 2))


def test_outside_the_table_there_is_no_connection():
    _, g, T = _chain_table()
    tab = TabulatedConnection((g, g), T, symmetry="three link")
    r = np.array([[0.0, 0.0], [1.6, 0.0], [0.0, -2.0]])
    assert tab.is_singular(r).tolist() == [False, True, True]
    assert np.isnan(tab.connection(r)[1:]).all() and np.isfinite(tab.connection(r)[0]).all()
    assert tab.singularity(r).tolist() == [1.0, 0.0, 0.0]


def test_bad_tables_are_refused_by_name():
    _, g, T = _chain_table()
    with pytest.raises(ValueError, match="table must have shape"):
        TabulatedConnection((g, g), T[:, :, :-1])
    with pytest.raises(ValueError, match=r"axes\[1\] must be an increasing"):
        TabulatedConnection((g, g[::-1]), T)
    with pytest.raises(TypeError, match="axes must be a pair"):
        TabulatedConnection(g, T)
    with pytest.raises(ValueError, match="symmetry"):
        TabulatedConnection((g, g), T, symmetry="mirror")
    with pytest.raises(ValueError, match="same grid for both joints"):
        TabulatedConnection((g, g + 0.1), T, symmetry="three link")
    with pytest.raises(TypeError, match="body must be"):
        TabulatedConnection((g, g), T, body="snake")


def test_a_cubic_table_converges_at_fourth_order_and_its_curvature_is_the_chains():
    chain, _, _ = _chain_table()
    r = np.array([[0.4, -1.1], [-0.93, 0.27]])
    errors = [np.abs(TabulatedConnection((h, h), U, method="cubic").connection(r) - chain.connection(r)).max()
              for _, h, U in (_chain_table(n) for n in (11, 21, 41))]
    assert errors[0] / errors[1] > 8 and errors[1] / errors[2] > 8          # about 16 per halving of the step
    _, g, T = _chain_table(41)
    tab = TabulatedConnection((g, g), T, method="cubic")
    np.testing.assert_allclose(tab.constraint_curvature(r), chain.constraint_curvature(r), atol=2e-4)
    # the spline's own derivative is that of its values (central differences of the table itself)
    A, dA = tab.connection_derivative(r)
    np.testing.assert_allclose(A, tab.connection(r), atol=1e-15)
    np.testing.assert_allclose(dA, fd_connection_derivative(tab, r)[1], atol=1e-7)
    # a table of a cubic polynomial in each variable is reproduced exactly, derivative included
    poly = np.einsum("ij,a,b->ijab", np.arange(6.0).reshape(3, 2), g ** 3, 1 - g ** 2)
    cubic = TabulatedConnection((g, g), poly, method="cubic")
    A, dA = cubic.connection_derivative(r)
    x, y = r[:, 0], r[:, 1]
    c = np.arange(6.0).reshape(3, 2)
    np.testing.assert_allclose(A, c * (x ** 3 * (1 - y ** 2))[:, None, None], atol=1e-12)
    np.testing.assert_allclose(dA[..., 0], c * (3 * x ** 2 * (1 - y ** 2))[:, None, None], atol=1e-11)
    np.testing.assert_allclose(dA[..., 1], c * (-2 * y * x ** 3)[:, None, None], atol=1e-11)


def test_a_cubic_table_averaged_over_the_symmetries_differentiates_through_them():
    chain, g, T = _chain_table(21)
    noise = np.random.default_rng(5).normal(0, 1e-3, T.shape)
    tab = TabulatedConnection((g, g), T + noise, symmetry="three link", method="cubic")
    r = np.array([[0.4, -1.1], [0.2, 0.3]])
    A, dA = tab.connection_derivative(r)
    np.testing.assert_allclose(A, tab.connection(r), atol=1e-15)
    np.testing.assert_allclose(dA, fd_connection_derivative(tab, r)[1], atol=1e-6)
    assert np.isnan(tab.connection([1.6, 0.0])).all() and tab.is_singular([1.6, 0.0])


def test_a_cubic_table_needs_four_nodes_and_a_known_method():
    _, g, T = _chain_table()
    with pytest.raises(ValueError, match="method must be one of"):
        TabulatedConnection((g, g), T, method="spline")
    with pytest.raises(ValueError, match="at least 4 nodes"):
        TabulatedConnection((g[:3], g), T[:, :, :3], method="cubic")


# ------------------------------------------------------------------ rotors on SO(3)
def test_rotors_keep_zero_angular_momentum_and_a_cycle_turns_the_body_as_rotation_matrices_say():
    """Two rotors about different axes, driven round a circle in shape space: the net rotation
    from the course's SO(3) Magnus integrator against scipy's solve_ivp of R_dot = R hat(omega)
    on 3 x 3 matrices (an independent route); and the body velocity annihilated by the Pfaffian."""
    from scipy.integrate import solve_ivp

    body = Rotors(((1, 0, 0), (0, 1, 1)), (0.3, 0.2), [[2.0, 0.1, 0.0], [0.1, 1.5, 0.0], [0.0, 0.0, 1.0]])
    gait = circle_gait(1.2, (0.3, -0.2), period=1.0)
    r, r_dot = gait(0.37), gait.velocity(0.37)
    xi = body.body_velocity(r, r_dot)
    np.testing.assert_allclose(body.pfaffian(r) @ np.concatenate([xi, r_dot]), 0.0, atol=1e-15)
    A = body.connection(r)

    def rhs(t, y):
        R = y.reshape(3, 3)
        w = -A @ gait.velocity(t)
        return (R @ SO3.hat(w)).ravel()

    sol = solve_ivp(rhs, (0.0, 1.0), np.eye(3).ravel(), rtol=1e-12, atol=1e-13, method="DOP853")
    R_T = sol.y[:, -1].reshape(3, 3)
    g = net_displacement(body, gait)
    np.testing.assert_allclose(SO3.matrix(g), R_T, atol=1e-9)
    assert np.linalg.norm(g) > 1e-3                               # the cycle does turn the body
    traj = trajectory(body, gait, 11)
    np.testing.assert_allclose(SO3.matrix(traj.g[-1]), R_T, atol=1e-8)
    # one axis only: the rotations commute, a cycle turns it by nothing
    twin = catalog.load("twin_rotor")
    np.testing.assert_allclose(net_displacement(twin, gait), 0.0, atol=1e-12)
    # curvature on SO(3): constant A, so F = [A_1, A_2], the cross product of the columns
    np.testing.assert_allclose(body.constraint_curvature(r), np.cross(A[:, 0], A[:, 1]), atol=1e-12)


def test_bad_rotors_are_refused_by_name():
    with pytest.raises(ValueError, match="axes"):
        Rotors(((0, 0, 0),))
    with pytest.raises(ValueError, match="rotor_inertias"):
        Rotors(((1, 0, 0),), (-1.0,))
    with pytest.raises(ValueError, match="inertia must be positive definite"):
        Rotors(((1, 0, 0),), (1.0,), -np.eye(3))
    with pytest.raises(ValueError, match="inertia must be a symmetric"):
        Rotors(((1, 0, 0),), (1.0,), [[1, 2, 0], [0, 1, 0], [0, 0, 1]])


# ------------------------------------------------------------------ sysplotter's continuous bodies
CONTINUOUS = [n for n in LOADABLE if FILES[n].rtol in (catalog.CONTINUOUS_RTOL, catalog.CONTINUOUS_JUMP_RTOL)]
CENTRE = [n for n in CONTINUOUS if not FILES[n].differs]
REFRAMED = [n for n in CONTINUOUS if FILES[n].differs]


def _shapes(name, k=3):
    """k shapes inside the file's window (seeded), away from the origin."""
    half = np.array([hi for _, hi in FILES[name].grid_range])
    u = np.random.default_rng(len(name)).uniform(0.2, 0.7, (k, half.size)) * np.where(np.arange(half.size) % 2, -1, 1)
    return u * half


def _refined(body, panels, order):
    from gm_core.systems import SlenderBody
    return SlenderBody(body.length, body.general or body.modes, integrals=body.integrals, breaks=body.breaks,
                       frame=body.frame, panels=panels, order=order)


def _backbone(body, r, s_eval):
    """Poses (x, y, theta) of the points s_eval in the middle frame by an ODE solver (scipy, rtol 1e-12):
    (x, y, theta)' = (cos theta, sin theta, kappa), from the middle to each end, restarted at every break."""
    from scipy.integrate import solve_ivp

    def rhs(s, y):
        return [np.cos(y[2]), np.sin(y[2]), body.curvature(r, np.array([s]))[0]]
    out = np.zeros((len(s_eval), 3))
    for lo, hi in ((0.5, 1.0), (0.5, 0.0)):
        stops = [lo] + sorted((b for b in body.breaks if min(lo, hi) < b < max(lo, hi)), reverse=hi < lo) + [hi]
        y = np.zeros(3)
        for a, b in zip(stops[:-1], stops[1:]):
            inside = [i for i, s in enumerate(s_eval) if min(a, b) <= s <= max(a, b)]
            sol = solve_ivp(rhs, (a, b), y, rtol=1e-12, atol=1e-13, dense_output=True)
            for i in inside:
                out[i] = sol.sol(s_eval[i])
            y = sol.y[:, -1]
    return out


def test_the_nine_continuous_files_load_in_their_frames():
    frames = {n: catalog.load(n).frame for n in CONTINUOUS}
    assert len(CONTINUOUS) == 9
    assert {n for n, f in frames.items() if f == "middle"} == set(CENTRE)
    assert frames["constantcurv3_lowRe"] == "tail"
    assert {n for n, f in frames.items() if f == "com-mean"} == {"serpenoid_lowRe", "serpenoid_lowRe_hf",
                                                                  "serpenoid_lowRe_hf_AmpPhase"}
    assert all(FILES[n].differs == catalog.FRAME_CHANGE for n in REFRAMED)


@pytest.mark.parametrize("name", CENTRE)
def test_centre_frame_continuous_files_agree_with_sysplotter_within_its_ode45_tolerance(name):
    system = catalog.load(name)
    ref = catalog.reference(name)
    A, M = catalog.sysplotter_view(system, ref["shapes"])
    assert _relative(A, ref["A"]) <= FILES[name].rtol
    assert _relative(M, ref["metric"]) <= FILES[name].rtol


@pytest.mark.parametrize("name", CONTINUOUS)
def test_the_continuous_bodies_converge_as_their_quadrature_is_refined(name):
    """Successive refinements of panels and order change A and M less and less, down to 1e-8, and
    the catalog's own quadrature is as good as the finest."""
    body = catalog.load(name)
    r = _shapes(name)
    values = [_refined(body, p, o) for p, o in ((4, 6), (8, 8), (16, 12), (32, 16))]
    A = [b.connection(r) for b in values]
    M = [b.shape_metric(r) for b in values]
    steps = [max(np.abs(A[i + 1] - A[i]).max(), np.abs(M[i + 1] - M[i]).max()) for i in range(3)]
    assert steps[2] <= 1e-8 and steps[2] < steps[0], steps
    assert np.abs(body.connection(r) - A[-1]).max() <= 1e-8
    assert np.abs(body.shape_metric(r) - M[-1]).max() <= 1e-8


@pytest.mark.parametrize("name", REFRAMED)
def test_reframed_continuous_files_are_right_where_sysplotter_is_not(name):
    """In the 'tail' and 'com-mean' frames: the reduced metric is the centre frame's (it cannot depend
    on the body frame); the connection is Ad_{beta^-1} A_center - B_beta with B_beta the body
    Jacobian of the frame's pose by central differences; sysplotter differs by more than its
    tolerance, and with its frame change put back the catalog reproduces sysplotter."""
    from gm_core import SE2
    from gm_core.systems.reframed import body_jacobian
    body = catalog.load(name)
    centre = body.with_frame("middle")
    ref = catalog.reference(name)
    r = ref["shapes"]
    M = body.shape_metric(r)
    np.testing.assert_allclose(M, centre.shape_metric(r), rtol=0, atol=1e-12 * np.abs(M).max())
    beta = body.frame_pose(r)[0]
    h = 1e-6
    dbeta = np.stack([(body.frame_pose(r + h * e)[0] - body.frame_pose(r - h * e)[0]) / (2 * h)
                      for e in np.eye(body.n_shape)], -1)
    expect = SE2.Ad(SE2.inverse(beta)) @ centre.connection(r) - body_jacobian(beta, dbeta)
    np.testing.assert_allclose(body.connection(r), expect, rtol=0, atol=1e-8)
    A, M = catalog.sysplotter_view(body, r)
    assert max(_relative(A, ref["A"]), _relative(M, ref["metric"])) > 10 * FILES[name].rtol
    theirs = catalog.with_sysplotter_frame_change(body)
    assert _relative(theirs.connection(r), ref["A"]) <= FILES[name].rtol
    assert _relative(theirs.shape_metric(r), ref["metric"]) <= FILES[name].rtol


def test_the_com_mean_frame_is_the_plain_mean_of_100_points_not_the_integral_mean():
    body = catalog.load("serpenoid_lowRe")
    r = np.array([7.0, -4.0])
    s = np.linspace(0.0, 1.0, 100)
    poses = _backbone(body, r, s)
    beta = body.frame_pose(r)[0]
    np.testing.assert_allclose(beta, poses.mean(0), rtol=0, atol=1e-10)
    integral_mean = body.with_frame("com").frame_pose(r)[0]
    assert np.abs(integral_mean - beta).max() > 1e-3
    fine = _backbone(body, r, np.linspace(0.0, 1.0, 20001))          # the integral mean, by the trapezoid rule
    trapezoid = (fine[1:] + fine[:-1]).sum(0) / 2 / 20000
    np.testing.assert_allclose(integral_mean, trapezoid, rtol=0, atol=1e-8)


@pytest.mark.parametrize("name", ["constantcurv3_lowRe", "serpenoid_lowRe"])
def test_the_tail_frame_is_the_pose_of_the_end_of_the_body(name):
    body = catalog.load(name).with_frame("tail")
    r = _shapes(name, 2)
    for shape in r:
        np.testing.assert_allclose(body.frame_pose(shape)[0], _backbone(body, shape, [0.0])[0], rtol=0, atol=1e-10)
    # the drawn pieces are seen from there: the first piece sits half a piece from the origin
    first = body.link_poses(r[0])[0]
    assert abs(np.hypot(first[0], first[1]) - 0.5 / body.segments) < 1e-3


@pytest.mark.parametrize("curvature", [catalog.triangle_curvature(1), catalog.triangle_curvature(2),
                                       catalog.amplitude_phase_curvature(2)], ids=lambda c: c.name)
def test_general_curvatures_have_their_derivatives_right(curvature):
    """d kappa / d r in closed form against central differences, away from the origin."""
    s = np.linspace(0.0, 1.0, 57)
    r = np.array([[3.0, -1.5], [-0.4, 2.2], [5.0, 0.01]])
    h = 1e-6
    fd = np.stack([(curvature.kappa(s, r + h * e) - curvature.kappa(s, r - h * e)) / (2 * h) for e in np.eye(2)], -1)
    np.testing.assert_allclose(curvature.dkappa(s, r), fd, rtol=0, atol=1e-7 * np.abs(fd).max())


def test_the_triangle_wave_is_sysplotters_pinched_sinusoid():
    """The shipped formula: P sqrt(a1^2 + a2^2) sign(w) |w|^20 / (a1^2 + a2^2)^10, w = a1 cos(2 pi u) + a2 sin(2 pi u)."""
    tri = catalog.triangle_curvature(1)
    u = np.linspace(-0.5, 0.5, 41)
    a1, a2 = 2.0, -3.0
    w = a1 * np.cos(2 * np.pi * u) + a2 * np.sin(2 * np.pi * u)
    expect = 3.581781447252943 * np.sqrt(a1 ** 2 + a2 ** 2) * np.sign(w) * np.abs(w) ** 20 / (a1 ** 2 + a2 ** 2) ** 10
    np.testing.assert_allclose(tri.kappa(u + 0.5, np.array([a1, a2])), expect, rtol=1e-13, atol=1e-300)
    assert np.isnan(tri.kappa(u, np.zeros(2))).all()


# -- the panel method: added mass of links whose flows interact (three_link_HighRe_panelMethod) ------------------
def _interior_source_added_mass(poses, axes, n=800, m=200):
    """An independent route: the added mass (N, 3, N, 3) of N ellipses from point sources inside each one
    (on the half-size ellipse), fitted by least squares to the normal velocity at n points per ellipse with
    zero net outflow per body; ``M = -rho oint phi_i (v_j . n) ds`` by the trapezoidal rule."""
    N = len(poses)
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    u = np.linspace(0, 2 * np.pi, m, endpoint=False) + np.pi / m
    pts, nrm, ds, src = [], [], [], []
    for (x, y, th), (a, b) in zip(poses, axes):
        R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        normal = np.stack([b * np.cos(t), a * np.sin(t)], -1)
        ds.append(np.linalg.norm(normal, axis=-1) * 2 * np.pi / n)
        nrm.append((normal / np.linalg.norm(normal, axis=-1)[:, None]) @ R.T)
        pts.append(np.stack([a * np.cos(t), b * np.sin(t)], -1) @ R.T + (x, y))
        src.append(np.stack([a / 2 * np.cos(u), b / 2 * np.sin(u)], -1) @ R.T + (x, y))
    p, nv, w, s = (np.concatenate(v) for v in (pts, nrm, ds, src))
    d = p[:, None, :] - s[None]
    r2 = (d ** 2).sum(-1)
    G = (d * nv[:, None, :]).sum(-1) / r2
    V = np.zeros((N * n, 3 * N))
    for i, (x, y, th) in enumerate(poses):
        q = p[i * n:(i + 1) * n] - (x, y)
        c, sn = np.cos(th), np.sin(th)
        e1, e2 = np.array([c, sn]), np.array([-sn, c])          # body axes: body velocity (u, v, w)
        k = nv[i * n:(i + 1) * n]
        V[i * n:(i + 1) * n, 3 * i:3 * i + 3] = np.stack([k @ e1, k @ e2, q[:, 0] * k[:, 1] - q[:, 1] * k[:, 0]], -1)
    flux = np.kron(np.eye(N), np.ones((1, m)))
    q = np.linalg.lstsq(np.vstack([G, flux]), np.vstack([V, np.zeros((N, 3 * N))]), rcond=None)[0]
    phi = 0.5 * np.log(r2) @ q
    return (-(phi * w[:, None]).T @ V).reshape(N, 3, N, 3)


def test_the_panel_method_tends_to_the_closed_form_for_one_ellipse_at_first_order():
    """One ellipse (ar 0.1), anywhere: pi rho (b^2, a^2, (a^2 - b^2)^2 / 8), the error halving with each doubling of panels."""
    a, b, rho = 0.6, 0.06, 1.3
    exact = ellipse_added_mass(a, b, rho)
    errors = []
    for panels in (100, 200, 400, 800):
        M = interacting_added_mass([[0.3, -0.2, 0.7]], [[a, b]], rho, panels=panels)[0, :, 0, :]
        errors.append(np.abs(M - exact).max() / np.abs(exact).max())
    assert errors[-1] < 2e-3
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert np.all((1.8 < ratios) & (ratios < 2.2)), ratios


def test_far_apart_bodies_do_not_interact_and_near_ones_match_an_independent_solver():
    """(b) two ellipses far apart: block diagonal, each block the lone ellipse's; near: the interior-source route."""
    axes = [[0.5, 0.25], [0.4, 0.2]]
    lone = [interacting_added_mass([[0, 0, 0]], [ab], panels=400)[0, :, 0, :] for ab in axes]
    coupling = []
    for d in (10.0, 100.0, 1000.0):
        M = interacting_added_mass([[0, 0, 0.3], [d, 0.5 * d, -1.0]], axes, panels=400)
        coupling.append(np.abs(M[0, :, 1, :]).max() / np.abs(M[0, :, 0, :]).max())
        if d == 1000.0:
            for i in range(2):
                np.testing.assert_allclose(M[i, :, i, :], lone[i], atol=1e-6 * np.abs(lone[i]).max())
    assert coupling[-1] < 1e-5 and coupling[0] > 10 * coupling[1] > 100 * coupling[2]
    poses = [[0.0, 0.0, 0.2], [1.1, 0.3, -0.5]]
    theirs = _interior_source_added_mass(np.array(poses), np.array(axes)).reshape(6, 6)
    assert np.abs(theirs[:3, 3:]).max() > 0.05 * np.abs(theirs).max()         # the coupling is not negligible here
    err = [np.abs(interacting_added_mass(poses, axes, panels=p).reshape(6, 6) - theirs).max() / np.abs(theirs).max()
           for p in (400, 800)]
    assert err[1] <= 3e-3 and err[0] > 1.8 * err[1]


def test_the_panel_mass_matrix_is_symmetric_positive_and_its_raw_asymmetry_vanishes_with_refinement():
    """(c) the returned matrix is symmetric and positive definite; the discrete form before symmetrising
    (the flow of body i on the surface of body j) is symmetric up to the discretisation, shrinking with it."""
    poses, axes = np.array([[0, 0, 0.0], [0.45, 0.1, 0.6], [-0.4, 0.05, -0.4]]), np.full((3, 2), [0.2, 0.02])
    M = interacting_added_mass(poses, axes, panels=100).reshape(9, 9)
    np.testing.assert_array_equal(M, M.T)
    assert np.linalg.eigvalsh(M).min() > 0
    skew = []
    for panels in (50, 100, 200, 400):
        raw = panel_method._common_frame_mass(poses, axes, panels, True)
        skew.append(np.abs(raw - raw.T).max() / np.abs(raw).max())
    assert skew[-1] < 1e-3 and skew[0] > 3 * skew[-1]


def test_the_panel_chain_converges_as_panels_are_refined_and_far_links_are_the_closed_form_chain():
    """(d) the catalog's connection converges at first order (its 200 panels are within 2e-3 of 1600); with
    wide gaps the chain is LinkChain with each ellipse's closed-form added mass on the same joints."""
    r = catalog.reference("three_link_HighRe_panelMethod")["shapes"][:2]
    A = {p: catalog._panel_chain(p).connection(r) for p in (100, 200, 400, 800)}
    steps = [np.abs(A[2 * p] - A[p]).max() / np.abs(A[800]).max() for p in (100, 200, 400)]
    assert steps[0] > 1.8 * steps[1] > 1.8 ** 2 * steps[2]
    assert np.abs(A[200] - A[800]).max() / np.abs(A[800]).max() < 2e-3
    lengths, sep = np.array([0.3, 0.25, 0.3]), 6.0
    wide = InteractingChain(lengths, aspect_ratio=4.0, separation=sep, body_density=0.5, panels=400)
    a, b = lengths / 2, lengths / 8
    m = 0.5 * np.pi * a * b
    d = [np.diag(ellipse_added_mass(ai, bi)) + [mi, mi, mi * (ai ** 2 + bi ** 2) / 4] for ai, bi, mi in zip(a, b, m)]
    closed = LinkChain(tuple(lengths + sep), "high_re", aspect_ratio=4.0, link_diagonals=d)
    shapes = np.array([[0.4, -0.7], [1.2, 0.3]])
    np.testing.assert_allclose(wide.link_poses(shapes), closed.link_poses(shapes), atol=1e-14)
    assert _relative(wide.connection(shapes), closed.connection(shapes)) < 5e-3
    assert _relative(wide.shape_metric(shapes), closed.shape_metric(shapes)) < 5e-3


def test_the_panel_method_file_is_sysplotters_once_its_method_is_put_back():
    """The catalog's chain differs from sysplotter's stored values; with sysplotter's 10 panels, atan and
    lumped links put back it reproduces them to 1e-8; the metric is the file's eye(2)."""
    name = "three_link_HighRe_panelMethod"
    system, ref = catalog.load(name), catalog.reference(name)
    assert isinstance(system, InteractingChain) and FILES[name].differs == catalog.PANEL_METHOD
    A, M = catalog.sysplotter_view(system, ref["shapes"])
    np.testing.assert_array_equal(M, np.broadcast_to(np.eye(2), M.shape))
    assert _relative(A, ref["A"]) > 0.1
    theirs = catalog.with_sysplotter_panel_method(system)
    assert _relative(theirs.connection(ref["shapes"]), ref["A"]) <= catalog.CLOSED_FORM_RTOL
    [row] = catalog.parity(name)
    assert row.status == "corrected" and row.as_sysplotter <= catalog.CLOSED_FORM_RTOL
    with pytest.raises(TypeError, match="system"):
        catalog.with_sysplotter_panel_method(catalog.load("three_link_HighRe"))


def test_sysplotters_angle_gives_a_lone_ten_panel_link_a_negative_added_mass():
    """The evidence for the defect: at 10 panels atan misses 2 pi where a panel subtends more than pi/2 (by the
    tips), and the lateral added mass of a lone link turns negative; arctan2 gives ~pi rho a^2; from 20 panels
    on no angle is that wide and the two agree."""
    a, b = 0.15625, 0.015625
    exact = ellipse_added_mass(a, b)[1, 1]
    raw = {(p, ex): panel_method._common_frame_mass(np.zeros((1, 3)), np.array([[a, b]]), p, ex)[1, 1]
           for p in (10, 20) for ex in (True, False)}
    assert raw[10, False] < 0 < raw[10, True]
    assert abs(raw[10, True] - exact) < 0.2 * exact
    assert raw[20, True] == pytest.approx(raw[20, False], rel=1e-12)


def test_sysplotters_lumping_is_right_for_rigid_motions_only():
    """Lumping sum_j M_ij onto link i (sysplotter, with fine panels and the right angle) gives the coupled
    locked inertia (the block of rigid motions) but not the coupling to shape changes."""
    chain = InteractingChain((0.3,) * 3, aspect_ratio=10.0, separation=0.03, body_density=1.0, panels=300)
    lumped = chain.with_model("sysplotter")
    r = [0.8, -0.5]
    D, L = chain.metric(r), lumped.metric(r)
    assert _relative(L[:3, :3], D[:3, :3]) < 1e-4          # equal but for the discrete form's asymmetry
    assert _relative(lumped.connection(r), chain.connection(r)) > 0.05


def test_bad_panel_method_input_is_refused_by_name():
    with pytest.raises(ValueError, match="poses"):
        interacting_added_mass([[0, 0]], [[1, 0.1]])
    with pytest.raises(ValueError, match="semi_axes"):
        interacting_added_mass([[0, 0, 0]], [[1, -0.1]])
    with pytest.raises(ValueError, match="panels"):
        interacting_added_mass([[0, 0, 0]], [[1, 0.1]], panels=2)
    with pytest.raises(TypeError, match="fluid_density"):
        interacting_added_mass([[0, 0, 0]], [[1, 0.1]], fluid_density="1")
    with pytest.raises(ValueError, match="panels"):
        panel_method.ellipse_panels(1.0, 0.1, 3)
    with pytest.raises(ValueError, match="b"):
        panel_method.ellipse_panels(1.0, 0.0, 10)
    with pytest.raises(ValueError, match="separation"):
        InteractingChain((1, 1, 1), separation=-0.1)
    with pytest.raises(ValueError, match="model"):
        InteractingChain((1, 1, 1), model="lumped")
    with pytest.raises(ValueError, match="lengths"):
        InteractingChain((1,))


# ------------------------------------------------------------------ the tape-measure swimmer (a looped chain)
TAPE_SHAPES = np.array([[0.05, 0.45], [0.4, 0.6], [1.2, 0.3], [np.pi / 2, 0.78], [-0.7, 0.5], [0.8, 0.0], [2.5, -0.6]])


def _world_part_velocities(system, r, r_dot, h=1e-5):
    """Body velocities (P, 3) of the head and segments by central differences of their world poses
    exp(t xi) link_poses(r + t r_dot) (the body at the identity at t = 0, xi = -A r_dot): SE2.log of
    g(-h)^-1 g(h) over 2 h, second order in h."""
    from gm_core import SE2

    xi = system.body_velocity(r, r_dot)
    world = [SE2.compose(SE2.exp(t * xi), system.link_poses(r + t * r_dot)) for t in (-h, h)]
    return SE2.log(SE2.compose(SE2.inverse(world[0]), world[1])) / (2 * h), system.link_poses(r)


@pytest.mark.parametrize("symmetric", [True, False])
def test_the_tape_measure_keeps_zero_momentum_by_finite_differences_of_its_parts(symmetric):
    """Independent of the closed-form Jacobians: the parts' body velocities from their world poses; their
    momenta sum_i Ad_{g_i^-1}^T M_i xi_i vanish, and sum_i xi_i^T M_i xi_i is r_dot^T M_r r_dot."""
    from gm_core import SE2
    from gm_core.systems.tape_measure import TapeMeasure

    system = TapeMeasure(symmetric=symmetric)
    rng = np.random.default_rng(37)
    for q in TAPE_SHAPES:
        r = q if symmetric else np.array([q[0], q[0] * 0.6 + 0.3, q[1]])
        r_dot = rng.normal(size=system.n_shape)
        xi, g = _world_part_velocities(system, r, r_dot)
        M = system.link_matrices(r)
        momenta = np.einsum("pji,pjk,pk->pi", SE2.Ad_inv(g), M, xi)
        scale = np.abs(momenta).max()
        assert np.abs(momenta.sum(0)).max() <= 1e-8 * scale
        energy = np.einsum("pi,pij,pj->", xi, M, xi)
        np.testing.assert_allclose(r_dot @ system.shape_metric(r) @ r_dot, energy, rtol=1e-8)


def test_the_tape_measure_loop_closes_and_its_pieces_lie_on_the_tapes():
    """Segment 1 leaves the head at the opening angle, segment 2 runs from the buckle to the tip (L, 0),
    each tape has length C; the drawing's pieces sit on the two segments."""
    from gm_core.systems.tape_measure import TapeMeasure

    system = TapeMeasure(0.8, symmetric=False, tape_pieces=8)
    r = np.array([0.7, 0.2, 0.5])
    g, lengths = system.link_poses(r), system.segment_lengths(r)
    ends = lambda i, sign: g[i, :2] + sign * lengths[i - 1] / 2 * np.array([np.cos(g[i, 2]), np.sin(g[i, 2])])  # noqa: E731
    for k, (a, s) in enumerate(((0.7, 1), (0.2, -1))):
        np.testing.assert_allclose(ends(1 + k, -1), [0, 0], atol=1e-15)
        assert np.isclose(g[1 + k, 2], s * a, rtol=0, atol=1e-15)
        np.testing.assert_allclose(ends(1 + k, 1), ends(3 + k, -1), atol=1e-14)
        np.testing.assert_allclose(ends(3 + k, 1), [0.5, 0], atol=1e-14)
        assert np.isclose(lengths[k] + lengths[2 + k], 0.8, rtol=1e-15)
    poses = system.part_poses(r)
    assert poses.shape == (1 + 2 * 8, 3) and len(system.parts()) == 17
    for k in (0, 1):
        for p in poses[1 + 8 * k: 9 + 8 * k]:
            off = [p[:2] - g[i, :2] for i in (1 + k, 3 + k)]
            on = [abs(np.cos(g[i, 2]) * d[1] - np.sin(g[i, 2]) * d[0]) < 1e-14 and abs(p[2] - g[i, 2]) < 1e-15
                  and np.hypot(*d) <= lengths[i - 1] / 2 + 1e-14 for i, d in zip((1 + k, 3 + k), off)]
            assert any(on)


def test_the_asymmetric_tape_measure_with_equal_angles_is_the_symmetric_one():
    """alpha1 = alpha2 = alpha: the symmetric connection's alpha column is the sum of the two angle columns."""
    from gm_core.systems.tape_measure import TapeMeasure

    sym, asym = TapeMeasure(), TapeMeasure(symmetric=False)
    R = TAPE_SHAPES
    A, B = sym.connection(R), asym.connection(np.stack([R[:, 0], R[:, 0], R[:, 1]], -1))
    np.testing.assert_allclose(A, np.stack([B[..., 0] + B[..., 1], B[..., 2]], -1), rtol=0, atol=1e-14)
    np.testing.assert_allclose(A[..., 1:, :], 0, atol=1e-15)           # no sideways or turning motion by symmetry
    assert np.abs(asym.connection([0.3, 0.9, 0.6])[1:]).max() > 1e-2


def test_the_tape_measure_has_no_shape_where_the_loop_cannot_close_and_refuses_bad_input_by_name():
    from gm_core.systems.tape_measure import TapeMeasure

    system = TapeMeasure()
    R = np.array([[0.3, -1.0], [0.3, 1.0], [0.3, 1.5], [0.3, -1.2], [0.3, 0.5], [0.3, 0.0], [2.0, -0.4]])
    A = system.connection(R)
    assert np.isnan(A[:4]).all() and np.isfinite(A[4:]).all()
    np.testing.assert_array_equal(system.is_singular(R), [True] * 4 + [False] * 3)
    folded = system.link_poses([0.3, 0.0])                   # L = 0: each tape runs out and back to the head
    np.testing.assert_allclose(folded[3:, :2], folded[1:3, :2], atol=1e-15)
    assert np.isnan(system.shape_metric(R[:1])).all()
    for bad, match in ((dict(tape_length=-1), "tape_length"), (dict(tape_length=1e-9), "tape_length"), (dict(head_mass=0), "head_mass"),
                       (dict(added_mass_rate=-1), "added_mass_rate"), (dict(tape_pieces=1), "tape_pieces")):
        with pytest.raises(ValueError, match=match):
            TapeMeasure(**bad)
    with pytest.raises(TypeError, match="symmetric"):
        TapeMeasure(symmetric="yes")
    with pytest.raises(ValueError, match="alpha, L"):
        system.connection([0.3, 0.5, 0.1])


def test_sysplotters_central_differences_limit_it_to_1e_11_on_the_tape_measure():
    """sysplotter's own values agree with the catalog's closed form far inside CLOSED_FORM_RTOL: its central
    differences of beta (step 1e-5) cost it about 1e-11 of the metric, no more."""
    system = catalog.load("symmetricTapeMeasure")
    ref = catalog.reference("symmetricTapeMeasure")
    A, M = catalog.sysplotter_view(system, ref["shapes"])
    assert _relative(A, ref["A"]) <= 1e-13
    assert _relative(M, ref["metric"]) <= 1e-10


def test_the_asymmetric_tape_measure_loads_from_the_symmetric_model_with_the_files_rates():
    """sysplotter cannot run sysf_asymmetricTapeMeasure.m; the catalog builds it from the symmetric model, and
    its parity row says so while keeping the status "sysplotter cannot run it"."""
    system = catalog.load("asymmetricTapeMeasure")
    entry = FILES["asymmetricTapeMeasure"]
    assert system.n_shape == len(entry.grid_range) == 3 and system.shape_names == ("alpha1", "alpha2", "L")
    d = np.diagonal(system.link_matrices([0.4, 0.4, 0.6]), axis1=-2, axis2=-1)
    l1, l2 = system.segment_lengths([0.4, 0.4, 0.6])[[0, 2]]
    np.testing.assert_allclose(d[0], [0.25, 0.25, 1.0])
    np.testing.assert_allclose(d[1], [0.001 * l1, 0.201 * l1, (l1 / 2) ** 3 / 15 + 5.9 * (l1 / 2) ** 4], rtol=1e-15)
    np.testing.assert_allclose(d[3], [0.001 * l2, 0.201 * l2, (l2 / 2) ** 3 / 15 + 5.9 * (l2 / 2) ** 4], rtol=1e-15)
    A, M = catalog.sysplotter_view(system, [0.3, 0.9, 0.6])
    assert A.shape == (3, 3) and np.all(np.isfinite(A)) and np.all(np.linalg.eigvalsh(M) > 0)
    (row,) = catalog.parity("asymmetricTapeMeasure")
    assert row.status == "sysplotter cannot run it" and "symmetric tape measure's model" in row.reason

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
from gm_core.systems import AffineRestriction, LinkChain, Rotors, catalog
from gm_core.systems.fluids import added_mass_bem
from gm_core.systems.gaits import circle_gait
from gm_core.systems.motion import net_displacement, trajectory
from gm_core.systems.tabulated import TabulatedConnection

FILES = catalog.sysplotter_files()
LOADABLE = catalog.names()
REFERENCE = catalog.reference()


def test_the_catalog_lists_every_one_of_sysplotters_41_files():
    """Every file Octave was run on (every sysf_*.m of sysplotter) is in the table, and no other."""
    assert len(FILES) == 41
    assert set(FILES) == set(REFERENCE["files"])
    assert set(LOADABLE) <= set(FILES)
    assert len(LOADABLE) >= 27
    for entry in FILES.values():
        assert entry.loadable == (entry.missing == ""), entry.name
        assert entry.model and len(entry.grid_range) >= 1


@pytest.mark.parametrize("name", LOADABLE)
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


@pytest.mark.parametrize("name", [n for n in LOADABLE if not FILES[n].differs])
def test_where_sysplotter_is_right_the_catalog_agrees_to_1e8(name):
    system = catalog.load(name)
    ref = catalog.reference(name)
    A, M = catalog.sysplotter_view(system, ref["shapes"])
    assert _relative(A, ref["A"]) <= catalog.CLOSED_FORM_RTOL
    if M is not None:
        assert _relative(M, ref["metric"]) <= catalog.CLOSED_FORM_RTOL


@pytest.mark.parametrize("name", [n for n in LOADABLE if FILES[n].differs])
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
            assert max(r.A_difference, r.M_difference) <= catalog.CLOSED_FORM_RTOL
        elif r.status == "corrected":
            assert r.as_sysplotter <= catalog.CLOSED_FORM_RTOL and r.reason
        else:
            assert r.reason, r.name
    assert by_status["sysplotter cannot run it"] == ["asymmetricTapeMeasure"]
    assert len(by_status["agrees"]) + len(by_status["corrected"]) == len(LOADABLE)


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
    with pytest.raises(ValueError, match="cannot load this file yet"):
        catalog.load("symmetricTapeMeasure")
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

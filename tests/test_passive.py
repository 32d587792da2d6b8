"""Passive spring/damper joints (gm_core.systems.passive), each result by a second route.

The shape dynamics M r_ddot + C = tau are checked by energy (the driven joint's work less the
damper's loss is the change of kinetic plus spring energy, with the energy read from the metric
alone), the Coriolis terms against Lagrange's equations worked by sympy on a closed-form metric
and against sysplotter's own formula, g(T) against an ode of the world pose, and the stiff-spring
limit against the quasi-static joint angle computed from the metric; and the whole simulation against
sysplotter's own simulate2DPassiveSwimmer.m run in Octave (tools/sysplotter_reference.py --passive).
"""
import json
from importlib import resources

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import simpson, solve_ivp

from gm_core.geometry.optimal import fourier_gait
from gm_core.systems import catalog
from gm_core.systems.gaits import Gait
from gm_core.systems.motion import net_displacement
from gm_core.systems.passive import PassiveJoints, christoffel_symbols

AMPLITUDE, PERIOD = 0.8, 1.0
SINE = fourier_gait([[0.0]], [[AMPLITUDE]], period=PERIOD)
W = 2 * np.pi / PERIOD


def sine_callables(amplitude=AMPLITUDE):
    return (lambda t: amplitude * np.sin(W * t), lambda t: amplitude * W * np.cos(W * t),
            lambda t: -amplitude * W ** 2 * np.sin(W * t))


@pytest.fixture(scope="module")
def chain():
    return catalog.load("three_link_passive")


@pytest.fixture(scope="module")
def limit():
    """The file's model driven by a sine on joint 2, five periods to settle, then one more."""
    return catalog.passive_model("three_link_passive").simulate(SINE, cycles=5, samples=401)


def energy(system, stiffness, r, v):
    """Kinetic plus spring energy at samples r, v (N, 2), from the metric alone (spring on joint 1)."""
    M = system.shape_metric(r)
    return 0.5 * np.einsum("ni,nij,nj->n", v, M, v) + 0.5 * stiffness * r[:, 0] ** 2


# -- (a) energy ----------------------------------------------------------------------------------------------
def test_the_driven_work_less_damping_is_the_change_of_kinetic_and_spring_energy(chain):
    """From rest (no settling), over one period: work - dissipated = E(T) - E(0), E read from M alone."""
    model = PassiveJoints(chain, passive=(0,), stiffness=0.074, damping=0.01)
    res = model.simulate(SINE, cycles=0, samples=2001)
    E = energy(chain, 0.074, res.shape, res.shape_velocity)
    change = E[-1] - E[0]
    assert abs(change) > 1e-3 * abs(res.work)                      # not on the limit cycle yet: energy moves
    assert res.work - res.dissipated == pytest.approx(change, rel=1e-7, abs=1e-12)
    # the ode's own integrals against Simpson's rule on the samples
    power = np.einsum("ni,ni->n", res.torque, res.shape_velocity[:, 1:])
    assert simpson(power, x=res.times) == pytest.approx(res.work, rel=1e-6)
    assert simpson(0.01 * res.shape_velocity[:, 0] ** 2, x=res.times) == pytest.approx(res.dissipated, rel=1e-6)
    assert simpson((res.torque ** 2).sum(-1), x=res.times) == pytest.approx(res.torque_squared, rel=1e-6)
    # along the way too: E(t) - E(0) is the work so far less the loss so far
    half = 1000
    assert simpson(power[:half + 1], x=res.times[:half + 1]) - simpson(
        0.01 * res.shape_velocity[:half + 1, 0] ** 2, x=res.times[:half + 1]) == pytest.approx(E[half] - E[0], rel=1e-5)


def test_on_the_limit_cycle_the_work_is_what_the_damper_dissipates(limit):
    assert limit.work > 0
    assert limit.work == pytest.approx(limit.dissipated, rel=1e-8)


# -- (b) a stiff spring --------------------------------------------------------------------------------------
@pytest.mark.slow
def test_a_stiff_spring_holds_the_passive_joint_at_its_quasi_static_angle_and_g_tends_to_the_one_joint_gait(chain):
    """k r_1 -> -(M_12 r_ddot_2 + C_1) at r_1 = 0 (central differences of M here), and g(T) -> 0 (the scallop)."""
    t = np.linspace(0.0, PERIOD, 401)
    r2, v2, a2 = (f(t) for f in sine_callables())
    r = np.stack([0 * t, r2], -1)
    h = 1e-5
    M = chain.shape_metric(r)
    d1 = (chain.shape_metric(r + [h, 0]) - chain.shape_metric(r - [h, 0])) / (2 * h)
    d2 = (chain.shape_metric(r + [0, h]) - chain.shape_metric(r - [0, h])) / (2 * h)
    C1 = (d2[:, 0, 1] - 0.5 * d1[:, 1, 1]) * v2 ** 2                # Lagrange at r_dot = (0, v2)
    quasi_static = np.abs(M[:, 0, 1] * a2 + C1).max()               # max |k r_1|
    one_joint = net_displacement(chain, Gait(lambda s: np.stack([0 * s, AMPLITUDE * np.sin(W * s)], -1), PERIOD))
    assert np.abs(one_joint).max() < 1e-12
    errors, moves = [], []
    for k in (1.0, 4.0):
        b = 2 * np.sqrt(k * M[0, 0, 0])                                 # critically damped: settles in one period
        res = PassiveJoints(chain, (0,), k, b).simulate(SINE, cycles=1, samples=401)
        errors.append(abs(k * np.abs(res.shape[:, 0]).max() / quasi_static - 1))
        moves.append(np.linalg.norm(res.displacement - one_joint))
    assert errors[0] < 2e-2 and errors[1] < 0.7 * errors[0]
    assert moves[1] < moves[0] / 3


# -- (c) the Coriolis terms ----------------------------------------------------------------------------------
def _closed_form():
    q = sp.symbols("q1 q2")
    M = sp.Matrix([[3 + 2 * sp.cos(q[1]) + sp.sin(q[0]) / 5, 1 + sp.cos(q[1]) + q[0] * q[1] / 5],
                   [1 + sp.cos(q[1]) + q[0] * q[1] / 5, 1 + sp.sin(q[0]) * sp.cos(q[1]) / 4]])
    return q, M


def test_the_coriolis_terms_are_lagranges_equations_worked_by_sympy(chain):
    """C = d/dt dL/dq_dot - dL/dq - M q_ddot for L = 1/2 q_dot^T M(q) q_dot, by sympy; and dM by sympy."""
    q, Msym = _closed_form()
    t = sp.symbols("t")
    path = [sp.Function(f"x{i}")(t) for i in (1, 2)]
    sub = dict(zip(q, path))
    Mt = Msym.subs(sub)
    qd = sp.Matrix([sp.diff(x, t) for x in path])
    L = (qd.T * Mt * qd)[0] / 2
    eqs = [sp.diff(sp.diff(L, qd[i]), t) - sp.diff(L, path[i]) - (Mt * sp.Matrix([sp.diff(x, t, 2) for x in path]))[i]
           for i in range(2)]
    v = sp.symbols("v1 v2")
    back = {sp.diff(path[i], t): v[i] for i in range(2)}
    back2 = {sp.diff(path[i], t, 2): 0 for i in range(2)}
    C_expr = [sp.simplify(e.subs(back2).subs(back).subs(dict(zip(path, q)))) for e in eqs]
    C_fun = sp.lambdify([q, v], C_expr, "numpy")
    dM_fun = sp.lambdify([q], [[[sp.diff(Msym[i, j], q[k]) for k in range(2)] for j in range(2)] for i in range(2)], "numpy")
    M_fun = sp.lambdify([q], Msym, "numpy")

    def metric(r):
        r = np.asarray(r, dtype=float)
        flat = r.reshape(-1, 2)
        return np.array([M_fun(x) for x in flat], dtype=float).reshape(r.shape[:-1] + (2, 2))

    model = PassiveJoints(chain, (0,), 1.0, 0.1, metric=metric)
    rng = np.random.default_rng(3)
    for _ in range(5):
        r, rd = rng.uniform(-1.5, 1.5, 2), rng.uniform(-3, 3, 2)
        assert model.coriolis(r, rd) == pytest.approx(np.array(C_fun(r, rd), dtype=float), rel=1e-9, abs=1e-10)
        Mv, dM = model.metric_derivative(r)
        assert dM == pytest.approx(np.array(dM_fun(r), dtype=float), rel=1e-9, abs=1e-10)
        assert Mv == pytest.approx(metric(r))


def test_the_chains_coriolis_terms_are_sysplotters_formula(chain):
    """sysplotter's getCoriolisForces: C = (dM/dr_1 r_dot_1 + dM/dr_2 r_dot_2) r_dot - 1/2 [r_dot^T dM/dr_i r_dot]_i."""
    model = catalog.passive_model("three_link_passive")
    rng = np.random.default_rng(7)
    h = 1e-5
    for _ in range(4):
        r, v = rng.uniform(-2, 2, 2), rng.uniform(-5, 5, 2)
        d = [(chain.shape_metric(r + e) - chain.shape_metric(r - e)) / (2 * h) for e in np.eye(2) * h]
        theirs = (d[0] * v[0] + d[1] * v[1]) @ v - 0.5 * np.array([v @ d[0] @ v, v @ d[1] @ v])
        assert model.coriolis(r, v) == pytest.approx(theirs, rel=1e-7, abs=1e-12 * np.abs(theirs).max())


def test_christoffel_symbols_are_symmetric_and_sum_to_the_metrics_derivative():
    """G_ijk = G_ikj and G_ijk + G_jik = dM_ij/dr_k, for any dM symmetric in i, j."""
    dM = np.random.default_rng(1).normal(size=(4, 3, 3, 3))
    dM = dM + dM.transpose(0, 2, 1, 3)
    G = christoffel_symbols(dM)
    assert np.allclose(G, G.transpose(0, 1, 3, 2))
    assert np.allclose(G + G.transpose(0, 2, 1, 3), dM)
    with pytest.raises(ValueError, match="dM must have shape"):
        christoffel_symbols(np.zeros((2, 2)))


# -- (d) the limit cycle and g(T) ------------------------------------------------------------------------------
def test_the_last_period_is_periodic_in_the_passive_joint(limit):
    assert np.abs(limit.shape[:, 0]).max() > 0.05                     # the tail really swings
    assert limit.shape[-1, 0] == pytest.approx(limit.shape[0, 0], abs=1e-8)
    assert limit.shape_velocity[-1, 0] == pytest.approx(limit.shape_velocity[0, 0], abs=1e-7)
    assert limit.torque[-1] == pytest.approx(limit.torque[0], rel=1e-6)


@pytest.mark.slow
def test_more_settling_periods_change_nothing(limit):
    later = catalog.passive_model("three_link_passive").simulate(SINE, cycles=8, samples=401)
    assert later.displacement == pytest.approx(limit.displacement, abs=1e-9)
    assert later.shape == pytest.approx(limit.shape, abs=1e-8)


def test_g_of_T_agrees_with_an_ode_of_the_world_pose(chain, limit):
    """sysplotter's route: (x, y, theta)' = R(theta) (-A r_dot), by solve_ivp on the reported shape path."""
    def rhs(t, y):
        xi = -chain.connection(limit.gait(t)) @ limit.gait.velocity(t)
        c, s = np.cos(y[2]), np.sin(y[2])
        return [c * xi[0] - s * xi[1], s * xi[0] + c * xi[1], xi[2]]
    world = solve_ivp(rhs, (0.0, PERIOD), [0.0, 0.0, 0.0], method="DOP853", rtol=1e-11, atol=1e-13).y[:, -1]
    assert np.abs(limit.displacement[:2]).max() > 1e-2
    assert limit.displacement == pytest.approx(world, abs=1e-9)


def test_three_callables_drive_like_the_fourier_gait(chain):
    model = catalog.passive_model("three_link_passive")
    a = model.simulate(SINE, cycles=1, samples=51)
    b = model.simulate(sine_callables(), PERIOD, cycles=1, samples=51)
    assert b.shape == pytest.approx(a.shape, abs=1e-9)
    assert b.displacement == pytest.approx(a.displacement, abs=1e-10)
    assert b.work == pytest.approx(a.work, rel=1e-8)


# -- catalog ------------------------------------------------------------------------------------------------
def test_the_catalog_says_where_the_passive_model_lives_and_gives_k_and_b():
    entry = catalog.sysplotter_files()["three_link_passive"]
    assert (entry.passive, entry.stiffness, entry.damping) == ((0,), 0.074, 0.01)
    assert "gm_core.systems.passive" in entry.model
    (row,) = catalog.parity("three_link_passive")
    assert "gm_core.systems.passive" in row.model and row.status == "corrected"
    model = catalog.passive_model("three_link_passive")
    assert model.passive == (0,) and model.driven == (1,)
    assert model.stiffness.tolist() == [0.074] and model.damping.tolist() == [0.01]
    with pytest.raises(ValueError, match="name 'three_link_HighRe' has no passive joints.*three_link_passive"):
        catalog.passive_model("three_link_HighRe")


# -- (e) bad input ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize(("kwargs", "error", "match"), [
    ({"stiffness": -1.0}, ValueError, "stiffness must be non-negative"),
    ({"damping": -0.1}, ValueError, "damping must be non-negative"),
    ({"stiffness": True}, TypeError, "stiffness"),
    ({"damping": [0.1, 0.2]}, ValueError, "damping must be one number or 1"),
    ({"passive": (2,)}, ValueError, "passive must index the 2 shape variables"),
    ({"passive": (-1,)}, ValueError, "passive"),
    ({"passive": (0, 1)}, ValueError, "at least one driven"),
    ({"passive": ()}, TypeError, "passive must be a non-empty tuple"),
    ({"passive": "0"}, TypeError, "passive"),
    ({"metric": 3.0}, TypeError, "metric must be a callable"),
])
def test_bad_model_arguments_are_refused_by_name(chain, kwargs, error, match):
    with pytest.raises(error, match=match):
        PassiveJoints(chain, **kwargs)


def test_a_system_must_be_a_system():
    with pytest.raises(TypeError, match="system must be a locomotion system"):
        PassiveJoints("three_link_passive")


@pytest.mark.parametrize(("args", "kwargs", "error", "match"), [
    ((lambda t: t,), {}, TypeError, "driven must be a FourierGait .* or three callables"),
    (((1.0, 2.0, 3.0), 1.0), {}, TypeError, "driven must be a FourierGait or three callables"),
    ((sine_callables(),), {}, ValueError, "period must be given"),
    ((sine_callables(), 0.0), {}, ValueError, "period must be positive"),
    ((sine_callables(), -1.0), {}, ValueError, "period must be positive"),
    ((SINE, 2.0), {}, ValueError, "period must match the Fourier gait's period"),
    ((fourier_gait([[0.0], [0.0]], [[1.0], [1.0]]),), {}, ValueError, "driven must move the 1 driven joint"),
    ((SINE,), {"cycles": -1}, ValueError, "cycles"),
    ((SINE,), {"samples": 1}, ValueError, "samples"),
])
def test_bad_simulation_arguments_are_refused_by_name(args, kwargs, error, match):
    with pytest.raises(error, match=match):
        catalog.passive_model("three_link_passive").simulate(*args, **kwargs)


# -- sysplotter's own simulation, run in Octave ----------------------------------------------------------------
#: How closely sysplotter's simulate2DPassiveSwimmer computes: ode45 at its default tolerances (RelTol 1e-3),
#: its last period read back by a spline through ode45's steps (tools/sysplotter_reference.py's deval).
SYSPLOTTER_RTOL = 5e-3


def test_the_model_is_sysplotters_simulate2DPassiveSwimmer_run_in_octave():
    """With sysplotter's added mass (the pi/8 defect) put back, the course reproduces sysplotter's g(T), cost
    (the driven joint's work) and passive joint to the accuracy of its ode45; with the course's own metric
    the answer differs by far more: the defect is the whole difference."""
    ref = json.loads(resources.files("gm_core.systems").joinpath("sysplotter_passive.json").read_text())
    drive = ref["drive"]
    assert drive["file"] == "three_link_passive" and (ref["k"], ref["b"]) == (0.074, 0.01)
    gait = fourier_gait([[0.0]], [[drive["amplitude"]]], period=drive["period"])
    theirs_g, theirs_r1 = np.array(ref["g"]), np.array(ref["passive"])
    as_sysplotter = PassiveJoints(catalog.with_sysplotter_added_mass(catalog.load(drive["file"])), (0,), ref["k"], ref["b"])
    mine = as_sysplotter.simulate(gait, cycles=5, samples=len(ref["times"]))
    assert mine.times == pytest.approx(ref["times"], abs=1e-12)
    assert mine.shape[:, 1] == pytest.approx(ref["driven"], abs=1e-12)
    scale = np.linalg.norm(theirs_g[:2])
    assert np.abs(mine.displacement - theirs_g).max() <= SYSPLOTTER_RTOL * scale
    assert np.hypot(*mine.displacement[:2]) == pytest.approx(ref["displ"], rel=SYSPLOTTER_RTOL)
    assert mine.work == pytest.approx(ref["cost"], rel=SYSPLOTTER_RTOL)
    amplitude = np.abs(theirs_r1).max()
    assert np.abs(mine.shape[:, 0] - theirs_r1).max() <= SYSPLOTTER_RTOL * amplitude
    corrected = catalog.passive_model(drive["file"]).simulate(gait, cycles=5, samples=11)
    assert np.abs(corrected.displacement - theirs_g).max() > 20 * SYSPLOTTER_RTOL * scale


def test_stiffness_and_damping_follow_the_order_of_the_passive_joints():
    chain = catalog.load("three_link_HighRe")
    three = PassiveJoints(catalog.load("four_link_HighRe"), passive=(2, 0), stiffness=(0.3, 0.1), damping=(0.02, 0.01))
    assert three.passive == (2, 0) and three.driven == (1,)
    assert three.stiffness.tolist() == [0.3, 0.1] and three.damping.tolist() == [0.02, 0.01]
    assert PassiveJoints(chain, passive=1).passive == (1,)


def test_two_passive_joints_keep_the_energy_balance():
    """A four-link chain (three joints), joints 1 and 3 on springs, joint 2 driven: work - loss = change of energy."""
    chain = catalog.load("four_link_HighRe")
    k, b = np.array([0.3, 0.1]), np.array([0.02, 0.01])
    res = PassiveJoints(chain, passive=(2, 0), stiffness=k, damping=b).simulate(SINE, cycles=0, samples=1001)
    r, v = res.shape, res.shape_velocity
    M = chain.shape_metric(r)
    E = 0.5 * np.einsum("ni,nij,nj->n", v, M, v) + 0.5 * (k * r[:, [2, 0]] ** 2).sum(-1)
    assert np.abs(r[:, [0, 2]]).max() > 0.05                          # both springs move
    assert res.work - res.dissipated == pytest.approx(E[-1] - E[0], rel=1e-7, abs=1e-12)
    assert simpson((b * v[:, [2, 0]] ** 2).sum(-1), x=res.times) == pytest.approx(res.dissipated, rel=1e-6)

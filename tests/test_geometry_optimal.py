"""Cost metrics, Fourier gaits, gradients and optimal gaits against sysplotter's strokes."""
import numpy as np
import pytest

from gm_core import SE2, SingularShapeError
from gm_core.geometry import (
    SYSPLOTTER_STROKES,
    FourierGait,
    dissipation_metric,
    efficiency,
    fourier_gait,
    gait_objective,
    minimum_perturbation_coordinates,
    optimize_gait,
    path_length,
    sysplotter_stroke,
    sysplotter_swimmer,
)
from gm_core.systems import DifferentialDrive, FloatingSnake, HighReSwimmer, KinematicSnake, LowReSwimmer
from gm_core.systems.gaits import Gait, circle_gait
from gm_core.systems.motion import check_gait, net_displacement, trajectory


# -- metrics -----------------------------------------------------------------------------------
@pytest.mark.parametrize("system", [LowReSwimmer(lengths=(0.5, 1, 1.5), drag_ratio=3), FloatingSnake(),
                                    HighReSwimmer(body_density=0.5)], ids=repr)
def test_metric_is_the_power_of_the_moving_links(system):
    """Independent route: differentiate the links' world poses along a gait, sum xi_i^T D_i xi_i."""
    gait = circle_gait((0.8, 0.5), (0.3, -0.2), period=1.0)
    tr = trajectory(system, gait, n_frames=2001)
    t_k, h = 0.37, tr.t[1] - tr.t[0]
    k = int(round(t_k / h))
    poses = [SE2.compose(tr.g[i][None], system.link_poses(tr.r[i])) for i in (k - 1, k + 1)]
    D = system.link_matrices()
    power = 0.0
    for i in range(3):
        xi = SE2.log(SE2.compose(SE2.inverse(poses[0][i]), poses[1][i])) / (2 * h)
        power += xi @ D[i] @ xi
    rd = gait.velocity(tr.t[k])
    M = dissipation_metric(system, tr.r[k])
    assert rd @ M @ rd == pytest.approx(power, rel=1e-4)
    w = np.linalg.eigvalsh(dissipation_metric(system, np.random.default_rng(0).uniform(-2, 2, (20, 2))))
    assert np.all(w > 0)


def test_path_length_is_pacing_independent_and_euclidean_circle():
    s = LowReSwimmer()
    g = circle_gait(0.7, (0.2, 0.1))
    slow = g.reparameterized(lambda t: t - 0.1 * np.sin(2 * np.pi * t) / (2 * np.pi),
                             lambda t: 1 - 0.1 * np.cos(2 * np.pi * t))
    assert path_length(s, slow) == pytest.approx(path_length(s, g), rel=1e-8)
    assert path_length(DifferentialDrive(), g, metric="euclidean") == pytest.approx(2 * np.pi * 0.7, rel=1e-12)
    with pytest.raises(TypeError, match="no physical cost metric"):
        path_length(DifferentialDrive(), g)
    with pytest.raises(ValueError, match="metric"):
        path_length(s, g, metric="riemann")
    with pytest.raises(ValueError, match="gait is not closed"):
        efficiency(s, Gait(lambda t: np.stack([t, 0 * t], -1), 1.0))
    with pytest.raises(TypeError, match="system"):
        dissipation_metric(None, np.zeros(2))
    with pytest.raises(ValueError, match="r must have shape"):
        dissipation_metric(s, np.zeros(3))


def test_efficiency_from_a_known_displacement_and_fewer_samples():
    """A live panel passes the g(T) of the trajectory it draws and fewer path samples: the same
    efficiency (to far below its readout's 4 decimals); a wrong g(T) gives a different one."""
    s = sysplotter_swimmer()
    g = sysplotter_stroke("efficiency")
    ref = efficiency(s, g)
    g_T = trajectory(s, g, n_frames=61, substeps=8).g[-1]
    assert efficiency(s, g, samples=1024, displacement=g_T) == pytest.approx(ref, rel=1e-7)
    assert efficiency(s, g, displacement=2 * g_T) == pytest.approx(2 * ref, rel=1e-7)
    with pytest.raises(ValueError, match="displacement"):
        efficiency(s, g, displacement=np.zeros(2))
    with pytest.raises(ValueError, match="samples"):
        efficiency(s, g, samples=3)


# -- sysplotter's strokes ----------------------------------------------------------------------
@pytest.mark.parametrize("which", ["displacement", "efficiency"])
def test_sysplotter_strokes_in_our_model(which):
    s, g, ref = sysplotter_swimmer(), sysplotter_stroke(which), SYSPLOTTER_STROKES[which]
    d = net_displacement(s, g)
    assert np.hypot(d[0], d[1]) == pytest.approx(ref["displacement"], abs=5e-6)
    assert abs(d[2]) < 1e-10  # symmetric strokes do not turn
    assert path_length(s, g) == pytest.approx(ref["path_length"], abs=5e-5)
    if "efficiency" in ref:
        assert efficiency(s, g) == pytest.approx(ref["efficiency"], abs=5e-6)


def test_sysplotter_stroke_matches_its_definition():
    a1, b1, a3, b3, a5, b5 = SYSPLOTTER_STROKES["displacement"]["coefficients"]
    t = np.linspace(0, 2 * np.pi, 50)
    u = a1 * np.cos(-t) + a3 * np.cos(-3 * t) + a5 * np.cos(-5 * t)
    v = b1 * np.sin(-t) + b3 * np.sin(-3 * t) + b5 * np.sin(-5 * t)
    c = np.sqrt(2) / 2
    np.testing.assert_allclose(sysplotter_stroke("displacement")(t), np.stack([c * (u - v), c * (u + v)], -1),
                               atol=1e-14)


# -- Fourier gaits and gradients -----------------------------------------------------------------
def test_fourier_gait_values_and_velocity():
    g = fourier_gait([[1.0, 0.2], [0.0, -0.3]], [[0.0, 0.1], [0.8, 0.0]], (0.5, -0.5), period=3.0)
    t = np.linspace(0, 3, 7)
    w = 2 * np.pi / 3
    np.testing.assert_allclose(g(t)[:, 0], 0.5 + np.cos(w * t) + 0.2 * np.cos(2 * w * t) + 0.1 * np.sin(2 * w * t))
    h = 1e-6
    np.testing.assert_allclose(g.velocity(t), (g(t + h) - g(t - h)) / (2 * h), atol=1e-7)
    np.testing.assert_allclose(g(0.0), g(3.0), atol=1e-14)
    g2 = FourierGait.from_parameters(g.parameters, 2, 2, 3.0)
    np.testing.assert_allclose(g2(t), g(t))


@pytest.mark.parametrize("objective", ["displacement", "efficiency"])
@pytest.mark.parametrize("frame", ["middle", "minimum perturbation"])
def test_adjoint_gradient_matches_differences(objective, frame):
    s = sysplotter_swimmer()
    if frame != "middle":
        s = minimum_perturbation_coordinates(s, ((-3, 3), (-3, 3)), 17)
    rng = np.random.default_rng(5)
    g = fourier_gait(np.array([[1.0, 0, 0], [0, 0, 0]]) + 0.3 * rng.normal(size=(2, 3)),
                     np.array([[0, 0, 0], [1.0, 0, 0]]) + 0.3 * rng.normal(size=(2, 3)), (0.2, -0.1))
    val, grad, _ = gait_objective(s, g, objective)
    p = g.parameters
    fd = np.zeros_like(p)
    for i in range(p.size):
        e = np.zeros_like(p)
        e[i] = 1e-5
        f = [gait_objective(s, FourierGait.from_parameters(p + sgn * e, 2, 3), objective, gradient=False)[0]
             for sgn in (1, -1)]
        fd[i] = (f[0] - f[1]) / 2e-5
    np.testing.assert_allclose(grad, fd, atol=1e-6 * np.abs(fd).max())


# -- optimisation --------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def optima():
    s = sysplotter_swimmer()
    return {obj: optimize_gait(s, obj, order=3) for obj in ("displacement", "efficiency")}


def test_optimiser_reaches_sysplotters_strokes(optima):
    ref = SYSPLOTTER_STROKES
    best_d, best_e = optima["displacement"], optima["efficiency"]
    assert best_d.displacement >= 0.995 * ref["displacement"]["displacement"]
    assert best_e.efficiency >= 0.995 * ref["efficiency"]["efficiency"]
    assert best_d.history[-1] > 2 * best_d.history[0]  # it really climbed from the circle
    assert np.all(np.diff(best_d.history) > -1e-9)
    check_gait(sysplotter_swimmer(), best_d.gait)
    # the result's gait is a plain gait for net_displacement
    d = net_displacement(sysplotter_swimmer(), best_d.gait)
    assert np.hypot(d[0], d[1]) > 0.09


@pytest.fixture(scope="module")
def sysplotter_mp():
    """The sysplotter swimmer in minimum-perturbation coordinates (computed once for both strokes)."""
    return minimum_perturbation_coordinates(sysplotter_swimmer())


@pytest.mark.parametrize("which", ["displacement", "efficiency"])
def test_sysplotter_strokes_are_near_stationary(which, sysplotter_mp):
    s = sysplotter_mp
    g = sysplotter_stroke(which)
    val, grad, _ = gait_objective(s, g, which)
    assert np.linalg.norm(grad) < 0.15 * val  # per radian of coefficient
    better = optimize_gait(s, which, order=5, start=g, coordinates="given", maxiter=60)
    assert better.history[-1] < 1.005 * val  # no nearby gait is more than 0.5 % better


def test_optimiser_refuses_singular_gaits():
    s = KinematicSnake()
    with pytest.raises(SingularShapeError):
        optimize_gait(s, coordinates="given")  # the unit circle crosses alpha1 = alpha2
    start = fourier_gait([[0.5, 0.0], [0.0, 0.0]], [[0.0, 0.0], [0.5, 0.0]], (1.2, -1.2))
    res = optimize_gait(s, "displacement", order=2, start=start, coordinates="given", maxiter=40)
    check_gait(s, res.gait)
    assert np.abs(s.singularity(res.gait(np.linspace(0, 2 * np.pi, 2001)))).min() >= 1e-3


def test_optimiser_bad_input():
    s = sysplotter_swimmer()
    for order in (0, -1, 2.5, True):
        with pytest.raises(ValueError, match="order must be a positive integer"):
            optimize_gait(s, order=order)
    with pytest.raises(ValueError, match="objective"):
        optimize_gait(s, "speed")
    with pytest.raises(ValueError, match="coordinates"):
        optimize_gait(s, coordinates="world")
    with pytest.raises(TypeError, match="start"):
        optimize_gait(s, start=circle_gait(1.0))
    with pytest.raises(TypeError, match="system"):
        optimize_gait("swimmer")
    with pytest.raises(TypeError, match="no physical cost metric"):
        optimize_gait(DifferentialDrive(), "efficiency", coordinates="given")
    with pytest.raises(ValueError, match="b must have"):
        fourier_gait([[1.0, 0.0]], [[1.0]])
    with pytest.raises(ValueError, match="a must have shape"):
        fourier_gait([1.0, 0.0])
    with pytest.raises(ValueError, match="period"):
        fourier_gait([[1.0]], period=-1)
    assert isinstance(Gait, type)


def test_optimize_gait_checks_the_system_once(monkeypatch):
    """The boundary is crossed once: a LocomotionSystem was checked when it was built, so one
    optimisation calls check_system once (its own entry), however many objectives, trajectories
    and connection derivatives it evaluates inside (every module's binding is counted)."""
    import sys

    from gm_core.systems import motion

    calls = []
    original = motion.check_system

    def counting(system, name="system"):
        calls.append(name)
        return original(system, name)

    bound = [m for m in list(sys.modules.values())
             if getattr(m, "__name__", "").startswith("gm_core") and getattr(m, "check_system", None) is original]
    assert motion in bound
    for module in bound:
        monkeypatch.setattr(module, "check_system", counting)
    res = optimize_gait(LowReSwimmer(), "efficiency", order=1, maxiter=3, intervals=64)
    assert res.nit >= 1 and len(res.history) >= 2            # it did iterate (many objective calls)
    assert calls == ["system"]


def test_a_duck_typed_system_is_still_checked_at_every_entry():
    """Objects that are not LocomotionSystems were never checked when built: each public entry
    still refuses a bad one, naming the argument."""
    class NoConnection:
        n_shape, name = 2, "no connection"

    for f in (lambda s: net_displacement(s, circle_gait(0.5)), lambda s: path_length(s, circle_gait(0.5)),
              lambda s: optimize_gait(s)):
        with pytest.raises(TypeError, match="system must be a locomotion system"):
            f(NoConnection())


# -- Fourier fits and trial gaits at the edge of the frame's window ------------------------------
def test_fourier_fit_returns_a_fourier_gait_and_least_squares_coefficients():
    """A Fourier gait of order <= the fit's comes back to round-off; a drawn spline gets the
    coefficients of the least-squares fit on the Fourier basis (an independent route: lstsq)."""
    from gm_core.geometry import fourier_fit

    g = fourier_gait([[0.7, -0.2, 0.05], [0.1, 0.3, 0.0]], [[0.0, 0.4, -0.1], [0.9, 0.0, 0.02]], (0.3, -0.5), period=2.5)
    for order in (3, 5):
        fit = fourier_fit(g, order)
        assert isinstance(fit, FourierGait) and fit.period == g.period and fit.order == order
        t = np.linspace(0.0, g.period, 97)
        np.testing.assert_allclose(fit(t), g(t), atol=1e-14)
        np.testing.assert_allclose(fit.a[:, :3], g.a, atol=1e-15)
        np.testing.assert_allclose(fit.a[:, 3:], 0.0, atol=1e-15)
    spline = Gait.from_samples([[-1.0, -0.8], [1.1, -0.9], [0.9, 1.2], [-1.2, 0.7]], 1.0)
    fit = fourier_fit(spline, 2, samples=512)
    t = np.arange(512) / 512
    basis = np.column_stack([np.ones_like(t)] + [f(2 * np.pi * k * t) for k in (1, 2) for f in (np.cos, np.sin)])
    coef = np.linalg.lstsq(basis, spline(t), rcond=None)[0]          # rows: 1, cos t, sin t, cos 2t, sin 2t
    np.testing.assert_allclose(fit.center, coef[0], atol=1e-13)
    np.testing.assert_allclose(fit.a.T, coef[[1, 3]], atol=1e-13)
    np.testing.assert_allclose(fit.b.T, coef[[2, 4]], atol=1e-13)
    with pytest.raises(ValueError, match="order"):
        fourier_fit(spline, 0)
    with pytest.raises(ValueError, match="samples"):
        fourier_fit(spline, 3, samples=6)


def test_the_optimiser_rejects_trial_gaits_that_graze_the_minimum_perturbation_window():
    """A trial gait whose g(T) is finite but that touches the edge of the frame's window (its
    connection derivative undefined there) is rejected like one leaving it, not a crash, and the
    optimum keeps EDGE_MARGIN of the window's width from the edge."""
    car = DifferentialDrive()
    mp = minimum_perturbation_coordinates(car, ((-2.5, 2.5), (-2.5, 2.5)))
    start = fourier_gait([[1.25, 0.0], [0.0, 0.0]], [[0.0, 0.0], [1.25, 0.0]])
    res = optimize_gait(mp, "displacement", order=2, start=start, maxiter=8)
    r = res.gait(np.linspace(0.0, res.gait.period, 2001))
    assert np.abs(r).max() <= 2.5 - 5.0 * 1e-3 + 1e-9 and res.displacement >= res.history[0] > 0
    np.testing.assert_allclose(res.net_displacement, net_displacement(mp, res.gait), atol=1e-6)

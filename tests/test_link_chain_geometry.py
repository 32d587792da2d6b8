"""The geometric analysis in any shape dimension: slices, the curvature 2-form, Stokes estimates,
minimum perturbation on a 3-D box, the continuous slender body and gait optimisation of a
five-link swimmer. Independent routes: net rotations (theta is abelian), finite differences,
the full system integrated along an embedded gait, chains of many links, and circles."""
import numpy as np
import pytest

from gm_core import SE2, SingularShapeError
from gm_core.geometry import (
    body_velocity_integral,
    constraint_curvature,
    fourier_gait,
    gait_objective,
    minimum_perturbation_coordinates,
    optimize_gait,
    stokes_estimate,
)
from gm_core.systems import (
    LinkChain,
    LowReSwimmer,
    SlenderBody,
    chain_approximation,
    shape_slice,
)
from gm_core.systems.gaits import Gait, circle_gait
from gm_core.systems.motion import net_displacement

RNG = np.random.default_rng(2022)


def _embedded(sl, gait2):
    """The 2-D gait of a slice as a gait of the full system."""
    return Gait(lambda t: sl.full_shape(gait2(t)), gait2.period, lambda t: gait2.velocity(t) @ sl.matrix.T)


# ------------------------------------------------------------------ curvature as a 2-form
@pytest.mark.parametrize("batch", [(), (1,), (3, 1, 2)], ids=str)
def test_curvature_two_form_against_differences_and_slices(batch):
    chain = LinkChain((1.0, 0.8, 1.2, 0.9, 1.1), "low_re")
    r = RNG.uniform(-1, 1, batch + (4,))
    F = constraint_curvature(chain, r)
    assert F.shape == batch + (3, 4, 4)
    np.testing.assert_allclose(F, -np.swapaxes(F, -1, -2), atol=1e-15)
    np.testing.assert_allclose(constraint_curvature(chain, r, pair=(1, 3)), F[..., 1, 3])
    for i, j in [(0, 1), (1, 3), (2, 3)]:       # the slice's curvature is the component of the 2-form
        for k in np.ndindex(batch):
            sl = shape_slice(chain, r[k], (i, j))
            np.testing.assert_allclose(constraint_curvature(sl, r[k][[i, j]]), F[k][:, i, j], atol=1e-7)
    # the three-link case keeps its (..., 3)
    assert constraint_curvature(LowReSwimmer(), np.zeros(batch + (2,))).shape == batch + (3,)


@pytest.mark.parametrize("axes", [(0, 1), (1, 3), (0, 3), "oblique"])
def test_theta_row_of_the_stokes_estimate_is_exact_in_every_slice(axes):
    chain = LinkChain((1.0, 0.9, 1.1, 1.0, 0.8), "low_re")
    through = np.array([0.3, -0.2, 0.4, 0.1])
    if axes == "oblique":
        axes = np.array([[1.0, 0.5], [0.0, 1.0], [-0.5, 0.2], [0.3, -1.0]])
    sl = shape_slice(chain, through, axes)
    gait = circle_gait(0.7, (0.2, -0.1))
    est = stokes_estimate(sl, gait, samples=(128, 16))
    full = net_displacement(chain, _embedded(sl, gait), steps=512)
    np.testing.assert_allclose(net_displacement(sl, gait, steps=512), full, atol=1e-13)   # the slice is the same system
    assert abs(est[2] - full[2]) < 1e-9 and abs(full[2]) > 1e-3                 # exact theta row
    np.testing.assert_allclose(body_velocity_integral(sl, gait, samples=256)[2], full[2], atol=1e-9)
    # x, y: leading order only, the error of third order in the size of the gait
    err = [np.abs(stokes_estimate(sl, circle_gait(R, (0.2, -0.1)), samples=(64, 12))[:2]
                  - net_displacement(sl, circle_gait(R, (0.2, -0.1)), steps=256)[:2]).max() for R in (0.4, 0.2)]
    assert err[1] < err[0] / 6


def test_body_velocity_integral_in_any_dimension():
    chain = LinkChain((1.0,) * 5)
    a = 0.5 * np.array([[1.0], [0.3], [-0.8], [0.1]])
    b = 0.5 * np.array([[0.0], [1.0], [0.4], [-1.0]])
    gait = fourier_gait(a, b)
    bvi = body_velocity_integral(chain, gait)
    assert bvi.shape == (3,)
    assert abs(bvi[2] - net_displacement(chain, gait)[2]) < 1e-9     # theta is abelian
    with pytest.raises(ValueError, match="shape_slice"):
        stokes_estimate(chain, gait)


# ------------------------------------------------------------------ minimum perturbation in 3-D
@pytest.fixture(scope="module")
def mp3():
    chain = LinkChain((1.0, 1.0, 1.0, 1.0))
    return chain, minimum_perturbation_coordinates(chain, ((-1.2, 1.2),) * 3, 9)


def test_minimum_perturbation_on_a_three_dimensional_box(mp3):
    chain, mp = mp3
    div, div0 = mp.frame.discrete_divergence(), mp.frame.discrete_divergence(of="base")
    assert np.abs(div0).max() > 1e-3 and np.abs(div).max() < 1e-12 * np.abs(div0).max()
    r = RNG.uniform(-1, 1, (10, 3))
    # covariance against differences of the new connection, and conjugated net displacements
    np.testing.assert_allclose(constraint_curvature(mp, r), constraint_curvature(mp, r, method="fd"), atol=1e-5)
    g = fourier_gait(0.6 * np.eye(3)[:, :1], 0.6 * np.array([[0.0], [1.0], [0.5]]))
    b = mp.beta(g(0.0))
    np.testing.assert_allclose(net_displacement(mp, g), SE2.compose(SE2.compose(SE2.inverse(b), net_displacement(chain, g)), b),
                               atol=1e-9)
    # the new connection is smaller in the mean square over the box
    q = RNG.uniform(-1.2, 1.2, (400, 3))
    assert np.sum(mp.connection(q) ** 2) < 0.7 * np.sum(chain.connection(q) ** 2)
    with pytest.raises(SingularShapeError, match="outside"):
        net_displacement(mp, fourier_gait(1.5 * np.eye(3)[:, :1], 1.5 * np.eye(3)[:, 1:2]))


def test_minimum_perturbation_built_into_the_chain(mp3):
    chain, mp = mp3
    own = LinkChain((1.0, 1.0, 1.0, 1.0), frame="minimum perturbation", bounds=((-1.2, 1.2),) * 3, nodes=9)
    r = RNG.uniform(-1, 1, (10, 3))
    np.testing.assert_allclose(own.connection(r), mp.connection(r), atol=1e-12)
    assert np.all(np.isnan(own.connection(np.array([1.5, 0.0, 0.0]))))


def test_too_large_boxes_are_refused_with_the_reason():
    """Four or more joints: refused at once (no minutes of finite elements), with a ValueError that
    names the argument that asked for it and says what to use instead."""
    with pytest.raises(ValueError, match="^system: .*at most 3 shape variables.*frame='com'"):
        minimum_perturbation_coordinates(LinkChain((1.0,) * 5))
    for N in (5, 6, 8):
        with pytest.raises(ValueError, match=f"^frame='minimum perturbation': .*at most 3 .*has {N - 1}"):
            LinkChain((1.0,) * N, frame="minimum perturbation")
        with pytest.raises(ValueError, match="^frame='minimum perturbation'"):
            LinkChain((1.0,) * N).with_frame("minimum perturbation")
    with pytest.raises(ValueError, match="^coordinates='minimum perturbation'.*coordinates='given'"):
        optimize_gait(LinkChain((1.0,) * 5), "efficiency", order=1)
    from gm_core.systems import MinimumPerturbationFrame
    with pytest.raises(ValueError, match="^system: "):
        MinimumPerturbationFrame.fit(chain_approximation(SlenderBody(3.0, "serpenoid"), 5).base_system, None, None)
    with pytest.raises(ValueError, match="nodes"):
        minimum_perturbation_coordinates(LinkChain((1.0,) * 4), n=40)
    with pytest.raises(ValueError, match=r"bounds must have shape \(3, 2\)"):
        minimum_perturbation_coordinates(LinkChain((1.0,) * 4), ((-1, 1), (-1, 1)))
    assert "minimum perturbation" not in LinkChain((1.0,) * 5).body_frames()


# ------------------------------------------------------------------ the continuous body
def test_straight_body_has_the_drag_of_one_link():
    body = SlenderBody(2.0, drag_ratio=3.0)
    np.testing.assert_allclose(body.metric(np.zeros(2))[:3, :3], np.diag([2.0, 6.0, 3.0 * 8 / 12]), atol=1e-13)


def test_body_quadrature_converges():
    r = np.array([[3.0, 1.0], [-2.0, 4.0]])
    fine = SlenderBody(panels=32, order=12).connection(r)
    errs = [np.abs(SlenderBody(panels=p, order=o).connection(r) - fine).max() for p, o in ((2, 4), (4, 6), (8, 8))]
    assert errs[0] > errs[1] > errs[2] and errs[2] < 1e-8


@pytest.mark.parametrize("frame", ["middle", "com"])
def test_chains_sampling_the_curvature_converge_to_the_body_at_rate_two(frame):
    body = SlenderBody(frame=frame, panels=16, order=12)
    r = np.array([[3.0, 1.0], [-2.0, 4.0], [1.0, -5.0]])
    A = body.connection(r)
    errs = np.array([np.abs(chain_approximation(body, N).connection(r) - A).max() for N in (8, 16, 32, 64)])
    assert errs[-1] < 2e-4
    rates = np.log2(errs[:-1] / errs[1:])
    assert np.all(np.abs(rates - 2) < 0.1), rates
    g = circle_gait(2.5)
    d, d64 = net_displacement(body, g, steps=256), net_displacement(chain_approximation(body, 64), g, steps=256)
    assert np.abs(d - d64).max() < 2e-3 * np.abs(d).max()


def test_any_modes_as_functions():
    """The serpenoid pair given as plain functions (integrated numerically) is the built-in pair."""
    w = 2 * np.pi
    own = SlenderBody(1.0, (lambda s: np.cos(w * s), lambda s: np.sin(w * s)))
    r = RNG.uniform(-4, 4, (5, 2))
    np.testing.assert_allclose(own.connection(r), SlenderBody().connection(r), atol=1e-11)
    three = SlenderBody(1.0, (lambda s: np.cos(w * s), lambda s: np.sin(w * s), lambda s: np.cos(2 * w * s)))
    assert three.connection(RNG.uniform(-2, 2, (4, 3))).shape == (4, 3, 3)
    with pytest.raises(TypeError, match="modes"):
        SlenderBody(1.0, "sinusoid" and 3)
    with pytest.raises(ValueError, match="modes"):
        SlenderBody(1.0, "sinusoid")
    with pytest.raises(ValueError, match="modes\\[0\\]"):
        SlenderBody(1.0, (lambda s: np.nan * s,))


def test_a_general_curvature_linear_in_r_is_the_modal_body():
    """The nonlinear route (theta by nested panel rules of kappa(s, r), d kappa / d r given) on a
    curvature that happens to be linear: the same body as its modes with exact integrals, in every frame."""
    from gm_core.systems.slender_body import GeneralCurvature, wave_modes
    modes, integrals = wave_modes((1, 2))
    phi = lambda s: np.stack([f(s) for f in modes], -1)                      # noqa: E731
    general = GeneralCurvature(lambda s, r: r @ phi(s).T, lambda s, r: np.broadcast_to(phi(s), r.shape[:-1] + phi(s).shape),
                               ("r1", "r2", "r3", "r4"))
    r = RNG.uniform(-6, 6, (4, 4))
    for frame in ("middle", "com", "tail", "com-mean"):
        a = SlenderBody(1.0, general, frame=frame, panels=16, order=12)
        b = SlenderBody(1.0, modes, integrals=integrals, frame=frame, panels=16, order=12)
        np.testing.assert_allclose(a.connection(r), b.connection(r), rtol=0, atol=1e-12)
        np.testing.assert_allclose(a.shape_metric(r), b.shape_metric(r), rtol=0, atol=1e-12)
        np.testing.assert_allclose(a.link_poses(r), b.link_poses(r), rtol=0, atol=1e-12)


def test_piecewise_constant_curvature_converges_fast_with_breaks_and_slowly_without():
    """Constant-curvature thirds: with panel edges at the jumps (exact theta or not) the body is right to
    rounding already with 4 panels of 8 nodes; panels straddling the jumps are still off by 1e-4 at 16 x 12."""
    from gm_core.systems.slender_body import segment_modes
    modes, integrals, breaks = segment_modes([0, 1 / 3, 2 / 3, 1])
    assert breaks == (1 / 3, 2 / 3)
    r = np.array([[4.0, -3.0, 2.0], [-1.0, 5.0, 0.5]])
    exact = SlenderBody(1.0, modes, integrals=integrals, breaks=breaks, panels=32, order=16).connection(r)
    for p, o in ((4, 8), (8, 8)):
        np.testing.assert_allclose(SlenderBody(1.0, modes, integrals=integrals, breaks=breaks, panels=p, order=o)
                                   .connection(r), exact, rtol=0, atol=1e-14)
        np.testing.assert_allclose(SlenderBody(1.0, modes, breaks=breaks, panels=p, order=o).connection(r), exact,
                                   rtol=0, atol=1e-14)
    straddled = [np.abs(SlenderBody(1.0, modes, panels=p, order=o).connection(r) - exact).max() for p, o in ((4, 8), (16, 12))]
    assert min(straddled) > 1e-4
    with pytest.raises(ValueError, match="breaks"):
        SlenderBody(1.0, modes, breaks=[0.5, 1.0])
    with pytest.raises(ValueError, match="bounds"):
        segment_modes([0.2, 0.5, 1.0])
    with pytest.raises(ValueError, match="frame"):
        SlenderBody(frame="head")
    with pytest.raises(ValueError, match="integrals must be the modes' integrals from the middle"):
        SlenderBody(1.0, modes, integrals=[lambda s: s] * 3)
    with pytest.raises(TypeError, match="integrals must be None or one function"):
        SlenderBody(1.0, modes, integrals=integrals[:2])
    with pytest.raises(ValueError, match="body must have modal curvature"):
        chain_approximation(SlenderBody(frame="tail"), 5)


# ------------------------------------------------------------------ optimisation in any dimension
def test_gradient_of_a_four_joint_gait_against_differences():
    chain = LinkChain((1.0,) * 5, frame="com")
    a = RNG.uniform(-0.5, 0.5, (4, 2))
    b = RNG.uniform(-0.5, 0.5, (4, 2))
    g = fourier_gait(a, b, RNG.uniform(-0.2, 0.2, 4))
    for objective in ("displacement", "efficiency"):
        val, grad, _ = gait_objective(chain, g, objective, intervals=256)
        p = g.parameters
        h = 1e-6
        fd = []
        for k in range(p.size):
            e = np.zeros_like(p)
            e[k] = h
            up = gait_objective(chain, type(g).from_parameters(p + e, 4, 2, g.period), objective, intervals=256,
                                gradient=False)[0]
            dn = gait_objective(chain, type(g).from_parameters(p - e, 4, 2, g.period), objective, intervals=256,
                                gradient=False)[0]
            fd.append((up - dn) / (2 * h))
        np.testing.assert_allclose(grad, fd, rtol=1e-4, atol=1e-7)


@pytest.fixture(scope="module")
def five_link_optimum():
    from gm_core.geometry import chain_swimmer

    chain = chain_swimmer(5)            # from the default start, a circle in the first two joints
    return chain, optimize_gait(chain, "efficiency", order=2, coordinates="given", maxiter=200, intervals=256)


def test_order_two_optimum_of_a_five_link_swimmer(five_link_optimum):
    """Near-stationary (the exact gradient vanishes there), better than the best circle in any pair
    of joints, and a travelling wave: equal-ish amplitudes, phase growing steadily along the body."""
    from gm_core.geometry import efficiency

    chain, res = five_link_optimum
    val, grad, _ = gait_objective(chain, res.gait, "efficiency", intervals=256)
    start = gait_objective(chain, fourier_gait(np.eye(4, 2), np.eye(4, 2)[:, ::-1]), "efficiency", intervals=256)
    assert np.abs(grad).max() < 1e-4 * np.abs(start[1]).max()
    assert val == pytest.approx(res.efficiency, rel=1e-3)
    from gm_core.geometry import CHAIN_STROKES

    assert res.efficiency == pytest.approx(CHAIN_STROKES[5]["efficiency"], rel=1e-4)   # the stored stroke
    circles = [efficiency(chain, fourier_gait(R * np.eye(4)[:, i:i + 1], R * np.eye(4)[:, j:j + 1]), check=False)
               for i in range(4) for j in range(i + 1, 4) for R in np.linspace(0.2, 2.0, 10)]
    assert res.efficiency > 1.5 * max(circles)
    g = res.gait
    amp = np.hypot(g.a[:, 0], g.b[:, 0])
    lag = np.diff(np.unwrap(np.arctan2(g.b[:, 0], g.a[:, 0])))
    assert amp.min() > 0.6 * amp.max()
    assert np.all(np.abs(lag - lag.mean()) < 0.25 * abs(lag.mean())) and abs(lag.mean()) > 0.5


@pytest.mark.parametrize("N", [3, 4, 5])
def test_stored_chain_strokes_are_local_optima(N):
    """The stored strokes of notebook 11: their values, a vanishing exact gradient, and every small
    random change of the coefficients makes them less efficient (a maximum, not a saddle)."""
    from gm_core.geometry import CHAIN_STROKES, chain_stroke, chain_swimmer

    s, g = chain_swimmer(N), chain_stroke(N)
    val, grad, info = gait_objective(s, g, "efficiency", intervals=256)
    assert val == pytest.approx(CHAIN_STROKES[N]["efficiency"], rel=2e-5)
    assert np.hypot(*info["g"][:2]) == pytest.approx(CHAIN_STROKES[N]["displacement"], rel=2e-5)
    assert np.abs(grad).max() < 1e-5
    p = g.parameters
    rng = np.random.default_rng(N)
    for _ in range(6):
        v = rng.normal(size=p.size)
        for eps in (0.02, -0.02):
            q = type(g).from_parameters(p + eps * v / np.linalg.norm(v), N - 1, 2, g.period)
            assert gait_objective(s, q, "efficiency", intervals=256, gradient=False)[0] < val
    if N > 3:   # more links swim more efficiently at the same total length
        assert CHAIN_STROKES[N]["efficiency"] > 1.1 * CHAIN_STROKES[N - 1]["efficiency"]


def test_slices_bad_input_is_named():
    chain = LinkChain((1.0,) * 5)
    with pytest.raises(ValueError, match="axes"):
        shape_slice(chain, None, (0, 0))
    with pytest.raises(ValueError, match="axes"):
        shape_slice(chain, None, (0, 4))
    with pytest.raises(ValueError, match="axes"):
        shape_slice(chain, None, np.ones((4, 2)))
    with pytest.raises(ValueError, match="through"):
        shape_slice(chain, np.zeros(3), (0, 1))
    with pytest.raises(TypeError, match="system"):
        shape_slice("chain", None, (0, 1))
    with pytest.raises(ValueError, match="n_links"):
        chain_approximation(SlenderBody(), 1)
    with pytest.raises(TypeError, match="body"):
        chain_approximation(chain, 8)

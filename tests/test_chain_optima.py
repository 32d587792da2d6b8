"""How the stored chain strokes were chosen, and the numbers notebook 11 may quote about them.

``gm_core.geometry.CHAIN_OPTIMA`` records, for chains of 3, 4 and 5 links, the distinct local
maxima of the efficiency that the optimiser reaches from the fifteen named starts of
``chain_starts``; the stored stroke (``CHAIN_STROKES``) is the most efficient of those whose links
do not cross. The fast tests check the records against fresh computation: every named start is
recorded once, every maximum is stationary, is a maximum and has its recorded efficiency and
displacement, and the stored stroke is the one the rule picks. The slow tests rerun the optimiser
from the named starts that lead to the stored strokes. The last tests compute what the book says
about the best strokes: the five-link stroke's phase step of about 76 degrees and the other maxima
within 0.032 % of it, its S-shaped mean body, and the folded three-link stroke found outside the
named starts.
"""
import numpy as np
import pytest

from gm_core.geometry import (
    CHAIN_OPTIMA,
    CHAIN_STROKES,
    OTHER_CHAIN_OPTIMA,
    FourierGait,
    chain_optima,
    chain_starts,
    chain_stroke,
    chain_swimmer,
    fourier_gait,
    gait_objective,
    links_cross,
    optimize_chain_gait,
    optimize_gait,
    random_start,
    wave_start,
)

LINKS = (3, 4, 5)


def first_harmonic(gait):
    """Amplitudes (rad) and phase steps from joint to joint (degrees) of the first harmonic."""
    amp = np.hypot(gait.a[:, 0], gait.b[:, 0])
    steps = np.degrees(np.diff(np.unwrap(np.arctan2(gait.b[:, 0], gait.a[:, 0]))))
    return amp, steps


def refined_end(n_links, start):
    """Where the search of CHAIN_OPTIMA leads from ``start``: the optimiser at 64 intervals, then
    at 256 (the recorded maxima were refined further, by Newton steps, which moves the efficiency
    by less than 1e-12)."""
    s = chain_swimmer(n_links)
    end = optimize_chain_gait(s, order=2, start=start, maxiter=400, intervals=64).gait
    return optimize_gait(s, "efficiency", order=2, start=end, coordinates="given", maxiter=400,
                         intervals=256, gtol=1e-10).gait


def efficiency_256(n_links, gait):
    return gait_objective(chain_swimmer(n_links), gait, "efficiency", intervals=256, gradient=False)[0]


# ------------------------------------------------------------------ the named starts
@pytest.mark.parametrize("N", LINKS)
def test_the_named_starts(N):
    starts = chain_starts(N)
    assert list(starts) == ([f"wave, lag {lag:g}" for lag in (0.4, 0.8, 1.2, 1.6, 2.0)]
                            + [f"random, seed {k}" for k in range(10)])
    assert np.allclose(starts["wave, lag 0.8"].parameters, wave_start(N - 1, 0.6, 0.8).parameters)
    assert np.allclose(starts["random, seed 3"].parameters, random_start(N - 1, 3).parameters)
    assert [g.order for g in starts.values()] == [1] * 5 + [2] * 10
    shapes = np.array([g(np.linspace(0.0, g.period, 16)).ravel() for g in starts.values()])
    assert len(np.unique(shapes.round(9), axis=0)) == 15                 # fifteen different starts


def test_random_start_is_reproducible_and_checks_its_input():
    a, b = random_start(4, 7), random_start(4, 7)
    assert np.array_equal(a.parameters, b.parameters) and a.order == 2 and a.n_shape == 4
    assert np.abs(a.center).max() <= 0.5
    assert not np.array_equal(a.parameters, random_start(4, 8).parameters)
    with pytest.raises(ValueError, match="seed"):
        random_start(4, -1)
    with pytest.raises(ValueError, match="scale"):
        random_start(4, 0, scale=-0.1)


# ------------------------------------------------------------------ the records
@pytest.mark.parametrize("N", LINKS)
def test_every_named_start_is_recorded_once(N):
    recorded = [name for optimum in CHAIN_OPTIMA[N] for name in optimum["starts"]]
    assert sorted(recorded) == sorted(chain_starts(N))


@pytest.mark.parametrize("N", LINKS)
def test_recorded_maxima_are_stationary_maxima_with_their_values(N):
    s = chain_swimmer(N)
    rng = np.random.default_rng(N)
    values = []
    for optimum, gait in zip(CHAIN_OPTIMA[N], chain_optima(N)):
        value, grad, info = gait_objective(s, gait, "efficiency", intervals=256)
        assert value == pytest.approx(optimum["efficiency"], abs=1e-10)
        assert np.hypot(*info["g"][:2]) == pytest.approx(optimum["displacement"], abs=1e-9)
        assert np.abs(grad).max() < 1e-9                                  # stationary
        p = gait.parameters
        for _ in range(4):                                                # and a maximum
            v = rng.normal(size=p.size)
            q = FourierGait.from_parameters(p + 0.02 * v / np.linalg.norm(v), N - 1, 2)
            assert efficiency_256(N, q) < value
        values.append(value)
    assert all(a > b * (1 + 1e-7) for a, b in zip(values, values[1:]))   # distinct, best first


@pytest.mark.parametrize("N, best", [(3, 1), (4, 0), (5, 0)])
def test_the_stored_stroke_is_the_best_maximum_whose_links_do_not_cross(N, best):
    s = chain_swimmer(N)
    crossing = [links_cross(s, g) for g in chain_optima(N)]
    assert crossing.index(False) == best          # for three links, the one better maximum crosses
    assert np.allclose(chain_stroke(N).parameters, chain_optima(N)[best].parameters)
    assert CHAIN_STROKES[N]["efficiency"] == CHAIN_OPTIMA[N][best]["efficiency"]


def test_links_cross():
    five = chain_swimmer(5)
    still = {tuple(c): fourier_gait(np.zeros((4, 1)), None, np.array(c)) for c in
             [(1.0, 1.0, 1.0, 1.0), (2.0, 2.0, 2.0, 2.0), (3.0, 0.0, 0.0, 0.0), (3.2, 0.0, 0.0, 0.0)]}
    assert not links_cross(five, still[1.0, 1.0, 1.0, 1.0])      # curled, but clear of itself
    assert links_cross(five, still[2.0, 2.0, 2.0, 2.0])          # a star: links 1 and 3 cross
    assert not links_cross(five, still[3.0, 0.0, 0.0, 0.0])      # folded almost flat
    assert links_cross(five, still[3.2, 0.0, 0.0, 0.0])          # folded through its neighbour
    with pytest.raises(TypeError, match="chain"):
        links_cross("five", still[1.0, 1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="shape variables"):
        links_cross(chain_swimmer(3), still[1.0, 1.0, 1.0, 1.0])


# ------------------------------------------------------------------ rerun the search (slow)
def _stored_starts():
    """(N, start) for every named start that leads to the stored stroke of N links."""
    out = []
    for N in LINKS:
        stored = chain_stroke(N).parameters
        for optimum in CHAIN_OPTIMA[N]:
            if np.allclose(optimum["parameters"], stored):
                out += [(N, name) for name in optimum["starts"]]
    return out


@pytest.mark.slow
@pytest.mark.parametrize("N, name", _stored_starts())
def test_each_start_of_the_stored_stroke_leads_to_it(N, name):
    """The climbs that choose the stored strokes, rerun (the other recorded maxima are checked
    above as stationary maxima with their values)."""
    recorded = next(o for o in CHAIN_OPTIMA[N] if name in o["starts"])
    assert efficiency_256(N, refined_end(N, chain_starts(N)[name])) == pytest.approx(
        recorded["efficiency"], rel=1e-7)


# ------------------------------------------------------------------ what the book says
def test_the_best_five_link_stroke_steps_76_degrees_and_others_are_within_0_032_percent():
    best = CHAIN_OPTIMA[5][0]["efficiency"]
    amp, steps = first_harmonic(chain_stroke(5))
    assert np.all(np.abs(steps - 76) < 1)                     # a uniform step of about 76 degrees
    close = [g for o, g in zip(CHAIN_OPTIMA[5][1:], chain_optima(5)[1:]) if o["efficiency"] > (1 - 3.2e-4) * best]
    assert len(close) == 4
    assert 3.1e-4 < 1 - CHAIN_OPTIMA[5][4]["efficiency"] / best      # the fourth is 0.031 % below
    others = np.abs(np.concatenate([first_harmonic(g)[1] for g in close]))
    assert 71.5 < others.min() < 72.5 and 85.5 < others.max() < 86.5  # their steps: 72 to 86 degrees
    assert CHAIN_OPTIMA[5][5]["efficiency"] < (1 - 2.5e-3) * best     # the next is 0.28 % below


def test_the_best_strokes_mean_body_is_a_slight_s():
    """Averaged over a cycle the joints are bent by the Fourier centre: for the best five-link
    stroke the front two joints one way, the back two the other (an S), by at most 0.22 rad,
    under a quarter of the first harmonic's amplitude. Not every maximum within 0.032 % has it."""
    c = chain_stroke(5).center
    amp, _ = first_harmonic(chain_stroke(5))
    assert np.sign(c[0]) == np.sign(c[1]) == -np.sign(c[2]) == -np.sign(c[3])
    assert 0.2 < np.abs(c).max() < 0.22 and np.abs(c).max() < 0.25 * amp.min()
    s_shaped = [np.sign(g.center[0]) == np.sign(g.center[1]) == -np.sign(g.center[2]) == -np.sign(g.center[3])
                for g in chain_optima(5)[:5]]
    assert s_shaped[0] and not all(s_shaped)
    # three links: the stored stroke bends its two joints opposite ways (an S); the best of the
    # travelling-wave starts, 0.075 % less efficient, bends both the same way (a C)
    c3 = chain_stroke(3).center
    wave = next(k for k, o in enumerate(CHAIN_OPTIMA[3]) if "wave, lag 0.8" in o["starts"])
    cw = chain_optima(3)[wave].center
    assert np.sign(c3[0]) == -np.sign(c3[1]) and np.sign(cw[0]) == np.sign(cw[1])
    assert 7e-4 < 1 - CHAIN_OPTIMA[3][wave]["efficiency"] / CHAIN_STROKES[3]["efficiency"] < 8e-4


def test_a_folded_three_link_stroke_outside_the_named_starts_is_14_percent_better():
    other = OTHER_CHAIN_OPTIMA[3][0]
    gait = FourierGait.from_parameters(other["parameters"], 2, 2)
    s = chain_swimmer(3)
    value, grad, _ = gait_objective(s, gait, "efficiency", intervals=256)
    assert value == pytest.approx(other["efficiency"], abs=1e-10) and np.abs(grad).max() < 1e-9
    assert 1.13 < value / CHAIN_STROKES[3]["efficiency"] < 1.15
    assert not links_cross(s, gait)
    fold = np.abs(gait(np.linspace(0, gait.period, 4096))).max()
    assert 2.9 < fold < 2.95                                          # joints bent up to 167 degrees
    assert other["starts"] == ("random, seed 72",)
    assert efficiency_256(3, refined_end(3, random_start(2, 72))) == pytest.approx(value, rel=1e-7)

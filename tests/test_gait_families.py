"""Gait families (gm_core.systems.gaits): closed loops, exact velocities against finite differences, pacing."""
import numpy as np
import pytest

from gm_core.systems import LowReSwimmer
from gm_core.systems.gaits import GAIT_FAMILIES, ellipse_gait, family_gait, serpenoid_gait
from gm_core.systems.motion import net_displacement
from gm_core.systems.pacing import sine_pacing

T = 1.7
GAITS = [ellipse_gait(0.9, 0.4, 0.6, (0.2, -0.3), T), serpenoid_gait((0.8, 0.5), 0.9, 1, (0.1, 0.0), T),
         serpenoid_gait(1.0, 0.0, 2, (0.0, 0.3), T)] + [
    family_gait(f, 0.7, (0.1, 0.2), 0.6, 0.5, T) for f in GAIT_FAMILIES]


@pytest.mark.parametrize("gait", GAITS, ids=lambda g: g.name)
def test_family_gaits_are_closed_with_derivative_matching_differences(gait):
    assert gait.is_closed()
    t = np.linspace(0.0, T, 37)
    h = 1e-6
    fd = (gait(t + h) - gait(t - h)) / (2 * h)
    np.testing.assert_allclose(gait.velocity(t), fd, atol=1e-7)


def test_ellipse_geometry_semi_axes_and_tilt():
    g = ellipse_gait(2.0, 0.5, np.pi / 6, (1.0, -1.0))
    p = g(np.linspace(0, 1, 4001)) - [1.0, -1.0]
    u = np.array([np.cos(np.pi / 6), np.sin(np.pi / 6)])
    v = np.array([-u[1], u[0]])
    np.testing.assert_allclose((p @ u / 2.0) ** 2 + (p @ v / 0.5) ** 2, 1.0, atol=1e-12)
    assert np.isclose(np.max(p @ u), 2.0, atol=1e-6) and np.isclose(np.max(p @ v), 0.5, atol=1e-6)


def test_figure_eight_lobes_have_opposite_signed_area_and_serpenoid_circle():
    # the lemniscate of Gerono: signed area of the whole loop is zero, each lobe's is not
    g = serpenoid_gait(1.0, 0.0, 2)
    t = np.linspace(0, 1, 20001)
    p, v = g(t), g.velocity(t)
    dA = 0.5 * (p[:, 0] * v[:, 1] - p[:, 1] * v[:, 0])
    half = t <= 0.5
    a1 = np.trapezoid(dA[half], t[half])
    a2 = np.trapezoid(dA[~half], t[~half])
    assert abs(a1 + a2) < 1e-9 and abs(a1) > 0.5
    c = serpenoid_gait(0.7, np.pi / 2, 1)
    np.testing.assert_allclose(np.linalg.norm(c(t), axis=-1), 0.7, atol=1e-12)


def test_sine_pacing_maps_the_period_onto_itself_and_keeps_the_displacement():
    tau, tau_dot = sine_pacing(0.6, 2.0)
    t = np.linspace(0, 2.0, 101)
    assert tau(0.0) == 0.0 and np.isclose(tau(2.0), 2.0)
    assert np.all(np.diff(tau(t)) > 0)
    np.testing.assert_allclose(tau_dot(t[1:-1]), (tau(t[1:-1] + 1e-6) - tau(t[1:-1] - 1e-6)) / 2e-6, atol=1e-8)
    g = ellipse_gait(0.9, 0.5, 0.3, period=2.0)
    sw = LowReSwimmer()
    np.testing.assert_allclose(net_displacement(sw, g.reparameterized(tau, tau_dot)), net_displacement(sw, g),
                               atol=1e-9)


@pytest.mark.parametrize("call, exc", [
    (lambda: ellipse_gait(-1, 1), ValueError), (lambda: ellipse_gait("a", 1), TypeError),
    (lambda: serpenoid_gait(1, frequency=1.5), ValueError), (lambda: family_gait("square", 1), ValueError),
    (lambda: sine_pacing(1.0), ValueError)])
def test_bad_family_input_names_the_argument(call, exc):
    with pytest.raises(exc):
        call()

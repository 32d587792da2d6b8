"""The locomotion lab's panel (notebook 12), headless: what it draws and prints is the math's."""
import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest

from gm_core.drawing.catalog import lab_names, lab_system
from gm_core.geometry.estimates import curvature_grid, displacement_estimates, shaped_gait
from gm_core.systems import SlenderBody, catalog
from gm_core.widgets.catalog import LabPanel

matplotlib.use("agg")


@pytest.fixture(scope="module")
def lab():
    panel = LabPanel()
    yield panel
    plt.close(panel.fig)


def test_the_lab_offers_the_planar_rigid_systems_of_the_catalog():
    names = lab_names()
    assert {"three_link_lowRe", "three_link_granular", "diffdrive", "two_mode_CC"} <= set(names)
    assert "twin_rotor" not in names                                   # on SO(3)
    assert not any(isinstance(catalog.load(n), SlenderBody) for n in names)
    for name in ("five_link_lowRe", "three_link_HighRe"):
        s = lab_system(name)
        assert s.n_shape == 2 and s.shape_limits == catalog.sysplotter_files()[name].grid_range[:2]
    np.testing.assert_allclose(lab_system("five_link_lowRe").connection([0.3, -0.4]),
                               catalog.load("five_link_lowRe").connection([0.3, -0.4, 0.0, 0.0])[:, :2], atol=1e-15)
    with pytest.raises(ValueError, match="name must be one of the lab's systems"):
        lab_system("serpenoid_lowRe")


@pytest.mark.parametrize("name", ["three_link_HighRe", "three_link_granular", "two_mode_CC", "three_link_lowRe"])
def test_switching_systems_draws_that_systems_map_body_and_numbers(lab, name):
    lab.controls["system"].value = name
    lab.controls["row"].value = 2
    lab.controls["c1"].value = 0.2
    scene, system = lab.scene, lab_system(name)
    assert scene.system is system
    F = curvature_grid(system, system.shape_limits, scene.MAP_N)[..., 2]
    shown = scene.map.image.get_array()
    np.testing.assert_array_equal(np.ma.getdata(shown)[~np.ma.getmaskarray(shown)], F[np.isfinite(F)])
    assert scene.map.image.get_extent() == [v for lim in system.shape_limits for v in lim]
    assert len(scene.body.bodies) == len(system.parts())
    half = system.shape_limits[0][1]
    gait = shaped_gait(0.2 * half, 0.0, 0.5 * half, 0.3 * half, 0.78)
    est = displacement_estimates(system, gait, interactive=True)
    np.testing.assert_allclose(scene.estimates.as_array(), est.as_array(), atol=1e-14)
    assert f"{est.as_array()[0, 0]:+.4f}" in lab.numbers.value or abs(est.as_array()[0, 0]) < 5e-5
    r = gait(0.0)
    np.testing.assert_allclose(scene.dot.get_data(), ([r[0]], [r[1]]))


def test_a_singular_gait_is_flagged_not_drawn_as_numbers(lab):
    lab.controls["system"].value = "three_link_kinematic"
    lab.controls["c1"].value, lab.controls["a"].value = 0.0, 0.8
    assert lab.scene.estimates is None and lab.scene.flag.text.get_visible()
    assert "singular" in lab.numbers.value


def test_a_gait_leaving_the_window_is_flagged_but_still_computed(lab):
    lab.controls["system"].value = "three_link_lowRe"
    lab.controls["c1"].value, lab.controls["a"].value = 0.8, 0.9
    assert lab.scene.estimates is not None and lab.scene.flag.text.get_visible()
    assert "leaves" in lab.scene.flag.text.get_text()
    lab.controls["c1"].value, lab.controls["a"].value = 0.0, 0.5
    assert not lab.scene.flag.text.get_visible()

"""The locomotion lab's panel (notebook 12), headless: what it draws and prints is the math's."""
import importlib.util
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest

from gm_core.drawing.catalog import RotorDials, lab_gait, lab_names, lab_system
from gm_core.geometry.curvature import constraint_curvature
from gm_core.geometry.estimates import curvature_grid, displacement_estimates, shaped_gait
from gm_core.groups import SO3
from gm_core.systems import catalog
from gm_core.systems.motion import curvature_form, fd_connection_derivative, net_displacement
from gm_core.systems.tabulated import TabulatedConnection
from gm_core.widgets.catalog import LabPanel

matplotlib.use("agg")


@pytest.fixture(scope="module")
def lab():
    panel = LabPanel()
    yield panel
    plt.close(panel.fig)


def test_the_lab_offers_every_system_of_the_catalog():
    names = lab_names()
    assert names == catalog.names() and len(names) == 41
    for name in ("five_link_lowRe", "three_link_HighRe"):
        s = lab_system(name)
        assert s.n_shape == 2 and s.shape_limits == catalog.sysplotter_files()[name].grid_range[:2]
    np.testing.assert_allclose(lab_system("five_link_lowRe").connection([0.3, -0.4]),
                               catalog.load("five_link_lowRe").connection([0.3, -0.4, 0.0, 0.0])[:, :2], atol=1e-15)
    assert isinstance(lab_system("serpenoid_lowRe"), TabulatedConnection)
    assert not isinstance(lab_system("three_link_lowRe"), TabulatedConnection)
    with pytest.raises(ValueError, match="name must be one of the lab's systems"):
        lab_system("serpenoid_highRe")


def test_the_asymmetric_tape_measures_slice_holds_its_length_at_the_windows_edge():
    window = catalog.sysplotter_files()["asymmetricTapeMeasure"].grid_range
    s = catalog.window_slice("asymmetricTapeMeasure")
    np.testing.assert_allclose(s.full_shape([0.2, 0.3]), [0.2, 0.3, window[2][0]], atol=0)
    np.testing.assert_allclose(s.connection([0.2, 0.3]),
                               catalog.load("asymmetricTapeMeasure").connection([0.2, 0.3, window[2][0]])[:, :2], atol=1e-15)


def test_twin_rotors_slice_keeps_so3_and_its_numbers_use_so3s_bracket():
    s = lab_system("twin_rotor")
    assert s.position_group is SO3
    r = np.array([[0.3, -0.7], [1.1, 0.4]])
    base = catalog.load("twin_rotor")
    F = curvature_form(*fd_connection_derivative(base, r), group=SO3)[..., 0, 1]
    np.testing.assert_allclose(constraint_curvature(s, r), F, atol=1e-8)
    gait = lab_gait(s, 0.2, 0.0, 0.5, 0.3, 0.78)
    est = displacement_estimates(s, gait, interactive=True)
    np.testing.assert_allclose(est.exact, net_displacement(base, gait, steps=2000), atol=1e-6)


def test_a_gait_in_a_window_off_the_origin_is_scaled_to_it():
    s = lab_system("symmetricTapeMeasure")
    (lo1, hi1), (lo2, hi2) = s.shape_limits
    gait = lab_gait(s, 0.0, 0.0, 0.5, 0.5, 0.0)
    p = gait(np.linspace(0, gait.period, 400, endpoint=False))
    np.testing.assert_allclose(p.mean(axis=0), [(lo1 + hi1) / 2, (lo2 + hi2) / 2], atol=1e-12)
    np.testing.assert_allclose(np.ptp(p, axis=0), [(hi1 - lo1) / 2, (hi2 - lo2) / 2], rtol=1e-4)
    square = lab_system("three_link_lowRe")
    half = square.shape_limits[0][1]
    g1, g2 = lab_gait(square, 0.2, -0.1, 0.5, 0.3, 0.78), shaped_gait(0.2 * half, -0.1 * half, 0.5 * half, 0.3 * half, 0.78)
    np.testing.assert_array_equal(g1(np.linspace(0, 1, 9)), g2(np.linspace(0, 1, 9)))


@pytest.mark.parametrize("name", catalog.tabulated_names())
def test_a_stored_table_agrees_with_the_live_system(name):
    tab, live = catalog.tabulated(name), catalog.window_slice(name)
    assert tab.shape_limits == catalog.sysplotter_files()[name].grid_range[:2] and tab.body is not None
    rng = np.random.default_rng(7)
    (lo1, hi1), (lo2, hi2) = tab.shape_limits
    r = np.column_stack([rng.uniform(lo1, hi1, 6), rng.uniform(lo2, hi2, 6)])
    r = r[np.hypot(*r.T) > catalog.TABLE_EXCLUDED.get(name, -1.0)][:3]
    A = live.connection(r)
    scale = np.abs(tab.table).max()
    assert np.abs(tab.connection(r) - A).max() <= catalog.TABLE_RTOL * scale
    assert tab.is_singular([hi1 + 0.01, lo2]) and not tab.is_singular(r).any()


def test_a_stored_table_is_what_the_tool_writes():
    path = Path(__file__).resolve().parents[1] / "tools" / "lab_tables.py"
    spec = importlib.util.spec_from_file_location("lab_tables", path)
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    assert set(tool.DEFAULT) == set(catalog.tabulated_names())
    name = "asymmetricTapeMeasure"                     # the cheapest: a few milliseconds
    fresh, tab = tool.table(name), catalog.tabulated(name)
    np.testing.assert_array_equal(fresh[f"{name}/alpha1"], tab.axes[0])
    np.testing.assert_array_equal(fresh[f"{name}/alpha2"], tab.axes[1])
    np.testing.assert_allclose(fresh[name], tab.table, rtol=1e-6, atol=1e-7 * np.abs(tab.table).max())
    assert tool.table_error(name, fresh) <= catalog.TABLE_RTOL


def test_tabulated_refuses_names_without_a_table():
    with pytest.raises(ValueError, match="has no stored table"):
        catalog.tabulated("three_link_lowRe")
    with pytest.raises(ValueError, match="has no stored table"):
        catalog.tabulated("serpenoid")
    with pytest.raises(TypeError, match="name must be"):
        catalog.tabulated(3)


def test_every_system_can_be_selected_and_redraws_a_gait_change():
    panel = LabPanel()
    try:
        for name in lab_names():
            panel.controls["system"].value = name
            scene = panel.scene
            assert scene.system is lab_system(name) and scene.axb.get_title().startswith(name)
            assert len(scene.body.bodies) == len(scene.system.parts())
            before = scene.gait_artist.points.copy()
            panel.controls["c2"].value = 0.1 if panel.controls["c2"].value != 0.1 else -0.1
            assert not np.allclose(scene.gait_artist.points, before)
            assert scene.estimates is not None or scene.flag.text.get_visible()
            panel.fig.canvas.draw()
        assert isinstance(panel.scene.body, RotorDials) or lab_names()[-1] != "twin_rotor"
    finally:
        plt.close(panel.fig)


def test_twin_rotor_is_drawn_as_its_frame_and_rotor_dials():
    lab = LabPanel()
    lab.controls["system"].value = "twin_rotor"
    lab.controls["phase"].value = 0.25
    scene, dials = lab.scene, lab.scene.body
    assert isinstance(dials, RotorDials) and scene.estimates is not None
    assert "ωz" in lab.numbers.value and "ωx" in scene.ax.get_title()
    r = scene.dot.get_data()
    x, y = dials.dials[0].get_data()
    np.testing.assert_allclose(np.arctan2(y[1], x[1]), np.arctan2(np.sin(r[0][0]), np.cos(r[0][0])), atol=1e-12)
    lab.controls["system"].value = "three_link_lowRe"
    assert not isinstance(scene.body, RotorDials) and not dials.note.get_visible() and not dials.dials[0].get_visible()
    assert all(p.patch.get_visible() for p in scene.body.bodies)
    plt.close(lab.fig)


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
    gait = lab_gait(system, 0.2, 0.0, 0.5, 0.3, 0.78)
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

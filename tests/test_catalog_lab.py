"""The locomotion lab's panel (notebook 12), headless: what it draws and prints is the math's."""
import importlib.util
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest

from gm_core.drawing.catalog import LabScene, RotorDials, add_lab_system, lab_gait, lab_names, lab_system
from gm_core.drawing.toolkit.primitives import jshtml
from gm_core.geometry import constraint_curvature, minimum_perturbation_coordinates
from gm_core.geometry.estimates import curvature_grid, displacement_estimates, shaped_gait, square_grid
from gm_core.groups import SO3
from gm_core.systems import LowReSwimmer, catalog, shape_slice
from gm_core.systems.gaits import Gait
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
    assert names[:41] == catalog.names() and len(catalog.names()) == 41   # then any a user added
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
    lab.controls["row"].value = 2
    assert [label for label, _ in lab.controls["row"].options] == ["ωx", "ωy", "ωz"]
    assert "ωz" in scene.ax.get_title() and lab.controls["row"].value == 2
    r = scene.dot.get_data()
    x, y = dials.dials[0].get_data()
    np.testing.assert_allclose(np.arctan2(y[1], x[1]), np.arctan2(np.sin(r[0][0]), np.cos(r[0][0])), atol=1e-12)
    lab.controls["system"].value = "three_link_lowRe"
    assert [label for label, _ in lab.controls["row"].options] == ["x", "y", "θ"]
    assert lab.controls["row"].value == 2 and "θ" in scene.ax.get_title()
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


# -- the body frame ------------------------------------------------------------------------------

def test_the_frame_control_shows_maps_field_and_numbers_in_the_minimum_perturbation_frame(lab):
    """Untouched, the lab is in the file's frame; "minimum perturbation" shows the map, the field and
    the numbers of minimum_perturbation_coordinates over the file's window (fitted again here)."""
    lab.set(system="three_link_lowRe", frame="file's frame", row=0, c1=0.2, c2=0.0, a=0.5, b=0.3, tilt=0.78)
    system = lab_system("three_link_lowRe")
    half = system.shape_limits[0][1]
    gait = shaped_gait(0.2 * half, 0.0, 0.5 * half, 0.3 * half, 0.78)
    given = displacement_estimates(system, gait, interactive=True).as_array()
    assert lab.scene.view is system
    np.testing.assert_allclose(lab.scene.estimates.as_array(), given, atol=1e-14)
    lab.controls["frame"].value = "minimum perturbation"
    mp = minimum_perturbation_coordinates(system, system.shape_limits)
    want = displacement_estimates(mp, gait, interactive=True).as_array()
    np.testing.assert_allclose(lab.scene.estimates.as_array(), want, atol=1e-12)
    assert abs(want[0, 0] - given[0, 0]) > 1e-3 and abs(want[0, 2] - given[0, 2]) < 1e-12   # x moves, θ does not
    assert f"{want[0, 0]:+.4f}" in lab.numbers.value
    shown = lab.scene.map.image.get_array()
    F = constraint_curvature(mp, square_grid(system.shape_limits, lab.scene.MAP_N))[..., 0]
    np.testing.assert_allclose(np.ma.getdata(shown)[~np.ma.getmaskarray(shown)], F[np.isfinite(F)], atol=1e-12)
    q = lab.scene.field.quiver                        # the arrows point along -A of that frame
    arrows, minus_A = np.column_stack([q.U, q.V]), -mp.connection(q.get_offsets())[:, 0, :]
    cross = arrows[:, 0] * minus_A[:, 1] - arrows[:, 1] * minus_A[:, 0]
    assert np.all(np.abs(cross) <= 1e-9 * np.abs(minus_A).max() * np.abs(arrows).max())
    assert np.all(np.einsum("ij,ij->i", arrows, minus_A) >= 0) and np.abs(arrows).max() > 0
    for part, pose in zip(lab.scene.body.bodies, mp.part_poses(gait(0.0))):     # the body in that frame
        np.testing.assert_allclose(part.g, pose, atol=1e-12)
    lab.controls["frame"].value = "file's frame"
    np.testing.assert_allclose(lab.scene.estimates.as_array(), given, atol=1e-14)


def test_a_frame_that_cannot_be_solved_is_said_and_a_wrong_frame_is_refused(lab):
    lab.set(system="three_link_kinematic", frame="minimum perturbation", c1=0.0, c2=0.0, a=0.3, b=0.3)
    assert lab.scene.view is lab_system("three_link_kinematic")         # singular shapes in its window
    assert lab.scene.flag.text.get_visible() and "minimum-perturbation" in lab.scene.flag.text.get_text()
    assert "no minimum-perturbation frame" in lab.numbers.value
    with pytest.raises(ValueError, match="frame must be one of"):
        lab.scene.set(system="three_link_lowRe", frame="centre of mass")
    lab.set(system="three_link_lowRe", frame="file's frame")


# -- a drawn gait ---------------------------------------------------------------------------------

def _click(panel, x, y, ax=None):
    """What a mouse click at data point (x, y) of ``ax`` (default the map) sends to the figure."""
    from matplotlib.backend_bases import MouseEvent

    ax = ax or panel.scene.ax
    px, py = ax.transData.transform((x, y))
    event = MouseEvent("button_press_event", panel.fig.canvas, px, py, button=1)
    panel.fig.canvas.callbacks.process("button_press_event", event)


def test_clicks_on_the_map_draw_a_spline_gait_whose_numbers_are_that_splines(lab):
    lab.set(system="three_link_HighRe", frame="file's frame", row=0, c1=0.0, c2=0.0, a=0.5, b=0.3, tilt=0.78)
    lab.clear_gait()
    before = lab.scene.estimates.as_array()
    _click(lab, 0.5, 0.5)                           # "draw gait" is up: a click does nothing
    assert lab.scene.points == [] and lab.scene.custom is None
    lab.draw.value = True
    pts = [(-1.0, -0.8), (1.1, -0.9), (0.9, 1.2), (-1.2, 0.7)]
    for p in pts[:2]:
        _click(lab, *p)
    assert "3 or more" in lab.status.value and lab.scene.custom is None        # two points: no gait yet
    np.testing.assert_allclose(lab.scene.estimates.as_array(), before)
    _click(lab, 0.0, 0.0, ax=lab.scene.axb)          # a click on the body's axes is no point of the gait
    for p in pts[2:]:
        _click(lab, *p)
    np.testing.assert_allclose(lab.scene.points, pts, atol=1e-9)
    spline = Gait.from_samples(np.array(lab.scene.points), 1.0)
    want = displacement_estimates(lab_system("three_link_HighRe"), spline, interactive=True)
    np.testing.assert_allclose(lab.scene.estimates.as_array(), want.as_array(), atol=1e-13)
    np.testing.assert_allclose(lab.scene.gait_artist.points, spline(np.linspace(0, 1, 201)), atol=1e-12)
    np.testing.assert_allclose(np.transpose(lab.scene.clicks.get_data()), pts, atol=1e-9)
    assert "4 points" in lab.status.value and f"{want.exact[0]:+.4f}" in lab.numbers.value
    lab.controls["row"].value = 2                    # another row keeps the drawn gait
    np.testing.assert_allclose(lab.scene.estimates.as_array(), want.as_array(), atol=1e-13)
    lab.clear.click()                                # "clear": the sliders' gait again
    lab.draw.value = False
    assert lab.scene.points == [] and lab.status.value == ""
    np.testing.assert_allclose(lab.scene.estimates.as_array(), before)


def test_moving_a_gait_slider_lets_a_drawn_gait_go(lab):
    lab.set(system="three_link_lowRe", c1=0.0, a=0.5)
    lab.clear_gait()
    before = lab.scene.estimates.as_array()
    for p in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0)]:
        lab.add_point(*p)
    assert lab.scene.custom is not None
    lab.controls["c1"].value = 0.1
    assert lab.scene.custom is None and lab.scene.points == []
    lab.controls["c1"].value = 0.0
    np.testing.assert_allclose(lab.scene.estimates.as_array(), before, atol=1e-14)


# -- a loaded gait --------------------------------------------------------------------------------

def test_a_gait_loaded_from_a_code_cell_is_shown_with_its_numbers(lab):
    lab.set(system="three_link_lowRe", frame="file's frame", c1=0.0, a=0.5)
    system = lab_system("three_link_lowRe")
    t = np.linspace(0.0, 1.0, 12, endpoint=False)
    pts = np.stack([1.2 * np.cos(2 * np.pi * t), 0.8 * np.sin(2 * np.pi * t) + 0.3 * np.cos(4 * np.pi * t)], -1)
    lab.load_gait(pts)
    want = displacement_estimates(system, Gait.from_samples(pts, 1.0), interactive=True)
    np.testing.assert_allclose(lab.scene.estimates.as_array(), want.as_array(), atol=1e-13)
    assert "loaded" in lab.status.value

    def loop(s):
        return np.stack([np.cos(s), np.sin(s)], -1)

    lab.load_gait(loop, period=2 * np.pi)
    want = displacement_estimates(system, Gait(loop, 2 * np.pi), interactive=True)
    np.testing.assert_allclose(lab.scene.estimates.as_array(), want.as_array(), atol=1e-13)
    np.testing.assert_allclose(lab.scene.gait_artist.points[0], [1.0, 0.0], atol=1e-15)


@pytest.mark.parametrize("bad, match", [
    (np.zeros((5, 3)), "gait must be shapes"),
    ([[0.0, 0.0], [1.0, 0.0]], "at least 3|K >= 3"),
    ("circle", "gait must be"),
    (lambda s: np.stack([s, np.zeros_like(s)], -1), "not closed"),
    (lambda s: np.stack([np.cos(s), np.sin(s), 0 * s], -1), "2 shape variables"),
])
def test_a_wrong_gait_is_refused_naming_it_and_the_shown_gait_stays(lab, bad, match):
    lab.set(system="three_link_lowRe", c1=0.0, a=0.5)
    lab.clear_gait()
    before = lab.scene.estimates.as_array()
    with pytest.raises(ValueError, match=match):
        lab.load_gait(bad, period=2 * np.pi)
    assert lab.scene.custom is None
    np.testing.assert_allclose(lab.scene.estimates.as_array(), before)


# -- optimise -------------------------------------------------------------------------------------

def test_optimise_shows_the_optimum_and_says_done_only_after_drawing_it():
    panel = LabPanel()
    try:
        panel.set(system="three_link_HighRe", frame="minimum perturbation")
        events = []
        panel.fig.canvas.mpl_connect("draw_event", lambda e: events.append(("draw", panel.status.value)))
        panel.status.observe(lambda ch: events.append(("status", ch["new"])), names="value")
        start = panel.scene.estimates.as_array()
        res = panel.run("speed")
        done = next(i for i, e in enumerate(events) if e[0] == "status" and e[1].startswith("done"))
        drawn = [i for i, e in enumerate(events) if e[0] == "draw"]
        assert drawn and drawn[-1] < done and events[drawn[-1]][1] == "drawing the best gait …"
        assert panel.scene.gait is res.gait and res.nit <= LabScene.OPT_MAXITER
        np.testing.assert_allclose(panel.scene.gait_artist.points, res.gait(np.linspace(0, res.gait.period, 201)))
        view = minimum_perturbation_coordinates(lab_system("three_link_HighRe"), lab_system("three_link_HighRe").shape_limits)
        est = displacement_estimates(view, res.gait, interactive=True).as_array()
        np.testing.assert_allclose(panel.scene.estimates.as_array(), est, atol=1e-12)
        assert np.hypot(*est[0, :2]) > 1.2 * np.hypot(*start[0, :2])        # it goes further than the start
        assert f"{res.displacement:.4f}" in panel.status.value
        page = panel.animation(n_frames=4, cycles=1).data                   # the course's player
        assert 'class="gm-anim-play"' in page and 'data-frames="4"' in page
        anim, fig, traj = panel.scene.animation(n_frames=5, cycles=1)
        assert "<img" in jshtml(anim).data                                 # rendered (and closed)
        np.testing.assert_allclose(traj.r, res.gait(traj.t), atol=1e-12)    # the body runs the optimum
    finally:
        plt.close(panel.fig)


def test_optimise_says_why_it_cannot_run(lab):
    lab.set(system="diffdrive", frame="file's frame")
    assert lab.run("efficiency") is None
    assert "cannot optimise" in lab.status.value and "metric" in lab.status.value
    assert lab.run("fastest") is None and "objective must be one of" in lab.status.value
    assert not lab.button.disabled and lab.scene.custom is None
    lab.set(system="three_link_lowRe")


# -- size and speed -------------------------------------------------------------------------------

def test_the_lab_fits_a_laptop_screen_with_all_its_controls(lab):
    """At 1366 x 768 with the file browser open (issue 19): the figure at most 900 x 340 px, its
    nine controls in three rows of three above it (each 268 px of the 920 px output area), and one
    row of buttons and status under the table: under 650 px in all."""
    import ipywidgets as W

    w, h = lab.fig.get_size_inches() * lab.fig.dpi
    assert w <= 900 and h <= 340
    per_row = (lab.OUTPUT_WIDTH + 16) // (lab.CONTROL_WIDTH + 8 + 16)
    rows = -(-len(lab.controls) // per_row)
    assert w + lab.CONTROL_WIDTH + 24 > lab.OUTPUT_WIDTH and rows <= 3       # rows above the figure
    tree, todo = [], [lab.widget]
    while todo:
        widget = todo.pop()
        tree.append(widget)
        todo += list(getattr(widget, "children", ()))
    assert {id(x) for x in (lab.draw, lab.clear, lab.objective, lab.button, lab.status)} <= {id(x) for x in tree}
    assert sum(isinstance(x, W.Output) for x in tree) <= 1                  # no player inside the panel
    assert rows * 52 + h + 4 * 20 + 34 + 24 <= 650     # controls, figure, table, buttons, title


def test_the_minimum_perturbation_frame_is_refused_in_so3_and_drawn_off_a_singular_straight_shape():
    panel = LabPanel()
    try:
        panel.controls["system"].value = "twin_rotor"
        panel.controls["frame"].value = "minimum perturbation"
        scene = panel.scene
        assert scene.view is scene.system and "SO(3)" in scene.frame_error and scene.estimates is not None
        panel.controls["system"].value = "triangle_lowRe"              # its body is undefined at the straight shape
        assert scene.view is not scene.system and scene.frame_error == ""
        assert len(scene.body.bodies) == len(scene.system.parts()) and scene.estimates is not None
    finally:
        plt.close(panel.fig)


def test_a_system_of_your_own_joins_the_dropdown_with_its_own_window_and_numbers(lab):
    mine = LowReSwimmer((1.0, 1.5, 1.0), drag_ratio=3.0)
    assert lab.add_system(mine, "my swimmer") == "my swimmer"
    assert lab.controls["system"].options[-1] == "my swimmer" and lab.controls["system"].value == "my swimmer"
    assert lab_system("my swimmer") is mine and lab.scene.system is mine
    assert lab.add_system(mine, "my swimmer") == "my swimmer"            # the same system again: nothing new
    assert list(lab.controls["system"].options).count("my swimmer") == 1
    lab.controls["c1"].value = 0.1
    gait = lab_gait(mine, 0.1, 0.0, 0.5, 0.3, 0.78)
    assert lab.scene.map.image.get_extent() == [v for lim in mine.shape_limits for v in lim]
    want = displacement_estimates(mine, gait, interactive=True)
    np.testing.assert_allclose(lab.scene.estimates.as_array(), want.as_array(), atol=1e-14)
    lab.controls["system"].value = "three_link_lowRe"
    lab.controls["system"].value = "my swimmer"                           # and back, from the dropdown
    assert lab.scene.system is mine


@pytest.mark.parametrize("system, name, error, match", [
    ("a swimmer", None, TypeError, "system must be a locomotion system"),
    (LowReSwimmer(), "", TypeError, "name must be a non-empty string"),
    (LowReSwimmer(), "three_link_lowRe", ValueError, "taken .by the catalog"),
    (catalog.load("four_link_lowRe"), "four", ValueError, "two shape variables.*shape_slice"),
])
def test_a_system_of_your_own_is_refused_with_a_reason(system, name, error, match):
    with pytest.raises(error, match=match):
        add_lab_system(system, name)
    assert lab_names().count(name) == (name in catalog.names())          # nothing added


def test_a_name_is_given_once_and_a_slice_of_a_bigger_system_is_welcome():
    four = catalog.load("four_link_lowRe")
    sliced = shape_slice(four)
    assert add_lab_system(sliced, "four, joints 1-2") == "four, joints 1-2"
    with pytest.raises(ValueError, match="taken .by another system"):
        add_lab_system(LowReSwimmer(), "four, joints 1-2")
    assert lab_system("four, joints 1-2") is sliced

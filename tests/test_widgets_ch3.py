"""Headless (Agg) tests of the chapter-3 panels: set controls, check the artists moved as gm_core says."""
import os

import matplotlib

matplotlib.use("Agg")
os.environ.setdefault("GM_COURSE_TESTING", "1")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from gm_core import SE2  # noqa: E402
from gm_core.drawing import rolling_disk as D_nh  # noqa: E402
from gm_core.drawing.connection import connection_fields_figure, regimes_figure, shape_grid
from gm_core.drawing.gaits import animate_gait
from gm_core.systems import ALL_SYSTEMS, FloatingSnake, HighReSwimmer, KinematicSnake, LowReSwimmer  # noqa: E402
from gm_core.systems.gaits import circle_gait
from gm_core.systems.motion import net_displacement
from gm_core.widgets import connection, gaits, motion, pacing, rolling_disk  # noqa: E402
from gm_core.widgets.base import PANELS, all_panels  # noqa: E402
from gm_core.widgets.connection import ConnectionFieldPanel
from gm_core.widgets.gaits import GaitPanel
from gm_core.widgets.motion import AckermanCarPanel, DiffDriveCarPanel
from gm_core.widgets.pacing import DirectionalLinearityPanel, PacingSquarePanel
from gm_core.widgets.rolling_disk import ParallelParkPanel

CH3_PANELS = [name for name, cls in all_panels().items()
              if cls.__module__ in {m.__name__ for m in (motion, connection, gaits, rolling_disk, pacing)}]


def outlines_at(system, g, r):
    poses = SE2.compose(np.asarray(g, float), system.part_poses(np.asarray(r, float)))
    return [SE2.act_on_points(pose, p.outline) for p, pose in zip(system.parts(), poses)]


def assert_body_at(art, system, g, r, atol=1e-9):
    for got, want in zip(art.world_outlines(), outlines_at(system, g, r)):
        np.testing.assert_allclose(got[: len(want)], want, atol=atol)


def test_ch3_panels_registered():
    assert {"DiffDriveCarPanel", "AckermanCarPanel", "ConnectionFieldPanel", "GaitPanel",
            "ParallelParkPanel", "PacingSquarePanel", "DirectionalLinearityPanel"} <= set(CH3_PANELS)


@pytest.mark.parametrize("name", CH3_PANELS)
def test_update_keeps_figure_and_naive_update_runs(name):
    p = PANELS[name]()
    fig = p.fig
    n_children = [len(ax.get_children()) for ax in fig.axes]
    rng = np.random.default_rng(1)
    for _ in range(2):
        p.update(**p.sample_values(rng))
    assert p.fig is fig
    assert [len(ax.get_children()) for ax in fig.axes] == n_children  # moved in place, nothing added
    p.naive_update(**p.values())


def test_diff_drive_car_follows_the_exponential():
    p = DiffDriveCarPanel()
    p.set(wheel1_speed=1.0, wheel2_speed=2.5, duration=2.0)
    s = p.system
    xi = s.body_velocity([0, 0], [1.0, 2.5])
    R, w = s.wheel_radius, s.half_width
    np.testing.assert_allclose(xi, [R / 2 * 3.5, 0.0, R / (2 * w) * 1.5])  # (3.29)
    g_end = SE2.exp(2.0 * xi)  # constant body velocity: g(T) = exp(T xi)
    np.testing.assert_allclose(p.traj.g[-1], g_end, atol=1e-9)
    assert_body_at(p.body, s, g_end, p.traj.r[-1])
    trail = np.column_stack(p.trail.line.get_data())
    np.testing.assert_allclose(trail[-1], g_end[:2], atol=1e-9)
    np.testing.assert_allclose(trail[len(trail) // 2], SE2.exp(1.0 * xi)[:2], atol=1e-9)
    np.testing.assert_allclose(p.vel.world_vector(), SE2.body_to_world(g_end, xi)[:2], atol=1e-9)
    # equal wheel speeds: straight line along x
    p.set(wheel1_speed=1.0, wheel2_speed=1.0)
    np.testing.assert_allclose(np.column_stack(p.trail.line.get_data())[:, 1], 0, atol=1e-12)


def test_ackerman_car_constant_steering_is_a_circle_and_singular_flag():
    p = AckermanCarPanel()
    p.set(wheel_speed=2.0, steering=0.4, steering_speed=0.0, duration=3.0)
    s = p.system
    xi = s.body_velocity([0, 0.4], [2.0, 0.0])
    np.testing.assert_allclose(p.traj.g[-1], SE2.exp(3.0 * xi), atol=1e-9)
    assert_body_at(p.body, s, SE2.exp(3.0 * xi), [6.0, 0.4])
    # turning radius L / tan(steer) about the centre (0, L / tan(steer))
    pts = np.column_stack(p.trail.line.get_data())
    rho = s.wheelbase / np.tan(0.4)
    np.testing.assert_allclose(np.hypot(pts[:, 0], pts[:, 1] - rho), rho, atol=1e-9)
    assert not p.flag.visible
    # steering through 90 degrees is singular: flag shown, body and trail hidden
    p.set(steering=1.3, steering_speed=1.0, duration=3.0)
    assert p.flag.visible and "singular" in p.message
    assert not p.trail.line.get_visible() and not p.body.bodies[0].patch.get_visible()
    p.set(steering=0.0, steering_speed=0.0)
    assert not p.flag.visible and p.trail.line.get_visible()


@pytest.mark.parametrize("system", [KinematicSnake(), FloatingSnake(), LowReSwimmer(), HighReSwimmer()],
                         ids=lambda s: type(s).__name__)
def test_connection_field_panel_cursor_body_and_velocity(system):
    p = ConnectionFieldPanel(system=system)
    r, rd = np.array([1.1, -0.7]), np.array([0.4, -0.9])
    p.set(alpha1=r[0], alpha2=r[1], alpha1_dot=rd[0], alpha2_dot=rd[1])
    for c in p.cursors:
        np.testing.assert_allclose(np.ravel(c.marker.get_data()), r)
    assert_body_at(p.body, system, np.zeros(3), r)
    xi = -system.connection(r) @ rd
    np.testing.assert_allclose(p.xi, xi, atol=1e-12)
    np.testing.assert_allclose(p.vel.world_vector(), xi[:2] * p.vel.scale, atol=1e-12)
    # the quivers show -A^i on the grid (times the display factor, where not clipped)
    for i, f in enumerate(p.fields):
        a1, a2, rg = shape_grid(system, f.n, f.grid_limits)
        A = system.connection(rg)
        U = np.ma.masked_invalid(-A[..., i, 0]).ravel()
        keep = ~np.ma.getmaskarray(U) & ~f.clipped.ravel()
        np.testing.assert_allclose(np.ma.filled(f.quiver.U, np.nan)[keep], (U * f.factor)[keep], atol=1e-12)


def test_connection_field_panel_singular_line_of_kinematic_snake():
    p = ConnectionFieldPanel(system=KinematicSnake())
    p.set(alpha1=0.5, alpha2=0.5)
    assert p.flag.visible
    assert not p.vel.quiver.get_visible()
    assert np.all(np.isnan(p.xi))
    # masked (never NaN) arrows on the diagonal of the grid
    f = p.fields[0]
    assert np.asarray(f.quiver.Umask).any()  # matplotlib keeps the mask, fills U with 1 there
    assert np.all(np.isfinite(f.quiver.U)) and np.all(np.isfinite(f.quiver.V))
    # the red singular curve is drawn on every field
    for ax in p.field_axes:
        assert any(type(c).__name__ in ("QuadContourSet", "ContourSet") for c in ax.get_children())
    p.set(alpha2=-0.5)
    assert not p.flag.visible and p.vel.quiver.get_visible()


def test_gait_panel_motion_matches_net_displacement():
    p = GaitPanel(system=LowReSwimmer())
    p.set(amplitude=1.2, center1=0.2, center2=-0.3)
    g = net_displacement(p.system, circle_gait(1.2, (0.2, -0.3)))
    np.testing.assert_allclose(p.net, g, atol=1e-8)
    assert_body_at(p.body, p.system, p.traj.g[-1], p.traj.r[-1])
    np.testing.assert_allclose(np.column_stack(p.trail.line.get_data())[-1], g[:2], atol=1e-8)
    path = np.column_stack(p.paths[2][0].get_data())
    np.testing.assert_allclose(path[0], [1.4, -0.3], atol=1e-12)


def test_gait_panel_singular_gait_flags():
    p = GaitPanel(system=KinematicSnake())
    p.set(amplitude=1.0, center1=0.0, center2=0.0)
    assert p.flag.visible and "singular" in p.message
    assert not p.trail.line.get_visible()
    p.set(amplitude=0.8, center1=0.4, center2=-1.0)
    assert not p.flag.visible
    np.testing.assert_allclose(p.net, net_displacement(p.system, circle_gait(0.8, (0.4, -1.0))), atol=1e-8)


def test_static_figures_and_animation():
    fig, axes, arts = connection_fields_figure(KinematicSnake(), n=9)
    assert len(arts) == 3
    fig2, axes2 = regimes_figure([ALL_SYSTEMS[k] for k in ("KinematicSnake", "LowReSwimmer")], n=7)
    assert axes2.shape == (2, 3)
    anim, fig3, traj = animate_gait(LowReSwimmer(), circle_gait(1.0), n_frames=12)
    assert traj.g.shape == (12, 3)
    from gm_core.drawing.toolkit.primitives import jshtml
    html = jshtml(anim)  # plays without a kernel; shortened under the test flag
    assert "<script" in html.data
    import matplotlib.pyplot as plt
    plt.close("all")


def test_zero_note_never_covers_a_singular_line():
    """Issue 36: notebook 09's "≡ 0" box sat on the kinematic snake's singular line on the
    window's top edge. In the regimes figure every shown note's box, as drawn, crosses no
    singular line (the red contour of draw_singular_set) and stays inside its axes."""
    from matplotlib.contour import ContourSet

    systems = [KinematicSnake(), FloatingSnake(), LowReSwimmer(), HighReSwimmer()]
    fig, axes = regimes_figure(systems)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    shown = 0
    for k, s in enumerate(systems):
        for i in range(3):
            ax = axes[k, i]
            notes = [t for t in ax.texts if t.get_visible() and t.get_text().startswith("≡ 0")]
            lines = [path.transformed(c.get_transform()) for c in ax.collections if isinstance(c, ContourSet)
                     for path in c.get_paths() if len(path.vertices)]
            for note in notes:
                shown += 1
                box = note.get_bbox_patch().get_window_extent(renderer)
                assert ax.get_window_extent(renderer).contains(box.x0, box.y0) and \
                    ax.get_window_extent(renderer).contains(box.x1, box.y1), f"{s.name} row {i}: note outside"
                assert not any(line.intersects_bbox(box, filled=False) for line in lines), \
                    f"{s.name} row {i}: the ≡ 0 note covers a singular line"
    assert shown == 3       # the snake's sideways row and the floating snake's two translation rows
    import matplotlib.pyplot as plt
    plt.close("all")


def test_singular_set_of_the_snake_includes_the_fold_lines_on_the_window_edge():
    # D = 4 sin((a1 - a2)/2) cos(a1/2) cos(a2/2) for equal links: zero on a1 = a2 and on a_i = +-pi
    import matplotlib.pyplot as plt

    from gm_core.drawing.connection import draw_singular_set

    snake = KinematicSnake()
    fig, ax = plt.subplots()
    cs = draw_singular_set(ax, snake)
    pts = np.vstack([p.vertices for p in cs.get_paths() if len(p.vertices)])
    on_diag = np.abs(pts[:, 0] - pts[:, 1]) < 1e-6
    assert on_diag.any()
    for k in (0, 1):
        for edge in (-np.pi, np.pi):
            near = np.abs(pts[:, k] - edge) < 0.02
            # the fold line runs along the whole edge, not just a corner
            assert np.ptp(pts[near, 1 - k]) > 5.5, (k, edge)
    # and every vertex drawn is singular: D is (nearly) zero there
    d = snake.singularity(pts)
    assert np.max(np.abs(d)) < 0.05
    plt.close(fig)


# ------------------------------------------------------------------------- gaits for every system
@pytest.fixture(scope="module", params=sorted(ALL_SYSTEMS))
def gait_panel(request):
    """``(name, GaitPanel)``: one panel per system, shared by the three families below (each test
    sets every control the family reads), closed after them."""
    import matplotlib.pyplot as plt

    p = GaitPanel(system=ALL_SYSTEMS[request.param])
    p.fig.gm_keep_open = True     # not closed by conftest's _close_figures between the tests
    yield request.param, p
    plt.close(p.fig)


@pytest.mark.parametrize("family", ["ellipse", "serpenoid", "figure eight"])
def test_gait_panel_families_for_every_system(gait_panel, family):
    from gm_core import SingularShapeError
    from gm_core.systems.gaits import family_gait

    name, p = gait_panel
    system = ALL_SYSTEMS[name]
    (lo1, hi1), (lo2, hi2) = system.shape_limits
    c = (0.1 * hi1, -0.3 * hi2) if name != "KinematicSnake" else (0.5, -1.2)
    size = 0.25 * min(hi1 - lo1, hi2 - lo2) if name != "KinematicSnake" else 0.6
    p.set(family=family, amplitude=size, center1=c[0], center2=c[1], aspect=0.5, angle=0.4)
    gait = family_gait(family, size, c, 0.5, 0.4)
    path = np.column_stack(p.paths[0][0].get_data())
    np.testing.assert_allclose(path, gait(np.linspace(0, 1, len(path))), atol=1e-12)
    try:
        g = net_displacement(p.system, gait)
    except SingularShapeError:
        assert p.flag.visible and p.net is None
        return
    assert not p.flag.visible
    np.testing.assert_allclose(p.net, g, atol=1e-7)
    assert "net displacement per cycle" in p.text.get_text()
    assert_body_at(p.body, p.system, p.traj.g[-1], p.traj.r[-1])


def test_gait_panel_floating_snake_body_frame_choice():
    p = GaitPanel(system=FloatingSnake())
    # the two frames of section 3.4.3: "centre of mass" alone means the mean orientation everywhere
    assert set(p.controls["frame"].options) == {"centre of mass (middle-link axes)", "middle link"}
    p.set(family="ellipse", amplitude=1.0, center1=0.6, center2=0.4, aspect=0.5, angle=0.3,
          frame="centre of mass (middle-link axes)")
    g_com = p.net.copy()
    # the centre-of-mass frame: the translation rows of A vanish, so the fields show no arrows there
    assert np.allclose(np.ma.filled(p.fields[0].U, 0.0), 0.0)
    p.set(frame="middle link")
    g_mid = p.net.copy()
    assert p.system.frame == "middle"
    gait = p.scene.gait(p.values())
    np.testing.assert_allclose(g_mid, net_displacement(FloatingSnake(frame="middle"), gait), atol=1e-7)
    # the same physical motion seen from two frames: same rotation, different translation
    assert np.isclose(g_com[2], g_mid[2], atol=1e-9) and abs(g_com[2]) > 1e-2
    assert not np.allclose(g_com[:2], g_mid[:2], atol=1e-3)
    assert np.abs(np.ma.filled(p.fields[0].U, 0.0)).max() > 1e-3


def _mouse(fig, name, ax, xy, button=1):
    from matplotlib.backend_bases import MouseEvent

    x, y = ax.transData.transform(xy)
    ev = MouseEvent(name, fig.canvas, x, y, button=button)
    fig.canvas.callbacks.process(name, ev)
    return ev


def test_gait_panel_drawn_loop_is_edited_by_dragging_a_control_point():
    from gm_core.systems.gaits import Gait

    p = GaitPanel(system=LowReSwimmer())
    p.set(amplitude=1.0, center1=0.0, center2=0.0)
    p.set(family="drawn")
    pts0 = p.points.copy()
    np.testing.assert_allclose(np.linalg.norm(pts0, axis=1), 1.0, atol=1e-12)   # seeded from the circle
    np.testing.assert_allclose(p.net, net_displacement(p.system, Gait.from_samples(pts0)), atol=1e-7)
    ax = p.field_axes[2]
    fig = p.fig
    _mouse(fig, "button_press_event", ax, pts0[2] + 0.02)          # near point 2: grabbed
    assert p.scene._grab == 2
    _mouse(fig, "motion_notify_event", ax, (0.3, 1.8))
    _mouse(fig, "button_release_event", ax, (0.3, 1.8))
    assert p.scene._grab is None
    want = pts0.copy()
    want[2] = (0.3, 1.8)
    np.testing.assert_allclose(p.points, want, atol=1e-9)
    np.testing.assert_allclose(p.net, net_displacement(p.system, Gait.from_samples(want)), atol=1e-7)
    dots = np.column_stack(p.handles[0].get_data())
    np.testing.assert_allclose(dots, want, atol=1e-9)
    # a press far from every point grabs nothing; dragging then moves nothing
    _mouse(fig, "button_press_event", ax, (-2.5, -2.5))
    _mouse(fig, "motion_notify_event", ax, (0.0, 0.0))
    np.testing.assert_allclose(p.points, want, atol=1e-9)


def test_gait_panel_drawn_loop_across_the_singular_line_raises_the_flag():
    p = GaitPanel(system=KinematicSnake())
    p.set(amplitude=0.6, center1=0.5, center2=-1.2)
    p.set(family="drawn")
    assert not p.flag.visible
    ax = p.field_axes[0]
    k = 0
    _mouse(p.fig, "button_press_event", ax, p.points[k])
    _mouse(p.fig, "motion_notify_event", ax, (-1.0, 1.0))          # across alpha1 = alpha2
    _mouse(p.fig, "button_release_event", ax, (-1.0, 1.0))
    assert p.flag.visible and p.net is None and "singular" in p.message
    assert not p.trail.line.get_visible()


def test_gait_panel_animation_plays_without_kernel():
    p = GaitPanel(system=LowReSwimmer())
    p.set(family="figure eight", amplitude=1.0, aspect=0.8, angle=0.0)
    html = p.animation(n_frames=12, cycles=1)
    assert "<script" in html.data
    import matplotlib.pyplot as plt
    plt.close("all")


def test_parallel_park_panel_shows_the_sideways_net_and_the_closed_radial_loop():
    from gm_core.systems.rolling_disk import bracket_estimate, parallel_park_displacement

    p = ParallelParkPanel()
    p.set(d=0.5, phi=0.4)
    g0 = np.array([0.0, -0.4, 0.0])
    np.testing.assert_allclose(p.net, parallel_park_displacement(0.5, 0.4), atol=1e-14)
    np.testing.assert_allclose(p.g_end, SE2.compose(g0, p.net), atol=1e-12)
    np.testing.assert_allclose(p.disk.patch.get_xy()[:4], SE2.act_on_points(p.g_end, D_nh.DISK_OUTLINE), atol=1e-12)
    np.testing.assert_allclose(p.net_arrow.U, p.g_end[0] - g0[0], atol=1e-12)
    assert np.isclose(p.estimate[1], -0.2) and np.isclose(p.net[1], p.estimate[1], rtol=0.1)
    np.testing.assert_allclose(p.estimate, bracket_estimate(0.5, 0.4))
    assert "net" in p.text.get_text()
    # the integrable constraint: the loop closes exactly and stays on the unit circle
    np.testing.assert_allclose(p.q[-1], p.q[0], atol=1e-14)
    np.testing.assert_allclose(np.hypot(*p.q.T), 1.0, atol=1e-14)
    # the drive segment of the disk is along its heading (theta = 0 at the start)
    seg = np.column_stack(p.segments[0].get_data())
    np.testing.assert_allclose(seg[:, 1], -0.4, atol=1e-14)
    np.testing.assert_allclose(seg[-1, 0], 0.5, atol=1e-14)


def test_pacing_square_panel_markers_commute_as_in_fig_3_1():
    from gm_core.systems.gaits import circle_gait as cg
    from gm_core.systems.motion import displacement_until
    from gm_core.systems.pacing import sine_pacing

    p = PacingSquarePanel()
    p.set(unevenness=0.6, t=0.3)
    tau, _ = sine_pacing(0.6)
    want = displacement_until(p.system, cg(1.0), float(tau(0.3)))
    np.testing.assert_allclose(p.g_top, want, atol=1e-12)
    np.testing.assert_allclose(p.g_bot, p.g_top, atol=1e-7)       # (3.4)
    np.testing.assert_allclose(p.markers[3].get_data(), [[p.g_bot[0]], [p.g_bot[1]]], atol=1e-12)
    np.testing.assert_allclose(p.markers[0].get_data(), p.markers[2].get_data(), atol=1e-12)  # same shape
    # the dots of the repaced row are the repaced loop at equal time steps
    rep = np.column_stack(p.dots[2].get_data())
    np.testing.assert_allclose(rep[3], cg(1.0)(np.array([float(tau(3 / 24))]))[0], atol=1e-12)


def test_directional_panel_numbers_prove_or_refute_each_property():
    from gm_core.systems.directional import RATE_MAPS

    A, B, C, D_ = list(RATE_MAPS)
    p = DirectionalLinearityPanel()
    for ex, same_pace, returns in [(A, True, True), (B, True, True), (C, False, True), (D_, True, False)]:
        p.set(example=ex, pace=2.5)
        x1, xk, back = p.ends
        assert np.isclose(x1, xk, atol=1e-12) == same_pace, ex
        assert np.isclose(back, 0.0, atol=1e-12) == returns, ex
        np.testing.assert_allclose(p.xk.get_data()[1][-1], xk)
        assert f"{xk:+.3f}" in p.text.get_text()

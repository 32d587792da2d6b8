"""Headless (Agg) tests of the geometry drawing and panels: artists show what gm_core.geometry computes."""
import os

import matplotlib

matplotlib.use("Agg")
os.environ.setdefault("GM_COURSE_TESTING", "1")

import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.animation import AbstractMovieWriter  # noqa: E402

from gm_core import SE2  # noqa: E402
from gm_core.drawing import curvature as D  # noqa: E402
from gm_core.geometry import (  # noqa: E402
    body_velocity_integral,
    constraint_curvature,
    stokes_estimate,
    sysplotter_stroke,
    sysplotter_swimmer,
)
from gm_core.geometry.estimates import field_rms, shaped_gait, square_grid  # noqa: E402
from gm_core.systems import FloatingSnake, KinematicSnake, LowReSwimmer  # noqa: E402
from gm_core.systems.gaits import circle_gait  # noqa: E402
from gm_core.systems.motion import net_displacement, trajectory  # noqa: E402
from gm_core.widgets import curvature as Wc  # noqa: E402
from gm_core.widgets.base import PANELS  # noqa: E402


@pytest.fixture(scope="module")
def stokes_panel():
    return Wc.GaitStokesPanel()


def figure_standard(fig):
    w, h = fig.get_size_inches() * fig.dpi
    assert w <= 900
    fig.canvas.draw()
    for t in fig.findobj(matplotlib.text.Text):
        if t.get_visible() and t.get_text().strip():
            assert t.get_fontsize() * fig.dpi / 72 >= 10, t.get_text()
    assert fig.get_layout_engine() is not None


def test_panels_registered_and_update_in_place():
    assert {"GaitStokesPanel", "FrameFieldsPanel"} <= set(PANELS)
    for p in (Wc.GaitStokesPanel(), Wc.FrameFieldsPanel()):  # fresh: naive_update clears the axes
        fig = p.fig
        n = [len(ax.get_children()) for ax in fig.axes]
        p.update(**p.sample_values(np.random.default_rng(0)))
        assert p.fig is fig and [len(ax.get_children()) for ax in fig.axes] == n
        figure_standard(fig)
        p.naive_update(**p.values())


@pytest.mark.parametrize("frame", ["middle link", "minimum perturbation"])
def test_bars_show_exact_stokes_and_integral(stokes_panel, frame):
    p = stokes_panel
    v = dict(c1=0.3, c2=-0.2, a=0.9, b=0.5, tilt=0.4, bend=0.25, frame=frame, row=2)
    p.set(**v)
    system = p.frames[frame]
    gait = shaped_gait(0.3, -0.2, 0.9, 0.5, 0.4, 0.25)
    # the panel's fixed interactive resolutions against the library's refined (adaptive) values
    want = [net_displacement(system, gait), stokes_estimate(system, gait), body_velocity_integral(system, gait)]
    shown = p.estimates.as_array()
    for s, w in zip(shown, want):
        np.testing.assert_allclose(s, w, atol=1e-7)
    np.testing.assert_allclose(shown[0][2], shown[1][2], atol=1e-8)  # theta row is exact
    # bars: each row divided by its largest |value| (by 5 % of the largest row when it is smaller:
    # a practically zero row stays practically zero), the axis fixed (so the panel can blit)
    heights = np.array([[r.get_height() for r in bars] for bars in p.bars.values()])
    top = np.abs(np.array(want)).max(axis=0)
    scale = np.maximum(top, 0.05 * top.max())
    np.testing.assert_allclose(heights, np.array(want) / scale, atol=1e-6)
    small = top < 0.05 * top.max()
    assert np.all(np.abs(heights[:, small]) <= 1.0 + 1e-9)
    assert np.abs(heights).max() <= 1.0 + 1e-12 and p.axb.get_ylim() == (-1.1, 1.45)
    for w in want:   # the numbers table shows all nine values
        for x in w:
            assert f"{x:+.4f}" in p.numbers.value or f"{x:+.4f}" == "-0.0000"
    line = np.column_stack(p.gait_artist.line.get_data())
    np.testing.assert_allclose(line, gait(np.linspace(0, 1, line.shape[0])), atol=1e-12)
    img = p.map.image.get_array()
    grid = square_grid(p.map.limits, p.map.n)
    np.testing.assert_allclose(img[10, 20], constraint_curvature(system, grid[10, 20])[2], rtol=1e-6, atol=1e-9)


def test_gait_leaving_the_map_raises_the_flag(stokes_panel):
    p = stokes_panel
    p.set(c1=1.5, c2=1.5, a=1.5, b=1.5, frame="minimum perturbation")
    assert p.flag.visible
    assert all(r.get_height() == 0 for bars in p.bars.values() for r in bars)
    assert "singular" in p.numbers.value and p.estimates is None
    p.set(c1=0.0, c2=0.0, a=0.5, b=0.5)
    assert not p.flag.visible and "exact g(T)" in p.numbers.value


def test_stokes_panel_widget_has_the_numbers(stokes_panel):
    box = stokes_panel.widget
    assert stokes_panel.numbers in box.children and stokes_panel.widget is box


def test_panels_are_scene_panels_over_scenes():
    from gm_core.drawing.toolkit import Scene
    from gm_core.widgets.base import ScenePanel

    for cls in (Wc.GaitStokesPanel, Wc.FrameFieldsPanel):
        assert issubclass(cls, ScenePanel) and issubclass(cls.scene_class, Scene)


def test_frame_fields_show_minus_the_connection_at_one_scale():
    p = Wc.FrameFieldsPanel()
    caps = [f.cap for f in p.fields]
    for frame in ("centre of mass", "minimum perturbation"):
        p.set(frame=frame)
        f = p.fields[1]
        V = -p.frames[frame].connection(p.grid)[..., 1, :].reshape(-1, 2)
        U = np.column_stack([f.quiver.U.ravel(), f.quiver.V.ravel()])
        k = np.argmax(np.linalg.norm(V, axis=1))
        np.testing.assert_allclose(U[k] / np.linalg.norm(U[k]), V[k] / np.linalg.norm(V[k]), atol=1e-9)
        assert [g.cap for g in p.fields] == caps          # the middle-link scale in every frame
        np.testing.assert_allclose(p.rms, field_rms(p.frames[frame], p.grid))
        assert f"{p.rms[1]:.3f}" in p.axes[1].get_title()
    assert p.rms[2] < field_rms(p.frames["middle link"], p.grid)[2]


def test_curvature_maps_figure_and_zero_rows():
    fig = D.curvature_maps_figure({"floating": (FloatingSnake(), circle_gait(1.0)),
                                   "snake": (KinematicSnake(), None)}, n=21)
    figure_standard(fig)
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    assert texts.count("≡ 0") == 2  # the floating snake's centre of mass cannot move


def test_swimmer_animation_places_the_links():
    s, g = sysplotter_swimmer(), sysplotter_stroke("efficiency")
    tr = trajectory(s, g, n_frames=31)
    fig, anim = D.animate_swimmer(s, g, tr, n_frames=31, row=0, limits=((-2.6, 2.6), (-2.6, 2.6)))
    figure_standard(fig)

    class Grab(AbstractMovieWriter):   # matplotlib's public writer interface: keep each frame's patches
        def setup(self, fig, outfile, dpi=None):
            super().setup(fig, outfile, dpi=dpi)
            self.seen = []

        def grab_frame(self, **savefig_kwargs):
            self.seen.append([p.get_xy().copy() for p in fig.axes[1].patches])

        def finish(self):
            pass

    writer = Grab(fps=10)
    anim.save("frames-kept-in-memory", writer=writer)
    # the third frame (frames are shortened under test, indices still map to traj)
    i = np.linspace(0, 30, 31).round().astype(int)[2]
    poses = SE2.compose(tr.g[i][None], s.part_poses(tr.r[i]))
    for xy, part, pose in zip(writer.seen[2], s.parts(), poses):
        np.testing.assert_allclose(xy[: len(part.outline)], SE2.act_on_points(pose, part.outline), atol=1e-12)


def test_optimize_with_progress_reports(capsys):
    res = Wc.optimize_with_progress(LowReSwimmer(lengths=(1 / 3,) * 3), "displacement", order=1, maxiter=3)
    assert len(res.history) >= 2 and res.history[-1] >= res.history[0]

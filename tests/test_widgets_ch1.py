"""Headless tests of the chapter-1 panels (gm_core.widgets.ch1) on the Agg backend.

Each test sets slider values the way a student would (``panel.controls[name].value = ...``) and
reads the artists back: polygons, quivers, lines and text must have moved by exactly what
gm_core's mathematics says, computed here by an independent route where one exists (matrix
products, finite differences, scipy.integrate.solve_ivp, scipy.linalg.expm).
"""
import os

os.environ.setdefault("GM_COURSE_TESTING", "1")

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from gm_core import R2xS1, SE2, S1  # noqa: E402
from gm_core.drawing import ch1 as D  # noqa: E402
from gm_core.widgets import ch1 as W  # noqa: E402
from gm_core.widgets.base import PANELS  # noqa: E402


def slide(panel, **values):
    """Move sliders one by one, as a user would (each change triggers an update)."""
    for k, v in values.items():
        panel.controls[k].value = v
    return panel


def body_xy(body):
    return np.asarray(body.patch.get_xy())[: len(body.outline)]


def quiver_uv(q):
    return np.stack([np.asarray(q.U, float), np.asarray(q.V, float)], -1)


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    plt.close("all")


def test_every_ch1_panel_is_registered_and_builds():
    names = [n for n, c in PANELS.items() if c.__module__ == W.__name__]
    assert set(W.__all__) - {"show"} <= set(names)
    rng = np.random.default_rng(0)
    for n in names:
        p = PANELS[n]()
        p.update(**p.sample_values(rng))
        p.naive_update(**p.sample_values(rng))  # the baseline must also run


# ---------------------------------------------------------------- 1.1 configuration spaces
def test_torus_path_pieces_stay_in_square_and_match_3d_curve():
    p = slide(W.TorusPathPanel(), a0=1.0, b0=2.0, slope=1.5, turns=2.0)
    segs = p.scene.segments
    pts = np.concatenate(segs)
    assert pts.min() >= 0 and pts.max() < 2 * np.pi
    a, b = p.scene.path(1.0, 2.0, 1.5, 2.0)
    xs, ys, zs = p.scene.curve3d.get_data_3d()
    assert np.allclose(np.c_[xs, ys, zs], D.torus_xyz(a, b))
    # straight: constant slope inside every piece
    for s in segs:
        d = np.diff(s, axis=0)
        assert np.allclose(d[:, 1] / d[:, 0], 1.5)


def test_pole_chart_flags_instead_of_plotting_inf():
    p = W.PoleChartPanel()
    slide(p, heading_deg=30.0, lat_deg=60.0)
    assert not p.scene.flag.visible and p.scene.arrow_c.get_visible()
    want = D.PoleChartScene.ARROW * np.array([np.sin(np.deg2rad(30)) / np.cos(np.deg2rad(60)),
                                              np.cos(np.deg2rad(30))])
    assert np.allclose(quiver_uv(p.scene.arrow_c)[0], want)
    slide(p, lat_deg=90.0)
    assert p.scene.at_pole and p.scene.flag.visible
    assert not p.scene.arrow_c.get_visible() and not p.scene.pt_c.get_visible()
    # the polar chart's velocity stays finite at the pole
    assert np.all(np.isfinite(p.scene.polar_vec))
    # nothing non-finite was handed to the visible artists
    assert np.all(np.isfinite(p.scene.speed_curve.get_ydata()))


def test_loops_sphere_contracts_torus_does_not():
    p = W.LoopsPanel()
    slide(p, s=0.5)
    L_t, L_s = p.scene.torus_length, p.scene.sphere_length
    assert np.isclose(L_s, 2 * np.pi * 1.6 * np.cos(np.pi / 4))
    slide(p, s=1.0)
    assert p.scene.sphere_length < 1e-9 and p.scene.sphere_point.get_visible()
    assert np.isclose(p.scene.torus_length, L_t)
    x, y, z = p.scene.torus_loop.get_data_3d()
    # the torus loop is a tube circle at angle a = 2 pi: its distance from the tube centre is r
    centre = np.array([2.0, 0.0, 0.0])
    assert np.allclose(np.linalg.norm(np.c_[x, y, z] - centre, axis=1), 0.7)


# ---------------------------------------------------------------------- 1.2-1.3 groups
def test_group_axioms_panel_bars_match_direct_computation():
    p = slide(W.GroupAxiomsPanel(), seed=7, scale=2.0)
    rng = np.random.default_rng(7)
    for k, G in D.ALL_GROUPS.items():
        direct = D.axiom_residuals(G, rng, scale=2.0)
        assert direct == p.scene.results[k]
        assert direct["closure"] and max(direct[a] for a in D.AXIOMS) < 1e-9
    rect = p.scene.bars["associativity"][list(D.ALL_GROUPS).index("SE2")]
    top = rect.get_y() + rect.get_height()
    assert np.isclose(top, max(p.scene.results["SE2"]["associativity"], D.GroupAxiomsScene.FLOOR))


def test_slide_rule_reads_the_product():
    p = slide(W.SlideRulePanel(), a=3.0, b=2.5)
    assert np.isclose(p.scene.reading, 7.5)
    x = p.scene.cursor.get_xdata()
    assert np.allclose(x, np.log10(7.5))
    segs = p.scene.slide.get_segments()
    assert np.isclose(segs[0][0, 0], np.log10(3.0))  # the C scale's "1" sits over a


def test_circle_iso_matrix_product_equals_sum():
    p = slide(W.CircleIsoPanel(), a1=0.7, a2=0.6)
    G = S1(1.0)
    s = G.compose([0.7], [0.6])
    assert np.isclose(s[0], 0.3)
    assert p.scene.mismatch < 1e-12
    uv = quiver_uv(p.scene.vecs)
    assert np.allclose(uv[2], [np.cos(2 * np.pi * 0.3), np.sin(2 * np.pi * 0.3)])


def test_left_right_action_bodies_move_by_se2_products():
    p = W.LeftRightActionPanel()
    g = np.array([1.2, -0.4, 0.8])
    h = np.array([-0.7, 1.1, -1.3])
    slide(p, x=g[0], y=g[1], theta=g[2], u=h[0], v=h[1], beta=h[2])
    outline = p.scene.hg_body.outline
    # independent route: homogeneous matrices
    Mhg = SE2.matrix(h) @ SE2.matrix(g)
    Mgh = SE2.matrix(g) @ SE2.matrix(h)
    pts = np.c_[outline, np.ones(len(outline))]
    assert np.allclose(body_xy(p.scene.hg_body), (pts @ Mhg.T)[:, :2])
    assert np.allclose(body_xy(p.scene.gh_body), (pts @ Mgh.T)[:, :2])
    assert np.allclose(body_xy(p.scene.g_body[0]), (pts @ SE2.matrix(g).T)[:, :2])
    # the arc ends where R(beta) puts g's position, and the shift adds (u, v)
    ax, ay = p.scene.arc.get_data()
    Rb = SE2.matrix([0, 0, h[2]])[:2, :2]
    assert np.allclose([ax[-1], ay[-1]], Rb @ g[:2])
    assert np.allclose(np.array([ax[-1], ay[-1]]) + h[:2], Mhg[:2, 2])
    # frame arrows of gh point along the rotated body axes
    uv = quiver_uv(p.scene.gh_frame.quiver)
    assert np.allclose(uv[0] / np.linalg.norm(uv[0]), Mgh[:2, 0])


def test_forward_left_poses_and_body_displacements():
    p = W.ForwardLeftPanel()
    slide(p, x=1.0, y=1.0, theta=np.pi / 2, n=4)
    add, se2 = p.scene.poses
    assert np.allclose(add[3], 3 * np.array([1.0, 1.0, np.pi / 2]))
    g = np.array([1.0, 1.0, np.pi / 2])
    M = np.linalg.matrix_power(SE2.matrix(g), 3)
    assert np.allclose(SE2.matrix(se2[3]), M)
    assert SE2.isclose(se2[4], SE2.identity())  # four quarter turns: back home
    verts = p.scene.bodies[1].get_paths()
    assert len(verts) == 5
    assert np.allclose(verts[2].vertices[:3], SE2.act_on_points(se2[2], D.BODY))
    d = D.ForwardLeftScene.body_displacements(se2)
    assert np.allclose(d, np.tile([1.0, 1.0], (4, 1)))
    d_add = D.ForwardLeftScene.body_displacements(add)
    assert np.allclose(d_add[1], [1.0, -1.0])
    assert "forward and to the right" in p.scene.texts[0].get_text()
    slide(p, n=1)
    assert len(p.scene.bodies[0].get_paths()) == 2


def test_body_points_world_position():
    p = W.BodyPointsPanel()
    slide(p, x=-0.5, y=1.0, theta=2.0, px=0.7, py=-0.2)
    want = SE2.matrix([-0.5, 1.0, 2.0]) @ np.array([0.7, -0.2, 1.0])
    x, y = p.scene.point.get_data()
    assert np.allclose([x[0], y[0]], want[:2])
    assert p.scene.matrix_mismatch < 1e-12


def test_path_text_renders_and_updates():
    fig, ax = plt.subplots()
    t = D.PathText(ax, 0.1, 0.2, "abc\ndef", ha="center")
    assert len(t.collection.get_paths()) == 2
    t.set_text("x")
    assert t.get_text() == "x" and len(t.collection.get_paths()) == 1
    t.set_position((0.5, 0.5))
    assert np.allclose(t.collection.get_offsets(), [[0.5, 0.5]])
    fig.canvas.draw()

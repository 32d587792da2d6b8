"""Headless tests of the chapter-1 panels on the Agg backend (gm_core.widgets.spaces, axioms,
groups, tangent, vector_fields, observers, geodesics, charts).

Each test sets slider values the way a student would (``panel.controls[name].value = ...``) and
reads the artists back: polygons, quivers, lines and text must have moved by exactly what
gm_core's mathematics says, computed here by an independent route where one exists (matrix
products, finite differences, scipy.integrate.solve_ivp, scipy.linalg.expm).
"""
import os
import sys
from pathlib import Path

os.environ.setdefault("GM_COURSE_TESTING", "1")

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

from gm_core import S1, SE2, R2xS1  # noqa: E402
from gm_core.calculus import binomial_table
from gm_core.drawing.axioms import GroupOrNotScene
from gm_core.drawing.geodesics import HelixScene, puck_vs_arc_animation
from gm_core.drawing.groups import BODY, ForwardLeftScene
from gm_core.drawing.spaces import PoleChartScene
from gm_core.drawing.toolkit import PathText
from gm_core.drawing.vector_fields import LiftedSE2Scene, VectorFieldScene
from gm_core.fields import FIELDS
from gm_core.manifolds import torus_xyz
from gm_core.widgets import axioms, charts, geodesics, groups, observers, spaces, tangent, vector_fields  # noqa: E402
from gm_core.widgets.axioms import GroupAxiomsPanel
from gm_core.widgets.base import PANELS  # noqa: E402
from gm_core.widgets.charts import PlaneChartsPanel
from gm_core.widgets.geodesics import (
    ExpFourWaysPanel,
    HelixPanel,
    PuckArcPanel,
    RPlusGeodesicPanel,
    SurfaceGeodesicsPanel,
)
from gm_core.widgets.groups import (
    BodyPointsPanel,
    CircleIsoPanel,
    ForwardLeftPanel,
    LeftRightActionPanel,
    ScaleShiftActionPanel,
    SlideRulePanel,
)
from gm_core.widgets.observers import FramesPanel, ObserverPanel
from gm_core.widgets.spaces import LoopsPanel, PoleChartPanel, TorusPathPanel
from gm_core.widgets.tangent import TangentSpacePanel
from gm_core.widgets.vector_fields import (
    AdjointPanel,
    LiftedScalarPanel,
    LiftedSE2Panel,
    VectorFieldPanel,
    VelocityPanel,
)


def rk4_curve(f, q0, T, n):
    """Independent route for integral curves: n classical RK4 steps over [0, T], (n+1, ..., 2)."""
    q = np.asarray(q0, float)
    h = T / n
    out = [q]
    for _ in range(n):
        k1 = f(q)
        k2 = f(q + 0.5 * h * k1)
        k3 = f(q + 0.5 * h * k2)
        k4 = f(q + h * k3)
        q = q + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        out.append(q)
    return np.array(out)


def slide(panel, **values):
    """Move sliders one by one, as a user would (each change triggers an update)."""
    for k, v in values.items():
        panel.controls[k].value = v
    return panel


def body_xy(body):
    return np.asarray(body.patch.get_xy())[: len(body.outline)]


def quiver_uv(q):
    return np.stack([np.asarray(q.U, float), np.asarray(q.V, float)], -1)


def test_every_ch1_panel_is_registered_and_builds():
    modules = (spaces, charts, axioms, groups, tangent, vector_fields, observers, geodesics)
    names = [n for n, c in PANELS.items() if c.__module__ in {m.__name__ for m in modules}]
    assert {n for m in modules for n in m.__all__} <= set(names) and len(names) == 24
    rng = np.random.default_rng(0)
    for n in names:
        p = PANELS[n]()
        p.update(**p.sample_values(rng))
        p.naive_update(**p.sample_values(rng))  # the baseline must also run
        if p.fig is not None:
            plt.close(p.fig)   # 24 panels: pyplot would keep every figure open


# ---------------------------------------------------------------- 1.1 configuration spaces
def test_torus_path_pieces_stay_in_square_and_match_3d_curve():
    p = slide(TorusPathPanel(), a0=1.0, b0=2.0, slope=1.5, turns=2.0)
    segs = p.scene.segments
    pts = np.concatenate(segs)
    assert pts.min() >= 0 and pts.max() < 2 * np.pi
    a, b = p.scene.path(1.0, 2.0, 1.5, 2.0)
    xs, ys, zs = p.scene.curve3d.get_data_3d()
    assert np.allclose(np.c_[xs, ys, zs], torus_xyz(a, b))
    # straight: constant slope inside every piece
    for s in segs:
        d = np.diff(s, axis=0)
        assert np.allclose(d[:, 1] / d[:, 0], 1.5)


def test_pole_chart_flags_instead_of_plotting_inf():
    p = PoleChartPanel()
    slide(p, heading_deg=30.0, lat_deg=60.0)
    assert not p.scene.flag.visible and p.scene.arrow_c.get_visible()
    want = PoleChartScene.ARROW * np.array([np.sin(np.deg2rad(30)) / np.cos(np.deg2rad(60)),
                                              np.cos(np.deg2rad(30))])
    assert np.allclose(quiver_uv(p.scene.arrow_c)[0], want)
    slide(p, lat_deg=89.5)                   # finite but huge: warned, still drawn
    assert p.scene.flag.visible and p.scene.arrow_c.get_visible()
    assert np.isclose(p.scene.chart_speed, np.hypot(np.cos(np.deg2rad(30)),
                                                    np.sin(np.deg2rad(30)) / np.cos(np.deg2rad(89.5))))
    slide(p, lat_deg=90.0)
    assert p.scene.at_pole and p.scene.flag.visible
    assert not p.scene.arrow_c.get_visible() and not p.scene.pt_c.get_visible()
    # the polar chart's velocity stays finite at the pole
    assert np.all(np.isfinite(p.scene.polar_vec))
    # nothing non-finite was handed to the visible artists
    assert np.all(np.isfinite(p.scene.speed_curve.get_ydata()))


def test_loops_sphere_contracts_torus_does_not():
    p = LoopsPanel()
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


def _polar(p):
    """Independent route for the polar chart: (hypot, arctan2) of Cartesian points (..., 2)."""
    p = np.asarray(p, float)
    return np.stack([np.hypot(p[..., 0], p[..., 1]), np.arctan2(p[..., 1], p[..., 0])], -1)


def _polar_push(p, v, h=1e-6):
    """Central difference of the polar coordinates along v at p: the pushforward, no Jacobian formula."""
    return (_polar(p + h * v) - _polar(p - h * v)) / (2 * h)


def test_plane_charts_panel_shows_the_transition_of_point_vector_and_field():
    p = slide(PlaneChartsPanel(), field="spiral sink", x=-1.2, y=0.8, v_angle=30.0, v_length=1.5)
    sc = p.scene
    q1 = np.array([-1.2, 0.8])
    v1 = 1.5 * np.array([np.cos(np.pi / 6), np.sin(np.pi / 6)])
    assert np.allclose(np.c_[sc.pt_c.get_data()], [q1])
    assert np.allclose(np.c_[sc.pt_p.get_data()], [_polar(q1)])
    assert np.allclose(sc.vec_c.get_offsets(), [q1]) and np.allclose(quiver_uv(sc.vec_c), [sc.V_SCALE * v1])
    assert np.allclose(sc.vec_p.get_offsets(), [_polar(q1)])
    assert np.allclose(quiver_uv(sc.vec_p), [sc.V_SCALE * _polar_push(q1, v1)], atol=1e-8)
    # the field in the polar chart points where the Cartesian field pushed forward points
    X1 = FIELDS["spiral sink"]
    g2 = sc.field_p.get_offsets() + quiver_uv(sc.field_p) / 2          # arrows are centred on the grid
    pts = np.stack([g2[:, 0] * np.cos(g2[:, 1]), g2[:, 0] * np.sin(g2[:, 1])], -1)
    want = np.array([_polar_push(q, X1(q)) for q in pts])
    got = quiver_uv(sc.field_p)
    cos = np.sum(got * want, 1) / np.linalg.norm(got, axis=1) / np.linalg.norm(want, axis=1)
    assert np.allclose(cos, 1.0, atol=1e-8)
    # the integral curve: an independent RK4 on the left, its polar image on the right, cut at the ray
    (left,) = sc.curves[0].get_segments()
    rk4 = rk4_curve(X1, q1, sc.T, 3000)
    assert np.allclose(left[-1], rk4[-1], atol=1e-4)
    right = np.concatenate(sc.curves[1].get_segments())
    assert np.allclose(right, _polar(left[np.abs(_polar(left)[:, 1]) < np.pi]), atol=1e-12)
    # coordinate lines through the point: r = r0 is a circle on the left and a vertical line on the right
    r0 = np.hypot(*q1)
    assert np.allclose(np.linalg.norm(np.concatenate(sc.lines["r"][0].get_segments()), axis=1), r0)
    assert np.allclose(np.concatenate(sc.lines["r"][1].get_segments())[:, 0], r0)
    xline = np.concatenate(sc.lines["x"][1].get_segments())
    assert np.allclose(xline[:, 0] * np.cos(xline[:, 1]), -1.2)              # x = x0 seen in the polar chart
    assert not sc.flag.visible and "v₂ = J v₁" in sc.read_p.get_text()


def test_plane_charts_panel_flags_the_ray_and_the_origin():
    p = slide(PlaneChartsPanel(), x=-1.0, y=0.0)
    sc = p.scene
    assert sc.flag.visible and "π and −π" in sc.flag.text.get_text()
    assert not sc.pt_p.get_visible() and not sc.vec_p.get_visible() and sc.q2 is None
    assert sc.lines["r"][1].get_segments() == [] and sc.lines["θ"][0].get_segments() == []
    for lc in [*sc.curves, *(lc for pair in sc.lines.values() for lc in pair)]:
        assert all(np.all(np.isfinite(s)) for s in lc.get_segments())
    slide(p, x=0.0)
    assert sc.flag.visible and "origin" in sc.flag.text.get_text()
    slide(p, y=0.5)
    assert not sc.flag.visible and sc.pt_p.get_visible()
    assert np.allclose(np.c_[sc.pt_p.get_data()], [[0.5, np.pi / 2]])


# ---------------------------------------------------------------------- 1.2-1.3 groups
def test_group_or_not_badges_follow_the_verdicts():
    from matplotlib.colors import to_rgba

    from gm_core.drawing.toolkit import PALETTE

    assert GroupAxiomsPanel.scene_class is GroupOrNotScene
    p = slide(GroupAxiomsPanel(), structure="(ℝ, −)", a=3.0, b=2.0, c=1.0)
    sc = p.scene
    assert not sc.is_group
    colours = [tuple(b.get_facecolor()) for b in sc.badges]
    assert colours[0] == to_rgba(PALETTE["green"])                      # closure holds for subtraction
    assert colours[1:] == [to_rgba(PALETTE["vermillion"])] * 3            # the other three fail
    assert [m.get_text() for m in sc.marks] == ["✓", "✗", "✗", "✗"]
    # the associativity row shows the numbers: (3 - 2) - 1 = 0 against 3 - (2 - 1) = 2
    assert "(3 − 2) − 1 = 0" in sc.whys[1].get_text() and "3 − (2 − 1) = 2" in sc.whys[1].get_text()
    assert sc.tries[1].get_text() == f"✗ (a−b)−c = {(3 - 2) - 1}, a−(b−c) = {3 - (2 - 1)}"
    assert "NOT a group" in sc.title.get_text()
    p.set(structure="(ℤ, ×)", a=2.0, b=3.0, c=1.0)
    assert [m.get_text() for m in sc.marks] == ["✓", "✓", "✓", "✗"]
    assert "2 × x = 1" in sc.whys[3].get_text() and sc.tries[0].get_text() == f"✓ a × b = {2 * 3}"
    p.set(structure="(ℝ⁺, +)")
    assert [m.get_text() for m in sc.marks] == ["✓", "✓", "✗", "✗"]
    for name in ("(ℤ, +)", "(ℝ⁺, ×)", "SE(2)"):
        p.set(structure=name)
        assert sc.is_group and all(tuple(b.get_facecolor()) == to_rgba(PALETTE["green"]) for b in sc.badges)


def test_slide_rule_reads_the_product():
    p = slide(SlideRulePanel(), a=3.0, b=2.5)
    assert np.isclose(p.scene.reading, 7.5)
    x = p.scene.cursor.get_xdata()
    assert np.allclose(x, np.log10(7.5))
    segs = p.scene.slide.get_segments()
    assert np.isclose(segs[0][0, 0], np.log10(3.0))  # the C scale's "1" sits over a


def test_circle_iso_matrix_product_equals_sum():
    p = slide(CircleIsoPanel(), a1=0.7, a2=0.6)
    G = S1(1.0)
    s = G.compose([0.7], [0.6])
    assert np.isclose(s[0], 0.3)
    assert p.scene.mismatch < 1e-12
    uv = quiver_uv(p.scene.vecs)
    assert np.allclose(uv[2], [np.cos(2 * np.pi * 0.3), np.sin(2 * np.pi * 0.3)])


def test_left_right_action_bodies_move_by_se2_products():
    p = LeftRightActionPanel()
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
    p = ForwardLeftPanel()
    slide(p, x=1.0, y=1.0, theta=np.pi / 2, n=4)
    add, se2 = p.scene.poses
    assert np.allclose(add[3], 3 * np.array([1.0, 1.0, np.pi / 2]))
    g = np.array([1.0, 1.0, np.pi / 2])
    M = np.linalg.matrix_power(SE2.matrix(g), 3)
    assert np.allclose(SE2.matrix(se2[3]), M)
    assert SE2.isclose(se2[4], SE2.identity())  # four quarter turns: back home
    verts = p.scene.bodies[1].get_paths()
    assert len(verts) == 5
    assert np.allclose(verts[2].vertices[:3], SE2.act_on_points(se2[2], BODY * p.scene.scale))
    d = ForwardLeftScene.body_displacements(se2)
    assert np.allclose(d, np.tile([1.0, 1.0], (4, 1)))
    d_add = ForwardLeftScene.body_displacements(add)
    assert np.allclose(d_add[1], [1.0, -1.0])
    assert "forward and to the right" in p.scene.texts[0].get_text()
    slide(p, n=1)
    assert len(p.scene.bodies[0].get_paths()) == 2


def test_forward_left_window_holds_every_pose_and_the_words_leave_the_path_alone():
    """Issue 36: n long steps of (R^2 x S^1, +) left the axes. Every body and frame stays inside
    the window at the corners of the sliders, the smallest window that holds them is chosen, and
    the readout sits in the corner where no body lies under it."""
    p = ForwardLeftPanel()
    for x, y, theta, n in [(2.0, 2.0, 0.0, 8), (-2.0, -2.0, -0.17, 8), (2.0, -2.0, 0.3, 8),
                           (-2.0, 2.0, np.pi, 5), (1.0, 1.0, np.pi / 2, 2), (0.3, -0.2, 2.0, 8)]:
        p.set(x=x, y=y, theta=theta, n=n)
        lim = p.scene.axes[0].get_xlim()[1]
        for ax, bodies, frames in zip(p.scene.axes, p.scene.bodies, p.scene.frames):
            assert ax.get_xlim() == (-lim, lim) and ax.get_ylim() == (-lim, lim)   # one window for both
            drawn = np.concatenate([np.concatenate([q.vertices for q in bodies.get_paths()]),
                                    np.concatenate(frames.get_segments())])
            assert np.abs(drawn).max() < lim, f"g = {(x, y, theta)}, n = {n}: drawn out to {np.abs(drawn).max():.2f}"
        smaller = [z for z in ForwardLeftScene.ZOOMS if z < lim]
        reach = max(np.abs(P[:, :2]).max() for P in p.scene.poses)
        assert all(reach > z - 0.6 * z / ForwardLeftScene.LIM for z in smaller), "a smaller window would do"
        fig = p.fig
        fig.canvas.draw()
        for ax, text, bodies in zip(p.scene.axes, p.scene.texts, p.scene.bodies):
            words = text.get_window_extent()
            # no body under the words: each body's pixels stay outside the readout's box
            for q in bodies.get_paths():
                px = ax.transData.transform(q.vertices)
                inside = ((px[:, 0] > words.x0) & (px[:, 0] < words.x1)
                          & (px[:, 1] > words.y0) & (px[:, 1] < words.y1))
                assert not inside.any(), f"g = {(x, y, theta)}, n = {n}: a body lies under the words"


def test_circle_names_never_cover_each_other_or_the_captions():
    """Issue 36: a₁'s name sat on the caption when a₁ was near the bottom of the circle, and the
    names of coinciding points covered each other. Over a grid of both sliders the figure
    standard's checker (tests/figstd.py) finds no overlap and every name stays near its point."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import figstd

    p = CircleIsoPanel()
    found = []
    for a1 in np.arange(0.0, 1.0, 0.125):
        for a2 in np.arange(0.0, 1.0, 0.125):
            p.set(a1=a1, a2=a2)
            found += [f"a1 = {a1}, a2 = {a2}: {m}" for m in figstd.check_figure(p.fig)]
            ang = 2 * np.pi * np.array([a1, a2, (a1 + a2) % 1])
            for name, a in zip(p.scene.names[1], ang):
                r = np.hypot(*name.xy)
                assert 1.1 < r < 1.6 and abs(np.angle(np.exp(1j * (np.arctan2(name.xy[1], name.xy[0]) - a)))) < 0.8
    assert not found, "\n".join(found[:10])


def test_body_points_world_position():
    p = BodyPointsPanel()
    slide(p, x=-0.5, y=1.0, theta=2.0, px=0.7, py=-0.2)
    want = SE2.matrix([-0.5, 1.0, 2.0]) @ np.array([0.7, -0.2, 1.0])
    x, y = p.scene.point.get_data()
    assert np.allclose([x[0], y[0]], want[:2])
    assert p.scene.matrix_mismatch < 1e-12


def test_scale_shift_panel_moves_the_grid_and_the_flows_by_matrix_products():
    """The scale-shift panel's dots and lines, read back, are the matrix route: [[α, β], [0, 1]]
    times [[a, b], [0, 1]] on either side for the grid, scipy's expm for exp(tξ) and its images."""
    import scipy.linalg

    p = slide(ScaleShiftActionPanel(), alpha=0.7, beta=-0.4, u=-0.8, v=1.3)
    H = np.array([[0.7, -0.4], [0.0, 1.0]])
    grid = [np.array([[a, b], [0.0, 1.0]]) for a in (0.5, 1.0, 1.5, 2.0) for b in (-1.0, -0.5, 0.0, 0.5, 1.0)]
    left, right = (np.asarray(d.get_xydata()) for d in p.scene.moved_dots)
    assert np.allclose(left, [(H @ M)[0] for M in grid], atol=1e-14)
    assert np.allclose(right, [(M @ H)[0] for M in grid], atol=1e-14)
    t = np.linspace(-1.5, 1.5, 61)
    E = [scipy.linalg.expm(s * np.array([[-0.8, 1.3], [0.0, 0.0]])) for s in t]
    for k, flow in enumerate(p.scene.flows):
        assert np.allclose(np.c_[p.scene.subgroup_lines[k].get_data()], [M[0] for M in E], atol=1e-12)
        want = [(H @ M)[0] if k == 0 else (M @ H)[0] for M in E]
        assert np.allclose(np.c_[flow.get_data()], want, atol=1e-12)
        assert np.allclose(p.scene.h_marks[k].get_data(), [[0.7], [-0.4]])
    # (the numbers stand between the formulas' $...$ spans, the sign inside: drop the $ to read them)
    shown = [f.get_text().replace("$", "") for f in p.scene.formulas]
    assert "0.70" in shown[0] and "b -0.40" in shown[1]


def test_scale_shift_formulas_are_laid_out_as_one_mathtext_formula_without_parsing_it_per_move():
    """The readouts keep their numbers outside the $...$ spans, so a move parses no mathtext; the
    line is as wide as matplotlib's mathtext lays out the whole formula as one span."""
    from matplotlib.font_manager import FontProperties
    from matplotlib.mathtext import MathTextParser

    from gm_core.drawing.toolkit import style

    p = ScaleShiftActionPanel()
    prop = FontProperties(family=style._FAMILIES["sans"], size=style.MATH_PT)
    parser = MathTextParser("path")
    for alpha, beta in ((0.7, -0.4), (1.85, 0.25), (1.5, 0.0)):
        p.set(alpha=alpha, beta=beta)
        whole = (rf"$h\circ g = ({alpha:.2f}\,a,\ {alpha:.2f}\,b {beta:+.2f})$",
                 rf"$g\circ h = ({alpha:.2f}\,a,\ b {beta:+.2f}\,a)$")
        for f, formula in zip(p.scene.formulas, whole):
            want = parser.parse(formula, dpi=7200, prop=prop).width / 7200.0 * 72.0
            assert abs(style._glyphs(f.get_text(), f.size, "normal")[1] * 72.0 - want) < 0.05, formula
    math_spans = {k for k in style._PATH_CACHE if k[-1] == "math"}
    for alpha in np.linspace(0.6, 1.9, 7):
        p.set(alpha=float(alpha), beta=-0.3)
    assert {k for k in style._PATH_CACHE if k[-1] == "math"} == math_spans, "a move laid out a new math span"
    plt.close(p.fig)


def test_path_text_renders_and_updates():
    fig, ax = plt.subplots()
    t = PathText(ax, 0.1, 0.2, "abc\ndef", ha="center")
    assert len(t.collection.get_paths()) == 2
    t.set_text("x")
    assert t.get_text() == "x" and len(t.collection.get_paths()) == 1
    t.set_position((0.5, 0.5))
    assert np.allclose(t.collection.get_offsets(), [[0.5, 0.5]])
    fig.canvas.draw()


# ---------------------------------------------------------------------- 1.4-1.5 velocities
@pytest.mark.parametrize("field", list(FIELDS))
def test_vector_field_curve_follows_the_field(field):
    p = slide(VectorFieldPanel(), field=field, x0=0.8, y0=-0.6)
    fx, fy = p.scene.forward.get_data()
    assert np.allclose([fx[0], fy[0]], [0.8, -0.6])
    # independent route: classical RK4 with small steps, forward and backward
    ref = rk4_curve(FIELDS[field], np.array([0.8, -0.6]), VectorFieldScene.T, 2400)[::10]
    m = len(fx)
    assert np.allclose(np.c_[fx, fy], ref[:m], atol=1e-4)
    bx, by = p.scene.backward.get_data()
    back = rk4_curve(lambda q: -FIELDS[field](q), np.array([0.8, -0.6]), VectorFieldScene.T, 2400)[::10]
    assert np.allclose(np.c_[bx, by], back[: len(bx)], atol=1e-4)
    assert np.all(np.isfinite(fx)) and np.all(np.isfinite(bx))
    # the background arrows point along the field
    uv = quiver_uv(p.scene.quiver)
    v = FIELDS[field](p.scene._grid)
    nz = np.linalg.norm(v, axis=1) > 1e-9
    cos = np.sum(uv[nz] * v[nz], 1) / np.linalg.norm(uv[nz], axis=1) / np.linalg.norm(v[nz], axis=1)
    assert np.allclose(cos, 1.0)


def test_lifted_scalar_actions():
    p = slide(LiftedScalarPanel(), hx=0.5, hy=-0.7, h=3.0)
    uv = quiver_uv(p.scene.arrows2)
    assert np.allclose(uv[0], uv[1])                         # (1.22): identity on R^2
    off = p.scene.arrows2.get_offsets()
    assert np.allclose(off[1] - off[0], [0.5, -0.7])
    uv1 = quiver_uv(p.scene.arrows1)
    assert np.isclose(uv1[1, 0], 3.0 * uv1[0, 0])           # (1.24): scaled by h
    off1 = p.scene.arrows1.get_offsets()
    assert np.isclose(off1[1, 0], 3.0 * off1[0, 0])


def test_lifted_se2_preserves_body_and_spatial_velocity():
    p = LiftedSE2Panel()
    slide(p, theta=-0.8, u=1.1, v=-0.4, beta=2.1)
    g, hg, gh = p.scene.poses
    h = np.array([1.1, -0.4, 2.1])
    gd = p.scene.world_vels[0]
    # independent route: finite differences of the group operation
    assert np.allclose(p.scene.world_vels[1], SE2.numerical_left_lifted_action(h, g) @ gd, atol=1e-6)
    assert np.allclose(p.scene.world_vels[2], SE2.numerical_right_lifted_action(h, g) @ gd, atol=1e-6)
    assert np.allclose(p.scene.body_vels[1], p.scene.body_vels[0])        # left: same body velocity
    assert np.allclose(p.scene.spatial_vels[2], p.scene.spatial_vels[0])  # right: same spatial velocity
    # the corner arrows of gh are the rigid-motion velocities of g's motion at those points
    pts = np.vstack([gh[:2], SE2.act_on_points(gh, p.scene.bodies[2].outline)])
    eps = 1e-6
    g_next = g + eps * gd
    moved = SE2.act_on_points(SE2.compose(g_next, h), np.vstack([[0, 0], p.scene.bodies[2].outline]))
    fd = (moved - pts) / eps
    assert np.allclose(quiver_uv(p.scene.vel[2]) / LiftedSE2Scene.SCALE, fd, atol=1e-4)


def test_velocity_panel_world_body_spatial():
    p = VelocityPanel()
    g = np.array([-1.0, 0.8, 2.0])
    xi = np.array([0.4, -0.9, 1.1])
    slide(p, x=g[0], y=g[1], theta=g[2], vx=xi[0], vy=xi[1], w=xi[2])
    # world velocity by differentiating g exp(t xi) (independent of the lifted-action formulas)
    eps = 1e-6
    gdot = (SE2.compose(g, SE2.exp(eps * xi)) - SE2.compose(g, SE2.exp(-eps * xi))) / (2 * eps)
    assert np.allclose(quiver_uv(p.scene.world)[0], gdot[:2], atol=1e-6)
    # spatial velocity: velocity of the body point over the origin
    p_body = SE2.act_on_points(SE2.inverse(g), np.zeros(2))
    v0 = (SE2.act_on_points(SE2.compose(g, SE2.exp(eps * xi)), p_body)
          - SE2.act_on_points(SE2.compose(g, SE2.exp(-eps * xi)), p_body)) / (2 * eps)
    assert np.allclose(quiver_uv(p.scene.spatial)[0], v0, atol=1e-6)
    parts = quiver_uv(p.scene.spatial_parts)
    assert np.allclose(parts.sum(0), v0, atol=1e-6)
    assert np.allclose(quiver_uv(p.scene.at_e)[0], xi[:2])
    assert np.allclose(body_xy(p.scene.bodies[2]), p.scene.bodies[2].outline)


def test_adjoint_three_ways_agree():
    p = AdjointPanel()
    slide(p, x=2.0, y=-1.5, theta=-2.5, vx=0.3, vy=1.2, w=-0.8)
    assert p.scene.mismatch < 1e-6
    import scipy.linalg

    g = np.array([2.0, -1.5, -2.5])
    xi = np.array([0.3, 1.2, -0.8])
    G = SE2.matrix(g)
    assert np.allclose(SE2.vee(G @ SE2.hat(xi) @ np.linalg.inv(G)), p.scene.xi_s)   # Ad as conjugation
    assert np.allclose(p.scene.xi_s_fd, p.scene.xi_s, atol=1e-6)
    assert np.allclose(scipy.linalg.expm(SE2.hat(xi)), SE2.matrix(SE2.exp(xi)))


# ---------------------------------------------------------------------- 1.6 geodesics and exp
def test_helix_panel_follows_exp_and_flags_straight_line():
    p = slide(HelixPanel(), thetadot=1.5)
    x, y, z = p.scene.helix.get_data_3d()
    import scipy.linalg

    for k in (0, 40, 120):
        t = HelixScene.T[k]
        M = scipy.linalg.expm(t * SE2.hat([1.0, 0.0, 1.5]))
        assert np.allclose([x[k], y[k]], M[:2, 2])
        assert np.isclose(z[k], 1.5 * t)
    # the xy shadow is a circle through the origin with diameter 2/|thetadot|
    cx, cy = p.scene.centre.get_data()
    assert np.allclose(np.hypot(np.asarray(x) - cx[0], np.asarray(y) - cy[0]), 1 / 1.5)
    assert np.isclose(p.scene.geometry["diameter"], 2 / 1.5)
    slide(p, thetadot=0.0)
    assert p.scene.geometry["straight"] and not p.scene.centre.get_visible()
    assert np.all(np.isfinite(p.scene.helix.get_data_3d()[0]))


def test_puck_vs_arc_positions():
    p = slide(PuckArcPanel(), w=1.0, t=2.0)
    xi = np.array([1.0, 1.0, 1.0])
    assert np.allclose(p.scene.bodies[0].g, R2xS1.exp(2.0 * xi))
    import scipy.linalg

    M = scipy.linalg.expm(2.0 * SE2.hat(xi))
    assert np.allclose(SE2.matrix(p.scene.bodies[1].g), M)
    assert np.allclose(body_xy(p.scene.bodies[1]), SE2.act_on_points(SE2.from_matrix(M), p.scene.bodies[1].outline))
    assert np.allclose(p.scene.now_state.arc_body_velocity, xi)
    assert np.allclose(p.scene.now_state.puck_body_velocity[-1, :2],
                       SE2.matrix([0, 0, -2.0])[:2, :2] @ xi[:2])


def test_puck_vs_arc_animation_runs():
    from gm_core.drawing.toolkit.primitives import jshtml

    anim = puck_vs_arc_animation(frames=3)
    html = jshtml(anim).data
    assert "<img" in html or "data:image/png" in html


def test_rplus_geodesic_ratios_and_slopes():
    p = slide(RPlusGeodesicPanel(), xi=0.7)
    assert np.allclose(p.scene.ratios, np.exp(0.7))
    t, g = p.scene.curve.get_data()
    # slope of the curve = xi * g, the left-invariant field (1.46) with T_eL_g = g (1.24)
    assert np.allclose(np.gradient(g, t)[5:-5], 0.7 * g[5:-5], rtol=1e-3)
    uv = quiver_uv(p.scene.arrows)
    assert np.allclose(uv[:, 1] / uv[:, 0], p.scene.slopes)


def test_exp_four_ways_errors_and_paths():
    p = slide(ExpFourWaysPanel(), thetadot=2.0, n=16, side="right")
    import scipy.linalg

    E = scipy.linalg.expm(SE2.hat([1.0, 0.0, 2.0]))
    A = SE2.hat([1.0, 0.0, 2.0])
    prod = np.linalg.matrix_power(np.eye(3) + A / 16, 16)
    assert np.isclose(p.scene.final_error["product"], np.linalg.norm(prod - E))
    taylor = sum(np.linalg.matrix_power(A, k) / np.prod(np.arange(1, k + 1)) for k in range(16))
    assert np.isclose(p.scene.final_error["taylor"], np.linalg.norm(taylor - E), atol=1e-12)
    x, y = p.scene.path_lines["product"].get_data()
    assert len(x) == 17 and np.allclose([x[-1], y[-1]], prod[:2, 2])
    # errors fall as n grows for every method
    for _m, h in p.scene.histories.items():
        assert h.error[-1] < h.error[0]


def test_binomial_table_limits():
    rows = binomial_table(ns=(10, 10000), kmax=4)
    for n, k, c, ratio, inv_fact, _draft in rows:
        assert c == __import__("math").comb(n, k)
        if n == 10000:
            assert abs(ratio - inv_fact) < 1e-3
    n, k, c, ratio, inv_fact, draft = rows[2]   # n = 10, k = 2
    assert c == 45 and draft == 50.0             # the draft's n^k/k! is not C(n, k)


def test_jshtml_page_has_a_sized_first_frame_and_waits_for_its_elements():
    """The player page shows frame 0 in the <img> itself, at the figure's pixel width (<= 900),
    and starts the player only once its elements are in the document (issue 12: an animation
    laid out at 0 x 0 in JupyterLab)."""
    import base64
    import re
    import struct

    from gm_core.drawing.toolkit.primitives import jshtml

    html = jshtml(puck_vs_arc_animation(frames=3)).data
    img = re.search(r'<img id="_anim_img\w+" src="data:image/png;base64,([^"]+)" width="(\d+)"', html)
    assert img, "first frame not embedded in the <img>"
    png = base64.b64decode(img.group(1))
    w, h = struct.unpack(">II", png[16:24])
    assert int(img.group(2)) == w <= 900 and h > 0
    # the player finds its own elements (document.currentScript, else its id once attached)
    assert "document.currentScript" in html and "isConnected" in html


# ----------------------------------------------------------- observers, frames (section 1.5)
def _arrow(a):
    return np.asarray(a.get_offsets())[0], np.array([a.U[0], a.V[0]])


def test_observer_panel_body_velocity_stays_spatial_velocity_moves():
    from gm_core.manifolds.observers import icr

    p = ObserverPanel()
    g = p.scene.G
    xi = np.array([0.8, 0.3, 0.6])
    seen = []
    for h in ((-1.5, -1.0, 0.0), (0.5, -2.0, 1.2), (2.0, 2.0, -2.0)):
        p.set(hx=h[0], hy=h[1], htheta=h[2], vx=xi[0], vy=xi[1], w=xi[2])
        sc = p.scene
        assert sc.readout.get_text().startswith("ξ  = (+0.80, +0.30, +0.60)")     # same for every h
        # the vermillion arrow at h is the velocity of the body point over h's origin (first principles)
        o, v = _arrow(sc.v_spatial)
        assert np.allclose(o, h[:2])
        g_dot = SE2.body_to_world(g, xi)
        lever = np.array(h[:2]) - g[:2]
        assert np.allclose(v, g_dot[:2] + xi[2] * np.array([-lever[1], lever[0]]))
        # ... and written in h's axes it is Ad_{h^-1 g} xi, the matrix route
        M = np.linalg.inv(SE2.matrix(np.array(h))) @ SE2.matrix(g)
        assert np.allclose(sc.xi_s, SE2.vee(M @ SE2.hat(xi) @ np.linalg.inv(M)))
        assert sc.mismatch < 1e-12
        # the ICR star is one page point, the same from the body's and the observer's numbers
        x, y = sc.icr_mark.get_data()
        star = np.array([x[0], y[0]])
        assert np.allclose(star, SE2.act_on_points(g, icr(xi)[0]))
        assert np.allclose(star, SE2.act_on_points(np.array(h), icr(sc.xi_s)[0]))
        seen.append(sc.xi_s.copy())
    assert np.ptp(np.array(seen), axis=0)[:2].min() > 0.1                      # xi^s did change
    p.set(w=0.0)
    assert p.scene.at_infinity and not p.scene.icr_mark.get_visible()
    assert "ICR at infinity" in p.scene.icr_note.get_text()


def test_frames_panel_same_arrow_different_numbers():
    p = FramesPanel()
    p.set(t=2.5, bx=-1.0, by=2.0, btheta=0.7)
    sc = p.scene
    b = np.array([-1.0, 2.0, 0.7])
    (tip, v), (tip_b, v_b) = sc.in_a, sc.in_b
    # frame B's numbers, mapped back through B, give the same point and the same arrow
    assert np.allclose(SE2.act_on_points(b, tip_b), tip)
    assert np.allclose(SE2.matrix(b)[:2, :2] @ v_b, v)
    assert not np.allclose(tip_b, tip) and not np.allclose(v_b, v)
    # the arrow drawn is the nose's velocity: finite differences of its path
    eps = 1e-6

    def nose(t):
        g = SE2.compose(sc.G0, SE2.exp(t * sc.XI))
        return SE2.act_on_points(g, sc.TIP)

    o, arrow_v = _arrow(sc.tip_velocity)
    assert np.allclose(o, nose(2.5)) and np.allclose(arrow_v, (nose(2.5 + eps) - nose(2.5 - eps)) / (2 * eps),
                                                      atol=1e-6)
    # against the instantaneous body frame, the body moves with its body velocity
    assert np.allclose(sc.seen_from_instant, sc.XI)
    assert np.allclose(sc.inst.g, sc.g) and np.allclose(sc.body_frame.g, sc.g)


# ----------------------------------------------------- tangent spaces (figs 1.11-1.12), fig. 1.16
def test_tangent_space_panel_velocity_lies_in_the_tangent_spaces():
    from gm_core.manifolds import sphere_xyz

    p = TangentSpacePanel()
    for s, speed in ((0.8, 1.0), (2.9, -1.5), (5.5, 0.7)):
        p.set(s=s, speed=speed)
        sc = p.scene
        # circle: the arrow starts at the point and is tangent (perpendicular to the radius)
        o, v = np.asarray(sc.arrows2.get_offsets())[0], np.array([sc.arrows2.U[0], sc.arrows2.V[0]])
        assert np.allclose(o, [np.cos(s), np.sin(s)]) and abs(o @ v) < 1e-12
        assert np.isclose(np.linalg.norm(v), sc.ARROW * abs(speed))
        # the tangent line passes through the point along the arrow
        x, y = sc.tangent_line.get_data()
        d = np.array([x[1] - x[0], y[1] - y[0]])
        assert np.isclose(d[0] * v[1] - d[1] * v[0], 0.0) and np.allclose([(x[0] + x[1]) / 2, (y[0] + y[1]) / 2], o)
        # sphere: the velocity is the finite-difference derivative of the drawn curve ...
        eps = 1e-6

        def curve(u):
            return sphere_xyz(sc.AMP * np.sin(2 * u), u)

        fd = (curve(s + eps) - curve(s - eps)) / (2 * eps) * speed
        assert np.allclose(sc.sphere_v, fd, atol=1e-6)
        # ... it lies in the tangent plane patch, whose corners are all tangent to the sphere at p
        P = sc.sphere_p
        assert abs(P @ sc.sphere_v) < 1e-12
        assert np.allclose((sc.plane_corners - P) @ P, 0.0)
        shaft = sc.arrow_segments[0]                                    # what the Line3DCollection was given
        assert np.allclose(shaft[0], P) and np.allclose(shaft[1] - shaft[0], sc.ARROW * sc.sphere_v)


def test_surface_geodesics_panel_matches_the_exact_curves():
    p = SurfaceGeodesicsPanel()
    for heading in (0.0, 15.0, 60.0, 90.0, -40.0):
        p.set(heading_deg=heading, length=3 * np.pi)
        sc = p.scene
        h = np.deg2rad(heading)
        # sphere: every point on the great circle through p0 = (1, 0, 0) in the plane normal to
        # p0 x v0 (independent route: the plane equation), at unit speed
        S = sc.sph_points
        normal = np.cross([1.0, 0.0, 0.0], [0.0, np.cos(h), np.sin(h)])
        assert np.allclose(S @ normal, 0.0, atol=1e-12) and np.allclose(np.linalg.norm(S, axis=1), 1.0)
        assert np.allclose(np.linalg.norm(sc.sph_velocity, axis=1), 1.0)
        xs, ys, zs = sc.sph_curve.get_data_3d()
        assert np.allclose(np.c_[xs, ys, zs], S)
        # cylinder: height rises linearly with the angle travelled (a straight line unrolled)
        C = sc.cyl_points
        assert np.all(np.abs(C[:, 2]) <= sc.H + 1e-9)
        ang = np.unwrap(np.arctan2(C[:, 1], C[:, 0]))
        assert np.allclose(C[:, 2], np.sin(h) * sc.cyl_t) and np.allclose(ang, np.cos(h) * sc.cyl_t, atol=1e-9)
        for seg in sc.flat_segments:                                     # straight pieces on the flat strip
            d = np.diff(seg, axis=0)
            assert np.allclose(d[:, 0] * np.sin(h) - d[:, 1] * np.cos(h), 0.0, atol=1e-12)
    p.set(heading_deg=0.0)
    assert "loop" in p.scene.readout.get_text()
    p.set(heading_deg=90.0)
    assert "axial line" in p.scene.readout.get_text()


def test_tangent_space_panel_line_point_and_its_velocity():
    p = TangentSpacePanel()
    p.set(s=2.0, speed=1.5)
    sc = p.scene
    h = 1e-6
    x = lambda s: sc.LINE_RATE * (s - np.pi)                    # noqa: E731 (the drawn position rule)
    xs, ys = sc.points2.get_data()
    assert np.isclose(xs[1], x(2.0)) and np.isclose(ys[1], sc.LINE_Y)
    # the arrow on the line is dx/dt = dx/ds * ds/dt, by finite differences, and lies along the line
    assert np.isclose(sc.arrows2.U[1], (x(2.0 + h) - x(2.0 - h)) / (2 * h) * 1.5) and sc.arrows2.V[1] == 0.0


def test_velocity_panel_marks_the_icr_at_rest():
    p = VelocityPanel()
    p.set(x=1.2, y=0.6, theta=0.7, vx=0.8, vy=0.3, w=0.6)
    sc = p.scene
    x, y = sc.icr_marks[0].get_data()
    star = np.array([x[0], y[0]])
    # first principles: the plane point at the star has zero velocity, g_dot_xy + w x (star - g_xy) = 0
    lever = star - np.array([1.2, 0.6])
    assert np.allclose(sc.g_dot[:2] + 0.6 * np.array([-lever[1], lever[0]]), 0.0)
    assert np.allclose(sc.icr_marks[1].get_data(), sc.icr_marks[0].get_data())   # same point in (d)
    assert "ICR ★" in sc.texts[0].get_text()
    p.set(w=0.0)
    assert not any(m.get_visible() for m in sc.icr_marks)
    assert "ICR at infinity" in sc.texts[0].get_text()

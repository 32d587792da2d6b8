"""Headless (Agg) tests of the chapter-2 panels: set controls, check the artists moved where gm_core says."""
import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from gm_core import SE2  # noqa: E402
from gm_core import chains as C  # noqa: E402
from gm_core.chains.arms import (
    rp_arm_body_jacobians,
    rp_arm_frames,
    rr_arm_frames,
    rr_arm_jacobian,
    single_link_frames,
)
from gm_core.chains.holonomic import pin_constraints, pinned_pair
from gm_core.chains.three_link import beta_frame_velocity, com_frame, three_link_frames, three_link_jacobians
from gm_core.drawing.chains import link_outline
from gm_core.widgets import chains as chain_panels  # noqa: E402
from gm_core.widgets import holonomic, jacobians  # noqa: E402
from gm_core.widgets.base import PANELS  # noqa: E402
from gm_core.widgets.chains import (
    BetaFramePanel,
    JacobianMethodsPanel,
    OffsetRPArmPanel,
    RPArmPanel,
    RRArmPanel,
    SingleLinkPanel,
    ThreeLinkMobilePanel,
    ThreeLinkVelocityPanel,
    TwoLinkMobilePanel,
)
from gm_core.widgets.holonomic import BetaVelocityPanel, PinnedBodiesPanel, RelativePosePanel
from gm_core.widgets.jacobians import JacobianStepPanel

CH2_PANELS = [name for name, cls in PANELS.items()
              if cls.__module__ in {m.__name__ for m in (chain_panels, holonomic, jacobians)}]


def frame_offsets(fa):
    return np.asarray(fa.quiver.get_offsets())[0]


def frame_angle(fa):
    return np.arctan2(fa.quiver.V[0], fa.quiver.U[0])


def assert_frame_at(fa, g):
    np.testing.assert_allclose(frame_offsets(fa), g[:2], atol=1e-12)
    assert abs(SE2.difference(np.r_[0, 0, frame_angle(fa)], np.r_[0, 0, g[2]])[2]) < 1e-12


def test_all_ch2_panels_registered():
    assert {"SingleLinkPanel", "RRArmPanel", "RPArmPanel", "OffsetRPArmPanel", "TwoLinkMobilePanel",
            "ThreeLinkMobilePanel", "BetaFramePanel", "JacobianMethodsPanel", "ThreeLinkVelocityPanel"} <= set(CH2_PANELS)


@pytest.mark.parametrize("name", CH2_PANELS)
def test_panel_update_and_naive_update_run(name):
    p = PANELS[name]()
    rng = np.random.default_rng(0)
    n_before = len(p.ax.get_children())
    for _ in range(3):
        p.set(**p.sample_values(rng))
    assert len(p.ax.get_children()) == n_before   # update moves artists, never adds them
    p.fig.canvas.draw()
    p.naive_update(**p.values())
    p.fig.canvas.draw()


def test_rr_arm_follows_sliders():
    p = RRArmPanel()
    p.set(alpha1=0.7, alpha2=-1.2, alpha1_dot=0.3, alpha2_dot=-0.8)
    L = p.chain.lengths
    fr = rr_arm_frames([0.7, -1.2], L)
    assert_frame_at(p.art.frames["h"][1], fr[3])
    assert_frame_at(p.art.frames["f"][1], fr[2])
    np.testing.assert_allclose(p.art.link_corners(1), link_outline(fr[2, :2], fr[3, :2], p.art.width), atol=1e-12)
    v = rr_arm_jacobian([0.7, -1.2], L) @ [0.3, -0.8]   # (2.19)
    np.testing.assert_allclose(p.vel.points[0], fr[3, :2], atol=1e-12)
    np.testing.assert_allclose(p.vel.vectors[0], v[:2], atol=1e-12)
    np.testing.assert_allclose(np.asarray(p.vel.quiver.get_offsets())[0], fr[3, :2], atol=1e-12)


def test_single_link_follows_slider():
    p = SingleLinkPanel()
    p.controls["alpha"].value = 1.1
    _, h = single_link_frames(1.1, 1.0)
    assert_frame_at(p.art.frames["h"][0], h)


def test_rp_arms_follow_sliders():
    p = RPArmPanel()
    p.set(alpha=0.9, delta=0.4, alpha_dot=0.5, delta_dot=0.7)
    fr = rp_arm_frames(0.9, 0.4, *p.chain.lengths)
    assert_frame_at(p.art.frames["h"][1], fr["h2"])
    assert_frame_at(p.art.frames["f"][1], fr["g2"])
    q = rp_arm_body_jacobians(0.9, 0.4, *p.chain.lengths)["h2"] @ [0.5, 0.7]
    np.testing.assert_allclose(p.vel.vectors[0], SE2.body_to_world(fr["h2"], q)[:2], atol=1e-12)
    po = OffsetRPArmPanel()
    po.set(alpha=-0.4, delta=0.6, alpha_dot=1.0, delta_dot=-0.3)
    a = po.chain.offsets[0]
    fr = rp_arm_frames(-0.4, 0.6, *po.chain.lengths, offset=a)
    assert_frame_at(po.art.frames["h"][1], fr["h2"])
    assert_frame_at(po.art.frames["h"][0], fr["h1"])
    np.testing.assert_allclose(po.vel.vectors[0], po.closed_form[:2], atol=1e-12)


def test_three_link_mobile_follows_sliders_and_base_link():
    p = ThreeLinkMobilePanel()
    p.set(x=0.3, y=-0.2, theta=0.5, alpha1=0.8, alpha2=-0.3, base_link=1, shape="free")
    g = np.array([0.3, -0.2, 0.5])
    fr = three_link_frames([0.8, -0.3], (1, 1, 1), g)
    for i in range(3):
        assert_frame_at(p.art.frames["g"][i], fr["g"][i])
    assert_frame_at(p.body, g)
    # base link 0: the slider pose now places link 1's centre; the shape is unchanged
    p.set(base_link=0)
    fr0 = C.MobileChain((1, 1, 1), base_link=0).frames([0.8, -0.3], g)
    assert_frame_at(p.art.frames["g"][0], g)
    assert_frame_at(p.art.frames["g"][2], fr0["g"][2])
    rel = SE2.compose(SE2.inverse(fr0["g"][0]), fr0["g"][2])
    rel_mid = SE2.compose(SE2.inverse(fr["g"][0]), fr["g"][2])
    assert SE2.isclose(rel, rel_mid)
    # even and odd shapes of fig. 2.6
    p.set(base_link=1, x=0, y=0, theta=0, shape="even", alpha1=0.6)
    gs = p.art.last["g"]
    np.testing.assert_allclose(gs[0, :2] * [-1, 1], gs[2, :2], atol=1e-12)
    assert p.controls["alpha2"].disabled
    p.set(shape="odd")
    gs = p.art.last["g"]
    np.testing.assert_allclose(-gs[0, :2], gs[2, :2], atol=1e-12)


def test_three_link_mobile_greyed_alpha2_shows_the_angle_the_shape_uses():
    """Issue 36: under "odd" the greyed α₂ slider kept a value the shape did not use. Now it
    follows α₁ (±α₁), its readout is the relative angle of links 2 and 3 as drawn, moving it
    costs no second update, and back to "free" the chain does not jump."""
    p = ThreeLinkMobilePanel()
    p.set(alpha1=0.3, alpha2=-0.9, shape="free")
    updates = []
    real = p.scene.set
    p.scene.set = lambda **v: (updates.append(v), real(**v))[1]
    for shape, sign in (("odd", -1.0), ("even", 1.0)):
        for a1 in (0.6, -1.7, 2.2):
            updates.clear()
            p.set(shape=shape, alpha1=a1)
            a2 = p.controls["alpha2"]
            assert a2.disabled and a2.value == sign * a1 and p.values()["alpha2"] == sign * a1
            thetas = p.art.last["g"][:, 2]
            assert np.isclose(thetas[2] - thetas[1], a2.value)          # the readout is what is drawn
            assert len(updates) == 1, "moving the greyed slider updated the picture again"
    drawn = p.art.last["g"].copy()
    p.set(shape="free")
    assert not p.controls["alpha2"].disabled and p.controls["alpha2"].value == 2.2
    np.testing.assert_allclose(p.art.last["g"], drawn, atol=1e-12)
    labels = dict((v, k) for k, v in p.controls["shape"].options)
    assert labels["odd"] == "odd: α₂ = −α₁" and labels["even"] == "even: α₂ = α₁"


def test_two_link_mobile_matches_213():
    p = TwoLinkMobilePanel()
    p.set(x=0.0, y=0.0, theta=0.0, alpha1=0.9, base_link=0)
    a = 0.9
    assert_frame_at(p.art.frames["g"][1], np.array([0.5 + 0.5 * np.cos(a), 0.5 * np.sin(a), a]))


def test_beta_frame_panel():
    p = BetaFramePanel()
    p.set(alpha1=0.5, alpha2=1.0, frame="centre of mass")
    beta, _ = com_frame([0.5, 1.0], p.lengths)
    assert_frame_at(p.beta_art, beta)
    p.set(frame="sliders", beta_x=0.2, beta_y=-0.3, beta_theta=0.4)
    assert_frame_at(p.beta_art, np.array([0.2, -0.3, 0.4]))
    assert not p.controls["beta_x"].disabled


def test_jacobian_methods_panel_agree_live():
    p = JacobianMethodsPanel()
    rng = np.random.default_rng(4)
    for _ in range(5):
        p.set(**p.sample_values(rng))
        assert p.spread < 1e-12
        q = np.array([p.controls[f"q{i + 1}"].value for i in range(3)])
        qd = np.array([p.controls[f"q{i + 1}_dot"].value for i in range(3)])
        fd = C.finite_difference_jacobians(lambda x: p.chain.frames(x)["h"], q)[-1] @ qd
        for _m, arrow in p.arrows.items():
            np.testing.assert_allclose(arrow.vectors[0], fd[:2], atol=1e-7)


def test_three_link_velocity_panel():
    p = ThreeLinkVelocityPanel()
    p.set(alpha1=0.4, alpha2=-0.9, xi_x=0.2, xi_y=-0.1, xi_theta=0.5, alpha1_dot=0.3, alpha2_dot=-0.6)
    a = np.array([0.4, -0.9])
    u = np.array([0.2, -0.1, 0.5, 0.3, -0.6])
    fr = three_link_frames(a, p.lengths)
    J = three_link_jacobians(a, p.lengths)
    for i in range(3):
        world = SE2.body_to_world(fr["g"][i], J[i] @ u)
        np.testing.assert_allclose(p.arrows.vectors[i], world[:2], atol=1e-12)
        np.testing.assert_allclose(p.arrows.points[i], fr["g"][i, :2], atol=1e-12)


# ------------------------------------------------------------------ issue 13: frames and steps
def test_new_ch2_panels_registered():
    assert {"PinnedBodiesPanel", "RelativePosePanel", "BetaVelocityPanel", "JacobianStepPanel"} <= set(CH2_PANELS)


def test_pinned_bodies_panel_follows_the_pin():
    from gm_core.drawing.holonomic import BODY_OUTLINE

    p = PinnedBodiesPanel()
    p.set(pinned=True, x1=0.4, y1=-0.3, theta1=0.2, x2=1.0, y2=1.0, theta2=1.5)
    pair = pinned_pair([0.4, -0.3, 0.2], 1.3)
    for body, fa, g in zip(p.bodies, p.frames, pair):
        np.testing.assert_allclose(body.patch.get_xy()[:len(BODY_OUTLINE)], SE2.act_on_points(g, BODY_OUTLINE),
                                   atol=1e-12)
        assert_frame_at(fa, g)
    np.testing.assert_allclose(p.constraints, 0.0, atol=1e-15)
    assert p.pin.get_visible() and not p.gap.get_visible()
    assert p.controls["x2"].disabled and "+1.30" in p.text.get_text()
    p.set(pinned=False)
    g2 = np.array([1.0, 1.0, 1.5])
    assert_frame_at(p.frames[1], g2)
    np.testing.assert_allclose(p.constraints, pin_constraints(pair[0], g2))
    np.testing.assert_allclose(np.c_[p.gap.get_data()], [[0.4, -0.3], [1.0, 1.0]])
    assert p.gap.get_visible() and not p.pin.get_visible() and not p.controls["x2"].disabled
    assert "-0.60" in p.text.get_text() and "-1.30" in p.text.get_text()


def test_relative_pose_panel_draws_g_ab_and_checks_cancellation():
    p = RelativePosePanel()
    p.set(alpha1=0.7, alpha2=-1.1, frame="h2", seen_from="g2", via="g1")
    fr = p.chain.frames([0.7, -1.1])
    a, b, _c = fr["h"][1], fr["g"][1], fr["g"][0]
    rel = C.relative_pose(a, b)
    assert SE2.isclose(p.rel, rel) and SE2.isclose(p.chained, rel) and SE2.isclose(p.swapped, SE2.inverse(rel))
    np.testing.assert_allclose(p.arrow.points[0], b[:2], atol=1e-12)
    np.testing.assert_allclose(p.arrow.vectors[0], a[:2] - b[:2], atol=1e-12)
    np.testing.assert_allclose(p.route.vectors.sum(0), a[:2] - b[:2], atol=1e-12)     # b -> c -> a
    # the dashed path runs x along b's first axis, then y along its second, and ends at a
    xs, ys = p.coord_x.get_data()
    np.testing.assert_allclose([xs[1], ys[1]], SE2.act_on_points(b, [rel[0], 0.0]), atol=1e-12)
    xs, ys = p.coord_y.get_data()
    np.testing.assert_allclose([xs[-1], ys[-1]], a[:2], atol=1e-12)
    assert "%+.2f" % rel[0] in p.text.get_text()
    p.set(seen_from="e", frame="g1")
    assert SE2.isclose(p.rel, fr["g"][0])    # no second subscript: seen from the origin


def test_beta_velocity_panel_arrows_match_the_split_and_finite_differences():
    p = BetaVelocityPanel()
    v = dict(alpha1=0.5, alpha2=-0.7, alpha1_dot=0.9, alpha2_dot=-0.4, xi_x=0.3, xi_y=-0.2, xi_theta=0.6)
    p.set(**v)
    a, ad = np.array([0.5, -0.7]), np.array([0.9, -0.4])
    xi = np.array([0.3, -0.2, 0.6])
    beta, dbeta = com_frame(a, p.lengths)
    parts = beta_frame_velocity(beta, dbeta, xi, ad)
    s = p.scene.SCALE
    assert_frame_at(p.beta_art, beta)
    for k in ("carried", "body"):
        np.testing.assert_allclose(p.arrows[k].vectors[0], SE2.body_to_world(beta, parts[k])[:2], atol=1e-12)
        np.testing.assert_allclose(p.arrows[k].points[0], beta[:2], atol=1e-12)
    # head to tail: the shape part starts where the (drawn) carried arrow ends
    np.testing.assert_allclose(p.arrows["shape"].points[0], beta[:2] + s * p.arrows["carried"].vectors[0])
    # independent route: finite differences of the frame's world pose, middle link at e moving along exp(t xi)
    eps = 1e-6
    pose = lambda t: SE2.compose(SE2.exp(t * xi), com_frame(a + t * ad, p.lengths)[0])   # noqa: E731
    g_dot = SE2.difference(pose(eps), pose(-eps)) / (2 * eps)
    np.testing.assert_allclose(p.arrows["body"].vectors[0], g_dot[:2], atol=1e-7)
    # each dotted path passes through the frame's origin, tangent to its own arrow
    for path, k in ((p.path_carried, "carried"), (p.path_shape, "shape")):
        x, y = path.get_data()
        mid = len(x) // 2
        np.testing.assert_allclose([x[mid], y[mid]], beta[:2], atol=1e-12)
        d = np.array([x[mid + 1] - x[mid - 1], y[mid + 1] - y[mid - 1]])
        w = SE2.body_to_world(beta, parts[k])[:2]
        assert abs(d[0] * w[1] - d[1] * w[0]) < 1e-3 * np.hypot(*d) * np.hypot(*w) + 1e-12
    np.testing.assert_allclose(p.link_vel.vectors[0], xi[:2])


def test_jacobian_step_panel_accumulates_columns():
    p = JacobianStepPanel()
    q, qd = np.array([0.7, 0.4, -1.0]), np.array([0.5, -0.8, 1.3])
    vals = {**{f"q{i + 1}": q[i] for i in range(3)}, **{f"q{i + 1}_dot": qd[i] for i in range(3)}}
    Jb = p.chain.jacobians(q, method="direct", velocity="body")["h"][-1]
    tip = p.chain.end_effector(q)
    s = p.scene.scale
    for k in range(4):
        p.set(step=k, **vals)
        np.testing.assert_allclose(p.partial, Jb[:, :k] @ qd[:k], atol=1e-12)
        drawn = np.c_[p.steps.U, p.steps.V]
        np.testing.assert_allclose(drawn[:k], s * SE2.body_to_world(tip, (Jb * qd).T[:k])[:, :2], atol=1e-12)
        np.testing.assert_allclose(drawn[k:], 0.0)
        np.testing.assert_allclose(np.c_[p.total.U, p.total.V][0], s * SE2.body_to_world(tip, p.partial)[:2],
                                   atol=1e-12)
        assert p.ring.get_visible() == (k > 0)
        if k:   # frames before joint k still, frames from f_k on move with the joint's velocity
            carried = np.c_[p.carried.U, p.carried.V]
            np.testing.assert_allclose(carried[:2 * (k - 1)], 0.0)
            np.testing.assert_allclose(carried[-1], drawn[k - 1], atol=1e-12)
    # the last step is the whole end-effector velocity: finite differences of forward kinematics
    fd = C.finite_difference_jacobians(p.chain.end_effector, q) @ qd
    np.testing.assert_allclose(np.c_[p.total.U, p.total.V][0], s * fd[:2], atol=1e-6)
    np.testing.assert_allclose(np.c_[p.target.U, p.target.V][0], s * fd[:2], atol=1e-6)
    with pytest.raises(ValueError, match="step"):
        p.scene.set(step=5, **vals)

"""Headless (Agg) tests of the chapter-2 panels: set controls, check the artists moved where gm_core says."""
import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from gm_core import SE2  # noqa: E402
from gm_core import chains as C  # noqa: E402
from gm_core.drawing.ch2 import link_outline  # noqa: E402
from gm_core.widgets import ch2  # noqa: E402
from gm_core.widgets.base import PANELS  # noqa: E402

CH2_PANELS = [name for name, cls in PANELS.items() if cls.__module__ == ch2.__name__]


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
    p = ch2.RRArmPanel()
    p.set(alpha1=0.7, alpha2=-1.2, alpha1_dot=0.3, alpha2_dot=-0.8)
    L = p.chain.lengths
    fr = C.rr_arm_frames([0.7, -1.2], L)
    assert_frame_at(p.art.frames["h"][1], fr[3])
    assert_frame_at(p.art.frames["f"][1], fr[2])
    np.testing.assert_allclose(p.art.link_corners(1), link_outline(fr[2, :2], fr[3, :2], p.art.width), atol=1e-12)
    v = C.rr_arm_jacobian([0.7, -1.2], L) @ [0.3, -0.8]   # (2.19)
    np.testing.assert_allclose(p.vel.points[0], fr[3, :2], atol=1e-12)
    np.testing.assert_allclose(p.vel.vectors[0], v[:2], atol=1e-12)
    np.testing.assert_allclose(np.asarray(p.vel.quiver.get_offsets())[0], fr[3, :2], atol=1e-12)


def test_single_link_follows_slider():
    p = ch2.SingleLinkPanel()
    p.controls["alpha"].value = 1.1
    _, h = C.single_link_frames(1.1, 1.0)
    assert_frame_at(p.art.frames["h"][0], h)


def test_rp_arms_follow_sliders():
    p = ch2.RPArmPanel()
    p.set(alpha=0.9, delta=0.4, alpha_dot=0.5, delta_dot=0.7)
    fr = C.rp_arm_frames(0.9, 0.4, *p.chain.lengths)
    assert_frame_at(p.art.frames["h"][1], fr["h2"])
    assert_frame_at(p.art.frames["f"][1], fr["g2"])
    q = C.rp_arm_body_jacobians(0.9, 0.4, *p.chain.lengths)["h2"] @ [0.5, 0.7]
    np.testing.assert_allclose(p.vel.vectors[0], SE2.body_to_world(fr["h2"], q)[:2], atol=1e-12)
    po = ch2.OffsetRPArmPanel()
    po.set(alpha=-0.4, delta=0.6, alpha_dot=1.0, delta_dot=-0.3)
    a = po.chain.offsets[0]
    fr = C.rp_arm_frames(-0.4, 0.6, *po.chain.lengths, offset=a)
    assert_frame_at(po.art.frames["h"][1], fr["h2"])
    assert_frame_at(po.art.frames["h"][0], fr["h1"])
    np.testing.assert_allclose(po.vel.vectors[0], po.closed_form[:2], atol=1e-12)


def test_three_link_mobile_follows_sliders_and_base_link():
    p = ch2.ThreeLinkMobilePanel()
    p.set(x=0.3, y=-0.2, theta=0.5, alpha1=0.8, alpha2=-0.3, base_link=1, shape="free")
    g = np.array([0.3, -0.2, 0.5])
    fr = C.three_link_frames([0.8, -0.3], (1, 1, 1), g)
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


def test_two_link_mobile_matches_213():
    p = ch2.TwoLinkMobilePanel()
    p.set(x=0.0, y=0.0, theta=0.0, alpha1=0.9, base_link=0)
    a = 0.9
    assert_frame_at(p.art.frames["g"][1], np.array([0.5 + 0.5 * np.cos(a), 0.5 * np.sin(a), a]))


def test_beta_frame_panel():
    p = ch2.BetaFramePanel()
    p.set(alpha1=0.5, alpha2=1.0, frame="centre of mass")
    beta, _ = C.com_frame([0.5, 1.0], p.lengths)
    assert_frame_at(p.beta_art, beta)
    p.set(frame="sliders", beta_x=0.2, beta_y=-0.3, beta_theta=0.4)
    assert_frame_at(p.beta_art, np.array([0.2, -0.3, 0.4]))
    assert not p.controls["beta_x"].disabled


def test_jacobian_methods_panel_agree_live():
    p = ch2.JacobianMethodsPanel()
    rng = np.random.default_rng(4)
    for _ in range(5):
        p.set(**p.sample_values(rng))
        assert p.spread < 1e-12
        q = np.array([p.controls[f"q{i + 1}"].value for i in range(3)])
        qd = np.array([p.controls[f"q{i + 1}_dot"].value for i in range(3)])
        fd = C.finite_difference_jacobians(lambda x: p.chain.frames(x)["h"], q)[-1] @ qd
        for m, arrow in p.arrows.items():
            np.testing.assert_allclose(arrow.vectors[0], fd[:2], atol=1e-7)


def test_three_link_velocity_panel():
    p = ch2.ThreeLinkVelocityPanel()
    p.set(alpha1=0.4, alpha2=-0.9, xi_x=0.2, xi_y=-0.1, xi_theta=0.5, alpha1_dot=0.3, alpha2_dot=-0.6)
    a = np.array([0.4, -0.9])
    u = np.array([0.2, -0.1, 0.5, 0.3, -0.6])
    fr = C.three_link_frames(a, p.lengths)
    J = C.three_link_jacobians(a, p.lengths)
    for i in range(3):
        world = SE2.body_to_world(fr["g"][i], J[i] @ u)
        np.testing.assert_allclose(p.arrows.vectors[i], world[:2], atol=1e-12)
        np.testing.assert_allclose(p.arrows.points[i], fr["g"][i, :2], atol=1e-12)

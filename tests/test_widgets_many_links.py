"""Notebook 11's panels, headless: ChainSlicePanel, WaveGaitPanel and OptimalGaitPanel (live optimisation)."""
import os

os.environ.setdefault("MPLBACKEND", "Agg")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from gm_core.geometry import efficiency, wave_start  # noqa: E402
from gm_core.systems import shape_slice  # noqa: E402
from gm_core.widgets.link_chain import ChainSlicePanel, OptimalGaitPanel, WaveGaitPanel  # noqa: E402


def test_chain_slice_panel_shows_the_slice_of_the_designed_chain():
    p = ChainSlicePanel(links=5, row=2)
    p.set(axis1=2, axis2=3)
    assert p.scene.system.n_links == 5 and p.scene.pair == (1, 2)
    # the map is the slice's curvature: the (2, 3) component of the chain's 2-form on the slice
    F = p.scene.map.values()[..., 2]
    lim = p.scene.limits
    q = np.array([0.4, -0.7])
    full = np.zeros(4)
    full[[1, 2]] = q
    F_chain = p.scene.system.constraint_curvature(full)[2, 1, 2]
    sl = shape_slice(p.scene.system, None, (1, 2), limits=lim)
    np.testing.assert_allclose(sl.constraint_curvature(q)[2], F_chain, atol=1e-6)
    assert np.isfinite(F).all() and F.shape == (p.scene.n_map, p.scene.n_map)
    p.set(links=3, axis1=1, axis2=2, row=0)       # the axes clamp to the joints there are
    assert p.controls["axis1"].max == 2 and p.scene.pair == (0, 1)
    # formulas in mathtext, as in notebooks 08-10: the row's title and the slice's joints
    assert r"row $\xi^x$" in p.scene.titles[0].text and r"row $\xi^x$" in p.scene.titles[1].text
    p.set(links=5)
    p.set(axis1=2, axis2=4)
    ax = p.scene.axes[1]
    assert (ax.get_xlabel(), ax.get_ylabel()) == (r"$\alpha_2$", r"$\alpha_4$")
    assert [label for label, _ in p.controls["row"].options] == ["ξˣ (forward)", "ξʸ (sideways)", "ξᶿ (turning)"]


def test_chain_slice_panel_refuses_one_joint_twice_on_the_figure():
    """Issue 36: joint 1 = joint 2 was silently turned into another slice. The math layer refuses
    it naming the argument; the panel hides the field and the map and says why on the figure,
    its sliders showing what the student chose; two different joints bring the slice back."""
    from gm_core.drawing.link_chain import design_chain

    with pytest.raises(ValueError, match="axes must name two different shape variables"):
        shape_slice(design_chain(5), None, (1, 1))
    p = ChainSlicePanel(links=5, row=0)
    p.set(axis1=2, axis2=2)
    assert (p.controls["axis1"].value, p.controls["axis2"].value) == (2, 2)
    assert p.scene.same and p.scene.slice is None
    for flag in p.scene.flags:
        assert flag.visible and "joint 2 twice" in flag.text.get_text() and "two different joints" in flag.text.get_text()
    assert not p.scene.field.quiver.get_visible() and not p.scene.map.image.get_visible()
    assert not p.scene.field.zero_note.get_visible() and not p.scene.field.scale_note.get_visible()
    p.set(axis2=4)
    assert not p.scene.same and p.scene.pair == (1, 3) and not any(f.visible for f in p.scene.flags)
    assert p.scene.field.quiver.get_visible() and p.scene.map.image.get_visible()


def test_chain_slice_panel_keeps_two_joints_when_the_chain_gets_shorter():
    """Fewer links move a slice joint beyond the chain's end onto its last joint; if both land on
    one joint, joint 1 takes the one before: the sliders and the slice drawn agree."""
    p = ChainSlicePanel(links=7, row=2)
    p.set(axis1=5, axis2=6)
    p.set(links=4)
    assert [p.controls[k].max for k in ("axis1", "axis2")] == [3, 3]
    assert (p.controls["axis1"].value, p.controls["axis2"].value) == (2, 3)
    assert p.scene.pair == (1, 2) and not p.scene.same
    assert (p.values()["axis1"], p.values()["axis2"]) == (2, 3)
    p.set(links=7, axis1=6, axis2=2)
    p.set(links=3)
    assert (p.controls["axis1"].value, p.controls["axis2"].value) == (1, 2) and p.scene.pair == (0, 1)


def test_wave_gait_panel_moves_only_with_a_lag():
    p = WaveGaitPanel(links=5, amplitude=0.9)
    p.set(lag=0.0)
    assert np.abs(p.scene.g[:2]).max() < 1e-9
    p.set(lag=1.2)
    assert np.hypot(*p.scene.g[:2]) > 0.1


def test_optimal_gait_panel_runs_the_optimisation_with_progress_and_keeps_it():
    p = OptimalGaitPanel(links=3)
    start = efficiency(p.scene.system, wave_start(2), check=False)
    assert np.isclose(p.scene.start_efficiency, start) and "optimise" in p.scene.text.text
    assert p.scene.result is None and p.bar.value == 0
    seen = []
    p.bar.observe(lambda ch: seen.append(ch["new"]), names="value")
    res = p.run()
    assert res.efficiency > start and res.nit >= 2
    assert len(seen) >= 3 and seen[-1] == p.bar.max               # the bar moved step by step
    assert "done" in p.status.value and f"{res.efficiency:.4f}" in p.status.value
    assert "best" in p.scene.text.text and not p.button.disabled
    drawn = p.scene.best_lines[0].get_ydata()
    np.testing.assert_allclose(drawn, res.gait(np.linspace(0, 2 * np.pi, 121))[:, 0])
    p.set(links=4)                       # another design: back to its start, nothing stored
    assert p.scene.result is None and p.bar.value == 0 and len(p.scene.best_lines[0].get_xdata()) == 0
    p.set(links=3)                       # the first design again: its result is kept
    assert p.scene.result is res and "optimised" in p.status.value


def test_optimal_gait_panel_says_done_only_after_drawing_the_best_gait():
    """Issue 36: "done" appeared a second or two before the figure. The picture of the best
    gait is drawn (and, on a live canvas, sent) before the status says "done"."""
    p = OptimalGaitPanel(links=3)
    events = []
    p.fig.canvas.mpl_connect("draw_event", lambda e: events.append(
        ("draw", p.status.value, len(p.scene.best_lines[0].get_xdata()))))
    p.status.observe(lambda ch: events.append(("status", ch["new"], None)), names="value")
    res = p.run()
    done = next(i for i, e in enumerate(events) if e[0] == "status" and e[1].startswith("done"))
    drawn = [i for i, e in enumerate(events) if e[0] == "draw" and e[2] > 0]
    assert drawn and drawn[-1] < done, f"'done' before the best gait was drawn: {events}"
    assert events[drawn[-1]][1] == "drawing the best gait …"
    assert f"{res.efficiency:.4f}" in p.status.value and "cell below" in p.status.value


def test_optimal_gait_panel_fits_a_screen_and_its_animation_is_the_course_player():
    """Issue 36: the panel drew its animation inside itself (taller than a 1366 x 768 screen,
    and it did not start). The panel holds no animation now; ``animation()`` is the course's
    player, with a play button, for a cell of its own below the panel."""
    import ipywidgets as W

    p = OptimalGaitPanel(links=3)
    tree, todo = [], [p.widget]
    while todo:
        w = todo.pop()
        tree.append(w)
        todo += list(getattr(w, "children", ()))
    # one Output at most: the figure's static view on a non-widget canvas (Agg here), no player
    outputs = [w for w in tree if isinstance(w, W.Output)]
    assert len(outputs) <= 1 and not isinstance(p.fig.canvas, W.DOMWidget)
    assert p.button in tree and p.status in tree
    assert p.fig.get_figheight() * p.fig.dpi <= 400          # with its controls, well under 650 px
    p.run()
    page = p.animation(n_frames=5, cycles=1).data
    assert 'class="gm-anim-play"' in page and 'data-frames="5"' in page
    assert "frames-kept-in-memory" not in page and "<img" in page


def test_optimal_gait_panel_animation_and_bad_values():
    p = OptimalGaitPanel(links=3)
    from gm_core.drawing.toolkit.primitives import jshtml

    anim, fig, traj = p.scene.animation(n_frames=6, cycles=1)
    assert traj.r.shape == (6, 2)
    assert "<img" in jshtml(anim).data          # plays without a kernel
    with pytest.raises(ValueError, match="links"):
        p.scene.set(links=9)
    with pytest.raises(ValueError, match="order"):
        p.scene.set(order=5)


def test_wave_readout_never_prints_negative_zero():
    """A travelling wave of an odd chain ends on a y and θ that are zero up to round-off; the
    readout shows them as +0.000 (rounded as shown), never -0.000."""
    from gm_core.drawing.toolkit import signed

    assert signed([-1e-17, -0.0004, 0.0005, -1.25]) == "+0.000, +0.000, +0.001, -1.250"
    for links in (3, 4, 5):
        p = WaveGaitPanel(links=links, lag=0.0)
        text = p.scene.text.get_text()
        assert text.startswith("g(T) = (") and "-0.000" not in text, text


def test_gait_curves_have_a_key_naming_each_joint_in_its_colour():
    for panel, links in ((WaveGaitPanel(links=3), (3, 7, 5)), (OptimalGaitPanel(links=3), (6, 4))):
        for n in links:
            panel.set(links=n)
            curves = [ln for ln in (getattr(panel.scene, "lines", None) or panel.scene.start_lines)
                      if len(ln.get_xdata())]
            shown_names = [t for t in panel.scene.names if t.get_visible()]
            assert [t.get_text() for t in shown_names] == [rf"$\alpha_{k + 1}$" for k in range(n - 1)]
            assert [t.get_color() for t in shown_names] == [c.get_color() for c in curves]


# Machado, Oliveira & Fernandes (2009), "A physiologically-based model for simulation of color vision
# deficiency", severity 1.0: linear-RGB matrices for protanopia, deuteranopia and tritanopia
_CVD = {
    "normal vision": np.eye(3),
    "protanopia": np.array([[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                            [-0.003882, -0.048116, 1.051998]]),
    "deuteranopia": np.array([[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                              [-0.011820, 0.042940, 0.968881]]),
    "tritanopia": np.array([[1.255528, -0.076749, -0.178779], [-0.078411, 0.930809, 0.147602],
                            [0.004733, 0.691367, 0.303900]]),
}


def _lab(colours, vision):
    """CIELAB (D65) of sRGB ``colours`` as seen with ``vision`` (sRGB -> linear -> CVD -> XYZ -> Lab)."""
    from matplotlib.colors import to_rgb

    c = np.array([to_rgb(x) for x in colours])
    lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    lin = np.clip(lin @ _CVD[vision].T, 0.0, 1.0)
    xyz = lin @ np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]]).T
    xyz = xyz / np.array([0.95047, 1.0, 1.08883])
    f = np.where(xyz > 216 / 24389, np.cbrt(xyz), (24389 / 27 * xyz + 16) / 116)
    return np.stack([116 * f[:, 1] - 16, 500 * (f[:, 0] - f[:, 1]), 200 * (f[:, 1] - f[:, 2])], -1)


def test_joint_colours_are_sequential_and_neighbours_are_told_apart_in_every_colour_vision():
    """Issue 36: α₁ and α₆ were near-identical blues (the Okabe-Ito blue and sky blue). The joints
    now take a sequential colour-vision-safe map: lightness rises from joint 1 to the last in
    normal vision and in the three dichromacies, by at least 10 CIELAB units per joint and with
    neighbours at least 12 units apart (ΔE*ab), for every chain the panels draw (up to six
    joints); the panels and the animation use exactly these colours."""
    from gm_core.drawing.link_chain import animate_chain_gait, joint_colours
    from gm_core.geometry import chain_stroke, chain_swimmer

    for n in range(2, 7):
        colours = joint_colours(n)
        for vision in _CVD:
            lab = _lab(colours, vision)
            steps = np.diff(lab[:, 0])
            gaps = np.linalg.norm(np.diff(lab, axis=0), axis=1)
            assert steps.min() > 10, f"{n} joints, {vision}: lightness steps {steps.round(1)}"
            assert gaps.min() > 12, f"{n} joints, {vision}: neighbours only {gaps.min():.1f} apart"
            assert lab[:, 0].max() < 82, f"{n} joints, {vision}: the last joint too pale on white"
    p = WaveGaitPanel(links=7)
    drawn = [ln.get_color() for ln in p.scene.lines if len(ln.get_xdata())]
    assert drawn == joint_colours(6)
    p.set(links=4)
    assert [ln.get_color() for ln in p.scene.lines[:3]] == joint_colours(3)
    from gm_core.drawing.toolkit.primitives import jshtml

    anim, fig, _ = animate_chain_gait(chain_swimmer(5), chain_stroke(5), n_frames=2, cycles=1)
    assert [ln.get_color() for ln in fig.axes[0].get_lines()[:4]] == joint_colours(4)
    assert "<img" in jshtml(anim).data

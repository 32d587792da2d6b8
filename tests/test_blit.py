"""Blitted frames must look exactly like full redraws, for every registered panel.

A live panel renders slider changes by blitting (gm_core.drawing.toolkit.blit). Here each panel is built
on Agg with blitting on and receives a sequence of changes; its last blitted picture is compared
pixel by pixel with a full redraw of the same figure in the same state (the blitter disconnected,
so every artist is drawn from scratch). One panel per comparison, not two, and one panel per name
for the two tests that move every panel (``panel``: first the full-draw test moves it through
three states, then the comparison moves it through four more and compares).
"""
import matplotlib.pyplot as plt
import numpy as np
import pytest

from gm_core.widgets.base import Panel, all_panels

PANELS = all_panels()


@pytest.fixture
def blitting(monkeypatch):
    monkeypatch.setattr(Panel, "blit_everywhere", True)


def _picture(fig):
    return np.asarray(fig.canvas.buffer_rgba()).copy()


@pytest.fixture(scope="module", params=sorted(PANELS))
def panel(request):
    """``(name, panel)``: one panel of each registered class, built with blitting on, shared by the
    tests below that take it (pytest runs them together, one name after the other, in file order);
    closed after the last of them."""
    name = request.param
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Panel, "blit_everywhere", True)
        p = PANELS[name]()
    p.fig.gm_keep_open = True     # not closed by conftest's _close_figures between the tests
    yield name, p
    p.fig.gm_keep_open = False
    plt.close(p.fig)


def test_full_draw_leaves_figure_clean(panel):
    """The draw callback must not touch the figure: a figure left stale after a draw makes ipympl
    request another draw, forever (a redraw loop that only shows in a live browser)."""
    name, p = panel
    rng = np.random.default_rng(5)
    for _ in range(3):
        p.refresh(**p.sample_values(rng))
        p.fig.canvas.draw()
        assert not p.fig.stale, f"{name}: figure is stale right after a full draw"


_LAST = {}   # the panel the fixture gave before this one (one kept: each holds a whole figure)


def test_the_panel_before_has_its_widgets_closed(panel):
    """A shared panel's widgets are closed when the fixture moves on to the next name
    (tests/conftest.py: pytest_fixture_post_finalizer): ipywidgets keeps a widget, and with it
    its panel's figure, until it is closed, and a worker would keep every panel of this file."""
    name, p = panel
    widgets = [c for c in p.controls.values() if hasattr(c, "comm")]
    assert widgets and all(c.comm is not None for c in widgets), f"{name}: its own widgets are open while in use"
    before = _LAST.get("panel")
    if before is not None and before[1] is not p:
        assert all(c.comm is None for c in before[1].controls.values() if hasattr(c, "comm")), \
            f"{before[0]}: its widgets are still open after the fixture moved on to {name}"
    _LAST["panel"] = (name, p)


def test_every_frame_leaves_the_figure_clean(panel):
    """After each update (blitted or drawn in full) nothing is left stale: in a notebook, pyplot
    redraws a stale figure when the kernel goes idle (draw_all after every comm message), a
    round trip through the browser and one more picture per slider move. (An axis label that
    changed is not blitted: it makes the frame a full draw.)"""
    name, p = panel
    p.fig.canvas.draw()
    rng = np.random.default_rng(11)
    for _ in range(4):
        p.refresh(**p.sample_values(rng))
        assert not p.fig.stale, f"{name}: the figure is stale after an update"


def test_blitted_frames_match_full_redraws(panel):
    name, p = panel
    try:
        p.fig.canvas.draw()
        drawn = (p.blitter.full_draws + p.blitter.blits) if p.blitter is not None else 0
        rng = np.random.default_rng(3)
        for _ in range(4):
            p.refresh(**p.sample_values(rng))
        blitted = _picture(p.fig)
        if p.blitter is not None:
            assert p.blitter.full_draws + p.blitter.blits - drawn >= 4
            p.blitter.disconnect()   # nothing animated any more: the next draw renders every artist
        p.fig.canvas.draw()          # the full redraw of the very same state, from scratch
        full = _picture(p.fig)
        assert blitted.shape == full.shape
        differing = (blitted != full).any(-1).mean()
        # Moving artists are drawn above static ones, so a sliver may differ where a static
        # artist overlapped a moving one; anything more means a stale or missing artist.
        assert differing < 5e-3, f"{name}: {differing:.2%} of pixels differ from a full redraw"
    finally:
        p.fig.gm_keep_open = False   # the last test using this panel


def test_the_blit_comparison_sees_a_stale_artist(monkeypatch):
    """The reference above is the same figure drawn in full: a moved artist the blitter does not
    repaint must show as a difference (here the readout is taken out of the blitter's hands)."""
    from gm_core.widgets.start import FrameDemo

    monkeypatch.setattr(Panel, "blit_everywhere", True)
    p = FrameDemo()
    p.fig.canvas.draw()
    p.refresh(x=0.2)                 # learns the moving artists
    p.blitter.dynamic = [a for a in p.blitter.dynamic if a is not p.body.patch]
    p.refresh(x=1.4)                 # the body moves, but only the others are repainted
    blitted = _picture(p.fig)
    p.blitter.disconnect()
    p.body.patch.set_animated(False)
    p.fig.canvas.draw()
    assert (blitted != _picture(p.fig)).any(-1).mean() > 5e-3
    plt.close(p.fig)


def test_blitting_redraws_only_moving_artists(blitting):
    from gm_core.widgets.start import FrameDemo

    p = FrameDemo()
    p.fig.canvas.draw()
    p.refresh(x=0.2)            # first change: learns which artists move (one full draw)
    draws = p.blitter.full_draws
    for x in (0.4, 0.6, 0.8):
        p.refresh(x=x)
    assert p.blitter.full_draws == draws and p.blitter.blits == 3
    assert p.body.patch in p.blitter.dynamic and p.frame.quiver in p.blitter.dynamic
    assert p.ax.xaxis not in p.blitter.dynamic
    # Changing the axis limits invalidates the background: the next frame is a full draw.
    p.ax.set_xlim(-3, 3)
    p.refresh(x=1.0)
    assert p.blitter.full_draws == draws + 1
    plt.close(p.fig)


def test_no_blitting_on_static_canvases():
    from gm_core.widgets.start import FrameDemo

    p = FrameDemo()
    assert p.blitter is None   # Agg in tests: plain updates, pictures drawn on demand
    plt.close(p.fig)


def test_saving_a_blitted_figure_draws_each_artist_once(blitting, tmp_path):
    """savefig of a live panel equals the picture of a panel that never blitted."""
    import matplotlib.image as mpimg

    from gm_core.widgets.start import FrameDemo

    Panel.blit_everywhere = True
    live = FrameDemo()
    live.fig.canvas.draw()
    for x in (0.3, 0.7):
        live.refresh(x=x)
    Panel.blit_everywhere = False
    plain = FrameDemo()
    plain.update(**{**live.values(), "x": 0.7})   # refresh(x=...) drew x without moving the slider
    live.fig.savefig(tmp_path / "live.png")
    plain.fig.savefig(tmp_path / "plain.png")
    a, b = mpimg.imread(tmp_path / "live.png"), mpimg.imread(tmp_path / "plain.png")
    assert a.shape == b.shape and np.abs(a - b).max() < 1e-6
    # Blitting still works after the save, from an unchanged background.
    blits = live.blitter.blits
    live.refresh(x=0.9)
    assert live.blitter.blits == blits + 1
    plt.close(live.fig)
    plt.close(plain.fig)



def test_a_moving_image_keeps_its_axes_frame(blitting):
    """The lab's map (an image filling its axes) moves when the system changes; blitted after
    that, it must not be painted over its axes' frame (a line drawn above it in a full draw)."""
    from gm_core.widgets.catalog import LabPanel

    p = LabPanel()
    p.fig.canvas.draw()
    p.controls["system"].value = "three_link_HighRe"       # the map changes: it moves from now on
    for v in (0.1, 0.3, 0.2):
        p.controls["c1"].value = v                          # gait moves: blits over the new map
    blitted = _picture(p.fig)
    assert p.blitter.blits >= 2
    p.blitter.disconnect()
    p.fig.canvas.draw()
    assert (blitted != _picture(p.fig)).any(-1).sum() == 0
    plt.close(p.fig)

"""Headless test of the start page's demo panel: sliders move the artists by the SE(2) amount."""
import numpy as np

from gm_core import SE2
from gm_core.drawing.toolkit.primitives import BodyArtist
from gm_core.widgets.base import all_panels
from gm_core.widgets.start import FrameDemo


def test_sliders_move_body_and_frame():
    p = FrameDemo()
    p.controls["x"].value = -1.0
    p.controls["theta"].value = np.pi / 2
    g = np.array([-1.0, p.controls["y"].value, np.pi / 2])
    expected = SE2.act_on_points(g, BodyArtist.triangle(0.5))
    np.testing.assert_allclose(p.body.patch.get_xy()[:3], expected, atol=1e-12)
    np.testing.assert_allclose(p.frame.quiver.get_offsets()[0], g[:2])
    # The x axis arrow of the frame points along +y after a quarter turn.
    np.testing.assert_allclose([p.frame.quiver.U[0], p.frame.quiver.V[0]], [0.0, 0.6], atol=1e-12)


def test_set_updates_once_and_rejects_unknown_controls():
    p = FrameDemo()
    p.set(x=0.0, y=2.0, theta=np.pi)
    np.testing.assert_allclose(p.frame.g, [0.0, 2.0, np.pi])
    try:
        p.set(z=1.0)
    except ValueError as e:
        assert "unknown control 'z'" in str(e)
    else:
        raise AssertionError("set() accepted an unknown control")


def _picture(panel):
    panel.fig.canvas.draw()
    return np.asarray(panel.fig.canvas.buffer_rgba()).copy()


def test_naive_update_draws_the_same_picture():
    """The clear-and-replot baseline of the latency benchmark draws what the in-place update draws,
    pixel for pixel, and both differ from the starting picture."""
    moved, replotted = FrameDemo(), FrameDemo()
    start = _picture(moved)
    moved.set(x=0.5, y=0.5, theta=0.3)
    replotted.naive_update(x=0.5, y=0.5, theta=0.3)
    a, b = _picture(moved), _picture(replotted)
    assert a.shape == b.shape and not np.array_equal(a, start)
    assert np.array_equal(a, b), f"{np.count_nonzero((a != b).any(axis=2))} pixels differ"
    assert "FrameDemo" in all_panels()


def test_set_survives_a_stale_echo_from_the_browser(monkeypatch):
    """Run All: set() runs before the browser renders the slider; the slider's first echo (its
    old value) must not overwrite the value set from code (issue 12, the start page race)."""
    p = FrameDemo()
    before = p.controls["theta"].value
    p.set(x=0.0, y=2.0, theta=np.pi)
    p.controls["theta"].value = before            # what a late initial echo does
    assert p.controls["theta"].value == np.pi
    np.testing.assert_allclose(p.frame.g, [0.0, 2.0, np.pi])
    # after the echo window a student's drag back to that value is an ordinary change
    monkeypatch.setattr(FrameDemo, "echo_window", 0.0)
    p.controls["theta"].value = before
    np.testing.assert_allclose(p.frame.g, [0.0, 2.0, before])


def test_browser_rounding_keeps_exact_values():
    """The browser shows sliders on their grid (min + k * step) and may echo the rounded position:
    neither the starting values nor values set from code change because of such an echo."""
    p = FrameDemo()
    start = p.values()["theta"]                   # 0.8, off the grid -pi + k * 0.01
    p.controls["theta"].value = -np.pi + round((start + np.pi) / 0.01) * 0.01   # the first render's echo
    assert p.values()["theta"] == start
    np.testing.assert_allclose(p.frame.g[2], start)
    p.set(x=0.123456)
    p.controls["x"].value = 0.12                 # the browser's echo of its rounded position
    assert p.values()["x"] == 0.123456           # keeps the exact value set from code
    np.testing.assert_allclose(p.frame.g[0], 0.123456)
    p.controls["x"].value = 0.5                  # a real move is a real change
    np.testing.assert_allclose(p.frame.g[0], 0.5)

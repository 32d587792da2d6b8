"""Live figures end on the truth (issue 19): key frames after a burst, marks kept through blits.

* :class:`gm_core.drawing.blit.KeyFrames` on a webagg canvas (the canvas ipympl builds on), with
  a recording socket in place of the browser: during a burst the pictures go out as differences;
  the key frame after it goes out whole, and nothing is sent after it.
* Blitting keeps static marks that sit above a moving artist (02's ✓/✗ on a badge whose colour
  is set on every update): the blitted picture equals a full redraw there, pixel for pixel.
* The group-or-not panel offers whole numbers for sets of integers.
"""
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.backends.backend_webagg_core import FigureCanvasWebAggCore, FigureManagerWebAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from gm_core.drawing.blit import KeyFrames, sends_differences  # noqa: E402
from gm_core.widgets.base import Panel  # noqa: E402


class _Socket:
    """Stands in for the browser: records what the canvas sends."""

    def __init__(self):
        self.sent = []   # ("json", dict) or ("binary", bytes)

    def send_json(self, content):
        self.sent.append(("json", json.loads(json.dumps(content))))

    def send_binary(self, blob):
        self.sent.append(("binary", blob))

    def modes(self):
        """The image mode in force for each picture sent, in order."""
        mode, out = "full", []
        for kind, what in self.sent:
            if kind == "json" and what.get("type") == "image_mode":
                mode = what["mode"]
            elif kind == "binary":
                out.append(mode)
        return out


def _webagg_figure():
    fig = Figure(figsize=(3, 2), dpi=100)
    canvas = FigureCanvasWebAggCore(fig)
    manager = FigureManagerWebAgg(canvas, 1)
    sock = _Socket()
    manager.add_web_socket(sock)
    ax = fig.add_subplot()
    ax.set(xlim=(0, 1), ylim=(0, 1))
    (line,) = ax.plot([0, 1], [0, 0.5])
    return fig, line, sock


def test_webagg_canvas_sends_differences():
    fig, _, _ = _webagg_figure()
    assert sends_differences(fig)
    assert not sends_differences(plt.figure())
    plt.close("all")


def test_key_frame_after_a_burst_is_sent_whole_and_last():
    fig, line, sock = _webagg_figure()
    fig.canvas.draw()                      # the first picture: whole
    for y in (0.6, 0.7, 0.8):              # a burst of changes: differences
        line.set_ydata([0, y])
        fig.canvas.draw()
    keys = KeyFrames(fig, delay=0.25)
    assert sock.modes() == ["full", "diff", "diff", "diff"]
    n = len(sock.sent)
    keys.send()                             # what the timer does after the burst
    after = sock.sent[n:]
    assert sock.modes()[-1] == "full" and keys.sent == 1
    assert after[-1][0] == "binary", "the key frame must be the last thing the browser gets"
    assert not [w for k, w in after if k == "json" and w.get("type") == "draw"], \
        "the key frame must not ask the browser for another (difference) picture"
    # the next change is a difference from the key frame again
    line.set_ydata([0, 0.2])
    fig.canvas.draw()
    assert sock.modes()[-1] == "diff"
    keys.disconnect()


def test_a_full_draw_restarts_the_key_frame_timer_but_the_key_frame_does_not():
    fig, line, sock = _webagg_figure()
    keys = KeyFrames(fig, delay=0.25)
    started = []
    keys._timer.start = lambda *a: started.append("start")   # observe the (tornado) timer
    keys._timer.stop = lambda *a: None
    fig.canvas.draw()
    assert started == ["start"]
    keys.send()
    assert started == ["start"], "the key frame's own draw must not schedule another key frame"
    keys.touch()
    assert started == ["start", "start"]


@pytest.fixture
def blitting(monkeypatch):
    monkeypatch.setattr(Panel, "blit_everywhere", True)


def test_group_axioms_badges_keep_their_marks(blitting, monkeypatch):
    from gm_core.widgets.group_or_not import GroupAxiomsPanel

    live = GroupAxiomsPanel()
    monkeypatch.setattr(Panel, "blit_everywhere", False)
    plain = GroupAxiomsPanel()
    live.fig.canvas.draw()
    for a in (1.0, 3.0, -2.0):
        live.refresh(a=a)
    plain.update(**{**live.values(), "a": -2.0})
    plain.fig.canvas.draw()
    assert live.blitter.blits >= 1
    a = np.asarray(live.fig.canvas.buffer_rgba())
    b = np.asarray(plain.fig.canvas.buffer_rgba())
    # the badge column (left 7 % of the table): the white ✓/✗ must be on every badge
    w = a.shape[1]
    col = slice(0, int(0.08 * w))
    assert (a[:, col] != b[:, col]).any(-1).sum() == 0, "a badge lost its mark after a blitted update"
    plt.close(live.fig)
    plt.close(plain.fig)


def test_integer_structures_take_whole_numbers():
    from gm_core.widgets.group_or_not import GroupAxiomsPanel

    p = GroupAxiomsPanel()
    p.set(structure="(ℤ, ×)", a=-0.5)
    assert p.controls["a"].step == 1.0 and p.values()["a"] in (0.0, -1.0)
    assert all(float(v).is_integer() for k, v in p.values().items() if k in "abc")
    assert not any(t.startswith("✓") and "∉" in t for t in p.scene.tried.values())
    p.set(structure="(ℝ⁺, ×)", a=0.5)
    assert p.controls["a"].step == 0.5 and p.values()["a"] == 0.5
    plt.close(p.fig)

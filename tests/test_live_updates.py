"""Live figures end on the truth (issue 19): key frames after a burst, marks kept through blits.

* :class:`gm_core.drawing.toolkit.blit.KeyFrames` on a webagg canvas (the canvas ipympl builds on), with
  a recording socket in place of the browser: during a burst the pictures go out as differences;
  the key frame after it goes out whole, and nothing is sent after it.
* Blitting keeps static marks that sit above a moving artist (02's ✓/✗ on a badge whose colour
  is set on every update): the blitted picture equals a full redraw there, pixel for pixel.
* The group-or-not panel offers whole numbers for sets of integers.
* A quick drag (a burst of changes) and a slow one (one change) to the same value leave the same
  picture, for every registered panel and for 09's gait panel on the kinematic snake, whose drag
  crosses into singular gaits.
* On a real ipympl canvas no picture leaves before the browser's view has said 'initialized',
  whatever the order in which the kernel handles the view's messages.
* Pictures leave at once (issue 36 item 8): a full draw, the blitter's or a non-blitted panel's,
  is drawn and sent right after the update, with no draw request to the browser.
* A 3-D camera that turns with the point turns at the key frame (03's tangent spaces): the burst's
  blits equal full draws at the still camera, and the key frame equals one change to the last value.
"""
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.backends.backend_webagg_core import FigureCanvasWebAggCore, FigureManagerWebAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

from gm_core.drawing.toolkit.blit import KeyFrames, sends_differences  # noqa: E402
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
    from gm_core.widgets.axioms import GroupAxiomsPanel

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
    from gm_core.widgets.axioms import GroupAxiomsPanel

    p = GroupAxiomsPanel()
    p.set(structure="(ℤ, ×)", a=-0.5)
    assert p.controls["a"].step == 1.0 and p.values()["a"] in (0.0, -1.0)
    assert all(float(v).is_integer() for k, v in p.values().items() if k in "abc")
    assert not any(t.startswith("✓") and "∉" in t for t in p.scene.tried.values())
    p.set(structure="(ℝ⁺, ×)", a=0.5)
    assert p.controls["a"].step == 0.5 and p.values()["a"] == 0.5
    plt.close(p.fig)


# -- quick and slow drags end on the same picture ----------------------------------------------

def _first_slider(panel):
    import ipywidgets as W

    return next((k for k, c in panel.controls.items()
                 if isinstance(c, (W.FloatSlider, W.IntSlider)) and not c.disabled), None)


def _target(c, fraction=0.35):
    """A value ``fraction`` of the slider's range from where it is, towards its far end, on its grid."""
    lo, hi = float(c.min), float(c.max)
    sign = 1 if c.value <= (lo + hi) / 2 else -1
    return _on_grid(c, c.value + sign * fraction * (hi - lo))


def _on_grid(c, v):
    lo, step = float(c.min), float(c.step)
    v = lo + round((v - lo) / step) * step
    v = min(max(v, c.min), c.max)
    return int(round(v)) if isinstance(c.value, int) else float(v)


def _keyframe_picture(panel):
    panel.fig.canvas.draw()    # what the key frame after a burst shows: a full draw
    return np.asarray(panel.fig.canvas.buffer_rgba()).copy()


def _first_choice(panel):
    """The first enabled control offering options (buttons, a dropdown) with at least two."""
    return next((k for k, c in panel.controls.items()
                 if len(getattr(c, "options", ())) > 1 and not c.disabled), None)


def _burst(c, steps):
    """(values a quick burst sends, its last value): a slider dragged over ``steps`` grid
    values, or, for a control of options, a click on every other option in turn."""
    if hasattr(c, "min"):
        target = _target(c)
        return [_on_grid(c, v) for v in np.linspace(c.value, target, steps + 1)[1:]], target
    values = [o[1] if isinstance(o, tuple) else o for o in c.options]
    others = [v for v in values if v != c.value]
    return others, others[-1]


def _quick_and_slow(cls, options, steps=10):
    """(quick, slow, key, target): the picture after a burst of ``steps`` changes of the first
    slider (as a quick mouse drag sends them, each on the slider's grid; a panel without one:
    quick clicks through every option of its first choice) and after one change to the same
    value, each from a freshly built panel."""
    quick = cls(**options)
    try:
        quick.fig.canvas.draw()
        key = _first_slider(quick) or _first_choice(quick)
        assert key is not None, f"{cls.__name__} has neither a slider nor a choice to move"
        c = quick.controls[key]
        burst, target = _burst(c, steps)
        for v in burst:
            c.value = v
        assert c.value == target
        q = _keyframe_picture(quick)
    finally:
        plt.close(quick.fig)
    slow = cls(**options)
    try:
        slow.fig.canvas.draw()
        slow.controls[key].value = target
        s = _keyframe_picture(slow)
    finally:
        plt.close(slow.fig)
    return q, s, key, target


def _drag_cases():
    from gm_core.widgets.base import all_panels

    cases = [pytest.param(name, {}, id=name) for name in sorted(all_panels())]
    # notebook 09 cell 20: the kinematic snake, whose first slider's drag ends on a gait that
    # crosses the singular line after passing non-singular ones (issue 19's one known difference)
    from gm_core.systems import KinematicSnake

    cases.append(pytest.param("GaitPanel", dict(system=KinematicSnake(), center=(0.4, -1.0), amplitude=0.8),
                              id="GaitPanel-09-kinematic-snake"))
    return cases


@pytest.mark.parametrize("name, options", _drag_cases())
def test_a_burst_of_changes_ends_on_the_picture_of_one_change(name, options, blitting):
    """A quick drag (ten changes) and a slow one (one change) to the same value leave the same
    picture: nothing in a panel's picture depends on the values it passed through."""
    from gm_core.widgets.base import all_panels

    quick, slow, key, target = _quick_and_slow(all_panels()[name], options)
    differing = (quick != slow).any(-1).mean()
    assert differing == 0, f"{name}: after a burst to {key} = {target}, {differing:.2%} of the canvas " \
                           "differs from one change to the same value"


def test_the_drag_comparison_sees_a_path_dependent_picture(blitting):
    """The comparison above can fail: a panel whose readout counts its updates differs."""
    from gm_core.widgets.start import FrameDemo

    class Counting(FrameDemo):
        def update(self, **values):
            super().update(**values)
            self.n = getattr(self, "n", 0) + 1
            self.fig.suptitle(f"update {self.n}")

    quick, slow, _, _ = _quick_and_slow(Counting, {})
    assert (quick != slow).any(-1).mean() > 0


# -- ipympl: no picture before the browser's view is ready --------------------------------------

@pytest.fixture
def ipympl():
    backend = matplotlib.get_backend()
    plt.switch_backend("module://ipympl.backend_nbagg")
    yield
    plt.switch_backend(backend)


def _browser_says(canvas, kind):
    """A message from ipympl's front end, dispatched as ipywidgets does (to every on_msg callback)."""
    canvas._handle_msg({"content": {"data": {"method": "custom", "content": {"type": kind}}}, "buffers": []})


def _pictures(canvas):
    """The list of pictures (binary messages) ``canvas`` sends to the browser from now on."""
    sent, send = [], canvas.send

    def record(content, buffers=None):
        if buffers:
            sent.append(bytes(memoryview(buffers[0])))
        return send(content, buffers)

    canvas.send = record
    return sent


def _proper(data_url):
    return data_url is None or data_url.startswith("data:image/png;base64,")


# ipympl's own Toolbar passes its canvas to HasTraits.__init__ (its code, not ours)
@pytest.mark.filterwarnings("ignore:Passing unrecognized arguments to super\\(Toolbar\\)")
def test_no_picture_leaves_before_the_browser_view_is_initialised(ipympl):
    """ipympl 0.10 takes a picture sent before its front end's 'initialized' message for the
    saved picture: ``_data_url`` loses its ``data:`` prefix and the browser gets raw pixels for a
    PNG, so the canvas stays blank (03-velocities under load: the browser's answer to a draw
    request, sent on a comm subshell, was handled before its 'initialized', sent on the main
    shell behind Run All's cells). Here the view's messages come
    in that order, with a cell's update and a key frame falling due in between: nothing is sent
    until 'initialized', then the picture of the panel as it is, whole, then differences again."""
    import io

    from PIL import Image

    from gm_core.drawing.toolkit import new_figure
    from gm_core.widgets.observers import FramesPanel

    panel = FramesPanel()
    canvas = panel.fig.canvas
    sent = _pictures(canvas)
    panel._repr_mimebundle_()                      # the cell displays it
    _browser_says(canvas, "refresh")               # the view's first message,
    _browser_says(canvas, "draw")                  # its answer to a draw request, handled early,
    panel.set(t=2.5)                               # a later cell moves the panel,
    assert panel.keyframes is not None
    panel.keyframes.send()                         # a key frame falls due,
    _browser_says(canvas, "draw")                  # the view answers again
    assert _proper(canvas._data_url), f"picture stored as {canvas._data_url[:30]!r}..."
    assert sent == [], "a picture was sent before the browser's view was initialised"
    _browser_says(canvas, "send_image_mode")
    _browser_says(canvas, "initialized")
    assert len(sent) == 1 and sent[0].startswith(b"\x89PNG"), "the picture held back goes out as a PNG"
    assert canvas._current_image_mode == "full" and _proper(canvas._data_url)
    shown = np.asarray(Image.open(io.BytesIO(sent[0])).convert("RGBA"))
    assert (shown == np.asarray(canvas.buffer_rgba())).all(), "the picture sent is not the panel as it is"
    panel.set(t=3.0)                               # from now on, pictures flow as before,
    assert len(sent) == 2 and canvas._current_image_mode == "diff"   # sent at once (no draw request)

    # a static figure of the course (shown with widgets.base.show or as fig.canvas) likewise
    fig, ax = new_figure()
    ax.plot([0, 1], [0, 1])
    sent = _pictures(fig.canvas)
    for kind in ("refresh", "draw"):
        _browser_says(fig.canvas, kind)
    assert sent == [] and _proper(fig.canvas._data_url)
    _browser_says(fig.canvas, "initialized")
    assert len(sent) == 1 and sent[0].startswith(b"\x89PNG")


@pytest.mark.filterwarnings("ignore:Passing unrecognized arguments to super\\(Toolbar\\)")
def test_course_figures_have_no_toolbar_floating_over_them(ipympl):
    """Issue 36: ipympl's toolbar fades in over a figure when the pointer hovers on it (it is
    absolutely positioned, on the left by default) and covered the tick labels. Every figure
    of the course, a panel's and a static one, is made without it, and without header and
    footer; a plain matplotlib figure keeps ipympl's defaults (the setting is the course's)."""
    import matplotlib.pyplot as plt

    from gm_core.drawing.toolkit import new_figure
    from gm_core.widgets.groups import CircleIsoPanel

    fig, _ = new_figure()
    panel = CircleIsoPanel()
    for canvas in (fig.canvas, panel.fig.canvas):
        assert type(canvas).__module__.startswith("ipympl")
        assert canvas.toolbar_visible is False
        assert not canvas.header_visible and not canvas.footer_visible
    plain = plt.figure()
    assert plain.canvas.toolbar_visible == "fade-in-fade-out"
    plt.close("all")


# -- pictures leave at once (no round trip through the browser), quickly encoded ---------------

def _draw_requests(sock):
    return [w for k, w in sock.sent if k == "json" and w.get("type") == "draw"]


def test_an_update_outside_a_blitter_is_drawn_and_sent_at_once():
    """webagg's draw_idle asks the browser to ask for a picture (a round trip before the draw);
    a panel update that is not blitted is drawn once, at once, however often it asked."""
    from gm_core.drawing.toolkit.blit import drawn_at_once

    fig, line, sock = _webagg_figure()
    fig.canvas.draw()
    n = len(sock.sent)
    with drawn_at_once(fig):
        line.set_ydata([0, 0.9])
        fig.canvas.draw_idle()
        fig.canvas.draw_idle()
    after = sock.sent[n:]
    assert [k for k, _ in after if k == "binary"] == ["binary"] and not _draw_requests(sock)
    with drawn_at_once(fig):
        pass                                    # no request, no picture
    assert len(sock.sent) == len(sock.sent[:n]) + len(after)
    # an Agg canvas draws on draw_idle itself: nothing is intercepted
    agg = plt.figure()
    calls = []
    agg.canvas.draw_idle = lambda *a, **k: calls.append(1)
    with drawn_at_once(agg):
        agg.canvas.draw_idle()
    assert calls == [1]
    plt.close(agg)


def test_a_blitter_draws_new_moving_artists_at_once():
    """The blitter's full draws (the first frame, new moving artists) are sent at once too."""
    from gm_core.drawing.toolkit.blit import Blitter

    fig, line, sock = _webagg_figure()
    blitter = Blitter(fig)
    for y in (0.6, 0.7, 0.8):     # the first frame and the line's first move are full draws, then a blit
        with blitter.frame():
            line.set_ydata([0, y])
            fig.canvas.draw_idle()
    with blitter.frame():
        (fig.axes[0].plot([0, 1], [1, 0])[0]).set_color("r")   # a new artist: a full draw
    assert blitter.full_draws == 3 and blitter.blits == 1
    assert len([k for k, _ in sock.sent if k == "binary"]) == 4 and not _draw_requests(sock)
    blitter.disconnect()


@pytest.mark.filterwarnings("ignore:Passing unrecognized arguments to super\\(Toolbar\\)")
def test_a_live_panel_without_blitting_sends_one_picture_per_move_and_asks_for_none(ipympl):
    """On a real ipympl canvas, once its view is ready: a 3-D panel that is not blitted sends one
    picture per slider move, and no draw request."""
    from gm_core.widgets.geodesics import SurfaceGeodesicsPanel

    panel = SurfaceGeodesicsPanel()
    canvas = panel.fig.canvas
    sent, asked = [], []
    send = canvas.send

    def record(content, buffers=None):
        if buffers:
            sent.append(bytes(memoryview(buffers[0])))
        elif json.loads(content.get("data", "{}")).get("type") == "draw":
            asked.append(1)
        return send(content, buffers)

    canvas.send = record
    panel._repr_mimebundle_()
    _browser_says(canvas, "initialized")
    _browser_says(canvas, "draw")
    assert panel.blitter is None and len(sent) >= 1
    n, asked[:] = len(sent), []
    for h in (20.0, 30.0, 40.0):
        panel.controls["heading_deg"].value = h
    assert len(sent) == n + 3 and asked == [], "each move: one picture, sent at once"
    assert canvas._current_image_mode == "diff"
    panel.keyframes.disconnect()
    plt.close(panel.fig)


# -- a 3-D camera that turns at the end of a burst ----------------------------------------------

def _agg_picture_of(cls, values, camera=None):
    """A fresh, unblitted Agg panel of ``cls`` at ``values`` (its camera set by ``set``, or put
    at ``camera = (elev, azim)``), drawn in full: the independent picture to compare with."""
    ref = cls()
    ref.set(**values)
    if camera is not None:
        ref.fig.axes[1].view_init(elev=camera[0], azim=camera[1])
    ref.fig.canvas.draw()
    out = np.asarray(ref.fig.canvas.buffer_rgba()).copy()
    plt.close(ref.fig)
    return out


def test_a_3d_blit_over_a_still_camera_equals_a_full_draw(blitting):
    """03's tangent-space panel, as on a live canvas (its camera left for the key frame): every
    move is a blit, and each blitted picture equals a full draw of a fresh panel at the same values
    and camera, pixel for pixel, including the moving 3-D plane and arrow (collections that only
    the axes' own draw projects). After ``settle`` the camera faces the point again."""
    from gm_core.widgets.tangent import TangentSpacePanel

    panel = TangentSpacePanel()
    panel.scene.settle_later = True
    panel.fig.canvas.draw()
    ax3 = panel.fig.axes[1]
    still = (ax3.elev, ax3.azim)
    for s, speed in ((1.2, 1.0), (1.9, -1.4), (3.4, 0.6)):
        panel.controls["speed"].value = speed
        panel.controls["s"].value = s
        assert (ax3.elev, ax3.azim) == still, "the camera turned during the burst"
        blitted = np.asarray(panel.fig.canvas.buffer_rgba()).copy()
        assert (blitted == _agg_picture_of(TangentSpacePanel, dict(s=s, speed=speed), still)).all()
    assert panel.blitter.full_draws == 1 and panel.blitter.blits == 4   # (speed = 1.0 is no change)
    panel.settle()
    lat = panel.scene.AMP * np.sin(2 * 3.4)                           # the point's latitude, book fig. 1.12
    assert np.isclose(ax3.elev, np.rad2deg(lat) * 0.6 + 12) and np.isclose(ax3.azim, np.rad2deg(3.4) - 20)
    plt.close(panel.fig)


@pytest.mark.filterwarnings("ignore:Passing unrecognized arguments to super\\(Toolbar\\)")
def test_a_live_3d_panel_blits_the_burst_and_its_key_frame_turns_the_camera(ipympl):
    """On a real ipympl canvas: 03's tangent-space panel sends one blitted picture per move with
    its camera still, and the key frame turns the camera and sends the whole picture, the same
    as an unblitted Agg panel set to the last values in one go (the slow drag's picture)."""
    import io

    from PIL import Image

    from gm_core.widgets.tangent import TangentSpacePanel

    panel = TangentSpacePanel()
    canvas = panel.fig.canvas
    sent = _pictures(canvas)
    panel._repr_mimebundle_()
    _browser_says(canvas, "initialized")
    _browser_says(canvas, "draw")
    ax3 = panel.fig.axes[1]
    still = (ax3.elev, ax3.azim)
    n = len(sent)
    for s in (1.0, 1.3, 1.6, 1.9):
        panel.controls["s"].value = s
    assert len(sent) == n + 4 and (ax3.elev, ax3.azim) == still
    assert panel.blitter.blits >= 2, "the burst's moves after the first new artists are blits"
    assert panel.keyframes is not None
    panel.keyframes.send()
    assert canvas._current_image_mode == "full" and len(sent) == n + 5
    shown = np.asarray(Image.open(io.BytesIO(sent[-1])).convert("RGBA"))
    assert (shown == _agg_picture_of(TangentSpacePanel, dict(s=1.9))).all(), \
        "the key frame is not the picture of one change to the last value"
    panel.keyframes.disconnect()
    plt.close(panel.fig)

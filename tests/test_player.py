"""The animation player (gm_core.drawing.toolkit.player, gm_core.drawing.toolkit.primitives.jshtml) is self-contained.

The browser tests press its ▶ button in JupyterLab; here, without a browser: every frame of the
animation is in the page, the first one is the image's own source, nothing refers to the network,
and bad arguments are refused with a clear message.
"""
import base64
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pytest  # noqa: E402

from gm_core.drawing.toolkit.player import MODES, player_html  # noqa: E402
from gm_core.drawing.toolkit.primitives import animate, jshtml  # noqa: E402

# the refused FuncAnimation below is never rendered; matplotlib says so when it is collected
pytestmark = pytest.mark.filterwarnings("ignore:Animation was deleted")


def _anim(n=4):
    fig, ax = plt.subplots(figsize=(3, 2), dpi=72)
    ax.set(xlim=(0, n), ylim=(0, 1))
    (dot,) = ax.plot([0], [0.5], "o")
    return fig, animate(fig, lambda k: dot.set_data([k], [0.5]), frames=range(n), interval=80)


def test_every_frame_is_embedded_and_distinct(monkeypatch):
    monkeypatch.delenv("GM_COURSE_TESTING", raising=False)
    fig, anim = _anim(5)
    page = jshtml(anim).data
    frames = re.findall(r'"(data:image/png;base64,[A-Za-z0-9+/=]+)"', page)
    assert len(set(frames)) == 5, "each of the 5 frames once, all different"
    png = base64.b64decode(frames[0].split(",", 1)[1])
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    # frames at the figure standard's 100 px per inch, whatever the figure's own dpi was
    width = int.from_bytes(png[16:20], "big")
    assert width == 300 and 'width="300"' in page
    # the first frame is the image's own source: a picture before (or without) the script
    img = re.search(r'<img id="_anim_img\w+" src="([^"]+)" width="300" class="gm-anim-frame"', page)
    assert img and img.group(1) == frames[0]
    assert "interval = 80" in page and 'class="gm-anim-play"' in page
    assert not plt.fignum_exists(fig.number), "the figure is closed once its frames are kept"


def test_nothing_is_fetched_from_the_network():
    _, anim = _anim(3)
    page = jshtml(anim).data
    assert not re.search(r"https?://|//cdn|<link|@import|font-awesome|fa-", page, re.I), \
        "the player must need nothing from the network"


@pytest.mark.parametrize("mode", MODES)
def test_modes_are_accepted(mode):
    page = player_html(["data:image/png;base64,AAAA"], interval=40, width=120, mode=mode)
    assert f"mode0 = \"{mode}\"" in page


def test_bad_arguments():
    with pytest.raises(ValueError, match="mode"):
        player_html(["data:,"], mode="bounce")
    with pytest.raises(ValueError, match="frames"):
        player_html([])
    with pytest.raises(TypeError, match="animate"):
        from matplotlib.animation import FuncAnimation
        fig, ax = plt.subplots()
        jshtml(FuncAnimation(fig, lambda k: None, frames=2))
    plt.close("all")


def test_palette_frames_are_smaller_and_look_the_same(monkeypatch):
    """``animate(..., palette=True)`` (line art): frames in at most 256 colours, every pixel within a
    few levels of the full-colour frame (a small marker keeps its colour), and fewer bytes."""
    import io

    import numpy as np
    from PIL import Image

    from gm_core.drawing.toolkit import PALETTE

    monkeypatch.delenv("GM_COURSE_TESTING", raising=False)

    def page(palette):
        fig, ax = plt.subplots(figsize=(6, 3))
        x = np.linspace(0, 10, 400)
        for k, c in enumerate(("blue", "orange", "green", "vermillion")):
            ax.plot(x, np.sin(x + k), color=PALETTE[c], lw=1.8)
        (dot,) = ax.plot([], [], "o", color="gold", mec="k", ms=8)
        ax.grid(True, alpha=0.3)
        anim = animate(fig, lambda k: dot.set_data([k], [0.0]), frames=range(3), palette=palette)
        html = jshtml(anim).data
        return [Image.open(io.BytesIO(base64.b64decode(u)))
                for u in re.findall(r'"data:image/png;base64,([A-Za-z0-9+/=]+)"', html)], len(html)

    (full, n_full), (small, n_small) = page(False), page(True)
    assert small[0].mode == "P" and full[0].mode != "P"
    for a, b in zip(full, small):
        diff = np.abs(np.asarray(a.convert("RGB"), int) - np.asarray(b.convert("RGB"), int))
        assert diff.max() <= 24, f"a pixel changed by {diff.max()} levels"
    assert n_small < 0.6 * n_full, (n_small, n_full)


def test_progress_note_counts_the_frames_and_leaves_nothing_behind(monkeypatch):
    """Issue 36: "drawing the animation ..." lines stayed above finished animations. While jshtml
    draws, its note says which frame, updated in place; once the player is ready (or the drawing
    failed) the note is emptied, so nothing stale stays. Outside a kernel no note is shown."""
    import IPython.display

    shown = []

    class Handle:
        def update(self, obj):
            shown.append(obj.data)

    def display(obj, display_id=None):
        assert display_id is True, "the note needs a display id to be updated in place"
        shown.append(obj.data)
        return Handle()

    monkeypatch.setattr(IPython.display, "display", display)
    monkeypatch.delenv("GM_COURSE_TESTING", raising=False)
    _, anim = _anim(4)
    page = jshtml(anim, progress=True)
    assert "drawing the animation" in shown[0]
    assert [re.search(r"frame (\d) of 4", t).group(1) for t in shown[1:-1]] == ["1", "2", "3", "4"]
    assert shown[-1] == "" and "<img" in page.data

    shown.clear()
    fig, ax = plt.subplots(figsize=(3, 2), dpi=72)

    def broken(k):
        if k == 2:
            raise RuntimeError("frame 2 cannot be drawn")

    with pytest.raises(RuntimeError, match="frame 2"):
        jshtml(animate(fig, broken, frames=range(4)), progress=True)
    assert shown[-1] == "", "a failed drawing leaves its note behind"

    shown.clear()
    _, anim = _anim(3)
    jshtml(anim)                  # not in a Jupyter kernel: no note at all
    assert shown == []
    plt.close("all")

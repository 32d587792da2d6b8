"""Scenes keep what they computed for their last few values (gm_core.drawing.toolkit.recent):
a value visited again draws exactly the picture a fresh scene draws, and only so many are kept."""
import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from gm_core.drawing.link_chain import ChainSliceScene, WaveGaitScene  # noqa: E402
from gm_core.drawing.toolkit.recent import Recent  # noqa: E402


def pixels(scene):
    scene.fig.canvas.draw()
    return np.asarray(scene.fig.canvas.buffer_rgba()).copy()


@pytest.mark.parametrize("cls, there, back", [
    (ChainSliceScene, dict(links=7, row=0, axis1=2, axis2=5), dict(links=4, row=1, axis1=1, axis2=3)),
    (WaveGaitScene, dict(links=6, amplitude=1.1, lag=0.7), dict(links=3, amplitude=0.5, lag=2.0)),
])
def test_a_value_visited_again_draws_what_a_fresh_scene_draws(cls, there, back):
    moved = cls()
    moved.set(**back)
    moved.set(**there)
    moved.set(**back)                       # from what it kept
    fresh = cls()
    fresh.set(**back)
    assert np.array_equal(pixels(moved), pixels(fresh))


def test_recent_keeps_the_last_values_and_makes_each_once():
    made = []
    memo: Recent[int, int] = Recent(2)

    def make(k):
        return lambda: made.append(k) or k * k

    assert [memo.get(k, make(k)) for k in (1, 2, 1, 3, 1, 2)] == [1, 4, 1, 9, 1, 4]
    assert made == [1, 2, 3, 2]             # 3 dropped 2 (1 was asked for since), 2 dropped 3
    assert len(memo) == 2 and 1 in memo and 2 in memo and 3 not in memo


@pytest.mark.parametrize("size", [0, -1, 2.5, True, "4"])
def test_recent_refuses_a_size_that_is_not_a_positive_integer(size):
    with pytest.raises(ValueError, match="size"):
        Recent(size)

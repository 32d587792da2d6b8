"""Bad input gets a TypeError/ValueError that names the argument, never an IndexError or a silent broadcast."""
import numpy as np
import pytest

from gm_core import ALL_GROUPS, S1, SE2, SO2, RPlus, Rn


@pytest.mark.parametrize("bad,exc,words", [
    ("abc", TypeError, "g must be a numeric array"),
    (None, TypeError, "g must be a numeric array"),
    ([1.0, 2.0], ValueError, "shape (..., 3)"),
    ([1.0, 2.0, 3.0, 4.0], ValueError, "shape (..., 3)"),
    (np.zeros((5, 4)), ValueError, "got shape (5, 4)"),
    ([1.0, np.nan, 0.0], ValueError, "NaN"),
    ([1.0, np.inf, 0.0], ValueError, "NaN or infinite"),
    ([["a", "b", "c"]], TypeError, "g must be a numeric array"),
    ({"x": 1}, TypeError, "g must be"),
])
def test_se2_element_errors_name_argument(bad, exc, words):
    with pytest.raises(exc) as info:
        SE2.inverse(bad)
    assert words in str(info.value)


def test_second_argument_is_named():
    with pytest.raises(ValueError, match=r"^h must have shape"):
        SE2.compose([0, 0, 0], [1, 2])
    with pytest.raises(ValueError, match=r"^xi must have shape"):
        SE2.exp([1, 2])
    with pytest.raises(ValueError, match=r"^g_dot must have shape"):
        SE2.world_to_body([0, 0, 0], [1, 2, 3, 4])


def test_no_silent_broadcast_of_mismatched_batches():
    with pytest.raises(ValueError):
        SE2.compose(np.zeros((4, 3)), np.zeros((5, 3)))


@pytest.mark.parametrize("G", list(ALL_GROUPS.values()), ids=list(ALL_GROUPS))
def test_every_group_rejects_wrong_shapes_and_strings(G):
    wrong = np.zeros(G.dim + 1)
    for fn in (G.inverse, G.exp, G.log, G.matrix, G.Ad):
        with pytest.raises(ValueError, match="must have shape"):
            fn(wrong)
        with pytest.raises(TypeError):
            fn("1")
    with pytest.raises(ValueError, match="must have shape"):
        G.from_matrix(np.eye(G.matrix_size + 1))


def test_rplus_rejects_non_positive():
    with pytest.raises(ValueError, match="positive"):
        RPlus.compose([2.0], [-1.0])
    with pytest.raises(ValueError, match="positive"):
        RPlus.log([0.0])


@pytest.mark.parametrize("G", [
    np.diag([2.0, 1.0, 1.0]),                                   # scaling
    np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),  # shear
    np.diag([1.0, -1.0, 1.0]),                                  # reflection (det -1)
    np.array([[1.0, 0.0, 1.0], [0.0, 1.0, 2.0], [0.3, 0.0, 1.0]]),  # bad last row
])
def test_from_matrix_rejects_non_rigid(G):
    with pytest.raises(ValueError, match="G "):
        SE2.from_matrix(G)
    if not np.allclose(G[:2, :2], np.eye(2)):
        with pytest.raises(ValueError, match="not a rotation"):
            SO2.from_matrix(G[:2, :2])


def test_vee_rejects_non_algebra_matrix():
    with pytest.raises(ValueError, match="se\\(2\\)"):
        SE2.vee(np.eye(3))
    with pytest.raises(ValueError, match="skew"):
        SO2.vee(np.eye(2))


def test_constructor_arguments():
    with pytest.raises(ValueError, match="n must be a positive integer"):
        Rn(0)
    with pytest.raises(ValueError, match="period must be a positive number"):
        S1(-1.0)


def test_matrix_arguments_named():
    with pytest.raises(ValueError, match=r"^G must have shape \(\.\.\., 3, 3\)"):
        SE2.from_matrix(np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"^X must have shape"):
        SE2.vee(np.zeros(3))

"""gm_core.printing.shown: printed numbers never show round-off (-0.0, -0.000, 1e-17) and keep
every digit Python's own formatting prints (the independent route: format, then parse)."""
import numpy as np
import pytest

from gm_core.printing import shown

RNG = np.random.default_rng(7)
NOISE = [0.0, -0.0, 1e-17, -1e-17, -2.2e-16, 5.7e-15, -1.7e-14, -4e-13]


@pytest.mark.parametrize("decimals", [0, 3, 4, 6, 12])
def test_round_off_never_shows(decimals):
    for v in NOISE:
        s = shown(v, decimals)
        assert s == 0.0 and np.copysign(1.0, s) == 1.0
        for text in (f"{s:.{decimals}f}", f"{s:+.{decimals}f}", f"{s:.1e}", str(s), repr(s)):
            assert not text.startswith("-") and "e-" not in text, text
    a = shown(np.array(NOISE + [-0.04218]).reshape(3, 3), decimals)
    text = np.array2string(a)
    assert "-0. " not in text and "-0.]" not in text and "e-" not in text, text
    assert np.all(np.copysign(1.0, a.ravel()[:-1]) == 1.0)


def test_digits_are_those_python_prints():
    """shown(v, d) is the number f"{v:.d f}" reads back as (correct rounding, ties included, where
    numpy.round can differ), and formatting it again prints the same text (never -0.000)."""
    values = np.concatenate([RNG.normal(0, 3, 300), RNG.normal(0, 1e-4, 100), [0.0005, 0.0015, 2.675, -1.0005, 0.125]])
    for d in (0, 2, 3, 4, 6):
        for v in values:
            text = f"{v:.{d}f}"
            assert shown(v, d) == float(text)
            assert f"{shown(v, d):.{d}f}" == (text[1:] if float(text) == 0 and text.startswith("-") else text)
        np.testing.assert_array_equal(shown(values, d), [shown(v, d) for v in values])
    assert f"{shown(0.0005, 3):+.3f}" == "+0.001" and f"{shown(-0.0004, 3):+.3f}" == "+0.000"


def test_types_shapes_and_non_finite_values():
    assert type(shown(np.float64(-0.15493287193190525))) is float and shown(np.float64(-0.15493287193190525)) == -0.1549
    assert shown([[1.23456, -1e-17]], 2).shape == (1, 2) and shown(np.zeros((0, 3))).shape == (0, 3)
    assert shown(3, 2) == 3.0 and shown([1, 2]).dtype == float
    a = shown([np.nan, np.inf, -np.inf, 1e308, -1e300], 4)
    assert np.isnan(a[0]) and a[1] == np.inf and a[2] == -np.inf and a[3] == 1e308 and a[4] == -1e300


@pytest.mark.parametrize("bad, error", [(None, TypeError), ("0.5", TypeError), (True, TypeError), (1 + 2j, TypeError),
                                        ([1, "a"], TypeError), ([[1, 2], [3]], TypeError)])
def test_bad_values_are_named(bad, error):
    with pytest.raises(error, match="^x "):
        shown(bad)


@pytest.mark.parametrize("bad, error", [(-1, ValueError), (16, ValueError), (2.5, TypeError), ("3", TypeError),
                                        (None, TypeError), (True, TypeError)])
def test_bad_decimals_are_named(bad, error):
    with pytest.raises(error, match="^decimals "):
        shown(1.0, bad)

"""Numbers as the course prints them (numpy only).

:func:`shown` rounds a number or an array to the decimals a notebook or a readout prints and turns
every negative zero into +0.0. Printed through it, a result that is exactly zero in exact
arithmetic reads ``0.0`` (never ``-0.0``, ``-0.000`` or ``1.7e-15``) and a result computed by two
routes that agree to rounding prints the same digits from either: the printed text does not depend
on the order in which a formula happens to be evaluated.
"""
from __future__ import annotations

import math
from typing import overload

import numpy as np
from numpy.typing import ArrayLike

from gm_core.validation import FloatArray, as_array, check_int

__all__ = ["shown"]


@overload
def shown(x: float, decimals: int = ...) -> float: ...
@overload
def shown(x: ArrayLike, decimals: int = ...) -> float | FloatArray: ...
def shown(x: ArrayLike, decimals: int = 4) -> float | FloatArray:
    """``x`` rounded to ``decimals`` decimal places, with -0.0 as 0.0: the value as it is printed.

    A number gives a Python float, an array a float array of the same shape; every entry is
    rounded correctly, like Python's ``round`` and ``format`` (so ``f"{shown(v, 3):+.3f}"`` and
    ``f"{v:+.3f}"`` print the same digits, except that the former never prints ``-0.000``;
    ``numpy.round`` scales by a power of ten first and can differ on ties). NaN and infinities pass
    through unchanged. ``decimals`` is an integer from 0 to 15: round-off noise of a quantity that
    is zero in exact arithmetic (a residual, a drift, a rotation that cancels) vanishes at
    ``decimals=12``.
    """
    decimals = check_int(decimals, "decimals", minimum=0, maximum=15, what=" (decimal places shown)")
    value = as_array(x, "x", allow_nan=True, what=" (a number or an array of numbers)")
    if value.ndim == 0:
        return _round(float(value), decimals)
    return np.array([_round(v, decimals) for v in value.ravel().tolist()], dtype=float).reshape(value.shape)


def _round(v: float, decimals: int) -> float:
    return round(v, decimals) + 0.0 if math.isfinite(v) else v

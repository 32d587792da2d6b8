"""Checking integer arguments (counts of samples, steps, frames) by name (numpy only).

Provisional home: this belongs beside ``as_array`` in :mod:`gm_core._validate`.
"""
from __future__ import annotations

import numbers

__all__ = ["check_int"]


def check_int(value, name, *, low=1, high=None, what=""):
    """Return ``value`` as a Python int after checking it is an integer in ``[low, high]``.

    Raises ``TypeError`` for non-integers (floats with a fraction, bools, strings, None, inf,
    NaN) and ``ValueError`` outside the range, naming ``name``. Integral floats such as ``20.0``
    are accepted, ``20.7`` is not.
    """
    if isinstance(value, bool) or value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be an integer{what}; got {value!r}")
    if isinstance(value, numbers.Integral):
        n = int(value)
    elif isinstance(value, numbers.Real) and float(value).is_integer():
        n = int(value)
    else:
        raise TypeError(f"{name} must be an integer{what}; got {value!r}")
    if n < low or (high is not None and n > high):
        rng = f">= {low}" if high is None else f"between {low} and {high}"
        raise ValueError(f"{name} must be an integer {rng}{what}; got {value!r}")
    return n

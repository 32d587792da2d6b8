"""Argument checks shared by the multiplicative-calculus modules (numpy only)."""
from __future__ import annotations

import numpy as np

from gm_core.validation import as_array, check_int, check_option, real_number

SIDES = ("left", "right")


# ---------------------------------------------------------------------------------- checking
def check_side(side, name="side"):
    return check_option(side, name, SIDES)


#: Largest number of steps, factors or series terms accepted (a Python loop runs over them).
MAX_STEPS = 10**5


def check_steps(n, name, minimum=1, maximum=MAX_STEPS):
    return check_int(n, name, minimum=minimum, maximum=maximum)


def check_n_list(n, name="n"):
    """An int or a sequence of ints >= 1, returned as a sorted 1-D int array without repeats."""
    if isinstance(n, (str, bytes)) or n is None:
        raise TypeError(f"{name} must be a positive integer or a sequence of them; got {n!r}")
    if np.ndim(n) == 0:
        return np.array([check_steps(n, name)], dtype=int)
    vals = [check_steps(v, name) for v in np.asarray(n, dtype=object).ravel()]
    if not vals:
        raise ValueError(f"{name} must contain at least one positive integer; got an empty sequence")
    return np.unique(np.array(vals, dtype=int))


def check_scalar(x, name):
    return real_number(x, name, " (a single real number)")


def check_xi(group, xi, name="xi"):
    xi = as_array(xi, name, (group.dim,), what=f", a Lie-algebra vector of {group.name}")
    if xi.ndim != 1:
        raise ValueError(f"{name} must be a single vector of shape ({group.dim},); got shape {xi.shape}")
    return xi


def matrix_value(value, name):
    """``value`` as a float array of shape (..., k, k), plus a flag saying it was a scalar."""
    arr = as_array(value, name, what=" (a number or a square matrix)")
    if arr.ndim == 0:
        return arr.reshape(1, 1), True
    if arr.ndim < 2 or arr.shape[-1] != arr.shape[-2]:
        raise ValueError(f"{name} must be a number or a square matrix (..., k, k); got shape {arr.shape}")
    return arr, False


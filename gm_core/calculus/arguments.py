"""Argument checks shared by the multiplicative-calculus modules (numpy only)."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from gm_core.groups import LieGroup
from gm_core.validation import FloatArray, as_array, check_int, check_option, real_number

SIDES = ("left", "right")


# ---------------------------------------------------------------------------------- checking
def check_side(side: str, name: str = "side") -> str:
    return check_option(side, name, SIDES)


#: Largest number of steps, factors or series terms accepted (a Python loop runs over them).
MAX_STEPS = 10**5


def check_steps(n: object, name: str, minimum: int = 1, maximum: int = MAX_STEPS) -> int:
    return check_int(n, name, minimum=minimum, maximum=maximum)


def check_n_list(n: ArrayLike, name: str = "n") -> NDArray[np.int_]:
    """An int or a sequence of ints >= 1, returned as a sorted 1-D int array without repeats."""
    if isinstance(n, (str, bytes)) or n is None:
        raise TypeError(f"{name} must be a positive integer or a sequence of them; got {n!r}")
    if np.ndim(n) == 0:
        return np.array([check_steps(n, name)], dtype=np.int_)
    vals = [check_steps(v, name) for v in np.asarray(n, dtype=object).ravel()]
    if not vals:
        raise ValueError(f"{name} must contain at least one positive integer; got an empty sequence")
    return np.unique(np.array(vals, dtype=np.int_))


def check_scalar(x: float, name: str) -> float:
    return real_number(x, name, " (a single real number)")


def check_xi(group: LieGroup, xi: ArrayLike, name: str = "xi") -> FloatArray:
    xi = as_array(xi, name, (group.dim,), what=f", a Lie-algebra vector of {group.name}")
    if xi.ndim != 1:
        raise ValueError(f"{name} must be a single vector of shape ({group.dim},); got shape {xi.shape}")
    return xi


def matrix_value(value: ArrayLike, name: str) -> tuple[FloatArray, bool]:
    """``value`` as a float array of shape (..., k, k), plus a flag saying it was a scalar."""
    arr = as_array(value, name, what=" (a number or a square matrix)")
    if arr.ndim == 0:
        return arr.reshape(1, 1), True
    if arr.ndim < 2 or arr.shape[-1] != arr.shape[-2]:
        raise ValueError(f"{name} must be a number or a square matrix (..., k, k); got shape {arr.shape}")
    return arr, False


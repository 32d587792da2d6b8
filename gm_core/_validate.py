"""Input checking shared by every gm_core module (numpy only).

Every public function turns its arguments into float arrays through :func:`as_array`, so a
student who passes a string, a list of the wrong length or a NaN gets an error that names the
argument and says what was expected, instead of an ``IndexError`` from deep inside numpy.
"""
from __future__ import annotations

import numpy as np

__all__ = ["as_array", "check_positive", "SingularShapeError"]


class SingularShapeError(ValueError):
    """Raised when a computation reaches a singular configuration (for example a shape where a
    local connection does not exist). The message says "singular" and where it happened."""


def _describe(tail):
    return "(..., " + ", ".join(str(s) for s in tail) + ")" if tail else "a scalar or array"


def as_array(value, name, tail=(), *, what="", allow_nan=False):
    """Return ``value`` as a float64 array whose trailing axes are ``tail``.

    Raises ``TypeError`` for non-numeric input (strings, None, objects) and ``ValueError`` for a
    wrong trailing shape or for NaN/inf entries, naming ``name`` and the expected shape.
    """
    if isinstance(value, np.ndarray) and value.dtype == np.float64:
        arr = value
    else:
        if value is None or isinstance(value, (str, bytes)):
            raise TypeError(
                f"{name} must be a numeric array of shape {_describe(tail)}{what}; "
                f"got {type(value).__name__}"
            )
        try:
            arr = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError):
            raise TypeError(
                f"{name} must be a numeric array of shape {_describe(tail)}{what}; "
                f"got {type(value).__name__} {value!r:.60}, which is not a list of numbers"
            ) from None
    nt = len(tail)
    if arr.ndim < nt or tuple(arr.shape[arr.ndim - nt:]) != tuple(tail):
        raise ValueError(f"{name} must have shape {_describe(tail)}{what}; got shape {arr.shape}")
    # Fast path: the sum of finite numbers is finite unless it overflows; only then look closer.
    if not allow_nan and arr.size and not np.isfinite(arr.sum()):
        if not np.isfinite(arr).all():
            raise ValueError(
                f"{name} contains NaN or infinite entries; every entry must be a finite number"
            )
    return arr


def check_positive(value, name, *, allow_zero=False):
    """Return ``value`` as a float array after checking that every entry is a positive number."""
    if isinstance(value, bool) or value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a positive number; got {value!r}")
    arr = as_array(value, name)
    bad = arr < 0 if allow_zero else arr <= 0
    if np.any(bad):
        kind = "non-negative" if allow_zero else "positive"
        raise ValueError(f"{name} must be {kind}; got {value!r}")
    return arr

"""Input checking shared by every gm_core module (numpy only).

Every public function turns its arguments into float arrays through :func:`as_array`, so a
student who passes a string, a complex number, a list of the wrong length or a NaN gets an error
that names the argument and says what was expected, instead of an ``IndexError`` from deep inside
numpy or, worse, a silently wrong number. Counts (steps, sizes, dimensions) go through
:func:`check_int`, shapes through :func:`check_shape`, and two arrays that must broadcast through
:func:`batch_shape`, whose message names both arguments.
"""
from __future__ import annotations

import numbers
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["as_array", "check_positive", "check_lengths", "real_number", "positive_number", "check_int",
           "check_shape", "batch_shape", "check_option", "SingularShapeError", "MAX_ELEMENTS", "FloatArray",
           "BoolArray"]

#: The arrays gm_core's numeric functions return: floats (..., k) and boolean masks (...,).
FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: Largest number of entries a size or batch-shape argument may ask for (about 0.8 GB of floats).
MAX_ELEMENTS = 10**8


class SingularShapeError(ValueError):
    """Raised when a computation reaches a singular configuration (for example a shape where a
    local connection does not exist). The message says "singular" and where it happened."""


def _describe(tail):
    return "(..., " + ", ".join(str(s) for s in tail) + ")" if tail else "a scalar or array"


def _of_shape(tail):
    return f" of shape {_describe(tail)}" if tail else ""


def _refuse(name, tail, what, value, why):
    raise TypeError(
        f"{name} must be a numeric array{_of_shape(tail)}{what}; got "
        f"{type(value).__name__}{why}"
    ) from None


def as_array(value: Any, name: str, tail: tuple[int, ...] = (), *, what: str = "",
             allow_nan: bool = False) -> FloatArray:
    """Return ``value`` as a float64 array whose trailing axes are ``tail``.

    Raises ``TypeError`` for non-numeric input (strings, None, objects, booleans, complex numbers)
    and ``ValueError`` for a wrong trailing shape or for NaN/inf entries, naming ``name`` and the
    expected shape.
    """
    if isinstance(value, np.ndarray) and value.dtype == np.float64:
        arr = value
    else:
        if value is None or isinstance(value, (str, bytes)):
            _refuse(name, tail, what, value, "")
        try:
            raw = value if isinstance(value, np.ndarray) else np.asarray(value)
        except (TypeError, ValueError, OverflowError):
            _refuse(name, tail, what, value, f" {value!r:.60}, which is not a list of numbers")
        kind = raw.dtype.kind
        if kind == "c":
            _refuse(name, tail, what, value, " with complex entries (only real numbers are accepted)")
        if kind == "b" or isinstance(value, (bool, np.bool_)):
            _refuse(name, tail, what, value, " with boolean entries (True/False are not numbers here)")
        if kind not in "iuf" and kind != "O":
            _refuse(name, tail, what, value, f" {value!r:.60}, which is not a list of numbers")
        if kind == "O" and any(isinstance(v, (complex, np.complexfloating, bool, np.bool_))
                               for v in raw.ravel()):
            _refuse(name, tail, what, value, " with complex or boolean entries")
        try:
            arr = raw.astype(np.float64)
        except (TypeError, ValueError):
            _refuse(name, tail, what, value, f" {value!r:.60}, which is not a list of numbers")
        except OverflowError:
            raise ValueError(f"{name} has an entry too large for a float; every entry must be a "
                             f"finite number") from None
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


def check_positive(value: Any, name: str, *, allow_zero: bool = False) -> FloatArray:
    """Return ``value`` as a float array after checking that every entry is a positive number."""
    if isinstance(value, bool) or value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be a positive number; got {value!r}")
    arr = as_array(value, name)
    bad = arr < 0 if allow_zero else arr <= 0
    if np.any(bad):
        kind = "non-negative" if allow_zero else "positive"
        raise ValueError(f"{name} must be {kind}; got {value!r:.80}")
    return arr


def check_lengths(lengths: ArrayLike, n: int, name: str = "lengths") -> FloatArray:
    """Return ``lengths`` as a float array of exactly ``n`` positive numbers (link lengths, weights)."""
    arr = check_positive(lengths, name)
    if arr.ndim != 1 or arr.shape[0] != n:
        raise ValueError(f"{name} must be a sequence of {n} positive numbers; got shape {arr.shape}")
    return arr


def real_number(value: Any, name: str, what: str = "") -> float:
    """Return ``value`` as a Python float after checking it is one finite real number (not an array)."""
    arr = as_array(value, name, what=what)
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a single number{what}; got an array of shape {arr.shape}")
    return float(arr)


def positive_number(value: Any, name: str, *, allow_zero: bool = False, what: str = "",
                    maximum: float | None = None) -> float:
    """Return ``value`` as a Python float after checking it is one positive (or, with
    ``allow_zero``, non-negative) finite number, at most ``maximum`` if given (a physical size
    whose powers must not overflow)."""
    arr = check_positive(value, name, allow_zero=allow_zero)
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a single number{what}; got an array of shape {arr.shape}")
    if maximum is not None and arr > maximum:
        raise ValueError(f"{name} must be at most {maximum:g}{what}; got {float(arr):g}")
    return float(arr)


def check_int(value: Any, name: str, minimum: int = 1, maximum: float | None = None, what: str = "") -> int:
    """Return ``value`` as a Python int in ``[minimum, maximum]``.

    Integral floats (``3.0``) are accepted; booleans, other floats, strings and None raise
    ``TypeError``; values out of range ``ValueError``. Both messages name ``name`` (and add
    ``what``, e.g. ``" (frames to return)"``).
    """
    rng = (f">= {minimum}" if maximum is None else f"between {minimum} and {maximum}") + what
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (numbers.Integral, float, np.floating)):
        raise TypeError(f"{name} must be an integer {rng}; got {type(value).__name__} {value!r:.60}")
    if not isinstance(value, numbers.Integral):
        if not np.isfinite(value) or not float(value).is_integer():
            raise TypeError(f"{name} must be an integer {rng}; got {value!r}")
        value = int(value)
    value = int(value)
    if value < minimum or (maximum is not None and value > maximum):
        raise ValueError(f"{name} must be an integer {rng}; got {value}")
    return value


def check_shape(value: Any, name: str, max_elements: int = MAX_ELEMENTS) -> tuple[int, ...]:
    """Return ``value`` (an int or a sequence of ints >= 0) as a shape tuple.

    The total number of entries is capped at ``max_elements`` so a typo cannot exhaust memory.
    """
    if isinstance(value, (numbers.Integral, np.integer)) and not isinstance(value, (bool, np.bool_)):
        dims = (value,)
    elif isinstance(value, (tuple, list)):
        dims = tuple(value)
    elif isinstance(value, np.ndarray) and value.ndim == 1 and value.dtype.kind in "iu":
        dims = tuple(value.tolist())
    else:
        raise TypeError(f"{name} must be a shape (an int or a tuple of ints >= 0); "
                        f"got {type(value).__name__} {value!r:.60}")
    out = tuple(check_int(d, f"{name}[{i}]" if len(dims) > 1 else name, minimum=0) for i, d in enumerate(dims))
    if int(np.prod(out, dtype=object)) > max_elements:
        raise ValueError(f"{name} = {out} asks for more than {max_elements:.0e} entries")
    return out


def batch_shape(*named: tuple[str, Any, int], tails: Any = None) -> tuple[int, ...]:
    """Broadcast batch shape of named arrays, naming them if they do not broadcast.

    ``named`` is a sequence of ``(name, array, n_tail)``: the last ``n_tail`` axes of each array
    are its per-item shape, the rest its batch shape.
    """
    shapes = [a.shape[: a.ndim - nt] for _, a, nt in named]
    if all(s == shapes[0] for s in shapes):
        return shapes[0]
    try:
        return np.broadcast_shapes(*shapes)
    except ValueError:
        parts = " and ".join(f"{n} (batch shape {s})" for (n, _, _), s in zip(named, shapes))
        raise ValueError(f"{parts} do not broadcast together: give them equal batch shapes, or "
                         f"batch shapes that numpy can broadcast") from None


def check_option(value: Any, name: str, options: Any) -> str:
    """Return ``value`` after checking it is one of the strings ``options`` (ValueError otherwise)."""
    if not isinstance(value, str) or value not in options:
        listed = ", ".join(repr(o) for o in options)
        raise ValueError(f"{name} must be one of {listed}; got {value!r:.60}")
    return value

"""Reading a student's answer: numbers, arrays, sympy objects, readable descriptions.

These helpers run on the student side (inside the sandbox's probes): they turn whatever was
handed in into float arrays, or raise :class:`Wrong` / :class:`Unattempted` with a message.
"""
from __future__ import annotations

import warnings
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, SupportsFloat

import numpy as np
import numpy.typing as npt

from gm_core.checks.sandbox import Unattempted, Wrong

if TYPE_CHECKING:
    import sympy


def is_starter(value: object) -> bool:
    """True for the untouched starter values None and Ellipsis."""
    return value is None or value is Ellipsis


def is_sympy(value: object) -> bool:
    """True for an object of sympy (an expression, a matrix, an equation, a number)."""
    return type(value).__module__.split(".")[0] == "sympy"


def _article(word: str) -> str:
    return "an" if word[:1].lower() in "aeiou" else "a"


def describe(value: object) -> str:
    """A short description of ``value`` for a message: "a numpy array of shape (3,)", "a dict"."""
    t = type(value).__name__
    if isinstance(value, np.ndarray):
        return f"a numpy array of shape {value.shape}"
    if isinstance(value, (list, tuple)):
        return f"{_article(t)} {t} of length {len(value)}"
    if isinstance(value, str):
        return f"the string {value[:40]!r}"
    return f"{_article(t)} {t}"


def _fmt_float(x: SupportsFloat) -> str:
    """A float as a person writes it: 4 significant digits, 1 not 1., 0 not -0 or 1e-17."""
    x = float(x)
    return f"{(0.0 if abs(x) < 1e-12 else x) + 0.0:.4g}"


def fmt_value(a: object) -> str:
    """A plain, short text for a number or array (never ``np.float64(1.0)``, ``1.`` or ``-0.``)."""
    if isinstance(a, np.ndarray):
        return np.array2string(a, separator=", ", formatter={"float_kind": _fmt_float})
    if isinstance(a, (bool, np.bool_)):
        return str(bool(a))
    if isinstance(a, (int, np.integer)):
        return str(int(a))
    if isinstance(a, (float, np.floating)):
        return _fmt_float(a)
    if isinstance(a, (list, tuple)):
        return "(" + ", ".join(fmt_value(x) for x in a) + ")"
    return repr(a)


def fmt_args(args: Sequence[object]) -> str:
    """``args`` as a parenthesised list of short values: "(1, [0, 1])"."""
    return "(" + ", ".join(fmt_value(a) for a in args) + ")"


def _sympy_to_list(value: Any) -> Any:
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [_sympy_to_list(v) for v in value]
    return value


def to_numbers(value: Any, what: str = "your answer") -> np.ndarray:
    """Numbers, lists, numpy arrays, sympy numbers/matrices (or lists of them) -> float array.

    Raises :class:`Wrong` for strings, leftover symbols, ragged lists and complex numbers with a
    non-zero imaginary part. NaN and inf are passed through (the judge names the input).
    """
    if is_starter(value):
        raise Unattempted()
    if isinstance(value, (str, bytes)) or isinstance(value, dict) or (
            callable(value) and not is_sympy(value) and not isinstance(value, np.ndarray)):
        raise Wrong(f"{what} is {describe(value)}; a number or an array of numbers was expected.")
    if is_sympy(value) or isinstance(value, (list, tuple)):
        free: set[str] = set()
        stack = [value]
        while stack:
            v = stack.pop()
            if isinstance(v, (list, tuple)):
                stack.extend(v)
            elif is_sympy(v):
                free |= {str(s) for s in getattr(v, "free_symbols", set())}
        if free:
            raise Wrong(f"{what} still contains the symbol(s) {', '.join(sorted(free))}; a number "
                        "was expected here.")
        if is_sympy(value) or any(is_sympy(v) for v in np.ravel(np.array(value, dtype=object))
                                  if not isinstance(v, (list, tuple))):
            try:
                value = np.array(_sympy_to_list(value), dtype=complex)
            except Exception:  # noqa: BLE001
                raise Wrong(f"{what} is a sympy object that could not be turned into numbers.") from None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            arr = np.array(value)
            if arr.dtype.kind == "c":
                if arr.size and np.nanmax(np.abs(arr.imag)) > 1e-12 * max(1.0, float(np.nanmax(np.abs(arr.real)) if arr.size else 1.0)):
                    raise Wrong(f"{what} is complex (imaginary part up to "
                                f"{float(np.nanmax(np.abs(arr.imag))):.3g}); a real number or array was "
                                "expected. Take .real only if you know the imaginary part must vanish.")
                arr = arr.real
            arr = np.asarray(arr, dtype=float)
    except Wrong:
        raise
    except Exception:  # noqa: BLE001
        raise Wrong(f"{what} is {describe(value)}, which is not a number or a (rectangular) array "
                    "of numbers.") from None
    return arr


def to_array(value: Any, what: str = "your answer") -> np.ndarray:
    """Like :func:`to_numbers`, but NaN or infinite entries are an error too."""
    arr = to_numbers(value, what)
    if arr.size and not np.all(np.isfinite(arr)):
        raise Wrong(f"{what} contains NaN or infinite entries.")
    return arr


def match_shape(got: np.ndarray, expected_shape: Sequence[int], what: str = "your answer") -> np.ndarray:
    """Return ``got`` reshaped to ``expected_shape`` if it only differs by singleton axes."""
    if got.shape == tuple(expected_shape):
        return got
    if got.size == int(np.prod(expected_shape)) and (
            tuple(s for s in got.shape if s != 1) == tuple(s for s in expected_shape if s != 1)):
        return got.reshape(expected_shape)
    if got.ndim == 2 and len(expected_shape) == 2 and got.shape == tuple(expected_shape)[::-1] \
            and got.shape[0] != got.shape[1]:
        raise Wrong(f"{what} has shape {got.shape}, but shape {tuple(expected_shape)} was expected: "
                    "is it transposed?")
    raise Wrong(f"{what} has shape {got.shape}, but shape {tuple(expected_shape)} was expected.")


def sympy_expr(answer: Any, what: str = "your expression") -> Any:
    """A sympy expression or Matrix from a sympy answer, a (nested) list of them, or ``Eq``."""
    import sympy as sp

    if isinstance(answer, (list, tuple)):
        try:
            return sp.Matrix(answer)
        except Exception:  # noqa: BLE001
            raise Wrong(f"{what} is a list that sympy cannot read as a matrix (ragged?).") from None
    if isinstance(answer, sp.Equality):
        return answer
    return answer


def equation_value(eq: sympy.Equality, names: Sequence[str]) -> sympy.Expr:
    """``Eq(lhs, rhs)``: the right-hand side when the left is a name for the result, else lhs - rhs."""
    lhs, rhs = eq.lhs, eq.rhs
    if getattr(lhs, "is_Symbol", False) and str(lhs) not in names:
        return rhs
    if getattr(lhs, "is_Function", False) and not getattr(lhs, "is_number", False) and \
            type(lhs).__module__.startswith("sympy.core.function"):
        return rhs
    return lhs - rhs


def sympy_function(answer: Any, names: Sequence[str], flat: Callable[..., Sequence[Any]] | None = None,
                   what: str = "your expression") -> Callable[..., Any] | None:
    """A numeric function of the part's arguments from a sympy answer (symbols matched by name).

    Returns None if ``answer`` is not a sympy object after all. ``flat(*args)`` maps the part's
    arguments to the values of ``names``.
    """
    import sympy as sp

    expr = sympy_expr(answer, what)
    if isinstance(expr, sp.Equality):
        expr = equation_value(expr, names)
    if not hasattr(expr, "free_symbols"):
        return None
    free = {str(s): s for s in expr.free_symbols}
    extra = sorted(set(free) - set(names))
    if extra:
        raise Wrong(f"{what} contains the symbol(s) {', '.join(extra)}; only "
                    f"{', '.join(names)} may appear.")
    symbols = [free.get(n, sp.Symbol(n)) for n in names]
    try:
        f = sp.lambdify(symbols, expr, modules="numpy")
    except Exception as exc:  # noqa: BLE001
        raise Wrong(f"{what} could not be evaluated numerically ({type(exc).__name__}).") from None
    flat = flat or (lambda *a: a)

    def call(*args: Any) -> Any:
        out = f(*flat(*args))
        if isinstance(out, (list, tuple)):
            out = np.array(np.broadcast_arrays(*[np.asarray(o) for o in out])
                           if out and not isinstance(out[0], (list, tuple)) else
                           [np.broadcast_arrays(*[np.asarray(o) for o in row]) for row in out])
        return out
    return call


def sample_gait(answer: Any, joints: int, example: str, n: int = 256,
                extra: npt.ArrayLike = ()) -> np.ndarray:
    """A student's gait (a Gait, a callable t -> r(t) of period 1, or an array of shapes (K, joints))
    sampled at ``n + 1`` equal times over one period, then at the fractions ``extra`` of the
    period (:mod:`gm_core.checks.gait_samples` draws them from the probe salt): the student side of the gait
    exercises.

    ``example`` names a constructor to suggest (e.g. ``"circle_gait(...)"``). Raises Unattempted for
    the starter value and Wrong, with a friendly message, for anything that is not a gait.
    """
    from gm_core.systems.gaits import Gait, as_gait

    if is_starter(answer):
        raise Unattempted()
    if isinstance(answer, (str, bytes, bool, np.bool_, dict)) or np.isscalar(answer) or not (
            isinstance(answer, (Gait, list, tuple, np.ndarray)) or callable(answer)):
        raise Wrong(f"your answer is {describe(answer)}; hand in a Gait (e.g. {example}), a "
                    f"callable t -> r(t) of period 1 or an array of shapes (K, {joints}).")
    if not callable(answer):
        pts = to_numbers(answer, "your array of shapes")
        if pts.ndim == 2 and pts.shape[0] == joints and pts.shape[1] > joints:
            raise Wrong(f"your array has shape {pts.shape}: one row per shape, (K, {joints}), was "
                        "expected (transpose it).")
        if pts.ndim != 2 or pts.shape[1] != joints or pts.shape[0] < 3:
            raise Wrong(f"your array has shape {pts.shape}; an array of K >= 3 shapes, (K, {joints}), "
                        "was expected.")
        if not np.all(np.isfinite(pts)):
            raise Wrong("your array of shapes contains NaN or infinite entries.")
        answer = pts
    gait = as_gait(answer)  # a callable of one time at a time works too (Gait handles it)
    period = float(gait.period)
    t = np.concatenate([np.linspace(0.0, period, n + 1), period * np.asarray(extra, dtype=float)])
    return to_numbers(gait(t), "the shapes your gait returned")

"""A small harness for fuzzing gm_core's public entry points with bad input (hypothesis).

A :class:`Case` names a callable and gives one *valid* example value per argument. The harness
replaces one argument at a time with a bad or unusual value and checks the outcome:

* the call returns a result whose numbers are finite (unless the case allows non-finite output,
  e.g. the infinite radius of a straight path) and whose array has the declared trailing shape,
  and equals the valid call's result when the replacement was an equivalent spelling of the
  same numbers (a list, an object array, integers); or
* it raises ``ValueError`` / ``TypeError`` whose message names the replaced argument.

Anything else (an ``IndexError``, a ``RuntimeWarning`` from an overflow, a ``ComplexWarning``, an
error naming an internal variable, a silently accepted NaN or complex number) is a failure.

Extending it to another module is a matter of adding rows to a table of ``Case`` objects (see
``tests/test_fuzz_math.py``). The tests run the table in :func:`chunks` of cases, one pytest item
per chunk: :func:`check_each` runs a check on every case of its chunk (every case runs, even after
one fails, and the failure names each failing case); :func:`fuzz_each` gives every case its own
hypothesis search (the same examples as one test per case).
"""
from __future__ import annotations

import dataclasses
import re
import warnings
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from hypothesis import strategies as st

__all__ = ["Case", "run_case", "baseline", "mutations", "outcome", "chunks", "check_each", "fuzz_each"]


@dataclass
class Case:
    """One public callable and a valid example call.

    ``args`` maps argument names to valid values in call order; names in ``kwonly`` are passed by
    keyword. The kind of each argument decides its mutations: ``ints`` are counts (integers with
    bounds), ``shapes`` are shape arguments (``batch_shape``, ``size``), ``options`` are option
    strings, ``flags`` are booleans, ``callables`` are functions, ``objects`` are passed through
    untouched except for type errors (groups, rngs); everything else is a numeric array.
    ``also_raises`` lists further documented exception types (e.g. ``RuntimeError`` when a
    solver fails), whose messages need not name an argument; ``also_valid`` maps an argument
    to values that are valid too (a default None, an int seed);
    ``batch`` lists array arguments whose leading axes broadcast together, ``nan_ok`` arguments
    that may hold NaN, ``out_tail`` the trailing shape of an array result, ``finite`` whether
    every number in the result must be finite, ``extra_kw`` whether unknown keywords are checked.
    """

    name: str
    func: Callable
    args: dict
    kwonly: frozenset = frozenset()
    ints: frozenset = frozenset()
    shapes: frozenset = frozenset()
    options: frozenset = frozenset()
    flags: frozenset = frozenset()
    callables: frozenset = frozenset()
    objects: frozenset = frozenset()
    batch: tuple = ()
    nan_ok: frozenset = frozenset()
    also_valid: dict = dataclasses.field(default_factory=dict)
    also_raises: tuple = ()
    out_tail: tuple | None = None
    finite: bool = True
    extra_kw: bool = True

    def __post_init__(self):
        for f in ("kwonly", "ints", "shapes", "options", "flags", "callables", "objects", "nan_ok"):
            setattr(self, f, frozenset(getattr(self, f)))

    def __repr__(self):
        return self.name

    def kind(self, name):
        for kind in ("ints", "shapes", "options", "flags", "callables", "objects"):
            if name in getattr(self, kind):
                return kind
        return "arrays"

    def call(self, args, extra=None):
        pos = [v for k, v in args.items() if k not in self.kwonly]
        kw = {k: v for k, v in args.items() if k in self.kwonly}
        kw.update(extra or {})
        return self.func(*pos, **kw)


# ------------------------------------------------------------------ mutations
class _Opaque:
    def __repr__(self):
        return "<object>"


GARBAGE = [None, "abc", b"\x00", {"x": 1}, _Opaque()]
ORIGINAL = object()   # "the valid example value itself"
#: A mutation is (kind, value, equivalent): ``equivalent`` is a value that must give the same
#: result (or None when no result is promised).
SHAPES = [(), (0,), (1,), (2,), (4,), (5,), (2, 1), (2, 3), (0, 3), (3, 3), (1, 1, 1)]


def _array_mutations(v, rng_draw):
    v = np.asarray(v, dtype=float)
    out = [("garbage", g, None) for g in GARBAGE]
    out.append(("complex", v.astype(complex), None))
    out.append(("complex-list", (v.astype(complex) + 1j).tolist(), None))
    out.append(("bool", v.astype(bool), None))
    out.append(("list", v.tolist(), ORIGINAL))
    out.append(("object", v.astype(object), ORIGINAL))
    rounded = np.round(v)
    out.append(("int", rounded.astype(np.int64), rounded if v.ndim else float(rounded)))
    for shape in SHAPES:
        out.append(("shape", np.ones(shape) * 0.5, None))
    out.append(("empty", np.empty((0,) + v.shape), None))
    out.append(("0-d", np.array(0.5), None))
    if v.size:
        for bad in (np.nan, np.inf, -np.inf):
            w = v.copy()
            w.flat[rng_draw(v.size)] = bad
            out.append(("nonfinite", w, None))
    out.append(("huge", v * 1e300, None))
    out.append(("tiny", v * 1e-300, None))
    out.append(("negated", -v, None))
    return out


def _int_mutations(v):
    bad = [("count-bad", x, None) for x in (-1, 10**12, 2.5, True, "3", None, np.inf, np.nan, 1j, [2])]
    return bad + [("count-zero", 0, None)]


def _shape_mutations(v):
    bad = [("shape-bad", x, None) for x in (-1, (2, -1), "3", 2.5, None, (10**6, 10**6), True)]
    return bad + [("shape-ok", x, None) for x in ((), 0, (0, 2))]


def _option_mutations(v):
    return [("option", x, None) for x in ("nonsense", "", None, 3, ("left",))]


def _flag_mutations(v):
    return [("flag", x, None) for x in (None, "yes", 2, np.array([True, False]))]


def _callable_mutations(v):
    return [("callable", x, None) for x in (None, 3, "f", np.ones(3))]


def _object_mutations(v):
    return [("object-arg", x, None) for x in (None, "SE2", 3, np.ones(3))]


_BY_KIND = {"ints": _int_mutations, "shapes": _shape_mutations, "options": _option_mutations,
            "flags": _flag_mutations, "callables": _callable_mutations, "objects": _object_mutations}


@st.composite
def mutations(draw, case):
    """``(argument name, kind, new args, equivalent args or None)`` for one mutated call."""
    names = list(case.args)
    options = ["arg"] + (["batch"] if len(case.batch) >= 2 else []) + (["extra_kw"] if case.extra_kw else [])
    which = draw(st.sampled_from(options))
    if which == "extra_kw":
        return "bogus_option", "extra_kw", dict(case.args), None
    if which == "batch":
        a, b = draw(st.permutations(list(case.batch)))[:2]
        args = dict(case.args)
        args[a] = np.broadcast_to(np.asarray(args[a], float), (7,) + np.shape(args[a])).copy()
        args[b] = np.broadcast_to(np.asarray(args[b], float), (5,) + np.shape(args[b])).copy()
        return (a, b), "batch", args, None
    name = draw(st.sampled_from(names))
    kind = case.kind(name)
    if kind == "arrays":
        pool = _array_mutations(case.args[name], lambda n: draw(st.integers(0, n - 1)))
    else:
        pool = _BY_KIND[kind](case.args[name])
    valid = case.also_valid.get(name, ())
    pool = [m for m in pool if not any(m[1] is v or (type(m[1]) is type(v) and m[1] == v) for v in valid)]
    label, value, equivalent = draw(st.sampled_from(pool))
    args = dict(case.args)
    args[name] = value
    equiv = None
    if equivalent is not None:
        equiv = dict(case.args)
        equiv[name] = case.args[name] if equivalent is ORIGINAL else equivalent
    return name, label, args, equiv


# ------------------------------------------------------------------ outcomes
def _numbers(x, path="result"):
    """Yield (path, float array) for every number inside a result."""
    if isinstance(x, (bool, np.bool_, str, bytes)) or x is None:
        return
    if isinstance(x, np.ndarray):
        if x.dtype.kind in "fiu":
            yield path, x.astype(float)
        elif x.dtype.kind == "c":
            yield path, np.array([np.nan])         # a complex result is never right here
        return
    if isinstance(x, (int, float, np.number)):
        yield path, np.asarray(float(x))
        return
    if isinstance(x, (tuple, list)):
        for i, item in enumerate(x):
            yield from _numbers(item, f"{path}[{i}]")
        return
    if isinstance(x, dict):
        for k, item in x.items():
            yield from _numbers(item, f"{path}[{k!r}]")
        return
    if dataclasses.is_dataclass(x):
        for f in dataclasses.fields(x):
            yield from _numbers(getattr(x, f.name), f"{path}.{f.name}")


def _names(message, names):
    return any(re.search(rf"(?<![\w]){re.escape(n)}(?![\w])", message) for n in names)


def outcome(case, args, extra=None):
    """Call the case; return ("ok", result) or ("error", exception). Warnings are errors."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            return "ok", case.call(args, extra)
        except (ValueError, TypeError) as exc:
            return "error", exc


def baseline(case):
    """The valid call must succeed with a finite, right-shaped result; returns it."""
    status, result = outcome(case, case.args)
    assert status == "ok", f"{case.name}: the valid example raised {result!r}"
    _check_result(case, result, "valid example")
    return result


def _check_result(case, result, what):
    if case.finite:
        for path, arr in _numbers(result):
            assert np.isfinite(arr).all(), f"{case.name} ({what}): {path} is not finite: {arr!r:.200}"
    if case.out_tail is not None:
        assert isinstance(result, np.ndarray), f"{case.name} ({what}): expected an array, got {type(result)}"
        n = len(case.out_tail)
        assert result.shape[result.ndim - n:] == case.out_tail, (
            f"{case.name} ({what}): result shape {result.shape}, expected (..., {case.out_tail})")


def run_case(case, mutation):
    """Check one mutated call (see the module docstring for what is allowed)."""
    name, kind, args, equiv = mutation
    extra = {"bogus_option": 1} if kind == "extra_kw" else None
    names = name if isinstance(name, tuple) else (name,)
    what = f"{names} <- {kind}: {_short(args.get(names[0]))}"
    try:
        status, result = outcome(case, args, extra)
    except case.also_raises:
        return
    except Exception as exc:      # noqa: BLE001 -- any other exception type is the failure we look for
        raise AssertionError(f"{case.name} ({what}) raised {type(exc).__name__}: {exc}") from exc
    if status == "error":
        msg = str(result)
        assert _names(msg, names), f"{case.name} ({what}): the error does not name {names}: {msg!r}"
        if equiv is not None:
            st2, _ = outcome(case, equiv)
            assert st2 == "error", f"{case.name} ({what}): refused an equivalent spelling of a valid call: {msg}"
        return
    assert kind not in ("garbage", "complex", "complex-list", "bool", "nonfinite", "option",
                        "callable", "object-arg", "flag", "extra_kw", "batch", "count-bad",
                        "shape-bad") or (
        kind == "nonfinite" and name in case.nan_ok), (
        f"{case.name} ({what}): accepted bad input silently and returned {_short(result)}")
    _check_result(case, result, what)
    if equiv is not None:
        st2, ref = outcome(case, equiv)
        assert st2 == "ok", f"{case.name} ({what}): an equivalent spelling succeeded but the float one raised {ref}"
        for (p1, a1), (_, a2) in zip(_numbers(result), _numbers(ref)):
            np.testing.assert_array_equal(a1, a2, err_msg=f"{case.name} ({what}): {p1} differs")


def _short(x):
    return f"{x!r}"[:120]


def cases_table(*groups_of_cases):
    """Flatten lists of cases into one list, checking names are unique."""
    out = [c for group in groups_of_cases for c in group]
    names = [c.name for c in out]
    dup = {n for n in names if names.count(n) > 1}
    assert not dup, f"duplicate case names: {dup}"
    return out



CHUNK = 20


def chunks(cases, size: int = CHUNK):
    """``pytest.param`` per run of ``size`` consecutive cases (id: first..last case name)."""
    import pytest

    out = []
    for i in range(0, len(cases), size):
        part = list(cases[i:i + size])
        out.append(pytest.param(part, id=f"{part[0].name}..{part[-1].name}" if len(part) > 1 else part[0].name))
    return out


def check_each(cases, check):
    """``check(case)`` for every case; then one failure listing every case that failed."""
    failures = []
    for case in cases:
        try:
            check(case)
        except Exception as exc:  # noqa: BLE001 - collected, reported below
            text = f"{type(exc).__name__}: {exc}"
            failures.append(f"{case.name}: {text[:2000]}")
    assert not failures, f"{len(failures)} of {len(cases)} cases failed:\n" + "\n".join(failures)


def fuzz_each(cases, profile):
    """A hypothesis search of ``profile``'s size over the mutations of each case, case by case."""
    from hypothesis import given, settings

    def one(case):
        @settings(profile)
        @given(data=st.data())
        def bad_input(data):
            run_case(case, data.draw(mutations(case)))

        bad_input()

    check_each(cases, one)

"""Assertions on one checker part's verdict, for the exercise-checker tests (tests/test_checks*.py).

Each runs ``part.check(answer, quiet=True)`` (its own probe sandbox; nothing printed) and fails with
the part, the status and the checker's message when the verdict is not the expected one; each
returns the verdict for further checks."""
from __future__ import annotations

from gm_core.checks.store import FAILED, PASSED, UNATTEMPTED


def _name(part) -> str:
    return f"{part.exercise.id}{part.name}"


def _check(part, answer, **kw):
    return part.check(answer, quiet=True, **kw)


def assert_check_passed(part, answer, **kw):
    """The answer passes (the verdict is truthy)."""
    v = _check(part, answer, **kw)
    assert v.status == PASSED and v, f"{_name(part)} should pass {answer!r}; {v.status}: {v.message}"
    return v


def assert_check_failed(part, answer, mentions=(), **kw):
    """The answer fails, and the message contains each of ``mentions`` (a string or several)."""
    v = _check(part, answer, **kw)
    assert v.status == FAILED, f"{_name(part)} should fail {answer!r}; {v.status}: {v.message}"
    for m in [mentions] if isinstance(mentions, str) else mentions:
        assert m in v.message, f"{_name(part)}: the message should mention {m!r}: {v.message}"
    return v


def assert_check_unattempted(part, answer, **kw):
    """The answer (a starter, None, ...) counts as not attempted."""
    v = _check(part, answer, **kw)
    assert v.status == UNATTEMPTED, f"{_name(part)} should call {answer!r} unattempted; {v.status}: {v.message}"
    return v

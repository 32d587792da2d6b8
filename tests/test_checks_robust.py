"""Checkers never hang and never raise (issue #14, point 1): each reproducer as a test."""
import os
import sys
import time
from dataclasses import FrozenInstanceError, replace

import numpy as np
import pytest

from gm_core import SE2, checks
from gm_core.checks.sandbox import (
    SandboxSettings,
    apply_settings,
    collect,
    current_settings,
    set_time_limit,
    using_settings,
)
from gm_core.checks.store import FAILED, PASSED

pytestmark = pytest.mark.usefixtures("clean")


@pytest.fixture
def short_limit():
    with using_settings(replace(current_settings(), time_limit=0.5)):
        yield


def test_endless_loop_is_stopped_and_the_kernel_stays_usable(short_limit):
    def forever(xi):
        while True:
            pass
    t = time.monotonic()
    v = checks.ex1_4.a.check(forever, quiet=True)
    assert time.monotonic() - t < 5
    assert v.status == FAILED and "took longer than 0.5 s" in v.message and "xi=" in v.message
    assert checks.ex1_4.a.check(checks.ex1_4.a.reference, quiet=True).passed   # still usable


def test_sleep_is_stopped(short_limit):
    v = checks.ex1_4.a.check(lambda xi: time.sleep(30), quiet=True)
    assert v.status == FAILED and "took longer" in v.message


def test_time_limit_is_per_check_call_and_configurable():
    v = checks.ex1_4.a.check(lambda xi: time.sleep(0.4) or SE2.exp(xi), quiet=True, time_limit=0.2)
    assert "took longer than 0.2 s" in v.message
    with pytest.raises(ValueError):
        set_time_limit(-1)


def test_sandbox_settings_change_only_through_the_settings_functions():
    before = current_settings()
    with pytest.raises(FrozenInstanceError):
        before.time_limit = 1.0  # type: ignore[misc]
    with pytest.raises(ValueError, match="time_limit"):
        SandboxSettings(time_limit=0)
    with using_settings(replace(before, time_limit=0.2, max_output_lines=2)) as inside:
        assert current_settings() is inside
        v = checks.ex1_4.a.check(lambda xi: time.sleep(0.4) or SE2.exp(xi), quiet=True)
        assert "took longer than 0.2 s" in v.message
        _, output = collect(None, [lambda a: print("1\n2\n3\n4")])
        assert output.startswith("1\n2\n...") and "4 lines in all" in output
        set_time_limit(3)
        assert current_settings() == replace(inside, time_limit=3.0)
    assert current_settings() is before
    assert apply_settings(apply_settings(replace(before, memory_mb=0))) == replace(before, memory_mb=0)
    assert current_settings() is before


@pytest.mark.parametrize("exc", [SystemExit(3), GeneratorExit(), StopIteration(), MemoryError()])
def test_base_exceptions_from_student_code_become_verdicts(exc):
    def f(xi):
        raise exc
    v = checks.ex1_4.a.check(f, quiet=True)
    assert v.status == FAILED and type(exc).__name__ in v.message


def test_sys_exit_does_not_escape():
    v = checks.ex1_4.a.check(lambda xi: sys.exit(3), quiet=True)
    assert v.status == FAILED and "SystemExit" in v.message


def test_exception_whose_str_raises_is_handled():
    class Hostile(Exception):
        def __str__(self):
            raise RuntimeError("no")

    def f(xi):
        raise Hostile()
    v = checks.ex1_4.a.check(f, quiet=True)
    assert v.status == FAILED and "Hostile" in v.message


def test_hard_crash_of_the_student_process_is_a_verdict():
    v = checks.ex1_4.a.check(lambda xi: os._exit(1), quiet=True)
    assert v.status == FAILED and "crashed" in v.message


def test_student_output_is_captured_and_truncated(capsys):
    def chatty(xi):
        for i in range(2000):
            print("line", i)
        return SE2.exp(xi)
    v = checks.ex1_4.a.check(chatty, quiet=True)
    assert v.passed and capsys.readouterr().out == ""     # nothing floods the notebook
    assert "line 0" in v.output and v.output.count("\n") < 40 and "not shown" in v.output
    checks.ex1_4.a.check(chatty)                            # shown, truncated, in the verdict box
    out = capsys.readouterr().out
    assert out.count("line ") < 40


def test_inputs_are_copied_for_every_call():
    seen = []

    def vandal(xi):
        seen.append(np.array(xi))
        out = SE2.exp(xi)
        xi[...] = 0.0
        return out
    assert checks.ex1_4.a.check(vandal, quiet=True).passed


def test_monkeypatching_inside_an_answer_cannot_change_the_judge():
    def sneaky(xi):
        import gm_core.checks.parts as core
        core.FunctionPart.close = lambda self, a, b: True
        return np.zeros(3)
    assert checks.ex1_4.a.check(sneaky, quiet=True).status == FAILED
    assert checks.ex1_4.a.check(lambda xi: np.zeros(3), quiet=True).status == FAILED


def test_in_process_fallback_still_catches_everything(monkeypatch):
    monkeypatch.setenv("GM_CHECKS_NO_FORK", "1")
    v = checks.ex1_4.a.check(lambda xi: sys.exit(2), quiet=True)
    assert v.status == FAILED and "SystemExit" in v.message
    assert checks.ex1_4.a.check(checks.ex1_4.a.reference, quiet=True).status == PASSED


def test_keyboard_interrupt_is_not_swallowed_in_process(monkeypatch):
    monkeypatch.setenv("GM_CHECKS_NO_FORK", "1")

    def f(xi):
        raise KeyboardInterrupt
    with pytest.raises(KeyboardInterrupt):
        checks.ex1_4.a.check(f, quiet=True)


def test_strict_mode_raises_assertion_with_the_same_message():
    p = checks.ex3_1.a
    v = p.check(lambda a1, a2, R, w: 0.0, quiet=True)
    with pytest.raises(AssertionError) as err:
        p.check(lambda a1, a2, R, w: 0.0, quiet=True, strict=True)
    assert v.message in str(err.value)
    assert p.check(p.reference, quiet=True, strict=True) is None   # doctest-style cells: nothing

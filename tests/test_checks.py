"""gm_core.checks: every checker passes the reference, fails plausible wrong answers with a message,
calls the untouched starter "unattempted", and turns junk (exceptions, NaN, wrong types and shapes)
into a verdict instead of a traceback. Also progress() and the widgets, headless."""
import subprocess
import sys

import numpy as np
import pytest
from checkbatch import check_each

from gm_core import checks
from gm_core.checks import EXERCISE_IDS
from gm_core.checks.exercise import REGISTRY, progress
from gm_core.checks.store import FAILED, PASSED, UNATTEMPTED

#: the starts of the checker's messages that say nothing about a particular wrong answer
GENERIC = ("Well done.", "The checker could not make sense of your answer", "The check stopped unexpectedly")
PARTS = [(ex_id, name) for ex_id in EXERCISE_IDS for name in REGISTRY[ex_id].parts]


def part(ex_id, name):
    return REGISTRY[ex_id].parts[name]


pytestmark = pytest.mark.usefixtures("clean")


def test_all_sixteen_exercises_are_registered():
    """The book's 13 (1.1-1.5, 2.1-2.4, 3.1-3.4), the curvature notebook's 4.1, 4.2 and the
    many-link notebook's 5.1, in course order; the same ids as the worked solutions on disk."""
    from pathlib import Path

    book = [f"{c}.{k}" for c, n in ((1, 5), (2, 4), (3, 4)) for k in range(1, n + 1)]
    expected = tuple(book) + ("4.1", "4.2", "5.1")
    assert len(book) == 13 and len(expected) == 16
    assert tuple(REGISTRY) == expected and EXERCISE_IDS == expected
    solutions = Path(__file__).resolve().parents[1] / "solutions"
    assert sorted(p.stem[2:].replace("_", ".") for p in solutions.glob("ex*_*.ipynb")) == sorted(expected)
    assert all(getattr(checks, "ex" + i.replace(".", "_")) is REGISTRY[i] for i in expected)


def verdicts_of(p, answers):
    """``[p.check(a, quiet=True) for a in answers]``, the probes of all answers run in one sandbox
    (tests/checkbatch.py), each answer judged on its own; one of them (a different one for each
    part, so every answer of a list is covered) also goes through ``check()`` itself, in a sandbox
    of its own, and must get the same verdict."""
    answers = list(answers)
    if len(answers) <= 2:   # a sandbox each costs no more than the batch plus the one check()
        return [p.check(a, quiet=True) for a in answers]
    verdicts = check_each(p, answers)
    k = PARTS.index((p.exercise.id, p.name)) % len(answers)
    v = p.check(answers[k], quiet=True)
    assert (v.status, v.message) == (verdicts[k].status, verdicts[k].message), (answers[k], v, verdicts[k])
    return verdicts


@pytest.mark.parametrize("ex_id,name", PARTS)
def test_reference_passes(ex_id, name):
    p = part(ex_id, name)
    v = p.check(p.reference, quiet=True)
    assert v.status == PASSED, v.message
    assert v and v.message


@pytest.mark.parametrize("ex_id,name", PARTS)
def test_wrong_answers_fail_with_a_message(ex_id, name):
    p = part(ex_id, name)
    assert p.wrong, f"{ex_id}{name} has no plausible wrong answer to test"
    for w, v in zip(p.wrong, verdicts_of(p, p.wrong), strict=True):
        assert v.status == FAILED and v.message.strip(), (w, v)
        # a hint about this answer, not one of the generic messages (junk, a crash, a pass)
        assert not v.message.startswith(GENERIC), (w, v)


@pytest.mark.parametrize("ex_id,name", PARTS)
def test_starter_is_unattempted(ex_id, name):
    p = part(ex_id, name)
    for v in verdicts_of(p, (p.starter, None, ...)):
        assert v.status == UNATTEMPTED, v


def starter_function(*args):
    return None  # what a generated exercise's `def f(...): return None  # your answer here` does


def raises(*args):
    raise ZeroDivisionError("division by zero")


JUNK = [
    "abc", 42, 3.5, float("nan"), object(), [1, 2], {}, {"x": 1}, np.full((7,), np.nan),
    np.zeros((4, 4, 4)), raises, lambda *a: np.full(7, np.nan), lambda *a: "text",
    lambda *a: np.zeros((9, 9)), lambda: 1.0, lambda *a: float("inf"), lambda *a: [1, [2, 3]],
    (raises, raises, raises, raises), (None, 1), True,
]


@pytest.mark.parametrize("ex_id,name", PARTS)
def test_junk_gives_a_verdict_not_a_traceback(ex_id, name, capsys):
    p = part(ex_id, name)
    for junk, v in zip(JUNK, verdicts_of(p, JUNK), strict=True):
        if p.kind == "choice" and isinstance(junk, str):
            # text that names no option asks for a letter and is not recorded as a wrong answer
            assert v.status == UNATTEMPTED and "letter" in v.message, (junk, v)
            continue
        assert v.status == FAILED, (junk, v)
        assert v.message and "Traceback" not in v.message
    assert capsys.readouterr().out == ""  # quiet=True prints nothing


FUNCTION_PARTS = [(e, n) for e, n in PARTS if part(e, n).kind == "function"]


@pytest.mark.parametrize("ex_id,name", FUNCTION_PARTS)
def test_starter_function_returning_none_is_unattempted(ex_id, name):
    assert part(ex_id, name).check(starter_function, quiet=True).status == UNATTEMPTED


def test_sympy_answer_with_foreign_symbol_names_it():
    import sympy as sp
    q = sp.Symbol("q")
    v = checks.ex1_2.b.check(sp.diag(q, q), quiet=True)
    assert v.status == FAILED and "q" in v.message


def test_exception_message_names_the_error_and_input():
    v = checks.ex1_4.a.check(raises, quiet=True)
    assert "ZeroDivisionError" in v.message and ("xi" in v.message.lower() or "called with" in v.message)


def test_nan_at_zero_rotation_is_reported():
    def naive(xi):
        vx, vy, w = xi
        return np.array([(vx * np.sin(w) - vy * (1 - np.cos(w))) / w,
                         (vx * (1 - np.cos(w)) + vy * np.sin(w)) / w, w])
    v = checks.ex1_4.a.check(naive, quiet=True)
    assert v.status == FAILED and "NaN" in v.message


def test_transposed_matrix_is_recognised():
    v = checks.ex2_2.a.check(lambda *a: part("2.2", "a").ref(*a).T, quiet=True)
    assert v.status == FAILED and "transposed" in v.message


def test_choice_accepts_letters_text_and_index():
    p = checks.ex1_1.a
    assert p.check("B", quiet=True).passed
    assert p.check(" (b) ", quiet=True).passed
    assert p.check(p.options["b"], quiet=True).passed
    assert p.check(1, quiet=True).passed
    assert p.check("", quiet=True).status == UNATTEMPTED


def test_hint_and_solution_show_their_text_once_and_never_raise(capsys):
    for ex_id, name in PARTS:
        p = part(ex_id, name)
        assert p.hint() is None and p.hint(2) is None and p.hint(99) is None and p.hint("junk") is None
        assert p.solution() is None          # no quoted Out[n] string after the rendered box
        assert p.hint_text(1) and "../solutions/ex" in p.solution_text_full()
    out = capsys.readouterr().out
    assert out.count("[Hint]") == 4 * len(PARTS) and out.count("[Solution]") == len(PARTS)


def test_check_prints_when_not_quiet(capsys):
    checks.ex1_1.a.check("b")
    assert "[Correct]" in capsys.readouterr().out


def test_progress_aggregates_parts():
    assert progress() == {i: UNATTEMPTED for i in EXERCISE_IDS}
    ex = checks.ex1_2
    ex.a.check(ex.a.reference, quiet=True)
    assert progress()["1.2"] == "in progress"        # some parts passed, the others unchecked
    ex.b.check(ex.b.wrong[0], quiet=True)
    assert progress()["1.2"] == FAILED               # latest check of a part failed
    for p in ex.parts.values():
        p.check(p.reference, quiet=True)
    assert progress()["1.2"] == PASSED
    assert set(progress()) == set(EXERCISE_IDS)
    assert all(progress()[i] == UNATTEMPTED for i in EXERCISE_IDS if i != "1.2")


def test_exercise_check_with_dict():
    ex = checks.ex1_1
    out = ex.check({"a": "b", "b": sorted(ex.b.key.correct)[0]})
    assert all(v.passed for v in out.values()) and progress()["1.1"] == PASSED
    assert ex.check("not a dict") == {}


def test_widgets_headless():
    w = checks.ex1_1.a.widget()
    w.radio.value = "b"
    w.button.click()
    assert "passed" in w.feedback.value and progress()["1.1"] == "in progress"  # part b unchecked
    box = checks.progress_widget()
    box.refresh()
    assert "1.1" in box.view.value and "3.4" in box.view.value


def test_slide_rule_reads_products():
    """ex1_5.slide_rule is the course's one slide rule drawing (SlideRuleScene), re-rendered."""
    from gm_core.drawing.groups import SlideRuleScene

    box = checks.ex1_5.slide_rule(2.0, 3.0)
    assert isinstance(box.scene, SlideRuleScene) and "slide_rule" in type(checks.ex1_5).__dict__
    sa, sb = box.sliders
    assert "D reads <b>6</b>" in box.readout.value        # not 5.998 (issue 12: log-slider rounding)
    first = box.view.value
    assert first[:8] == b"\x89PNG\r\n\x1a\n"
    for a, b in [(1.0, 1.0), (9.9, 9.9), (3.7, 2.4), (4.0, 2.5)]:
        sa.value, sb.value = a, b
        assert np.isclose(box.scene.reading, a * b)
        assert np.isclose(box.scene.cursor.get_xdata()[0], np.log10(a * b))
    assert "D reads <b>10</b>" in box.readout.value and box.view.value != first


def test_import_stays_light():
    code = ("import sys, gm_core, gm_core.checks; "
            "bad = [m for m in ('matplotlib', 'ipywidgets', 'sympy') if m in sys.modules]; "
            "print(bad)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_student_function_that_edits_its_input_cannot_corrupt_the_checker():
    from gm_core import SE2

    def vandal(xi):
        out = SE2.exp(xi)
        xi[...] = 0.0
        return out
    assert checks.ex1_4.a.check(vandal, quiet=True).passed
    assert checks.ex1_4.a.check(checks.ex1_4.a.reference, quiet=True).passed
    first = [a[0].copy() for a in checks.ex1_4.a.inputs()][:3]
    checks.ex1_4.a.check(vandal, quiet=True)
    assert all(np.array_equal(x, a[0]) for x, a in zip(first, checks.ex1_4.a.inputs()))


def test_one_sandbox_for_many_answers_falls_back_to_one_each_after_a_hang():
    """tests/checkbatch.py (used above): an answer that hangs is stopped at its own time limit, and
    it and every later answer get a sandbox each, so their verdicts are check()'s."""
    import time

    def hangs(*args):
        while True:
            time.sleep(0.01)

    p = part("1.2", "a")
    answers = [lambda *a: "text", hangs, raises]
    batch = check_each(p, answers, time_limit=0.5)
    single = [p.check(a, quiet=True, time_limit=0.5) for a in answers]
    assert [(v.status, v.message) for v in batch] == [(v.status, v.message) for v in single]
    assert batch[1].status == FAILED and "second" in batch[1].message, batch[1].message

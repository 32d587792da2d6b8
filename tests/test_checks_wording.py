"""Feedback in the student's words (issue 36, "what the student sees" 5): where a checker says which
entries of a list or array differ, it counts from 1 and names them ("the second entry"), never
Python's indices counted from 0; a multiple-choice answer given as a number says which option
that number is. The judges are called with plain probe outcomes (what the sandbox returns), so
each message is checked without a sandbox."""
import re

import numpy as np
import pytest

from gm_core import checks
from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import REGISTRY, exercise_ids
from gm_core.checks.parts import FunctionPart, TuplePart, Verdict
from gm_core.checks.sandbox import Wrong
from gm_core.checks.store import FAILED, PASSED
from gm_core.checks.wording import differing_entries, entry_name, ordinal

pytestmark = pytest.mark.usefixtures("clean")

#: How the old messages said it: "(entries 1 differ)", "(entries (0, 1), (2, 1) differ)"
ZERO_BASED = re.compile(r"entr(y|ies) \(?\d")


@pytest.mark.parametrize("n, word", [(1, "first"), (2, "second"), (3, "third"), (10, "tenth"),
                                     (12, "twelfth"), (13, "13th"), (21, "21st"), (22, "22nd"),
                                     (23, "23rd"), (111, "111th"), (112, "112th")])
def test_ordinals(n, word):
    assert ordinal(n) == word


@pytest.mark.parametrize("indices, shape, text", [
    ([[1]], (2,), "the second entry differs"),
    ([[0], [2]], (3,), "the first and third entries differ"),
    ([[0], [1]], (2,), "every entry differs"),
    ([[0], [1], [2], [4], [5]], (7,), "the first, second, third and 2 more entries differ"),
    ([[1, 0]], (3, 2), "the entry in the second row and first column differs"),
    ([[1, 0], [1, 2]], (3, 3), "in the second row, the first and third entries differ"),
    ([[0, 2], [2, 2]], (3, 3), "in the third column, the first and third entries differ"),
    ([[0, 2], [1, 2], [2, 2]], (3, 3), "the whole third column differs"),
    ([[2, 0], [2, 1]], (3, 2), "the whole third row differs"),
    ([[0, 2], [1, 0]], (3, 3), "the entry in the first row and third column and the entry in the "
                               "second row and first column differ"),
    ([[0, 2, 4]], (3, 3, 5), "the entry in the third row and fifth column of the first matrix differs"),
    ([[2, 0]], (3, 1), "the third entry differs"),            # a column: its entries, not rows
    ([[0, 1]], (1, 3), "the second entry differs"),
    ([], (3,), ""),
])
def test_differing_entries_are_counted_from_one_and_named(indices, shape, text):
    assert differing_entries(np.array(indices, dtype=int).reshape(-1, len(shape)), shape) == text


def test_an_entry_of_a_higher_array_says_how_it_counts():
    assert entry_name((0, 1, 2, 3), (2, 2, 3, 4)) == "the entry at position (1, 2, 3, 4) (counting from 1)"


def _function_parts():
    """Every FunctionPart of the course with the label its message carries and its key (TuplePart
    components too, with their keys in the tuple's key)."""
    out = []
    for ex_id in exercise_ids():
        for name, part in REGISTRY[ex_id].parts.items():
            if isinstance(part, FunctionPart):
                out.append((f"{ex_id}{name}", part, part.key))
            elif isinstance(part, TuplePart):
                out += [(f"{ex_id}{name} {label}", p, key)
                        for (label, p), key in zip(part.components, part.key.components)]
    return out


def _verdict(part, key, outcomes):
    """``part.verdict(outcomes)``; a TuplePart's component, which has no key of its own, is judged
    with ``key`` as its tuple judges it."""
    if part.exercise is not None:
        return part.verdict(outcomes)
    try:
        return Verdict(PASSED, part.judge_with(key, outcomes), part.title)
    except Wrong as w:
        return Verdict(FAILED, str(w), part.title)


FUNCTION_PARTS = _function_parts()


def test_the_course_has_function_parts_with_arrays():
    assert len(FUNCTION_PARTS) >= 15
    assert any(len(p.shape) == 2 for _, p, _ in FUNCTION_PARTS) and any(len(p.shape) == 1 for _, p, _ in FUNCTION_PARTS)


@pytest.mark.parametrize("label, part, key", FUNCTION_PARTS, ids=[lbl for lbl, _, _ in FUNCTION_PARTS])
def test_a_wrong_last_entry_is_named_in_words(label, part, key):
    """The reference's values with its last entry off by 1, as the sandbox would hand them to the
    judge: the verdict fails and names that entry counted from 1 ("the third entry", "the entry in
    the third row and second column"), never by a 0-based index."""
    outcomes = []
    for args in part.inputs():
        v = np.array(key.ref(*args), dtype=float)
        v.flat[-1] += 1.0
        outcomes.append({"k": "ok", "v": v})
    verdict = _verdict(part, key, outcomes)
    assert verdict.status == FAILED
    if int(np.prod(part.shape)) > 1 and "different value" in verdict.message:
        last = tuple(s - 1 for s in part.shape)
        assert entry_name(last, part.shape) + " differs" in verdict.message, verdict.message
    assert not ZERO_BASED.search(verdict.message), verdict.message


def test_a_list_answer_to_1_2a_names_its_second_entry():
    """The issue's case: a list whose second entry is wrong said "(entries 1 differ)"."""
    v = checks.ex1_2.a.check(lambda h, g: [h[0] * g[0], h[1] * g[1] + 1], quiet=True)
    assert v.status == FAILED
    assert "the second entry differs" in v.message and not ZERO_BASED.search(v.message), v.message
    assert "h=[1, 1], g=[2, 3]" in v.message, v.message        # values as written, not [1., 1.]


def test_a_matrix_entry_is_named_by_row_and_column():
    p = checks.ex2_2.a

    def off(*args):
        out = np.array(p.ref(*args), dtype=float)
        out[1, 1] += 0.5
        return out
    v = p.check(off, quiet=True)
    assert v.status == FAILED
    assert "the entry in the second row and second column differs" in v.message, v.message


def test_an_angle_off_by_a_full_turn_is_not_called_different():
    """Entries compared modulo 2 pi (``angles``) are named only when they really differ."""
    p = checks.ex1_4.a
    assert p.angles, "1.4a compares its angle modulo 2 pi"
    outcomes = []
    for args in p.inputs():
        v = np.array(p.ref(*args), dtype=float)
        v[0] += 1.0                      # x wrong
        v[p.angles[0]] += 2 * np.pi      # theta right, a turn further
        outcomes.append({"k": "ok", "v": v})
    message = p.verdict(outcomes).message
    assert "the first entry differs" in message, message
    assert "third" not in message


def test_numbers_in_messages_are_written_as_a_person_writes_them():
    from gm_core.checks.answers import fmt_value
    assert fmt_value(np.array([1.0, -0.0, 1e-17, 2.123456])) == "[1, 0, 0, 2.123]"
    assert fmt_value(-0.0) == "0" and fmt_value(np.float64(0.25)) == "0.25"
    assert fmt_value(np.array([np.nan, np.inf])) == "[nan, inf]"


@pytest.mark.parametrize("answer, letter", [(0, "a"), (1, "b")])
def test_a_number_for_a_choice_says_which_option_it_is(answer, letter):
    p = checks.ex1_1.a
    v = p.check(answer, quiet=True)
    assert v.status == (PASSED if letter in p.key.correct else FAILED)       # the verdict is unchanged
    assert f"You answered {answer}: numbers count the options from 0, so {answer} is option ({letter})" \
        in v.message, v.message
    assert "You answered" not in p.check(letter, quiet=True).message


def test_every_choice_feedback_is_friendly_for_every_number():
    for ex_id in exercise_ids():
        for part in REGISTRY[ex_id].parts.values():
            if isinstance(part, ChoicePart):
                for n in range(len(part.options) + 1):
                    v = part.verdict([{"k": "ok", "v": n}])
                    assert isinstance(v, Verdict) and v.message, (ex_id, part.name, n)
                    assert "Traceback" not in v.message


def test_the_solution_box_links_the_worked_solution():
    """solution() names the worked notebook by a path relative to the exercise; in Jupyter that
    path is a link (the plain-text box keeps the path as it is)."""
    from gm_core.checks.display import box_html
    text = checks.ex1_4.a.solution_text_full()
    assert "../solutions/ex1_4.ipynb" in text
    html = box_html("solution", "exercise 1.4a", text)
    assert '<a href="../solutions/ex1_4.ipynb">../solutions/ex1_4.ipynb</a>' in html
    assert "<a " not in box_html("hint", "x", "a < b and ex1_4.ipynb without a folder")

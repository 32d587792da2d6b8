"""ValuePart, the declarative form of a one-value part (gm_core.checks.parts): a part declared by
class attributes gets its probe and its judge from the base class, and its key (a ValueKey) its
default reference and wrong answers from the expected value and the mistakes."""
import numpy as np
import pytest
from checkhelpers import assert_check_failed, assert_check_passed, assert_check_unattempted

from gm_core.checks.answer_key import Mistake, ValueKey, provide
from gm_core.checks.exercise import REGISTRY, Exercise
from gm_core.checks.parts import ValuePart

pytestmark = pytest.mark.usefixtures("clean")


class DiscArea(ValuePart):
    name = "a"
    prompt = "The area of the unit disc (a number)"
    hints = ["The area of a disc of radius r is pi r^2."]


QUARTER_TURN = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0]])


class Rotation(ValuePart):
    name = "b"
    prompt = "The rotation matrix by pi/2 (a 2 x 3 array: the matrix and a zero column)"
    shape = (2, 3)
    success = "Correct: a quarter turn."


@pytest.fixture
def parts():
    ex = Exercise("9.7", "values", [DiscArea(), Rotation(weight=1.0)])
    provide(ex,
            a=ValueKey(expected=np.pi, solution_text="pi r^2 = pi for r = 1.",
                       mistakes=[Mistake(2 * np.pi, "that is the circumference 2 pi r, not the area."),
                                 Mistake(1.0, "that is r^2 without pi.", 0.05)]),
            b=ValueKey(expected=QUARTER_TURN, mistakes=[Mistake(-QUARTER_TURN, "that turns by -pi/2.")]))
    try:
        yield ex.a, ex.b
    finally:
        REGISTRY.pop("9.7", None)


def test_a_declared_value_part_judges_like_a_checker(parts):
    disc, rot = parts
    assert disc.kind == "number" and disc.reference == np.pi and disc.wrong == [2 * np.pi, 1.0]
    assert disc.weight == 2.0 and rot.weight == 1.0 and disc.hints == DiscArea.hints
    assert_check_passed(disc, np.pi * (1 + 1e-8))
    assert_check_passed(disc, np.array([[np.pi]]))
    assert_check_failed(disc, 2 * np.pi, mentions="circumference")
    assert_check_failed(disc, 1.04, mentions="without pi")
    assert_check_failed(disc, 3.0, mentions=["your answer 3 is not the expected value", ".hint()"])
    assert_check_failed(disc, True, mentions="your answer is a bool; one number was expected")
    assert_check_failed(disc, [1.0, 2.0], mentions="your answer has 2 numbers (shape (2,)); one number")
    assert_check_failed(disc, "pi", mentions="a number or an array of numbers was expected")
    assert_check_failed(disc, float("nan"), mentions="not finite")
    assert_check_failed(disc, lambda: np.pi)
    assert_check_unattempted(disc, None)
    assert_check_unattempted(disc, ...)


def test_an_array_value_part_compares_entry_by_entry(parts):
    _, rot = parts
    good = QUARTER_TURN
    v = assert_check_passed(rot, good.tolist())
    assert v.message == "Correct: a quarter turn."
    assert_check_failed(rot, -good, mentions="-pi/2")
    assert_check_failed(rot, good.T, mentions="transposed")
    assert_check_failed(rot, np.zeros(5), mentions="an array of shape (2, 3) was expected")
    bad = good.copy()
    bad[1, 2] = 0.1
    assert_check_failed(rot, bad, mentions="not the expected value")


def test_the_judge_reads_only_plain_outcomes(parts):
    disc, rot = parts
    assert disc.judge([{"k": "ok", "v": np.pi}]) == "Correct."
    for junk in ([{"k": "ok", "v": 3}], [{"k": "ok", "v": "3.14"}], [{"k": "ok", "v": None}]):
        assert disc.verdict(junk).message == "one number was expected."
    assert rot.verdict([{"k": "ok", "v": np.zeros(6)}]).message == "an array of shape (2, 3) was expected."
    assert "took longer than 5 s" in disc.verdict([{"k": "timeout", "m": "5"}]).message


def test_a_declaration_names_its_part_and_nothing_unknown():
    class Nameless(ValuePart):
        rtol = 0.1

    with pytest.raises(TypeError, match="must declare a name and a prompt"):
        Nameless()
    with pytest.raises(TypeError, match=r"unexpected arguments \['tolerance'\]"):
        DiscArea(tolerance=0.1)
    assert DiscArea(name="c", prompt="again").name == "c"

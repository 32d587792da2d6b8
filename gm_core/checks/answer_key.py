"""Answer keys: what a right answer to each exercise part is, kept apart from the part itself.

A part (:mod:`gm_core.checks.parts`) holds what a student may see and what touches the answer:
its prompt, hints, starter, the inputs it tries and the probes that read the answer as plain data.
Its *answer key* holds what a right answer is: the reference function or value, the known
mistakes and the messages they deserve, the correct option of a multiple-choice question, a custom
judge, the key result that ``solution()`` shows, and the wrong answers the tests try.

The keys live in the package :mod:`gm_core.checks.keys`, one module per chapter, each calling
:func:`provide` for its exercises. A self-study install has that package and checks answers as
always. The **graded build** of the course (what the grader's sandbox and a graded student's
kernel see, :mod:`gm_grader.view`) has the same course without it: there a check runs its probes
(their plain outcomes go to the grader, which judges them with its own keys) but cannot judge,
and asking a part for its key (``.reference``, ``.solution()``, ...) raises
:class:`AnswerKeyHidden` and is reported to the grader, which gives that part no marks.

Every kind of part has its kind of key (``Part.key_type``): :class:`FunctionKey` (a reference
function and mistakes), :class:`TupleKey` (one FunctionKey per component), :class:`ValueKey` (an
expected value), :class:`ChoiceKey` (the correct options and feedback) and :class:`JudgeKey` (a
judge of its own).
"""
from __future__ import annotations

import importlib
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy.typing as npt

from gm_core.checks import channel

if TYPE_CHECKING:
    from gm_core.checks.exercise import Exercise
    from gm_core.checks.parts import Part
    from gm_core.checks.sandbox import ProbeOutcome

#: The package holding the keys; the graded build has no such package.
KEYS_PACKAGE = "gm_core.checks.keys"


class AnswerKeyHidden(LookupError):
    """This build of the course has no answer keys (a graded run): the part cannot say what a right
    answer is, and the grader has been told that the notebook asked."""


class Mistake(NamedTuple):
    """A plausible wrong value for a :class:`~gm_core.checks.parts.ValuePart` and the message it
    deserves.

    ``tol``: how close (absolutely) an answer must come to ``value`` to be taken for this mistake;
    None: the part's own tolerance (``atol + rtol * |value|``)."""

    value: npt.ArrayLike
    message: str
    tol: float | None = None


#: A wrong function a part knows, with the message it deserves (:class:`FunctionKey`'s ``mistakes``).
FunctionMistake = tuple[Callable[..., npt.ArrayLike], str]


@dataclass(frozen=True, kw_only=True)
class AnswerKey:
    """What every key has: a correct answer as a student would give it (``reference``, or
    ``reference_factory()`` when it is costly to build, e.g. a sympy expression), plausible wrong
    answers (``wrong``, which the tests try) and the key result ``solution()`` shows."""

    reference: Any = None
    reference_factory: Callable[[], Any] | None = None
    wrong: Sequence[Any] = ()
    solution_text: str = ""

    def correct_answer(self) -> Any:
        """A correct answer, as a student would give it (built now if the key has a factory)."""
        return self.reference_factory() if self.reference_factory is not None else self.reference


@dataclass(frozen=True, kw_only=True)
class FunctionKey(AnswerKey):
    """The key of a :class:`~gm_core.checks.parts.FunctionPart`: ``ref(*args)`` is the expected
    value; ``mistakes`` are ``(wrong_function, message)`` pairs, a message given only when the
    answer equals that wrong function on every input checked. ``reference`` defaults to ``ref``;
    ``wrong`` is every mistake's function followed by the further wrong answers given."""

    ref: Callable[..., npt.ArrayLike]
    mistakes: Sequence[FunctionMistake] = ()

    def __post_init__(self) -> None:
        if self.reference is None:
            object.__setattr__(self, "reference", self.ref)
        known = [fn for fn, _ in self.mistakes]
        object.__setattr__(self, "wrong", known + [w for w in self.wrong if all(w is not k for k in known)])


@dataclass(frozen=True, kw_only=True)
class TupleKey(AnswerKey):
    """The key of a :class:`~gm_core.checks.parts.TuplePart`: one :class:`FunctionKey` per
    component, in order. ``reference`` defaults to the tuple of the components' references."""

    components: Sequence[FunctionKey]

    def __post_init__(self) -> None:
        if self.reference is None:
            object.__setattr__(self, "reference", tuple(c.reference for c in self.components))


@dataclass(frozen=True, kw_only=True)
class ValueKey(AnswerKey):
    """The key of a :class:`~gm_core.checks.parts.ValuePart`: the ``expected`` value (or a
    function computing it when first needed) and the ``mistakes`` tried, in order, on a value that
    is not close to it (or a function of the expected value giving them). ``success``: the message
    of a right answer from (value, expected); None: the part's own. ``reference`` defaults to
    ``expected`` (when it is a value) and ``wrong`` to the mistakes' values."""

    expected: npt.ArrayLike | Callable[[], npt.ArrayLike]
    mistakes: Sequence[Mistake] | Callable[[npt.ArrayLike], Sequence[Mistake]] = ()
    success: Callable[[Any, npt.ArrayLike], str] | None = None

    def __post_init__(self) -> None:
        if self.reference is None and not callable(self.expected):
            object.__setattr__(self, "reference", self.expected)
        if not self.wrong and not callable(self.mistakes):
            object.__setattr__(self, "wrong", [m[0] for m in self.mistakes])

    def expected_value(self) -> npt.ArrayLike:
        """The value a right answer is close to."""
        return self.expected() if callable(self.expected) else self.expected

    def known_mistakes(self, expected: npt.ArrayLike) -> list[Mistake]:
        """The mistakes tried, in order, on a value that is not close to ``expected``."""
        found = self.mistakes(expected) if callable(self.mistakes) else self.mistakes
        return [Mistake(*m) for m in found]


@dataclass(frozen=True, kw_only=True)
class ChoiceKey(AnswerKey):
    """The key of a :class:`~gm_core.checks.choice.ChoicePart`: the correct option letter(s) and
    the feedback each option gets. ``reference`` defaults to the first correct letter."""

    correct: frozenset[str]
    feedback: Mapping[str, str] = field(default_factory=dict)

    def __init__(self, *, correct: str | Iterable[str], feedback: Mapping[str, str] | None = None,
                 reference: Any = None, reference_factory: Callable[[], Any] | None = None,
                 wrong: Sequence[Any] = (), solution_text: str = "") -> None:
        letters = frozenset({correct} if isinstance(correct, str) else correct)
        object.__setattr__(self, "correct", letters)
        object.__setattr__(self, "feedback", dict(feedback or {}))
        object.__setattr__(self, "reference", sorted(letters)[0] if reference is None else reference)
        object.__setattr__(self, "reference_factory", reference_factory)
        object.__setattr__(self, "wrong", list(wrong))
        object.__setattr__(self, "solution_text", solution_text)


@dataclass(frozen=True, kw_only=True)
class JudgeKey(AnswerKey):
    """The key of a :class:`~gm_core.checks.parts.CustomPart`: ``judge(outcomes)`` returns the
    success message or raises Wrong / Unattempted, from the probes' plain outcomes."""

    judge: Callable[[list[ProbeOutcome]], str]


#: Every key provided, by part ("1.4/a").
_KEYS: dict[str, AnswerKey] = {}


def part_key_id(part: Part) -> str:
    ex = part.exercise.id if part.exercise is not None else "?"
    return f"{ex}/{part.name}"


def provide(exercise: Exercise, **keys: AnswerKey) -> None:
    """Register the keys of ``exercise``'s parts, by part name (called by the key modules)."""
    for name, key in keys.items():
        if name not in exercise.parts:
            raise ValueError(f"exercise {exercise.id} has no part {name!r} (parts: {', '.join(exercise.parts)})")
        part = exercise.parts[name]
        if not isinstance(key, part.key_type):
            raise TypeError(f"the key of exercise {exercise.id} part {name} must be a "
                            f"{part.key_type.__name__}, not {type(key).__name__}")
        part.check_key(key)
        _KEYS[part_key_id(part)] = key


def keys_installed() -> bool:
    """Whether this build of the course has the answer keys (False in the graded build, where
    the package is missing, or its folder is empty or unreadable: then Python finds at most a
    namespace package without a file)."""
    try:
        module = importlib.import_module(KEYS_PACKAGE)
    except ModuleNotFoundError as exc:
        if exc.name is not None and KEYS_PACKAGE.startswith(exc.name):
            return False
        raise
    except PermissionError:
        return False
    return getattr(module, "__file__", None) is not None


def key_of(part: Part, asked: str = "key") -> AnswerKey:
    """The answer key of ``part``; :class:`AnswerKeyHidden` in the graded build (and the grader is
    told that the notebook asked, ``asked`` saying for what)."""
    found = _KEYS.get(part_key_id(part))
    if found is not None:
        return found
    if not keys_installed():
        channel.key_requested(part, asked)
        raise AnswerKeyHidden(
            f"{part.title}: this copy of the course is the graded build, which has no answer keys "
            f"(asked for: {asked}). Your answers are judged by the grader after the run.")
    found = _KEYS.get(part_key_id(part))
    if found is None:
        raise LookupError(f"no answer key was provided for {part.title} (add it to {KEYS_PACKAGE})")
    return found


__all__ = ["AnswerKey", "FunctionKey", "TupleKey", "ValueKey", "ChoiceKey", "JudgeKey", "Mistake",
           "FunctionMistake", "AnswerKeyHidden", "provide", "key_of", "keys_installed", "KEYS_PACKAGE"]

"""Multiple-choice parts: a letter, the option's text, or a phrase that names one option."""
from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any

import numpy as np
from typing_extensions import override

from gm_core.checks.answer_key import AnswerKey, ChoiceKey
from gm_core.checks.answers import describe, is_starter
from gm_core.checks.parts import Part, first_value
from gm_core.checks.sandbox import Probe, ProbeOutcome, Unattempted, Wrong

if TYPE_CHECKING:
    import ipywidgets


def _words(text: object) -> str:
    return re.sub(r"[^a-z0-9^+]+", " ", str(text).lower()).strip()


class ChoicePart(Part):
    """A multiple-choice question. The answer is an option letter (or the option's text).

    A free-text answer that names exactly one option ("torus", "T^2") counts as that option; one
    that names none is not recorded as failed (the verdict asks for a letter).
    """

    kind: str = "choice"
    weight: float = 1.0
    key_type = ChoiceKey

    def __init__(self, name: str, prompt: str, options: dict[str, str], **kw: Any) -> None:
        super().__init__(name, prompt, **kw)
        self.options = dict(options)  # letter -> text; the correct ones are in the key

    @override
    def check_key(self, key: AnswerKey) -> None:
        if isinstance(key, ChoiceKey):
            unknown = sorted(set(key.correct) - set(self.options))
            if unknown or not key.correct:
                raise ValueError(f"the key of {self.title} must name options it has (correct: "
                                 f"{sorted(key.correct)}, options: {', '.join(self.options)})")

    @property
    @override
    def wrong(self) -> list[Any]:
        """The key's wrong answers, by default every option that is not correct."""
        key = self.key_as(ChoiceKey, "wrong")
        return list(key.wrong) or [k for k in self.options if k not in key.correct]

    @staticmethod
    def _read(answer: Any) -> int | str:
        """Student side: the answer as plain data (a stripped string or an int)."""
        if is_starter(answer):
            raise Unattempted()
        if isinstance(answer, (bool, np.bool_)):
            raise Wrong(f"your answer is {describe(answer)}; give one of the option letters.")
        if isinstance(answer, (int, np.integer)):
            return int(answer)
        if isinstance(answer, str):
            return str(answer)[:500]
        raise Wrong(f"your answer is {describe(answer)}; give one of the option letters.")

    @override
    def probes(self) -> list[Probe]:
        return [self._read]

    def letter(self, value: int | str) -> str | None:
        """The option letter a plain answer names, None if it names none (or several)."""
        letters = list(self.options)
        if isinstance(value, int):
            return letters[value] if 0 <= value < len(letters) else None
        a = value.strip().strip("().").strip().lower()
        for k, text in self.options.items():
            if a == k.lower() or _words(a) == _words(text):
                return k
        w = _words(a)
        if len(w) >= 3 or any(c.isdigit() or c == "^" for c in w):
            hits = [k for k, text in self.options.items() if f" {w} " in f" {_words(text)} "]
            if len(hits) == 1:
                return hits[0]
        return None

    @override
    def judge(self, outcomes: list[ProbeOutcome]) -> str:
        value = first_value(outcomes, "your answer", "no arguments")
        if isinstance(value, str) and value.strip().strip("().").strip() == "":
            raise Unattempted()
        if not isinstance(value, (str, int)):
            raise Wrong("give one of the option letters.")
        k = self.letter(value)
        if k is None:
            choices = ", ".join(repr(x) for x in self.options)
            if isinstance(value, int):
                raise Wrong(f"there is no option number {value}; give one of the letters {choices}.")
            raise Unattempted(f"'{value[:40]}' does not name one of the options; give one of the "
                              f"letters {choices} (this is not counted as a wrong answer).")
        # a number is read as Python counts, from 0: say which option that is, so a student who
        # counted from 1 sees why the verdict is about another option than they meant
        note = (f"(You answered {value}: numbers count the options from 0, so {value} is option "
                f"({k}); giving the letter is clearer.) " if isinstance(value, int) else "")
        key = self.key_as(ChoiceKey)
        if k in key.correct:
            return note + key.feedback.get(k, "Correct.")
        raise Wrong(note + key.feedback.get(k, "Not this one: reread the section the prompt cites."))

    def markdown_table(self) -> str:
        """The options as the markdown table the exercise notebook shows."""
        rows = [f"| {k} | {text} |" for k, text in self.options.items()]
        return "| letter | statement |\n|---|---|\n" + "\n".join(rows)

    def widget(self) -> ipywidgets.VBox:
        """Radio buttons, a Check button and feedback (ipywidgets)."""
        from gm_core.checks.views import choice_widget
        return choice_widget(self)

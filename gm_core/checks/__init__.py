"""Exercise checkers for the 13 exercises of chapters 1-3, in the spirit of Kaggle's learntools.

Usage in an exercise notebook::

    from gm_core.checks import ex1_4, progress
    ex1_4.a.check(exp_left)     # -> Verdict: passed / failed / unattempted, with a message
    ex1_4.a.hint()              # graded hints: hint(2), hint(3) say more
    ex1_4.a.solution()          # the key result and the worked-solution notebook to open
    progress()                  # {"1.1": "passed" | "failed" | "unattempted", ..., "3.4": ...}

Every exercise is an object ``exN_M`` whose parts are attributes (``ex2_3.a``, ``ex2_3.b``, ...).
A check never raises into the notebook. Conceptual parts (``ChoicePart``) also have ``.widget()``;
exercise 1.5 has ``ex1_5.slide_rule()``. ``progress_widget()`` shows the record as a table.

numpy only at import time: sympy is used only for sympy answers and ipywidgets only for widgets.
"""
from __future__ import annotations

from ._core import (EXERCISE_IDS, FAILED, PASSED, REGISTRY, UNATTEMPTED, ChoicePart, CustomPart,
                    Exercise, FunctionPart, Part, TuplePart, Verdict, part_progress, progress,
                    reset_progress)
from .ch1 import ex1_1, ex1_2, ex1_3, ex1_4, ex1_5
from .ch2 import ex2_1, ex2_2, ex2_3, ex2_4
from .ch3 import ex3_1, ex3_2, ex3_3, ex3_4

__all__ = [
    "progress", "progress_widget", "part_progress", "reset_progress", "exercise", "Verdict",
    "EXERCISE_IDS", "PASSED", "FAILED", "UNATTEMPTED",
    "ex1_1", "ex1_2", "ex1_3", "ex1_4", "ex1_5", "ex2_1", "ex2_2", "ex2_3", "ex2_4",
    "ex3_1", "ex3_2", "ex3_3", "ex3_4",
]


def exercise(ex_id):
    """The exercise object for an id such as "1.4"."""
    return REGISTRY[str(ex_id)]


def progress_widget():
    """A small ipywidgets table of progress() for this kernel (with a Refresh button)."""
    from ._widgets import progress_widget as _pw
    return _pw()

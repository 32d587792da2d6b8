"""Exercise checkers for the course's exercises, in the spirit of Kaggle's learntools.

Usage in an exercise notebook::

    from gm_core.checks import ex1_4, progress, progress_widget
    ex1_4.a.check(exp_left)     # Correct / Not yet / Unattempted, with a message
    ex1_4.a.hint()              # graded hints: hint(2), hint(3) say more
    ex1_4.a.solution()          # the key result and the worked-solution notebook to open
    progress()                  # a table of every exercise: passed, in progress, failed, unattempted
                                # (a dict to a program: progress()["1.4"] == "passed")
    progress_widget()           # the same table with a Refresh button and pending course updates

Every exercise is an object ``exN_M`` whose parts are attributes (``ex2_3.a``, ``ex2_3.b``, ...).
A check never raises into the notebook and never hangs: your code runs in a separate process
under a time limit (``set_time_limit(seconds)``; see :mod:`gm_core.checks.sandbox`). ``check(answer, strict=True)``
returns None when right and raises AssertionError when wrong, for nbgrader / otter-grader test
cells. Inside a student workspace
progress is saved in ``workspace/.progress.json``; ``reset_progress()`` forgets it.

Adding a chapter: write a module in this folder creating its ``Exercise`` objects (they register
themselves) and add its name to ``EXERCISE_MODULES``; its exercises are then available as
``gm_core.checks.exN_M`` and listed by ``progress()``. What a right answer is goes into a module
of the same name in :mod:`gm_core.checks.keys` (imported there), which the graded build leaves
out (:mod:`gm_core.checks.answer_key`).

numpy only at import time: sympy is used only for sympy answers and ipywidgets only for widgets.
"""
from __future__ import annotations

import importlib
import re
from typing import TYPE_CHECKING, Any

from gm_core.checks.answer_key import (
    AnswerKey,
    AnswerKeyHidden,
    ChoiceKey,
    FunctionKey,
    JudgeKey,
    Mistake,
    TupleKey,
    ValueKey,
    keys_installed,
)
from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import (
    REGISTRY,
    Exercise,
    ProgressTable,
    exercise_ids,
    part_progress,
    progress,
    reset_progress,
    solutions_viewed,
)
from gm_core.checks.parts import CustomPart, FunctionPart, Part, TuplePart, ValuePart, Verdict
from gm_core.checks.sandbox import set_time_limit
from gm_core.checks.store import FAILED, IN_PROGRESS, PASSED, UNATTEMPTED, pending_updates

#: The modules that declare exercises (each ``Exercise(...)`` registers itself on import).
EXERCISE_MODULES = ("ex1", "ex2", "ex3", "ex4", "ex5")

if TYPE_CHECKING:
    import ipywidgets

for _name in EXERCISE_MODULES:
    importlib.import_module(f".{_name}", __name__)

__all__ = [
    "progress", "ProgressTable", "progress_widget", "part_progress", "reset_progress", "exercise", "exercise_ids",
    "Verdict", "EXERCISE_IDS", "PASSED", "FAILED", "UNATTEMPTED", "IN_PROGRESS", "set_time_limit",
    "course_updates", "pending_updates", "solutions_viewed",
    "Part", "FunctionPart", "TuplePart", "ChoicePart", "CustomPart", "ValuePart", "Mistake", "Exercise",
    "AnswerKey", "FunctionKey", "TupleKey", "ValueKey", "ChoiceKey", "JudgeKey", "AnswerKeyHidden",
    "keys_installed",
] + ["ex" + i.replace(".", "_") for i in exercise_ids()]


def __getattr__(name: str) -> Any:
    # Any: exN_M is an Exercise and EXERCISE_IDS a tuple of ids; one signature cannot say which
    # EXERCISE_IDS and every exN_M come from the registry, so a new chapter module needs no edit here
    if name == "EXERCISE_IDS":
        return exercise_ids()
    m = re.fullmatch(r"ex(\d+)_(\d+)", name)
    if m and f"{m.group(1)}.{m.group(2)}" in REGISTRY:
        return REGISTRY[f"{m.group(1)}.{m.group(2)}"]
    raise AttributeError(f"module 'gm_core.checks' has no attribute {name!r}")


def exercise(ex_id: str) -> Exercise:
    """The exercise object for an id such as "1.4"."""
    return REGISTRY[str(ex_id)]


def progress_widget() -> ipywidgets.VBox:
    """The table of progress() (all exercises, saved record) with a Refresh button, after any
    pending course updates."""
    from gm_core.checks.views import progress_widget as _pw
    return _pw()


def course_updates() -> None:
    """Show the course updates waiting in your workspace (once), e.g. on the start page.

    Each entry is an exercise you had edited when the course changed it: your file is kept, and
    the new version sits beside it. Returns None (the list is displayed); ``pending_updates()``
    returns it as data.
    """
    from gm_core.checks.display import in_notebook
    from gm_core.checks.views import updates_html
    pending = pending_updates(mark_seen=True)
    if not pending:
        text = "No course updates are waiting in your workspace."
        if in_notebook():
            from IPython.display import HTML, display
            display(HTML(f"<p style='color:#555'>{text}</p>"))
        else:
            print(text)
        return
    if in_notebook():
        from IPython.display import HTML, display
        display(HTML(updates_html(pending)))
    else:
        for n in pending:
            print(f"Course update: your {n['file']} is kept; the new version is {n['new_version']}")

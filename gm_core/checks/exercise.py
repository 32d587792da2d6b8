"""Exercises, the registry of all exercises, and the progress summaries built on it.

No imports from the parts (``parts``): a part is anything with ``name`` and ``exercise``.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from typing_extensions import override

from gm_core.checks import store
from gm_core.checks.display import progress_table_html, show
from gm_core.checks.store import FAILED, PASSED, Progress

if TYPE_CHECKING:   # the parts import this module, never the other way round
    from gm_core.checks.parts import Part, Verdict

#: Every registered exercise, by id ("1.4"), in registration order.
REGISTRY: dict[str, Exercise] = {}


class _MissingPart:
    """What an old notebook gets for a part the course renamed or removed: friendly messages."""

    def __init__(self, exercise: Exercise, name: str) -> None:
        self.exercise, self.name = exercise, name

    def _say(self, *args: object, **kwargs: object) -> None:
        ex = self.exercise
        new = ex.renamed.get(self.name)
        where = f"ex{ex.id.replace('.', '_')}"
        text = (f"Exercise {ex.id} has no part {self.name!r} any more: the course was updated. "
                + (f"It is now called {new!r} ({where}.{new}). " if new else "")
                + f"The parts now are {', '.join(ex.parts)}. Open the course's new version of this "
                "notebook (see the list of course updates on the start page); your answers here "
                "are kept.")
        show(FAILED, f"exercise {ex.id} {self.name}", text)

    check = hint = solution = widget = _say

    @override
    def __repr__(self) -> str:
        return f"<exercise {self.exercise.id} has no part {self.name!r} (course updated)>"


class Exercise:
    """An exercise of the book: its parts are attributes (``ex1_4.a``, ``ex1_4.d``, ...).

    Creating one registers it (the course's list of exercises is the registry, in creation
    order): a new chapter only needs a module ``gm_core/checks/chN.py`` that creates its
    ``Exercise`` objects. ``renamed`` maps old part names to new ones (or to None for a removed
    part) for old notebooks, which then keep working or get a friendly "course updated" note.
    """

    def __init__(self, id: str, title: str, parts: Sequence[Part],
                 renamed: dict[str, str | None] | None = None) -> None:
        self.id = str(id)
        self.title = title
        self.parts: dict[str, Part] = {}
        self.renamed = dict(renamed or {})
        for p in parts:
            p.exercise = self
            self.parts[p.name] = p
            setattr(self, p.name, p)
        REGISTRY[self.id] = self

    def __getattr__(self, name: str) -> Part | _MissingPart:
        # Only names the course once had get the "course was updated" answer (``renamed``: old
        # name -> new name, or None for a removed part); any other name is an AttributeError,
        # so hasattr works and a typo is not mistaken for a course update.
        renamed = self.__dict__.get("renamed", {})
        if name.startswith("_") or name not in renamed:
            parts = ", ".join(self.__dict__.get("parts", {}))
            raise AttributeError(f"exercise {self.__dict__.get('id', '?')} has no part or attribute "
                                 f"{name!r}; its parts are {parts}")
        new = renamed[name]
        if new in self.parts:
            return self.parts[new]
        return _MissingPart(self, name)

    @override
    def __repr__(self) -> str:
        return f"<exercise {self.id}: {self.title}; parts {', '.join(self.parts)}>"

    def status(self, data: Progress | None = None) -> str:
        """passed / in progress / failed / unattempted, from the latest check of each part."""
        return store.exercise_status(self.id, list(self.parts), data)

    def check(self, answers: dict[str, Any] | None = None, **kw: Any) -> dict[str, Verdict | None]:
        """Check several parts at once from a dict {part name: answer}; returns the verdicts."""
        if not isinstance(answers, dict):
            show(FAILED, f"exercise {self.id}", "Pass a dict {part name: answer}, or check one part "
                 f"at a time, e.g. ex{self.id.replace('.', '_')}.{next(iter(self.parts))}.check(...).")
            return {}
        return {name: self.parts[name].check(a, **kw) for name, a in answers.items() if name in self.parts}


def exercise_ids() -> tuple[str, ...]:
    """The ids of every registered exercise, in course order."""
    return tuple(sorted(REGISTRY, key=lambda s: tuple(int(x) if x.isdigit() else x for x in s.split("."))))


class ProgressTable(dict[str, str]):
    """What :func:`progress` returns: ``{exercise id: status}``, a plain dict to a program
    (``progress()["1.4"] == "passed"``), shown to the student as a small table, an HTML table in
    Jupyter (``_repr_html_``) and a plain-text one anywhere else, never as a raw dict.

    Besides the statuses it keeps, from the same reading of the record, how many parts of each
    exercise have passed (``parts``: {id: (passed, parts)}), whose solutions were shown
    (``viewed``: {id: [part names]}) and where the record is kept (``where``).
    """

    parts: dict[str, tuple[int, int]]
    viewed: dict[str, list[str]]
    where: str

    def __init__(self, status: Mapping[str, str] | None = None,
                 parts: Mapping[str, tuple[int, int]] | None = None,
                 viewed: Mapping[str, Sequence[str]] | None = None, where: str = "") -> None:
        super().__init__(status or {})
        self.parts = dict(parts or {})
        self.viewed = {k: list(v) for k, v in (viewed or {}).items()}
        self.where = where

    def rows(self) -> list[tuple[str, str, str, str]]:
        """(exercise, status, parts passed, note) for every exercise, as the table shows them."""
        out = []
        for ex_id, status in self.items():
            done, total = self.parts.get(ex_id, (0, 0))
            seen = self.viewed.get(ex_id, [])
            out.append((ex_id, status, f"{done} of {total}" if total else "",
                        f"solution viewed: {', '.join(seen)}" if seen else ""))
        return out

    def text(self) -> str:
        """The plain-text table (ASCII apart from what the record itself holds)."""
        head = ("exercise", "status", "parts passed", "")
        body = self.rows()
        widths = [max(len(r[i]) for r in [head, *body]) for i in range(3)]
        lines = ["Your progress" + (f" ({self.where})" if self.where else "") + ":"]
        for r in [head, *body]:
            lines.append("  " + "  ".join(c.ljust(w) for c, w in zip(r, widths)) +
                         (f"  {r[3]}" if r[3] else ""))
        return "\n".join(line.rstrip() for line in lines)

    @override
    def __repr__(self) -> str:
        return self.text()

    @override
    def __str__(self) -> str:
        return self.text()

    def _repr_pretty_(self, printer: Any, cycle: bool) -> None:
        # IPython's plain-text display (a terminal, or a front end without HTML)
        printer.text(self.text())

    def _repr_html_(self) -> str:
        return progress_table_html(self.rows(), self.where)


def record_place() -> str:
    """Where the progress record is kept, in a few words for the progress table."""
    why = store.not_saved()
    if why:
        return f"NOT SAVED, kept in this kernel only: the workspace cannot be written ({why})"
    return ("saved in your workspace" if store.find_workspace() is not None
            else "this kernel only, not in a workspace")


def progress() -> ProgressTable:
    """Every exercise's status, "passed" | "in progress" | "failed" | "unattempted", by id: a dict
    ``{exercise id: status}`` that shows itself as a small table (:class:`ProgressTable`), with
    how many parts of each have passed and which solutions were viewed.

    Inside a student workspace this is the saved record (all notebooks, across restarts);
    elsewhere it covers this kernel. When the workspace cannot be written, it also shows this
    kernel's unsaved verdicts, and says so.
    """
    data = store.load()
    why = store.not_saved()
    if why:
        print(f"(Not saved: the workspace cannot be written ({why}); these verdicts are kept in "
              "this kernel's memory only.)")
    status = {ex_id: REGISTRY[ex_id].status(data) for ex_id in exercise_ids()}
    parts = {ex_id: (sum(store.part_status(ex_id, name, data) == PASSED for name in ex.parts),
                     len(ex.parts))
             for ex_id, ex in ((i, REGISTRY[i]) for i in exercise_ids())}
    return ProgressTable(status, parts, _viewed(data), record_place())


def part_progress() -> dict[str, dict[str, str]]:
    """{exercise id: {part name: latest status}} (parts never checked are "unattempted")."""
    data = store.load()
    return {ex_id: {name: store.part_status(ex_id, name, data) for name in REGISTRY[ex_id].parts}
            for ex_id in exercise_ids()}


def solutions_viewed() -> dict[str, list[str]]:
    """{exercise id: [part names whose solution() was shown]}."""
    return _viewed(store.load())


def _viewed(data: Progress) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for key, rec in data.items():
        if rec.get("solution_viewed"):
            ex_id, part = key.split("/", 1)
            out.setdefault(ex_id, []).append(part)
    return out


def reset_progress() -> None:
    """Forget every recorded check (and the workspace's saved record, when in a workspace)."""
    store.reset()



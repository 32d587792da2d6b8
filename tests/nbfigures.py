"""Run a course notebook headlessly in this process and check every figure it makes.

:func:`run_notebook` executes the code cells of one notebook in a fresh IPython namespace with
the Agg backend (the ``%matplotlib widget`` / ``%matplotlib inline`` lines are dropped: the
figures are the same matplotlib figures, measured at their own size and dpi), watched by the same
:class:`nbrecord.Recorder` that watches the notebooks' kernels under ``make test``: each figure
after the cell that made it and in its final state, every frame of every animation shown through
``to_jshtml``. This is the one in-process notebook runner; under ``make test`` the figure standard
reads the record of the run's one execution of each notebook instead (tests/nbrun.py).

Used by tools/screenshots.py (``visit`` callback) and the figure standard's self-checks.
"""
from __future__ import annotations

import os
import sys
from dataclasses import dataclass, field
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import nbrecord  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
COURSE_DIRS = ("book", "exercises", "solutions")
shows_inline = nbrecord.shows_inline


def course_notebooks(root: Path = ROOT) -> list[Path]:
    """Every notebook of book/, exercises/ and solutions/ (found on disk: new chapters included)."""
    return [p for d in COURSE_DIRS for p in sorted((root / d).glob("*.ipynb"))]


@dataclass
class NotebookFigures:
    path: str
    breaches: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    figures: int = 0
    animations: int = 0
    #: what ``epilogue`` printed (run after the last cell, see run_notebook)
    epilogue: str = ""

    @classmethod
    def from_record(cls, record: dict) -> NotebookFigures:
        epi = record.get("epilogue") or {}
        return cls(record["path"], list(record["breaches"]), list(record["errors"]), record["figures"],
                   record["animations"], epi.get("stdout", ""))


def _shell():
    from IPython.core.interactiveshell import InteractiveShell
    from traitlets.config import Config

    # one plain (kernel-less) shell for every notebook, no history database written
    shell = InteractiveShell.instance(config=Config({"HistoryManager": {"enabled": False}}))
    shell.reset(new_session=False)
    return shell


def run_notebook(path: Path, visit=None, root: Path = ROOT, epilogue: str | None = None) -> NotebookFigures:
    """Execute ``path`` and check its figures; ``visit(where, fig_or_anim, kind)`` sees each one
    in its final state (kind "figure" or "animation"). ``epilogue`` is code run after the last
    cell in the notebook's namespace; what it prints is kept in ``.epilogue``."""
    from IPython.utils.capture import capture_output

    path = Path(path).resolve()
    rel = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.name
    plt.close("all")
    shell = _shell()
    cwd = os.getcwd()
    os.chdir(path.parent)
    workspace = os.environ.pop("GM_COURSE_WORKSPACE", None)  # checks keep progress in memory only
    recorder = nbrecord.Recorder(shell, path, rel, "in-process", match_cells=False, visit=visit)
    nbrecord.log_execution(rel, "in-process")
    try:
        for k, src, _ in recorder.cells:
            recorder.begin_cell(k)
            with capture_output(display=True):
                shell.run_cell(nbrecord.strip_magics(src), store_history=False, silent=False)
        with capture_output(display=True):
            record = recorder.finish(epilogue)
    finally:
        recorder.uninstall()
        os.chdir(cwd)
        if workspace is not None:
            os.environ["GM_COURSE_WORKSPACE"] = workspace
        plt.close("all")
        shell.reset(new_session=False)
        checks = sys.modules.get("gm_core.checks")
        if checks is not None and hasattr(checks, "reset_progress"):
            checks.reset_progress()  # the exercises' verdicts do not leak into later tests
    return NotebookFigures.from_record(record)

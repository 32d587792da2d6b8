"""Run a course notebook headlessly in this process and check every figure it makes (figstd).

:func:`run_notebook` executes the code cells of one notebook in a fresh IPython namespace with
the Agg backend (the ``%matplotlib widget`` / ``%matplotlib inline`` lines are dropped: the
figures are the same matplotlib figures, measured at their own size and dpi). After each cell,
the figures it created are checked; at the end every figure still open is checked again in its
final state (a later ``panel.set(...)`` may have moved a readout). Animations are caught where
they become HTML: while the notebook runs, ``matplotlib.animation.Animation.save`` (behind both
``to_jshtml`` and the course's ``jshtml``) first renders every frame through
:class:`figstd.FrameChecker` (a movie writer, public API), then saves as asked. Much faster than a kernel per notebook: gm_core is imported once.

Used by tests/test_figure_standard.py and tools/screenshots.py (``visit`` callback).
"""
from __future__ import annotations

import contextlib
import json
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import figstd  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import animation  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
COURSE_DIRS = ("book", "exercises", "solutions")
_MAGIC = re.compile(r"^\s*%matplotlib\b.*$", re.M)


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

    def add(self, messages):
        for m in messages:
            if m not in self.breaches:
                self.breaches.append(m)


def shows_inline(path: Path) -> bool:
    """True when the notebook uses ``%matplotlib inline`` (figures shown as tight-cropped PNGs)."""
    return any(re.search(r"^\s*%matplotlib\s+inline\b", src, re.M) for src in _sources(path))


def _sources(path: Path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    for cell in nb.get("cells", []):
        if cell.get("cell_type") == "code":
            src = cell.get("source", "")
            yield "".join(src) if isinstance(src, list) else src


def _code_cells(path: Path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    k = 0
    for cell in nb.get("cells", []):
        if cell.get("cell_type") != "code":
            continue
        k += 1
        src = cell.get("source", "")
        src = "".join(src) if isinstance(src, list) else src
        tags = cell.get("metadata", {}).get("tags", [])
        yield k, _MAGIC.sub("pass", src), "raises-exception" in tags


@contextlib.contextmanager
def _catch_animations(on_animation):
    """While active, every ``Animation.save`` (what ``to_jshtml`` and ``gm_core.drawing.primitives.jshtml``
    render their frames with) first hands the animation to ``on_animation``; the checker's own
    save (a ``figstd.FrameChecker`` writer) passes straight through."""
    original = animation.Animation.save

    def save(anim, filename, writer=None, *args, **kwargs):
        if not isinstance(writer, figstd.FrameChecker):
            on_animation(anim)
        return original(anim, filename, writer, *args, **kwargs)

    animation.Animation.save = save
    try:
        yield
    finally:
        animation.Animation.save = original


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
    cell in the notebook's namespace; what it prints is kept in ``.epilogue`` (the browser tests
    compare the kernel state after Run All in JupyterLab with this cell-by-cell run)."""
    from IPython.utils.capture import capture_output

    path = Path(path)
    rel = path.relative_to(root).as_posix() if path.is_relative_to(root) else path.name
    res = NotebookFigures(rel)
    tight = shows_inline(path)
    plt.close("all")
    shell = _shell()
    seen: dict[int, str] = {}  # figure number -> where it appeared
    state = {"cell": 0}

    def on_animation(anim):
        res.animations += 1
        where = f"{rel} In[{state['cell']}] animation"
        checker = figstd.FrameChecker(where)
        try:
            anim.save("frames-not-written", writer=checker)
        except Exception as e:  # noqa: BLE001 - report, never hide
            res.errors.append(f"{where}: rendering its frames failed: {type(e).__name__}: {e}")
            return
        if checker.frames == 0:
            res.breaches.append(f"{where}: the animation renders no frames")
        res.add(checker.breaches)
        if visit is not None:
            visit(where, anim, "animation")

    cwd = os.getcwd()
    os.chdir(path.parent)
    workspace = os.environ.pop("GM_COURSE_WORKSPACE", None)  # checks keep progress in memory only
    try:
        with _catch_animations(on_animation):
            for k, src, may_raise in _code_cells(path):
                state["cell"] = k
                with capture_output(display=True):
                    r = shell.run_cell(src, store_history=False, silent=False)
                err = r.error_before_exec or r.error_in_exec
                if err is not None and not may_raise:
                    res.errors.append(f"{rel} In[{k}] raised {type(err).__name__}: {err}")
                for num in plt.get_fignums():
                    if num not in seen:
                        seen[num] = f"{rel} In[{k}]"
                        res.figures += 1
                        res.add(figstd.check_figure(plt.figure(num), seen[num], tight=tight))
        if epilogue is not None:
            with capture_output() as cap:
                r = shell.run_cell(epilogue, store_history=False)
            err = r.error_before_exec or r.error_in_exec
            if err is not None:
                res.errors.append(f"{rel} epilogue raised {type(err).__name__}: {err}")
            res.epilogue = cap.stdout
        for num in plt.get_fignums():
            fig = plt.figure(num)
            where = seen.get(num, rel)
            res.add(figstd.check_figure(fig, where, tight=tight))  # its final state (duplicates dropped)
            if visit is not None:
                visit(where, fig, "figure")
    finally:
        os.chdir(cwd)
        if workspace is not None:
            os.environ["GM_COURSE_WORKSPACE"] = workspace
        plt.close("all")
        shell.reset(new_session=False)
        checks = sys.modules.get("gm_core.checks")
        if checks is not None and hasattr(checks, "reset_progress"):
            checks.reset_progress()  # the exercises' verdicts do not leak into later tests
    return res

"""What one execution of a course notebook showed: the figure standard after every cell, every
animation frame, the cells that raised, and the checkers' progress at the end.

A :class:`Recorder` watches an IPython shell while a notebook's code cells run in it (IPython's
``pre_run_cell`` / ``post_run_cell`` events, public API). It is installed in two places, with the
same checks:

* in the **kernel** of the one execution of every notebook of book/, exercises/ and solutions/
  during ``make test`` (tests/nbrun.py installs it before the first cell and finishes it after the
  last), shared by the notebook's own test item, the figure standard, the exercise tests, the
  quiet-output test and the browser tests' reference;
* in a **plain in-process shell** by :func:`nbfigures.run_notebook` (tools/screenshots.py and the
  browser tests' cell-by-cell reference run).

After each cell, every figure the cell created is checked (tests/figstd.py); at the end every figure
still open is checked again in its final state (a later ``panel.set(...)`` may have moved a readout).
Animations are caught where their frames are rendered: while the recorder is installed,
``matplotlib.animation.Animation.save`` (which ``to_jshtml`` and the course's own player both use)
first renders every frame through :class:`figstd.FrameChecker` (a movie writer, public API).

The recorder loads nothing a notebook does not: a notebook that never imports matplotlib (most
exercises) runs without it, as it does for the student. Figures are looked for only once the
notebook has imported pyplot, and ``Animation.save`` is wrapped as soon as
``matplotlib.animation`` is imported, by whom and in whichever cell (:class:`_AfterImport`, an
import-system finder: public importlib API), before any code can use it.

:meth:`Recorder.finish` returns the record as plain data (JSON-able), see :func:`empty_record`.
"""
from __future__ import annotations

import contextlib
import importlib.abc
import importlib.util
import io
import json
import os
import re
import sys
import time
from pathlib import Path

_MAGIC = re.compile(r"^\s*%matplotlib\b.*$", re.M)


def code_cells(path: Path) -> list[tuple[int, str, bool]]:
    """(k, source, may_raise) of every code cell, k counted from 1 as Run All numbers them."""
    nb = json.loads(Path(path).read_text(encoding="utf-8"))
    out = []
    for cell in nb.get("cells", []):
        if cell.get("cell_type") != "code":
            continue
        src = cell.get("source", "")
        src = "".join(src) if isinstance(src, list) else src
        out.append((len(out) + 1, src, "raises-exception" in cell.get("metadata", {}).get("tags", [])))
    return out


def shows_inline(path: Path) -> bool:
    """True when the notebook uses ``%matplotlib inline`` (figures shown as tight-cropped PNGs)."""
    return any(re.search(r"^\s*%matplotlib\s+inline\b", src, re.M) for _, src, _ in code_cells(path))


def strip_magics(src: str) -> str:
    """The cell as run in a plain shell: ``%matplotlib ...`` lines become ``pass``."""
    return _MAGIC.sub("pass", src)


def empty_record(rel: str, host: str) -> dict:
    return {
        "path": rel,            # relative to the repository root
        "host": host,           # "kernel" (tests/nbrun.py) or "in-process" (nbfigures.run_notebook)
        "complete": False,      # finish() ran: every cell was run and the final state checked
        "cells_run": [],        # k of every code cell that ran (Run All numbering)
        "errors": [],           # "<rel> In[k] raised Name: message" (cells not tagged raises-exception)
        "breaches": [],         # figure-standard messages, each once
        "figures": 0,
        "animations": 0,
        "progress": None,       # gm_core.checks.progress() at the end, when the notebook imported it
        "epilogue": None,       # {"code": ..., "stdout": ...} when an epilogue was run at the end
        "seconds": 0.0,         # from install to finish
        "cpu_seconds": 0.0,     # CPU time of the process running the cells, from install to finish
    }


class Recorder:
    """Checks the figures of one notebook's execution in ``shell`` (see the module docstring).

    ``match_cells=True`` (in a kernel) finds which code cell is running by its source, so code
    that is not one of the notebook's cells (the recorder's own install and finish) is ignored;
    otherwise the host calls :meth:`begin_cell` before each cell."""

    def __init__(self, shell, path: Path, rel: str, host: str, match_cells: bool, visit=None):
        self.shell = shell
        self.path = Path(path)
        self.cells = code_cells(self.path)
        self.tight = shows_inline(self.path)
        self.rel = rel
        self.visit = visit
        self.match_cells = match_cells
        self.record = empty_record(rel, host)
        self.current: int | None = None
        self._next = 0          # index into self.cells where the next match is searched
        self._seen: dict[int, str] = {}   # figure number -> where it appeared
        self._t0 = time.monotonic()
        self._cpu0 = _cpu()
        self._original_save = None
        self._waiting_for_animation: _AfterImport | None = None
        self._finished = False
        self._install()

    @staticmethod
    def _pyplot():
        """matplotlib.pyplot when the notebook has imported it (else no figure of it can be open)."""
        return sys.modules.get("matplotlib.pyplot")

    # -- hooks ----------------------------------------------------------------------------------
    def _install(self):
        animation = sys.modules.get("matplotlib.animation")
        if animation is not None:
            self._wrap_save(animation)
        else:   # wrapped the moment it is imported (and not loaded before the notebook needs it)
            self._waiting_for_animation = _AfterImport("matplotlib.animation", self._wrap_save)
            sys.meta_path.insert(0, self._waiting_for_animation)
        self.shell.events.register("pre_run_cell", self.pre_run_cell)
        self.shell.events.register("post_run_cell", self.post_run_cell)

    def _wrap_save(self, animation):
        import figstd

        original = animation.Animation.save
        recorder = self

        def save(anim, filename, writer=None, *args, **kwargs):
            # every way to show an animation renders its frames through save (to_jshtml with
            # matplotlib's HTML writer, the course's player with its own writer): check them first
            if not isinstance(writer, figstd.FrameChecker):
                recorder.on_animation(anim)
            return original(anim, filename, writer, *args, **kwargs)

        self._original_save = original
        animation.Animation.save = save

    def uninstall(self):
        if self._waiting_for_animation is not None:
            with contextlib.suppress(ValueError):
                sys.meta_path.remove(self._waiting_for_animation)
            self._waiting_for_animation = None
        if self._original_save is not None:
            sys.modules["matplotlib.animation"].Animation.save = self._original_save
            self._original_save = None
        for name, fn in (("pre_run_cell", self.pre_run_cell), ("post_run_cell", self.post_run_cell)):
            with contextlib.suppress(ValueError):
                self.shell.events.unregister(name, fn)

    def begin_cell(self, k: int):
        self.current = k

    def pre_run_cell(self, info):
        if not self.match_cells:
            return
        raw = getattr(info, "raw_cell", None)
        self.current = None
        for j in range(self._next, len(self.cells)):
            if self.cells[j][1] == raw:
                self.current, self._next = self.cells[j][0], j + 1
                return

    def post_run_cell(self, result):
        k = self.current
        if k is None or self._finished:
            return
        self.current = None if self.match_cells else k
        self.record["cells_run"].append(k)
        err = result.error_before_exec or result.error_in_exec
        if err is not None and not self.cells[k - 1][2]:
            self.record["errors"].append(f"{self.rel} In[{k}] raised {type(err).__name__}: {err}")
        plt = self._pyplot()
        if plt is None:     # the notebook has not imported pyplot: none of its figures exists
            return
        import figstd

        for num in plt.get_fignums():
            if num not in self._seen:
                self._seen[num] = f"{self.rel} In[{k}]"
                self.record["figures"] += 1
                self._add(figstd.check_figure(plt.figure(num), self._seen[num], tight=self.tight))

    def on_animation(self, anim):
        import figstd

        self.record["animations"] += 1
        where = f"{self.rel} In[{self.current}] animation"
        checker = figstd.FrameChecker(where)
        try:
            anim.save("frames-not-written", writer=checker)
        except Exception as e:  # noqa: BLE001 - report, never hide
            self.record["errors"].append(f"{where}: rendering its frames failed: {type(e).__name__}: {e}")
            return
        if checker.frames == 0:
            self.record["breaches"].append(f"{where}: the animation renders no frames")
        self._add(checker.breaches)
        if self.visit is not None:
            self.visit(where, anim, "animation")

    def _add(self, messages):
        for m in messages:
            if m not in self.record["breaches"]:
                self.record["breaches"].append(m)

    # -- the end --------------------------------------------------------------------------------
    def finish(self, epilogue: str | None = None) -> dict:
        """Check every open figure in its final state, read progress(), run ``epilogue`` (code run
        in the notebook's namespace; its stdout is kept); returns the record."""
        if self._finished:
            return self.record
        self._finished = True
        try:
            if epilogue is not None:
                buf = io.StringIO()
                try:
                    with contextlib.redirect_stdout(buf):
                        exec(compile(epilogue, f"<epilogue of {self.rel}>", "exec"), self.shell.user_ns)
                except Exception as e:  # noqa: BLE001
                    self.record["errors"].append(f"{self.rel} epilogue raised {type(e).__name__}: {e}")
                self.record["epilogue"] = {"code": epilogue, "stdout": buf.getvalue()}
            self._check_open_figures()
            checks = sys.modules.get("gm_core.checks")
            if checks is not None and hasattr(checks, "progress"):
                self.record["progress"] = dict(checks.progress())
            self.record["complete"] = True
        finally:
            self.record["seconds"] = round(time.monotonic() - self._t0, 2)
            self.record["cpu_seconds"] = round(_cpu() - self._cpu0, 2)
            self.uninstall()
        return self.record

    def _check_open_figures(self):
        """Every figure still open, in its final state (messages already recorded are dropped)."""
        plt = self._pyplot()
        if plt is None:
            return
        import figstd

        for num in plt.get_fignums():
            fig = plt.figure(num)
            where = self._seen.get(num, self.rel)
            self._add(figstd.check_figure(fig, where, tight=self.tight))
            if self.visit is not None:
                self.visit(where, fig, "figure")


class _AfterImport(importlib.abc.MetaPathFinder):
    """Calls ``then(module)`` right after the module ``name`` is first imported (before the
    importer gets it), then leaves the import system. A finder placed first in ``sys.meta_path``
    that finds the module's spec with the finders after it and wraps the spec's loader."""

    def __init__(self, name: str, then):
        self.name, self.then = name, then

    def find_spec(self, fullname, path=None, target=None):
        if fullname != self.name:
            return None
        with contextlib.suppress(ValueError):
            sys.meta_path.remove(self)            # once; and not asked again by the line below
        spec = importlib.util.find_spec(fullname)
        if spec is not None and spec.loader is not None:
            spec.loader = _ThenLoader(spec.loader, self.then)
        return spec


class _ThenLoader(importlib.abc.Loader):
    """A module's own loader, then ``then(module)``; anything else is the loader's."""

    def __init__(self, loader, then):
        self._loader, self._then = loader, then

    def create_module(self, spec):
        return self._loader.create_module(spec)

    def exec_module(self, module):
        self._loader.exec_module(module)
        self._then(module)

    def __getattr__(self, name):      # get_source, get_data, is_package, ... (tracebacks, inspect)
        return getattr(self._loader, name)


def _cpu() -> float:
    t = os.times()
    return t.user + t.system


def log_execution(rel: str, host: str):
    """Append one line to $GM_NBRUN_DIR/executions.jsonl: one execution of a notebook (counted by
    benchmarks/suite_time.py). Nothing happens outside a test run."""
    d = os.environ.get("GM_NBRUN_DIR")
    if not d:
        return
    line = json.dumps({"path": rel, "host": host, "pid": os.getpid(), "t": time.time()})
    with contextlib.suppress(OSError), open(Path(d) / "executions.jsonl", "a", encoding="utf-8") as f:
        f.write(line + "\n")


# -- in the kernel (tests/nbrun.py sends these two calls as code) --------------------------------

_KERNEL: dict = {}


def install_in_kernel(path: str, rel: str):
    """Start recording the notebook ``path`` in this kernel (called before its first cell)."""
    from IPython import get_ipython

    _KERNEL["recorder"] = Recorder(get_ipython(), Path(path), rel, "kernel", match_cells=True)
    log_execution(rel, "kernel")


def finish_in_kernel(out: str, epilogue: str | None = None):
    """Finish the record and write it (JSON) to ``out`` (called after the last cell)."""
    rec = _KERNEL.pop("recorder", None)
    record = rec.finish(epilogue) if rec is not None else None
    tmp = Path(out).with_suffix(".tmp")
    tmp.write_text(json.dumps(record), encoding="utf-8")
    os.replace(tmp, out)

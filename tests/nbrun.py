"""One execution of every course notebook per test run, shared by every test that needs it.

nbval is THE executor of book/, exercises/ and solutions/ under ``make test``: one kernel per
notebook, every code cell an item. This module (hooks called from the root conftest.py) makes that
single execution the source for every other test that looks at a notebook:

* before a notebook's first cell, it installs :class:`nbrecord.Recorder` in nbval's kernel (the
  figure standard after every cell and on every animation frame, the cells that raised); after its
  last cell it finishes the record (final state of every figure, ``progress()``) and adds what
  nbval read from the kernel: the outputs of every cell and nbval's verdict on it;
* the record is kept in memory and written to the run's folder ``build/nbrun/<run>/`` (git-ignored):
  ``<notebook>.json`` and the executed notebook ``<notebook>.ipynb``, plus ``executions.jsonl``
  (one line per execution of a notebook, whoever ran it) and ``durations.json`` (seconds per test
  group, read by benchmarks/suite_time.py and used to start the longest groups first);
* the consumers (tests marked by :func:`params`, e.g. tests/test_figure_standard.py,
  tests/test_exercises.py, tests/test_notebook_outputs.py) read it through the ``notebook_record``
  fixture. Collection puts each consumer right after the cells of its notebook, and under
  pytest-xdist :func:`make_scheduler` keeps a notebook's cells and its readers on one worker (one
  kernel per notebook), so the record is always there when they run;
* when a consumer runs without its notebook's cells in the session (``pytest
  tests/test_figure_standard.py``, ``-p no:nbval``, ``-k``), the fixture runs the missing notebooks
  through nbval once, in one pytest subprocess writing into the same run folder.

Under pytest-xdist the controller makes the run folder and hands it to its workers.
"""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TESTS = ROOT / "tests"
BUILD = ROOT / "build" / "nbrun"
COURSE_DIRS = ("book", "exercises", "solutions")
KEEP_RUNS = 3
MARK = "nbrecord"
ENV = "GM_NBRUN_DIR"
#: in config.stash: this process made the run folder (the controller, or a run without xdist)
OWNER = pytest.StashKey[bool]()
#: scheduling groups (group_of): "nb:<notebook>" holds a notebook's nbval cells and the tests that
#: read its record (its browser test among them); BROWSER holds the browser self-checks
NOTEBOOK_GROUP = "nb:"
BROWSER_GROUP = "browser"

#: rel -> merged record of this process (this worker's notebooks)
_RECORDS: dict[str, dict] = {}
#: nodeid of the notebook file -> state of its execution in this process
_STATE: dict[str, dict] = {}
_DURATIONS: dict[str, float] = {}


def rel_of(path) -> str:
    p = Path(path).resolve()
    return p.relative_to(ROOT).as_posix() if p.is_relative_to(ROOT) else p.as_posix()


def slug(rel: str) -> str:
    return rel.replace("/", "__")


def run_dir() -> Path | None:
    d = os.environ.get(ENV)
    return Path(d) if d else None


def params(paths, id_of=None):
    """``pytest.param`` per notebook, marked as a reader of that notebook's record."""
    out = []
    for p in paths:
        rel = rel_of(p)
        out.append(pytest.param(p, id=id_of(p) if id_of else rel, marks=getattr(pytest.mark, MARK)(rel)))
    return out


# -- configuration -------------------------------------------------------------------------------

def configure(config):
    config.addinivalue_line("markers", f"{MARK}(notebook): reads the record of that notebook's one "
                            "execution (tests/nbrun.py)")
    workerinput = getattr(config, "workerinput", None)
    if workerinput is not None and workerinput.get(ENV):
        os.environ[ENV] = workerinput[ENV]
    if not os.environ.get(ENV):   # the controller (or a plain run) makes the run's folder
        BUILD.mkdir(parents=True, exist_ok=True)
        runs = sorted(p for p in BUILD.iterdir() if p.is_dir() and p.name.startswith("run-"))
        for old in runs[:max(0, len(runs) - KEEP_RUNS + 1)]:
            if time.time() - old.stat().st_mtime > 3600:   # never the folder of a run still going
                shutil.rmtree(old, ignore_errors=True)
        d = BUILD / f"run-{time.strftime('%Y%m%d-%H%M%S')}-{os.getpid()}"
        d.mkdir()
        os.environ[ENV] = str(d)
        config.stash[OWNER] = True
    if hasattr(config.option, "loadscopereorder"):
        config.option.loadscopereorder = False   # our order: longest groups first (modify_items)


def configure_node(node):
    node.workerinput[ENV] = os.environ[ENV]


def make_scheduler(config, log):
    """pytest-xdist's scheduler for this suite: xdist's scope scheduling, with our groups as the
    scopes (a notebook's cells and its readers, its browser test included; the browser
    self-checks; else one test file), read from
    the table the workers write at collection (``groups.json``), in collection order."""
    if config.getvalue("dist") == "each":
        return None
    from xdist.scheduler import LoadScopeScheduling

    class NotebookGroups(LoadScopeScheduling):
        _groups: dict | None = None

        def _split_scope(self, nodeid: str) -> str:   # the documented way to define scopes
            if self._groups is None:
                try:
                    self._groups = json.loads((run_dir() / "groups.json").read_text(encoding="utf-8"))
                except (OSError, ValueError):
                    self._groups = {}
            return self._groups.get(nodeid) or nodeid.rsplit("::", 1)[0]

        def _assign_work_unit(self, node):
            nodes = self.nodes   # the first two run the notebooks; with three or more, the rest the unit tests
            group = next_group(list(self.workqueue), unit_worker=len(nodes) >= 3 and node in nodes[2:])
            self.workqueue.move_to_end(group, last=False)   # xdist hands out the queue's first
            super()._assign_work_unit(node)

    return NotebookGroups(config, log)


def next_group(queue: list[str], unit_worker: bool) -> str:
    """The group a worker takes next from ``queue`` (the waiting groups, in order): the first,
    except for a unit worker, which takes the first group with no notebook in it (no nbval
    kernel, JupyterLab or Chromium) while there is one. With four workers on two cores (`make
    test`) two run the notebooks and their browser tests, which wait for the page and the kernel
    between their steps; the two unit workers' tests fill those pauses (a third browser worker
    would only add waits of its own). Two, because the longest unit groups wait too (the
    grader's time limits, the site's and kits' subprocesses): with one unit worker the two
    cores stood idle for about 25 CPU-s of a run, with two for about 6."""
    if unit_worker:
        for g in queue:
            if not g.startswith(NOTEBOOK_GROUP) and g != BROWSER_GROUP:
                return g
    return queue[0]


# -- collection: groups and their order -------------------------------------------------------------

def _is_cell(item) -> bool:
    return type(item).__name__ == "IPyNbCell"


def group_of(item) -> str:
    if _is_cell(item):
        return NOTEBOOK_GROUP + rel_of(item.path)
    m = item.get_closest_marker(MARK)
    if m is not None:
        return NOTEBOOK_GROUP + m.args[0]
    if "selfcheck_records" in getattr(item, "fixturenames", ()):
        return NOTEBOOK_GROUP + "selfcheck"   # one subprocess for the generated notebooks
    rel = rel_of(item.path)
    if rel.startswith("tests/browser/"):
        return BROWSER_GROUP   # the self-checks (a notebook's browser test reads its record: above)
    return rel


#: seconds per group of a full run on this machine, committed: the order of a fresh clone's first run
DEFAULT_DURATIONS = TESTS / "suite_durations.json"


def _previous_durations() -> dict[str, float]:
    """Seconds per group: of earlier runs here (build/nbrun/durations.json), else the committed table."""
    for f in (BUILD / "durations.json", DEFAULT_DURATIONS):
        try:
            return json.loads(f.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
    return {}


def modify_items(config, items):
    """Order: each notebook's cells, then the tests reading its record; groups longest first (from
    the previous run's durations; without them: browser, notebooks, then the rest as collected)."""
    groups: dict[str, list] = {}
    for item in items:
        g = group_of(item)
        groups.setdefault(g, []).append(item)
        item.user_properties.append(("gm_group", g))
    for g, its in groups.items():
        if g.startswith(NOTEBOOK_GROUP):
            its.sort(key=lambda it: 0 if _is_cell(it) else 1)   # stable: cells in order, then readers
    before = _previous_durations()
    first = list(groups)

    def rank(g):
        # the browser self-checks first; then the notebooks (each with its browser test, which
        # reads the record nbval has just made on the same worker); then everything else,
        # longest first
        if g == BROWSER_GROUP:
            return (0, 0.0, first.index(g))
        if g.startswith(NOTEBOOK_GROUP):
            return (1, 0.0, first.index(g))
        return (2, -before.get(g, 1.0), first.index(g))

    order = sorted(groups, key=rank)
    items[:] = [it for g in order for it in groups[g]]
    if getattr(config, "workerinput", None) is not None:   # for the controller's scheduler
        d = run_dir()
        tmp = d / f"groups.json.{os.getpid()}"
        tmp.write_text(json.dumps({it.nodeid: g for g in order for it in groups[g]}), encoding="utf-8")
        os.replace(tmp, d / "groups.json")


# -- around every nbval cell ------------------------------------------------------------------------

def _send(kernel, code: str, timeout: float) -> list[str]:
    """Run ``code`` in nbval's kernel (not a notebook cell); returns the errors it raised."""
    msg_id = kernel.execute_cell_input(code, allow_stdin=False)
    kernel.await_reply(msg_id, timeout=timeout)
    errors = []
    while True:
        msg = kernel.get_message(stream="iopub", timeout=timeout)
        if msg["parent_header"].get("msg_id") != msg_id:
            continue
        if msg["msg_type"] == "error":
            errors.append(f"{msg['content']['ename']}: {msg['content']['evalue']}")
        if msg["msg_type"] == "status" and msg["content"]["execution_state"] == "idle":
            return errors


def _state(item) -> dict:
    key = item.parent.nodeid
    st = _STATE.get(key)
    if st is None:
        cells = [it for it in item.session.items if _is_cell(it) and it.parent is item.parent]
        st = _STATE[key] = {"rel": rel_of(item.path), "last": cells[-1] if cells else item, "outputs": {},
                            "installed": False, "install_errors": []}
    return st


def _timeout(item) -> float:
    return float(getattr(item.config.option, "nbval_cell_timeout", None) or 300)


def around_cell(item):
    """A generator used as a hookwrapper of pytest_runtest_call for every nbval cell."""
    if not _is_cell(item):
        yield
        return
    st = _state(item)
    kernel = item.parent.kernel
    if not st["installed"] and kernel is not None and kernel.is_alive():
        st["installed"] = True
        path = str(item.path)
        code = (f"__import__('sys').path.append({str(TESTS)!r}) if {str(TESTS)!r} not in __import__('sys').path "
                f"else None\n__import__('nbrecord').install_in_kernel({path!r}, {st['rel']!r})\n")
        st["install_errors"] = _send(kernel, code, _timeout(item))
    try:
        yield
    finally:
        k = item.cell_num + 1
        st["outputs"][k] = [dict(o) for o in (item.test_outputs or [])]
        if item is st["last"]:
            finish(item, st)


def finish(item, st):
    rel = st["rel"]
    d = run_dir()
    kernel_out = d / f"{slug(rel)}.kernel.json"
    kernel = item.parent.kernel
    record = None
    problem = ""
    if kernel is not None and kernel.is_alive():
        epilogue = panel_state_code()
        code = (f"__import__('nbrecord').finish_in_kernel({str(kernel_out)!r}, "
                f"{epilogue!r})\n")
        try:
            errs = _send(kernel, code, _timeout(item))
        except Exception as e:  # noqa: BLE001 - the record says what went wrong
            errs = [f"{type(e).__name__}: {e}"]
        try:
            record = json.loads(kernel_out.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            record = None
        if errs:
            problem = "finishing the record in the kernel failed: " + "; ".join(errs)
    else:
        problem = "nbval's kernel was not alive after the last cell (it died or timed out)"
    if record is None:
        import nbrecord

        record = nbrecord.empty_record(rel, "kernel")
        record["errors"].append(f"{rel}: no record of its execution: {problem or st['install_errors']}")
    if st["install_errors"]:
        record["errors"].append(f"{rel}: installing the recorder failed: {st['install_errors']}")
    record["outputs"] = {str(k): v for k, v in sorted(st["outputs"].items())}
    _RECORDS[rel] = record
    _write(record)


def _write(record):
    d = run_dir()
    rel = record["path"]
    tmp = d / f"{slug(rel)}.json.tmp"
    tmp.write_text(json.dumps(record), encoding="utf-8")
    os.replace(tmp, d / f"{slug(rel)}.json")
    try:   # the executed form of the notebook, for people (and any later tool) to read
        (d / f"{slug(rel)}.ipynb").write_text(json.dumps(executed_notebook(record), indent=1), encoding="utf-8")
    except (OSError, ValueError):
        pass


def executed_notebook(record: dict) -> dict:
    """The notebook of ``record`` as its execution left it: every code cell with the outputs nbval
    read from the kernel and its execution count (cells counted from 1, as Run All numbers them)."""
    nb = json.loads((ROOT / record["path"]).read_text(encoding="utf-8"))
    k = 0
    for cell in nb.get("cells", []):
        if cell.get("cell_type") == "code":
            k += 1
            cell["outputs"] = record["outputs"].get(str(k), [])
            cell["execution_count"] = k
    return nb


def panel_state_code() -> str | None:
    """The browser tests' panel-state epilogue, so their cell-by-cell reference comes from this run."""
    try:
        sys.path.insert(0, str(TESTS / "browser"))
        import labview
    except Exception:  # noqa: BLE001 - no browser tests, no epilogue
        return None
    finally:
        with __import__("contextlib").suppress(ValueError):
            sys.path.remove(str(TESTS / "browser"))
    return getattr(labview, "PANEL_STATE_CODE", None)


# -- reading records ----------------------------------------------------------------------------------

def recorded(path, epilogue: str | None = None) -> dict | None:
    """The complete record of ``path`` from this run (memory, else the run folder), or None; with
    ``epilogue``, only a record whose execution ran that same epilogue."""
    rel = rel_of(path)
    rec = _RECORDS.get(rel)
    d = run_dir()
    if rec is None and d is not None:
        try:
            rec = json.loads((d / f"{slug(rel)}.json").read_text(encoding="utf-8"))
        except (OSError, ValueError):
            rec = None
    if rec is None or not rec.get("complete"):
        return None
    if epilogue is not None and (rec.get("epilogue") or {}).get("code") != epilogue:
        return None
    return rec


def _started(rel: str) -> bool:
    """Whether nbval's execution of ``rel`` has begun in this run (on any worker)."""
    d = run_dir()
    try:
        lines = (d / "executions.jsonl").read_text(encoding="utf-8").splitlines()
    except (OSError, TypeError):
        return False
    return any(json.loads(line).get("path") == rel and json.loads(line).get("host") == "kernel" for line in lines)


def wait_for_record(path, epilogue: str | None = None, timeout: float = 240.0) -> dict | None:
    """:func:`recorded`, waiting while nbval's execution of ``path`` is under way on another worker
    (at most ``timeout`` s); None at once when it has not begun (the caller then executes it)."""
    rel = rel_of(path)
    d = run_dir()
    deadline = time.monotonic() + timeout
    while True:
        rec = recorded(path, epilogue=epilogue)
        if rec is not None:
            return rec
        if d is None or (d / f"{slug(rel)}.json").exists() or not _started(rel) or time.monotonic() > deadline:
            return None   # finished without a usable record, not begun, or too long
        time.sleep(0.5)


def any_record(path) -> dict | None:
    rec = recorded(path)
    if rec is not None:
        return rec
    rel = rel_of(path)
    if rel in _RECORDS:
        return _RECORDS[rel]
    d = run_dir()
    try:
        return json.loads((d / f"{slug(rel)}.json").read_text(encoding="utf-8"))
    except (OSError, ValueError, TypeError):
        return None


def run_missing(session, wanted: list[str]) -> str:
    """Execute (through nbval, in one pytest subprocess) the notebooks among ``wanted`` that no
    item of this session executes; returns the subprocess's output tail."""
    in_session = {rel_of(it.path) for it in session.items if _is_cell(it)}
    missing = sorted(r for r in set(wanted) if r not in in_session and recorded(ROOT / r) is None)
    return execute(missing) if missing else ""


def execute(paths) -> str:
    """Execute notebooks through nbval (and this module's recorder) in one pytest subprocess that
    writes into this run's folder; returns the tail of its output."""
    env = {**os.environ, ENV: str(run_dir())}
    cmd = [sys.executable, "-m", "pytest", *[str(p) for p in paths], "-q", "-p", "nbval", "-o", "testpaths="]
    if "xdist" in sys.modules:
        cmd += ["-p", "no:xdist"]
    p = subprocess.run(cmd, cwd=ROOT, env=env, capture_output=True, text=True)
    return (p.stdout + p.stderr)[-3000:]


def wanted_by(session) -> list[str]:
    out = []
    for it in session.items:
        m = it.get_closest_marker(MARK)
        if m is not None:
            out.append(m.args[0])
    return out


# -- durations by group (controller side) ----------------------------------------------------------

_BY_FILE: dict[str, dict] = {}
#: xdist worker -> {"seconds": summed test time, "last": when its last report came (s after start)}
_WORKERS: dict[str, dict] = {}
_T0 = time.time()


def category(nodeid: str) -> str:
    """The row of build/nbrun/run-*/by-file.json: "nbval book" etc. for notebooks, else the test file."""
    f = nodeid.split("::")[0]
    return "nbval " + f.split("/")[0] if f.endswith(".ipynb") else f


def logreport(report):
    g = dict(report.user_properties).get("gm_group") if report.user_properties else None
    dt = float(report.duration or 0.0)
    if g is not None:
        _DURATIONS[g] = _DURATIONS.get(g, 0.0) + dt
    node = getattr(report, "node", None)   # under pytest-xdist, the worker that ran it
    w = _WORKERS.setdefault(getattr(getattr(node, "gateway", None), "id", "main"), {"seconds": 0.0, "last": 0.0})
    w["seconds"] += dt
    w["last"] = time.time() - _T0
    row = _BY_FILE.setdefault(category(report.nodeid), {"tests": 0, "seconds": 0.0, "failed": 0})
    row["seconds"] += dt
    if report.when == "call" or (report.when == "setup" and report.outcome != "passed"):
        row["tests"] += 1
        row["failed"] += report.outcome == "failed"


def session_finish(config):
    if not config.stash.get(OWNER, False) or not _DURATIONS:
        return
    d = run_dir()
    rounded = {g: round(s, 2) for g, s in sorted(_DURATIONS.items(), key=lambda kv: -kv[1])}
    (d / "durations.json").write_text(json.dumps(rounded, indent=1), encoding="utf-8")
    rows = {k: {**v, "seconds": round(v["seconds"], 2)} for k, v in sorted(_BY_FILE.items())}
    (d / "by-file.json").write_text(json.dumps(rows, indent=1), encoding="utf-8")
    workers = {k: {"seconds": round(v["seconds"], 1), "last": round(v["last"], 1)} for k, v in sorted(_WORKERS.items())}
    (d / "workers.json").write_text(json.dumps(workers, indent=1), encoding="utf-8")
    merged = {**_previous_durations(), **rounded}
    (BUILD / "durations.json").write_text(json.dumps(merged, indent=1), encoding="utf-8")

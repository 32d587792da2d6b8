"""One execution of every course notebook per test run, shared by every test that reads it.

* Every notebook of book/, exercises/ and solutions/ is one test item, ``<notebook>::runs``
  (:class:`NotebookFile`, pytest's documented way to collect non-Python tests): it fails when a
  cell raised (cells tagged ``raises-exception`` may) or the notebook did not run to its end.
  ``pytest book/04-geodesics-and-exp.ipynb`` runs one.
* :func:`record` executes a notebook with nbclient (public API) in a fresh kernel of this
  environment, its working folder the notebook's, with :class:`nbrecord.Recorder` installed before
  the first cell and finished after the last: the figure standard after every cell and on every
  animation frame, the cells that raised, ``progress()`` and the browser tests' panel state at the
  end, and the outputs of every cell. The record is kept in memory and in the run's folder
  ``build/nbrun/<run>/`` (git-ignored): ``<notebook>.json``, the executed notebook
  ``<notebook>.ipynb``, ``executions.jsonl`` (one line per execution of a notebook) and, at the end,
  ``by-file.json`` and ``workers.json`` (read by benchmarks/suite_time.py).
* The notebook's item and every test reading its record (parametrized by :func:`params`, read
  through the ``notebook_record`` fixture) carry ``xdist_group("nb:<notebook>")``; under
  ``--dist loadgroup`` (``make test``) pytest-xdist runs a group on one worker, so whichever of
  them comes first executes the notebook and the rest read the record. Every other test runs in
  its file's group (:func:`default_groups`).

Under pytest-xdist the controller makes the run folder and hands it to its workers.
"""
from __future__ import annotations

import json
import os
import shutil
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
#: seconds one cell may run before the notebook's execution is stopped and its item fails
CELL_TIMEOUT = 300
#: seconds a new kernel may take to answer, and how often a kernel that never answered is started
#: again (no cell has run then, so starting again changes nothing the notebook does)
STARTUP_TIMEOUT = 300
STARTS = 2
#: in config.stash: this process made the run folder (the controller, or a run without xdist)
OWNER = pytest.StashKey[bool]()
#: xdist group of a notebook's item and of the tests that read its record
NOTEBOOK_GROUP = "nb:"
#: the group of the tests reading the generated notebooks of the ``selfcheck_records`` fixture
SELFCHECK = pytest.mark.xdist_group(NOTEBOOK_GROUP + "selfcheck")

#: rel -> record of this process
_RECORDS: dict[str, dict] = {}


def rel_of(path) -> str:
    p = Path(path).resolve()
    return p.relative_to(ROOT).as_posix() if p.is_relative_to(ROOT) else p.as_posix()


def slug(rel: str) -> str:
    return rel.replace("/", "__")


def run_dir() -> Path | None:
    d = os.environ.get(ENV)
    return Path(d) if d else None


def group(path) -> pytest.MarkDecorator:
    """The xdist group of the notebook ``path``: its item and the tests reading its record."""
    return pytest.mark.xdist_group(NOTEBOOK_GROUP + rel_of(path))


def params(paths, id_of=None):
    """``pytest.param`` per notebook, marked as a reader of that notebook's record (and in its group)."""
    return [pytest.param(p, id=id_of(p) if id_of else rel_of(p), marks=[getattr(pytest.mark, MARK)(rel_of(p)), group(p)])
            for p in paths]


# -- configuration -------------------------------------------------------------------------------

def configure(config):
    config.addinivalue_line("markers", f"{MARK}(notebook): reads the record of that notebook's one "
                            "execution (tests/nbrun.py)")
    # pytest-xdist registers it too; this keeps runs without xdist (-p no:xdist) free of warnings
    config.addinivalue_line("markers", "xdist_group(name): tests run on one worker under --dist loadgroup")
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


def configure_node(node):
    node.workerinput[ENV] = os.environ[ENV]


def default_groups(items):
    """pytest_collection_modifyitems (before pytest-xdist reads the marks): a test with no
    ``xdist_group`` of its own runs in its file's group, so a module-scoped fixture is built once;
    the browser self-checks share the group "browser" (one JupyterLab for them all). A test
    reading a notebook's record already has that notebook's group (:func:`params`)."""
    for item in items:
        if item.get_closest_marker("xdist_group") is None:
            rel = rel_of(item.path)
            item.add_marker(pytest.mark.xdist_group("browser" if rel.startswith("tests/browser/") else rel))


# -- the notebooks as test items ----------------------------------------------------------------------

def collect(file_path: Path, parent):
    """pytest_collect_file: a course notebook is a :class:`NotebookFile`."""
    if file_path.suffix != ".ipynb" or rel_of(file_path).split("/")[0] not in COURSE_DIRS:
        return None
    return NotebookFile.from_parent(parent, path=file_path)


class NotebookFailed(Exception):
    """A notebook raised in a cell, or did not run to its end."""


class NotebookFile(pytest.File):
    def collect(self):
        yield NotebookRun.from_parent(self, name="runs")


class NotebookRun(pytest.Item):
    """Executes its notebook (once per run: :func:`record`) and fails on what went wrong."""

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.add_marker(group(self.path))

    def runtest(self):
        rec = record(self.path)
        problems = list(rec["errors"])
        if not rec["complete"]:
            problems.append(f"{rec['path']}: its execution did not reach the end")
        if problems:
            raise NotebookFailed("\n".join(problems))

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, NotebookFailed):
            return str(excinfo.value)
        return super().repr_failure(excinfo, style=style)

    def reportinfo(self):
        return self.path, None, f"{rel_of(self.path)} runs"


# -- executing and recording ------------------------------------------------------------------------

def record(path) -> dict:
    """The record of ``path``'s one execution in this process (executed at the first call)."""
    rel = rel_of(path)
    if rel not in _RECORDS:
        rec = execute(Path(path).resolve())
        _RECORDS[rel] = rec
        _write(rec)
    return _RECORDS[rel]


def execute(path: Path) -> dict:
    """Execute the notebook ``path`` with nbclient, recorded (see the module docstring)."""
    import nbformat
    import nbrecord
    from nbclient import NotebookClient

    rel = rel_of(path)
    d = run_dir()
    if d is None:
        raise RuntimeError(f"{ENV} is not set: records are made inside a pytest run (tests/nbrun.py)")
    kernel_out = d / f"{slug(rel)}.kernel.json"
    kernel_out.unlink(missing_ok=True)
    nb = nbformat.read(path, as_version=4)
    install = (f"import sys\nsys.path.append({str(TESTS)!r}) if {str(TESTS)!r} not in sys.path else None\n"
               f"__import__('nbrecord').install_in_kernel({str(path)!r}, {rel!r})\n")
    finish = f"__import__('nbrecord').finish_in_kernel({str(kernel_out)!r}, {panel_state_code()!r})\n"
    problem = ""
    for _ in range(STARTS):
        run = nbformat.v4.new_notebook(metadata=nb.metadata)
        run.cells = [nbformat.v4.new_code_cell(install), *nbformat.read(path, as_version=4).cells,
                     nbformat.v4.new_code_cell(finish)]
        client = NotebookClient(run, timeout=CELL_TIMEOUT, startup_timeout=STARTUP_TIMEOUT, kernel_name="python3",
                                allow_errors=True, resources={"metadata": {"path": str(path.parent)}})
        try:
            client.execute()
            problem = ""
            break
        except Exception as e:  # noqa: BLE001 - a timeout or a dead kernel: the record says so
            problem = f"{type(e).__name__}: {str(e)[-1500:]}"
            if run.cells[0].get("execution_count") is not None:
                break   # the kernel ran the notebook's code: never run it twice
    try:
        rec = json.loads(kernel_out.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        rec = None
    if rec is None:
        rec = nbrecord.empty_record(rel, "kernel")
        rec["errors"].append(f"{rel}: no record of its execution: {problem or 'the recorder wrote none'}")
    elif problem:
        rec["errors"].append(f"{rel}: {problem}")
    for hidden in (run.cells[0], run.cells[-1]):
        for o in hidden.get("outputs", []):
            if o.get("output_type") == "error":
                rec["errors"].append(f"{rel}: the recorder raised {o.get('ename')}: {o.get('evalue')}")
    code = [c for c in run.cells[1:-1] if c.cell_type == "code"]
    rec["outputs"] = {str(k): json.loads(json.dumps(c.get("outputs", []))) for k, c in enumerate(code, 1)}
    return rec


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
    """The notebook of ``record`` as its execution left it: every code cell with its outputs and
    its execution count (cells counted from 1, as Run All numbers them)."""
    nb = json.loads((ROOT / record["path"]).read_text(encoding="utf-8"))
    k = 0
    for cell in nb.get("cells", []):
        if cell.get("cell_type") == "code":
            k += 1
            cell["outputs"] = record["outputs"].get(str(k), [])
            cell["execution_count"] = k
    return nb


def panel_state_code() -> str | None:
    """The browser tests' panel-state epilogue, so their reference comes from this run's record."""
    sys.path.insert(0, str(TESTS / "browser"))
    try:
        import labview
    except ImportError:   # no browser tests, no epilogue
        return None
    finally:
        sys.path.remove(str(TESTS / "browser"))
    return labview.PANEL_STATE_CODE


# -- durations by file and worker (controller side) ------------------------------------------------

_BY_FILE: dict[str, dict] = {}
#: xdist worker -> {"seconds": summed test time, "last": when its last report came (s after start)}
_WORKERS: dict[str, dict] = {}
_T0 = time.time()


def category(nodeid: str) -> str:
    """The row of build/nbrun/run-*/by-file.json: "notebooks book" etc., else the test file."""
    f = nodeid.split("::")[0]
    return "notebooks " + f.split("/")[0] if f.endswith(".ipynb") else f


def logreport(report):
    dt = float(report.duration or 0.0)
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
    if not config.stash.get(OWNER, False) or not _BY_FILE:
        return
    d = run_dir()
    rows = {k: {**v, "seconds": round(v["seconds"], 2)} for k, v in sorted(_BY_FILE.items())}
    (d / "by-file.json").write_text(json.dumps(rows, indent=1), encoding="utf-8")
    workers = {k: {"seconds": round(v["seconds"], 1), "last": round(v["last"], 1)} for k, v in sorted(_WORKERS.items())}
    (d / "workers.json").write_text(json.dumps(workers, indent=1), encoding="utf-8")

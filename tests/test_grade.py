"""The autograder (issue 20): python -m gm_grader, graded on a hostile batch.

One grading run takes, together, a notebook that tries to edit the course's code and drop a .pth
into site-packages, read and rewrite a classmate's file and the results, start setsid daemons,
then kills its parent; an honest classmate whose answers are slow (1.5 s per call), who uses
every call form and reassigns an answer after checking it, with a cell that sleeps forever; a
forger (a post_run_cell hook printing evidence, all-"skip", replayed, mistyped, extra and
secret-less records, a deep-JSON record, a deep expression, an output flood, a loop that ignores
SIGINT); two key seekers (issue 38: the reference reached through a hook, a patched emitter, a
thread, directly, by the run's secret, and the worked solution looked for on disk); one real
solution and its untouched exercise. Each must get exactly its deserved grade, with the course,
the classmate and the results untouched and no process left behind. Further runs (no kernels,
or one) cover assignments, leftovers, bad files, empty uploads and the refusal to run without a
sandbox."""
import base64
import csv
import hashlib
import inspect
import json
import os
import re
import site
import subprocess
import sys
import time
import uuid
from pathlib import Path

import nbformat
import numpy as np
import pytest

from gm_core.checks import channel
from gm_core.checks.ex1 import ex1_1, ex1_2
from gm_core.checks.exercise import REGISTRY, exercise_ids
from gm_core.checks.protocol import (
    CellEnded,
    CellStarted,
    CellStatus,
    Done,
    EvidenceLine,
    Fatal,
    ForeignEvidence,
    Limits,
    ProtocolError,
    Started,
)
from gm_grader import evidence as _evidence
from gm_grader import report as _report
from gm_grader.batch import identify, leftover_reason, load_assignment
from gm_grader.isolate import Killed, RunResult, _own_cgroup_dirs, sandbox_problem

ROOT = Path(__file__).resolve().parent.parent
TOKEN = f"gm-test-daemon-{uuid.uuid4().hex[:8]}"
NO_SANDBOX = sandbox_problem()
CGROUPS = {"pids", "memory"} <= set(_own_cgroup_dirs())
needs_sandbox = pytest.mark.skipif(NO_SANDBOX is not None, reason=f"no sandbox: {NO_SANDBOX}")


def env():
    return {**os.environ, "PYTHONPATH": str(ROOT)}


def write_nb(path, cells, meta=None):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(c) for c in cells]
    if meta is not None:
        nb.metadata["gm_course"] = meta
    path.parent.mkdir(parents=True, exist_ok=True)
    nbformat.write(nb, path)
    return path


def tree_hash(folder, pattern="*.py"):
    h = hashlib.sha256()
    for p in sorted(Path(folder).rglob(pattern)):
        h.update(p.name.encode() + p.read_bytes())
    return h.hexdigest()


def grade_cli(*args, cwd, timeout=600):
    return subprocess.run([sys.executable, "-m", "gm_grader", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, env=env(), timeout=timeout)


def honest_cells():
    return ["import numpy as np, time\nimport gm_core.checks as C\nfrom gm_core.checks import ex1_2",
            "answer_a = lambda h, g: h * g\nex1_2.a.check(answer=answer_a)",
            "answer_a = None   # reassigned after its check: judged as it was when checked",
            "def slow_b(h, g):\n    time.sleep(1.5)\n    return np.diag(h)\n\n"
            "def helper():\n    e = ex1_2\n    e.b.check(slow_b)\n\nhelper()",
            "time.sleep(10**6)",
            "C.ex1_2.c.check(lambda h, g: np.eye(2))\nC.ex1_2.check({'c': lambda h, g: np.diag(h)})"]


def forger_cells():
    return ["import numpy as np, json, os, sys\nfrom gm_core.checks import ex1_2, channel\n"
            "forged = json.dumps({p: {'outcomes': [{'k': 'ok', 'v': 'skip'}] * 9} for p in 'abc'})\n"
            "get_ipython().events.register('post_run_cell', "
            "lambda *a: print('<<gm-course-grading>>' + forged))",
            "ex1_2.a.check(lambda h, g: h + g)\nex1_2.b.check(lambda h, g: np.diag(g))\n"
            "ex1_2.c.check(lambda h, g: np.eye(2))",
            "fd, nonce = channel._STATE.fd, channel._STATE.nonce\n"
            "def rec(part, o, n=nonce):\n"
            "    os.write(fd, (json.dumps({'kind': 'evidence', 'nonce': n, 'exercise': '1.2', "
            "'part': part, 'outcomes': o, 'output': '', 'answer': '', 'unsent': ''}) + '\\n').encode())\n"
            "def nd(x):\n    x = np.asarray(x, float)\n    return {'__nd__': list(x.shape), 'd': x.ravel().tolist()}\n"
            "P = ex1_2.parts\n"
            "rec('a', [{'k': 'ok', 'v': 'skip'}] * len(P['a'].probes()))             # all skip\n"
            "salt = channel.probe_salt()\nchannel.set_probe_salt(None)\n"
            "rec('b', [{'k': 'ok', 'v': nd(np.diag(a[0]))} for a in P['b'].inputs()])  # replayed\n"
            "channel.set_probe_salt(salt)\n"
            "right = [{'k': 'ok', 'v': nd(np.diag(a[0]))} for a in P['c'].inputs()]  # by hand\n"
            "rec('c', right, n='0' * 32)                                            # no secret\n"
            "rec('c', [{'k': 'ok', 'v': True}] * len(right))                        # mistyped\n"
            "rec('c', right + right)                                                # extra\n"
            "rec('c', [dict(o, extra=1) for o in right])                            # extra field\n"
            "os.write(fd, b'[' * 100000 + b'\\n')                                   # deep JSON",
            "for _ in range(200):\n    sys.stdout.write('x' * 100_000 + '\\n')     # 20 MB of output",
            "x = " + "-" * 5000 + "1",
            "import signal\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\nwhile True:\n    pass"]


def key_seeker_cells():
    """Three ways to full marks with wrong answers, each through the answer key: an IPython
    post_run_cell hook re-checking with the reference (a), the function that emits outcomes
    replaced to send the reference's (b), a thread re-checking with the reference after the
    last cell starts (c)."""
    return ["import numpy as np, threading, time\nfrom gm_core.checks import ex1_2, channel\n"
            "from gm_core.checks.sandbox import collect\n"
            "def quietly(f):\n    try:\n        f()\n    except Exception:\n        pass\n"
            "get_ipython().events.register('post_run_cell', "
            "lambda *a: quietly(lambda: ex1_2.a.check(ex1_2.a.reference)))\n"
            "ex1_2.a.check(lambda h, g: h + g)",
            "send = channel.emit\n"
            "def emit(part, outcomes, output='', answer=None):\n"
            "    try:\n        outcomes = collect(part.reference, part.probes(), raw=True)[0]\n"
            "    except Exception:\n        pass\n"
            "    send(part, outcomes, output, answer)\n"
            "channel.emit = emit\n"
            "ex1_2.b.check(lambda h, g: np.diag(g))",
            "def later():\n    time.sleep(0.2)\n    quietly(lambda: ex1_2.c.check(ex1_2.c.reference))\n"
            "threading.Thread(target=later).start()\n"
            "ex1_2.c.check(lambda h, g: np.eye(2))",
            "time.sleep(1.5)"]


def solution_seeker_cells():
    """Three more: the reference checked directly (a); the worked solution notebook and the key
    files looked for wherever the course lives, and run if found (b); the run's secret used to
    write well-formed outcomes computed from the key's reference function, after .solution() (c)."""
    return ["import numpy as np, json, os, glob, runpy\nimport gm_core\nfrom gm_core.checks import ex1_2, channel\n"
            "try:\n    ex1_2.a.check(ex1_2.a.reference)\nexcept Exception:\n    ex1_2.a.check(lambda h, g: h + g)",
            "root = os.path.dirname(os.path.dirname(gm_core.__file__))\n"
            "found = [p for pat in ('solutions/ex1_2.ipynb', 'gm_core/checks/keys/*.py', '**/ex1_2.ipynb')\n"
            "         for p in glob.glob(os.path.join(root, pat), recursive=True) + glob.glob('/' + pat)]\n"
            "answer_b = lambda h, g: np.diag(np.asarray(h, float) + 1.0)\n"
            "for p in found:\n"
            "    if p.endswith('.py'):\n        runpy.run_path(p)\n"
            "    else:\n        cells = json.load(open(p))['cells']\n"
            "        exec('\\n'.join(''.join(c['source']) for c in cells if c['cell_type'] == 'code'))\n"
            "ex1_2.b.check(answer_b)\nprint(found)",
            "ex1_2.c.solution()\n"
            "fd, nonce = channel._STATE.fd, channel._STATE.nonce\n"
            "nd = lambda x: {'__nd__': [2, 2], 'd': np.asarray(x, float).ravel().tolist()}\n"
            "out = [{'k': 'ok', 'v': nd(ex1_2.c.ref(*a))} for a in ex1_2.c.inputs()]\n"
            "os.write(fd, (json.dumps({'kind': 'evidence', 'nonce': nonce, 'exercise': '1.2', "
            "'part': 'c', 'outcomes': out, 'output': '', 'answer': '', 'unsent': ''}) + '\\n').encode())"]


def outcome_forger_cells(out):
    """Wrong answers checked while the function that sends outcomes is replaced to send those of
    the right answers (as a notebook with the answer key would once have): the outcomes a notebook
    sends weigh nothing, its answers are called again by the grader (a); an answer whose pickle
    runs code when the grader's sandbox loads it, there trying to write into the grader's output
    folder (b). And an answer that holds a lock, which cannot be handed to the grader, gets a
    message saying so (c)."""
    forge = f"open({str(out / 'grades.csv')!r}, 'w').write('forged')"
    return ["import numpy as np, threading\nfrom gm_core.checks import ex1_2, channel\n"
            "from gm_core.checks.sandbox import collect\n"
            "right = {'a': lambda h, g: h * g, 'b': lambda h, g: np.diag(h)}\n"
            "send = channel.emit\n"
            "def emit(part, outcomes, output='', answer=None):\n"
            "    send(part, collect(right[part.name], part.probes(), raw=True)[0], output, answer)\n"
            "channel.emit = emit\n"
            "class Loaded:\n    def __reduce__(self):\n"
            f"        return (exec, ({forge!r},))\n"
            "ex1_2.a.check(lambda h, g: h + g)\nex1_2.b.check(Loaded())",
            "channel.emit = send\nlock = threading.Lock()\n"
            "def answer_c(h, g):\n    with lock:\n        return np.diag(h)\n\n"
            "ex1_2.c.check(answer_c)"]


def tamper_cells(out, honest, neighbour):
    return [f"import numpy as np, os, sys, subprocess, site, glob\nfrom gm_core.checks import ex1_2\n"
            f"OUT, HONEST, NEIGHBOUR = {str(out)!r}, {str(honest)!r}, {str(neighbour)!r}\n"
            "def attempt(f):\n    try:\n        f()\n    except Exception:\n        pass\n"
            "import gm_core.checks.channel as g\n"
            f"attempt(lambda: open(g.__file__, 'a').write('\\n# {TOKEN}\\n'))\n"
            "for sp in site.getsitepackages():\n"
            "    attempt(lambda: open(os.path.join(sp, 'zz_gm_tamper.pth'), 'w').write('import sys\\n'))\n"
            "attempt(lambda: open(HONEST, 'a').write(' '))\n"
            "attempt(lambda: os.makedirs(OUT, exist_ok=True))\n"
            "attempt(lambda: open(os.path.join(OUT, 'results.json'), 'w').write('{}'))\n"
            "names = [open(p, 'rb').read() for p in glob.glob('/proc/[0-9]*/cmdline')]\n"
            "daemon = ('import time, os\\ntime.sleep(2.5)\\nfor f in (\"results.json\", \"grades.csv\"):\\n'\n"
            "          '    open(os.path.join(%r, f), \"w\").write(\"forged\")\\n' % OUT)\n"
            f"subprocess.Popen([sys.executable, '-c', daemon, {TOKEN!r}], start_new_session=True)",
            "try:\n    big = bytearray(3 << 30)        # over the 2 GiB memory limit\n"
            "except MemoryError:\n"
            "    if not os.path.exists(HONEST) and not os.path.exists(NEIGHBOUR):   # out of sight\n"
            "        ex1_2.a.check(lambda h, g: h * g)",
            "os.kill(os.getppid(), 9)",
            "ex1_2.b.check(lambda h, g: np.diag(h))"]


def staller_cells():
    """A kernel that pauses the cell clock: a check announced for a part that does not exist, a
    patched clock, then its runner stopped with SIGSTOP (only the grading process's own clock,
    outside the sandbox, can end that cell)."""
    return ["import numpy as np, os, signal, time\nfrom gm_core.checks import ex1_2, channel\n"
            "from gm_core.checks.protocol import CheckBegun, encode_kernel_message as enc\n"
            "ex1_2.a.check(lambda h, g: h * g)",
            "os.write(channel._STATE.fd, enc(CheckBegun('9.9/z')))  # 'my probes are running'\n"
            "time.monotonic = time.time = time.perf_counter = lambda: 0.0\n"
            "time.sleep(10**6)",
            "ex1_2.b.check(lambda h, g: np.diag(h))",
            "os.kill(os.getppid(), signal.SIGSTOP)           # the grader's runner\n"
            "signal.signal(signal.SIGINT, signal.SIG_IGN)\ntime.sleep(10**6)",
            "ex1_2.c.check(lambda h, g: np.diag(h))"]


BOMB = f"gmb{TOKEN[-8:]}"          # the fork bomb's processes carry this name (/proc/<pid>/comm)


def bomb_cells():
    """A fork bomb, once it has checked that the process limit holds (so it never runs unbounded)."""
    name = f"ctypes.CDLL(None).prctl(15, {BOMB.encode()!r}, 0, 0, 0)"
    return ["import numpy as np, os, signal, time, ctypes\nfrom gm_core.checks import ex1_2\n"
            "ex1_2.a.check(lambda h, g: h * g)",
            "n = 0\nwhile n < 150:\n    try:\n        pid = os.fork()\n    except OSError:\n        break\n"
            f"    if pid == 0:\n        {name}\n        while True:\n            time.sleep(1)\n"
            "    n += 1\nheld = n < 100\n"
            "if held:                                        # the process limit held\n"
            "    ex1_2.b.check(lambda h, g: np.diag(h))",
            "signal.signal(signal.SIGINT, signal.SIG_IGN)\n"
            f"while held:\n    try:\n        if os.fork() == 0:\n            {name}\n"
            "    except OSError:\n        time.sleep(0.5)",
            "ex1_2.c.check(lambda h, g: h + g)"]


def named(comm):
    found = []
    for p in Path("/proc").glob("[0-9]*/comm"):
        try:
            if p.read_text().strip() == comm:
                found.append(p.parent.name)
        except OSError:
            pass
    return found


def alive_with(token):
    found = []
    for p in Path("/proc").glob("[0-9]*/cmdline"):
        try:
            if token.encode() in p.read_bytes():
                found.append(p.parent.name)
        except OSError:
            pass
    return found


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("grading")
    out = tmp / "out"
    honest = write_nb(tmp / "honest" / "ex1_2.ipynb", honest_cells())
    write_nb(tmp / "forger" / "ex1_2.ipynb", forger_cells())
    write_nb(tmp / "keyseeker" / "ex1_2.ipynb", key_seeker_cells())
    write_nb(tmp / "solseeker" / "ex1_2.ipynb", solution_seeker_cells())
    write_nb(tmp / "outcomes" / "ex1_2.ipynb", outcome_forger_cells(out))
    neighbour = tmp / "not-in-this-batch" / "ex1_2.ipynb"          # another upload, not graded now
    neighbour.parent.mkdir()
    neighbour.write_text("{}")
    write_nb(tmp / "tamper" / "ex1_2.ipynb", tamper_cells(out, honest, neighbour))
    write_nb(tmp / "staller" / "ex1_2.ipynb", staller_cells())
    write_nb(tmp / "bomb" / "ex1_2.ipynb", bomb_cells())
    for kind in ("solutions", "exercises"):
        (tmp / kind).mkdir()
        (tmp / kind / "ex1_1.ipynb").write_bytes((ROOT / kind / "ex1_1.ipynb").read_bytes())
    course, pth = tree_hash(ROOT / "gm_core"), honest.read_bytes()
    t = time.monotonic()
    proc = subprocess.Popen([sys.executable, "-m", "gm_grader", *map(str, (
        tmp / "tamper", tmp / "honest", tmp / "forger", tmp / "staller", tmp / "bomb", tmp / "solutions",
        tmp / "exercises", tmp / "keyseeker", tmp / "solseeker", tmp / "outcomes",
        "--out", out, "--cell-timeout", "4", "--jobs", "3", "--memory", "2048",
        "--max-processes", "64"))], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
        cwd=tmp, env=env())
    stdout, stderr = proc.communicate(timeout=900)
    res = subprocess.CompletedProcess(proc.args, proc.returncode, stdout, stderr)
    elapsed = time.monotonic() - t
    assert res.returncode == 0, res.stderr + res.stdout
    snapshot = {f: (out / f).read_bytes() for f in ("results.json", "grades.csv")}
    rows = list(csv.DictReader(open(out / "grades.csv", encoding="utf-8")))
    return {"tmp": tmp, "out": out, "rows": rows, "stdout": res.stdout, "snapshot": snapshot,
            "results": json.loads(snapshot["results.json"]), "course": course, "honest": pth,
            "honest_path": honest, "elapsed": elapsed, "grader_pid": proc.pid}


def rows_of(batch, folder):
    return {r["part"]: r for r in batch["rows"] if r["notebook"].split("/")[0] == folder}


def scores(batch, folder):
    return {p: float(r["score"]) for p, r in rows_of(batch, folder).items()}


@needs_sandbox
def test_honest_slow_every_call_form_judged_at_check_time(batch):
    rows = rows_of(batch, "honest")
    assert scores(batch, "honest") == {"a": 2.0, "b": 2.0, "c": 2.0}, rows
    assert "cell 4" in rows["b"]["message"]             # 8 calls x 1.5 s under a 4 s cell limit
    assert "cell 6" in rows["c"]["message"]             # after the interrupted sleep


@needs_sandbox
def test_forged_evidence_never_passes(batch):
    rows = rows_of(batch, "forger")
    assert scores(batch, "forger") == {"a": 0.0, "b": 0.0, "c": 0.0}, rows
    msg = rows["c"]["message"]
    assert "rejected evidence" in msg and "this run's secret" in msg and "not valid JSON" in msg
    assert "wrong number of outcomes" in msg and "malformed outcomes" in msg


ASKED = "asked for this part's answer key"


@needs_sandbox
def test_the_grade_comes_from_the_graders_own_calls_not_the_notebooks_outcomes(batch):
    rows = rows_of(batch, "outcomes")
    assert scores(batch, "outcomes") == {"a": 0.0, "b": 0.0, "c": 0.0}, rows
    for part in "ab":                    # judged on the grader's calls of the wrong answers
        assert rows[part]["status"] == "failed" and "Correct" not in rows[part]["message"], rows
        assert "checked in cell 1" in rows[part]["message"], rows[part]
    assert "added the parameters" in rows["a"]["message"]     # the mistake h + g makes
    assert "could not be rebuilt outside the notebook" in rows["b"]["message"], rows["b"]
    assert batch["snapshot"]["grades.csv"] != b"forged"      # the grader's own sandbox held it
    assert "could not be handed to the grader" in rows["c"]["message"], rows["c"]
    assert "lock" in rows["c"]["message"], rows["c"]


@needs_sandbox
def test_the_answer_key_is_out_of_reach_and_asking_for_it_earns_nothing(batch):
    """Issue 38's forging routes through the reference (a hook, a patched emitter, a thread, the
    reference itself, the solution notebook, the secret with the key's outcomes) score 0, and
    each row says why; the honest classmate in the same batch keeps full marks."""
    seek, sol = rows_of(batch, "keyseeker"), rows_of(batch, "solseeker")
    assert scores(batch, "keyseeker") == scores(batch, "solseeker") == {"a": 0.0, "b": 0.0, "c": 0.0}
    for part in "abc":
        assert ASKED in seek[part]["message"], seek[part]
    assert ASKED in sol["a"]["message"] and "(reference)" in sol["a"]["message"], sol["a"]
    assert ASKED in sol["c"]["message"] and "(solution())" in sol["c"]["message"], sol["c"]
    assert ASKED not in sol["b"]["message"] and "differ" in sol["b"]["message"], sol["b"]  # nothing found
    assert scores(batch, "honest") == {"a": 2.0, "b": 2.0, "c": 2.0}


@needs_sandbox
def test_tampering_reaches_nothing_and_no_process_survives(batch):
    # a is checked only if the memory limit held and neither classmate's file was in sight
    assert scores(batch, "tamper") == {"a": 2.0, "b": 0.0, "c": 0.0}
    msg = rows_of(batch, "tamper")["b"]["message"]
    assert "not checked before the notebook ended its own grading in cell 3 (`os.kill" in msg, msg
    time.sleep(3.0)                                      # the daemon would have written by now
    for f, data in batch["snapshot"].items():
        assert (batch["out"] / f).read_bytes() == data
    assert sorted(p.name for p in batch["out"].iterdir()) == ["grades.csv", "results.json"]
    assert tree_hash(ROOT / "gm_core") == batch["course"]
    assert TOKEN not in (ROOT / "gm_core" / "checks" / "channel.py").read_text()
    assert not any(Path(sp, "zz_gm_tamper.pth").exists() for sp in site.getsitepackages())
    assert batch["honest_path"].read_bytes() == batch["honest"]
    assert alive_with(TOKEN) == []
    assert alive_with(str(batch["tmp"])) == []             # no sandbox of this run either


@needs_sandbox
def test_a_kernel_cannot_stop_its_cell_clock(batch):
    rows = rows_of(batch, "staller")
    assert scores(batch, "staller") == {"a": 2.0, "b": 2.0, "c": 0.0}, rows
    lines = batch["results"]["output"].splitlines()
    assert any(ln.startswith("staller/ex1_2.ipynb: cell 2 (`os.write(channel._STATE.fd, enc(CheckBegun('9.9/z'")
               and ln.endswith("ran longer than the cell limit and was interrupted") for ln in lines), lines
    msg = rows["c"]["message"]
    assert "the grader ended the notebook in cell 4 (`os.kill(os.getppid(), signal.SIGSTOP)" in msg, msg


@needs_sandbox
def test_a_fork_bomb_is_held_and_ended_whole(batch):
    held = CGROUPS or os.geteuid() != 0
    rows = rows_of(batch, "bomb")
    assert scores(batch, "bomb") == {"a": 2.0, "b": 2.0 if held else 0.0, "c": 0.0}, rows
    if held:
        assert "kernel stopped in cell 3" in rows["c"]["message"], rows["c"]["message"]
    else:
        assert "no pids" in batch["results"]["output"]
    assert named(BOMB) == []
    assert scores(batch, "honest") == {"a": 2.0, "b": 2.0, "c": 2.0}     # its classmates unharmed
    left = [d for c in ("pids", "memory") for d in Path(f"/sys/fs/cgroup/{c}").rglob("gm-grade-*")
            if str(batch["grader_pid"]) in d.name]
    assert left == []                                                    # its cgroups removed


@needs_sandbox
def test_a_solution_full_marks_its_exercise_zero(batch):
    assert scores(batch, "solutions") == {"a": 1.0, "b": 1.0}
    assert scores(batch, "exercises") == {"a": 0.0, "b": 0.0}


@needs_sandbox
def test_results_are_gradescope_ready(batch):
    res = batch["results"]
    held = CGROUPS or os.geteuid() != 0
    total = 6 + 2 + 4 + (4 if held else 2) + 2          # honest, tamper, staller, bomb, solution
    assert res["score"] == pytest.approx(sum(t["score"] for t in res["tests"])) == total, \
        {(r["notebook"], r["part"]): r["score"] for r in batch["rows"] if float(r["score"])}
    assert len(res["tests"]) == len(batch["rows"]) == 8 * 3 + 2 * 2
    for t in res["tests"]:
        assert {"name", "number", "score", "max_score", "output", "visibility", "status"} <= set(t)
        assert 0 <= t["score"] <= t["max_score"] and t["visibility"] == "visible"
        assert not t["name"].startswith("/") and str(batch["tmp"]) not in t["name"] + t["output"]
    assert f"{total} / 52 points" in batch["stdout"]


@needs_sandbox
def test_assignment_leftovers_bad_files_and_no_sandbox(tmp_path):
    """Declared exercises fix the maximum; leftovers are skipped with a note; a misnamed, a
    deep-JSON and a metadata-string notebook get messages; the dict call form (no sandbox); a
    setsid daemon, which no pid namespace ends here, is ended with the notebook's cgroup."""
    sub = tmp_path / "sub"
    token = f"gm-test-nosandbox-{uuid.uuid4().hex[:8]}"
    write_nb(sub / "ex1_1.ipynb", [
        "import subprocess, sys\nfrom gm_core.checks import ex1_1\n"
        f"subprocess.Popen([sys.executable, '-c', 'import time\\nwhile True: time.sleep(1)', {token!r}],"
        " start_new_session=True)\nex1_1.check({'a': 'b', 'b': 'c'}, strict=True)"])
    for name in ("ex1_1.course-update.ipynb", "ex1_1-Copy1.ipynb", "Copy of ex1_2.ipynb",
                 ".ipynb_checkpoints/ex1_1-checkpoint.ipynb"):
        write_nb(sub / name, ["from gm_core.checks import ex1_1\nex1_1.a.check('b')"])
    (sub / "ex1_3.ipynb").write_text("[" * 100000)
    write_nb(sub / "homework.ipynb", ["1"], meta="not a dict")
    (tmp_path / "a.json").write_text(json.dumps({"exercises": ["1.1", "1.2", "1.3"], "max_score": 10,
                                                 "visibility": "after_due_date",
                                                 "part_visibility": {"1.1a": "hidden"}}))
    try:
        res = grade_cli(sub, "--out", tmp_path / "out", "--assignment", tmp_path / "a.json",
                        "--no-sandbox", cwd=tmp_path)
        daemons = alive_with(token)
    finally:
        for pid in alive_with(token):
            os.kill(int(pid), 9)
    assert daemons == [] if CGROUPS else daemons            # without a cgroup: the limitation
    assert res.returncode == 0, res.stderr
    r = json.loads((tmp_path / "out" / "results.json").read_text())
    tests = {t["number"]: t for t in r["tests"] if t["number"]}
    assert set(tests) == {"1.1a", "1.1b", "1.2a", "1.2b", "1.2c", "1.3a", "1.3b", "1.3c"}
    assert sum(t["max_score"] for t in tests.values()) == 13.0
    assert tests["1.1a"]["score"] == tests["1.1b"]["score"] == 1.0
    assert r["score"] == pytest.approx(2 * 10 / 13)                 # scaled to the declared max
    assert "not found" in tests["1.2a"]["output"] and "nested too deeply" in tests["1.3a"]["output"]
    assert tests["1.1a"]["visibility"] == "hidden" and tests["1.1b"]["visibility"] == "after_due_date"
    for leftover in ("course-update", "Copy1", "Copy of", "checkpoint"):
        assert leftover in r["output"], r["output"]
    assert "homework.ipynb" in r["output"] and "not one of the course's exercise" in r["output"]
    assert ("Grader note" in r["output"]) != CGROUPS


def test_empty_upload_says_so_and_no_sandbox_means_refusal(tmp_path):
    (tmp_path / "empty").mkdir()
    res = grade_cli(tmp_path / "empty", "--out", tmp_path / "out", "--no-sandbox", cwd=tmp_path)
    assert res.returncode == 0, res.stderr
    r = json.loads((tmp_path / "out" / "results.json").read_text())
    assert r["tests"] == [] and r["score"] == 0 and "No exercise notebook" in r["output"]
    e = {**env(), "PATH": str(tmp_path)}                          # no bwrap on this PATH
    res = subprocess.run([sys.executable, "-m", "gm_grader", str(tmp_path / "empty"), "--out",
                          str(tmp_path / "o2")], capture_output=True, text=True, env=e)
    assert res.returncode == 3 and "--no-sandbox" in res.stderr and "bubblewrap" in res.stderr
    assert not (tmp_path / "o2").exists()


def test_cli_errors_are_clear(tmp_path):
    res = grade_cli(tmp_path / "nope.ipynb", "--out", tmp_path, cwd=tmp_path)
    assert res.returncode == 2 and "no such file" in res.stderr
    (tmp_path / "a.json").write_text('{"exercises": ["9.9"]}')
    res = grade_cli(tmp_path, "--out", tmp_path / "o", "--assignment", tmp_path / "a.json", cwd=tmp_path)
    assert res.returncode == 2 and "9.9" in res.stderr


# ------------------------------------------------------------------ without kernels
def test_leftovers_and_identification(tmp_path):
    assert leftover_reason(Path("ex1_1.course-update.ipynb"))
    assert leftover_reason(Path("ex1_1.course-update-2.ipynb"))
    assert leftover_reason(Path("ex1_4-Copy2.ipynb")) and leftover_reason(Path("Copy of ex1_4.ipynb"))
    assert leftover_reason(Path(".ipynb_checkpoints/ex1_4-checkpoint.ipynb"))
    assert leftover_reason(Path("ex1_4.ipynb")) is None
    assert identify(write_nb(tmp_path / "ex2_3.ipynb", []))[0] == "2.3"
    ex_id, note, _ = identify(write_nb(tmp_path / "ex1_4 (1).ipynb", []))
    assert ex_id == "1.4" and "named" in note
    ex_id, note, _ = identify(write_nb(tmp_path / "mine.ipynb", [], {"generated_from": "solutions/ex3_1.ipynb"}))
    assert ex_id == "3.1" and "metadata" in note
    assert identify(write_nb(tmp_path / "x.ipynb", [], "a string"))[0] is None
    (tmp_path / "deep.ipynb").write_text("{" + '"a":' * 1 + "[" * 100000)
    assert identify(tmp_path / "deep.ipynb")[0] is None
    (tmp_path / "ex1_1.ipynb").symlink_to("/dev/zero")            # never read, never run
    assert identify(tmp_path / "ex1_1.ipynb") == ("1.1", "", None)


def test_assignment_validation(tmp_path):
    p = tmp_path / "a.json"
    p.write_text('{"notebooks": ["ex1_1.ipynb"], "max_score": 5}')
    assert load_assignment(p).exercises == ("1.1",)
    for bad in ('[1]', '{"exercises": []}', '{"exercises": ["1.1"], "visibility": "sometimes"}',
                '{"exercises": ["1.1"], "max_score": -1}', '{"exercises": ["1.1"], "typo": 1}'):
        p.write_text(bad)
        with pytest.raises(ValueError):
            load_assignment(p)


def evidence_line(o, nonce="s", ex="1.2", name="a", **kw):
    """A kernel's evidence line, written by hand (as a forger would)."""
    return json.dumps({"kind": "evidence", "nonce": nonce, "exercise": ex, "part": name,
                       "outcomes": o, "output": "", "answer": "", "unsent": "", **kw})


@pytest.mark.parametrize("outcomes", [None, {}, "x", [], "stopped", "too large",
                                      [{"k": "ok", "v": {"__nd__": [3], "d": [1, 2]}}],
                                      [{"k": "ok", "v": "a"}] * 99,
                                      [{"k": "ok", "v": "skip"}] * 99, {"missing": "NameError"}])
def test_forged_or_garbled_evidence_never_passes(outcomes):
    for ex_id in exercise_ids():
        ex = REGISTRY[ex_id]
        for part in ex.parts.values():
            o = outcomes
            if outcomes == [{"k": "ok", "v": "skip"}] * 99:
                o = outcomes[:len(part.probes())]               # the right count: judged, failed
            try:
                ev = _evidence.parse_line(evidence_line(o, ex=ex_id, name=part.name), "s", ex)
            except ProtocolError:
                continue                                        # rejected
            assert not _evidence.judge_part(part, ev).passed, (ex_id, part.name, outcomes)
        assert not _evidence.judge_part(part, None).passed


def test_records_are_checked_not_believed():
    part = ex1_2.a
    n = len(part.probes())
    ok = [{"k": "ok", "v": {"__nd__": [2], "d": list(map(float, part.ref(*a)))}} for a in part.inputs()]
    line = evidence_line
    ev = _evidence.parse_line(line(ok), "s", REGISTRY["1.2"])
    assert ev.part == "a" and _evidence.judge_part(part, ev).passed   # the right values do pass
    for bad in (line(ok, nonce="t"), line(ok, name="z"), line(ok + ok), line(ok[:-1]),
                line(ok, extra=1), line([dict(o, x="") for o in ok]), "[" * 50000, "{}",
                line([{"k": "ok", "v": {"__nd__": [3], "d": [1.0, 2.0]}}] * n),
                line([{"k": "nope", "v": 1}] * n), line([{"k": "ok", "v": [[[[[[[[[[[[[[1]]]]]]]]]]]]]]}] * n),
                line(ok).replace('"evidence"', '"begin"')):
        with pytest.raises(ProtocolError) as exc:
            _evidence.parse_line(bad, "s", REGISTRY["1.2"])
        assert not isinstance(exc.value, ForeignEvidence), bad
    with pytest.raises(ForeignEvidence):
        _evidence.parse_line(line(ok, ex="1.1"), "s", REGISTRY["1.2"])       # other exercise


def test_probe_inputs_are_salted_and_skip_only_where_sympy_allows():
    part = ex1_2.a
    plain = [a for a in part.inputs()]
    try:
        channel.set_probe_salt(12345)
        salted = [a for a in part.inputs()]
        same = sum(all(np.array_equal(x, y) for x, y in zip(p, s)) for p, s in zip(plain, salted))
        assert 0 < same < len(plain)                     # edge cases fixed, random inputs moved
    finally:
        channel.set_probe_salt(None)
    assert [np.asarray(a[0]).tolist() for a in part.inputs()] == [np.asarray(a[0]).tolist() for a in plain]


class Replay:
    """A reference function that records its outputs, then plays them back in call order: the
    'answer' of a student who hard-codes what the checker's calls returned last time."""

    def __init__(self, f):
        self.f, self.tape, self.replay, self.i = f, [], False, 0
        self.__signature__ = inspect.signature(f)     # called the way the reference is

    def __deepcopy__(self, memo):     # the in-process probes copy the answer: keep one tape
        return self

    def __call__(self, *args):
        if not self.replay:
            self.tape.append(self.f(*args))
            return self.tape[-1]
        self.i += 1
        return self.tape[(self.i - 1) % len(self.tape)]


def _replaying(ref):
    if isinstance(ref, dict):
        return {k: Replay(v) for k, v in ref.items()}
    if isinstance(ref, tuple):
        return tuple(Replay(v) for v in ref)
    return Replay(ref)


@pytest.mark.parametrize("part_id", ["1.2a", "1.4d", "2.1a", "4.2a", "5.1a"])
def test_last_runs_probe_outputs_hard_coded_fail_a_new_run(part_id, clean, monkeypatch):
    """Every part whose answer is called on inputs gets fresh inputs each graded run: the outputs
    of the last run, played back, pass that run's inputs but not the next run's. (1.3c's and
    4.1b's answers are values, called on nothing: there is no input to choose.)"""
    monkeypatch.setenv("GM_CHECKS_NO_FORK", "1")          # the tape must stay in this process
    ex_id, name = part_id[:3], part_id[3:]
    part = REGISTRY[ex_id].parts[name]
    answer = _replaying(part.reference)
    tapes = list(answer.values()) if isinstance(answer, dict) else list(answer) \
        if isinstance(answer, tuple) else [answer]
    try:
        channel.set_probe_salt(1111)
        assert part.check(answer, quiet=True).passed              # recorded on last run's inputs
        for t in tapes:
            t.replay = True
        assert part.check(answer, quiet=True).passed              # the tape fools a fixed input
        for t in tapes:
            t.i = 0
        channel.set_probe_salt(2222)
        v = part.check(answer, quiet=True)
        assert not v.passed, (part_id, v.message)                 # ... but not this run's
        assert part.check(part.reference, quiet=True).passed      # the honest answer still passes
    finally:
        channel.set_probe_salt(None)
    plain = [str(p) for p in part.probes()]
    assert len(plain) == len(part.probes())


def test_unsimplified_products_are_evaluated_at_a_salted_point(clean):
    import sympy as sp
    x, t = sp.symbols("x theta", real=True)
    left = sp.Matrix([[sp.cos(t), -sp.sin(t), 0], [sp.sin(t), sp.cos(t), 0], [0, 0, 1]])
    right_unsimplified = (left.T * left).applyfunc(lambda e: sp.expand(e))
    v = REGISTRY["1.3"].parts["c"].check((x / x, 1, right_unsimplified, sp.eye(3)), quiet=True)
    if right_unsimplified.free_symbols:
        assert not v.passed and "only the simplification is missing" in v.message, v.message
    v = REGISTRY["1.3"].parts["c"].check((1, 1, left * left, sp.eye(3)), quiet=True)
    assert not v.passed and "is not the identity" in v.message, v.message
    assert REGISTRY["1.3"].parts["c"].check((1, 1, sp.eye(3), sp.eye(3)), quiet=True).passed


def test_strict_returns_none_on_success_and_raises_on_failure(clean):
    assert ex1_1.a.check("b", strict=True, quiet=True) is None
    with pytest.raises(AssertionError, match="exercise 1.1a"):
        ex1_1.a.check("a", strict=True, quiet=True)
    assert ex1_1.a.check("b", quiet=True).passed                 # the default still returns a Verdict


def test_the_cell_clock_credits_checks_only_as_long_as_an_honest_one_takes():
    from gm_grader.clock import CELL_BUDGET, CellClock, check_caps
    caps = check_caps(REGISTRY["1.2"], 5.0)
    cap = caps["1.2/a"]
    assert set(caps) == {"1.2/a", "1.2/b", "1.2/c"} and cap >= 5.0 * len(ex1_2.a.probes())
    clock = CellClock(caps)
    clock.restart(100.0)
    clock.begin("1.2/a", 101.0)
    clock.end(104.0)                                    # a real check: 3 s not counted
    assert clock.seconds(110.0) == pytest.approx(7.0)
    clock.begin("9.9/z", 110.0)                         # a part this notebook does not grade
    assert clock.seconds(120.0) == pytest.approx(17.0)
    clock.begin("1.2/a", 120.0)                         # announced, never ended: capped
    assert clock.seconds(120.0 + cap + 30) == pytest.approx(17.0 + 30)
    clock.restart(0.0)
    for k in range(100):                                # announced again and again: the budget
        clock.begin("1.2/b", k * 1000.0)
        clock.end(k * 1000.0 + 999.0)
    assert clock.credited(1e6) == pytest.approx(CELL_BUDGET * sum(caps.values()))


@pytest.mark.skipif(not CGROUPS, reason="no writable pids and memory cgroups here")
def test_cgroups_of_a_sandbox_end_every_process_and_a_dead_graders_are_removed():
    from gm_grader.isolate import _Cgroups
    gone = subprocess.Popen(["true"])
    gone.wait()
    stale = [Path(base) / f"gm-grade-{gone.pid}-dead" for _, base in _own_cgroup_dirs().values()]
    for d in stale:
        d.mkdir()
    cg = _Cgroups(Limits(processes=16), f"gm-grade-{os.getpid()}-{uuid.uuid4().hex[:6]}")
    try:
        assert sorted(cg.kinds) == ["memory", "pids"] and not any(d.exists() for d in stale)
        pids = next(d for d in cg.dirs if "pids" in str(d))
        assert (pids / "pids.max").read_text().strip() == "16"
        daemon = subprocess.Popen(["sh", "-c", f"echo $$ > {pids}/cgroup.procs; setsid sleep 60 & "
                                   "sleep 60"])
        deadline = time.monotonic() + 10
        while len(cg.pids()) < 2 and time.monotonic() < deadline:
            time.sleep(0.05)
        assert len(cg.pids()) >= 2                       # the shell and its setsid'd sleep
    finally:
        cg.close()
    daemon.wait(timeout=10)
    assert not any(d.exists() for d in cg.dirs)          # every process ended, the cgroups gone


def test_the_report_says_when_no_cgroup_could_be_made():
    from gm_grader.batch import _limits_note
    assert _limits_note([("memory", "pids")], True) is None
    note = _limits_note([(), ("memory", "pids")], True)
    assert "no memory or pids cgroup" in note and "pid namespace" in note and "README" in note
    assert "outlived" in _limits_note([("memory",)], False)


def test_results_are_written_atomically(tmp_path):
    rows = [{"notebook": "ex1_4.ipynb", "exercise": "1.4", "part": "a", "status": "passed",
             "score": 3.0, "max_score": 3.0, "message": "ok"}]
    res = _report.write(rows, tmp_path, visibility="after_published")
    assert res["score"] == 3.0 and res["tests"][0]["visibility"] == "after_published"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["grades.csv", "results.json"]
    with pytest.raises(ValueError, match="visibility"):
        _report.write(rows, tmp_path, visibility="later")
    assert ex1_1.a.weight == 1.0 and REGISTRY["1.4"].parts["a"].weight == 2.0


def test_every_way_a_run_ends_gives_every_part_a_row_and_a_reason():
    ex = REGISTRY["1.2"]
    good = evidence_line([{"k": "ok", "v": {"__nd__": [2], "d": list(map(float, ex.parts["a"].ref(*a)))}}
                          for a in ex.parts["a"].inputs()])
    base = [Started(), EvidenceLine(cell=1, line=good), CellEnded(index=1, status=CellStatus.OK)]
    endings = {"killed by the notebook limit": ([], Killed.TIME, "longer than the time allowed"),
               "kernel died": ([CellStarted(index=2), CellEnded(index=2, status=CellStatus.DIED)],
                               None, "kernel stopped in cell 3"),
               "cell limit, then killed": ([CellEnded(index=2, status=CellStatus.TIMEOUT)], None,
                                           "after it exceeded the cell limit"),
               "runner killed": ([CellStarted(index=2)], None, "ended its own grading in cell 3"),
               "runner killed between cells": ([], None, "ended its own grading"),
               "unreadable": ([Fatal(message="the notebook could not be read (ValueError)")], None,
                              "could not be read"),
               "finished": ([Done()], None, "")}
    for what, (tail, killed, phrase) in endings.items():
        run = RunResult(records=(*base, *tail), nonce="s", salt=0, killed=killed)
        summary = _evidence.summarise(run, ex, {1: "ex1_2.a.check(f)", 2: "boom()"})
        problem, verdicts = summary.problem, summary.parts
        assert set(verdicts) == {"a", "b", "c"}, what
        assert verdicts["a"].verdict.passed and verdicts["a"].cell == 1, what   # checked before: kept
        assert phrase in problem if phrase else problem == "", (what, problem)
        for name in "bc":
            v = verdicts[name].verdict
            assert not v.passed and (phrase in v.message if phrase else "no check" in v.message), (what, v)


def test_a_part_is_decided_by_the_graders_calls_and_says_why_when_they_give_nothing():
    ex = REGISTRY["1.2"]
    part = ex.parts["a"]
    right = [{"k": "ok", "v": {"__nd__": [2], "d": list(map(float, part.ref(*a)))}}
             for a in part.inputs()]
    wrong = [{"k": "ok", "v": {"__nd__": [2], "d": [9.0, 9.0]}} for _ in part.inputs()]
    carried = base64.b64encode(b"an answer").decode()

    def run_of(*lines, done=True):
        recs = [Started(), *(EvidenceLine(cell=1, line=ln) for ln in lines),
                CellEnded(index=1, status=CellStatus.OK)]
        return RunResult(records=(*recs, *([Done()] if done else [])), nonce="s", salt=0)

    sources = {1: "ex1_2.a.check(f)"}
    notebook = _evidence.summarise(run_of(evidence_line(right, answer=carried),
                                          evidence_line(right, name="b", unsent="a lock")), ex, sources)
    assert notebook.parts["a"].verdict.passed          # its own outcomes would have passed ...
    for calls, says in ((run_of(evidence_line(wrong)), "different value"),
                        (run_of(done=False), "did not finish"),
                        (None, "did not finish"),
                        (run_of(evidence_line("stopped", output="could not be rebuilt (X)")),
                         "could not be rebuilt")):
        got = _evidence.decide(ex, notebook, None if calls is None else
                               _evidence.summarise(calls, ex, {}))
        a = got.parts["a"]
        assert not a.verdict.passed and says in a.verdict.message and a.cell == 1, (says, a)
        assert "could not be handed to the grader: a lock" in got.parts["b"].verdict.message
        assert "no check of this part ran" in got.parts["c"].verdict.message
    got = _evidence.decide(ex, notebook, _evidence.summarise(run_of(evidence_line(right)), ex, {}))
    assert got.parts["a"].verdict.passed                # ... and the grader's calls decide
    unjudged = _evidence.summarise(run_of(evidence_line(right, answer=carried),
                                          evidence_line(right, name="b", unsent="a lock")), ex, sources,
                                   judge=False)          # as the grader reads the notebook's run
    def decided(first):
        parts = _evidence.decide(ex, first, _evidence.summarise(run_of(evidence_line(wrong)), ex, {})).parts
        return {n: (r.verdict.status, r.verdict.message, r.cell) for n, r in parts.items()}

    assert decided(unjudged) == decided(notebook)
    assert _evidence.collect(run_of(evidence_line(right, answer=carried)), ex).answers() == {"a": carried}


@needs_sandbox
def test_the_notebook_limit_ends_the_sandbox_and_everything_in_it(tmp_path, monkeypatch):
    import tempfile

    from gm_grader.isolate import run_submission
    nb = write_nb(tmp_path / "ex1_1.ipynb", ["import time\ntime.sleep(10**6)"])
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))   # bwrap's command line names it
    t = time.monotonic()
    run = run_submission(nb, limits=Limits(notebook_timeout=2.0))
    assert run.killed is Killed.TIME and time.monotonic() - t < 30
    summary = _evidence.summarise(run, REGISTRY["1.1"], {})
    assert "longer than the time allowed" in summary.problem
    assert not any(r.verdict.passed for r in summary.parts.values())
    assert alive_with(str(tmp_path)) == []          # bwrap (its command line names tmp_path) is gone


def _in_sandbox(script, course=None, tmp=None):
    """Run a shell script in a sandbox laid out as for a notebook (gm_grader.view)."""
    import tempfile

    from gm_grader import view
    private = Path(tempfile.mkdtemp(dir=tmp))
    inbox = view.make_inbox(private)
    ident = view.sandbox_identity()
    etc = view.write_identity_files(private / "etc", ident)
    cmd = view.command(inbox, etc, ident, Limits(), ["/bin/sh", "-c", script],
                       **({"course": course} if course else {}))
    return subprocess.run(cmd, capture_output=True, text=True, env={"PATH": "/usr/bin:/bin"})


@needs_sandbox
def test_a_sandbox_sees_the_course_not_what_lies_beside_it():
    """A sandbox sees the course's packages, never the folder around them (solutions/, a grading
    folder beside them) nor a folder elsewhere: it was never put there. The answer keys' folder
    is there, empty (the graded build)."""
    import shutil
    import tempfile
    base = Path(tempfile.mkdtemp(prefix="gm-hide-", dir="/var/tmp"))
    try:
        (base / "bob").mkdir()
        (base / "bob" / "ex1_1.ipynb").write_text("secret")
        res = _in_sandbox(f"cat {base}/bob/ex1_1.ipynb; ls {ROOT}; ls {ROOT}/gm_core/checks; "
                          f"echo keys:; ls -A {ROOT}/gm_core/checks/keys; echo :keys")
        assert "secret" not in res.stdout and "No such file" in res.stderr
        assert "parts.py" in res.stdout                             # the course's code is there
        assert "solutions" not in res.stdout and "gm_core" in res.stdout
        assert "keys:\n:keys" in res.stdout                         # the graded build: no keys
    finally:
        shutil.rmtree(base)


@needs_sandbox
def test_a_course_cloned_under_tmp_stays_visible_and_its_notebooks_do_not(tmp_path):
    """The sandbox's empty /tmp must not hide a course (or venv) that lives under /tmp, as a CI
    clone may; what lies beside its packages stays out of sight."""
    course = (tmp_path / "course").resolve()
    (course / "solutions").mkdir(parents=True)
    (course / "solutions" / "ex1_1.ipynb").write_text("secret")
    (course / "gm_core").mkdir()
    (course / "gm_core" / "mark.py").write_text("")
    res = _in_sandbox(f"ls {course} {course}/gm_core; cat {course}/solutions/ex1_1.ipynb",
                      course=course, tmp=tmp_path)
    assert "gm_core" in res.stdout and "mark.py" in res.stdout
    assert "solutions" not in res.stdout and "secret" not in res.stdout


def test_the_runner_reads_notebooks_without_compiling_the_iri_grammar():
    """The runner process of every graded notebook imports nbformat without rfc3987_syntax's Lark
    grammar (1-2 s of CPU each), and still reads and validates a notebook."""
    code = ("import sys\n"
            "from gm_grader import runner\n"
            "runner._without_iri_grammar()\n"
            "import nbformat\n"
            "nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell('x = 1')])\n"
            "nbformat.validate(nbformat.reads(nbformat.writes(nb), as_version=4))\n"
            "print(sorted(m for m in ('lark', 'rfc3987_syntax') if sys.modules.get(m) is not None))\n")
    res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr[-2000:]
    assert res.stdout.strip() == "[]", res.stdout


# ------------------------------------------------------------------ the protocol, encoded and decoded
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from gm_core.checks import protocol as P  # noqa: E402

_text = st.text(max_size=40)
_nd = st.lists(st.integers(0, 3), max_size=3).flatmap(
    lambda shape: st.lists(st.floats(allow_nan=False, width=32) | st.integers(-9, 9),
                           min_size=int(np.prod(shape)), max_size=int(np.prod(shape))).map(
        lambda d: {"__nd__": shape, "d": d}))
_plain = st.recursive(
    st.none() | st.booleans() | st.integers(-2**40, 2**40) | st.floats(allow_nan=False) | _text | _nd,
    lambda inner: st.lists(inner, max_size=3)
    | st.lists(st.tuples(_text, inner).map(list), max_size=3).map(lambda kv: {"__dict__": kv}),
    max_leaves=12)


@st.composite
def outcomes(draw):
    kind = draw(st.sampled_from(P.OutcomeKind))
    if kind is P.OutcomeKind.OK:
        return P.Outcome(kind, draw(_plain))
    detail = "" if kind in (P.OutcomeKind.WRONG, P.OutcomeKind.UNATTEMPTED) else draw(_text)
    return P.Outcome(kind, None, draw(_text), detail)


_cell = st.none() | st.integers(-1, 10**6)
_at = st.floats(0, 1e5).map(lambda x: round(x, 2))
records = st.one_of(
    st.builds(P.Started, at=_at), st.builds(P.Done, at=_at),
    st.builds(P.KernelStarted, at=_at, pid=st.none() | st.integers(1, 2**22)),
    st.builds(P.CellStarted, at=_at, index=st.integers(0, 10**4)),
    st.builds(P.CellEnded, at=_at, index=st.integers(0, 10**4), status=st.sampled_from(P.CellStatus),
              error=_text, seconds=st.floats(0, 1e4)),
    st.builds(P.CheckAnnounced, at=_at, cell=_cell, part=st.text(max_size=P.MAX_PART_KEY)),
    st.builds(P.EvidenceLine, at=_at, cell=_cell, line=st.text(max_size=200)),
    st.builds(P.OutputSize, at=_at, size=st.integers(0, 2**40)),
    st.builds(P.Flooded, at=_at, message=_text), st.builds(P.Fatal, at=_at, message=_text))


@settings(max_examples=150, deadline=None)
@given(outcomes())
def test_an_outcome_survives_its_codec(o):
    wire = json.loads(json.dumps(P.encode_outcome(o)))
    assert P.decode_outcome(wire) == o
    from gm_core.checks.sandbox import decode_outcome
    assert decode_outcome(wire)["k"] == o.kind.value          # the form the checkers' judges read


@settings(max_examples=100, deadline=None)
@given(st.lists(outcomes(), max_size=4), _text, st.sampled_from([None, *P.Withheld]),
       st.binary(max_size=64), st.text(max_size=P.MAX_UNSENT))
def test_evidence_and_announcements_survive_their_codec(outs, output, withheld, answer, unsent):
    got = withheld if withheld is not None else tuple(outs)
    ev = P.Evidence("n" * 32, "1.2", "a", got, output, base64.b64encode(answer).decode(), unsent)
    line = P.encode_kernel_message(ev)
    assert line.endswith(b"\n") and line.count(b"\n") == 1
    assert P.decode_evidence(line, nonce="n" * 32, exercise="1.2", probes={"a": len(outs)}) == ev
    for spaced in (json.dumps(json.loads(line)), json.dumps(json.loads(line), indent=None,
                                                             separators=(" , ", " : "))):
        assert P.decode_evidence(spaced, nonce="n" * 32, exercise="1.2", probes={"a": len(outs)}) == ev
    assert P.decode_check_begun(P.encode_kernel_message(P.CheckBegun("1.2/a"))) == P.CheckBegun("1.2/a")
    with pytest.raises(P.ProtocolError):
        P.decode_check_begun(line)                            # evidence is no announcement


@settings(max_examples=200, deadline=None)
@given(records)
def test_a_runner_record_survives_its_codec_however_json_is_spaced(rec):
    line = P.encode_record(rec)
    assert P.decode_record(line) == rec
    data = json.loads(line)
    assert P.decode_record(json.dumps(data, indent=2, sort_keys=True)) == rec   # no byte prefixes
    assert P.decode_record(json.dumps(data, separators=(",", ":"))) == rec


@settings(max_examples=200, deadline=None)
@given(records, st.data())
def test_a_malformed_runner_record_is_rejected(rec, data):
    wire = json.loads(P.encode_record(rec))
    how = data.draw(st.sampled_from(["extra", "missing", "kind", "type", "bool", "list"]))
    if how == "extra":
        wire[data.draw(st.text(min_size=1, max_size=5).filter(lambda k: k not in wire))] = 1
    elif how == "missing":
        del wire[data.draw(st.sampled_from(sorted(wire)))]
    elif how == "kind":
        wire["kind"] = data.draw(st.text(max_size=8).filter(lambda k: k not in {r.value for r in P.RecordKind})
                                 | st.integers() | st.none())
    elif how == "type":
        key = data.draw(st.sampled_from(sorted(set(wire) - {"kind"})))
        wire[key] = data.draw(st.sampled_from([[1], {"a": 1}] + (["1" * 3000] if key != "line" else [])))
    elif how == "bool":
        key = data.draw(st.sampled_from(sorted(set(wire) - {"kind"})))
        if isinstance(wire[key], str) or wire[key] is None:
            wire[key] = [wire[key]]
        else:
            wire[key] = True
    else:
        wire = [wire]
    with pytest.raises(P.ProtocolError):
        P.decode_record(json.dumps(wire))


@settings(max_examples=200, deadline=None)
@given(st.binary(max_size=300) | st.recursive(st.none() | st.booleans() | st.integers() | _text,
                                               lambda i: st.lists(i) | st.dictionaries(_text, i),
                                               max_leaves=10).map(lambda v: json.dumps(v).encode()))
def test_junk_is_rejected_with_a_reason_never_a_crash(line):
    for decode in (P.decode_record, P.decode_check_begun,
                   lambda x: P.decode_evidence(x, nonce="s", exercise="1.2", probes={"a": 1})):
        try:
            decode(line)
        except P.ProtocolError as exc:
            assert str(exc)
    try:
        data = json.loads(line)
    except ValueError:
        return
    try:
        P.decode_outcome(data)
    except P.ProtocolError as exc:
        assert str(exc)


def test_malformed_evidence_is_rejected_for_the_reason_the_report_gives():
    ok = [{"k": "ok", "v": 1.0}]
    cases = {"an over-long or missing record": "x" * (P.MAX_EVIDENCE_LINE + 1),
             "a record that is not valid JSON (or nested too deeply)": "[" * 100000,
             "a record of the wrong form": evidence_line(ok, extra=1),
             "a record without this run's secret": evidence_line(ok, nonce="t"),
             "a record for a part this exercise does not have": evidence_line(ok, name="b"),
             "a record for part a with the wrong number of outcomes": evidence_line(ok * 2),
             "a record for part a with malformed outcomes": evidence_line([{"k": "ok", "v": 1, "m": ""}]),
             "a record for part a with a malformed answer": evidence_line(ok, answer="{not base64}")}
    for why, line in cases.items():
        with pytest.raises(P.ProtocolError, match=re.escape(why)):
            P.decode_evidence(line, nonce="s", exercise="1.2", probes={"a": 1})
    for bad in ({"k": "ok"}, {"k": "ok", "v": "t" * 601}, {"k": "wrong", "m": "", "x": ""},
                {"k": "error", "m": 1}, {"k": "ok", "v": {"__nd__": [2], "d": [1, True]}},
                {"k": "ok", "v": {"__nd__": [-1], "d": []}}, {"k": "ok", "v": {"a": 1}},
                {"k": "ok", "v": [[[[[[[[[[[[[[1]]]]]]]]]]]]]]}, {"k": ["ok"]}, ["ok"]):
        with pytest.raises(P.ProtocolError):
            P.decode_outcome(bad)


def test_the_runner_configuration_survives_its_codec():
    cfg = P.RunnerConfig("/tmp/.gm-in/submission.ipynb", "/tmp/work", 7, "ab" * 16, 2**61 + 3,
                         P.Limits(cell_timeout=4, memory_mb=2048), {"1.2/a": 40.5}, None)
    assert P.decode_config(P.encode_config(cfg)) == cfg
    assert P.Limits(cell_timeout=4).cell_timeout == 4.0 and isinstance(P.Limits().memory_mb, int)
    for broken in ("{}", P.encode_config(cfg).replace('"evidence_fd": 7', '"evidence_fd": "7"')):
        with pytest.raises(P.ProtocolError):
            P.decode_config(broken)

"""Progress that lasts (issue #14, point 4): four states, saved in the workspace across kernels
and restarts, in memory elsewhere, a reset; and exercises come from a registry."""
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from gm_core import checks
from gm_core.checks import store
from gm_core.checks.answer_key import FunctionKey, provide
from gm_core.checks.exercise import REGISTRY, Exercise, exercise_ids, progress, reset_progress
from gm_core.checks.parts import FunctionPart
from gm_core.checks.store import FAILED, IN_PROGRESS, PASSED, UNATTEMPTED

ROOT = Path(__file__).resolve().parent.parent
pytestmark = pytest.mark.usefixtures("clean")


@pytest.fixture
def workspace(tmp_path, monkeypatch):
    ws = tmp_path / "workspace"
    (ws / "sub").mkdir(parents=True)
    (ws / ".course-manifest.json").write_text('{"version": 2, "files": {}, "beside": {}}')
    monkeypatch.chdir(ws / "sub")          # a kernel running anywhere inside the workspace
    yield ws
    reset_progress()


def kernel(cwd, code):
    """A fresh Python process (a new kernel) running ``code`` in ``cwd``; returns its stdout."""
    env = dict(os.environ, PYTHONPATH=str(ROOT), GM_CHECKS_NO_FORK="")
    env.pop("GM_COURSE_WORKSPACE", None)
    res = subprocess.run([sys.executable, "-c", code], cwd=cwd, env=env, capture_output=True,
                         text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    return res.stdout


def test_four_states():
    ex = checks.ex1_2
    assert progress()["1.2"] == UNATTEMPTED
    ex.a.check(ex.a.reference, quiet=True)
    assert progress()["1.2"] == IN_PROGRESS
    ex.b.check(ex.b.wrong[0], quiet=True)
    assert progress()["1.2"] == FAILED
    for p in ex.parts.values():
        p.check(p.reference, quiet=True)
    assert progress()["1.2"] == PASSED
    ex.a.check(None, quiet=True)                     # re-running an untouched cell
    assert progress()["1.2"] == PASSED


def test_progress_is_saved_in_the_workspace_across_kernels(workspace):
    code = ("from gm_core.checks import ex1_1, ex3_1, progress\n"
            "ex1_1.a.check('b', quiet=True); ex1_1.b.check('{b}', quiet=True)\n"
            "ex3_1.a.check(ex3_1.a.reference, quiet=True)\n")
    kernel(workspace, code.replace("{b}", ex_b_letter()))
    saved = json.loads((workspace / ".progress.json").read_text())
    assert saved["1.1/a"]["status"] == PASSED
    out = kernel(workspace / "sub", "from gm_core.checks import progress; print(dict(progress()))")
    status = eval(out)
    assert status["1.1"] == PASSED and status["3.1"] == IN_PROGRESS
    assert list(status) == list(exercise_ids()) and len(status) >= 13
    assert progress()["1.1"] == PASSED               # this process sees it too


def ex_b_letter():
    return sorted(checks.ex1_1.b.key.correct)[0]


def test_outside_a_workspace_progress_stays_in_memory(tmp_path):
    out = kernel(tmp_path, "from gm_core.checks import ex1_1, progress\n"
                           "ex1_1.a.check('b', quiet=True); print(progress()['1.1'])")
    assert out.strip() == IN_PROGRESS
    assert not list(tmp_path.rglob(".progress.json"))
    assert kernel(tmp_path, "from gm_core.checks import progress; print(progress()['1.1'])").strip() == UNATTEMPTED


def test_reset_clears_the_saved_record(workspace):
    checks.ex1_1.a.check("b", quiet=True)
    assert progress()["1.1"] == IN_PROGRESS
    reset_progress()
    assert progress()["1.1"] == UNATTEMPTED
    assert json.loads((workspace / ".progress.json").read_text()) == {}


def test_progress_file_is_written_atomically_and_survives_garbage(workspace):
    (workspace / ".progress.json").write_text("{garbage")
    assert progress()["1.1"] == UNATTEMPTED          # unreadable record: no crash
    checks.ex1_1.a.check("b", quiet=True)
    assert json.loads((workspace / ".progress.json").read_text())["1.1/a"]["status"] == PASSED
    assert not [p for p in workspace.iterdir() if p.name.endswith(".tmp")]


def test_solution_views_are_recorded(workspace, capsys):
    checks.ex2_2.b.solution()
    assert checks.solutions_viewed() == {"2.2": ["b"]}
    assert "../solutions/ex2_2.ipynb" in capsys.readouterr().out
    html = checks.progress_widget().view.value
    assert "solution viewed: b" in html and "saved in your workspace" in html


def test_progress_shows_a_table_never_a_raw_dict(workspace):
    """progress() is still a dict to a program, and a small table to the student: plain text
    (a terminal, print, repr) and HTML in Jupyter, one row per exercise with its status in words,
    its parts passed and the solutions viewed, and where the record is kept."""
    from IPython.lib.pretty import pretty

    checks.ex1_2.a.check(checks.ex1_2.a.reference, quiet=True)
    checks.ex1_1.a.check("a", quiet=True)
    checks.ex3_2.b.solution()
    status = progress()
    assert isinstance(status, dict) and status["1.2"] == IN_PROGRESS and status["1.1"] == FAILED
    assert dict(status) == {i: REGISTRY[i].status() for i in exercise_ids()}
    assert json.loads(json.dumps(status)) == dict(status)
    text = repr(status)
    assert text == str(status) == pretty(status)
    assert "{" not in text and "'" not in text, text
    lines = text.splitlines()
    assert lines[0] == "Your progress (saved in your workspace):"
    assert lines[1].split() == ["exercise", "status", "parts", "passed"]
    rows = {line.split()[0]: line for line in lines[2:]}
    assert list(rows) == list(exercise_ids())
    assert rows["1.2"].split() == ["1.2", "in", "progress", "1", "of", "3"]
    assert rows["1.1"].split() == ["1.1", "failed", "0", "of", "2"]
    assert rows["3.2"].split() == ["3.2", "unattempted", "0", "of", "2", "solution", "viewed:", "b"]
    html = status._repr_html_()
    assert html.startswith("<table") and html.count("<tr>") == len(exercise_ids()) + 1
    row = re.search(r"<tr><td>1\.2</td>(.*?)</tr>", html).group(1)
    assert "in progress" in row and "1 of 3" in row
    assert "solution viewed: b" in html and "saved in your workspace" in html


def test_the_progress_table_of_a_kernel_outside_a_workspace_says_so():
    checks.ex2_4.a.check(checks.ex2_4.a.reference, quiet=True)
    text = str(progress())
    assert text.startswith("Your progress (this kernel only, not in a workspace):")
    assert re.search(r"^  2\.4 +passed +1 of 1$", text, re.M), text


def test_progress_widget_and_start_page_list_pending_updates_once(workspace, capsys):
    (workspace / "ex1_4.course-update.ipynb").write_text("{}")
    (workspace / ".course-notices.json").write_text(json.dumps(
        [{"file": "ex1_4.ipynb", "new_version": "ex1_4.course-update.ipynb", "seen": False}]))
    box = checks.progress_widget()
    assert "ex1_4.course-update.ipynb" in box.view.value
    box.refresh()
    assert "course-update" not in box.view.value       # shown once
    checks.course_updates()
    assert "No course updates" in capsys.readouterr().out


def test_old_notebook_calling_a_renamed_or_removed_part_gets_a_friendly_message(capsys):
    ex = REGISTRY["1.4"]
    ex.renamed.update(d_speed=None, old_a="a")       # a removed part and a renamed one
    try:
        checks.ex1_4.d_speed.check(lambda: 1)
        checks.ex1_4.d_speed.hint()
        out = capsys.readouterr().out
        assert "no part 'd_speed'" in out and "course was updated" in out
        assert ex.old_a is ex.a
    finally:
        del ex.renamed["d_speed"], ex.renamed["old_a"]
    assert not hasattr(ex, "d_speed") and not hasattr(ex, "no_such_thing")


def test_a_typo_is_an_attribute_error_naming_the_parts():
    with pytest.raises(AttributeError, match=r"no part or attribute 'e'; its parts are a, b, c, d"):
        checks.ex1_4.e.check(lambda xi: xi)
    assert hasattr(checks.ex1_4, "a") and hasattr(checks.ex1_5, "slide_rule")


def test_a_new_exercise_module_only_needs_to_register():
    import numpy as np
    try:
        ex = Exercise("9.1", "test exercise", [FunctionPart(
            "a", "double it", inputs=lambda: [(1.0,), (2.5,)], arg_names=("t",), shape=())])
        provide(ex, a=FunctionKey(ref=lambda t: 2 * t))
        assert "9.1" in exercise_ids() and checks.ex9_1.a.check(lambda t: 2 * t, quiet=True).passed
        assert progress()["9.1"] == IN_PROGRESS or progress()["9.1"] == PASSED
        assert "9.1" in checks.EXERCISE_IDS
        assert np.isfinite(1.0)
    finally:
        REGISTRY.pop("9.1", None)


def test_every_exercise_comes_from_a_declared_module():
    import sys

    from gm_core.checks import EXERCISE_MODULES

    assert EXERCISE_MODULES == ("ex1", "ex2", "ex3", "ex4", "ex5")
    declared = [sys.modules[f"gm_core.checks.{m}"] for m in EXERCISE_MODULES]
    where = {eid: [m.__name__ for m in declared if any(v is ex for v in vars(m).values())]
             for eid, ex in REGISTRY.items()}
    assert len(where) >= 16 and all(len(w) == 1 for w in where.values()), where


# ------------------------------------------------------------------------------ never lost (issue 20, point 6)
def _start_together(cwd, code, n, timeout=240):
    """Start ``n`` real Python processes running ``code`` (with WORKER = 0..n-1) and release them
    at the same instant; returns their stdouts."""
    go = Path(cwd) / "go"
    go.unlink(missing_ok=True)
    env = dict(os.environ, PYTHONPATH=str(ROOT), GM_CHECKS_NO_FORK="")
    env.pop("GM_COURSE_WORKSPACE", None)
    ready = [Path(cwd) / f"ready-{w}" for w in range(n)]
    for r in ready:
        r.unlink(missing_ok=True)
    prelude = ("import os, time, sys\nWORKER = int(sys.argv[1])\n"
               f"open({str(cwd)!r} + '/ready-%d' % WORKER, 'w').close()\n"
               f"while not os.path.exists({str(go)!r}): time.sleep(0.005)\n")
    procs = [subprocess.Popen([sys.executable, "-c", prelude + code, str(w)], cwd=cwd, env=env,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for w in range(n)]
    import time
    deadline = time.monotonic() + 60
    while not all(r.exists() for r in ready):        # every process is waiting at the barrier
        assert time.monotonic() < deadline and all(p.poll() is None for p in procs), \
            [p.communicate()[1] for p in procs if p.poll() is not None]
        time.sleep(0.01)
    for r in ready:
        r.unlink()
    go.write_text("go")
    outs = []
    for p in procs:
        out, err = p.communicate(timeout=timeout)
        assert p.returncode == 0, err
        outs.append(out)
    return outs


@pytest.mark.slow
@pytest.mark.parametrize("locks", ["filelock", "filelock and bare flock"])
def test_concurrent_kernels_marking_parts_lose_no_update(workspace, locks):
    """The reproducer: processes marking parts in a loop lost 121-185 of 400 updates. Kernels
    without filelock (a bare `pip install .`) take the same lock."""
    n, per = 3, 100
    block = "if WORKER == 1: sys.modules['filelock'] = None\n" if "bare" in locks else ""
    code = (block + "from gm_core.checks import store\n"
            f"for i in range({per}):\n"
            "    store.record('9.%d' % WORKER, 'p%d' % i, 'passed')\n")
    _start_together(workspace / "sub", code, n)
    saved = json.loads((workspace / ".progress.json").read_text())
    missing = [f"9.{w}/p{i}" for w in range(n) for i in range(per) if f"9.{w}/p{i}" not in saved]
    assert not missing, f"{len(missing)} of {n * per} updates lost"
    assert not [p for p in workspace.iterdir() if p.name.endswith(".tmp")]


@pytest.mark.slow
def test_two_kernels_checking_at_the_same_moment_lose_no_pass(workspace):
    """Two real check() calls at once, part after part: every pass of both kernels is kept."""
    code = ("from gm_core.checks.exercise import REGISTRY\n"
            "from gm_core.checks import exercise_ids\n"
            "parts = [(e, p) for e in exercise_ids() for p in REGISTRY[e].parts.values()]\n"
            "for k, (e, p) in enumerate(parts):\n"
            "    if k % 2 == WORKER:\n"
            "        assert p.check(p.reference, quiet=True).passed, (e, p.name)\n")
    _start_together(workspace / "sub", code, 2)
    from gm_core.checks.exercise import REGISTRY
    expected = {f"{e}/{p}" for e in exercise_ids() for p in REGISTRY[e].parts}
    saved = json.loads((workspace / ".progress.json").read_text())
    assert {k for k, r in saved.items() if r["status"] == PASSED} == expected
    assert set(progress().values()) == {PASSED}


GOOD = {"1.1/a": {"status": "passed", "solution_viewed": False, "when": 1.0},
        "1.2/b": {"status": "failed", "solution_viewed": True, "when": 2.0}}
DAMAGE = {
    "truncated": json.dumps(dict(GOOD, **{"3.1/a": GOOD["1.1/a"]})).encode()[:-30],
    "utf-16": json.dumps(GOOD).encode("utf-16"),
    "utf-16 without BOM": json.dumps(GOOD).encode("utf-16-le"),
    "latin-1 bytes": json.dumps(dict(GOOD, **{"1.3/a": {"status": "passed", "note": "caf\u00e9"}}),
                                ensure_ascii=False).encode("latin-1"),
    "list-shaped": json.dumps([{"1.1/a": GOOD["1.1/a"]}, {"1.2/b": GOOD["1.2/b"]}]).encode(),
    "entries that are no records": json.dumps(dict(GOOD, **{"1.3/a": "passed", "x": {}})).encode(),
    "deeply nested": b"[" * 100000,
    "binary garbage": bytes(range(256)) * 4,
}


@pytest.mark.parametrize("damage", list(DAMAGE))
def test_a_damaged_file_is_kept_aside_its_readable_entries_kept_and_the_student_told(
        workspace, damage, capsys):
    raw = DAMAGE[damage]
    (workspace / ".progress.json").write_bytes(raw)
    v = checks.ex3_1.a.check(checks.ex3_1.a.reference, quiet=True)
    assert v.passed
    aside = list(workspace.glob(".progress.json.damaged-*"))
    assert len(aside) == 1 and aside[0].read_bytes() == raw          # kept, byte for byte
    saved = json.loads((workspace / ".progress.json").read_text(encoding="utf-8"))
    assert saved["3.1/a"]["status"] == PASSED
    salvageable = {"deeply nested": set(), "binary garbage": set()}.get(damage, set(GOOD))
    assert salvageable <= set(saved)
    for key in salvageable:
        assert saved[key]["status"] == GOOD[key]["status"]
    if damage == "latin-1 bytes":
        assert saved["1.3/a"]["status"] == PASSED
    out = capsys.readouterr().out
    assert out.count("Note about your progress record") == 1 and "was damaged" in out
    assert aside[0].name in out and "Traceback" not in out
    checks.ex3_1.a.check(checks.ex3_1.a.reference, quiet=True)
    progress()
    assert "damaged" not in capsys.readouterr().out                    # told once
    assert len(list(workspace.glob(".progress.json.damaged-*"))) == 1


def test_progress_reads_a_damaged_file_without_losing_it(workspace, capsys):
    raw = DAMAGE["truncated"]
    (workspace / ".progress.json").write_bytes(raw)
    assert progress()["1.1"] == IN_PROGRESS                              # salvaged 1.1/a
    [aside] = workspace.glob(".progress.json.damaged-*")
    assert aside.read_bytes() == raw and "damaged" in capsys.readouterr().out


def test_bad_fields_are_tolerated_and_never_raise_out_of_check(workspace, capsys):
    (workspace / ".progress.json").write_text(json.dumps({
        "1.1/a": {"status": "passed", "when": "yesterday", "solution_viewed": "yes"},
        "1.1/b": {"status": "failed", "when": None},
        "2.2/b": {"status": "unattempted", "when": float("inf"), "solution_viewed": 1}}))
    v = checks.ex1_1.b.check(ex_b_letter(), quiet=True)
    assert v.passed
    assert progress()["1.1"] == PASSED
    assert checks.solutions_viewed() == {"1.1": ["a"], "2.2": ["b"]}
    saved = json.loads((workspace / ".progress.json").read_text())
    assert saved["1.1/a"]["status"] == PASSED and isinstance(saved["1.1/a"]["when"], float)
    assert not list(workspace.glob(".progress.json.damaged-*"))       # nothing was lost
    assert "Traceback" not in capsys.readouterr().out


@pytest.fixture
def read_only(workspace):
    """``read_only(True)`` makes the workspace folder really unwritable (chattr +i as root, since
    chmod does not stop root; chmod elsewhere), ``read_only(False)`` writable again."""
    def switch(on):
        if os.geteuid() == 0:
            res = subprocess.run(["chattr", "+i" if on else "-i", str(workspace)], capture_output=True)
            if on and res.returncode:
                pytest.skip("chattr +i is not supported here")
        else:
            workspace.chmod(0o555 if on else 0o755)
        if on:
            try:
                (workspace / "probe").write_text("x")
            except OSError:
                return
            switch(False)
            pytest.skip("cannot make a read-only folder here")
    yield switch
    switch(False)


def test_an_unwritable_workspace_warns_once_keeps_progress_in_memory_and_saves_it_later(
        workspace, read_only, capsys):
    (workspace / ".progress.json").write_text(json.dumps(GOOD))     # yesterday's record
    read_only(True)
    assert checks.ex3_1.a.check(checks.ex3_1.a.reference, quiet=True).passed
    assert checks.ex3_1.b.check(checks.ex3_1.b.wrong[0], quiet=True).status == FAILED
    out = capsys.readouterr().out
    assert out.count("cannot be saved") == 1 and "kernel's memory" in out
    status = progress()
    assert status["3.1"] == FAILED and status["1.1"] == IN_PROGRESS     # memory + the file
    assert "Not saved" in capsys.readouterr().out
    assert "NOT SAVED" in checks.progress_widget().view.value
    assert json.loads((workspace / ".progress.json").read_text()) == GOOD
    read_only(False)                                                     # writable again
    assert checks.ex1_4.a.check(checks.ex1_4.a.reference, quiet=True).passed
    saved = json.loads((workspace / ".progress.json").read_text())
    assert {k: saved[k]["status"] for k in ("3.1/a", "3.1/b", "1.4/a", "1.1/a")} == {
        "3.1/a": PASSED, "3.1/b": FAILED, "1.4/a": PASSED, "1.1/a": PASSED}
    assert "saved again" in capsys.readouterr().out
    progress()
    assert "Not saved" not in capsys.readouterr().out


def test_a_read_only_mounted_workspace_in_a_real_kernel(workspace, tmp_path):
    """A kernel whose workspace is a read-only mount (bubblewrap): the check still passes, the
    student is told, progress() shows the pass and says it is not saved."""
    import shutil
    if not shutil.which("bwrap"):
        pytest.skip("bubblewrap is not installed")
    (workspace / ".progress.json").write_text(json.dumps(GOOD))
    code = ("from gm_core.checks import ex3_1, progress\n"
            "v = ex3_1.a.check(ex3_1.a.reference, quiet=True)\n"
            "print('VERDICT', v.status)\n"
            "print('PROGRESS', progress()['3.1'], progress()['1.1'])\n")
    env = dict(os.environ, PYTHONPATH=str(ROOT), GM_CHECKS_NO_FORK="")
    env.pop("GM_COURSE_WORKSPACE", None)
    res = subprocess.run(["bwrap", "--bind", "/", "/", "--dev", "/dev", "--proc", "/proc",
                          "--ro-bind", str(workspace), str(workspace), "--chdir", str(workspace / "sub"),
                          sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         timeout=120)
    if res.returncode and "bwrap" in res.stderr:
        pytest.skip(f"bubblewrap cannot run here: {res.stderr[:200]}")
    assert res.returncode == 0, res.stderr
    out = res.stdout
    assert "VERDICT passed" in out and "PROGRESS in progress in progress" in out
    assert out.count("cannot be saved") == 1 and "Not saved" in out and "Read-only" in out
    assert json.loads((workspace / ".progress.json").read_text()) == GOOD   # untouched


@pytest.mark.parametrize("what", ["a folder", "a symlink loop"])
def test_an_unreadable_record_is_moved_aside_and_progress_saved_again(workspace, capsys, what):
    record = workspace / ".progress.json"
    if what == "a folder":
        record.mkdir()
        (record / "inside.txt").write_text("kept")
    else:
        record.symlink_to(record.name)               # reading it fails: too many levels of links
    assert checks.ex3_1.a.check(checks.ex3_1.a.reference, quiet=True).passed
    assert json.loads(record.read_text())["3.1/a"]["status"] == PASSED
    [aside] = workspace.glob(".progress.json.damaged-*")
    if what == "a folder":
        assert (aside / "inside.txt").read_text() == "kept"
    else:
        assert aside.is_symlink()
    out = capsys.readouterr().out
    assert "was damaged" in out and aside.name in out and "Traceback" not in out
    assert progress()["3.1"] == IN_PROGRESS


def test_a_kernel_holding_the_lock_forever_costs_no_verdict(workspace, monkeypatch, capsys):
    from filelock import FileLock

    monkeypatch.setattr(store, "LOCK_TIMEOUT", 0.3)
    holder = subprocess.Popen([sys.executable, "-c",
                               "import sys, time\nfrom filelock import FileLock\n"
                               "l = FileLock(sys.argv[1]); l.acquire(); print('held', flush=True)\n"
                               "time.sleep(60)", str(workspace / ".progress.json.lock")],
                              stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "held"
        assert checks.ex3_1.a.check(checks.ex3_1.a.reference, quiet=True).passed
        assert progress()["3.1"] == IN_PROGRESS
        assert "cannot be saved" in capsys.readouterr().out
    finally:
        holder.kill()
        holder.wait()
    assert FileLock(str(workspace / ".progress.json.lock"), timeout=5).acquire()


def test_a_bookkeeping_error_never_costs_the_verdict(workspace, monkeypatch, capsys):
    """Whatever goes wrong while saving (here: a bug that raises), the check still gives its
    verdict and progress() still shows it."""

    def broken(*a, **k):
        raise RuntimeError("a bug while saving")
    monkeypatch.setattr(store, "write_json_atomic", broken)
    assert checks.ex3_1.a.check(checks.ex3_1.a.reference, quiet=True).passed
    assert progress()["3.1"] == IN_PROGRESS
    assert "Traceback" not in capsys.readouterr().out

"""Progress that lasts (issue #14, point 4): four states, saved in the workspace across kernels
and restarts, in memory elsewhere, a reset; and exercises come from a registry."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from gm_core import checks
from gm_core.checks import (
    FAILED,
    IN_PROGRESS,
    PASSED,
    UNATTEMPTED,
    exercise_ids,
    progress,
    reset_progress,
)
from gm_core.checks._core import REGISTRY, Exercise, FunctionPart

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
    out = kernel(workspace / "sub", "from gm_core.checks import progress; print(progress())")
    status = eval(out)
    assert status["1.1"] == PASSED and status["3.1"] == IN_PROGRESS
    assert list(status) == list(exercise_ids()) and len(status) >= 13
    assert progress()["1.1"] == PASSED               # this process sees it too


def ex_b_letter():
    return sorted(checks.ex1_1.b.correct)[0]


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
        Exercise("9.1", "test exercise", [FunctionPart(
            "a", "double it", ref=lambda t: 2 * t, inputs=lambda: [(1.0,), (2.5,)],
            arg_names=("t",), shape=(), reference=lambda t: 2 * t)])
        assert "9.1" in exercise_ids() and checks.ex9_1.a.check(lambda t: 2 * t, quiet=True).passed
        assert progress()["9.1"] == IN_PROGRESS or progress()["9.1"] == PASSED
        assert "9.1" in checks.EXERCISE_IDS
        assert np.isfinite(1.0)
    finally:
        REGISTRY.pop("9.1", None)


def test_every_exercise_comes_from_a_declared_module():
    import sys

    from gm_core.checks import EXERCISE_MODULES

    assert EXERCISE_MODULES == ("ch1", "ch2", "ch3", "curvature")
    declared = [sys.modules[f"gm_core.checks.{m}"] for m in EXERCISE_MODULES]
    where = {eid: [m.__name__ for m in declared if any(v is ex for v in vars(m).values())]
             for eid, ex in REGISTRY.items()}
    assert len(where) >= 15 and all(len(w) == 1 for w in where.values()), where

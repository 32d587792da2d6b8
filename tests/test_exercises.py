"""exercises/ is generated from solutions/ by tools/make_exercises.py and must stay in sync.

Also: the generator's marker rules, its determinism, and that every untouched exercise notebook
runs without error and leaves its exercise "unattempted" (read from the record of the one
execution of the notebook, which includes progress() at its end: tests/nbrun.py)."""
import importlib.util
import re
import subprocess
import sys
from pathlib import Path

import nbformat
import nbrun
import pytest

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "make_exercises.py"
spec = importlib.util.spec_from_file_location("make_exercises", SCRIPT)
mk = importlib.util.module_from_spec(spec)
spec.loader.exec_module(mk)

SOLUTIONS = sorted((ROOT / "solutions").glob("ex*.ipynb"))
EXERCISES = sorted((ROOT / "exercises").glob("ex*.ipynb"))


def ex_id(path):
    return path.stem[2:].replace("_", ".")


def test_there_is_one_exercise_per_solution():
    assert SOLUTIONS, "no worked solutions found"
    assert [p.name for p in SOLUTIONS] == [p.name for p in EXERCISES]


def test_exercises_are_up_to_date():
    changes = mk.plan(ROOT / "solutions", ROOT / "exercises")
    assert not changes, ("exercises/ is out of date with solutions/: run `make exercises` "
                         f"({', '.join(p.name for p in changes)})")


@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.name)
def test_exercise_has_no_markers_or_outputs(path):
    text = path.read_text(encoding="utf-8")
    for marker in ("BEGIN SOLUTION", "END SOLUTION", "#> ", "solution_only"):
        assert marker not in text, f"{path.name} contains {marker!r}"
    nb = nbformat.read(path, as_version=4)
    assert all(not c.get("outputs") and c.get("execution_count") is None
               for c in nb.cells if c.cell_type == "code")


@pytest.mark.parametrize("path", SOLUTIONS, ids=lambda p: p.name)
def test_solution_is_committed_without_outputs_and_ends_with_progress(path):
    nb = nbformat.read(path, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert all(not c.get("outputs") and c.get("execution_count") is None for c in code)
    assert any(c.source.strip() == "progress()" for c in code)
    assert f'progress()["{ex_id(path)}"] == "passed"' in code[-1].source


def test_generation_is_deterministic(tmp_path):
    out = tmp_path / "ex"
    assert mk.main(["--exercises", str(out)]) == 0
    first = {p.name: p.read_text() for p in out.glob("*.ipynb")}
    assert mk.main(["--exercises", str(out), "--check"]) == 0
    assert mk.main(["--exercises", str(out)]) == 0
    assert {p.name: p.read_text() for p in out.glob("*.ipynb")} == first


def make_solution(tmp_path, cells):
    nb = nbformat.v4.new_notebook()
    nb.cells = cells
    for i, c in enumerate(nb.cells):
        c["id"] = f"c{i}"
    d = tmp_path / "solutions"
    d.mkdir(exist_ok=True)
    nbformat.write(nb, d / "ex9_9.ipynb")
    return d


def generated(tmp_path, cells):
    src = make_solution(tmp_path, cells)
    assert mk.main(["--solutions", str(src), "--exercises", str(tmp_path / "exercises")]) == 0
    return nbformat.read(tmp_path / "exercises" / "ex9_9.ipynb", as_version=4)


def test_marker_rules(tmp_path):
    v4 = nbformat.v4
    nb = generated(tmp_path, [
        v4.new_code_cell("x = 1\n### BEGIN SOLUTION\n#> answer = None  # your answer here\n"
                         "answer = 42\n### END SOLUTION\nprint(answer)"),
        v4.new_code_cell("def f():\n    ### BEGIN SOLUTION\n    return 3\n    ### END SOLUTION"),
        v4.new_markdown_cell("Intro\n<!-- ### BEGIN SOLUTION -->\nThe secret.\n<!-- ### END SOLUTION -->"),
        v4.new_markdown_cell("### BEGIN SOLUTION\nBare secret\n### END SOLUTION\nafter"),
        v4.new_code_cell("assert True", metadata={"tags": ["solution_only"]}),
    ])
    src = [c.source for c in nb.cells]
    assert src[0] == "x = 1\nanswer = None  # your answer here\nprint(answer)"
    assert src[1] == "def f():\n    # your code here"
    assert src[2] == "Intro\n*Your answer here.*"
    assert src[3] == "*Your answer here.*\nafter"
    assert len(src) == 4  # the solution_only cell is gone
    assert [c["id"] for c in nb.cells] == ["c0", "c1", "c2", "c3"]


@pytest.mark.parametrize("source", ["### BEGIN SOLUTION\nx = 1",
                                    "x = 1\n### END SOLUTION",
                                    "### BEGIN SOLUTION\n### BEGIN SOLUTION\n### END SOLUTION"])
def test_unbalanced_markers_are_an_error(tmp_path, source, capsys):
    src = make_solution(tmp_path, [nbformat.v4.new_code_cell(source)])
    assert mk.main(["--solutions", str(src), "--exercises", str(tmp_path / "ex")]) == 2
    assert "ex9_9.ipynb cell 0" in capsys.readouterr().err


def test_check_mode_detects_stale_and_missing(tmp_path):
    src = make_solution(tmp_path, [nbformat.v4.new_code_cell("x = 1")])
    out = tmp_path / "exercises"
    args = ["--solutions", str(src), "--exercises", str(out)]
    assert mk.main(args + ["--check"]) == 1          # not generated yet
    assert mk.main(args) == 0 and mk.main(args + ["--check"]) == 0
    (out / "ex9_9.ipynb").write_text("{}")
    assert mk.main(args + ["--check"]) == 1          # edited by hand
    (out / "ex8_8.ipynb").write_text("{}")
    assert mk.main(args) == 0 and not (out / "ex8_8.ipynb").exists()  # stale file removed


def test_script_runs_from_the_command_line():
    res = subprocess.run([sys.executable, str(SCRIPT), "--check"], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr


@pytest.mark.parametrize("path", nbrun.params(EXERCISES, id_of=lambda p: p.name))
def test_untouched_exercise_runs_and_is_unattempted(path, notebook_record):
    """From the record of the one execution of the exercise notebook in this run (tests/nbrun.py):
    every cell ran without raising, and progress() at the end calls every exercise unattempted."""
    rec = notebook_record(path)
    assert not rec["errors"], "the untouched exercise raised:\n  " + "\n  ".join(rec["errors"])
    assert rec["complete"], f"{path.name}: its execution did not reach the end"
    status = rec["progress"]
    assert status is not None, f"{path.name} never imported gm_core.checks"
    assert status[ex_id(path)] == "unattempted", status
    assert set(status.values()) == {"unattempted"}


@pytest.mark.parametrize("path", EXERCISES + SOLUTIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_everything_the_notebook_advertises_is_imported(path):
    nb = nbformat.read(path, as_version=4)
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    prose = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    imported = set()
    for line in code.splitlines():
        m = re.match(r"\s*from gm_core\.checks import (.*)", line)
        if m:
            imported |= {n.strip() for n in m.group(1).split(",")}
    for name in ("progress", "progress_widget", "set_time_limit", "reset_progress"):
        if re.search(rf"`{name}\(", prose):
            assert name in imported, f"{path.name} mentions {name}() but does not import it"


def test_solution_links_resolve_from_the_workspace_and_exercises():
    from gm_core.checks.exercise import REGISTRY, exercise_ids
    for ex_id in exercise_ids():
        part = next(iter(REGISTRY[ex_id].parts.values()))
        for folder in ("workspace", "exercises"):
            assert (ROOT / folder / part.solution_path()).resolve().exists(), (ex_id, folder)


def test_exercise_notebooks_point_to_the_workspace_readme():
    for path in EXERCISES:
        text = path.read_text(encoding="utf-8")
        assert "exercises/README.md" not in text, path.name

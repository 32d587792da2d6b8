"""otter-grader and nbgrader versions of the exercises (tools/export_kits.py).

Fast tests check the converted notebooks for every solution: one question / one autograder test
per part with the registry's points, the starter code kept, instructor-only cells never turned
into student tasks. The slow tests run the real tools (from PyPI, in their own venv .venv-kits
made by tools/venvs.py in set-up) on exercise 3.2, with a correct and a wrong submission:
``otter assign`` + ``otter run`` and nbgrader's ``generate_assignment`` + ``autograde``."""
import csv
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import export_kits  # noqa: E402
import make_exercises  # noqa: E402
import venvs  # noqa: E402

from gm_core.checks.exercise import REGISTRY  # noqa: E402

SOLUTIONS = sorted((ROOT / "solutions").glob("ex*.ipynb"))
# Exercise 3.2: two parts, each graded alone; its notebook runs in a few seconds (each tool
# executes it several times).
EX = "3.2"
STEM = "ex3_2"


def _id(path):
    return path.stem[2:].replace("_", ".")


def _answer_cells(nb):
    """The exercise notebook's fill-in cells (sources), in order."""
    return [c.source for c in nb.cells if c.cell_type == "code" and "your answer here" in c.source]


@pytest.mark.parametrize("path", SOLUTIONS, ids=lambda p: p.stem)
def test_otter_master_has_one_question_per_part(path):
    ex_id = _id(path)
    nb = nbformat.read(path, as_version=4)
    master = export_kits.otter_master(nb, ex_id)
    nbformat.validate(master)
    raws = [c.source for c in master.cells if c.cell_type == "raw"]
    assert raws[0].startswith("# ASSIGNMENT CONFIG")
    questions = [r for r in raws if r.startswith("# BEGIN QUESTION")]
    parts = REGISTRY[ex_id].parts
    names = [q.splitlines()[1].removeprefix("name: ") for q in questions]
    assert sorted(names) == sorted(f"{path.stem}_{p}" for p in parts)
    for q in questions:
        part = q.splitlines()[1][len(f"name: {path.stem}_"):]
        assert f"points: {parts[part].weight:g}" in q
    assert raws.count("# BEGIN SOLUTION") == raws.count("# END SOLUTION") == len(parts)
    assert raws.count("# BEGIN TESTS") == raws.count("# END TESTS") == len(parts)
    assert not any("### BEGIN SOLUTION" in c.source for c in master.cells), "otter's markers only"
    tests = [c.source for c in master.cells if "# BEGIN TEST CONFIG" in c.source]
    assert len(tests) == len(parts) and all("strict=True" in t for t in tests)


@pytest.mark.parametrize("path", SOLUTIONS, ids=lambda p: p.stem)
def test_nbgrader_source_keeps_starters_and_drops_instructor_cells(path):
    ex_id = _id(path)
    nb = nbformat.read(path, as_version=4)
    src = export_kits.nbgrader_source(nb, ex_id)
    nbformat.validate(src)
    meta = [c.metadata.get("nbgrader") for c in src.cells]
    graded = [m for m in meta if m and m["grade"]]
    assert sorted(m["grade_id"] for m in graded) == sorted(f"{path.stem}_{p}_test" for p in REGISTRY[ex_id].parts)
    for m in graded:
        part = m["grade_id"][len(path.stem) + 1:-len("_test")]
        assert m["locked"] and m["points"] == REGISTRY[ex_id].parts[part].weight
    ids = [m["grade_id"] for m in meta if m]
    assert len(ids) == len(set(ids)), "grade ids are unique"
    # What generate_assignment hands out (region -> the configured stub) equals exercises/' answer cells.
    released = []
    for cell, m in zip(src.cells, meta):
        if m and m["solution"]:
            before, region = cell.source.split("### BEGIN SOLUTION\n")
            _, after = region.split("### END SOLUTION")
            released.append((before + after.lstrip("\n")).rstrip("\n"))
    exercise = nbformat.read(ROOT / "exercises" / path.name, as_version=4)
    assert _answer_cells(exercise) == [r for r in released if "your answer here" in r]
    # nothing marked solution outside solution cells; instructor-only cells are gone
    for cell, m in zip(src.cells, meta):
        if not (m and m["solution"]):
            assert "BEGIN SOLUTION" not in cell.source
    n_instr = sum(export_kits.classify(c) == "instructor" for c in nb.cells)
    n_plain = sum(1 for c in nb.cells if export_kits.classify(c) in ("plain", "check")
                  and make_exercises.SOLUTION_ONLY not in c.metadata.get("tags", []))
    n_answer = sum(export_kits.classify(c) == "answer" for c in nb.cells)
    assert len(src.cells) == n_plain + n_answer + len(graded), n_instr


def test_two_exports_write_the_same_files(tmp_path):
    """Exporting twice gives byte-identical kits (cell ids come from the content, not chance), so
    an instructor's repository of kits changes only where the course changed."""
    runs = []
    for name in ("a", "b"):
        written = export_kits.write_otter(tmp_path / name / "otter", ["1.1", "3.2"])
        written += export_kits.write_nbgrader(tmp_path / name / "nbgrader", ["1.1", "3.2"])
        runs.append({p.relative_to(tmp_path / name).as_posix(): p.read_bytes() for p in written})
    assert runs[0].keys() == runs[1].keys() and len(runs[0]) == 4
    assert runs[0] == runs[1]
    for blob in runs[0].values():
        ids = [c["id"] for c in json.loads(blob)["cells"]]
        assert len(set(ids)) == len(ids), "cell ids are unique within a notebook"


def test_bad_input_is_refused_clearly(tmp_path):
    with pytest.raises(ValueError, match="exercises"):
        export_kits.write_otter(tmp_path, ["9.9"])
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell("### BEGIN SOLUTION\nx = 1\n### BEGIN SOLUTION\n### END SOLUTION")]
    with pytest.raises(make_exercises.MarkerError):
        export_kits.otter_master(nb, "1.1")


# ---- the real tools --------------------------------------------------------------------------

@pytest.fixture(scope="module")
def kits_bin():
    try:
        return venvs.ensure("kits")
    except venvs.VenvError as exc:    # only when PyPI cannot be reached
        pytest.skip(f"otter-grader / nbgrader could not be installed from PyPI: {exc}")


def _env(bin_dir):
    env = {k: v for k, v in os.environ.items() if k != "VIRTUAL_ENV"}
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    env["PYTHONPATH"] = str(ROOT)
    env.setdefault("MPLBACKEND", "Agg")
    return env


def _run(bin_dir, args, cwd, timeout=600):
    res = subprocess.run([str(bin_dir / args[0]), *args[1:]], cwd=cwd, env=_env(bin_dir),
                         capture_output=True, text=True, timeout=timeout)
    assert res.returncode == 0, f"{args[0]} failed:\n{res.stdout[-3000:]}\n{res.stderr[-3000:]}"
    return res


def _wrong(nb):
    """A plausible wrong 3.2: a wrong letter for part a, the right letter for part b."""
    right_b = sorted(REGISTRY[EX].parts["b"].key.correct)[0]
    wrong_a = sorted(set("abcd") - set(REGISTRY[EX].parts["a"].key.correct))[0]
    seen = set()
    for cell in nb.cells:
        if cell.cell_type == "code" and cell.source.startswith("answer_a = None"):
            cell.source, _ = f"answer_a = {wrong_a!r}   # wrong", seen.add("a")
        elif cell.cell_type == "code" and cell.source.startswith("answer_b = None"):
            cell.source, _ = f"answer_b = {right_b!r}", seen.add("b")
    assert seen == {"a", "b"}, "the student notebook has both answer cells"
    return nb


@pytest.mark.slow
def test_otter_assign_and_run_grade_right_and_wrong(kits_bin, tmp_path):
    master = export_kits.write_otter(tmp_path / "otter", [EX])[0]
    # (otter assign could also run the tests against the worked solution; `otter run` on that
    # solution below does the same and more, so assign skips it)
    _run(kits_bin, ["otter", "assign", "--no-run-tests", master.name, "dist"], cwd=master.parent)
    dist = master.parent / "dist"
    student = nbformat.read(dist / "student" / master.name, as_version=4)
    exercise = nbformat.read(ROOT / "exercises" / master.name, as_version=4)
    assert _answer_cells(student) == _answer_cells(exercise), "otter keeps the starter code"
    assert "grader.check" not in nbformat.writes(student) and "BEGIN SOLUTION" not in nbformat.writes(student)
    zip_path = next((dist / "autograder").glob("*.zip"))
    total = sum(p.weight for p in REGISTRY[EX].parts.values())
    scores = {}
    for name, nb in (("right", nbformat.read(dist / "autograder" / master.name, as_version=4)),
                     ("wrong", _wrong(student))):
        sub = tmp_path / name / f"{STEM}.ipynb"
        sub.parent.mkdir()
        nbformat.write(nb, sub)
        _run(kits_bin, ["otter", "run", "-a", str(zip_path), "-o", str(sub.parent), sub.name], cwd=sub.parent)
        res = json.loads((sub.parent / "results.json").read_text())
        scores[name] = {t["name"]: t["score"] for t in res["tests"] if t.get("max_score")}
    assert sum(scores["right"].values()) == total, scores
    assert scores["wrong"][f"{STEM}_a"] == 0 and scores["wrong"][f"{STEM}_b"] == REGISTRY[EX].parts["b"].weight


@pytest.mark.slow
def test_nbgrader_generate_and_autograde_right_and_wrong(kits_bin, tmp_path):
    course = tmp_path / "course"
    export_kits.write_nbgrader(course, [EX])
    _run(kits_bin, ["nbgrader", "generate_assignment", STEM, "--create", "--force"], cwd=course)
    release = nbformat.read(course / "release" / STEM / f"{STEM}.ipynb", as_version=4)
    exercise = nbformat.read(ROOT / "exercises" / f"{STEM}.ipynb", as_version=4)
    assert [s.replace("\n# your code here", "") for s in _answer_cells(release)] == _answer_cells(exercise)
    assert "raise NotImplementedError" not in nbformat.writes(release)
    solution = nbformat.read(course / "source" / STEM / f"{STEM}.ipynb", as_version=4)
    right = nbformat.read(course / "release" / STEM / f"{STEM}.ipynb", as_version=4)
    answers = iter(c.source for c in solution.cells if c.metadata.get("nbgrader", {}).get("solution"))
    for cell in right.cells:
        if cell.metadata.get("nbgrader", {}).get("solution"):
            cell.source = next(answers)
    for student, nb in (("right", right), ("wrong", _wrong(release))):
        path = course / "submitted" / student / STEM / f"{STEM}.ipynb"
        path.parent.mkdir(parents=True)
        nbformat.write(nb, path)
    _run(kits_bin, ["nbgrader", "autograde", STEM, "--create", "--force"], cwd=course)
    _run(kits_bin, ["nbgrader", "export", "--to", "grades.csv"], cwd=course)
    rows = {r["student_id"]: r for r in csv.DictReader(open(course / "grades.csv"))}
    total = sum(p.weight for p in REGISTRY[EX].parts.values())
    assert float(rows["right"]["score"]) == float(rows["right"]["max_score"]) == total, rows
    assert float(rows["wrong"]["score"]) == REGISTRY[EX].parts["b"].weight, rows
    shutil.rmtree(course / "autograded", ignore_errors=True)


@pytest.mark.parametrize("path", SOLUTIONS, ids=lambda p: p.stem)
def test_otter_master_cells_are_valid_python(path):
    """otter runs the master notebook (prompts as string literals) to check the solution: every
    code cell must parse, e.g. a starter's docstring must not end the prompt's string early."""
    import ast
    import re

    master = export_kits.otter_master(nbformat.read(path, as_version=4), _id(path))
    for i, cell in enumerate(master.cells):
        if cell.cell_type == "code":
            src = re.sub(r"^(\s*)[%!].*$", r"\1pass", cell.source, flags=re.M)
            try:
                ast.parse(src)
            except SyntaxError as exc:
                pytest.fail(f"{path.stem} master cell {i} does not parse ({exc}):\n{cell.source[:400]}")

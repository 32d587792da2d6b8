"""Grading for instructors (issue #14, point 6): python -m gm_core.grade.

Notebooks run in fresh kernels, answers are probed there, and every part is judged in the grading
process: the solutions get full marks, the untouched exercises zero, and a notebook that tampers
with gm_core, the checkers or their state gets nothing for the parts it tampered with."""
import csv
import json
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

from gm_core import grade
from gm_core.checks import exercise_ids
from gm_core.checks._core import REGISTRY

ROOT = Path(__file__).resolve().parent.parent
FEW = ["ex1_1.ipynb", "ex2_4.ipynb", "ex3_1.ipynb"]


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """One grading run over a few solutions, the same untouched exercises and a tampering notebook."""
    tmp = tmp_path_factory.mktemp("grading")
    nb = nbformat.read(ROOT / "exercises" / "ex3_1.ipynb", as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "code" and "def theta(" in cell.source:
            cell.source = "def theta(alpha1, alpha2, R, w):\n    return 0.0   # wrong"
        if cell.cell_type == "code" and cell.source.startswith("answer_b = None"):
            cell.source = f'answer_b = "{sorted(REGISTRY["3.1"].parts["b"].correct)[0]}"   # right'
    nb.cells.append(nbformat.v4.new_code_cell(
        "import gm_core, gm_core.checks as C, gm_core.checks._core as core, gm_core.checks.ch3 as ch3\n"
        "from gm_core.checks import _progress\n"
        "ch3._theta_dd = lambda *a: 0.0                       # monkeypatch the reference\n"
        "core.FunctionPart.judge = lambda self, o: 'Correct'  # replace the judge\n"
        "C.ex3_1.a.check = lambda *a, **k: None              # replace the checker\n"
        "_progress.record('3.1', 'a', 'passed')              # write 'passed' into the state\n"
        "_progress._MEMORY['3.1/a'] = {'status': 'passed', 'solution_viewed': False, 'when': 0}\n"
        "assert C.progress()['3.1'] == 'passed'\n"
        "core.FunctionPart.student_value = lambda self, ans, args: self.ref(*args)  # forge outputs\n"))
    tamper = tmp / "tamper" / "ex3_1.ipynb"
    tamper.parent.mkdir()
    nbformat.write(nb, tamper)
    sol = sorted((ROOT / "solutions").glob("ex*.ipynb"))          # all of them: ~45 s
    ex = [ROOT / "exercises" / f for f in FEW]
    out = tmp / "out"
    res = subprocess.run([sys.executable, "-m", "gm_core.grade", *map(str, sol + ex), str(tamper),
                          "--out", str(out)], capture_output=True, text=True, cwd=tmp,
                         env={**__import__("os").environ, "PYTHONPATH": str(ROOT)}, timeout=600)
    assert res.returncode == 0, res.stderr
    rows = list(csv.DictReader(open(out / "grades.csv")))
    return json.loads((out / "results.json").read_text()), rows, res.stdout


def rows_for(rows, folder):
    return [r for r in rows if Path(r["notebook"]).parent.name == folder]


def test_results_json_is_in_gradescope_format(graded):
    results, rows, stdout = graded
    assert isinstance(results["score"], float) and isinstance(results["tests"], list)
    for t in results["tests"]:
        assert {"name", "score", "max_score", "output", "visibility"} <= set(t)
        assert 0 <= t["score"] <= t["max_score"] and t["visibility"] == "visible"
    assert len(results["tests"]) == len(rows)
    assert results["score"] == pytest.approx(sum(t["score"] for t in results["tests"]))
    assert "points" in stdout


def test_all_solutions_get_full_marks(graded):
    _, rows, _ = graded
    sol = rows_for(rows, "solutions")
    assert {r["exercise"] for r in sol} == set(exercise_ids())
    assert len(sol) == sum(len(ex.parts) for ex in REGISTRY.values())
    assert all(r["status"] == "passed" and float(r["score"]) == float(r["max_score"]) > 0 for r in sol), sol


def test_untouched_exercises_get_zero(graded):
    _, rows, _ = graded
    ex = rows_for(rows, "exercises")
    assert {r["exercise"] for r in ex} == {"1.1", "2.4", "3.1"}   # all 13: test_exercises.py
    assert all(float(r["score"]) == 0.0 for r in ex), ex


def test_tampering_gains_nothing(graded):
    _, rows, _ = graded
    t = {r["part"]: r for r in rows_for(rows, "tamper")}
    assert float(t["a"]["score"]) == 0.0 and t["a"]["status"] == "failed"
    assert float(t["b"]["score"]) == float(t["b"]["max_score"])      # the honest part still counts


def test_default_weights_and_overrides(tmp_path):
    part = REGISTRY["1.4"].parts["a"]
    assert part.weight == 2.0 and REGISTRY["1.4"].parts["d_rates"].weight == 1.0
    rows = [{"notebook": "n", "exercise": "1.4", "part": "a", "status": "passed", "score": 3.0,
             "max_score": 3.0, "message": "ok"}]
    res = grade.write_results(rows, tmp_path)
    assert res["score"] == 3.0 and (tmp_path / "grades.csv").read_text().count("\n") == 2


def test_answer_expressions_come_from_the_check_cells():
    nb = nbformat.read(ROOT / "solutions" / "ex1_4.ipynb", as_version=4)
    exprs = grade.answer_expressions(nb, "1.4")
    assert exprs == {"a": "exp_left", "b": "exp_right", "c": "helix", "d": "methods",
                     "d_rates": "answer_rates", "d_meaning": "answer_meaning"}
    assert grade.exercise_of(ROOT / "exercises" / "ex2_3.ipynb") == "2.3"
    assert grade.exercise_of(Path("notes.ipynb")) is None


@pytest.mark.parametrize("evidence", [None, {}, {"outcomes": "x"}, {"outcomes": []},
                                      {"outcomes": [{"k": "ok", "v": {"__nd__": [3], "d": [1, 2]}}]},
                                      {"outcomes": [{"k": "ok", "v": "a"}] * 99},
                                      {"missing": "NameError"}])
def test_forged_or_garbled_evidence_never_passes(evidence):
    for ex_id in exercise_ids():
        for part in REGISTRY[ex_id].parts.values():
            v = grade.judge_part(part, evidence)
            assert not v.passed, (ex_id, part.name, evidence)


def test_cli_errors_are_clear(tmp_path):
    res = subprocess.run([sys.executable, "-m", "gm_core.grade", str(tmp_path / "nope.ipynb"), "--out",
                          str(tmp_path)], capture_output=True, text=True, env={**__import__("os").environ,
                                                                                 "PYTHONPATH": str(ROOT)})
    assert res.returncode == 2 and "no such file" in res.stderr

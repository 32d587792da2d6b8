"""For every exercise: `otter assign` succeeds and otter grades the solution full and the starter
zero; nbgrader's generate_assignment + autograde give full and zero; the Gradescope kit's
run_autograder gives full and zero. The tools are the instructor's own, from PyPI (.venv-kits,
.venv-gradescope, made by tools/venvs.py)."""
import csv
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
import export_kits  # noqa: E402
import gradescope_kit  # noqa: E402
import venvs  # noqa: E402

from gm_core.checks.exercise import REGISTRY  # noqa: E402

EXERCISES = sorted(REGISTRY, key=lambda e: tuple(int(x) for x in e.split(".")))


def _stem(ex):
    return "ex" + ex.replace(".", "_")


def _total(ex):
    return sum(p.weight for p in REGISTRY[ex].parts.values())


@pytest.fixture(scope="module")
def kits_bin():
    return venvs.ensure("kits")            # an error, not a skip: make test-kits needs the tools


def _run(bin_dir, args, cwd, timeout=900):
    env = {k: v for k, v in os.environ.items() if k != "VIRTUAL_ENV"}
    env.update(PATH=f"{bin_dir}{os.pathsep}{env.get('PATH', '')}", PYTHONPATH=str(ROOT), MPLBACKEND="Agg")
    res = subprocess.run([str(bin_dir / args[0]), *args[1:]], cwd=cwd, env=env, capture_output=True,
                         text=True, timeout=timeout)
    assert res.returncode == 0, f"{' '.join(args)} failed:\n{res.stdout[-3000:]}\n{res.stderr[-3000:]}"
    return res


@pytest.mark.parametrize("ex", EXERCISES)
def test_otter_assigns_and_grades_solution_full_and_starter_zero(ex, kits_bin, tmp_path):
    master = export_kits.write_otter(tmp_path / "otter", [ex])[0]
    _run(kits_bin, ["otter", "assign", master.name, "dist"], cwd=master.parent)   # runs the solution's tests
    dist = master.parent / "dist"
    zip_path = next((dist / "autograder").glob("*.zip"))
    scores = {}
    for name, nb in (("solution", dist / "autograder" / master.name), ("starter", dist / "student" / master.name)):
        sub = tmp_path / name / master.name
        sub.parent.mkdir()
        shutil.copyfile(nb, sub)
        _run(kits_bin, ["otter", "run", "-a", str(zip_path), "-o", str(sub.parent), sub.name], cwd=sub.parent)
        res = json.loads((sub.parent / "results.json").read_text())
        scores[name] = sum(t["score"] for t in res["tests"] if t.get("max_score"))
    assert scores == {"solution": _total(ex), "starter": 0}, scores


@pytest.mark.parametrize("ex", EXERCISES)
def test_nbgrader_grades_solution_full_and_starter_zero(ex, kits_bin, tmp_path):
    stem, course = _stem(ex), tmp_path / "course"
    export_kits.write_nbgrader(course, [ex])
    _run(kits_bin, ["nbgrader", "generate_assignment", stem, "--create", "--force"], cwd=course)
    release = course / "release" / stem / f"{stem}.ipynb"
    solution = nbformat.read(course / "source" / stem / f"{stem}.ipynb", as_version=4)
    right = nbformat.read(release, as_version=4)
    answers = iter(c.source for c in solution.cells if c.metadata.get("nbgrader", {}).get("solution"))
    for cell in right.cells:
        if cell.metadata.get("nbgrader", {}).get("solution"):
            cell.source = next(answers)
    for student, nb in (("solution", right), ("starter", nbformat.read(release, as_version=4))):
        path = course / "submitted" / student / stem / f"{stem}.ipynb"
        path.parent.mkdir(parents=True)
        nbformat.write(nb, path)
    _run(kits_bin, ["nbgrader", "autograde", stem, "--create", "--force"], cwd=course)
    _run(kits_bin, ["nbgrader", "export", "--to", "grades.csv"], cwd=course)
    rows = {r["student_id"]: float(r["score"]) for r in csv.DictReader(open(course / "grades.csv"))}
    assert rows == {"solution": _total(ex), "starter": 0.0}, rows


@pytest.fixture(scope="module")
def gradescope(tmp_path_factory):
    root = venvs.gradescope()
    kit = gradescope_kit.build_kit(tmp_path_factory.mktemp("gradescope") / "kit.zip", exercises=EXERCISES)
    venvs.unpack_kit(kit, root)
    res = venvs.run_setup(root)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-3000:]
    results = {}
    for name, folder in (("solution", ROOT / "solutions"), ("starter", ROOT / "exercises")):
        sub, out = root / "submission", root / "results"
        for d in (sub, out):
            shutil.rmtree(d, ignore_errors=True)
        sub.mkdir()
        for ex in EXERCISES:
            shutil.copyfile(folder / f"{_stem(ex)}.ipynb", sub / f"{_stem(ex)}.ipynb")
        env = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
        env.update(GM_AUTOGRADER_ROOT=str(root), GM_AUTOGRADER_PYTHON=venvs.AUTOGRADER_PYTHON)
        run = subprocess.run([str(root / "source" / "run_autograder")], cwd=root, env=env,
                             capture_output=True, text=True, timeout=3600)
        assert run.returncode == 0, run.stderr[-3000:]
        results[name] = json.loads((out / "results.json").read_text())
        results[name]["kit_log"] = run.stdout[-6000:]    # the grader's own output, for failures
    return results


@pytest.mark.xdist_group("gradescope")   # one worker builds the autograder folder and grades once
@pytest.mark.parametrize("ex", EXERCISES)
def test_gradescope_grades_solution_full_and_starter_zero(ex, gradescope):
    def score(name):
        tests = [t for t in gradescope[name]["tests"] if f": exercise {ex} part " in t["name"]]
        why = "\n".join([*(f"{t['name']}: {t.get('output', '')[:300]}" for t in tests),
                         gradescope[name].get("output", "")[:2000], gradescope[name]["kit_log"]])
        assert len(tests) == len(REGISTRY[ex].parts), why
        return sum(t["score"] for t in tests), sum(t["max_score"] for t in tests), why

    got, most, why = score("solution")
    assert got == most == _total(ex), why
    got, _, why = score("starter")
    assert got == 0, why

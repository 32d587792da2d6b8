"""The Gradescope kit (tools/gradescope_kit.py, `make gradescope`), used as Gradescope uses it.

The zip is unpacked into a folder laid out like Gradescope's /autograder (paths redirected with
GM_AUTOGRADER_ROOT); setup.sh installs the course from the zip into its venv, and run_autograder
grades a worked solution (full marks), an untouched exercise (zero) and an empty submission (zero,
every part listed as not submitted). The folder's venv was made by the kit's own setup.sh in a
fresh folder, from the package index, during set-up (``tools/venvs.py gradescope``, again whenever
the course's requirements or setup.sh change); here setup.sh runs again on the current zip and
installs this course into it, which a test compares file by file with the repository's."""
import hashlib
import json
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import gradescope_kit  # noqa: E402
import venvs  # noqa: E402

EXERCISE = "1.1"
pytestmark = pytest.mark.slow   # setup.sh installs the course into the kit's venv


def _env(root):
    env = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
    env.update(GM_AUTOGRADER_ROOT=str(root), GM_AUTOGRADER_PYTHON=venvs.AUTOGRADER_PYTHON)
    return env


@pytest.fixture(scope="module")
def autograder(tmp_path_factory):
    try:
        root = venvs.gradescope()           # made in set-up (make test); made here if missing
    except venvs.VenvError as exc:          # only when the package index cannot be reached
        pytest.skip(f"the Gradescope kit's setup.sh could not install from the package index: {exc}")
    kit = gradescope_kit.build_kit(tmp_path_factory.mktemp("gradescope") / "kit.zip", exercises=[EXERCISE])
    with zipfile.ZipFile(kit) as zf:
        modes = {i.filename: i.external_attr >> 16 for i in zf.infolist()}
    venvs.unpack_kit(kit, root)                              # Gradescope keeps the zip's modes
    for name in ("submission", "results"):
        shutil.rmtree(root / name, ignore_errors=True)
    res = venvs.run_setup(root)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-3000:]
    return root, modes


_RUNS = {}


def run(root, files):
    key = tuple(sorted((k, str(v)) for k, v in files.items()))
    if key in _RUNS:                       # the same submission is graded once per session
        return _RUNS[key]
    sub, out = root / "submission", root / "results"
    shutil.rmtree(sub, ignore_errors=True)
    shutil.rmtree(out, ignore_errors=True)
    sub.mkdir()
    for name, path in files.items():
        shutil.copyfile(path, sub / name)
    res = subprocess.run([str(root / "source" / "run_autograder")], cwd=root, env=_env(root),
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr[-3000:]
    _RUNS[key] = json.loads((out / "results.json").read_text())
    return _RUNS[key]


def test_zip_layout_and_modes(autograder):
    root, modes = autograder
    assert modes["setup.sh"] & 0o111 and modes["run_autograder"] & 0o111
    assert (root / "source" / "course" / "pyproject.toml").exists()
    assert (root / "source" / "course" / "gm_grader" / "batch.py").exists()
    assert (root / "source" / "course" / "gm_core" / "checks" / "parts.py").exists()
    assert (root / "gm-venv" / "bin" / "python").exists()


def _digest(folder):
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*.py")) if "__pycache__" not in p.parts}


def test_course_is_installed_from_the_zip_not_the_repository(autograder):
    root, _ = autograder
    py = root / "gm-venv" / "bin" / "python"
    out = subprocess.run([str(py), "-c", "import gm_core; print(gm_core.__file__)"], cwd=root,
                         env=_env(root), capture_output=True, text=True, check=True).stdout
    installed = Path(out.strip()).parent
    assert installed.is_relative_to(root / "gm-venv") and not installed.is_relative_to(ROOT / "gm_core")
    assert _digest(installed) == _digest(ROOT / "gm_core"), "setup.sh installed this zip's course, file for file"


def test_solution_gets_full_marks(autograder):
    root, _ = autograder
    r = run(root, {"ex1_1.ipynb": ROOT / "solutions" / "ex1_1.ipynb"})
    total = sum(t["max_score"] for t in r["tests"])
    assert total > 0 and r["score"] == total, r


def test_blank_submission_gets_zero(autograder):
    root, _ = autograder
    r = run(root, {"ex1_1.ipynb": ROOT / "exercises" / "ex1_1.ipynb"})
    assert r["tests"] and r["score"] == 0 and all(t["score"] == 0 for t in r["tests"]), r


def test_nothing_submitted_lists_every_part_with_zero(autograder):
    root, _ = autograder
    r = run(root, {})
    full = run(root, {"ex1_1.ipynb": ROOT / "solutions" / "ex1_1.ipynb"})
    assert r["score"] == 0 and r["tests"] and all(t["score"] == 0 for t in r["tests"]), r
    assert sum(t["max_score"] for t in r["tests"]) == sum(t["max_score"] for t in full["tests"])


def _seeker(root):
    """A submission that looks for the answers instead of giving them: (a) through the answer
    key (the course's own function for it); (b) on disk -- the key files in the installed
    course, the worked solution in the autograder's source, /etc/shadow -- giving the right
    answer to (b) only if it could read any of them, or runs as root."""
    import nbformat
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell(c) for c in (
        "import glob, os\nimport gm_core\nfrom gm_core.checks import ex1_1\n"
        "from gm_core.checks.answer_key import key_of",
        "try:\n    ex1_1.a.check(key_of(ex1_1.a).correct_answer())\n"
        "except Exception:\n    ex1_1.a.check('a')",
        "course = os.path.dirname(gm_core.__file__)\n"
        f"paths = glob.glob(os.path.join(course, 'checks', 'keys', '*.py')) + [\n"
        f"    os.path.join(course, 'checks', 'keys', 'ex1.py'), '/etc/shadow',\n"
        f"    {str(root / 'source' / 'course' / 'solutions' / 'ex1_1.ipynb')!r}]\n"
        "read = []\nfor p in paths:\n    try:\n        read.append(len(open(p).read()))\n"
        "    except OSError:\n        pass\n"
        "ex1_1.b.check('c' if read or os.getuid() == 0 else 'a')")]
    return nbformat.writes(nb)


@pytest.mark.skipif(os.geteuid() != 0, reason="as a user, notebooks run as the grader's own user")
def test_a_root_grader_runs_notebooks_as_their_own_user_out_of_reach_of_the_keys(autograder, tmp_path):
    root, _ = autograder
    seeker = tmp_path / "ex1_1.ipynb"
    seeker.write_text(_seeker(root))
    r = run(root, {"ex1_1.ipynb": seeker})
    by_part = {t["name"].rsplit(" part ", 1)[-1][:1]: t for t in r["tests"]}
    assert r["score"] == 0, r
    assert "answer key" in by_part["a"]["output"], by_part["a"]
    assert "answer key" not in by_part["b"]["output"], by_part["b"]   # nothing read, not root
    full = run(root, {"ex1_1.ipynb": ROOT / "solutions" / "ex1_1.ipynb"})
    assert full["score"] == sum(t["max_score"] for t in full["tests"]) > 0   # honest: full


def _kit_run(tmp_path, grader_code, exit_code):
    """kit_run.py from the zip, with a stand-in ``gm_grader`` that writes ``grader_code``'s
    report (or none) and exits ``exit_code``: what Gradescope is left with."""
    root = tmp_path / "autograder"
    (root / "source").mkdir(parents=True)
    with zipfile.ZipFile(gradescope_kit.build_kit(tmp_path / "kit.zip", exercises=[EXERCISE])) as zf:
        for name in ("kit_run.py", "kit.json", "assignment.json"):
            (root / "source" / name).write_bytes(zf.read(name))
    fake = tmp_path / "fake" / "gm_grader"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text("")
    (fake / "__main__.py").write_text(
        "import json, sys\nfrom pathlib import Path\n"
        "out = Path(sys.argv[sys.argv.index('--out') + 1])\n"
        f"{grader_code}\nsys.exit({exit_code})\n")
    (root / "results").mkdir()
    (root / "results" / "results.json").write_text('{"score": 99, "tests": []}')   # a stale one
    env = {**_env(root), "PYTHONPATH": str(fake.parent)}
    res = subprocess.run([sys.executable, str(root / "source" / "kit_run.py")], cwd=root, env=env,
                         capture_output=True, text=True, timeout=120)
    assert res.returncode == 0, res.stderr
    return json.loads((root / "results" / "results.json").read_text())


def test_a_grader_fault_on_one_notebook_keeps_every_other_grade(tmp_path):
    rows = [{"name": "ex1_1.ipynb: exercise 1.1 part a", "score": 2, "max_score": 2},
            {"name": "ex1_2.ipynb: exercise 1.2 part a", "score": 0, "max_score": 2,
             "output": "Not graded, because of a fault in the grader, not in your notebook"}]
    report = {"score": 2, "tests": rows, "output": "GRADER FAULT: ex1_2.ipynb: ..."}
    got = _kit_run(tmp_path, f"(out / 'results.json').write_text(json.dumps({report!r}))", 4)
    assert got == report


@pytest.mark.parametrize("code", ["pass", "raise SystemExit('crashed')"])
def test_a_grader_that_writes_no_report_leaves_a_message_not_a_stale_grade(tmp_path, code):
    got = _kit_run(tmp_path, code, 4 if code == "pass" else 1)
    assert got["score"] == 0 and got["tests"] == [] and "tell your instructor" in got["output"]


def test_bad_options_are_refused_clearly(tmp_path):
    with pytest.raises(ValueError, match="exercises"):
        gradescope_kit.build_kit(tmp_path / "k.zip", exercises=["9.9"])
    with pytest.raises(ValueError, match="exercises"):
        gradescope_kit.build_kit(tmp_path / "k.zip", exercises=["1.4; rm -rf /"])
    with pytest.raises(TypeError, match="weights"):
        gradescope_kit.build_kit(tmp_path / "k.zip", weights=[1, 2])
    with pytest.raises(ValueError, match="positive"):
        gradescope_kit.build_kit(tmp_path / "k.zip", time_limit=0)
    assert not (tmp_path / "k.zip").exists()

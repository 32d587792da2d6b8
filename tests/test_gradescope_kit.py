"""The Gradescope kit (tools/gradescope_kit.py, `make gradescope`), used as Gradescope uses it.

The zip is unpacked into a fresh folder laid out like Gradescope's /autograder (paths redirected
with GM_AUTOGRADER_ROOT); setup.sh installs the course from the zip into a new venv (from the
package index, so no copy of the repository is involved), and run_autograder grades a worked
solution (full marks), an untouched exercise (zero) and an empty submission (zero, every part
listed as not submitted)."""
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

EXERCISE = "1.1"
pytestmark = pytest.mark.slow   # setup.sh installs the course into a new venv: about a minute


def _env(root):
    env = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
    env.update(GM_AUTOGRADER_ROOT=str(root), GM_AUTOGRADER_PYTHON=sys.executable)
    return env


@pytest.fixture(scope="module")
def autograder(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("gradescope")
    kit = gradescope_kit.build_kit(tmp / "kit.zip", exercises=[EXERCISE])
    root = tmp / "autograder"
    (root / "source").mkdir(parents=True)
    with zipfile.ZipFile(kit) as zf:
        zf.extractall(root / "source")
        modes = {i.filename: i.external_attr >> 16 for i in zf.infolist()}
    for script in ("setup.sh", "run_autograder"):           # Gradescope keeps the zip's modes
        os.chmod(root / "source" / script, modes[script] & 0o777)
    res = subprocess.run(["bash", str(root / "source" / "setup.sh")], cwd=root, env=_env(root),
                         capture_output=True, text=True, timeout=900)
    assert res.returncode == 0, res.stdout[-2000:] + res.stderr[-3000:]
    return root, modes


def run(root, files):
    sub, out = root / "submission", root / "results"
    shutil.rmtree(sub, ignore_errors=True)
    shutil.rmtree(out, ignore_errors=True)
    sub.mkdir()
    for name, path in files.items():
        shutil.copyfile(path, sub / name)
    res = subprocess.run([str(root / "source" / "run_autograder")], cwd=root, env=_env(root),
                         capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr[-3000:]
    return json.loads((out / "results.json").read_text())


def test_zip_layout_and_modes(autograder):
    root, modes = autograder
    assert modes["setup.sh"] & 0o111 and modes["run_autograder"] & 0o111
    assert (root / "source" / "course" / "pyproject.toml").exists()
    assert (root / "source" / "course" / "gm_core" / "grade.py").exists() or \
        list((root / "source" / "course" / "gm_core").rglob("grade*.py"))
    assert (root / "gm-venv" / "bin" / "python").exists()


def test_course_is_installed_from_the_zip_not_the_repository(autograder):
    root, _ = autograder
    py = root / "gm-venv" / "bin" / "python"
    out = subprocess.run([str(py), "-c", "import gm_core; print(gm_core.__file__)"], cwd=root,
                         env=_env(root), capture_output=True, text=True, check=True).stdout
    assert str(root / "gm-venv") in out and str(ROOT) not in out


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

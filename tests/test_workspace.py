"""tools/sync_workspace.py (run by `make lab`): copies exercises once, never overwrites student work."""
import importlib.util
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "sync_workspace.py"

spec = importlib.util.spec_from_file_location("sync_workspace", SCRIPT)
sync_workspace = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sync_workspace)


def run(src, dst):
    return subprocess.run([sys.executable, str(SCRIPT), "--exercises", str(src), "--workspace", str(dst)],
                          capture_output=True, text=True, check=True).stdout


def make_course(tmp_path):
    src = tmp_path / "exercises"
    src.mkdir()
    (src / "ex1_1.ipynb").write_text('{"v": "course 1"}')
    (src / "README.md").write_text("how exercises work")
    (src / ".ipynb_checkpoints").mkdir()
    (src / ".ipynb_checkpoints" / "ex1_1-checkpoint.ipynb").write_text("junk")
    return src


def test_first_run_copies_everything_but_checkpoints(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    out = run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 1"}'
    assert (dst / "README.md").exists()
    assert not (dst / ".ipynb_checkpoints").exists()
    assert "added" in out


def test_edited_file_survives_second_setup_and_new_exercises_arrive(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / "ex1_1.ipynb").write_text('{"v": "my work"}')      # the student edits
    (src / "ex1_2.ipynb").write_text('{"v": "new exercise"}')  # a course update adds one
    out = run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "my work"}'
    assert (dst / "ex1_2.ipynb").read_text() == '{"v": "new exercise"}'
    assert "ex1_2.ipynb" in out and "ex1_1.ipynb" not in out
    assert "up to date" in run(src, dst)                       # third run: nothing to do


def test_changed_course_file_is_reported_not_overwritten(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / "ex1_1.ipynb").write_text('{"v": "my work"}')
    (src / "ex1_1.ipynb").write_text('{"v": "course 2"}')
    out = run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "my work"}'
    assert "newer version" in out
    copied, updated = sync_workspace.sync(src, dst)
    assert copied == [] and updated == [dst / "ex1_1.ipynb"]


def test_deleted_copy_is_restored(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / "ex1_1.ipynb").unlink()
    run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 1"}'


def test_missing_exercises_folder_is_a_clear_error(tmp_path):
    res = subprocess.run([sys.executable, str(SCRIPT), "--exercises", str(tmp_path / "nope"),
                          "--workspace", str(tmp_path / "ws")], capture_output=True, text=True)
    assert res.returncode == 1 and "no exercises folder" in res.stderr


def test_workspace_is_git_ignored():
    assert "workspace/" in (ROOT / ".gitignore").read_text().split()

"""tools/sync_workspace.py (run by `make lab`): course updates never cost the student any work."""
import importlib.util
import json
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "sync_workspace.py"

spec = importlib.util.spec_from_file_location("sync_workspace", SCRIPT)
sync_workspace = importlib.util.module_from_spec(spec)
spec.loader.exec_module(sync_workspace)


def run(src, dst, *extra):
    return subprocess.run([sys.executable, str(SCRIPT), "--exercises", str(src), "--workspace", str(dst), *extra],
                          capture_output=True, text=True, check=True).stdout


def make_course(tmp_path):
    src = tmp_path / "exercises"
    src.mkdir()
    (src / "ex1_1.ipynb").write_text('{"v": "course 1"}')
    (src / "README.md").write_text("how the exercises folder works")
    (src / ".ipynb_checkpoints").mkdir()
    (src / ".ipynb_checkpoints" / "ex1_1-checkpoint.ipynb").write_text("junk")
    return src


def snapshot(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in folder.rglob("*") if p.is_file()}


def test_first_run_copies_everything_but_checkpoints_and_writes_the_student_readme(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    out = run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 1"}'
    readme = (dst / "README.md").read_text()
    assert readme == (ROOT / "tools" / "workspace_README.md").read_text()
    assert "work on the exercises **here**" in readme and "not here" not in readme
    assert "../solutions/" in readme
    assert not (dst / ".ipynb_checkpoints").exists()
    assert "added" in out


def test_edited_file_survives_and_new_exercises_arrive(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / "ex1_1.ipynb").write_text('{"v": "my work"}')
    (src / "ex1_2.ipynb").write_text('{"v": "new exercise"}')
    out = run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "my work"}'
    assert (dst / "ex1_2.ipynb").read_text() == '{"v": "new exercise"}'
    assert "ex1_2.ipynb" in out and "ex1_1.ipynb" not in out
    assert "up to date" in run(src, dst)


def test_untouched_copy_is_updated_automatically(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    (src / "ex1_1.ipynb").write_text('{"v": "course 2"}')
    out = run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 2"}'
    assert "updated" in out and not list(dst.glob("*.course-update*"))


def test_course_update_over_an_edited_copy_keeps_every_byte_and_writes_beside(tmp_path, monkeypatch):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    mine = b'{"v": "my work \xc3\xa9", "cells": [1, 2, 3]}\n'
    (dst / "ex1_1.ipynb").write_bytes(mine)
    before = snapshot(dst)
    (src / "ex1_1.ipynb").write_text('{"v": "course 2"}')
    out = run(src, dst)
    assert (dst / "ex1_1.ipynb").read_bytes() == mine
    assert (dst / "ex1_1.course-update.ipynb").read_text() == '{"v": "course 2"}'
    assert "kept your" in out and "ex1_1.course-update.ipynb" in out
    for rel, data in before.items():          # nothing the student had is changed or gone
        if not rel.startswith(".course-"):
            assert (dst / rel).read_bytes() == data
    # the student learns of it inside JupyterLab, once
    from gm_core.checks import store
    monkeypatch.setenv("GM_COURSE_WORKSPACE", str(dst))
    pending = store.pending_updates(mark_seen=True)
    assert pending == [{"file": "ex1_1.ipynb", "new_version": "ex1_1.course-update.ipynb", "seen": False}]
    assert store.pending_updates() == []
    # a second update replaces the untouched beside file, and is announced again
    (src / "ex1_1.ipynb").write_text('{"v": "course 3"}')
    run(src, dst)
    assert (dst / "ex1_1.ipynb").read_bytes() == mine
    assert (dst / "ex1_1.course-update.ipynb").read_text() == '{"v": "course 3"}'
    assert len(store.pending_updates()) == 1
    assert "up to date" in run(src, dst)


def test_edited_beside_file_is_never_overwritten(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / "ex1_1.ipynb").write_text("mine")
    (src / "ex1_1.ipynb").write_text("course 2")
    run(src, dst)
    (dst / "ex1_1.course-update.ipynb").write_text("I worked in the new version too")
    (src / "ex1_1.ipynb").write_text("course 3")
    run(src, dst)
    assert (dst / "ex1_1.course-update.ipynb").read_text() == "I worked in the new version too"
    assert (dst / "ex1_1.course-update-2.ipynb").read_text() == "course 3"


def test_missing_or_corrupt_manifest_loses_no_notice_and_no_file(tmp_path, monkeypatch):
    from gm_core.checks import store
    monkeypatch.setenv("GM_COURSE_WORKSPACE", str(tmp_path / "workspace"))
    for damage in ("missing", "corrupt"):
        src = tmp_path / "exercises"
        dst = tmp_path / "workspace"
        if src.exists():
            import shutil
            shutil.rmtree(src)
            shutil.rmtree(dst)
        src = make_course(tmp_path)
        run(src, dst)
        (dst / "ex1_1.ipynb").write_text("mine")
        (src / "ex1_1.ipynb").write_text("course 2")
        manifest = dst / ".course-manifest.json"
        if damage == "missing":
            manifest.unlink()
        else:
            manifest.write_text("{not json")
        (dst / ".course-notices.json").unlink(missing_ok=True)
        run(src, dst)
        assert (dst / "ex1_1.ipynb").read_text() == "mine"
        assert (dst / "ex1_1.course-update.ipynb").read_text() == "course 2"
        assert [n["file"] for n in store.pending_updates()] == ["ex1_1.ipynb"]
        if damage == "corrupt":
            assert (dst / ".course-manifest.json.corrupt").read_text() == "{not json"
        (dst / ".course-notices.json").unlink()          # notices file lost as well
        assert [n["file"] for n in store.pending_updates()] == ["ex1_1.ipynb"]


def test_untouched_old_copy_without_manifest_is_kept_not_overwritten(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / ".course-manifest.json").unlink()
    (src / "ex1_1.ipynb").write_text("course 2")
    run(src, dst)          # cannot know it was untouched: keep it, new version beside
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 1"}'
    assert (dst / "ex1_1.course-update.ipynb").read_text() == "course 2"


def test_version_1_manifest_is_read(tmp_path):
    src = make_course(tmp_path)
    dst = tmp_path / "workspace"
    dst.mkdir()
    (dst / "ex1_1.ipynb").write_text('{"v": "course 1"}')
    digest = sync_workspace._digest(dst / "ex1_1.ipynb")
    (dst / ".course-manifest.json").write_text(json.dumps({"ex1_1.ipynb": digest}))
    (src / "ex1_1.ipynb").write_text("course 2")
    run(src, dst)
    assert (dst / "ex1_1.ipynb").read_text() == "course 2"     # untouched: updated


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


# ------------------------------------------------------------------------------ never stops halfway (issue 20, point 8)
import os  # noqa: E402
import shutil  # noqa: E402

import pytest  # noqa: E402


def run_cli(src, dst, wrap=()):
    """The real command (optionally inside a sandbox wrapper); returns the CompletedProcess."""
    return subprocess.run([*wrap, sys.executable, str(SCRIPT), "--exercises", str(src), "--workspace", str(dst)],
                          capture_output=True, text=True, timeout=120)


def course_of_three(tmp_path):
    """A workspace after a first sync, then: 1.1 untouched, 1.2 edited by the student; the course
    then updates 1.1 and 1.2 and adds 1.3."""
    src = make_course(tmp_path)
    (src / "ex1_2.ipynb").write_text('{"v": "course 1 of 1.2"}')
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / "ex1_2.ipynb").write_text('{"v": "my work on 1.2"}')
    (src / "ex1_1.ipynb").write_text('{"v": "course 2"}')
    (src / "ex1_2.ipynb").write_text('{"v": "course 2 of 1.2"}')
    (src / "ex1_3.ipynb").write_text('{"v": "new exercise"}')
    return src, dst


def _chattr(path, flag):
    return subprocess.run(["chattr", flag, str(path)], capture_output=True).returncode == 0


@pytest.fixture
def immutable():
    """immutable(path): really unchangeable, even by root (chattr +i); undone at the end."""
    done = []

    def make(path):
        if os.geteuid() != 0 or not shutil.which("chattr") or not _chattr(path, "+i"):
            pytest.skip("needs root and chattr (chmod does not stop root)")
        done.append(path)
    yield make
    for path in done:
        _chattr(path, "-i")


def test_a_notebook_that_cannot_be_replaced_is_named_and_every_other_file_still_synced(tmp_path, immutable):
    src, dst = course_of_three(tmp_path)
    immutable(dst / "ex1_1.ipynb")
    res = run_cli(src, dst)
    assert res.returncode == 0 and "Traceback" not in res.stderr
    assert "PROBLEM" in res.stderr and "ex1_1.ipynb could not be replaced" in res.stderr
    assert "run `make workspace` again" in res.stderr
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 1"}'              # unchanged
    assert (dst / "ex1_2.ipynb").read_text() == '{"v": "my work on 1.2"}'         # never touched
    assert (dst / "ex1_2.course-update.ipynb").read_text() == '{"v": "course 2 of 1.2"}'
    assert (dst / "ex1_3.ipynb").read_text() == '{"v": "new exercise"}'
    assert not [p for p in dst.iterdir() if p.name.endswith(".tmp")]
    _chattr(dst / "ex1_1.ipynb", "-i")
    res = run_cli(src, dst)                      # fixed: the update arrives on the next run
    assert res.returncode == 0 and not res.stderr
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 2"}'
    assert (dst / "ex1_2.ipynb").read_text() == '{"v": "my work on 1.2"}'


@pytest.mark.parametrize("how", ["immutable folder", "read-only mount"])
def test_a_read_only_workspace_gives_a_message_per_file_and_changes_nothing(tmp_path, immutable, how):
    src, dst = course_of_three(tmp_path)
    before = snapshot(dst)
    if how == "immutable folder":
        immutable(dst)
        res = run_cli(src, dst)
    else:
        if not shutil.which("bwrap"):
            pytest.skip("bubblewrap is not installed")
        res = run_cli(src, dst, wrap=("bwrap", "--bind", "/", "/", "--dev", "/dev", "--proc", "/proc",
                                      "--ro-bind", str(dst), str(dst)))
        if res.returncode and "bwrap:" in res.stderr:
            pytest.skip(res.stderr[:200])
    assert res.returncode == 0 and "Traceback" not in res.stderr, res.stderr
    for name in ("ex1_1.ipynb", "ex1_2.ipynb", "ex1_3.ipynb", ".course-manifest.json"):
        assert any(name in line and "PROBLEM" in line for line in res.stderr.splitlines()), name
    assert "make the workspace (and this file) writable again" in res.stderr
    assert "no file of yours was changed or lost" in res.stderr
    assert snapshot(dst) == before


def test_a_folder_where_a_notebook_should_be_is_kept_and_the_notebook_written_beside(tmp_path):
    src, dst = course_of_three(tmp_path)
    (dst / "ex1_3.ipynb").mkdir()
    (dst / "ex1_3.ipynb" / "notes.txt").write_text("my notes")
    res = run_cli(src, dst)
    assert res.returncode == 0 and "Traceback" not in res.stderr
    assert "ex1_3.ipynb is a folder" in res.stderr and "Rename or move the folder" in res.stderr
    assert (dst / "ex1_3.ipynb" / "notes.txt").read_text() == "my notes"
    assert (dst / "ex1_3.course-update.ipynb").read_text() == '{"v": "new exercise"}'
    assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 2"}'                # the others
    assert (dst / "ex1_2.course-update.ipynb").read_text() == '{"v": "course 2 of 1.2"}'
    assert (dst / "ex1_2.ipynb").read_text() == '{"v": "my work on 1.2"}'


@pytest.mark.parametrize("name", [".course-manifest.json", ".course-notices.json"])
def test_a_folder_where_the_manifest_or_notices_should_be_stops_nothing(tmp_path, name):
    src, dst = course_of_three(tmp_path)
    (dst / name).unlink()
    (dst / name).mkdir()
    res = run_cli(src, dst)
    assert res.returncode == 0 and "Traceback" not in res.stderr
    assert f"{name} could not be saved" in res.stderr and "move that folder away" in res.stderr
    if name == ".course-manifest.json":
        assert f"{name} is a folder" in res.stderr
        # without the record, the untouched 1.1 cannot be told from an edit: kept, new beside
        assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 1"}'
        assert (dst / "ex1_1.course-update.ipynb").read_text() == '{"v": "course 2"}'
    else:
        assert (dst / "ex1_1.ipynb").read_text() == '{"v": "course 2"}'
    assert (dst / "ex1_2.ipynb").read_text() == '{"v": "my work on 1.2"}'
    assert (dst / "ex1_2.course-update.ipynb").read_text() == '{"v": "course 2 of 1.2"}'
    assert (dst / "ex1_3.ipynb").read_text() == '{"v": "new exercise"}'
    assert (dst / name).is_dir()


def test_a_symlinked_exercise_stays_a_link_and_its_file_is_never_written(tmp_path):
    src, dst = course_of_three(tmp_path)
    mine = tmp_path / "elsewhere" / "ex1_1.ipynb"
    mine.parent.mkdir()
    mine.write_text('{"v": "course 1"}')          # a link to a file with the untouched content
    (dst / "ex1_1.ipynb").unlink()
    (dst / "ex1_1.ipynb").symlink_to(mine)
    res = run_cli(src, dst)
    assert res.returncode == 0 and "Traceback" not in res.stderr
    assert (dst / "ex1_1.ipynb").is_symlink() and os.readlink(dst / "ex1_1.ipynb") == str(mine)
    assert mine.read_text() == '{"v": "course 1"}'
    assert (dst / "ex1_1.course-update.ipynb").read_text() == '{"v": "course 2"}'
    assert "kept your" in res.stdout and "ex1_1.ipynb" in res.stdout
    res = run_cli(src, dst)                        # and stays so
    assert (dst / "ex1_1.ipynb").is_symlink() and "up to date" in res.stdout


def test_a_link_to_the_course_file_and_a_dangling_link_are_kept(tmp_path):
    src, dst = course_of_three(tmp_path)
    (dst / "ex1_3.ipynb").symlink_to(src / "ex1_3.ipynb")                # follows the course
    (dst / "ex1_1.ipynb").unlink()
    (dst / "ex1_1.ipynb").symlink_to(tmp_path / "deleted.ipynb")         # points nowhere
    res = run_cli(src, dst)
    assert res.returncode == 0 and "Traceback" not in res.stderr
    assert (dst / "ex1_3.ipynb").is_symlink() and not (dst / "ex1_3.course-update.ipynb").exists()
    assert (dst / "ex1_1.ipynb").is_symlink() and not (tmp_path / "deleted.ipynb").exists()
    assert (dst / "ex1_1.course-update.ipynb").read_text() == '{"v": "course 2"}'
    assert "which does not exist" in res.stderr and "Remove the link" in res.stderr
    (src / "ex1_3.ipynb").write_text('{"v": "new exercise, corrected"}')
    run_cli(src, dst)
    assert (dst / "ex1_3.ipynb").is_symlink() and not (dst / "ex1_3.course-update.ipynb").exists()


def test_a_kernel_marking_notices_as_shown_while_sync_runs_loses_neither(tmp_path):
    """The notices file has two writers: the sync adds notices, a kernel (start page, progress
    widget) marks them shown. A kernel holding the lock mid-update: the sync waits, then adds its
    notice to what the kernel wrote, so neither the new notice nor the "shown" mark is lost."""
    from filelock import FileLock
    src = make_course(tmp_path)
    (src / "ex1_2.ipynb").write_text('{"v": "1.2 course 1"}')
    dst = tmp_path / "workspace"
    run(src, dst)
    (dst / "ex1_1.ipynb").write_text("mine")
    (dst / "ex1_2.ipynb").write_text("mine too")
    (src / "ex1_1.ipynb").write_text("course 2")
    run(src, dst)                                     # notice for 1.1, not yet shown
    notices = dst / ".course-notices.json"
    [n11] = json.loads(notices.read_text())
    (src / "ex1_2.ipynb").write_text("1.2 course 2")
    with FileLock(str(notices) + ".lock", timeout=5):          # the kernel, mid-update
        proc = subprocess.Popen([sys.executable, str(SCRIPT), "--exercises", str(src), "--workspace", str(dst)],
                                stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(2.0)                               # the sync waits for the kernel
        assert proc.poll() is None and not (dst / "ex1_2.course-update.ipynb").exists()
        notices.write_text(json.dumps([dict(n11, seen=True)]))  # the kernel's write
    out, err = proc.communicate(timeout=60)
    assert proc.returncode == 0 and not err
    saved = {n["new_version"]: n["seen"] for n in json.loads(notices.read_text())}
    assert saved == {"ex1_1.course-update.ipynb": True, "ex1_2.course-update.ipynb": False}

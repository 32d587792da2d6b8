"""tools/sync_workspace.py (run by `make lab`): course updates never cost the student any work."""
import importlib.util
import json
import subprocess
import sys
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
    from gm_core.checks import _progress
    monkeypatch.setenv("GM_COURSE_WORKSPACE", str(dst))
    pending = _progress.pending_updates(mark_seen=True)
    assert pending == [{"file": "ex1_1.ipynb", "new_version": "ex1_1.course-update.ipynb", "seen": False}]
    assert _progress.pending_updates() == []
    # a second update replaces the untouched beside file, and is announced again
    (src / "ex1_1.ipynb").write_text('{"v": "course 3"}')
    run(src, dst)
    assert (dst / "ex1_1.ipynb").read_bytes() == mine
    assert (dst / "ex1_1.course-update.ipynb").read_text() == '{"v": "course 3"}'
    assert len(_progress.pending_updates()) == 1
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
    from gm_core.checks import _progress
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
        assert [n["file"] for n in _progress.pending_updates()] == ["ex1_1.ipynb"]
        if damage == "corrupt":
            assert (dst / ".course-manifest.json.corrupt").read_text() == "{not json"
        (dst / ".course-notices.json").unlink()          # notices file lost as well
        assert [n["file"] for n in _progress.pending_updates()] == ["ex1_1.ipynb"]


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

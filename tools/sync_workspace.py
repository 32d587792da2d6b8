"""Bring the student's personal, git-ignored workspace/ up to date with the course. Never loses work.

Run by `make lab` (and `make workspace`). For every course file (the exercise notebooks of
exercises/, and tools/workspace_README.md as workspace/README.md):

* missing from workspace/            -> copied in (a new exercise, or one you deleted to start afresh);
* unchanged by you since it was copied, and the course has a newer version
                                     -> replaced by the new version (nothing of yours is in it);
* edited by you, and the course has a newer version
                                     -> YOUR FILE IS KEPT, byte for byte; the new version is written
                                        beside it as ``<name>.course-update.ipynb``, and a notice is
                                        recorded that the start page and progress_widget() show once
                                        inside JupyterLab (and this script prints).

The manifest ``workspace/.course-manifest.json`` remembers which course version of each file was
copied (its sha256). If it is missing or unreadable (a corrupt one is kept aside as
``.course-manifest.json.corrupt``), a file that differs from the course is treated as edited: kept,
with the new version beside it. Notices live in ``workspace/.course-notices.json``; every write is
atomic (temporary file + rename).

    python tools/sync_workspace.py [--exercises DIR] [--workspace DIR] [--readme FILE] [--quiet]
"""
from __future__ import annotations

import argparse
import hashlib
import json
import os
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MANIFEST = ".course-manifest.json"
NOTICES = ".course-notices.json"
BESIDE = ".course-update"
SKIP_PARTS = {".ipynb_checkpoints", "__pycache__"}
README_TEMPLATE = ROOT / "tools" / "workspace_README.md"


def _digest_bytes(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _digest(path: Path) -> str:
    return _digest_bytes(path.read_bytes())


def _atomic_write(path: Path, data: bytes):
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def _write_json(path: Path, data):
    _atomic_write(path, (json.dumps(data, indent=1, sort_keys=True) + "\n").encode("utf-8"))


def course_files(src: Path, readme: Path | None = README_TEMPLATE):
    """{relative path in the workspace: source path} for every course file."""
    out = {}
    for path in sorted(src.rglob("*")):
        rel = path.relative_to(src)
        if not path.is_file() or SKIP_PARTS.intersection(rel.parts) or any(
                p.startswith(".") for p in rel.parts):
            continue
        if rel.as_posix() == "README.md" and readme is not None:
            continue  # exercises/README.md is for the course folder; the workspace gets its own
        out[rel.as_posix()] = path
    if readme is not None and Path(readme).is_file():
        out["README.md"] = Path(readme)
    return out


def read_manifest(dst: Path):
    """(files {rel: digest}, beside {rel: digest}, ok). A corrupt manifest is kept aside."""
    path = dst / MANIFEST
    if not path.exists():
        return {}, {}, False
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        if not isinstance(data, dict):
            raise ValueError("not an object")
    except (OSError, ValueError):
        try:
            shutil.copy2(path, dst / (MANIFEST + ".corrupt"))
        except OSError:
            pass
        return {}, {}, False
    if "files" in data and isinstance(data["files"], dict):
        files, beside = data["files"], data.get("beside", {})
    else:  # version 1: a flat {rel: digest}
        files, beside = data, {}
    files = {k: v for k, v in files.items() if isinstance(k, str) and isinstance(v, str)}
    beside = {k: v for k, v in beside.items() if isinstance(k, str) and isinstance(v, str)} \
        if isinstance(beside, dict) else {}
    return files, beside, True


def read_notices(dst: Path):
    try:
        data = json.loads((dst / NOTICES).read_text(encoding="utf-8"))
        return [n for n in data if isinstance(n, dict) and isinstance(n.get("new_version"), str)]
    except (OSError, ValueError, TypeError):
        return []


def _beside_path(dst: Path, rel: str, new_digest: str, beside: dict) -> Path | None:
    """Where to write the new version next to the student's file (None: it is already there)."""
    target = dst / rel
    stem, suffix = target.name[: -len(target.suffix)] if target.suffix else target.name, target.suffix
    for k in range(1, 100):
        name = f"{stem}{BESIDE}{'' if k == 1 else f'-{k}'}{suffix}"
        cand = target.parent / name
        key = cand.relative_to(dst).as_posix()
        if not cand.exists():
            return cand
        cur = _digest(cand)
        if cur == new_digest:
            return None
        if beside.get(key) == cur:  # an older course update the student has not touched
            return cand
    raise RuntimeError(f"too many course updates beside {rel}")


def sync(src: Path, dst: Path, readme: Path | None = README_TEMPLATE):
    """Bring ``dst`` up to date with ``src``. Returns a dict of lists of workspace paths:
    ``copied``, ``updated`` (untouched copies replaced), ``kept`` ([(your file, new version)])."""
    src, dst = Path(src), Path(dst)
    if not src.is_dir():
        raise FileNotFoundError(f"no exercises folder at {src}")
    dst.mkdir(parents=True, exist_ok=True)
    files, beside, _ok = read_manifest(dst)
    notices = read_notices(dst)
    report = {"copied": [], "updated": [], "kept": []}
    for rel, source in course_files(src, readme).items():
        data = source.read_bytes()
        new = _digest_bytes(data)
        target = dst / rel
        if not target.exists():
            _atomic_write(target, data)
            files[rel] = new
            report["copied"].append(target)
            continue
        cur = _digest(target)
        if cur == new:
            files[rel] = new
            continue
        known = files.get(rel)
        if known is not None and cur == known:
            _atomic_write(target, data)  # the student never changed it: take the new version
            files[rel] = new
            report["updated"].append(target)
            continue
        if known == new:
            continue  # the student edited the current course version: nothing new to announce
        where = _beside_path(dst, rel, new, beside)
        if where is not None:
            _atomic_write(where, data)
            key = where.relative_to(dst).as_posix()
            beside[key] = new
            notices = [n for n in notices if n.get("new_version") != key]
            notices.append({"file": rel, "new_version": key, "seen": False})
            report["kept"].append((target, where))
        files[rel] = new
    _write_json(dst / NOTICES, notices)
    _write_json(dst / MANIFEST, {"version": 2, "files": files, "beside": beside})
    return report


def main(argv=None):
    ap = argparse.ArgumentParser(description="Bring workspace/ up to date with the course; never loses work.")
    ap.add_argument("--exercises", type=Path, default=ROOT / "exercises")
    ap.add_argument("--workspace", type=Path, default=ROOT / "workspace")
    ap.add_argument("--readme", type=Path, default=README_TEMPLATE)
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    try:
        report = sync(args.exercises, args.workspace, args.readme)
    except FileNotFoundError as exc:
        print(f"workspace: {exc}", file=sys.stderr)
        return 1
    say = (lambda *a: None) if args.quiet else print

    def show(p):
        try:
            return p.relative_to(Path.cwd())
        except ValueError:
            return p

    for p in report["copied"]:
        say(f"workspace: added {show(p)}")
    for p in report["updated"]:
        say(f"workspace: updated {show(p)} to the course's new version (you had not changed it)")
    for mine, new in report["kept"]:
        say(f"workspace: kept your {show(mine)} as it is; the course's newer version is beside it: "
            f"{show(new)} (the start page lists it too)")
    if not any(report.values()):
        say("workspace: up to date (your files are never overwritten)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

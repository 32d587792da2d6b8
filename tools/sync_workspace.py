"""Copy exercises/ into the student's personal, git-ignored workspace/ folder.

Run by `make lab` (and `make workspace`). A file that already exists in workspace/ is never
touched, so a student's work survives every re-run and every course update; exercises added by an
update are copied in. When the course changes an exercise the student already has, the student's
copy is still kept and a notice names the new version in exercises/ (a small manifest,
``workspace/.course-manifest.json``, remembers which version of each file was copied). To start an
exercise afresh, delete your copy and run `make workspace` again.

    python tools/sync_workspace.py [--exercises DIR] [--workspace DIR] [--quiet]
"""
from __future__ import annotations

import argparse
import hashlib
import json
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MANIFEST = ".course-manifest.json"
SKIP_PARTS = {".ipynb_checkpoints", "__pycache__"}


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def _course_files(src: Path):
    for path in sorted(src.rglob("*")):
        rel = path.relative_to(src)
        if not path.is_file() or SKIP_PARTS.intersection(rel.parts) or any(
                p.startswith(".") for p in rel.parts):
            continue
        yield path, rel


def _read_manifest(dst: Path) -> dict:
    try:
        data = json.loads((dst / MANIFEST).read_text(encoding="utf-8"))
        return data if isinstance(data, dict) else {}
    except (OSError, ValueError):
        return {}


def sync(src: Path, dst: Path):
    """Copy every file under ``src`` that is missing from ``dst``; never overwrite.

    Returns ``(copied, updated)``: the files copied now, and the existing workspace files whose
    course version changed since they were copied (left untouched).
    """
    src, dst = Path(src), Path(dst)
    if not src.is_dir():
        raise FileNotFoundError(f"no exercises folder at {src}")
    manifest = _read_manifest(dst)
    copied, updated = [], []
    for path, rel in _course_files(src):
        key = rel.as_posix()
        target = dst / rel
        digest = _digest(path)
        if target.exists():
            if key in manifest and manifest[key] != digest:
                updated.append(target)
            manifest.setdefault(key, digest)
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, target)
        manifest[key] = digest
        copied.append(target)
    dst.mkdir(parents=True, exist_ok=True)
    (dst / MANIFEST).write_text(json.dumps(manifest, indent=1, sort_keys=True) + "\n", encoding="utf-8")
    return copied, updated


def main(argv=None):
    ap = argparse.ArgumentParser(description="Copy new exercises into workspace/ (never overwrites).")
    ap.add_argument("--exercises", type=Path, default=ROOT / "exercises")
    ap.add_argument("--workspace", type=Path, default=ROOT / "workspace")
    ap.add_argument("--quiet", action="store_true")
    args = ap.parse_args(argv)
    try:
        copied, updated = sync(args.exercises, args.workspace)
    except FileNotFoundError as exc:
        print(f"workspace: {exc}", file=sys.stderr)
        return 1
    say = (lambda *a: None) if args.quiet else print

    def show(p):
        try:
            return p.relative_to(Path.cwd())
        except ValueError:
            return p

    for p in copied:
        say(f"workspace: added {show(p)}")
    for p in updated:
        say(f"workspace: kept your {show(p)}; the course has a newer version at "
            f"{show(args.exercises / p.relative_to(args.workspace))} (delete your copy to take it)")
    if not copied and not updated:
        say("workspace: up to date (your files are never overwritten)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

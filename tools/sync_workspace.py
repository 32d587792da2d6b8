"""Copy exercises/ into the student's personal, git-ignored workspace/ folder.

Run by `make lab`. A file that already exists in workspace/ is never touched, so a student's
work survives every re-run and every course update; exercises added by an update are copied in.
"""
from __future__ import annotations

import shutil
import sys
from pathlib import Path


def sync(src: Path, dst: Path) -> list[Path]:
    """Copy every file under ``src`` that is missing from ``dst``; return the files copied."""
    copied = []
    for path in sorted(src.rglob("*")):
        if not path.is_file() or ".ipynb_checkpoints" in path.parts:
            continue
        target = dst / path.relative_to(src)
        if target.exists():
            continue
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, target)
        copied.append(target)
    return copied


def main(argv=None):
    root = Path(__file__).resolve().parent.parent
    copied = sync(root / "exercises", root / "workspace")
    for p in copied:
        print(f"workspace: added {p.relative_to(root)}")
    if not copied:
        print("workspace: up to date (your files are never overwritten)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

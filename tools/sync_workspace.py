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

It never stops halfway: a file that cannot be written (a read-only workspace, an immutable or
locked notebook, a full disk), a folder where a notebook or the manifest should be, or a link
pointing nowhere becomes a message naming the file and saying what to do, and every other file
is still brought up to date (an edited copy still gets its new version beside it). A file that
could not be updated keeps its old entry in the manifest, so the next run tries again. A
symlinked exercise stays a link: it is never written through or replaced; a newer course version
goes beside it.

    python tools/sync_workspace.py [--exercises DIR] [--workspace DIR] [--readme FILE] [--quiet]
"""
from __future__ import annotations

import argparse
import contextlib
import errno
import hashlib
import json
import os
import shutil
import sys
from pathlib import Path

from gm_core.checks.files import atomic_write

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
    atomic_write(path, data)


def _lock(path: Path, timeout: float = 15.0):
    """The lock the course's kernels take on ``path`` (gm_core.checks.store: filelock on
    ``<path>.lock``). filelock comes with the [lab] extra that `make lab` installs; without it the
    write is still atomic, only not serialised with a kernel marking notices as shown."""
    try:
        from filelock import FileLock
    except ImportError:
        return contextlib.nullcontext()
    return FileLock(f"{path}.lock", timeout=timeout)


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


def read_manifest(dst: Path, problems: list | None = None):
    """(files {rel: digest}, beside {rel: digest}, ok). A corrupt manifest is kept aside."""
    path = dst / MANIFEST
    if path.is_dir() and not path.is_symlink():
        if problems is not None:
            problems.append((path, "is a folder, where the course keeps its record of which versions "
                                   "you have. Move that folder somewhere else and run this again; "
                                   "until then every file that differs from the course is treated as "
                                   "yours (kept, the new version written beside it)."))
        return {}, {}, False
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
    """Where to write the new version next to the student's file (None: it is already there).
    Never a folder, never a link, never a file the student has changed."""
    target = dst / rel
    stem, suffix = target.name[: -len(target.suffix)] if target.suffix else target.name, target.suffix
    for k in range(1, 100):
        name = f"{stem}{BESIDE}{'' if k == 1 else f'-{k}'}{suffix}"
        cand = target.parent / name
        key = cand.relative_to(dst).as_posix()
        if cand.is_symlink() or cand.is_dir():
            continue
        if not cand.exists():
            return cand
        cur = _digest(cand)
        if cur == new_digest:
            return None
        if beside.get(key) == cur:  # an older course update the student has not touched
            return cand
    raise RuntimeError(f"too many course updates beside {rel}")


def _as(where: Path | None) -> str:
    return f" as {where.name}" if where is not None else " (written there by an earlier run)"


def _why(exc: BaseException) -> str:
    text = getattr(exc, "strerror", None) or str(exc) or type(exc).__name__
    return f"{type(exc).__name__}: {text}"


def _what_to_do(exc: BaseException) -> str:
    """What the student can do about ``exc``, as the end of a sentence starting "To fix it, "."""
    if isinstance(exc, OSError) and exc.errno in (errno.EROFS, errno.EACCES, errno.EPERM):
        return ("make the workspace (and this file) writable again - `chmod -R u+w workspace`, or "
                "remount it read-write, or `chattr -i` an immutable file - and run `make workspace` "
                "again")
    if isinstance(exc, OSError) and exc.errno == errno.ENOSPC:
        return "free some disk space and run `make workspace` again"
    return ("close any program that holds the file, check that it can be written, and run "
            "`make workspace` again")


def sync(src: Path, dst: Path, readme: Path | None = README_TEMPLATE):
    """Bring ``dst`` up to date with ``src``. Returns a dict of lists of workspace paths:
    ``copied``, ``updated`` (untouched copies replaced), ``kept`` ([(your file, new version)]),
    ``problems`` ([(path, what went wrong and what to do)]). A problem with one file never stops
    the others, and never costs a file of yours."""
    src, dst = Path(src), Path(dst)
    if not src.is_dir():
        raise FileNotFoundError(f"no exercises folder at {src}")
    report = {"copied": [], "updated": [], "kept": [], "problems": []}
    problems = report["problems"]
    try:
        dst.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        problems.append((dst, f"the workspace folder could not be made ({_why(exc)}); "
                              f"{_what_to_do(exc)}."))
        return report
    with contextlib.ExitStack() as held:
        try:     # kernels marking notices as shown wait until this run has added its own
            held.enter_context(_lock(dst / NOTICES))
        except OSError:
            pass  # a read-only workspace: each write below reports its own problem
        return _sync(src, dst, readme, report)


def _sync(src: Path, dst: Path, readme: Path | None, report: dict):
    problems = report["problems"]
    files, beside, _ok = read_manifest(dst, problems)
    fresh = []                     # this run's new notices, added to the file at the end

    def beside_copy(rel, target, data, new, announce=True):
        where = _beside_path(dst, rel, new, beside)
        if where is not None:
            _atomic_write(where, data)
            key = where.relative_to(dst).as_posix()
            beside[key] = new
            fresh.append({"file": rel, "new_version": key, "seen": False})
            if announce:
                report["kept"].append((target, where))
        return where

    for rel, source in course_files(src, readme).items():
        target = dst / rel
        try:
            data = source.read_bytes()
        except OSError as exc:
            problems.append((source, f"the course file could not be read ({_why(exc)}); "
                                     "your workspace copy is unchanged."))
            continue
        new = _digest_bytes(data)
        try:
            if target.is_symlink():
                # a link the student made: kept as a link, never written through or over
                if target.exists() and _digest(target) == new:
                    files[rel] = new
                    continue
                if files.get(rel) == new and target.exists():
                    continue  # the linked file is their edit of the current version
                where = beside_copy(rel, target, data, new, announce=target.exists())
                if not target.exists():
                    problems.append((target, f"is a link to {os.readlink(target)}, which does not "
                                             "exist. The link is kept; the course's version is "
                                             f"beside it{_as(where)}. "
                                             "Remove the link to get a fresh copy next time."))
                files[rel] = new
                continue
            if target.is_dir():
                where = beside_copy(rel, target, data, new, announce=False)
                problems.append((target, "is a folder, where this exercise notebook should be. Your "
                                         f"folder is kept; the notebook is beside it{_as(where)}. "
                                         "Rename or move the "
                                         "folder and run `make workspace` again to get it in place."))
                files[rel] = new
                continue
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
                try:
                    _atomic_write(target, data)  # the student never changed it: the new version
                except OSError as exc:
                    problems.append((target, f"could not be replaced by the course's new version "
                                             f"({_why(exc)}); it is unchanged. To get the update, "
                                             f"{_what_to_do(exc)}."))
                    continue                     # the manifest keeps the old version: retried
                files[rel] = new
                report["updated"].append(target)
                continue
            if known == new:
                continue  # the student edited the current course version: nothing new to announce
            beside_copy(rel, target, data, new)
            files[rel] = new
        except (OSError, RuntimeError) as exc:
            problems.append((target, f"could not be brought up to date ({_why(exc)}); your file is "
                                     f"unchanged. To fix it, {_what_to_do(exc)}."))
    def add_notices(path):
        keys = {n["new_version"] for n in fresh}
        _write_json(path, [n for n in read_notices(dst) if n["new_version"] not in keys] + fresh)

    for name, write, what in (
            (NOTICES, add_notices, "the list of course updates to show you (the start page "
                                   "still finds the *.course-update* files)"),
            (MANIFEST, lambda path: _write_json(path, {"version": 2, "files": files, "beside": beside}),
             "the record of which course versions you have (next time, files that differ from "
             "the course are treated as yours: kept, the new version beside)")):
        path = dst / name
        try:
            if path.is_dir() and not path.is_symlink():
                raise IsADirectoryError(errno.EISDIR, "a folder stands where the file should be")
            write(path)
        except OSError as exc:
            todo = ("move that folder away and run `make workspace` again"
                    if isinstance(exc, IsADirectoryError) else _what_to_do(exc))
            problems.append((path, f"could not be saved ({_why(exc)}): {what}. To fix it, {todo}."))
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
    for path, text in report["problems"]:
        print(f"workspace: PROBLEM: {show(path)} {text}", file=sys.stderr)
    if report["problems"]:
        print(f"workspace: {len(report['problems'])} problem(s) above; every other file was brought "
              "up to date, and no file of yours was changed or lost.", file=sys.stderr)
    elif not any(report.values()):
        say("workspace: up to date (your files are never overwritten)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

"""The progress record: the latest verdict of every part, kept where it lasts.

Four states per exercise: passed (every part passed), in progress (some parts passed, none failed
at its latest check), failed (the latest check of some part failed), unattempted.

Where it is kept: inside a student workspace (a folder holding ``.course-manifest.json``, made by
``tools/sync_workspace.py``; found from the kernel's working directory upwards, or named by the
environment variable ``GM_COURSE_WORKSPACE``) the record lives in ``<workspace>/.progress.json``,
written atomically (a temporary file renamed over the old one) and re-read before every change, so
every notebook of the workspace sees all exercises across kernels and restarts. Anywhere else (CI,
``solutions/``, ``exercises/``) it stays in this kernel's memory.

This module imports nothing from the rest of gm_core.checks (no import cycles).
"""
from __future__ import annotations

import json
import os
import tempfile
import time
from pathlib import Path

PASSED, FAILED, UNATTEMPTED, IN_PROGRESS = "passed", "failed", "unattempted", "in progress"
STATES = (PASSED, IN_PROGRESS, FAILED, UNATTEMPTED)
MANIFEST = ".course-manifest.json"
NOTICES = ".course-notices.json"
PROGRESS_FILE = ".progress.json"

#: {"1.4/a": {"status": ..., "solution_viewed": bool, "when": float}} when no workspace is in use.
_MEMORY: dict = {}


def find_workspace(start=None):
    """The student workspace this kernel runs in, or None (then progress stays in memory)."""
    env = os.environ.get("GM_COURSE_WORKSPACE")
    if env:
        p = Path(env)
        return p if p.is_dir() else None
    try:
        here = Path(start or os.getcwd()).resolve()
    except OSError:
        return None
    for d in (here, *here.parents):
        if (d / MANIFEST).is_file():
            return d
    return None


def course_workspace():
    """The repository's workspace/ folder (for the start page), or the one this kernel runs in."""
    ws = find_workspace()
    if ws is not None:
        return ws
    guess = Path(__file__).resolve().parents[2] / "workspace"
    return guess if (guess / MANIFEST).is_file() else None


def _read_json(path, default):
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return default
    return data if isinstance(data, type(default)) else default


def write_json_atomic(path, data):
    """Write JSON to ``path`` through a temporary file in the same folder and an atomic rename."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            json.dump(data, f, indent=1, sort_keys=True)
            f.write("\n")
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def _clean(data):
    out = {}
    for key, rec in data.items():
        if isinstance(key, str) and isinstance(rec, dict) and rec.get("status") in (PASSED, FAILED, UNATTEMPTED):
            out[key] = {"status": rec["status"], "solution_viewed": bool(rec.get("solution_viewed")),
                        "when": float(rec.get("when", 0) or 0)}
    return out


def load():
    """The whole record {"ex/part": {...}} (from the workspace file when there is one)."""
    ws = find_workspace()
    if ws is None:
        return dict(_MEMORY)
    return _clean(_read_json(ws / PROGRESS_FILE, {}))


def _update(key, **changes):
    ws = find_workspace()
    if ws is None:
        rec = dict(_MEMORY.get(key, {"status": UNATTEMPTED, "solution_viewed": False}))
        rec.update(changes, when=time.time())
        _MEMORY[key] = rec
        return
    try:
        data = _clean(_read_json(ws / PROGRESS_FILE, {}))
        rec = dict(data.get(key, {"status": UNATTEMPTED, "solution_viewed": False}))
        rec.update(changes, when=time.time())
        data[key] = rec
        write_json_atomic(ws / PROGRESS_FILE, data)
    except OSError:  # a read-only workspace: keep the record in memory rather than fail
        rec = dict(_MEMORY.get(key, {"status": UNATTEMPTED, "solution_viewed": False}))
        rec.update(changes, when=time.time())
        _MEMORY[key] = rec


def record(ex_id, part, status):
    _update(f"{ex_id}/{part}", status=status)


def record_solution_view(ex_id, part):
    _update(f"{ex_id}/{part}", solution_viewed=True)


def part_status(ex_id, part, data=None):
    data = load() if data is None else data
    return data.get(f"{ex_id}/{part}", {}).get("status", UNATTEMPTED)


def exercise_status(ex_id, parts, data=None):
    states = [part_status(ex_id, p, data) for p in parts]
    if any(s == FAILED for s in states):
        return FAILED
    if states and all(s == PASSED for s in states):
        return PASSED
    if any(s == PASSED for s in states):
        return IN_PROGRESS
    return UNATTEMPTED


def reset(confirm=True):
    """Forget every recorded check (in memory, and in the workspace's progress file if any)."""
    _MEMORY.clear()
    ws = find_workspace()
    if ws is not None and (ws / PROGRESS_FILE).exists():
        write_json_atomic(ws / PROGRESS_FILE, {})


# ------------------------------------------------------------------------------ course updates
def pending_updates(mark_seen=False):
    """Course updates of exercises the student had edited: [{"file", "new_version", ...}].

    Each entry names the student's kept file and the new course version written beside it.
    ``mark_seen=True`` marks them as shown (so the start page / progress widget show them once).
    Files named ``*.course-update*.ipynb`` on disk are always listed while unseen, even if the
    notice file was lost.
    """
    ws = course_workspace()
    if ws is None:
        return []
    notices = _read_json(ws / NOTICES, [])
    notices = [n for n in notices if isinstance(n, dict) and isinstance(n.get("new_version"), str)]
    known = {n["new_version"] for n in notices}
    for beside in sorted(ws.rglob("*.course-update*.ipynb")):
        rel = beside.relative_to(ws).as_posix()
        if rel not in known and ".ipynb_checkpoints" not in rel:
            stem = beside.name.split(".course-update")[0]
            notices.append({"file": (beside.parent.relative_to(ws) / (stem + ".ipynb")).as_posix(),
                            "new_version": rel, "seen": False})
    pending = [dict(n) for n in notices if not n.get("seen") and (ws / n["new_version"]).exists()]
    if mark_seen and pending:
        for n in notices:
            if n["new_version"] in {p["new_version"] for p in pending}:
                n["seen"] = True
        try:
            write_json_atomic(ws / NOTICES, notices)
        except OSError:
            pass
    return pending

"""The progress record: the latest verdict of every part, kept where it lasts, never lost.

Four states per exercise: passed (every part passed), in progress (some parts passed, none failed
at its latest check), failed (the latest check of some part failed), unattempted.

Where it is kept: inside a student workspace (a folder holding ``.course-manifest.json``, made by
``tools/sync_workspace.py``; found from the kernel's working directory upwards, or named by the
environment variable ``GM_COURSE_WORKSPACE``) the record lives in ``<workspace>/.progress.json``.
Anywhere else (CI, ``solutions/``, ``exercises/``) it stays in this kernel's memory.

How it is never lost:

* every change is a read-modify-write under a file lock (``filelock``, on
  ``.progress.json.lock``; the same ``flock`` without it), so kernels checking at the same moment
  never lose each other's parts;
  the new record is written to a temporary file, flushed to disk and renamed over the old one;
* a damaged or unreadable record (cut short, another encoding, not a JSON object, entries that
  make no sense) is moved aside as ``.progress.json.damaged-<date>-<time>`` (kept, never deleted),
  every entry that can still be read is kept, and the student is told once; odd fields (a
  ``"when"`` that is not a time) are tolerated, and nothing here raises into a check;
* when the workspace cannot be written (read-only, full disk), the student is told once, the
  verdicts are kept in this kernel's memory (``progress()`` shows them and says they are not
  saved) and written as soon as a later check can write again.

This module imports nothing from the rest of gm_core.checks (no import cycles).
"""
from __future__ import annotations

import codecs
import json
import math
import os
import re
import time
from collections.abc import Sequence
from contextlib import AbstractContextManager
from pathlib import Path
from typing import Any, TypeAlias, TypedDict, cast

from gm_core.checks.files import atomic_write

PASSED, FAILED, UNATTEMPTED, IN_PROGRESS = "passed", "failed", "unattempted", "in progress"
STATES = (PASSED, IN_PROGRESS, FAILED, UNATTEMPTED)
MANIFEST = ".course-manifest.json"
NOTICES = ".course-notices.json"
PROGRESS_FILE = ".progress.json"
LOCK_SUFFIX = ".lock"
DAMAGED_TAG = ".damaged-"
#: Seconds to wait for another kernel holding the lock before keeping the verdict in memory.
LOCK_TIMEOUT = 15.0


class PartRecord(TypedDict):
    """One part's record: its latest status, whether its solution was shown, when (time.time())."""

    status: str
    solution_viewed: bool
    when: float


class _Changes(TypedDict, total=False):
    status: str
    solution_viewed: bool


#: The whole record: {"1.4/a": PartRecord}.
Progress: TypeAlias = dict[str, PartRecord]


class Notice(TypedDict):
    """A course update (``tools/sync_workspace.py``): the student's kept ``file``, the course's
    ``new_version`` written beside it (paths in the workspace), and whether it was ``seen``."""

    file: str
    new_version: str
    seen: bool


#: The record when no workspace is in use.
_MEMORY: Progress = {}
#: {workspace path: {key: record}}: verdicts a workspace could not take yet (it was not writable).
_UNSAVED: dict[str, Progress] = {}
#: {workspace path: "why it could not be written"} while its record is not being saved.
_NOT_SAVED: dict[str, str] = {}
#: Messages already shown to the student in this kernel (each is shown once).
_TOLD: set[str] = set()


def find_workspace(start: str | os.PathLike[str] | None = None) -> Path | None:
    """The student workspace this kernel runs in, or None (then progress stays in memory)."""
    env = os.environ.get("GM_COURSE_WORKSPACE")
    try:
        if env:
            p = Path(env)
            return p if p.is_dir() else None
        here = Path(start or os.getcwd()).resolve()
    except (OSError, ValueError):
        return None
    for d in (here, *here.parents):
        try:
            if (d / MANIFEST).is_file():
                return d
        except OSError:
            continue
    return None


def course_workspace() -> Path | None:
    """The repository's workspace/ folder (for the start page), or the one this kernel runs in."""
    ws = find_workspace()
    if ws is not None:
        return ws
    guess = Path(__file__).resolve().parents[2] / "workspace"
    return guess if (guess / MANIFEST).is_file() else None


def _read_json(path: str | os.PathLike[str], default: Any) -> Any:
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return default
    return data if isinstance(data, type(default)) else default


def write_json_atomic(path: str | os.PathLike[str], data: object) -> None:
    """Write JSON to ``path`` atomically (gm_core.checks.files.atomic_write)."""
    atomic_write(path, json.dumps(data, indent=1, sort_keys=True) + "\n")


def _tell(key: str, text: str) -> None:
    """Tell the student something about their record, once per kernel."""
    if key in _TOLD:
        return
    _TOLD.add(key)
    try:
        print(f"Note about your progress record: {text}", flush=True)
    except Exception:  # noqa: BLE001 - a closed stdout must not break a check
        pass


# ------------------------------------------------------------------------------ reading, tolerantly
def _when(value: Any) -> float:
    """A record's time as a float; anything that is not a finite number of seconds becomes 0."""
    try:
        t = float(value)
    except (TypeError, ValueError, OverflowError):
        return 0.0
    return t if math.isfinite(t) else 0.0


def _flag(value: object) -> bool:
    if isinstance(value, str):
        return value.strip().lower() in ("true", "yes", "1")
    try:
        return bool(value)
    except Exception:  # noqa: BLE001 - a hostile __bool__
        return False


def _clean_record(key: object, rec: object) -> PartRecord | None:
    """A tidy record, or None when ``key``/``rec`` cannot be one (bad fields are tolerated)."""
    if not isinstance(key, str) or "/" not in key or not isinstance(rec, dict):
        return None
    status = rec.get("status", UNATTEMPTED if "solution_viewed" in rec else None)
    if status not in (PASSED, FAILED, UNATTEMPTED):
        return None
    return {"status": status, "solution_viewed": _flag(rec.get("solution_viewed")),
            "when": _when(rec.get("when", 0))}


def _clean(data: dict[Any, Any]) -> Progress:
    out: Progress = {}
    for key, rec in data.items():
        tidy = _clean_record(key, rec)
        if tidy is not None:
            out[key] = tidy
    return out


def _text(raw: bytes) -> tuple[str, bool]:
    """(text, plain UTF-8?) from the file's bytes, whatever encoding an editor gave it."""
    for bom, codec in ((codecs.BOM_UTF32_LE, "utf-32"), (codecs.BOM_UTF32_BE, "utf-32"),
                       (codecs.BOM_UTF8, "utf-8-sig"), (codecs.BOM_UTF16_LE, "utf-16"),
                       (codecs.BOM_UTF16_BE, "utf-16")):
        if raw.startswith(bom):
            try:
                return raw.decode(codec), False
            except UnicodeDecodeError:
                break
    if raw.count(b"\x00") > len(raw) // 4:        # UTF-16 without a byte-order mark
        for codec in ("utf-16-le", "utf-16-be"):
            try:
                text = raw.decode(codec)
            except UnicodeDecodeError:
                continue
            if text.lstrip()[:1] in ("{", "["):
                return text, False
    try:
        return raw.decode("utf-8"), True
    except UnicodeDecodeError:
        pass
    return raw.decode("latin-1"), False             # never fails: every byte is a character


_ENTRY = re.compile(r'"((?:[^"\\\n]|\\.){1,200})"\s*:\s*\{')


def _salvage(text: str) -> Progress:
    """Every ``"key": {record}`` that still parses, wherever it stands in a damaged text."""
    found: Progress = {}
    decoder = json.JSONDecoder()
    for m in _ENTRY.finditer(text):
        try:
            key = json.loads(f'"{m.group(1)}"')
            rec, _end = decoder.raw_decode(text, m.end() - 1)
        except (ValueError, RecursionError):
            continue
        tidy = _clean_record(key, rec)
        if tidy is not None:
            found[key] = tidy
    return found


def parse_record(raw: bytes) -> tuple[Progress, str | None]:
    """(entries, problem) from the bytes of a progress file: ``problem`` is None for a sound file,
    otherwise a short description of the damage (the entries are then what could be salvaged)."""
    if not raw.strip():
        return {}, None                 # an empty file holds nothing to lose
    text, plain = _text(raw)
    try:
        data = json.loads(text)
    except RecursionError:
        return _salvage(text), "it is nested too deeply to read"
    except ValueError:
        return _salvage(text), "it is not complete JSON (cut short or edited by hand)"
    if isinstance(data, dict):
        tidy = _clean(data)
        if len(tidy) < len(data):
            bad = len(data) - len(tidy)
            return tidy, f"{bad} of its {len(data)} entries could not be read"
        if not plain:
            return tidy, "it was saved in another text encoding"
        return tidy, None
    if isinstance(data, list):     # e.g. [{"1.1/a": {...}}, ...]: keep every record in it
        return _salvage(text), "it holds a list, not a record"
    return {}, f"it holds a {type(data).__name__}, not a record"


def _aside_name(path: Path) -> Path:
    stamp = time.strftime("%Y%m%d-%H%M%S")
    for k in range(1, 1000):
        cand = path.with_name(f"{path.name}{DAMAGED_TAG}{stamp}{'' if k == 1 else f'-{k}'}")
        if not cand.exists():
            return cand
    raise OSError("too many damaged progress files kept aside")


def _read_file(ws: Path, fix: bool) -> tuple[Progress, bool]:
    """The workspace's record; returns (entries, damaged: bool). A damaged or unreadable file (or
    a folder in its place) is moved aside, kept, when ``fix`` (under the lock): the entries that
    could be read go into a new file, and the student is told."""
    path = ws / PROGRESS_FILE
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        return {}, False
    except IsADirectoryError:
        entries: Progress = {}
        problem: str | None = "it is a folder, not a file"
    except OSError as exc:
        entries, problem = {}, f"it cannot be read: {type(exc).__name__}, {exc.strerror or exc}"
    else:
        entries, problem = parse_record(raw)
    if problem is None:
        return entries, False
    if fix:
        aside = _aside_name(path)
        os.replace(path, aside)     # kept as it was, byte for byte; the salvaged record follows
        write_json_atomic(path, entries)
        _tell(f"damaged:{aside}",
              f"{path.name} in {ws} was damaged ({problem}). It is kept unchanged as {aside.name}, "
              f"and the {len(entries)} part verdict(s) that could still be read are kept in a new "
              f"{path.name}. Nothing to do; re-run a check cell if one of your parts is missing.")
    return entries, True


class _Flock:
    """The same lock as filelock's on POSIX (``flock`` on the same file), for a bare ``pip install
    .`` without the [lab] extra; without fcntl (Windows) only the atomic write remains."""

    def __init__(self, path: str, timeout: float) -> None:
        self.path, self.timeout = path, timeout
        self.fd: int | None = None

    def __enter__(self) -> _Flock:
        try:
            import fcntl
        except ImportError:
            return self
        self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        deadline = time.monotonic() + self.timeout
        while True:
            try:
                fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                return self
            except BlockingIOError:
                if time.monotonic() > deadline:
                    os.close(self.fd)
                    raise TimeoutError(f"another kernel holds {self.path}") from None
                time.sleep(0.01)

    def __exit__(self, *exc: object) -> None:
        if self.fd is not None:
            os.close(self.fd)            # closing the file releases the lock


def _lock(ws: Path, name: str = PROGRESS_FILE) -> AbstractContextManager[object]:
    path = str(ws / (name + LOCK_SUFFIX))
    try:
        from filelock import FileLock
    except ImportError:
        return _Flock(path, LOCK_TIMEOUT)
    return FileLock(path, timeout=LOCK_TIMEOUT)


def _merge(data: Progress, extra: Progress) -> Progress:
    """``data`` updated with every record of ``extra`` that is at least as recent."""
    for key, rec in extra.items():
        if key not in data or rec.get("when", 0) >= data[key].get("when", 0):
            data[key] = rec.copy()
    return data


def load() -> Progress:
    """The whole record {"ex/part": {...}} (from the workspace file when there is one)."""
    ws = find_workspace()
    if ws is None:
        return {k: v.copy() for k, v in _MEMORY.items()}
    key = str(ws)
    try:
        data, damaged = _read_file(ws, fix=False)
        if damaged:                       # fix it under the lock (another kernel may be at it too)
            try:
                with _lock(ws):
                    data, _ = _read_file(ws, fix=True)
            except OSError as exc:
                _not_saved(ws, exc)
    except Exception:  # noqa: BLE001 - reading progress must never break a notebook
        data = {}
    return _merge(data, _UNSAVED.get(key, {}))


def _not_saved(ws: Path, exc: BaseException) -> None:
    key = str(ws)
    why = f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__
    _NOT_SAVED[key] = why
    _tell(f"unsaved:{key}",
          f"it cannot be saved in {ws} ({why}). Your verdicts are kept in this kernel's memory "
          "(progress() shows them) but will be gone when the kernel stops. Make the workspace "
          "folder writable (or free some disk space) and run a check again: it is then saved.")


def _new_record(old: PartRecord | None, changes: _Changes) -> PartRecord:
    rec: PartRecord = old.copy() if old else {"status": UNATTEMPTED, "solution_viewed": False, "when": 0.0}
    rec.update(changes)
    rec["when"] = time.time()
    return rec


def _update(key: str, changes: _Changes) -> None:
    """Change one part's record. Never raises (a verdict is never lost to a bookkeeping error)."""
    try:
        _save(key, changes)
    except Exception:  # noqa: BLE001 - last resort: this kernel's memory still has it
        ws = find_workspace()
        kept = _MEMORY if ws is None else _UNSAVED.setdefault(str(ws), {})
        kept[key] = _new_record(kept.get(key), changes)


def _save(key: str, changes: _Changes) -> None:
    ws = find_workspace()
    if ws is None:
        _MEMORY[key] = _new_record(_MEMORY.get(key), changes)
        return
    wkey = str(ws)
    pending = _UNSAVED.setdefault(wkey, {})
    try:
        with _lock(ws):
            data, _ = _read_file(ws, fix=True)
            _merge(data, pending)                 # what an earlier, failed write could not save
            data[key] = _new_record(data.get(key), changes)
            write_json_atomic(ws / PROGRESS_FILE, data)
    except Exception as exc:  # noqa: BLE001 - read-only workspace, full disk, lock timeout, ...
        base = _merge(_safe_file(ws), pending).get(key)
        pending[key] = _new_record(base, changes)
        _not_saved(ws, exc)
        return
    _UNSAVED.pop(wkey, None)
    if _NOT_SAVED.pop(wkey, None) is not None:
        _TOLD.discard(f"unsaved:{wkey}")
        _tell(f"saved:{wkey}:{time.time()}", f"it is saved again in {ws / PROGRESS_FILE}, "
                                             "including the verdicts kept in memory.")


def _safe_file(ws: Path) -> Progress:
    try:
        return _read_file(ws, fix=False)[0]
    except Exception:  # noqa: BLE001
        return {}


def not_saved() -> str | None:
    """Why this kernel's progress is not being saved in its workspace, or None when it is."""
    ws = find_workspace()
    return None if ws is None else _NOT_SAVED.get(str(ws))


def record(ex_id: str, part: str, status: str) -> None:
    """Record the latest verdict of part ``part`` of exercise ``ex_id``."""
    _update(f"{ex_id}/{part}", {"status": status})


def record_solution_view(ex_id: str, part: str) -> None:
    """Record that the solution of the part was shown."""
    _update(f"{ex_id}/{part}", {"solution_viewed": True})


def part_status(ex_id: str, part: str, data: Progress | None = None) -> str:
    """The latest status of the part (in ``data``, or the record loaded now)."""
    data = load() if data is None else data
    rec = data.get(f"{ex_id}/{part}")
    return UNATTEMPTED if rec is None else rec.get("status", UNATTEMPTED)


def exercise_status(ex_id: str, parts: Sequence[str], data: Progress | None = None) -> str:
    """passed / in progress / failed / unattempted, from the latest status of each of ``parts``."""
    states = [part_status(ex_id, p, data) for p in parts]
    if any(s == FAILED for s in states):
        return FAILED
    if states and all(s == PASSED for s in states):
        return PASSED
    if any(s == PASSED for s in states):
        return IN_PROGRESS
    return UNATTEMPTED


def reset(confirm: bool = True) -> None:
    """Forget every recorded check (in memory, and in the workspace's progress file if any)."""
    _MEMORY.clear()
    _UNSAVED.clear()
    _NOT_SAVED.clear()
    _TOLD.clear()
    ws = find_workspace()
    if ws is None or not (ws / PROGRESS_FILE).exists():
        return
    try:
        with _lock(ws):
            write_json_atomic(ws / PROGRESS_FILE, {})
    except OSError as exc:
        _tell(f"reset:{ws}", f"it could not be reset in {ws} ({type(exc).__name__}); the saved "
                             "verdicts are still there.")


# ------------------------------------------------------------------------------ course updates
def pending_updates(mark_seen: bool = False) -> list[Notice]:
    """Course updates of exercises the student had edited: [{"file", "new_version", ...}].

    Each entry names the student's kept file and the new course version written beside it.
    ``mark_seen=True`` marks them as shown (so the start page / progress widget show them once).
    Files named ``*.course-update*.ipynb`` on disk are always listed while unseen, even if the
    notice file was lost.
    """
    try:
        return _pending_updates(mark_seen)
    except Exception:  # noqa: BLE001 - a listing problem must not break the start page
        return []


def _pending_updates(mark_seen: bool) -> list[Notice]:
    ws = course_workspace()
    if ws is None:
        return []
    if not mark_seen:
        return _listed(ws)[1]
    try:     # read, mark and write under the lock tools/sync_workspace.py takes to add notices
        with _lock(ws, NOTICES):
            notices, pending = _listed(ws)
            if pending:
                shown = {p["new_version"] for p in pending}
                for n in notices:
                    if n["new_version"] in shown:
                        n["seen"] = True
                write_json_atomic(ws / NOTICES, notices)
            return pending
    except OSError:       # a read-only workspace: they are shown again next time
        return _listed(ws)[1]


def _listed(ws: Path) -> tuple[list[Notice], list[Notice]]:
    """(every notice, the unseen ones whose new version is still there)."""
    # the sync tool's notices: kept if they name their new version; their other fields as written
    notices: list[Notice] = [cast(Notice, n) for n in _read_json(ws / NOTICES, [])
                             if isinstance(n, dict) and isinstance(n.get("new_version"), str)]
    known = {n["new_version"] for n in notices}
    for beside in sorted(ws.rglob("*.course-update*.ipynb")):
        rel = beside.relative_to(ws).as_posix()
        if rel not in known and ".ipynb_checkpoints" not in rel:
            stem = beside.name.split(".course-update")[0]
            notices.append({"file": (beside.parent.relative_to(ws) / (stem + ".ipynb")).as_posix(),
                            "new_version": rel, "seen": False})
    pending = [n.copy() for n in notices if not n.get("seen") and (ws / n["new_version"]).exists()]
    return notices, pending

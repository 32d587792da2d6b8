"""Process trees for the probe sandbox (:mod:`gm_core.checks.sandbox`): keep every descendant findable, and end
them all. Linux gives the exact tree (``/proc/<pid>/task/<tid>/children``, or a scan of
``/proc/*/stat``, plus ``PR_SET_CHILD_SUBREAPER`` so that orphans stay in it); elsewhere the
keeper's process group is killed. Standard library only; no gm_core imports.

Two subreapers, so that nothing a probe starts can leave the tree: the keeper (everything below
it), and, while a check runs, the checking process itself (:class:`Adoption`). A probe that kills
its keeper and then calls ``setsid`` is out of the keeper's tree, process group and session, but
as an orphan it becomes a child of the checking process, which finds it there (a child born after
the keeper that is not the keeper) and ends it with everything below it.
"""
from __future__ import annotations

import ctypes
import os
import signal
import threading
import time
from typing import ClassVar

PR_SET_CHILD_SUBREAPER = 36
PR_GET_CHILD_SUBREAPER = 37
try:  # loaded now, not in a freshly forked process (the loader's lock may be held there)
    _LIBC = ctypes.CDLL(None, use_errno=True) if os.name == "posix" else None
except Exception:  # noqa: BLE001
    _LIBC = None


def _prctl(option: int, arg: object) -> int | None:
    """libc's ``prctl(option, arg, 0, 0, 0)``; None where there is none (no libc, not Linux)."""
    if _LIBC is None:
        return None
    try:
        return int(_LIBC.prctl(option, arg, 0, 0, 0))
    except (OSError, AttributeError):
        return None


def become_subreaper() -> None:
    """Orphans of this process's descendants become its children, not init's (Linux >= 3.4)."""
    _prctl(PR_SET_CHILD_SUBREAPER, 1)


def _is_subreaper() -> bool | None:
    flag = ctypes.c_int(0)
    if _prctl(PR_GET_CHILD_SUBREAPER, ctypes.byref(flag)) != 0:
        return None
    return bool(flag.value)


def _start_time(pid: int) -> int | None:
    """The start time of ``pid`` in clock ticks since boot (field 22 of /proc/<pid>/stat)."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as f:
            return int(f.read().rsplit(")", 1)[1].split()[19])
    except (OSError, ValueError, IndexError):
        return None


def _ticks_now() -> int | None:
    """Now, in the clock of /proc/<pid>/stat's start times (clock ticks since boot)."""
    try:
        with open("/proc/uptime", encoding="ascii") as f:
            return int(float(f.read().split()[0]) * os.sysconf("SC_CLK_TCK"))
    except (OSError, ValueError, IndexError):
        return None


class Adoption:
    """While a check runs, the checking process is a child subreaper too (Linux), so that an
    orphan of the probe tree -- its keeper killed -- becomes *our* child and cannot get away.

    ``start()`` before forking the keeper (it records the children there are), ``fork()`` to
    fork it (registered, so no other check takes it for a stray), ``close_window()`` when the
    check is over (a child born later is the notebook's own, however late the reaper runs),
    ``end_strays()`` kills every child born since then that is not the keeper, with all
    below it, and reaps it; ``release()`` turns the subreaper off again once no check needs it.
    Counted, so that checks in several threads share it; a process that was a subreaper already
    (a course tool, the grader's runner) stays one. The one thing taken for a stray wrongly: a
    process that another thread of the notebook starts *while* a check runs (children from
    before the check, and from after it, are never touched)."""

    _lock: ClassVar[threading.Lock] = threading.Lock()
    _users: ClassVar[int] = 0
    _was: ClassVar[bool | None] = None
    _keepers: ClassVar[set[int]] = set()

    def __init__(self) -> None:
        self.before: set[int] = set()
        self.keeper: int | None = None
        self.since: int | None = None
        self.active = False
        self.until: int | None = None

    def close_window(self) -> None:
        """The check is over: a child born from now on is the notebook's own, never a stray."""
        self.until = _ticks_now()

    def start(self) -> Adoption:
        """Make this process a subreaper while the check runs (counted); record its children now."""
        cls = type(self)
        with cls._lock:
            if cls._users == 0:
                cls._was = _is_subreaper()
                if cls._was is False:
                    become_subreaper()
            if cls._was is not None:
                cls._users += 1
                self.active = True
        if self.active:
            self.before = set(_children(os.getpid()) or [])
        return self

    def fork(self) -> int:
        """``os.fork()``, the child registered as a keeper (never taken for a stray by any check)."""
        cls = type(self)
        with cls._lock:
            pid = os.fork()
            if pid:
                cls._keepers.add(pid)
                self.keeper, self.since = pid, _start_time(pid)
        if pid == 0:   # the keeper: a lock of its own (the copy is held), no checks of its own yet
            cls._lock, cls._users, cls._was, cls._keepers = threading.Lock(), 0, None, set()
        return pid

    def keeper_reaped(self) -> None:
        """The keeper is reaped: its pid may be reused, so it is no keeper any more."""
        with type(self)._lock:
            type(self)._keepers.discard(self.keeper)

    def _strays(self) -> list[int]:
        if not self.active or self.since is None:
            return []
        out = []
        with type(self)._lock:
            for p in _children(os.getpid()) or []:
                if p in type(self)._keepers or p in self.before:
                    continue
                born = _start_time(p)
                if born is not None and born >= self.since and (
                        self.until is None or born <= self.until):
                    out.append(p)
        return out

    def end_strays(self) -> bool:
        """Kill and reap every stray child (and its tree); True if there were any."""
        found = False
        for _round in range(50):
            strays = self._strays()
            if not strays:
                break
            found = True
            below = list(strays)
            for p in strays:
                below += descendants(p) or []
            for _freeze in range(20):
                for p in below:
                    _signal(p, signal.SIGSTOP)
                again = list(strays)
                for p in strays:
                    again += descendants(p) or []
                if set(again) <= set(below):
                    break
                below = list(dict.fromkeys(below + again))
            for p in below:
                _signal(p, signal.SIGKILL)
            for p in strays:               # our children: reap them (their orphans come next)
                try:
                    os.waitpid(p, 0)
                except (ChildProcessError, InterruptedError):
                    pass
        return found

    def release(self) -> None:
        """This check no longer needs adoption; the last one turns the subreaper off again."""
        cls = type(self)
        if not self.active:
            return
        self.active = False
        with cls._lock:
            cls._users -= 1
            if cls._users == 0 and cls._was is False:
                _prctl(PR_SET_CHILD_SUBREAPER, 0)


def _children(pid: int) -> list[int] | None:
    """Direct children of ``pid`` (from /proc); None when /proc cannot tell."""
    try:
        tids = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return None
    out = []
    for tid in tids:
        try:
            with open(f"/proc/{pid}/task/{tid}/children", encoding="ascii") as f:
                out += [int(x) for x in f.read().split()]
        except FileNotFoundError:
            if os.path.exists(f"/proc/{pid}/task/{tid}"):
                return _children_by_scan(pid)      # a kernel without /proc/.../children
        except (OSError, ValueError):
            pass
    return out


def _children_by_scan(pid: int) -> list[int]:
    out = []
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/stat", encoding="ascii", errors="replace") as f:
                    stat = f.read()
                if int(stat.rsplit(")", 1)[1].split()[1]) == pid:
                    out.append(int(name))
            except (OSError, ValueError, IndexError):
                pass
    return out


def descendants(root: int) -> list[int] | None:
    """Every process below ``root`` (children, their children, ...), or None without /proc."""
    first = _children(root)
    if first is None:
        return None
    seen, todo = [], list(first)
    while todo:
        p = todo.pop()
        if p in seen:
            continue
        seen.append(p)
        todo += _children(p) or []
    return seen


def _signal(pid: int, sig: int) -> None:
    try:
        os.kill(pid, sig)
    except OSError:
        pass


def _freeze_and_kill(keeper: int) -> bool:
    """SIGSTOP everything below the keeper until nothing new appears, then SIGKILL it all.
    False when /proc cannot list the tree."""
    below = descendants(keeper)
    if below is None:
        return False
    for _round in range(20):               # frozen processes cannot fork while we look again
        for p in below:
            _signal(p, signal.SIGSTOP)
        again = descendants(keeper) or []
        if set(again) <= set(below):
            break
        below = list(dict.fromkeys(below + again))
    for p in below:
        _signal(p, signal.SIGKILL)
    return True


def _exited(pid: int) -> bool:
    """True once ``pid`` (our child) has exited, without reaping it (so its id stays reserved)."""
    if hasattr(os, "waitid") and hasattr(os, "WNOWAIT"):
        try:
            return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None
        except ChildProcessError:
            return True
    return False


def _finish(keeper: int, patience: float = 0.25, rounds: int = 40,
            adoption: Adoption | None = None) -> None:
    """Wait for the keeper, which reaps the killed tree and then exits, killing any straggler
    meanwhile; then kill what is left of its process group and reap it; then end (and reap) the
    orphans that came to this process, and stop adopting."""
    for _ in range(rounds):
        deadline = time.monotonic() + patience
        while time.monotonic() < deadline and not _exited(keeper):
            time.sleep(0.002)
        if _exited(keeper):
            break
        _freeze_and_kill(keeper)
    else:
        _signal(keeper, signal.SIGKILL)
    try:
        os.killpg(keeper, signal.SIGKILL)  # still reserved: the keeper is not reaped yet
    except OSError:
        pass
    try:
        os.waitpid(keeper, 0)
    except ChildProcessError:
        pass
    if adoption is not None:
        adoption.keeper_reaped()
        try:
            adoption.end_strays()
        finally:
            adoption.release()


def _killed_early(pid: int) -> bool:
    """True when ``pid`` (our child, not reaped) was killed by a signal before we ended it."""
    if not (hasattr(os, "waitid") and hasattr(os, "WNOWAIT") and hasattr(os, "CLD_EXITED")):
        return False
    try:
        res = os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT)
    except ChildProcessError:
        return False
    return res is not None and res.si_code != os.CLD_EXITED


def _kill_session(keeper: int) -> None:
    """Kill every process still in the keeper's session or process group (its orphans, once
    something killed the keeper itself: they are no longer below it)."""
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        try:
            with open(f"/proc/{name}/stat", encoding="ascii", errors="replace") as f:
                fields = f.read().rsplit(")", 1)[1].split()
            pgrp, session = int(fields[2]), int(fields[3])
        except (OSError, ValueError, IndexError):
            continue
        if keeper in (pgrp, session) and int(name) != keeper:
            _signal(int(name), signal.SIGKILL)


def kill_tree(keeper: int, wait: bool = False, adoption: Adoption | None = None) -> None:
    """End the keeper's whole tree: every process below it is frozen and killed now; the keeper
    (which reaps them) is waited for in a background thread unless ``wait``. Without /proc the
    keeper's process group is killed instead. With an :class:`Adoption`, the orphans that escaped
    the keeper (now children of this process) are ended too, now and once the keeper is gone."""
    if _killed_early(keeper) and os.path.isdir("/proc"):
        _kill_session(keeper)
    if adoption is not None:
        adoption.close_window()
        adoption.end_strays()
    if not _freeze_and_kill(keeper):
        try:
            os.killpg(keeper, signal.SIGKILL)
        except OSError:
            _signal(keeper, signal.SIGKILL)
        try:
            os.waitpid(keeper, 0)
        except ChildProcessError:
            pass
        if adoption is not None:
            adoption.keeper_reaped()
            adoption.release()
        return
    if wait:
        _finish(keeper, adoption=adoption)
    else:
        threading.Thread(target=_finish, args=(keeper,), kwargs={"adoption": adoption},
                         name="gm-checks-reaper", daemon=True).start()


def how_it_ended(status: int | None) -> str:
    """A friendly account of a worker's wait status."""
    if status is None:
        return "the process running it was stopped from outside"
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        known: dict[int, str] = {
            signal.SIGKILL: "it was killed (SIGKILL), most likely because the computer ran out of memory",
            signal.SIGSEGV: "a segmentation fault: a recursion deeper than the interpreter survives "
                            "(was sys.setrecursionlimit raised?) or a bug in compiled code",
            signal.SIGABRT: "it aborted (SIGABRT): a fatal error inside Python or a library",
            signal.SIGALRM: "an alarm signal (SIGALRM) ended it: signal.alarm() or a timer in your code",
            signal.SIGTERM: "it was terminated (SIGTERM)",
            signal.SIGINT: "it was interrupted (SIGINT)",
        }
        if hasattr(signal, "SIGBUS"):
            known[signal.SIGBUS] = known[signal.SIGSEGV]
        try:
            name = signal.Signals(sig).name
        except ValueError:
            name = f"signal {sig}"
        return known.get(sig, f"it was stopped by {name}")
    if os.WIFEXITED(status):
        return (f"it ended the Python process itself with exit status {os.WEXITSTATUS(status)} "
                "(os._exit() or a library that exits)")
    return "it ended in an unusual way"

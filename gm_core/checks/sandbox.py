"""Run a student's answer through a list of probes in a separate, killable process tree.

Every call into student code made by a checker goes through :func:`collect`: the *probes* (small
functions ``probe(answer) -> plain data``) run one after another in a child process forked from
this one (POSIX ``fork``, so student functions and lambdas need not be picklable; only the plain
results travel back, as JSON). The parent waits at most ``time_limit`` seconds for each probe.
Whatever happens in the child (``sys.exit``, a ``GeneratorExit``, an exception whose ``__str__``
raises, a segfault, a function that edits its inputs or monkeypatches gm_core) stays in the child:
the parent only sees plain outcomes, and it is the parent that judges them. Student output
(``print``) is captured and handed back, truncated.

Nothing is left behind: the fork is a small *keeper* that starts a session of its own (its own
process group) and becomes the "child subreaper" of everything below it (Linux), then forks the
*worker* that runs the probes. Whatever the worker starts (a forked busy loop, a process that
calls ``os.setsid`` and forks again, a daemon) stays in the keeper's tree; when the probes are
done, or at the time limit, the parent stops and kills that whole tree and the keeper's process
group, the keeper reaps them, and the check returns at once (it does not wait for a grandchild
that still holds the result pipe). A worker can kill its keeper and call ``setsid`` (out of the
keeper's tree, group and session); while a check runs the checking process is a subreaper as
well, so such an orphan becomes its child, and it is ended and reaped there with its own tree
(:class:`gm_core.checks.proctree.Adoption`). No cgroup is needed (a student's laptop has none to give).
The worker runs with a memory limit (``memory_mb`` more address space than the kernel uses;
``GM_CHECKS_MEMORY_MB`` sets it, 0 turns it off) so a runaway allocation is a ``MemoryError``,
not a frozen computer.

The settings (the time limit, the memory budget, how much printed output comes back) are one
frozen :class:`SandboxSettings`: :func:`current_settings` gives the ones in force,
:func:`apply_settings` puts others in force, :func:`using_settings` does so for a ``with`` block,
and :func:`set_time_limit` (the student's) changes the time limit only.

What stopped a call is said plainly: the time limit (``"timeout"``), Ctrl-C / SIGINT
(``KeyboardInterrupt``), an alarm (``AlarmSignal``: ``signal.alarm`` or a timer in the student's
code), the memory limit (``MemoryError``), an endless recursion (``RecursionError``), or the
worker's death (``"crash"``, with ``x`` saying how: which signal, an exit status, a segfault).

Why processes and not a thread: a thread cannot be killed, so an endless loop would keep burning
a core after the checker gave up, and it shares the kernel's memory. Where ``fork`` is not
available (Windows) or is turned off (``GM_CHECKS_NO_FORK=1``) the probes run in this process,
still catching every exception except ``KeyboardInterrupt``, but without a time limit.

An outcome is a dict ``{"k": kind, "v": value, "m": message}`` with kind one of ``"ok"``,
``"wrong"`` (the probe raised Wrong: a readable problem with the answer), ``"unattempted"``,
``"error"`` (the student code raised; ``m`` names the exception, ``x`` says more), ``"timeout"``,
``"crash"`` (the worker died; ``x`` says how) or ``"skipped"`` (an earlier probe timed out or
crashed).
"""
from __future__ import annotations

import copy
import faulthandler
import io
import json
import os
import select
import signal
import sys
import time
import warnings
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager, redirect_stderr, redirect_stdout
from dataclasses import dataclass, replace
from types import FrameType
from typing import Any, TypeAlias, cast

import numpy as np
from typing_extensions import Required, TypedDict

from gm_core.checks import channel
from gm_core.checks.proctree import Adoption, become_subreaper, how_it_ended, kill_tree
from gm_core.checks.protocol import JSON

try:
    import resource
except ImportError:  # pragma: no cover - Windows
    resource = None  # type: ignore[assignment]  # checked before every use


@dataclass(frozen=True)
class SandboxSettings:
    """How :func:`collect` runs probes.

    ``time_limit``: seconds each probe may take before the worker is stopped (a ``time_limit``
    given to :func:`collect` overrides it for that call; while grading, neither may exceed the
    grader's per-call limit, :attr:`gm_core.checks.protocol.Limits.time_limit`).
    ``memory_mb``: megabytes of address space the worker may take beyond what the kernel already
    uses (0 or less: no limit). ``max_output_chars``, ``max_output_lines``: how much of what the
    probes print comes back (the rest is cut, and the cut said).

    Frozen: change the settings in force with :func:`apply_settings` or :func:`using_settings`,
    e.g. ``using_settings(replace(current_settings(), time_limit=1.0))``.
    """

    time_limit: float = 5.0
    memory_mb: int = 2048
    max_output_chars: int = 1500
    max_output_lines: int = 25

    def __post_init__(self) -> None:
        object.__setattr__(self, "time_limit", float(self.time_limit))
        for name in ("memory_mb", "max_output_chars", "max_output_lines"):
            object.__setattr__(self, name, int(getattr(self, name)))
        if not self.time_limit > 0:
            raise ValueError(f"time_limit must be a positive number of seconds; got {self.time_limit!r}")
        if self.max_output_chars < 0 or self.max_output_lines < 0:
            raise ValueError("max_output_chars and max_output_lines must not be negative")


#: The settings in force; the memory budget comes from ``GM_CHECKS_MEMORY_MB`` when it is set.
_settings = SandboxSettings(memory_mb=int(os.environ.get("GM_CHECKS_MEMORY_MB", "2048") or 0))


def current_settings() -> SandboxSettings:
    """The :class:`SandboxSettings` in force."""
    return _settings


def apply_settings(settings: SandboxSettings) -> SandboxSettings:
    """Put ``settings`` in force for every later check in this process; return the previous ones."""
    global _settings
    if not isinstance(settings, SandboxSettings):
        raise TypeError(f"settings must be a SandboxSettings; got {type(settings).__name__}")
    previous, _settings = _settings, settings
    return previous


@contextmanager
def using_settings(settings: SandboxSettings) -> Iterator[SandboxSettings]:
    """Put ``settings`` in force inside a ``with`` block; the previous ones come back after it."""
    previous = apply_settings(settings)
    try:
        yield settings
    finally:
        apply_settings(previous)


#: A probe: ``probe(answer) -> plain data``; the answer is whatever the student handed in.
Probe: TypeAlias = Callable[[Any], Any]


class ProbeOutcome(TypedDict, total=False):
    """One probe's outcome (see the module docstring): its kind ``k``; ``v``, the probe's plain
    value (``ok`` only: decoded numbers, text, float arrays, lists and dicts, or their JSON form
    before :func:`decode_outcome`); ``m``, a message; ``x``, what more there is to say."""

    k: Required[str]
    v: Any
    m: str
    x: str


class Wrong(Exception):
    """Raised inside a checker with a friendly message when the answer is wrong."""


class Unattempted(Exception):
    """Raised inside a checker when the answer is still the starter value."""


class AlarmSignal(BaseException):
    """Raised in the worker when SIGALRM arrives (``signal.alarm`` or a timer in student code)."""


def _on_alarm(signum: int, frame: FrameType | None) -> None:
    raise AlarmSignal()


def set_time_limit(seconds: float) -> None:
    """Set how many seconds a checker lets one call of your function take (default 5)."""
    try:
        s = float(seconds)
    except (TypeError, ValueError):
        raise TypeError(f"seconds must be a number of seconds; got {seconds!r}") from None
    if not s > 0:
        raise ValueError(f"seconds must be positive; got {seconds!r}")
    apply_settings(replace(_settings, time_limit=s))


def safe_text(exc: object, limit: int = 200) -> str:
    """str(exc), or a placeholder when even that fails (a hostile __str__)."""
    try:
        text = str(exc)
    except BaseException:  # noqa: BLE001 - the student's __str__ may raise anything
        text = "<the exception's message could not be printed>"
    if not isinstance(text, str):
        text = "<the exception's message is not text>"
    return text[:limit]


def safe_name(exc: object) -> str:
    """The name of ``exc``'s type, or "Exception" when even that fails."""
    try:
        name = type(exc).__name__
        return name if isinstance(name, str) else "Exception"
    except BaseException:  # noqa: BLE001
        return "Exception"


# ------------------------------------------------------------------------------ plain data
def encode(value: object) -> JSON:
    """Plain data -> JSON-able (numpy arrays tagged); anything else becomes a short description."""
    if value is None or isinstance(value, (bool, str)):
        return value
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value)
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "biuf":
            return {"__nd__": list(value.shape), "d": value.astype(float).ravel().tolist()}
        raise TypeError("only numeric arrays travel back from a probe")
    if isinstance(value, (list, tuple)):
        return [encode(v) for v in value]
    if isinstance(value, dict):
        return {"__dict__": [[str(k), encode(v)] for k, v in value.items()]}
    raise TypeError(f"a probe returned {type(value).__name__}, which is not plain data")


def decode(data: JSON) -> Any:
    """JSON from :func:`encode` -> plain data (float arrays, lists, dicts, numbers, text)."""
    if isinstance(data, list):
        return [decode(v) for v in data]
    if isinstance(data, dict):
        if "__nd__" in data:
            shape = tuple(int(s) for s in data["__nd__"])
            return np.asarray(data["d"], dtype=float).reshape(shape)
        if "__dict__" in data:
            return {str(k): decode(v) for k, v in data["__dict__"]}
        raise ValueError("unexpected data")
    return data


# ------------------------------------------------------------------------------ one probe
def _run_probe(probe: Probe, answer: Any, forked: bool = False) -> ProbeOutcome:
    """Run one probe, turning whatever it does into an outcome dict. In this process (not
    ``forked``) Ctrl-C still interrupts; in the worker it becomes an outcome like any other."""
    try:
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            value = probe(answer)
        return {"k": "ok", "v": encode(value)}
    except Wrong as w:
        return {"k": "wrong", "m": safe_text(w, 600)}
    except Unattempted as u:
        return {"k": "unattempted", "m": safe_text(u, 600)}
    except RecursionError:
        return {"k": "error", "m": "RecursionError", "x": "it recursed without end"}
    except KeyboardInterrupt:
        if not forked:
            raise
        return {"k": "error", "m": "KeyboardInterrupt",
                "x": "it was interrupted (Ctrl-C, a SIGINT, or a raise KeyboardInterrupt in it)"}
    except AlarmSignal:
        return {"k": "error", "m": "AlarmSignal",
                "x": "an alarm signal (SIGALRM) went off: signal.alarm() or a timer in your code"}
    except MemoryError:
        budget = _settings.memory_mb
        more = f" (a check allows {budget} MB more than the kernel uses)" if budget else ""
        return {"k": "error", "m": "MemoryError", "x": f"it asked for more memory than it may have{more}"}
    except BaseException as exc:  # noqa: BLE001 - SystemExit, GeneratorExit, anything
        return {"k": "error", "m": safe_name(exc), "x": safe_text(exc)}


def _truncate(text: str) -> str:
    max_lines, max_chars = _settings.max_output_lines, _settings.max_output_chars
    lines = text.splitlines()
    cut = len(lines) > max_lines or len(text) > max_chars
    if cut:
        text = "\n".join(lines[:max_lines])[:max_chars]
        text += f"\n... ({len(lines)} lines in all; the rest is not shown)"
    return text


def _quiet_display_in_child() -> None:
    """In the child, send IPython display calls to the captured stdout, not the kernel's socket."""
    ip_mod = sys.modules.get("IPython")
    if ip_mod is None:
        return
    try:
        from IPython.core.displaypub import DisplayPublisher
        ip = ip_mod.get_ipython()
        if ip is not None:
            ip.display_pub = DisplayPublisher(shell=ip)
    except BaseException:  # noqa: BLE001
        pass


def _limit_memory() -> None:
    """Cap the worker's address space at what it has now plus the settings' ``memory_mb`` (Linux)."""
    budget = _settings.memory_mb
    if resource is None or not budget or budget <= 0:
        return
    try:
        with open("/proc/self/status", encoding="ascii", errors="replace") as f:
            size = next(int(line.split()[1]) * 1024 for line in f if line.startswith("VmSize:"))
        soft, hard = resource.getrlimit(resource.RLIMIT_AS)
        want = size + int(budget) * 2 ** 20
        if hard != resource.RLIM_INFINITY:
            want = min(want, hard)
        if soft == resource.RLIM_INFINITY or want < soft:
            resource.setrlimit(resource.RLIMIT_AS, (want, hard))
    except (OSError, ValueError, StopIteration):
        pass


def _child(probes: list[Probe], answer: Any, wfd: int) -> None:
    """The worker: run every probe, one JSON line each, then the captured output; then exit."""
    buf = io.StringIO()
    try:
        signal.signal(signal.SIGINT, signal.default_int_handler)
        signal.signal(signal.SIGALRM, _on_alarm)
        faulthandler.disable()            # a segfault is reported as a verdict, not a dump
        _limit_memory()
        _quiet_display_in_child()
        with os.fdopen(wfd, "w", encoding="utf-8") as pipe, redirect_stdout(buf), redirect_stderr(buf):
            for probe in probes:
                outcome = _run_probe(probe, answer, forked=True)
                pipe.write(json.dumps(outcome) + "\n")
                pipe.flush()
            pipe.write(json.dumps({"k": "output", "v": _truncate(buf.getvalue())}) + "\n")
            pipe.flush()
    finally:
        os._exit(0)


def _keeper(probes: list[Probe], answer: Any, wfd: int) -> None:
    """The fork's first process: own session and process group, subreaper of all below; forks
    the worker, reports how it ended, and reaps every descendant until none is left."""
    try:
        os.setsid()
        become_subreaper()
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        worker = os.fork()
        if worker == 0:
            _child(probes, answer, wfd)
        while True:
            try:
                pid, status = os.waitpid(-1, 0)
            except ChildProcessError:
                break                      # nothing left below: the tree is gone
            except InterruptedError:
                continue
            if pid == worker:
                try:
                    os.write(wfd, (json.dumps({"k": "exit", "v": status}) + "\n").encode())
                except OSError:
                    pass
    finally:
        os._exit(0)


def _can_fork() -> bool:
    return hasattr(os, "fork") and os.environ.get("GM_CHECKS_NO_FORK", "") not in ("1", "true")


def _in_process(probes: list[Probe], answer: Any, raw: bool = False) -> tuple[list[ProbeOutcome], str]:
    buf = io.StringIO()
    outcomes: list[ProbeOutcome] = []
    with redirect_stdout(buf), redirect_stderr(buf):
        for probe in probes:
            # copies, so a function that edits its input cannot change what later probes see
            try:
                a = copy.deepcopy(answer)
            except BaseException:  # noqa: BLE001
                a = answer
            outcomes.append(_run_probe(probe, a))
    return (outcomes if raw else [decode_outcome(o) for o in outcomes]), _truncate(buf.getvalue())


def decode_outcome(o: object) -> ProbeOutcome:
    """An outcome as the judges read it (``v`` decoded), from its JSON form; anything else, or
    a value that cannot be decoded, is a crash ("unreadable result")."""
    if not isinstance(o, dict) or o.get("k") not in (
            "ok", "wrong", "unattempted", "error", "timeout", "crash", "skipped"):
        return {"k": "crash", "m": "unreadable result"}
    out: ProbeOutcome = {"k": o["k"], "m": o.get("m", ""), "x": o.get("x", "")}
    if o["k"] == "ok":
        try:
            out["v"] = decode(o.get("v"))
        except Exception:  # noqa: BLE001
            return {"k": "crash", "m": "unreadable result"}
    return out


def collect(answer: Any, probes: Iterable[Probe], time_limit: float | None = None,
            raw: bool = False) -> tuple[list[ProbeOutcome], str]:
    """Run ``probe(answer)`` for every probe, each under the time limit; return (outcomes, output).

    Outcomes are decoded dicts (see the module docstring), one per probe, in order; with
    ``raw=True`` they stay JSON-able (for the grader, which decodes them in its own process).
    """
    limit = _settings.time_limit if time_limit is None else float(time_limit)
    graded = channel.time_limit()
    if graded is not None:
        limit = min(limit, graded)     # while grading, no call gets more than the grader allows
    probes = list(probes)
    if not probes:
        return [], ""
    if not _can_fork():
        return _in_process(probes, answer, raw)
    rfd, wfd = os.pipe()
    adoption = Adoption().start()   # orphans of the probe tree come to this process, not init
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "multi-threaded process, fork() may deadlock" (3.12+)
            pid = adoption.fork()
    except OSError:
        os.close(rfd)
        os.close(wfd)
        adoption.release()
        return _in_process(probes, answer, raw)
    if pid == 0:  # pragma: no cover - runs in the keeper
        os.close(rfd)
        _keeper(probes, answer, wfd)
    os.close(wfd)
    outcomes: list[ProbeOutcome] = []
    output, pending = "", b""
    deadline = time.monotonic() + limit
    ended, status, done = False, None, False
    try:
        while not (done or ended):
            wait = deadline - time.monotonic()
            if wait <= 0:
                break
            ready, _, _ = select.select([rfd], [], [], wait)
            if not ready:
                break
            chunk = os.read(rfd, 65536)
            if not chunk:
                ended = True                  # the keeper is gone (killed from outside)
                break
            pending += chunk
            while b"\n" in pending:
                line, pending = pending.split(b"\n", 1)
                try:
                    o = json.loads(line.decode("utf-8"))
                except (ValueError, RecursionError):
                    o = None
                if isinstance(o, dict) and o.get("k") == "output":
                    output = o.get("v", "") if isinstance(o.get("v"), str) else ""
                    done = True               # every probe answered: no need to wait for more
                    break
                if isinstance(o, dict) and o.get("k") == "exit":
                    status = o.get("v") if isinstance(o.get("v"), int) else None
                    ended = True              # the worker died before it was done
                    break
                # raw: the JSON form, read strictly by the grader's decoder in its own process
                outcomes.append(cast(ProbeOutcome, o) if raw and isinstance(o, dict) else decode_outcome(o))
                deadline = time.monotonic() + limit  # the next probe gets its own limit
    finally:
        os.close(rfd)
        kill_tree(pid, adoption=adoption)
    outcomes = outcomes[:len(probes)]
    if len(outcomes) < len(probes):
        if ended:
            outcomes.append({"k": "crash", "m": "", "x": how_it_ended(status)})
        else:
            outcomes.append({"k": "timeout", "m": f"{limit:g}", "x": ""})
        outcomes += [{"k": "skipped", "m": "", "x": ""} for _ in range(len(probes) - len(outcomes))]
    return outcomes, output

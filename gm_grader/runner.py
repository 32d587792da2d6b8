"""Run one submitted notebook cell by cell: ``python -m gm_grader.runner CONFIG.json``.

This process is started by the grader (:mod:`.grade`), normally inside the submission's
bubblewrap sandbox (:mod:`gm_grader.isolate`); it is the only course code there besides the kernel.
It writes the records of :mod:`gm_core.checks.protocol` (:class:`~gm_core.checks.protocol.Record`),
one JSON line each, to the evidence descriptor it inherited from the grader
(``RunnerConfig.evidence_fd``): it started, the kernel started, a code cell starts or ends (with
its status), a check announced itself in the kernel (its probes' time is credited, capped, on
this runner's cell clock and on the grader's, :mod:`gm_grader.clock`), a line of the kernel's
evidence (forwarded as text; the grader decodes and checks it), the notebook flooded the pipe,
could not be run, or is done.

Before the student's first cell a hidden cell binds the kernel's end of that pipe
(:func:`gm_core.checks.channel.open_channel`). Each code cell runs under the cell limit, *not counting the
time its checks' probes take* (every probe already has the per-call limit the student's own
kernel uses; each check is credited at most its part's longest honest time, :mod:`gm_grader.clock`); a
cell over the limit is interrupted (SIGINT), and killed 5 s later if it ignores that, so only
the parts checked in it or later are lost. The kernel can signal this process (same user), so
the grading process keeps the same clock outside the sandbox from these records and ends the
whole sandbox should this runner stop keeping it (a SIGSTOP, say). Outputs are counted and dropped: the
grader never looks at what a notebook prints.
"""
from __future__ import annotations

import os
import shutil
import signal
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import replace
from typing import Any

from gm_core.checks.protocol import (
    CellEnded,
    CellStarted,
    CellStatus,
    CheckAnnounced,
    Done,
    EvidenceLine,
    Fatal,
    Flooded,
    KernelStarted,
    OutputSize,
    ProtocolError,
    Record,
    RunnerConfig,
    Started,
    decode_check_begun,
    decode_config,
    encode_record,
)
from gm_grader.clock import CellClock

MAX_FORWARD_BYTES = 32_000_000
MAX_LINE_BYTES = 4_100_000
GRACE = 5.0
#: A check's announcement is short; a longer line is evidence (or junk) and is not parsed here.
MAX_ANNOUNCEMENT_BYTES = 200


class _Out:
    """The evidence descriptor: whole records, one line each, written under a lock."""

    def __init__(self, fd: int) -> None:
        self.fd, self.lock, self.t0 = fd, threading.Lock(), time.monotonic()

    def send(self, rec: Record) -> None:
        data = encode_record(_stamped(rec, time.monotonic() - self.t0))
        with self.lock:
            try:
                while data:
                    data = data[os.write(self.fd, data):]
            except OSError:
                pass


def _stamped(rec: Record, at: float) -> Record:
    return replace(rec, at=round(at, 2))


class _State:
    def __init__(self, caps: dict[str, float] | None = None) -> None:
        self.cell: int | None = None         # index of the cell running now
        self.clock = CellClock(caps)         # student seconds of that cell (checks' probes credited)
        self.interrupted: float | None = None
        self.timed_out = False
        self.lock = threading.Lock()

    def start_cell(self, index: int, now: float) -> None:
        with self.lock:
            self.cell = index
            self.clock.restart(now)
            self.interrupted, self.timed_out = None, False

    def student_seconds(self, now: float) -> float:
        with self.lock:
            return self.clock.seconds(now)


def _forward(rfd: int, out: _Out, state: _State) -> None:
    """Forward the kernel's check lines, tagged with the cell that was running."""
    pending, total, noted = b"", 0, False
    while True:
        try:
            chunk = os.read(rfd, 65536)
        except OSError:
            break
        if not chunk:
            break
        total += len(chunk)
        if total > MAX_FORWARD_BYTES:
            if not noted:
                out.send(Flooded(message="the kernel wrote too much on the evidence channel"))
                noted = True
            pending = b""
            continue
        pending += chunk
        while b"\n" in pending:
            line, pending = pending.split(b"\n", 1)
            _handle(line, out, state)
        if len(pending) > MAX_LINE_BYTES:
            out.send(EvidenceLine(cell=state.cell, line=""))    # an over-long record: rejected
            pending = b""


def _handle(line: bytes, out: _Out, state: _State) -> None:
    """One line of the kernel: a check's announcement (parsed) or evidence (forwarded as text)."""
    now = time.monotonic()
    if len(line) <= MAX_ANNOUNCEMENT_BYTES:
        try:
            key = decode_check_begun(line).part
        except ProtocolError:
            pass
        else:
            with state.lock:
                state.clock.begin(key, now)
            out.send(CheckAnnounced(cell=state.cell, part=key))  # the grader's clock credits it too
            return
    with state.lock:
        state.clock.end(now)
    out.send(EvidenceLine(cell=state.cell, line=line.decode("utf-8", "replace")))


def _watchdog(state: _State, limit: float, pid_of: Callable[[], int | None],
              stop: threading.Event) -> None:
    while not stop.wait(0.2):
        now = time.monotonic()
        if state.cell is None or state.cell < 0:
            continue
        pid = pid_of()
        if pid is None:
            continue
        if state.interrupted is None and state.student_seconds(now) > limit:
            state.timed_out, state.interrupted = True, now
            _signal(pid, signal.SIGINT)
        elif state.interrupted is not None and now - state.interrupted > GRACE:
            _signal(pid, signal.SIGKILL)
            state.interrupted = now + 3600  # once


def _signal(pid: int, sig: int) -> None:
    for kill in (lambda: os.killpg(pid, sig), lambda: os.kill(pid, sig)):
        try:
            kill()
            return
        except OSError:
            pass


def _without_iri_grammar() -> None:
    """Importing nbformat imports jsonschema, which imports ``rfc3987_syntax`` when it is installed
    (an extra that jupyter_events asks for) and that compiles a Lark grammar at import: 1-2 s of CPU
    for every graded notebook. The notebook schema has no IRI format to check, so this process,
    which only reads and runs one notebook, marks the module absent (``sys.modules[name] = None``
    is Python's documented way to make an import fail) and jsonschema does without it."""
    sys.modules.setdefault("rfc3987_syntax", None)  # type: ignore[arg-type]


def _client_class() -> Any:
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionComplete

    class QuietClient(NotebookClient):
        """Executes cells but keeps none of their output (counted, then dropped)."""

        output_bytes = 0
        last_error: str | None = None

        def process_message(self, msg: dict[str, Any], cell: Any, cell_index: int) -> None:
            mtype = msg.get("msg_type")
            content = msg.get("content") or {}
            if mtype == "status":
                if content.get("execution_state") == "idle":
                    raise CellExecutionComplete()
                return None
            if mtype == "error":
                self.last_error = str(content.get("ename", "Exception"))[:80]
            for v in content.values():   # sizes only: no copy of a huge output is made
                if isinstance(v, str):
                    self.output_bytes += len(v)
                elif isinstance(v, dict):
                    self.output_bytes += sum(len(x) for x in v.values() if isinstance(x, str))
            return None

    return QuietClient


def _copy_font_cache(src: str, dst: str) -> None:
    try:
        os.makedirs(dst, exist_ok=True)
        for name in os.listdir(src):
            if name.startswith("fontlist") and name.endswith(".json"):
                shutil.copy(os.path.join(src, name), dst)
    except OSError:
        pass


def _setup_source(wfd: int, config: RunnerConfig) -> str:
    """The hidden first cell: bind the kernel's end of the evidence pipe (answers carried by
    :func:`gm_grader.probe.dumps`), set the per-call limit."""
    limit = config.limits.time_limit
    return ("import gm_core.checks.channel as __gm_grading, gm_core.checks.sandbox as __gm_sandbox\n"
            "import gm_grader.probe as __gm_probe\n"
            f"__gm_grading.open_channel({wfd}, {config.nonce!r}, {config.salt!r}, {limit!r}, "
            "__gm_probe.dumps)\n"
            f"__gm_sandbox.set_time_limit({limit!r})\n"
            "del __gm_grading, __gm_sandbox, __gm_probe")


def run(config: RunnerConfig) -> int:
    out = _Out(config.evidence_fd)
    out.send(Started())
    work = config.workdir
    os.makedirs(work, exist_ok=True)
    for d in ("HOME", "IPYTHONDIR", "JUPYTER_RUNTIME_DIR", "MPLCONFIGDIR"):
        if os.environ.get(d):
            os.makedirs(os.environ[d], exist_ok=True)
    mpl_dir = os.environ.get("MPLCONFIGDIR")
    if config.mpl_cache and mpl_dir:
        _copy_font_cache(config.mpl_cache, mpl_dir)
    try:
        _without_iri_grammar()
        import nbformat
        with open(config.notebook, "rb") as f:
            raw = f.read(config.max_notebook_bytes + 1)
        if len(raw) > config.max_notebook_bytes:
            raise ValueError("the notebook file is too large")
        nb = nbformat.reads(raw.decode("utf-8"), as_version=4)
        cells = [(i, c) for i, c in enumerate(nb.cells) if c.get("cell_type") == "code"]
        for _, c in cells:
            if not isinstance(c.get("source"), str):
                raise ValueError("a cell's source is not text")
    except (Exception, RecursionError) as exc:  # noqa: BLE001 - malformed, deep, huge JSON
        out.send(Fatal(message=f"the notebook could not be read ({type(exc).__name__})"))
        return 0
    name = os.path.basename(config.notebook)
    try:
        shutil.copy(config.notebook, os.path.join(work, name))
    except OSError:
        pass

    rfd, wfd = os.pipe()
    state = _State(dict(config.caps))
    stop = threading.Event()
    reader = threading.Thread(target=_forward, args=(rfd, out, state), daemon=True)
    reader.start()
    setup = nbformat.v4.new_code_cell(_setup_source(wfd, config))
    nb.cells.insert(0, setup)
    client = _client_class()(nb, timeout=None, kernel_name="python3", allow_errors=True,
                             startup_timeout=120, resources={"metadata": {"path": work}})

    def pid_of() -> int | None:
        try:
            pid = client.km.provisioner.process.pid
        except AttributeError:
            return None
        return pid if isinstance(pid, int) else None

    dog = threading.Thread(target=_watchdog,
                           args=(state, config.limits.cell_timeout, pid_of, stop), daemon=True)
    dog.start()
    try:
        with client.setup_kernel(pass_fds=(wfd,), cwd=work):
            os.close(wfd)
            out.send(KernelStarted(pid=pid_of()))
            state.start_cell(-1, time.monotonic())
            client.execute_cell(setup, 0)
            if client.last_error:
                out.send(Fatal(message="the course's checkers could not be loaded in the "
                               f"notebook's kernel ({client.last_error})"))
                return 0
            for index, cell in cells:
                state.start_cell(index, time.monotonic())
                client.last_error = None
                out.send(CellStarted(index=index))
                try:
                    client.execute_cell(cell, index + 1)
                except Exception as exc:  # noqa: BLE001 - DeadKernelError and kin
                    out.send(CellEnded(
                        index=index, status=CellStatus.TIMEOUT if state.timed_out else CellStatus.DIED,
                        error=type(exc).__name__,
                        seconds=round(time.monotonic() - state.clock.started, 1)))
                    return 0
                status = (CellStatus.TIMEOUT if state.timed_out else
                          CellStatus.ERROR if client.last_error else CellStatus.OK)
                out.send(CellEnded(index=index, status=status, error=client.last_error or "",
                                   seconds=round(time.monotonic() - state.clock.started, 1)))
            state.cell = None
            out.send(OutputSize(size=client.output_bytes))
            out.send(Done())   # the grader ends the sandbox now: no slow kernel shutdown
    except (Exception, RecursionError) as exc:  # noqa: BLE001 - the kernel would not start, ...
        out.send(Fatal(message=f"the notebook's kernel stopped ({type(exc).__name__})"))
        return 0
    finally:
        stop.set()
    return 0


def _not_dumpable() -> None:
    """Keep the kernel (same user) out of this process: no ptrace, no /proc/<pid>/fd."""
    try:
        import ctypes
        ctypes.CDLL(None).prctl(4, 0, 0, 0, 0)   # PR_SET_DUMPABLE = 4
    except Exception:  # noqa: BLE001 - not Linux
        pass


def main(argv: list[str] | None = None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    _not_dumpable()
    with open(argv[0], encoding="utf-8") as f:
        config = decode_config(f.read())
    try:
        return run(config)
    except Exception as exc:  # noqa: BLE001 - say so on the channel rather than vanish
        _Out(config.evidence_fd).send(
            Fatal(message=f"the grader's runner failed ({type(exc).__name__}: {exc})"[:300]))
        raise


if __name__ == "__main__":
    sys.exit(main())

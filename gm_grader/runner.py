"""Run one submitted notebook cell by cell: ``python -m gm_grader.runner CONFIG.json``.

This process is started by the grader (:mod:`.grade`), normally inside the submission's
bubblewrap sandbox (:mod:`gm_grader.isolate`); it is the only course code there besides the kernel.
It writes plain records, one JSON line each, to the evidence descriptor it inherited from the
grader (``config["evidence_fd"]``):

* ``{"t": "start"}``, ``{"t": "kernel", "pid": ...}``;
* ``{"t": "run", "i": index}`` as a code cell starts, ``{"t": "cell", "i": index, "status":
  "ok" | "error" | "timeout" | "died", ...}`` when it ends;
* ``{"t": "k", "cell": index, "line": "..."}``: a line the kernel's checks wrote on the pipe
  this runner created *before the kernel started* (forwarded as text; the grader parses it);
* ``{"t": "b", "cell": index, "part": "1.4/a"}``: a check announced itself (its probes' time is
  credited, capped, on this runner's cell clock and on the grader's, :mod:`gm_grader.clock`);
* ``{"t": "fatal", "m": ...}`` and ``{"t": "done"}``.

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

import json
import os
import shutil
import signal
import sys
import threading
import time

from gm_grader.clock import CellClock

MAX_FORWARD_BYTES = 32_000_000
MAX_LINE_BYTES = 4_100_000
GRACE = 5.0


class _Out:
    """The evidence descriptor: whole JSON lines, written under a lock."""

    def __init__(self, fd):
        self.fd, self.lock, self.t0 = fd, threading.Lock(), time.monotonic()

    def send(self, rec):
        data = (json.dumps({**rec, "at": round(time.monotonic() - self.t0, 2)}) + "\n").encode()
        with self.lock:
            try:
                while data:
                    data = data[os.write(self.fd, data):]
            except OSError:
                pass


class _State:
    def __init__(self, caps=None):
        self.cell = None            # index of the cell running now
        self.clock = CellClock(caps)   # student seconds of that cell (checks' probes credited)
        self.interrupted = None
        self.timed_out = False
        self.lock = threading.Lock()

    def start_cell(self, index, now):
        with self.lock:
            self.cell = index
            self.clock.restart(now)
            self.interrupted, self.timed_out = None, False

    def student_seconds(self, now):
        with self.lock:
            return self.clock.seconds(now)


def _forward(rfd, out, state):
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
                out.send({"t": "flood", "m": "the kernel wrote too much on the evidence channel"})
                noted = True
            pending = b""
            continue
        pending += chunk
        while b"\n" in pending:
            line, pending = pending.split(b"\n", 1)
            _handle(line, out, state)
        if len(pending) > MAX_LINE_BYTES:
            out.send({"t": "k", "cell": state.cell, "line": "", "m": "an over-long record"})
            pending = b""


def _handle(line, out, state):
    now = time.monotonic()
    if line.startswith(b"B "):
        key = line[2:80].decode("utf-8", "replace").strip()
        with state.lock:
            state.clock.begin(key, now)
        out.send({"t": "b", "cell": state.cell, "part": key})   # the grader's clock credits it too
        return
    with state.lock:
        state.clock.end(now)
    text = line.decode("utf-8", "replace")
    out.send({"t": "k", "cell": state.cell, "line": text[2:] if text.startswith("R ") else text})


def _watchdog(state, limit, pid_of, stop):
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


def _signal(pid, sig):
    for kill in (lambda: os.killpg(pid, sig), lambda: os.kill(pid, sig)):
        try:
            kill()
            return
        except OSError:
            pass


def _without_iri_grammar():
    """Importing nbformat imports jsonschema, which imports ``rfc3987_syntax`` when it is installed
    (an extra that jupyter_events asks for) and that compiles a Lark grammar at import: 1-2 s of CPU
    for every graded notebook. The notebook schema has no IRI format to check, so this process,
    which only reads and runs one notebook, marks the module absent (``sys.modules[name] = None``
    is Python's documented way to make an import fail) and jsonschema does without it."""
    sys.modules.setdefault("rfc3987_syntax", None)


def _client_class():
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionComplete

    class QuietClient(NotebookClient):
        """Executes cells but keeps none of their output (counted, then dropped)."""

        output_bytes = 0
        last_error = None

        def process_message(self, msg, cell, cell_index):
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


def _copy_font_cache(src, dst):
    try:
        os.makedirs(dst, exist_ok=True)
        for name in os.listdir(src):
            if name.startswith("fontlist") and name.endswith(".json"):
                shutil.copy(os.path.join(src, name), dst)
    except OSError:
        pass


def run(config):
    out = _Out(int(config["evidence_fd"]))
    out.send({"t": "start"})
    work = config["workdir"]
    os.makedirs(work, exist_ok=True)
    for d in ("HOME", "IPYTHONDIR", "JUPYTER_RUNTIME_DIR", "MPLCONFIGDIR"):
        if os.environ.get(d):
            os.makedirs(os.environ[d], exist_ok=True)
    if config.get("mpl_cache") and os.environ.get("MPLCONFIGDIR"):
        _copy_font_cache(config["mpl_cache"], os.environ["MPLCONFIGDIR"])
    try:
        _without_iri_grammar()
        import nbformat
        with open(config["notebook"], "rb") as f:
            raw = f.read(int(config.get("max_notebook_bytes", 50_000_000)) + 1)
        if len(raw) > int(config.get("max_notebook_bytes", 50_000_000)):
            raise ValueError("the notebook file is too large")
        nb = nbformat.reads(raw.decode("utf-8"), as_version=4)
        cells = [(i, c) for i, c in enumerate(nb.cells) if c.get("cell_type") == "code"]
        for _, c in cells:
            if not isinstance(c.get("source"), str):
                raise ValueError("a cell's source is not text")
    except (Exception, RecursionError) as exc:  # noqa: BLE001 - malformed, deep, huge JSON
        out.send({"t": "fatal", "m": f"the notebook could not be read ({type(exc).__name__})"})
        return 0
    name = os.path.basename(config["notebook"])
    try:
        shutil.copy(config["notebook"], os.path.join(work, name))
    except OSError:
        pass

    rfd, wfd = os.pipe()
    state = _State(config.get("caps"))
    stop = threading.Event()
    reader = threading.Thread(target=_forward, args=(rfd, out, state), daemon=True)
    reader.start()
    setup = nbformat.v4.new_code_cell(
        "import gm_core.checks.channel as __gm_grading, gm_core.checks.sandbox as __gm_sandbox\n"
        f"__gm_grading.open_channel({wfd}, {config['nonce']!r}, {config['salt']!r}, "
        f"{config['time_limit']!r})\n"
        f"__gm_sandbox.set_time_limit({config['time_limit']!r})\n"
        "del __gm_grading, __gm_sandbox")
    nb.cells.insert(0, setup)
    client = _client_class()(nb, timeout=None, kernel_name="python3", allow_errors=True,
                             startup_timeout=120, resources={"metadata": {"path": work}})

    def pid_of():
        try:
            return client.km.provisioner.process.pid
        except AttributeError:
            return None

    dog = threading.Thread(target=_watchdog,
                           args=(state, float(config["cell_timeout"]), pid_of, stop), daemon=True)
    dog.start()
    try:
        with client.setup_kernel(pass_fds=(wfd,), cwd=work):
            os.close(wfd)
            out.send({"t": "kernel", "pid": pid_of()})
            state.start_cell(-1, time.monotonic())
            client.execute_cell(setup, 0)
            if client.last_error:
                out.send({"t": "fatal", "m": "the course's checkers could not be loaded in the "
                          f"notebook's kernel ({client.last_error})"})
                return 0
            for index, cell in cells:
                state.start_cell(index, time.monotonic())
                client.last_error = None
                out.send({"t": "run", "i": index})
                try:
                    client.execute_cell(cell, index + 1)
                except Exception as exc:  # noqa: BLE001 - DeadKernelError and kin
                    status = "timeout" if state.timed_out else "died"
                    out.send({"t": "cell", "i": index, "status": status,
                              "m": type(exc).__name__, "s": round(time.monotonic() - state.clock.started, 1)})
                    return 0
                status = "timeout" if state.timed_out else ("error" if client.last_error else "ok")
                out.send({"t": "cell", "i": index, "status": status, "m": client.last_error or "",
                          "s": round(time.monotonic() - state.clock.started, 1)})
            state.cell = None
            out.send({"t": "output", "bytes": client.output_bytes})
            out.send({"t": "done"})   # the grader ends the sandbox now: no slow kernel shutdown
    except (Exception, RecursionError) as exc:  # noqa: BLE001 - the kernel would not start, ...
        out.send({"t": "fatal", "m": f"the notebook's kernel stopped ({type(exc).__name__})"})
        return 0
    finally:
        stop.set()
    return 0


def _not_dumpable():
    """Keep the kernel (same user) out of this process: no ptrace, no /proc/<pid>/fd."""
    try:
        import ctypes
        ctypes.CDLL(None).prctl(4, 0, 0, 0, 0)   # PR_SET_DUMPABLE = 4
    except Exception:  # noqa: BLE001 - not Linux
        pass


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    _not_dumpable()
    with open(argv[0], encoding="utf-8") as f:
        config = json.load(f)
    try:
        return run(config)
    except Exception as exc:  # noqa: BLE001 - say so on the channel rather than vanish
        _Out(int(config["evidence_fd"])).send(
            {"t": "fatal", "m": f"the grader's runner failed ({type(exc).__name__}: {exc})"[:300]})
        raise


if __name__ == "__main__":
    sys.exit(main())

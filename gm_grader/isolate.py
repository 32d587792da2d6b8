"""Run one submission's notebook in its own bubblewrap sandbox and bring back its evidence.

The sandbox (``bwrap``, Debian's ``bubblewrap`` package) gives the notebook's kernel:

* **only what it needs** to see (:mod:`gm_grader.view`): the system's programs and libraries, the
  Python the grader runs on and the course's packages, all read-only; its own staged notebook;
  a fresh, size-capped ``/tmp`` and ``/dev/shm`` as the only writable places. No grading folder,
  no other submission, no output folder, no home, no ``/etc/shadow``, no host sockets: they are
  not hidden, they were never put there, and nothing a submission holds decides what is;
* **its own user**: a root grader's sandbox drops to a uid and gid of its own (nobody's root);
* new pid, network, IPC and UTS namespaces (no network at all), no capabilities, a new
  session; ``--die-with-parent`` and the pid namespace mean that when the
  sandbox ends, every process it started ends too (a ``setsid`` daemon included);
* limits: total wall time per notebook and per cell, kept by the grading process itself
  (:class:`_OuterClock`: the kernel can stop its runner, not the grader), memory (``RLIMIT_AS`` per
  process, and a memory cgroup for the whole tree), processes (a pids cgroup; ``RLIMIT_NPROC``
  too, of the sandbox's own user), file size and ``/tmp`` size. Each notebook gets cgroups of its own
  (``pids.max``, the memory limit) wherever this process may create them (cgroup v1 or v2); at the
  end, or at a limit, every process in them is killed and they are removed. Where none can be
  made (``GM_GRADE_NO_CGROUPS=1`` also says so) the sandbox's pid namespace still ends every
  process with it, but the memory limit is per process (and without a sandbox a root grader's
  processes are not bounded in number): the grader says so in its report.

Evidence comes back on a pipe created here before the sandbox starts and inherited by the
runner (:mod:`gm_grader.runner`); the grader reads at most ``MAX_EVIDENCE_BYTES`` of it. Nothing the
sandbox writes anywhere else is read.

Without bubblewrap (or where user namespaces are forbidden) :func:`sandbox_problem` says why
and the grader refuses unless told ``--no-sandbox`` (for a container per submission, as on
Gradescope): then the runner is a plain child process with the same limits and its own process
group, killed at the end.
"""
from __future__ import annotations

import os
import resource
import secrets
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from enum import Enum
from pathlib import Path

from gm_core.checks.protocol import (
    CellEnded,
    CellStarted,
    CheckAnnounced,
    Done,
    EvidenceLine,
    Fatal,
    KernelStarted,
    Limits,
    ProtocolError,
    Record,
    RunnerConfig,
    Started,
    decode_record,
    encode_config,
)
from gm_grader import view
from gm_grader.clock import OUTER_MARGIN, STARTUP_LIMIT, CellClock
from gm_grader.runner import GRACE as _RUNNER_GRACE

MAX_EVIDENCE_BYTES = 64_000_000
MAX_LOG_BYTES = 20_000


class Killed(Enum):
    """Why the grading process ended a sandbox before its runner said it was done."""

    TIME = "time"            # the notebook ran past --notebook-timeout
    CELL = "cell"            # a cell ran far past its limit and the runner did not end it
    EVIDENCE = "evidence"    # the runner sent more than MAX_EVIDENCE_BYTES


@dataclass(frozen=True)
class RunResult:
    """What one sandboxed run of a notebook brought back (the grading process's view)."""

    records: tuple[Record, ...]
    nonce: str
    salt: int
    killed: Killed | None = None
    log: str = ""
    seconds: float = 0.0
    cgroups: tuple[str, ...] = ()

    @property
    def kernel_pid(self) -> int | None:
        return next((r.pid for r in self.records if isinstance(r, KernelStarted)), None)


def sandbox_problem() -> str | None:
    """None when bubblewrap works here; otherwise a sentence saying why not."""
    bwrap = shutil.which("bwrap")
    if bwrap is None:
        return "bubblewrap (bwrap) is not installed (Debian/Ubuntu: apt-get install bubblewrap)"
    try:
        res = subprocess.run([bwrap, "--ro-bind", "/", "/", "--dev", "/dev", "--proc", "/proc",
                              "--unshare-all", "--die-with-parent", "--cap-drop", "ALL", "true"],
                             capture_output=True, timeout=30)
    except (OSError, subprocess.SubprocessError) as exc:
        return f"bubblewrap could not be started ({type(exc).__name__})"
    if res.returncode != 0:
        err = res.stderr.decode("utf-8", "replace").strip().splitlines()
        return "bubblewrap cannot make a sandbox here (" + (err[-1] if err else "unknown error") + ")"
    return None


# ------------------------------------------------------------------------------ cgroups
def _own_cgroup_dirs() -> dict[str, tuple[str, Path]]:
    """{controller: (cgroup version, folder of this process's cgroup)} for writable memory/pids
    controllers."""
    out: dict[str, tuple[str, Path]] = {}
    root = Path("/sys/fs/cgroup")
    try:
        lines = Path("/proc/self/cgroup").read_text().splitlines()
    except OSError:
        return out
    for line in lines:
        parts = line.split(":", 2)
        if len(parts) != 3:
            continue
        _, ctrls, path = parts
        if ctrls == "" and (root / "cgroup.controllers").exists():
            base = root / path.lstrip("/")
            try:
                avail = (base / "cgroup.controllers").read_text().split()
            except OSError:
                continue
            for c in ("memory", "pids"):
                if c in avail:
                    out.setdefault(c, ("v2", base))
        for c in ctrls.split(","):
            if c in ("memory", "pids") and (root / c).is_dir():
                out[c] = ("v1", root / c / path.lstrip("/"))
    return {c: v for c, v in out.items() if os.access(v[1], os.W_OK)}


def _remove_stale(base: Path) -> None:
    """Remove the empty cgroups a grader that died (killed, power cut) left behind: named
    ``gm-grade-<pid>-...`` after a process that is gone. A cgroup with a process in it cannot be
    removed, so nothing that still runs loses its limits."""
    try:
        names = [p for p in base.iterdir() if p.name.startswith("gm-grade-")]
    except OSError:
        return
    for d in names:
        pid = d.name.split("-")[2] if d.name.count("-") >= 3 else ""
        if pid.isdigit() and not Path(f"/proc/{pid}").exists():
            try:
                d.rmdir()
            except OSError:
                pass


class _Cgroups:
    """Child cgroups (memory, pids) for one sandbox, where this process may create them."""

    def __init__(self, limits: Limits, tag: str) -> None:
        self.dirs: list[Path] = []
        self.kinds: list[str] = []
        try:
            found = {} if os.environ.get("GM_GRADE_NO_CGROUPS") == "1" else _own_cgroup_dirs()
        except Exception:  # noqa: BLE001
            found = {}
        for ctrl, (ver, base) in found.items():
            _remove_stale(base)
            d = base / tag
            try:
                d.mkdir(exist_ok=True)
                if ctrl == "pids":
                    (d / "pids.max").write_text(str(limits.processes))
                elif ver == "v1":
                    (d / "memory.limit_in_bytes").write_text(str(limits.memory_mb << 20))
                else:
                    (d / "memory.max").write_text(str(limits.memory_mb << 20))
                self.dirs.append(d)
                self.kinds.append(ctrl)
            except OSError:
                try:
                    d.rmdir()
                except OSError:
                    pass

    def join(self) -> None:  # runs in the child between fork and exec
        for d in self.dirs:
            try:
                with open(d / "cgroup.procs", "w") as f:
                    f.write("0")
            except OSError:
                pass

    def pids(self) -> set[int]:
        out: set[int] = set()
        for d in self.dirs:
            try:
                out |= {int(p) for p in (d / "cgroup.procs").read_text().split()}
            except (OSError, ValueError):
                pass
        return out

    def close(self) -> None:
        """Kill every process of the cgroups (a daemon that called setsid, a probe that killed its
        keeper: all of them), then remove the cgroups."""
        for d in self.dirs:
            try:
                (d / "cgroup.kill").write_text("1")    # cgroup v2 (Linux 5.14+): all at once
            except OSError:
                pass
        for _ in range(100):
            left = self.pids()
            if not left:
                break
            for p in left:
                try:
                    os.kill(p, signal.SIGKILL)
                except OSError:
                    pass
            time.sleep(0.05)
        for d in self.dirs:
            try:
                d.rmdir()
            except OSError:
                pass


# ------------------------------------------------------------------------------ one run
def run_env(home: str) -> dict[str, str]:
    """The environment of a graded run whose writable folders are under ``home``."""
    keep = {k: v for k, v in os.environ.items() if k in ("PATH", "LANG", "LC_ALL", "TZ")}
    pp = [str(view.PKG_PARENT)]
    return {**keep, "PYTHONPATH": os.pathsep.join(pp), "HOME": f"{home}/home",
            "IPYTHONDIR": f"{home}/ipython", "JUPYTER_RUNTIME_DIR": f"{home}/runtime",
            "JUPYTER_CONFIG_DIR": f"{home}/jupyter", "MPLCONFIGDIR": f"{home}/mpl",
            "XDG_CACHE_HOME": f"{home}/cache", "MPLBACKEND": "Agg", "PYTHONDONTWRITEBYTECODE": "1",
            "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1",
            "PYDEVD_DISABLE_FILE_VALIDATION": "1", "GM_CHECKS_GRADING": "1"}


def _mpl_cache() -> str | None:
    try:
        import matplotlib
        return str(matplotlib.get_cachedir())
    except Exception:  # noqa: BLE001
        return None


class _OuterClock:
    """The runner's cell clock kept again here, outside the sandbox, from its records as they
    arrive (:mod:`gm_grader.clock`): the kernel can stop or stall its runner, not this process.
    Each whole line is decoded (:func:`gm_core.checks.protocol.decode_record`) once, here; the
    records are kept for the judge and junk lines are dropped."""

    def __init__(self, limits: Limits, caps: Mapping[str, float] | None, started: float) -> None:
        self.clock = CellClock(caps)
        self.clock.restart(started)
        self.cell_bound = limits.cell_timeout + _RUNNER_GRACE + OUTER_MARGIN
        self.bound = STARTUP_LIMIT            # until the first cell starts
        self.pending: list[bytes] = []        # the pieces of the line being received
        self.records: list[Record] = []
        self.done = False

    def feed(self, chunk: bytes, now: float) -> None:
        if b"\n" not in chunk:
            self.pending.append(chunk)        # joined once, when its line ends
            return
        first, *lines, last = chunk.split(b"\n")
        for line in [b"".join([*self.pending, first]), *lines]:
            if line.strip():
                self._line(line, now)
        self.pending = [last] if last else []

    def _line(self, line: bytes, now: float) -> None:
        try:
            rec = decode_record(line)
        except ProtocolError:
            return                             # junk: the runner writes none
        self.records.append(rec)
        if isinstance(rec, (CellStarted, CellEnded)):
            self.clock.restart(now)
            self.bound = self.cell_bound
        elif isinstance(rec, CheckAnnounced):
            self.clock.begin(rec.part, now)
        elif isinstance(rec, EvidenceLine):
            self.clock.end(now)
        elif isinstance(rec, Done):
            self.done = True

    def over(self, now: float) -> bool:
        return self.clock.seconds(now) > self.bound


def run_submission(notebook: str | Path, *, limits: Limits, sandbox: bool = True,
                   nonce: str | None = None, salt: int | None = None,
                   caps: Mapping[str, float] | None = None, own_user: bool = False) -> RunResult:
    """Run ``notebook`` (a staged copy: a plain file of the grader's) in its sandbox; return what
    it brought back.

    ``own_user`` (without a sandbox, a root grader): run it as a fresh uid of its own
    (:func:`gm_grader.view.unsandboxed_user` says whether that works here).

    ``caps``: {"<exercise>/<part>": seconds} the longest honest check of each part may take
    (:func:`gm_grader.clock.check_caps`), credited on the cell clocks."""
    notebook = Path(notebook)
    private = Path(tempfile.mkdtemp(prefix="gm-grade-"))
    os.chmod(private, 0o700)
    log, received = b"", 0
    killed: Killed | None = None
    proc = None
    cgroups: _Cgroups | None = None
    rfd = wfd = -1
    started = time.monotonic()
    try:
        inbox = view.make_inbox(private)
        name = "submission.ipynb"
        shutil.copyfile(notebook, inbox / name)
        identity = view.sandbox_identity() if sandbox or own_user else None
        inside = view.INBOX if sandbox else str(inbox)
        fonts = _stage_font_cache(inbox / "mpl")
        rfd, wfd = os.pipe()
        scratch = "/tmp" if sandbox else str(private / "tmp")
        config = RunnerConfig(notebook=f"{inside}/{name}", workdir=f"{scratch}/work",
                              evidence_fd=wfd, nonce=nonce or secrets.token_hex(16),
                              salt=salt if salt is not None else secrets.randbits(62),
                              limits=limits, caps=dict(caps or {}),
                              mpl_cache=f"{inside}/mpl" if fonts else None)
        (inbox / "config.json").write_text(encode_config(config))
        for f in inbox.rglob("*"):
            f.chmod(0o755 if f.is_dir() else 0o644)   # the sandbox's user reads them; no one writes
        cmd = [sys.executable, "-m", "gm_grader.runner", f"{inside}/config.json"]
        if sandbox and identity is not None:
            etc = view.write_identity_files(private / "etc", identity)
            cmd = view.command(inbox, etc, identity, limits, cmd)
        else:
            (private / "tmp").mkdir()
            if identity is not None:     # no sandbox: the run's own user, in its own /tmp only
                os.chmod(private, 0o711)
                os.chown(private / "tmp", identity.uid, identity.gid)
                cmd = view.dropped(identity, cmd)
        cgroups = _Cgroups(limits, f"gm-grade-{os.getpid()}-{secrets.token_hex(4)}")
        cmd, preexec = _limited(cmd, limits, cgroups,
                                own_user=identity is not None and identity.drop)
        started = time.monotonic()
        outer = _OuterClock(limits, caps, started)
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, pass_fds=(wfd,), env=run_env(scratch),
                                cwd=str(private if not sandbox else "/"), preexec_fn=preexec,
                                start_new_session=True)
        os.close(wfd)
        wfd = -1
        assert proc.stdout is not None
        streams = {rfd: "e", proc.stdout.fileno(): "o"}
        deadline = started + limits.notebook_timeout
        while streams:
            if rfd not in streams and proc.poll() is not None:
                break   # the runner is gone and said all it will say
            now = time.monotonic()
            wait = deadline - now
            if wait <= 0:
                killed = Killed.TIME
                break
            if outer.over(now):
                killed = Killed.CELL      # the runner did not end an over-long cell: end it all
                break
            ready, _, _ = select.select(list(streams), [], [], min(wait, 0.5))
            for fd in ready:
                chunk = os.read(fd, 1 << 16)
                if not chunk:
                    del streams[fd]
                elif streams[fd] == "e":
                    if received >= MAX_EVIDENCE_BYTES:
                        killed = killed or Killed.EVIDENCE
                        continue
                    received += len(chunk)
                    outer.feed(chunk, time.monotonic())
                    if outer.done:
                        streams.clear()     # the runner has said all: end the sandbox now
                        break
                elif len(log) < MAX_LOG_BYTES:
                    log += chunk
            if killed is Killed.EVIDENCE:
                break
    finally:
        for fd in (wfd, rfd):
            if fd >= 0:
                os.close(fd)
        if proc is not None:
            _stop(proc)
        if cgroups is not None:
            cgroups.close()
        shutil.rmtree(private, ignore_errors=True)
    result = RunResult(records=tuple(outer.records), nonce=config.nonce, salt=config.salt,
                       killed=killed, log=log.decode("utf-8", "replace")[-4000:],
                       seconds=time.monotonic() - started,
                       cgroups=tuple(sorted(cgroups.kinds)) if cgroups is not None else ())
    kernel_pid = result.kernel_pid
    if not sandbox and kernel_pid and proc is not None and _session_of(kernel_pid) == kernel_pid \
            and kernel_pid not in (os.getpid(), os.getpgrp(), os.getsid(0)):
        _killpg(kernel_pid)   # the kernel has its own session; without a pid namespace end it here
    return result


def _stage_font_cache(dst: Path) -> bool:
    """Copy matplotlib's font list (built once on this machine) into the run's inbox, so the
    kernel need not rebuild it: True if there was one. The cache folder itself is not shown to
    the sandbox (it may lie in the grader's home)."""
    src = _mpl_cache()
    if src is None:
        return False
    try:
        names = [n for n in os.listdir(src) if n.startswith("fontlist") and n.endswith(".json")]
        if not names:
            return False
        dst.mkdir()
        for n in names:
            shutil.copyfile(os.path.join(src, n), dst / n)
    except OSError:
        return False
    return True


def startup_fault(result: RunResult) -> str | None:
    """Why the grader, not the notebook, is to blame for a run that ended before any of the
    student's cells began (None when a cell began, the notebook could not be read, or the run
    finished): the sandbox or the runner did not start, the kernel or the course's checkers could
    not be loaded. Nothing of the submission runs before its first cell, so none of this can be
    its doing."""
    recs = result.records
    if not any(isinstance(r, Started) for r in recs):
        tail = [ln.strip() for ln in result.log.splitlines() if ln.strip()]
        return ("the sandbox or the grader's runner could not start"
                + (f" ({tail[-1][:200]})" if tail else ""))
    if any(isinstance(r, (CellStarted, CellEnded, EvidenceLine, Done)) for r in recs):
        return None
    fatal = next((r.message for r in recs if isinstance(r, Fatal)), None)
    if fatal is not None and fatal.startswith("the notebook could not be read"):
        return None
    if fatal is not None:
        return f"the notebook's kernel could not be prepared ({fatal[:200]})"
    if result.killed is not None:
        return "the notebook's kernel did not start in time"
    return "the grader's runner ended before the notebook's first cell"


_JOIN = ('for c in "$@"; do [ "$c" = -- ] && break; echo $$ > "$c/cgroup.procs" 2>/dev/null; '
         'shift; done; shift; exec "$@"')


def _limited(cmd: list[str], limits: Limits, cgroups: _Cgroups,
             own_user: bool = False) -> tuple[list[str], Callable[[], None] | None]:
    """(command, preexec_fn) applying the limits before ``cmd`` starts: a shell joins the cgroups
    and ``prlimit`` sets the resource limits, then both exec (no Python runs between fork and
    exec, which matters with --jobs); without prlimit, a preexec_fn does the same.

    ``own_user``: the sandbox drops to a uid of its own (a root grader, :mod:`gm_grader.view`),
    so ``RLIMIT_NPROC`` counts this notebook's processes alone; a root grader's other runs are
    not held by it (the pids cgroup does that), a user's are counted with the user's own."""
    mem, fsize = limits.memory_mb << 20, limits.tmp_mb << 20
    nproc = (limits.processes if own_user else
             limits.processes + _user_processes() if os.geteuid() != 0 else None)
    prlimit = shutil.which("prlimit")
    if prlimit is not None and Path("/bin/sh").exists():
        lim = [f"--as={mem}", f"--fsize={fsize}", "--core=0"]
        if nproc is not None:   # root is not held by RLIMIT_NPROC: its sandbox's own user is
            lim.append(f"--nproc={nproc}")
        return ["/bin/sh", "-c", _JOIN, "sh", *map(str, cgroups.dirs), "--", prlimit, *lim,
                "--", *cmd], None

    def preexec() -> None:
        cgroups.join()
        for res, val in ((resource.RLIMIT_AS, mem), (resource.RLIMIT_CORE, 0),
                         (resource.RLIMIT_FSIZE, fsize)) + (
                ((resource.RLIMIT_NPROC, nproc),) if nproc is not None else ()):
            try:
                resource.setrlimit(res, (val, val))
            except (ValueError, OSError):
                pass
    return cmd, preexec


def _session_of(pid: int) -> int | None:
    """The session id of a live process (the kernel leads its own), or None."""
    try:
        return os.getsid(pid)
    except OSError:
        return None


def _user_processes() -> int:
    uid, n = os.getuid(), 0
    for p in Path("/proc").iterdir():
        if p.name.isdigit():
            try:
                if p.stat().st_uid == uid:
                    n += 1
            except OSError:
                pass
    return n


def _killpg(pid: int) -> None:
    try:
        os.killpg(pid, signal.SIGKILL)
    except OSError:
        pass


def _stop(proc: subprocess.Popen[bytes]) -> None:
    """End the sandbox: its process group first, then bwrap itself (taking its namespace)."""
    if proc.poll() is None:
        _killpg(proc.pid)
        try:
            proc.kill()
        except OSError:
            pass
    try:
        proc.wait(timeout=30)
    except subprocess.TimeoutExpired:
        pass
    _killpg(proc.pid)
    if proc.stdout is not None:
        proc.stdout.close()

"""The probe sandbox cleans up after itself and says what stopped a call (issue 20, point 7).

Real forks, real sessions, real signals: a student function that forks a grandchild that never
ends, one that calls os.setsid and forks, a double-forked daemon, one that kills the sandbox's
keeper, a fork bomb of busy loops under the time limit; after the check returns, none of them is
left. And KeyboardInterrupt, SIGALRM, the time limit, memory, recursion and crashes each give
their own friendly message.

The processes left behind sleep rather than spin: the sandbox ends a process the same way
whatever it does, and a dozen busy loops living until each check ended only took the test
machine's two cores from the rest of the suite. The fork bomb, the Stop button and the time limit
keep their busy loops: spinning is what those cases are about.
"""
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from gm_core import SE2, checks
from gm_core.checks.sandbox import collect, current_settings
from gm_core.checks.store import FAILED, PASSED

ROOT = Path(__file__).resolve().parent.parent
pytestmark = [pytest.mark.usefixtures("clean"),
              pytest.mark.skipif(not (hasattr(os, "fork") and Path("/proc/self/stat").exists()),
                                 reason="needs fork and /proc (Linux)")]
OURS = Path("/proc/self/cmdline").read_bytes()


def _announce(pids):
    (pids / f"{os.getpid()}.pid").write_text("")


def linger(pids):
    """Become a process that never ends on its own and that anyone can find (its pid is written
    into the folder ``pids``)."""
    _announce(pids)
    while True:
        time.sleep(3600)


def busy(pids):
    """Become a busy loop that anyone can find (its pid is written into the folder ``pids``)."""
    _announce(pids)
    while True:
        pass


def running(pids):
    """The recorded processes that still exist (same command line: not a reused pid)."""
    left = []
    for f in pids.glob("*.pid"):
        try:
            if Path(f"/proc/{f.stem}/cmdline").read_bytes() == OURS:
                left.append(int(f.stem))
        except OSError:
            pass
    return left


def gone(pids, within=10.0):
    """Wait until none of the recorded processes exists; return those still there."""
    deadline = time.monotonic() + within
    while running(pids) and time.monotonic() < deadline:
        time.sleep(0.05)
    return running(pids)


@pytest.fixture(autouse=True)
def _no_escapee_survives_a_failing_test(tmp_path):
    """Should the sandbox ever fail, the processes a test started do not outlive the test."""
    yield
    for pid in running(tmp_path):
        try:
            os.kill(pid, signal.SIGKILL)
        except OSError:
            pass


def wait_for_pids(pids, n, within=10.0):
    deadline = time.monotonic() + within
    while len(list(pids.glob("*.pid"))) < n and time.monotonic() < deadline:
        time.sleep(0.02)
    assert len(list(pids.glob("*.pid"))) >= n, "the student's process never started"


def forks_a_lingering_grandchild(pids):
    def f(xi):
        if os.fork() == 0:
            linger(pids)
        return SE2.exp(xi)
    return f


def setsid_then_fork(pids):
    def f(xi):
        try:
            os.setsid()               # the first call makes a new session; later calls refuse
        except OSError:
            pass
        if os.fork() == 0:
            linger(pids)
        return SE2.exp(xi)
    return f


def double_forked_daemon(pids):
    def f(xi):
        if os.fork() == 0:
            os.setsid()
            if os.fork() == 0:
                linger(pids)
            os._exit(0)               # the daemon is orphaned at once
        time.sleep(0.02)
        return SE2.exp(xi)
    return f


@pytest.mark.parametrize("make", [forks_a_lingering_grandchild, setsid_then_fork, double_forked_daemon])
def test_no_grandchild_outlives_the_check_and_the_check_does_not_wait_for_it(make, tmp_path):
    student = make(tmp_path)
    t = time.monotonic()
    v = checks.ex1_4.a.check(student, quiet=True, time_limit=30)
    took = time.monotonic() - t
    assert v.status == PASSED, v.message                 # the answer itself is right
    assert took < 15, f"the check waited {took:.1f} s for processes it should have ended"
    assert list(tmp_path.glob("*.pid")), "the student's grandchildren never ran"
    assert gone(tmp_path) == []


def test_a_grandchild_holding_the_result_pipe_does_not_hold_the_check(tmp_path):
    def f(_):
        if os.fork() == 0:
            linger(tmp_path)          # inherits the pipe's write end and never closes it
        return 1.0
    t = time.monotonic()
    outcomes, _ = collect(f, [lambda g: g(0)], time_limit=30)
    assert outcomes[0]["k"] == "ok" and outcomes[0]["v"] == 1.0
    assert time.monotonic() - t < 5
    assert gone(tmp_path) == []


def test_a_fork_bomb_under_the_time_limit_is_ended_whole(tmp_path):
    def bomb(_):
        for _ in range(4):
            os.fork()
        busy(tmp_path)
    t = time.monotonic()
    outcomes, _ = collect(bomb, [lambda g: g(0), lambda g: g(1)], time_limit=1.5)
    assert time.monotonic() - t < 10
    assert [o["k"] for o in outcomes] == ["timeout", "skipped"]
    wait_for_pids(tmp_path, 1)
    assert gone(tmp_path) == []


@pytest.mark.parametrize("then", ["returns", "leaves its process group and loops",
                                  "leaves its session and loops", "leaves its session, forks, returns"])
def test_a_student_process_that_kills_its_parent_leaves_nothing_behind(tmp_path, then):
    def f(_):
        if os.fork() == 0:
            linger(tmp_path)
        os.kill(os.getppid(), signal.SIGKILL)    # the sandbox's keeper
        time.sleep(0.1)
        if then == "leaves its process group and loops":
            os.setpgid(0, 0)
            linger(tmp_path)
        elif then.startswith("leaves its session"):
            os.setsid()                          # out of the keeper's session and group
            if then.endswith("loops"):
                linger(tmp_path)
            if os.fork() == 0:
                os.setsid()                      # (fails: already a leader) and orphaned below
                linger(tmp_path)
            time.sleep(0.1)
        return 2.0
    outcomes, _ = collect(f, [lambda g: g(0)], time_limit=2)
    assert outcomes[0]["k"] == ("timeout" if then.endswith("loops") else "ok")
    wait_for_pids(tmp_path, 1 if then == "returns" else 2)
    assert gone(tmp_path) == []


def test_the_late_reaper_never_takes_a_process_the_notebook_starts_after_the_check():
    """The check's process adopts orphans of the probe tree while the check runs; a process the
    notebook starts once the check has returned (its next cell's subprocess) is not one of them,
    however late the background reaper runs."""
    from gm_core.checks.proctree import Adoption
    adoption = Adoption().start()
    pid = adoption.fork()
    if pid == 0:  # pragma: no cover - a keeper with nothing to do
        os._exit(0)
    os.waitpid(pid, 0)
    adoption.keeper_reaped()
    adoption.close_window()                    # the check is over
    time.sleep(0.05)
    later = subprocess.Popen(["sleep", "30"])
    try:
        adoption.end_strays()                  # what the reaper thread does, late
        assert later.poll() is None, "the notebook's own process was killed"
    finally:
        adoption.release()
        later.kill()
        later.wait()


def test_the_stop_button_interrupts_the_check_and_ends_the_student_processes(tmp_path):
    """Jupyter's Stop button sends SIGINT to the kernel: the check stops at once with the usual
    KeyboardInterrupt, and the student's processes end with it."""
    code = f"""
import os, signal, sys, time
# as ipykernel runs a cell (Kernel.pre_handler_hook): SIGINT raises KeyboardInterrupt, whatever
# disposition this process inherited from the test run (an ignored SIGINT is inherited)
signal.signal(signal.SIGINT, signal.default_int_handler)
sys.path.insert(0, {str(ROOT)!r})
from pathlib import Path
from gm_core import checks
pids = Path({str(tmp_path)!r})
def f(xi):
    if os.fork() == 0:
        (pids / f"{{os.getpid()}}.pid").write_text("")
        while True: pass
    (pids / f"{{os.getpid()}}.pid").write_text("")
    while True: pass
try:
    checks.ex1_4.a.check(f, quiet=True, time_limit=60)
    print("NOT INTERRUPTED")
except KeyboardInterrupt:
    print("INTERRUPTED", flush=True)
time.sleep(30)
"""
    env = dict(os.environ, PYTHONPATH=str(ROOT), GM_CHECKS_NO_FORK="")
    proc = subprocess.Popen([sys.executable, "-c", code], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        wait_for_pids(tmp_path, 2, within=60)
        t = time.monotonic()
        proc.send_signal(signal.SIGINT)
        assert proc.stdout.readline().strip() == "INTERRUPTED"
        assert time.monotonic() - t < 15                 # not the 60 s limit
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and any(Path(f"/proc/{f.stem}").exists()
                                                  for f in tmp_path.glob("*.pid")):
            time.sleep(0.05)
        assert not [f.stem for f in tmp_path.glob("*.pid") if Path(f"/proc/{f.stem}").exists()]
    finally:
        proc.kill()
        proc.wait()
        for f in tmp_path.glob("*.pid"):          # should anything have escaped: not past the test
            try:
                if str(tmp_path).encode() in Path(f"/proc/{f.stem}/cmdline").read_bytes():
                    os.kill(int(f.stem), signal.SIGKILL)
            except OSError:
                pass


# ------------------------------------------------------------------------------ what happened, said plainly
def _raise_keyboard_interrupt(xi):
    raise KeyboardInterrupt


def _sigint_to_itself(xi):
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(5)


def _alarm(xi):
    signal.setitimer(signal.ITIMER_REAL, 0.05)
    time.sleep(5)


def _too_much_memory(xi):
    return bytearray((current_settings().memory_mb + 1024) * 2 ** 20)


def _endless_recursion(xi):
    return _endless_recursion(xi)


def _segfault(xi):
    import ctypes
    return ctypes.string_at(0)


def _exits(xi):
    os._exit(3)


def _killed(xi):
    os.kill(os.getpid(), signal.SIGKILL)


def _forever(xi):
    while True:
        pass


CASES = {
    _raise_keyboard_interrupt: ("KeyboardInterrupt", "interrupted"),
    _sigint_to_itself: ("KeyboardInterrupt", "interrupted"),
    _alarm: ("AlarmSignal", "alarm signal (SIGALRM)"),
    _too_much_memory: ("MemoryError", "more memory than it may have"),
    _endless_recursion: ("RecursionError", "recursed without end"),
    _segfault: ("crashed", "segmentation fault"),
    _exits: ("crashed", "exit status 3"),
    _killed: ("crashed", "SIGKILL"),
    _forever: ("took longer than 1.5 s", "set_time_limit"),
}


def test_every_way_a_call_can_stop_has_its_own_friendly_message():
    if not current_settings().memory_mb:
        pytest.skip("the memory limit is turned off (GM_CHECKS_MEMORY_MB=0)")
    messages = {}
    for f, words in CASES.items():
        v = checks.ex1_4.a.check(f, quiet=True, time_limit=1.5)
        assert v.status == FAILED
        for w in words:
            assert w in v.message, (f.__name__, v.message)
        assert "xi=" in v.message and "Traceback" not in v.message
        assert "too much memory, or a recursion" not in v.message      # the old catch-all
        messages[f.__name__] = v.message
    assert len(set(messages.values())) == len(set(CASES.values()))     # one per kind of stop
    assert checks.ex1_4.a.check(checks.ex1_4.a.reference, quiet=True).passed   # kernel fine


def test_an_alarm_in_one_call_does_not_stop_the_next_calls():
    calls = []

    def f(x):
        calls.append(x)
        if x == 0:
            signal.setitimer(signal.ITIMER_REAL, 0.1)
            time.sleep(5)
        return float(x)
    outcomes, _ = collect(f, [lambda g: g(0), lambda g: g(1)], time_limit=4)
    assert outcomes[0]["k"] == "error" and outcomes[0]["m"] == "AlarmSignal"
    assert outcomes[1] == {"k": "ok", "m": "", "x": "", "v": 1.0}

"""The student-side half of grading: the evidence channel inside the graded notebook's kernel.

When the grader runs a notebook (:mod:`gm_grader.batch`), its runner executes one hidden
cell *before any of the student's cells*: :func:`open_channel` binds the write end of a pipe the
runner created before the kernel started, and records this run's nonce and probe-input salt
(chosen by the grader, unpredictable to the notebook) and the grader's per-call time limit (a
``set_time_limit`` or ``check(time_limit=...)`` in the notebook may lower it, not raise it). From then on every ``part.check(...)``
in the notebook, whatever form the call takes (keywords, ``Exercise.check({...})``, an alias, a
helper function), writes one line to that pipe at the moment it is called: the part, and the
plain outcomes its probes produced on the answer *as it was then*. The grader reads that pipe,
never the notebook's printed output, and judges in its own process.

Lines on the pipe: ``B <part id>`` when a check starts (the runner stops the cell clock while
probes run: each probe has its own per-call limit), then ``R <json>`` with the evidence.
"""
from __future__ import annotations

import json
import os

_STATE = {"fd": None, "nonce": None, "salt": None, "time_limit": None}
MAX_RECORD_BYTES = 4_000_000


def open_channel(fd, nonce, salt, time_limit=None):
    """Bind the evidence pipe (called by the grader's runner before any student code runs)."""
    _STATE["fd"], _STATE["nonce"] = int(fd), str(nonce)
    set_probe_salt(salt)
    if time_limit is not None:     # the runner also makes it the default (sandbox.set_time_limit)
        _STATE["time_limit"] = float(time_limit)


def time_limit():
    """The grader's per-call limit while grading (no check may allow more), else None."""
    return _STATE["time_limit"] if active() else None


def set_probe_salt(salt):
    """Set (or clear, with None) the salt mixed into the seeds of the checkers' random inputs."""
    _STATE["salt"] = None if salt is None else int(salt)


def probe_salt():
    return _STATE["salt"]


def active():
    return _STATE["fd"] is not None


def _write(data: bytes):
    fd = _STATE["fd"]
    if fd is None:
        return
    try:
        while data:
            n = os.write(fd, data)
            data = data[n:]
    except OSError:
        _STATE["fd"] = None   # the runner is gone; the kernel carries on


def begin(part):
    """A check of ``part`` starts (its probes' time is not counted against the cell)."""
    if active():
        _write(f"B {part.exercise.id}/{part.name}\n".encode())


def emit(part, outcomes, output=""):
    """Send the evidence of one check call: plain (JSON-able) outcomes, the captured output."""
    if not active():
        return
    rec = {"n": _STATE["nonce"], "ex": part.exercise.id, "part": part.name,
           "o": outcomes, "out": str(output)[:2000]}
    try:
        line = json.dumps(rec)
    except (TypeError, ValueError):
        line = json.dumps({**rec, "o": "unserialisable"})
    data = ("R " + line + "\n").encode()
    if len(data) > MAX_RECORD_BYTES:
        data = ("R " + json.dumps({**rec, "o": "too large", "out": ""}) + "\n").encode()
    _write(data)

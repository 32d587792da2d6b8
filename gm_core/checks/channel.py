"""The student-side half of grading: the evidence channel inside the graded notebook's kernel.

When the grader runs a notebook (:mod:`gm_grader.batch`), its runner executes one hidden
cell *before any of the student's cells*: :func:`open_channel` binds the write end of a pipe the
runner created before the kernel started, and records this run's nonce and probe-input salt
(chosen by the grader, unpredictable to the notebook) and the grader's per-call time limit (a
``set_time_limit`` or ``check(time_limit=...)`` in the notebook may lower it, not raise it). From then on every ``part.check(...)``
in the notebook, whatever form the call takes (keywords, ``Exercise.check({...})``, an alias, a
helper function), writes one line to that pipe at the moment it is called: the part, and the
plain outcomes its probes produced on the answer *as it was then* (the student's feedback; they
carry no weight in the grade), and the answer itself as it was then, as text made by the
grader's carrier (the hidden cell passes :func:`gm_grader.probe.dumps`: a pickle by value). The
grader reads that pipe, never the notebook's printed output. It never loads an answer itself: after
the notebook has ended it chooses new probe inputs and calls the last checked answer of every part
in a fresh sandbox of its own (:mod:`gm_grader.probe`), then judges the plain outcomes there
in its own process.

The lines are the messages of :mod:`gm_core.checks.protocol`: a :class:`~.protocol.CheckBegun`
when a check starts (the runner stops the cell clock while probes run: each probe has its own
per-call limit), then the :class:`~.protocol.Evidence` of the call. A notebook that asks a part
for its answer key (the graded build has none, :mod:`gm_core.checks.answer_key`) sends an Evidence
saying so (:func:`key_requested`).
"""
from __future__ import annotations

import os
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from gm_core.checks.protocol import (
    MAX_ANSWER,
    MAX_OUTPUT,
    MAX_UNSENT,
    CheckBegun,
    Evidence,
    KernelMessage,
    Outcome,
    OutcomeKind,
    ProtocolError,
    Withheld,
    decode_outcome,
    encode_kernel_message,
)

if TYPE_CHECKING:
    from gm_core.checks.parts import Part

__all__ = ["open_channel", "time_limit", "set_probe_salt", "probe_salt", "active", "begin", "emit",
           "key_requested", "stop_carrying_answers", "carried", "MAX_RECORD_BYTES"]

MAX_RECORD_BYTES = 4_000_000


@dataclass
class _Channel:
    """The kernel's end of the grader's pipe (fd None: not grading) and this run's settings."""

    fd: int | None = None
    nonce: str = ""
    salt: int | None = None
    time_limit: float | None = None
    carrier: Callable[[object], str] | None = None


_STATE = _Channel()


def open_channel(fd: int, nonce: str, salt: int | None, time_limit: float | None = None,
                 carrier: Callable[[object], str] | None = None) -> None:
    """Bind the evidence pipe (called by the grader's runner before any student code runs);
    ``carrier`` turns a checked answer into text for the grader (None: answers are not sent)."""
    _STATE.fd, _STATE.nonce, _STATE.carrier = int(fd), str(nonce), carrier
    set_probe_salt(salt)
    if time_limit is not None:     # the runner also makes it the default (sandbox.set_time_limit)
        _STATE.time_limit = float(time_limit)


def stop_carrying_answers() -> None:
    """From now on send only outcomes (the grader's own calls of an answer,
    :mod:`gm_grader.probe`, carry nothing back)."""
    _STATE.carrier = None


def carried(answer: object) -> tuple[str, str]:
    """``answer`` as the grader's carrier writes it, or ``("", why not)`` (``("", "")`` when no
    carrier was given)."""
    carrier = _STATE.carrier
    if carrier is None:
        return "", ""
    try:
        text = carrier(answer)
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # noqa: BLE001 - a lock, a generator, an open file...
        return "", _cannot_copy(exc)
    if not isinstance(text, str) or len(text) > MAX_ANSWER:
        return "", "it is too large to hand over, with everything it refers to"
    return text, ""


_CANNOT_PICKLE = re.compile(r"cannot pickle '([A-Za-z_][\w.]{0,60})' object")


def _cannot_copy(exc: BaseException) -> str:
    """Why an answer could not be carried, in the grader's own words: the kind of object pickle
    named, never text the answer's own code chose."""
    m = _CANNOT_PICKLE.search(str(exc))
    what = f"a {m.group(1)}" if m else f"something that cannot be copied ({type(exc).__name__[:40]})"
    return f"it holds {what}, which cannot be copied out of the notebook"[:MAX_UNSENT]


def time_limit() -> float | None:
    """The grader's per-call limit while grading (no check may allow more), else None."""
    return _STATE.time_limit if active() else None


def set_probe_salt(salt: int | None) -> None:
    """Set (or clear, with None) the salt mixed into the seeds of the checkers' random inputs."""
    _STATE.salt = None if salt is None else int(salt)


def probe_salt() -> int | None:
    return _STATE.salt


def active() -> bool:
    return _STATE.fd is not None


def _write(data: bytes) -> None:
    fd = _STATE.fd
    if fd is None:
        return
    try:
        while data:
            n = os.write(fd, data)
            data = data[n:]
    except OSError:
        _STATE.fd = None   # the runner is gone; the kernel carries on


def _send(msg: KernelMessage) -> None:
    _write(encode_kernel_message(msg))


def _exercise_id(part: Part) -> str:
    return part.exercise.id if part.exercise is not None else ""


def begin(part: Part) -> None:
    """A check of ``part`` starts (its probes' time is not counted against the cell)."""
    if active():
        _send(CheckBegun(f"{_exercise_id(part)}/{part.name}"))


def _outcome(raw: object) -> Outcome:
    """A probe's plain result as an Outcome; one the grader could not read is a crash (as the
    student's own check sees it)."""
    try:
        return decode_outcome(raw)
    except ProtocolError:
        return Outcome(OutcomeKind.CRASH, message="unreadable result")


def emit(part: Part, outcomes: Sequence[Mapping[str, object]] | str, output: str = "",
         answer: object = None) -> None:
    """Send the evidence of one check call: the probes' plain outcomes (or ``"stopped"``), the
    captured output and the checked ``answer`` (pickled, see :func:`carried`)."""
    if not active():
        return
    got: tuple[Outcome, ...] | Withheld = (
        tuple(_outcome(o) for o in outcomes) if isinstance(outcomes, list) else Withheld.STOPPED)
    text, unsent = carried(answer)
    ev = Evidence(_STATE.nonce, _exercise_id(part), part.name, got, str(output)[:MAX_OUTPUT],
                  text, unsent)
    try:
        data = encode_kernel_message(ev)
    except (TypeError, ValueError):
        data = encode_kernel_message(Evidence(ev.nonce, ev.exercise, ev.part,
                                              Withheld.UNSERIALISABLE, ev.output, text, unsent))
    if len(data) > MAX_RECORD_BYTES:
        data = encode_kernel_message(Evidence(ev.nonce, ev.exercise, ev.part, Withheld.TOO_LARGE,
                                              "", text, unsent))
    _write(data)


def key_requested(part: Part, asked: str) -> None:
    """Tell the grader that the notebook asked ``part`` for its answer key (``asked``: which
    attribute or method), which the graded build does not have: the part gets no marks."""
    if active():
        _send(Evidence(_STATE.nonce, _exercise_id(part), part.name, Withheld.KEY_ASKED,
                       str(asked)[:200]))

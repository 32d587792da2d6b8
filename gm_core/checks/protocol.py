"""The grader's wire protocol: every message that crosses a process boundary, typed, one codec.

Three processes talk while a notebook is graded (:mod:`gm_grader`): the grading process starts
the runner (a :class:`RunnerConfig` in a JSON file), the runner runs the notebook's kernel, and
the kernel's checks (:mod:`gm_core.checks.channel`) write :class:`CheckBegun` and
:class:`Evidence` lines on a pipe to the runner, which forwards them, with its own records of
cells and kernels, as :class:`Record` lines to the grading process. Each message is a frozen
dataclass; each is turned into JSON by one ``encode_*`` function here and read back by one
``decode_*`` function here, which parses the whole line and checks it strictly (exact fields, exact
types, sizes and nesting capped) and raises :class:`ProtocolError` with the reason otherwise. No
other module reads or writes these lines, so no reader depends on how JSON was spaced.

An :class:`Outcome` is the plain result of one probe, in the form the probes' sandbox
(:mod:`gm_core.checks.sandbox`) writes (keys ``k``, ``v``, ``m``, ``x``); :meth:`Outcome.to_json`
gives that form back for the checkers' judges. This module imports nothing of the course (the
kernel imports it before any student code runs).
"""
from __future__ import annotations

import json
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from enum import Enum
from typing import Any, ClassVar, TypeAlias

__all__ = [
    "ProtocolError", "ForeignEvidence", "OutcomeKind", "Outcome", "plain_value", "Withheld", "Evidence",
    "CheckBegun", "KernelMessage", "RecordKind", "CellStatus", "Record", "Started",
    "KernelStarted", "CellStarted", "CellEnded", "CheckAnnounced", "EvidenceLine", "OutputSize",
    "Flooded", "Fatal", "Done", "Limits", "RunnerConfig", "encode_outcome", "decode_outcome",
    "encode_kernel_message", "decode_check_begun", "decode_evidence", "encode_record",
    "decode_record", "encode_config", "decode_config", "MAX_EVIDENCE_LINE", "MAX_DEPTH",
    "MAX_TEXT", "MAX_MESSAGE", "MAX_OUTPUT", "MAX_PART_KEY", "MAX_ANSWER", "MAX_UNSENT",
]

#: Characters of a kernel's evidence line the grader reads at most.
MAX_EVIDENCE_LINE = 4_100_000
#: Nesting depth of a probe's value (lists in lists ...) the grader reads at most.
MAX_DEPTH = 12
#: Characters of a text inside a probe's value, of an outcome's message, of a check's output.
MAX_TEXT, MAX_MESSAGE, MAX_OUTPUT = 600, 2000, 2000
#: Characters of a part's key ("1.4/a") in a check's announcement.
MAX_PART_KEY = 78
#: Characters of a checked answer carried to the grader (base64 of its pickle), and of the reason
#: an answer could not be carried.
MAX_ANSWER, MAX_UNSENT = 1_000_000, 300
#: Characters of a message in a runner record (a fatal error, a flood note).
MAX_RECORD_TEXT = 2000

JSON: TypeAlias = Any    # plain JSON data (None, bool, int, float, str, list, dict)


class ProtocolError(ValueError):
    """A line that is not a well-formed message of this protocol; ``str(exc)`` says why."""


class ForeignEvidence(ProtocolError):
    """Well-formed evidence with this run's secret, for an exercise this notebook is not."""


def _loads(line: bytes | str, limit: int) -> JSON:
    if isinstance(line, (bytes, bytearray)):
        line = bytes(line).decode("utf-8", "replace")
    if not isinstance(line, str) or len(line) > limit:
        raise ProtocolError("an over-long or missing record")
    try:
        return json.loads(line)
    except (ValueError, RecursionError):
        raise ProtocolError("a record that is not valid JSON (or nested too deeply)") from None


def _dumps(obj: JSON) -> str:
    return json.dumps(obj, separators=(",", ":"))


def _is_int(v: object) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _is_number(v: object) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


# ------------------------------------------------------------------------------ outcomes
class OutcomeKind(Enum):
    """How one probe ended."""

    OK = "ok"
    WRONG = "wrong"
    UNATTEMPTED = "unattempted"
    ERROR = "error"
    TIMEOUT = "timeout"
    CRASH = "crash"
    SKIPPED = "skipped"


#: The fields each kind of outcome may carry on the wire (besides ``k``).
_OUTCOME_FIELDS = {OutcomeKind.OK: {"v"}, OutcomeKind.WRONG: {"m"}, OutcomeKind.UNATTEMPTED: {"m"}}
_OUTCOME_DEFAULT_FIELDS = {"m", "x"}


def plain_value(v: JSON, depth: int = 0) -> bool:
    """True for JSON data that :func:`gm_core.checks.sandbox.decode` turns into numbers, text,
    arrays (``{"__nd__": shape, "d": flat}`` with a consistent shape), lists and dicts."""
    if depth > MAX_DEPTH:
        return False
    if v is None or isinstance(v, bool):
        return True
    if isinstance(v, str):
        return len(v) <= MAX_TEXT
    if isinstance(v, (int, float)):
        return True
    if isinstance(v, list):
        return all(plain_value(x, depth + 1) for x in v)
    if isinstance(v, dict):
        if set(v) == {"__nd__", "d"}:
            shape, d = v["__nd__"], v["d"]
            return (isinstance(shape, list) and all(_is_int(s) and s >= 0 for s in shape)
                    and isinstance(d, list) and len(d) == math.prod(shape)
                    and all(_is_number(x) for x in d))
        if set(v) == {"__dict__"} and isinstance(v["__dict__"], list):
            return all(isinstance(kv, list) and len(kv) == 2 and isinstance(kv[0], str)
                       and plain_value(kv[1], depth + 1) for kv in v["__dict__"])
    return False


@dataclass(frozen=True)
class Outcome:
    """The plain result of one probe: its kind, the value (``OK`` only) or a message and detail."""

    kind: OutcomeKind
    value: JSON = None
    message: str = ""
    detail: str = ""

    def to_json(self) -> dict[str, JSON]:
        """The sandbox's form of this outcome (``{"k": ..., "v" | "m", "x": ...}``)."""
        return encode_outcome(self)


def encode_outcome(o: Outcome) -> dict[str, JSON]:
    """``o`` as JSON data (the sandbox's form: only the fields its kind has)."""
    out: dict[str, JSON] = {"k": o.kind.value}
    allowed = _OUTCOME_FIELDS.get(o.kind, _OUTCOME_DEFAULT_FIELDS)
    if "v" in allowed:
        out["v"] = o.value
    if "m" in allowed:
        out["m"] = o.message
    if "x" in allowed:
        out["x"] = o.detail
    return out


def decode_outcome(data: JSON) -> Outcome:
    """An :class:`Outcome` from JSON data, checked: a known kind, exactly the fields that kind may
    have (an ``ok`` needs its value), a plain value, texts of bounded length."""
    if not isinstance(data, dict) or "k" not in data:
        raise ProtocolError("an outcome that is not an object with a kind")
    try:
        kind = OutcomeKind(data["k"])
    except (ValueError, TypeError):
        raise ProtocolError("an outcome of an unknown kind") from None
    allowed = _OUTCOME_FIELDS.get(kind, _OUTCOME_DEFAULT_FIELDS)
    if not set(data) - {"k"} <= allowed:
        raise ProtocolError("an outcome with fields its kind does not have")
    if kind is OutcomeKind.OK:
        if "v" not in data or not plain_value(data["v"]):
            raise ProtocolError("an ok outcome without a plain value")
        return Outcome(kind, data["v"])
    texts = {f: data.get(f, "") for f in ("m", "x")}
    if not all(isinstance(t, str) and len(t) <= MAX_MESSAGE for t in texts.values()):
        raise ProtocolError("an outcome whose message is not short text")
    return Outcome(kind, None, texts["m"], texts["x"])


# ------------------------------------------------------------------------------ kernel -> runner
class Withheld(Enum):
    """Why a check call's evidence carries no outcomes."""

    STOPPED = "stopped"              # the check stopped before its probes finished
    UNSERIALISABLE = "unserialisable"
    TOO_LARGE = "too large"
    KEY_ASKED = "asked for the answer key"   # the notebook asked the graded build for a key


@dataclass(frozen=True)
class CheckBegun:
    """A check of ``part`` ("1.4/a") starts in the kernel: its probes' time is not the cell's."""

    part: str


@dataclass(frozen=True)
class Evidence:
    """One check call's evidence: the part, its probes' outcomes on the answer at that call (the
    student's feedback; no weight in a grade), and the answer itself as it was then, carried to the
    grader (``answer``: base64 of its pickle, which only a sandbox ever loads) or why it could not
    be (``unsent``)."""

    nonce: str
    exercise: str
    part: str
    outcomes: tuple[Outcome, ...] | Withheld
    output: str = ""
    answer: str = ""
    unsent: str = ""

    @property
    def stopped(self) -> bool:
        return self.outcomes is Withheld.STOPPED


KernelMessage: TypeAlias = CheckBegun | Evidence
_BEGIN, _EVIDENCE = "begin", "evidence"
_EVIDENCE_KEYS = {"kind", "nonce", "exercise", "part", "outcomes", "output", "answer", "unsent"}
_BASE64 = re.compile(r"[A-Za-z0-9+/]*={0,2}")


def encode_kernel_message(msg: KernelMessage) -> bytes:
    """One line (JSON and a newline) for the kernel's end of the evidence pipe."""
    if isinstance(msg, CheckBegun):
        return (_dumps({"kind": _BEGIN, "part": msg.part[:MAX_PART_KEY]}) + "\n").encode()
    outcomes: JSON = (msg.outcomes.value if isinstance(msg.outcomes, Withheld)
                      else [encode_outcome(o) for o in msg.outcomes])
    return (_dumps({"kind": _EVIDENCE, "nonce": msg.nonce, "exercise": msg.exercise,
                    "part": msg.part, "outcomes": outcomes, "output": msg.output[:MAX_OUTPUT],
                    "answer": msg.answer if len(msg.answer) <= MAX_ANSWER else "",
                    "unsent": (msg.unsent if len(msg.answer) <= MAX_ANSWER else "too large")
                    [:MAX_UNSENT]}) + "\n").encode()


def decode_check_begun(line: bytes | str) -> CheckBegun:
    """A check's announcement, or :class:`ProtocolError` (evidence and junk included)."""
    rec = _loads(line, 200)
    if not (isinstance(rec, dict) and set(rec) == {"kind", "part"} and rec["kind"] == _BEGIN
            and isinstance(rec["part"], str) and len(rec["part"]) <= MAX_PART_KEY):
        raise ProtocolError("not a check's announcement")
    return CheckBegun(rec["part"])


def decode_evidence(line: bytes | str, *, nonce: str, exercise: str,
                    probes: Mapping[str, int]) -> Evidence:
    """A check call's evidence for this run, checked and not believed.

    Accepted only if it parses (size and nesting capped), has exactly the evidence fields, carries
    ``nonce``, names a part of ``exercise`` (``probes``: {part name: number of probes}) and holds
    exactly one well-formed outcome per probe of that part (or says the check stopped). Raises
    :class:`ForeignEvidence` for a well-formed record of another exercise (not an offence) and
    :class:`ProtocolError` with the reason for anything else."""
    rec = _loads(line, MAX_EVIDENCE_LINE)
    if not isinstance(rec, dict) or set(rec) != _EVIDENCE_KEYS or rec["kind"] != _EVIDENCE:
        raise ProtocolError("a record of the wrong form")
    if rec["nonce"] != nonce:
        raise ProtocolError("a record without this run's secret")
    if rec["exercise"] != exercise:
        raise ForeignEvidence("a check of another exercise")
    part = rec["part"]
    if not isinstance(part, str) or part not in probes:
        raise ProtocolError("a record for a part this exercise does not have")
    output = rec["output"][:MAX_OUTPUT] if isinstance(rec["output"], str) else ""
    answer, unsent = rec["answer"], rec["unsent"]
    if not (isinstance(answer, str) and len(answer) <= MAX_ANSWER and _BASE64.fullmatch(answer)
            and isinstance(unsent, str) and len(unsent) <= MAX_UNSENT):
        raise ProtocolError(f"a record for part {part} with a malformed answer")
    raw = rec["outcomes"]
    for withheld in Withheld:
        if raw == withheld.value:
            return Evidence(nonce, exercise, part, withheld, output, answer, unsent)
    if not isinstance(raw, list) or len(raw) != probes[part]:
        raise ProtocolError(f"a record for part {part} with the wrong number of outcomes")
    try:
        outcomes = tuple(decode_outcome(o) for o in raw)
    except ProtocolError:
        raise ProtocolError(f"a record for part {part} with malformed outcomes") from None
    return Evidence(nonce, exercise, part, outcomes, output, answer, unsent)


# ------------------------------------------------------------------------------ runner -> grader
class RecordKind(Enum):
    """The kinds of record the runner sends the grading process."""

    START = "start"          # the runner runs
    KERNEL = "kernel"        # the kernel started (its pid)
    RUN = "run"              # a code cell starts
    CELL = "cell"            # a code cell ended (its status)
    BEGIN = "begin"          # a check announced itself in the kernel
    EVIDENCE = "evidence"    # a check's evidence line, forwarded as the kernel wrote it
    OUTPUT = "output"        # bytes the notebook printed (counted, then dropped)
    FLOOD = "flood"          # the kernel wrote too much on the evidence pipe
    FATAL = "fatal"          # the notebook could not be run at all
    DONE = "done"            # every cell ran


class CellStatus(Enum):
    """How a code cell ended."""

    OK = "ok"
    ERROR = "error"
    TIMEOUT = "timeout"
    DIED = "died"


@dataclass(frozen=True, kw_only=True)
class Record:
    """One record of the runner: its kind (fixed per class) and seconds since the runner started."""

    kind: ClassVar[RecordKind]
    at: float = 0.0


@dataclass(frozen=True, kw_only=True)
class Started(Record):
    kind: ClassVar[RecordKind] = RecordKind.START


@dataclass(frozen=True, kw_only=True)
class KernelStarted(Record):
    kind: ClassVar[RecordKind] = RecordKind.KERNEL
    pid: int | None = None


@dataclass(frozen=True, kw_only=True)
class CellStarted(Record):
    kind: ClassVar[RecordKind] = RecordKind.RUN
    index: int


@dataclass(frozen=True, kw_only=True)
class CellEnded(Record):
    kind: ClassVar[RecordKind] = RecordKind.CELL
    index: int
    status: CellStatus
    error: str = ""          # the exception's name (a cell that raised, or how the kernel went)
    seconds: float = 0.0


@dataclass(frozen=True, kw_only=True)
class CheckAnnounced(Record):
    kind: ClassVar[RecordKind] = RecordKind.BEGIN
    cell: int | None
    part: str


@dataclass(frozen=True, kw_only=True)
class EvidenceLine(Record):
    """A line of the kernel's evidence pipe, as text: :func:`decode_evidence` reads it."""

    kind: ClassVar[RecordKind] = RecordKind.EVIDENCE
    cell: int | None
    line: str


@dataclass(frozen=True, kw_only=True)
class OutputSize(Record):
    kind: ClassVar[RecordKind] = RecordKind.OUTPUT
    size: int


@dataclass(frozen=True, kw_only=True)
class Flooded(Record):
    kind: ClassVar[RecordKind] = RecordKind.FLOOD
    message: str = ""


@dataclass(frozen=True, kw_only=True)
class Fatal(Record):
    kind: ClassVar[RecordKind] = RecordKind.FATAL
    message: str


@dataclass(frozen=True, kw_only=True)
class Done(Record):
    kind: ClassVar[RecordKind] = RecordKind.DONE


def _opt_int(v: JSON) -> bool:
    return v is None or _is_int(v)


def _text(v: JSON) -> bool:
    return isinstance(v, str) and len(v) <= MAX_RECORD_TEXT


def _cell_status(v: JSON) -> bool:
    return isinstance(v, str) and v in {s.value for s in CellStatus}


#: {kind: (class, {field: check of its JSON value})}; every field is required on the wire.
_RECORDS: dict[RecordKind, tuple[type[Record], dict[str, Any]]] = {
    RecordKind.START: (Started, {}),
    RecordKind.KERNEL: (KernelStarted, {"pid": _opt_int}),
    RecordKind.RUN: (CellStarted, {"index": _is_int}),
    RecordKind.CELL: (CellEnded, {"index": _is_int, "status": _cell_status, "error": _text,
                                  "seconds": _is_number}),
    RecordKind.BEGIN: (CheckAnnounced, {"cell": _opt_int,
                                        "part": lambda v: isinstance(v, str) and len(v) <= MAX_PART_KEY}),
    RecordKind.EVIDENCE: (EvidenceLine, {"cell": _opt_int, "line": lambda v: isinstance(v, str)}),
    RecordKind.OUTPUT: (OutputSize, {"size": _is_int}),
    RecordKind.FLOOD: (Flooded, {"message": _text}),
    RecordKind.FATAL: (Fatal, {"message": _text}),
    RecordKind.DONE: (Done, {}),
}


def encode_record(rec: Record) -> bytes:
    """One line (JSON and a newline) for the runner's evidence descriptor."""
    _, checks = _RECORDS[rec.kind]
    data: dict[str, JSON] = {"kind": rec.kind.value, "at": round(float(rec.at), 2)}
    for name in checks:
        v = getattr(rec, name)
        data[name] = v.value if isinstance(v, Enum) else v
    return (_dumps(data) + "\n").encode()


def decode_record(line: bytes | str, limit: int = 6 * MAX_EVIDENCE_LINE + 200) -> Record:
    """A runner record from one line, checked: a known kind with exactly its fields, each of its
    type; :class:`ProtocolError` otherwise."""
    data = _loads(line, limit)
    if not isinstance(data, dict) or not isinstance(data.get("kind"), str):
        raise ProtocolError("a runner record that is not an object with a kind")
    try:
        kind = RecordKind(data["kind"])
    except ValueError:
        raise ProtocolError("a runner record of an unknown kind") from None
    cls, checks = _RECORDS[kind]
    if set(data) != {"kind", "at", *checks} or not _is_number(data["at"]):
        raise ProtocolError(f"a {kind.value} record with the wrong fields")
    values: dict[str, Any] = {}
    for name, ok in checks.items():
        if not ok(data[name]):
            raise ProtocolError(f"a {kind.value} record with a bad {name}")
        values[name] = CellStatus(data[name]) if name == "status" else data[name]
    return cls(at=float(data["at"]), **values)


# ------------------------------------------------------------------------------ grader -> runner
@dataclass(frozen=True)
class Limits:
    """Per-notebook limits (seconds, MiB, counts)."""

    cell_timeout: float = 120.0
    time_limit: float = 5.0
    notebook_timeout: float = 900.0
    memory_mb: int = 4096
    processes: int = 256
    tmp_mb: int = 512

    def __post_init__(self) -> None:
        for name in ("cell_timeout", "time_limit", "notebook_timeout"):
            object.__setattr__(self, name, float(getattr(self, name)))
        for name in ("memory_mb", "processes", "tmp_mb"):
            object.__setattr__(self, name, int(getattr(self, name)))


@dataclass(frozen=True)
class RunnerConfig:
    """What the grading process tells the runner of one notebook (a JSON file in its sandbox)."""

    notebook: str
    workdir: str
    evidence_fd: int
    nonce: str
    salt: int
    limits: Limits = field(default_factory=Limits)
    caps: Mapping[str, float] = field(default_factory=dict)
    mpl_cache: str | None = None
    max_notebook_bytes: int = 50_000_000


def encode_config(cfg: RunnerConfig) -> str:
    lim = cfg.limits
    return json.dumps({
        "notebook": cfg.notebook, "workdir": cfg.workdir, "evidence_fd": cfg.evidence_fd,
        "nonce": cfg.nonce, "salt": cfg.salt,
        "limits": {"cell_timeout": lim.cell_timeout, "time_limit": lim.time_limit,
                   "notebook_timeout": lim.notebook_timeout, "memory_mb": lim.memory_mb,
                   "processes": lim.processes, "tmp_mb": lim.tmp_mb},
        "caps": dict(cfg.caps), "mpl_cache": cfg.mpl_cache,
        "max_notebook_bytes": cfg.max_notebook_bytes})


def decode_config(text: str) -> RunnerConfig:
    """The runner's configuration, checked (it was written by the grading process)."""
    data = _loads(text, 10_000_000)
    want = {"notebook", "workdir", "evidence_fd", "nonce", "salt", "limits", "caps", "mpl_cache",
            "max_notebook_bytes"}
    if not isinstance(data, dict) or set(data) != want:
        raise ProtocolError("a runner configuration with the wrong fields")
    lim, caps = data["limits"], data["caps"]
    ok = (isinstance(data["notebook"], str) and isinstance(data["workdir"], str)
          and _is_int(data["evidence_fd"]) and isinstance(data["nonce"], str)
          and _is_int(data["salt"]) and _is_int(data["max_notebook_bytes"])
          and (data["mpl_cache"] is None or isinstance(data["mpl_cache"], str))
          and isinstance(caps, dict) and all(_is_number(v) for v in caps.values())
          and isinstance(lim, dict) and set(lim) == {"cell_timeout", "time_limit",
                                                     "notebook_timeout", "memory_mb", "processes",
                                                     "tmp_mb"}
          and all(_is_number(v) for v in lim.values()))
    if not ok:
        raise ProtocolError("a runner configuration with a bad value")
    return RunnerConfig(data["notebook"], data["workdir"], data["evidence_fd"], data["nonce"],
                        data["salt"], Limits(**lim), {str(k): float(v) for k, v in caps.items()},
                        data["mpl_cache"], data["max_notebook_bytes"])

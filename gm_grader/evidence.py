"""Evidence, checked and not believed: from the runner's records to one verdict per part.

A kernel's evidence line (an :class:`~gm_core.checks.protocol.EvidenceLine` record) is accepted
only if :func:`gm_core.checks.protocol.decode_evidence` accepts it: it parses (size and nesting
capped), carries this run's nonce, names a part of the notebook's exercise, and holds exactly one
outcome per probe of that part, each of a known kind with exactly the fields that kind has and a
value of plain numbers/text (arrays with a consistent shape). Anything else is counted as
*rejected* and reported. The judge then runs here, on the grader's own checkers, with the probe
inputs of this run (the salt the kernel was given).

The last accepted check call of a part names its answer (as the student's own last check did);
its outcomes are the student's feedback and weigh nothing. What decides the part is the grader's
own call of that answer after the notebook has ended, on inputs drawn then, in a fresh sandbox
(:mod:`gm_grader.probe`): :func:`decide` takes each part's verdict from that run and the
notebook's run only for where the part was checked and why a part has no answer. A part with no
accepted call gets a message saying why (never checked, or the notebook stopped first).
A part whose answer key the notebook asked for (``.reference``, ``.solution()``...: the graded
build has none, :mod:`gm_core.checks.answer_key`) gets no marks, whatever its checks sent, and
its row says where it asked.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from gm_core.checks.exercise import Exercise
from gm_core.checks.parts import Part, Verdict
from gm_core.checks.protocol import (
    MAX_OUTPUT,
    CellEnded,
    CellStarted,
    CellStatus,
    Evidence,
    EvidenceLine,
    Fatal,
    Flooded,
    ForeignEvidence,
    ProtocolError,
    Withheld,
    decode_evidence,
)
from gm_core.checks.protocol import Done as DoneRecord
from gm_core.checks.sandbox import decode_outcome
from gm_core.checks.store import FAILED
from gm_grader.isolate import Killed, RunResult


def parse_line(line: str, nonce: str, ex: Exercise) -> Evidence:
    """The evidence of one check call of ``ex`` in this run (``nonce``), checked; raises
    :class:`~gm_core.checks.protocol.ForeignEvidence` for another exercise's check and
    :class:`~gm_core.checks.protocol.ProtocolError` (the reason) for anything not accepted."""
    probes: dict[str, int] = {}
    for name, part in ex.parts.items():
        try:
            probes[name] = len(part.probes())
        except Exception:  # noqa: BLE001 - a checker that cannot list its probes accepts nothing
            continue
    return decode_evidence(line, nonce=nonce, exercise=ex.id, probes=probes)


def judge_part(part: Part, evidence: Evidence | None) -> Verdict:
    """A Verdict for one part from one accepted record's plain evidence (never raises)."""
    if evidence is None:
        return Verdict(FAILED, "no answer was collected for this part", part.title)
    if evidence.stopped:
        return Verdict(FAILED, "the check of this part stopped before it finished", part.title)
    if isinstance(evidence.outcomes, Withheld):
        return Verdict(FAILED, "no answer was collected for this part", part.title)
    return part.verdict([decode_outcome(o.to_json()) for o in evidence.outcomes],
                        evidence.output[:MAX_OUTPUT])


def _snippet(source: str) -> str:
    first = next((ln.strip() for ln in str(source).splitlines() if ln.strip()), "")
    return first[:50] + ("..." if len(first) > 50 else "")


@dataclass(frozen=True)
class PartResult:
    """One part's verdict and the cell (index) of the check call that decided it, if any."""

    verdict: Verdict
    cell: int | None = None


@dataclass(frozen=True)
class Summary:
    """One run of a notebook, judged: every part's result, why the run stopped early (``problem``,
    empty when it did not) and notes on what the notebook did that the grader flags."""

    parts: dict[str, PartResult]
    problem: str = ""
    notes: tuple[str, ...] = ()
    sources: Mapping[int, str] = field(default_factory=dict)
    #: each part's last accepted evidence (its carried answer), and the parts that asked for a key
    checked: Mapping[str, Evidence] = field(default_factory=dict)
    asked: frozenset[str] = frozenset()

    def where(self, i: int | None) -> str:
        """A cell named for the reader: its number and its first line."""
        if not isinstance(i, int):
            return "a cell"
        return f"cell {i + 1} (`{_snippet(self.sources.get(i, ''))}`)"


@dataclass(frozen=True)
class Collected:
    """A run's accepted evidence, parsed and not judged: each part's last check call (and its
    cell), the first request for each part's answer key, and the rejected lines by reason."""

    latest: dict[str, tuple[Evidence, int | None]]
    asked: dict[str, tuple[str, int | None]]
    rejected: dict[str, int]

    def answers(self) -> dict[str, str]:
        """{part: carried answer} of the parts whose last check carried one (none that asked for
        its key: such a part gets no marks whatever it sends)."""
        return {name: ev.answer for name, (ev, _) in self.latest.items()
                if ev.answer and name not in self.asked}


def collect(run: RunResult, ex: Exercise) -> Collected:
    """Parse every evidence line of ``run`` for ``ex`` (no judging: safe in any thread)."""
    latest: dict[str, tuple[Evidence, int | None]] = {}
    asked: dict[str, tuple[str, int | None]] = {}
    rejected: dict[str, int] = {}
    for r in run.records:
        if isinstance(r, EvidenceLine):
            try:
                ev = parse_line(r.line, run.nonce, ex)
            except ForeignEvidence:
                continue                                  # ignored, not an offence
            except ProtocolError as exc:
                rejected[str(exc)] = rejected.get(str(exc), 0) + 1
                continue
            if ev.outcomes is Withheld.KEY_ASKED:
                asked.setdefault(ev.part, (ev.output, r.cell))
                continue
            latest[ev.part] = (ev, r.cell)
    return Collected(latest, asked, rejected)


def summarise(run: RunResult, ex: Exercise, sources: Mapping[int, str], *,
              judge: bool = True) -> Summary:
    """Every part of ``ex`` judged from one run's outcomes, with the run's problem and notes.

    ``sources`` maps cell indices to their source (to name a cell by its first line).
    ``judge=False`` (the notebook's own run, whose outcomes weigh nothing): a checked part's
    verdict is left for :func:`decide` to take from the grader's calls."""
    got = collect(run, ex)
    latest, asked, rejected = got.latest, got.asked, got.rejected
    cells: dict[int, CellEnded] = {}
    problem, notes = "", []
    running: int | None = None
    fatal = done = False
    for r in run.records:
        if isinstance(r, CellStarted):
            running = r.index
        elif isinstance(r, CellEnded):
            cells[r.index] = r
        elif isinstance(r, Fatal):
            fatal, problem = True, r.message[:300]
        elif isinstance(r, DoneRecord):
            done = True
        elif isinstance(r, Flooded):
            notes.append("the notebook flooded the grader's evidence channel")
    where = Summary({}, sources=sources).where

    stop_cell = None
    last = max(cells, default=None)
    for i, c in sorted(cells.items()):
        if c.status is CellStatus.TIMEOUT:
            notes.append(f"{where(i)} ran longer than the cell limit and was interrupted")
            if stop_cell is None and i == last and not done:
                stop_cell = i
        elif c.status is CellStatus.DIED:
            stop_cell = i
    if not fatal and not done:
        if run.killed is Killed.TIME:
            problem = "the notebook ran longer than the time allowed for a whole notebook"
        elif run.killed is Killed.CELL:
            at = where(running) if running is not None and running not in cells else "a cell"
            problem = (f"the grader ended the notebook in {at}: it ran far past the cell limit "
                       "while the grader's runner had stopped enforcing it (stopped or stalled "
                       "from inside the notebook)")
        elif run.killed is Killed.EVIDENCE:
            problem = "the notebook sent far too much on the grader's evidence channel"
        elif stop_cell is not None:
            c = cells[stop_cell]
            problem = (f"the notebook's kernel stopped in {where(stop_cell)}"
                       + (" after it exceeded the cell limit" if c.status is CellStatus.TIMEOUT
                          else " (it crashed, ran out of memory, or ended the grader's runner)"))
        elif running is not None and running not in cells:
            problem = (f"the notebook ended its own grading in {where(running)} (it stopped the "
                       "grader's runner, or everything crashed)")
        else:
            problem = "the notebook ended its own grading (it stopped the grader's runner)"
    if rejected:
        notes.append("the grader rejected evidence it could not verify: " + "; ".join(
            f"{n} x {why}" for why, n in sorted(rejected.items())))
    parts: dict[str, PartResult] = {}
    for name, part in ex.parts.items():
        if name in asked:
            what, cell = asked[name]
            msg = (f"the notebook asked for this part's answer key ({what[:60]}) in {where(cell)}; "
                   "a graded run has no answer keys or worked solutions, so this part gets no marks")
            parts[name] = PartResult(Verdict(FAILED, msg, part.title), cell)
        elif name in latest:
            ev, cell = latest[name]
            parts[name] = PartResult(judge_part(part, ev) if judge else
                                     Verdict(FAILED, "not judged: see the grader's calls", part.title),
                                     cell)
        else:
            msg = (f"this part was not checked before {problem}" if problem else
                   f"no check of this part ran in the notebook (call ex{ex.id.replace('.', '_')}."
                   f"{name}.check(...) in a cell, and run it)")
            parts[name] = PartResult(Verdict(FAILED, msg, part.title), None)
    return Summary(parts, problem, tuple(notes), sources,
                   {name: ev for name, (ev, _) in latest.items()}, frozenset(asked))


def decide(ex: Exercise, notebook: Summary, calls: Summary | None) -> Summary:
    """The grade of every part: from ``calls`` (the grader's own calls of the carried answers,
    :mod:`gm_grader.probe`; None when no part carried one), never from the outcomes the notebook
    sent. The notebook's run still says where each part was checked, why a part has no answer
    (never checked, stopped first, asked for its key) and what the notebook did that the grader
    flags."""
    parts = dict(notebook.parts)
    notes = list(notebook.notes)
    if calls is not None and calls.problem:
        notes.append(f"the grader's own calls of your answers were cut short: {calls.problem}")
    for name, part in ex.parts.items():
        ev = notebook.checked.get(name)
        if name in notebook.asked or ev is None:
            continue                          # no marks, and the notebook's run says why
        cell = parts[name].cell
        if not ev.answer:
            why = ev.unsent or "the check stopped before it could send it"
            msg = (f"your answer could not be handed to the grader: {why}. Define it from "
                   "numbers, arrays and functions only, then check it again")
            parts[name] = PartResult(Verdict(FAILED, msg, part.title), cell)
            continue
        final = calls.checked.get(name) if calls is not None else None
        if calls is None or final is None:
            msg = ("the grader's own call of your answer did not finish"
                   + (f" ({calls.problem})" if calls is not None and calls.problem else ""))
            parts[name] = PartResult(Verdict(FAILED, msg, part.title), cell)
        elif final.stopped and final.output:
            parts[name] = PartResult(Verdict(FAILED, final.output, part.title), cell)
        else:                                 # judged by summarise, on the calls' inputs
            parts[name] = PartResult(calls.parts[name].verdict, cell)
    return Summary(parts, notebook.problem, tuple(notes), notebook.sources, notebook.checked,
                   notebook.asked)


__all__ = ["parse_line", "judge_part", "collect", "Collected", "summarise", "decide", "Summary",
           "PartResult"]

"""Evidence, checked and not believed: from the runner's records to one verdict per part.

A record from the kernel (``{"t": "k", "line": ...}``) is accepted only if it parses (size and
nesting capped), carries this run's nonce, names a part of the notebook's exercise, and holds
exactly one outcome per probe of that part, each of a known kind with exactly the fields that
kind has and a value of plain numbers/text (arrays with a consistent shape). Anything else is
counted as *rejected* and reported. The judge then runs here, on the grader's own checkers, with
the probe inputs of this run (the salt the kernel was given).

The last accepted check call of a part decides it (as the student's own last check did); a part
with no accepted call gets a message saying why (never checked, or the notebook stopped first).
"""
from __future__ import annotations

import json
import math

from gm_core.checks.parts import Verdict
from gm_core.checks.sandbox import decode_outcome
from gm_core.checks.store import FAILED

KINDS = {"ok": {"k", "v"}, "wrong": {"k", "m"}, "unattempted": {"k", "m"},
         "error": {"k", "m", "x"}, "timeout": {"k", "m", "x"}, "crash": {"k", "m", "x"},
         "skipped": {"k", "m", "x"}}
MAX_LINE = 4_100_000
MAX_DEPTH = 12


def _plain(v, depth=0):
    """JSON data that :func:`gm_core.checks.sandbox.decode` can turn into numbers, text, arrays, lists, dicts."""
    if depth > MAX_DEPTH:
        return False
    if v is None or isinstance(v, (bool, str)):
        return not isinstance(v, str) or len(v) <= 600
    if isinstance(v, (int, float)):
        return True
    if isinstance(v, list):
        return all(_plain(x, depth + 1) for x in v)
    if isinstance(v, dict):
        if set(v) == {"__nd__", "d"}:
            shape, d = v["__nd__"], v["d"]
            return (isinstance(shape, list) and all(isinstance(s, int) and not isinstance(s, bool)
                                                    and 0 <= s for s in shape)
                    and isinstance(d, list) and len(d) == math.prod(shape)
                    and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in d))
        if set(v) == {"__dict__"} and isinstance(v["__dict__"], list):
            return all(isinstance(kv, list) and len(kv) == 2 and isinstance(kv[0], str)
                       and _plain(kv[1], depth + 1) for kv in v["__dict__"])
    return False


def valid_outcome(o):
    if not isinstance(o, dict) or o.get("k") not in KINDS:
        return False
    allowed = KINDS[o["k"]]
    if not set(o) <= allowed or "k" not in o:
        return False
    if o["k"] == "ok":
        return "v" in o and _plain(o["v"])
    return all(isinstance(o.get(f, ""), str) and len(o.get(f, "")) <= 2000 for f in ("m", "x"))


def parse_line(line, nonce, ex):
    """(part name, {"outcomes", "output"}) for a valid kernel record, or (None, reason)."""
    if not isinstance(line, str) or len(line) > MAX_LINE:
        return None, "an over-long or missing record"
    try:
        rec = json.loads(line)
    except (ValueError, RecursionError):
        return None, "a record that is not valid JSON (or nested too deeply)"
    if not isinstance(rec, dict) or set(rec) != {"n", "ex", "part", "o", "out"}:
        return None, "a record of the wrong form"
    if rec["n"] != nonce:
        return None, "a record without this run's secret"
    if rec["ex"] != ex.id:
        return "", "a check of another exercise"          # ignored, not an offence
    part = ex.parts.get(rec["part"]) if isinstance(rec["part"], str) else None
    if part is None:
        return None, "a record for a part this exercise does not have"
    outcomes = rec["o"]
    if outcomes == "stopped":
        return part.name, {"stopped": True}
    if not isinstance(outcomes, list) or len(outcomes) != len(part.probes()):
        return None, f"a record for part {part.name} with the wrong number of outcomes"
    if not all(valid_outcome(o) for o in outcomes):
        return None, f"a record for part {part.name} with malformed outcomes"
    output = rec["out"] if isinstance(rec["out"], str) else ""
    return part.name, {"outcomes": outcomes, "output": output[:2000]}


def judge_part(part, evidence):
    """A Verdict for one part from one accepted record's plain evidence (never raises)."""
    if not isinstance(evidence, dict):
        return Verdict(FAILED, "no answer was collected for this part", part.title)
    if evidence.get("stopped"):
        return Verdict(FAILED, "the check of this part stopped before it finished", part.title)
    raw = evidence.get("outcomes")
    if not isinstance(raw, list) or not all(valid_outcome(o) for o in raw):
        return Verdict(FAILED, "no answer was collected for this part", part.title)
    output = evidence.get("output") if isinstance(evidence.get("output"), str) else ""
    return part.verdict([decode_outcome(o) for o in raw], output[:2000])


def _snippet(source):
    first = next((ln.strip() for ln in str(source).splitlines() if ln.strip()), "")
    return first[:50] + ("..." if len(first) > 50 else "")


def summarise(run, ex, sources):
    """{part: (verdict, cell index or None)}, the run's problem text and notes, from one run.

    ``sources`` maps cell indices to their source (to name a cell by its first line)."""
    nonce = run["nonce"]
    latest, rejected, cells, problem, notes = {}, {}, {}, "", []
    running = None
    fatal = done = False
    for r in run["records"]:
        t = r.get("t")
        if t == "k":
            name, ev = parse_line(r.get("line"), nonce, ex)
            if name:
                latest[name] = (ev, r.get("cell"))
            elif name is None:
                rejected[ev] = rejected.get(ev, 0) + 1
        elif t == "run":
            running = r.get("i")
        elif t == "cell":
            cells[r.get("i")] = r
        elif t == "fatal":
            fatal, problem = True, str(r.get("m", ""))[:300]
        elif t == "done":
            done = True
        elif t == "flood":
            notes.append("the notebook flooded the grader's evidence channel")

    def where(i):
        if not isinstance(i, int):
            return "a cell"
        return f"cell {i + 1} (`{_snippet(sources.get(i, ''))}`)"

    stop_cell = None
    for i, c in sorted(((k, v) for k, v in cells.items() if isinstance(k, int)), key=lambda kv: kv[0]):
        if c.get("status") == "timeout":
            notes.append(f"{where(i)} ran longer than the cell limit and was interrupted")
            if stop_cell is None and i == max(k for k in cells if isinstance(k, int)) and not done:
                stop_cell = i
        elif c.get("status") == "died":
            stop_cell = i
    if not fatal and not done:
        if run.get("killed") == "time":
            problem = "the notebook ran longer than the time allowed for a whole notebook"
        elif run.get("killed") == "cell":
            at = where(running) if isinstance(running, int) and running not in cells else \
                "a cell"
            problem = (f"the grader ended the notebook in {at}: it ran far past the cell limit "
                       "while the grader's runner had stopped enforcing it (stopped or stalled "
                       "from inside the notebook)")
        elif run.get("killed") == "evidence":
            problem = "the notebook sent far too much on the grader's evidence channel"
        elif stop_cell is not None:
            c = cells[stop_cell]
            problem = (f"the notebook's kernel stopped in {where(stop_cell)}"
                       + (" after it exceeded the cell limit" if c.get("status") == "timeout" else
                          " (it crashed, ran out of memory, or ended the grader's runner)"))
        elif isinstance(running, int) and running not in cells:
            problem = (f"the notebook ended its own grading in {where(running)} (it stopped the "
                       "grader's runner, or everything crashed)")
        else:
            problem = "the notebook ended its own grading (it stopped the grader's runner)"
    if rejected:
        notes.append("the grader rejected evidence it could not verify: " + "; ".join(
            f"{n} x {why}" for why, n in sorted(rejected.items())))
    verdicts = {}
    for name, part in ex.parts.items():
        if name in latest:
            ev, cell = latest[name]
            verdicts[name] = (judge_part(part, ev), cell)
        else:
            msg = (f"this part was not checked before {problem}" if problem else
                   f"no check of this part ran in the notebook (call ex{ex.id.replace('.', '_')}."
                   f"{name}.check(...) in a cell, and run it)")
            verdicts[name] = (Verdict(FAILED, msg, part.title), None)
    return verdicts, problem, notes, where

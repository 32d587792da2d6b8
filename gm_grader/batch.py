"""Grade submitted exercise notebooks: ``python -m gm_grader SUBMISSIONS... --out DIR``.

Each SUBMISSION is a folder (one student's upload) or a single notebook. Each is first copied
into the grader's private staging folder (:mod:`gm_grader.staging`: regular files only, never
through a link; links, devices, FIFOs, folders named like notebooks and hard links to elsewhere
get a row saying why they are not graded, names that are not UTF-8 or hold control characters
are normalised and the rows say so); from then on only those copies are read. For every
exercise notebook ``exN_M.ipynb`` in it:

1. it runs **in its own sandbox** (:mod:`gm_grader.isolate`: bubblewrap, read-only course and Python,
   a private ``/tmp``, no network, no view of the other submissions or of the output folder,
   limits on time, memory, processes and file size; the whole process tree ends with it), cell
   by cell in a fresh kernel (:mod:`gm_grader.runner`), each cell under ``--cell-timeout`` seconds not
   counting its checks' probes, each probe under ``--time-limit`` seconds as in the student's own
   kernel, the whole notebook under ``--notebook-timeout``;
2. every ``check(...)`` call the notebook makes sends, **at the moment it is called**, on a pipe
   opened before the student's first cell (:mod:`gm_core.checks.channel`, with this run's
   secret), the outcomes of that part's probes -- the student's feedback, weighing nothing --
   and the answer itself as it was then, pickled by value;
3. once the notebook has ended (however it ended), the grader draws new probe inputs and calls
   the last checked answer of every part **in a fresh sandbox of its own**, holding nothing of
   the submission but those answers (:mod:`gm_grader.probe`), and every part is **judged here**,
   in the grading process, by its untouched checkers, from the plain outcomes of those calls
   (:mod:`gm_grader.evidence`); malformed, forged-looking or unverifiable evidence is rejected
   and reported, never passed.

Outputs: ``DIR/results.json`` (Gradescope's format: relative test names, ``visibility``) and
``DIR/grades.csv``, one row per notebook and part, both written atomically by this process after
every sandbox has ended. ``--assignment FILE.json`` declares the expected exercises (missing
notebooks then get a row each and the maximum never depends on the upload), points, maximum
score and visibilities::

    {"exercises": ["1.1", "1.4"], "max_score": 20, "weights": {"1.4a": 3},
     "visibility": "after_due_date", "part_visibility": {"1.4d": "hidden"}}

Points per part default to ``Part.weight`` (2 for a computed answer, 1 for a multiple-choice
question); ``--weights FILE.json`` maps part ids (``"1.4a"``, ``"1.4 d_rates"``) to points.
Without bubblewrap the grader refuses to run unless told ``--no-sandbox`` (for a container per
submission, as on Gradescope).

Exit status: 0 when every notebook was graded (whatever it scored); 2 for a usage error (an
argument, the assignment, an output or submission folder inside what every sandbox reads); 3
when no sandbox can run here (a sandbox made as for a notebook is tried first; nothing is
graded); 4 when the grader itself failed during the batch -- a sandbox that did not start in
``STARTUP_ATTEMPTS`` tries, a notebook it could not judge, a report file it could not write:
every other grade is written, the notebooks it failed on get rows saying the fault is the
grader's, and stderr says why. In nbgrader / otter-grader test cells use
``ex1_4.a.check(answer, strict=True)`` instead (None on success, AssertionError on failure).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import secrets
import shutil
import sys
import tempfile
import time
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, TypeAlias

from gm_core.checks import channel
from gm_core.checks.answer_key import KEYS_PACKAGE, keys_installed
from gm_core.checks.exercise import REGISTRY, exercise_ids
from gm_core.checks.parts import Part
from gm_core.checks.protocol import Limits
from gm_core.checks.store import FAILED, PASSED
from gm_grader import probe, view
from gm_grader import report as _report
from gm_grader.clock import check_caps
from gm_grader.evidence import Summary, collect, decide, summarise
from gm_grader.isolate import RunResult, run_env, run_submission, sandbox_problem, startup_fault
from gm_grader.staging import MAX_NOTEBOOK_BYTES, Upload, leftover_reason, stage

_EXACT = re.compile(r"ex(\d+)_(\d+)\.ipynb")
_ANY = re.compile(r"ex(\d+)_(\d+)", re.IGNORECASE)

#: Runs of one notebook when its sandbox or kernel does not start (nothing of the student's ran).
STARTUP_ATTEMPTS = 3

Row: TypeAlias = dict[str, Any]            # one row of grades.csv (report.FIELDS, visibility)
Notebook: TypeAlias = dict[str, Any]       # a notebook's JSON


class SandboxUnavailable(RuntimeError):
    """bubblewrap cannot make a sandbox here, and ``--no-sandbox`` was not given."""


class GraderFaults(RuntimeError):
    """The grader itself failed during a batch (a sandbox that could not start, a notebook it
    could not judge, a report file it could not write): ``causes`` says what; every grade it
    could still give has been written (``results``: what was written, or None)."""

    def __init__(self, causes: Sequence[str], results: dict[str, Any] | None) -> None:
        super().__init__("; ".join(causes))
        self.causes = tuple(causes)
        self.results = results


@dataclass(frozen=True)
class Fault:
    """The grader's own failure on one notebook: not the student's doing."""

    cause: str


@dataclass(frozen=True)
class Ran:
    """One notebook's two sandboxed runs: the notebook itself, and the grader's own calls of the
    answers its checks carried (:mod:`gm_grader.probe`; None when no part carried one)."""

    notebook: RunResult
    calls: RunResult | None = None
    call_sources: Mapping[int, str] = field(default_factory=dict)


@dataclass(frozen=True)
class GradeSettings:
    """How a batch is graded: the limits of each notebook, the sandbox, the parallel runs and the
    results' Gradescope visibility (the command line's options, with the same defaults)."""

    limits: Limits = field(default_factory=Limits)
    sandbox: bool = True
    jobs: int = 1
    visibility: str = "visible"


@dataclass(frozen=True)
class Assignment:
    """The declared assignment (``--assignment``), or the empty one: nothing declared."""

    exercises: tuple[str, ...] | None = None
    max_score: float | None = None
    weights: Mapping[str, float] = field(default_factory=dict)
    visibility: str | None = None
    part_visibility: Mapping[str, str] = field(default_factory=dict)


def _read_notebook(path: Path) -> tuple[dict[str, Any], Notebook] | str:
    """(the notebook's top-level metadata, its JSON), or the reason it cannot be read -- never raises."""
    try:
        if path.is_symlink() or not path.is_file():
            return "it is not a plain file (a link, a folder or a device)"
        size = path.stat().st_size
        if size > MAX_NOTEBOOK_BYTES:
            return f"it is too large ({size >> 20} MB)"
        data = json.loads(path.read_bytes().decode("utf-8"))
    except RecursionError:
        return "it is not a readable notebook (its JSON is nested too deeply)"
    except (OSError, ValueError, UnicodeDecodeError) as exc:
        return f"it is not a readable notebook ({type(exc).__name__})"
    if not isinstance(data, dict) or not isinstance(data.get("cells"), list):
        return "it is not a readable notebook (no list of cells)"
    meta = data.get("metadata")
    return (meta if isinstance(meta, dict) else {}), data


def identify(path: Path, name: str | None = None) -> tuple[str | None, str, Notebook | None]:
    """(exercise id or None, note, notebook JSON or None) for a notebook file; ``name``: the
    name it was uploaded under (default: its own)."""
    read = _read_notebook(path)
    meta, data = read if isinstance(read, tuple) else (None, None)
    name = path.name if name is None else name
    m = _EXACT.fullmatch(name)
    note = ""
    if m is None:
        m = _ANY.search(name)
        if m is not None:
            note = f"named {name!r}, graded as ex{m.group(1)}_{m.group(2)}.ipynb"
    if m is None and meta is not None:
        course = meta.get("gm_course")
        src = course.get("generated_from") if isinstance(course, dict) else None
        if isinstance(src, str):
            m = _ANY.search(src)
            if m is not None:
                note = (f"named {name!r}; recognised from its metadata as "
                        f"ex{m.group(1)}_{m.group(2)}.ipynb (please keep the course's file names)")
    if m is None:
        return None, "", data
    return f"{int(m.group(1))}.{int(m.group(2))}", note, data


def load_assignment(path: str | Path) -> Assignment:
    """The assignment declaration (see the module docstring), validated."""
    try:
        a = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise ValueError(f"assignment: cannot read {path} ({exc})") from None
    if not isinstance(a, dict):
        raise ValueError("assignment: the file must hold a JSON object")
    exs = list(a.get("exercises", []))
    exs += [f"{int(m.group(1))}.{int(m.group(2))}" for n in a.get("notebooks", [])
            if (m := _EXACT.fullmatch(str(n)))]
    bad = [e for e in exs if str(e) not in REGISTRY]
    if bad or not exs:
        raise ValueError(f"assignment: 'exercises' must list exercise ids of this course "
                         f"({', '.join(exercise_ids())}); got {bad or exs}")
    unknown = set(a) - {"exercises", "notebooks", "max_score", "weights", "visibility",
                        "part_visibility"}
    if unknown:
        raise ValueError(f"assignment: unknown key(s) {', '.join(sorted(unknown))}")
    _report.check_visibility(a.get("visibility", "visible"), "assignment visibility")
    part_vis = a.get("part_visibility", {})
    for k, v in part_vis.items():
        _report.check_visibility(v, f"assignment part_visibility[{k!r}]")
    if "max_score" in a and not (isinstance(a["max_score"], (int, float)) and a["max_score"] > 0):
        raise ValueError("assignment: max_score must be a positive number")
    return Assignment(exercises=tuple(dict.fromkeys(str(e) for e in exs)),
                      max_score=a.get("max_score"), weights=dict(a.get("weights", {})),
                      visibility=a.get("visibility"), part_visibility=dict(part_vis))


# ------------------------------------------------------------------------------ plan
@dataclass(frozen=True)
class NotGraded:
    """An entry of an upload that is not graded (no exercise of the course, a link, a device, a
    folder in place of a notebook...): one row saying why."""

    rel: str
    why: str


@dataclass(frozen=True)
class ToRun:
    """A staged notebook to run and judge as exercise ``exercise`` (``notebook`` None:
    unreadable); ``note``: what the student is told about its name, or ''."""

    path: Path
    rel: str
    exercise: str
    notebook: Notebook | None
    note: str = ""


@dataclass(frozen=True)
class Missing:
    """An exercise the assignment expects that the submission lacks: its rows, each failed."""

    want: str
    exercise: str
    message: str


PlanItem: TypeAlias = NotGraded | ToRun | Missing


@dataclass(frozen=True)
class Plan:
    """What a batch will grade, in the report's order, and the notes so far."""

    items: tuple[PlanItem, ...]
    notes: tuple[str, ...]

    @property
    def runs(self) -> tuple[ToRun, ...]:
        """The notebooks to run (the readable ones)."""
        return tuple(i for i in self.items if isinstance(i, ToRun) and i.notebook is not None)


@dataclass(frozen=True)
class _Choice:
    path: Path
    rel: str
    note: str
    exact: bool
    notebook: Notebook | None
    renamed: str


def plan(uploads: Sequence[Upload], assignment: Assignment) -> Plan:
    """Which staged notebook of each upload (:func:`gm_grader.staging.stage`) grades which
    exercise, and what is missing, refused or not graded."""
    items: list[PlanItem] = []
    lines: list[str] = []
    expected = assignment.exercises
    for up in uploads:
        lines += up.skipped
        for r in up.refused:
            items.append(NotGraded(r.rel, r.why))
            lines.append(f"{r.rel}: not graded ({r.why})")
        chosen: dict[str, _Choice] = {}
        for f in up.files:
            rel = f.rel
            if f.note:
                lines.append(f"{rel}: {f.note}")
            if f.shared:
                lines.append(f"{rel}: {f.shared}")
            ex_id, note, data = identify(f.path, Path(f.inner).name)
            if ex_id is None or ex_id not in REGISTRY:
                why = (f"there is no exercise {ex_id} in this course" if ex_id else
                       "it is not one of the course's exercise notebooks (exN_M.ipynb, e.g. "
                       "ex1_4.ipynb)")
                items.append(NotGraded(rel, why))
                lines.append(f"{rel}: not graded ({why})")
                continue
            if expected is not None and ex_id not in expected:
                lines.append(f"{rel}: not graded (exercise {ex_id} is not part of this assignment)")
                continue
            exact = _EXACT.fullmatch(Path(f.inner).name) is not None
            before = chosen.get(ex_id)
            if before is not None and (before.exact or not exact):
                lines.append(f"{rel}: not graded (exercise {ex_id} is graded from {before.rel})")
                continue
            if before is not None:
                lines.append(f"{before.rel}: not graded (exercise {ex_id} is graded from {rel})")
            chosen[ex_id] = _Choice(f.path, rel, note, exact, data, f.note)
        for ex_id, c in sorted(chosen.items()):
            if c.note:
                lines.append(f"{c.rel}: {c.note}")
            items.append(ToRun(c.path, c.rel, ex_id, c.notebook, c.renamed))
        for ex_id in expected or ():
            if ex_id not in chosen:
                want = f"{up.prefix}ex{ex_id.replace('.', '_')}.ipynb"
                msg = (f"{want} was not found in the submission (upload the exercise notebook "
                       "under this name)")
                items.append(Missing(want, ex_id, msg))
                lines.append(msg)
    return Plan(tuple(items), tuple(lines))


# ------------------------------------------------------------------------------ run
def run(the_plan: Plan, settings: GradeSettings) -> dict[Path, Ran | Fault]:
    """Run every readable notebook of the plan in its sandbox, then the grader's own calls of its
    checked answers in another, ``settings.jobs`` notebooks at a time: {path: what the runs
    brought back, or the grader's failure to run them}."""
    done: dict[Path, Ran | Fault] = {}
    own_user = False
    if not settings.sandbox and the_plan.runs:
        own_user, note = view.unsandboxed_user(run_env("/tmp"))
        if note:
            print(f"gm-grade: warning: {note}", file=sys.stderr)
    with ThreadPoolExecutor(max_workers=max(1, int(settings.jobs))) as pool:
        futures = {pool.submit(_run_one, item, settings, own_user): item.path
                   for item in the_plan.runs}
        for fut, path in futures.items():
            try:
                done[path] = fut.result()
            except Exception as exc:  # noqa: BLE001 - the grader's own failure: said, not hidden
                done[path] = Fault(f"the grader could not run it ({type(exc).__name__}: {exc})"[:300])
    return done


def _run_one(item: ToRun, settings: GradeSettings, own_user: bool = False) -> Ran | Fault:
    """The notebook's run, then (the notebook over, however it ended) the grader's calls of the
    answers it carried, on probe inputs of a salt drawn now (:mod:`gm_grader.probe`)."""
    ex, limits = REGISTRY[item.exercise], settings.limits
    caps = check_caps(ex, limits.time_limit)
    first, fault = _started(item.path, limits, settings.sandbox, caps, own_user)
    if fault:
        return Fault(fault)
    answers = collect(first, ex).answers()
    if not answers:
        return Ran(first)
    nb = probe.notebook(ex.id, answers)
    folder = Path(tempfile.mkdtemp(prefix="gm-calls-"))
    try:
        path = folder / "calls.ipynb"
        path.write_text(json.dumps(nb), encoding="utf-8")
        calls, fault = _started(path, limits, settings.sandbox, caps, own_user,
                                salt=secrets.randbits(62))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    if fault:
        return Fault(f"the grader's own calls of the answers did not run: {fault}")
    return Ran(first, calls, _sources(nb))


def _started(path: Path, limits: Limits, sandbox: bool, caps: Mapping[str, float],
             own_user: bool, salt: int | None = None) -> tuple[RunResult, str | None]:
    """Run ``path``; a run that ended before the notebook's first cell (nothing of the student's
    ran: :func:`~gm_grader.isolate.startup_fault`) is run again, ``STARTUP_ATTEMPTS`` times in
    all, as a busy machine can fail to start a sandbox or a kernel in time. (The run, and the
    fault of the last attempt or None.)"""
    for attempt in range(1, STARTUP_ATTEMPTS + 1):
        result = run_submission(path, limits=limits, sandbox=sandbox, caps=caps, salt=salt,
                                own_user=own_user)
        fault = startup_fault(result)
        if fault is None:
            return result, None
        print(f"gm-grade: warning: attempt {attempt} of {STARTUP_ATTEMPTS} did not start: "
              f"{fault}", file=sys.stderr)
    return result, f"{fault}; tried {STARTUP_ATTEMPTS} times"


# ------------------------------------------------------------------------------ judge
def _rows_for(ex_id: str, rel: str, assignment: Assignment, weights: Mapping[str, float],
              message_of: Callable[[str, Part], tuple[str, str]]) -> list[Row]:
    rows = []
    part_vis = assignment.part_visibility
    for name, part in REGISTRY[ex_id].parts.items():
        pts = float(weights.get(part.id, weights.get(f"{ex_id}{name}", part.weight)))
        status, msg = message_of(name, part)
        row: Row = {"notebook": rel, "exercise": ex_id, "part": name, "status": status,
                    "score": pts if status == PASSED else 0.0, "max_score": pts, "message": msg}
        vis = part_vis.get(part.id, part_vis.get(f"{ex_id}{name}"))
        if vis:
            row["visibility"] = vis
        rows.append(row)
    return rows


def _sources(notebook: Notebook) -> dict[int, str]:
    sources = {}
    for i, c in enumerate(notebook.get("cells", [])):
        src = c.get("source", "") if isinstance(c, dict) else ""
        sources[i] = "".join(src) if isinstance(src, list) and all(isinstance(s, str) for s in src) \
            else (src if isinstance(src, str) else "")
    return sources


def _judge_one(item: ToRun, result: Ran | Fault | None, assignment: Assignment,
               weights: Mapping[str, float], lines: list[str], faults: list[str]) -> list[Row]:
    ex_id, rel = item.exercise, item.rel
    if isinstance(result, Ran) and item.notebook is not None:
        try:
            return _judged(item, result, assignment, weights, lines)
        except Exception as exc:  # noqa: BLE001 - the grader's own failure: said, not hidden
            result = Fault(f"the grader could not judge it ({type(exc).__name__}: {exc})"[:300])
    if isinstance(result, Fault):
        faults.append(f"{rel}: {result.cause}")
        lines.append(f"{rel}: GRADER FAULT, not graded: {result.cause}")
        msg = ("Not graded, because of a fault in the grader, not in your notebook "
               f"({result.cause}); your instructor has been told and will grade it again.")
        return _rows_for(ex_id, rel, assignment, weights, _failed_with(msg))
    read = _read_notebook(item.path)
    msg = f"the notebook could not be graded: {read if isinstance(read, str) else ''}"
    lines.append(f"{rel}: {msg}")
    return _rows_for(ex_id, rel, assignment, weights, _failed_with(_noted(msg, item.note)))


def _noted(msg: str, note: str) -> str:
    return f"{msg} (Note: {note}.)" if note else msg


def _summarised(run: RunResult, ex_id: str, sources: Mapping[int, str]) -> Summary:
    """``run`` judged here on the probe inputs of its salt."""
    old = channel.probe_salt()
    try:
        channel.set_probe_salt(run.salt)
        return summarise(run, REGISTRY[ex_id], sources)
    finally:
        channel.set_probe_salt(old)


def _judged(item: ToRun, result: Ran, assignment: Assignment,
            weights: Mapping[str, float], lines: list[str]) -> list[Row]:
    ex_id, rel = item.exercise, item.rel
    assert item.notebook is not None
    notebook = summarise(result.notebook, REGISTRY[ex_id], _sources(item.notebook), judge=False)
    summary = decide(REGISTRY[ex_id], notebook,
                     None if result.calls is None else
                     _summarised(result.calls, ex_id, result.call_sources))
    if summary.problem:
        lines.append(f"{rel}: {summary.problem}")
    notes = summary.notes
    lines += [f"{rel}: {n}" for n in notes]

    def message_of(name: str, part: Part) -> tuple[str, str]:
        judged = summary.parts[name]
        msg = judged.verdict.message
        if judged.cell is not None:
            msg += f" (checked in {summary.where(judged.cell)})"
        if not judged.verdict.passed and notes:
            msg += " Note: " + "; ".join(notes) + "."
        return judged.verdict.status, _noted(msg, item.note)

    return _rows_for(ex_id, rel, assignment, weights, message_of)


def _failed_with(message: str) -> Callable[[str, Part], tuple[str, str]]:
    return lambda name, part: (FAILED, message)


def judge(the_plan: Plan, runs: Mapping[Path, Ran | Fault], assignment: Assignment,
          weights: Mapping[str, float], settings: GradeSettings,
          faults: list[str] | None = None) -> tuple[list[Row], list[str]]:
    """The report's rows, in the plan's order, and its overall lines; the grader's own failures
    are added to ``faults`` (and said in the lines and the rows: never the student's)."""
    faults = [] if faults is None else faults
    lines = list(the_plan.notes)
    ran = [r.notebook.cgroups for r in runs.values() if isinstance(r, Ran)]
    if ran:
        note = _limits_note(ran, settings.sandbox)
        if note:
            lines.insert(0, note)
    rows: list[Row] = []
    for item in the_plan.items:
        if isinstance(item, NotGraded):
            rows.append({"notebook": item.rel, "exercise": "", "part": "", "status": FAILED,
                         "score": 0.0, "max_score": 0.0,
                         "message": f"Not graded: {item.why}."})
        elif isinstance(item, Missing):
            rows += _rows_for(item.exercise, item.want, assignment, weights,
                              _failed_with(item.message))
        else:
            rows += _judge_one(item, runs.get(item.path), assignment, weights, lines, faults)
    if not rows:
        lines.insert(0, "No exercise notebook of this course was found in the submission: upload "
                     "the notebooks named exN_M.ipynb (e.g. ex1_4.ipynb) from your workspace.")
    if faults:
        lines.insert(0, f"GRADER FAULT: the grader failed on {len(faults)} notebook(s), not "
                     "because of anything in them; grade them again once the cause is fixed.")
    return rows, lines


def grade(paths: Sequence[str | Path], out_dir: str | Path,
          weights: Mapping[str, float] | None = None, *,
          settings: GradeSettings | None = None,
          assignment: Assignment | None = None) -> dict[str, Any]:
    """Grade every submission under ``paths``; write results.json and grades.csv; return results.

    Raises :class:`SandboxUnavailable` when no sandbox can run here and
    :class:`~gm_grader.view.NoAnswerKeys` when this copy of the course cannot judge (the graded
    build; nothing is written in either case),
    ``ValueError`` when the output folder, a submission or the staging folder lies where every
    sandbox can read it, and :class:`GraderFaults` *after writing every grade it could* when the
    grader failed on some notebook or could not write a report file."""
    t0 = time.monotonic()
    settings = settings or GradeSettings()
    if not keys_installed():
        raise view.NoAnswerKeys(f"this copy of the course has no answer keys ({KEYS_PACKAGE}), so "
                                "it cannot judge: grade with the full course, not the graded build")
    _report.check_visibility(settings.visibility)
    assignment = assignment or Assignment()
    weights = {**(weights or {}), **assignment.weights}
    visibility = assignment.visibility or settings.visibility
    if settings.sandbox:
        problem = sandbox_problem() or view.preflight(settings.limits)
        if problem:
            raise SandboxUnavailable(problem)
    staging = Path(tempfile.mkdtemp(prefix="gm-stage-"))
    try:
        if settings.sandbox:
            bad = view.exposed([out_dir, *paths, staging])
            if bad:
                raise ValueError("refusing to grade: " + "; ".join(bad) + " (grade from and into "
                                 "folders outside it)")
        the_plan = plan(stage(paths, staging), assignment)
        runs = run(the_plan, settings)
        faults: list[str] = []
        rows, lines = judge(the_plan, runs, assignment, weights, settings, faults)
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    try:
        results = _report.write(rows, out_dir, message="\n".join(lines),
                                elapsed=time.monotonic() - t0, visibility=visibility,
                                max_score=assignment.max_score)
    except _report.ReportError as exc:
        raise GraderFaults([*faults, *exc.causes], exc.results) from None
    if faults:
        raise GraderFaults(faults, results)
    return results


def _limits_note(cgroups: Sequence[Sequence[str]], sandbox: bool) -> str | None:
    """The report's header line when a notebook ran without its own cgroups (else None);
    ``cgroups``: the cgroup controllers each run had."""
    missing = sorted({c for kinds in cgroups for c in ("pids", "memory") if c not in kinds})
    if not missing:
        return None
    what = {"pids": ("its processes were bounded by RLIMIT_NPROC of the sandbox's own user"
                     if sandbox else "the number of its processes was not bounded (RLIMIT_NPROC "
                     "does not hold root)") if os.geteuid() == 0 else "its processes were bounded "
                    "per user (RLIMIT_NPROC), not per notebook",
            "memory": "its memory was limited per process (RLIMIT_AS), not for the whole tree"}
    end = ("the sandbox's pid namespace still ended every process with it" if sandbox else
           "processes that left the kernel's session may have outlived it")
    return (f"Grader note: no {' or '.join(missing)} cgroup could be made here for "
            f"{'a notebook' if len(cgroups) == 1 else 'the notebooks'}, so "
            + "; ".join(what[c] for c in missing) + f"; {end} (see the README, 'Limits').")


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m gm_grader",
                                 description=(__doc__ or "").splitlines()[0])
    ap.add_argument("paths", nargs="+", help="submission folders, or exercise notebooks")
    ap.add_argument("--out", required=True, type=Path, help="folder for results.json and grades.csv")
    ap.add_argument("--assignment", type=Path, help="JSON: expected exercises, max_score, weights, visibility")
    ap.add_argument("--weights", type=Path, help="JSON {part id: points}, e.g. {\"1.4a\": 3}")
    ap.add_argument("--visibility", default="visible", choices=_report.VISIBILITIES,
                    help="Gradescope visibility of the results (default visible)")
    ap.add_argument("--cell-timeout", type=float, default=120.0,
                    help="seconds per notebook cell, not counting its checks' probes")
    ap.add_argument("--time-limit", type=float, default=5.0, help="seconds per call of student code")
    ap.add_argument("--notebook-timeout", type=float, default=900.0, help="seconds per notebook in all")
    ap.add_argument("--memory", type=int, default=4096, help="MiB of memory per notebook")
    ap.add_argument("--max-processes", type=int, default=256, help="processes per notebook")
    ap.add_argument("--jobs", type=int, default=1, help="notebooks run at the same time (default 1)")
    ap.add_argument("--no-sandbox", action="store_true",
                    help="run without bubblewrap (only where each submission already has its own "
                    "container, e.g. on Gradescope)")
    args = ap.parse_args(argv)
    missing = [p for p in args.paths if not os.path.lexists(p)]
    if missing:
        print(f"grade: no such file or folder: {', '.join(missing)}", file=sys.stderr)
        return 2
    faults: tuple[str, ...] = ()
    try:
        weights = json.loads(args.weights.read_text()) if args.weights else None
        assignment = load_assignment(args.assignment) if args.assignment else None
        limits = Limits(cell_timeout=args.cell_timeout, time_limit=args.time_limit,
                        notebook_timeout=args.notebook_timeout, memory_mb=args.memory,
                        processes=args.max_processes)
        settings = GradeSettings(limits=limits, sandbox=not args.no_sandbox, jobs=args.jobs,
                                 visibility=args.visibility)
        results: dict[str, Any] | None = grade(args.paths, args.out, weights, settings=settings,
                                               assignment=assignment)
    except SandboxUnavailable as exc:
        print(f"grade: refusing to run student notebooks without a sandbox: {exc}. Install "
              "bubblewrap, or pass --no-sandbox where each submission already runs in its own "
              "container (Gradescope).", file=sys.stderr)
        return 3
    except view.NoAnswerKeys as exc:
        print(f"grade: {exc}", file=sys.stderr)
        return 3
    except GraderFaults as exc:
        faults, results = exc.causes, exc.results
    except (ValueError, OSError) as exc:
        print(f"grade: {exc}", file=sys.stderr)
        return 2
    if results is not None:
        total = sum(t["max_score"] for t in results["tests"])
        n = len({t["name"].split(":")[0] for t in results["tests"] if t["max_score"] > 0})
        print(f"graded {n} notebook(s): {results['score']:g} / {total:g} points; see "
              f"{args.out / 'results.json'} and grades.csv")
        if results.get("output"):
            print(results["output"])
    if faults:
        print(f"grade: the grader itself failed ({len(faults)} fault(s)); every other grade is "
              "written:", file=sys.stderr)
        for f in faults:
            print(f"grade: GRADER FAULT: {f}", file=sys.stderr)
        return 4
    return 0


__all__ = ["grade", "plan", "run", "judge", "main", "identify", "leftover_reason",
           "load_assignment", "SandboxUnavailable", "GraderFaults", "Fault", "Ran", "GradeSettings",
           "Assignment", "Plan", "ToRun", "Missing", "NotGraded", "MAX_NOTEBOOK_BYTES"]

"""Grade submitted exercise notebooks: ``python -m gm_grader SUBMISSIONS... --out DIR``.

Each SUBMISSION is a folder (one student's upload) or a single notebook. For every exercise
notebook ``exN_M.ipynb`` in it:

1. it runs **in its own sandbox** (:mod:`gm_grader.isolate`: bubblewrap, read-only course and Python,
   a private ``/tmp``, no network, no view of the other submissions or of the output folder,
   limits on time, memory, processes and file size; the whole process tree ends with it), cell
   by cell in a fresh kernel (:mod:`gm_grader.runner`), each cell under ``--cell-timeout`` seconds not
   counting its checks' probes, each probe under ``--time-limit`` seconds as in the student's own
   kernel, the whole notebook under ``--notebook-timeout``;
2. every ``check(...)`` call the notebook makes sends, **at the moment it is called**, the plain
   outcomes of that part's probes on a pipe opened before the student's first cell
   (:mod:`gm_core.checks.channel`), with this run's secret; the probe inputs are salted per run;
3. every part is **judged here**, in the grading process, by its untouched checkers, from the
   last accepted check call of that part (:mod:`gm_grader.evidence`); malformed, forged-looking or
   unverifiable evidence is rejected and reported, never passed.

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
submission, as on Gradescope). In nbgrader / otter-grader test cells use
``ex1_4.a.check(answer, strict=True)`` instead (None on success, AssertionError on failure).
"""
from __future__ import annotations

import argparse
import json
import os
import re
import secrets
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from gm_core.checks import channel
from gm_core.checks.exercise import REGISTRY, exercise_ids
from gm_core.checks.store import PASSED
from gm_grader import report as _report
from gm_grader.clock import check_caps
from gm_grader.evidence import summarise
from gm_grader.isolate import Limits, run_submission, sandbox_problem

_EXACT = re.compile(r"ex(\d+)_(\d+)\.ipynb")
_ANY = re.compile(r"ex(\d+)_(\d+)", re.IGNORECASE)
MAX_NOTEBOOK_BYTES = 50_000_000


class SandboxUnavailable(RuntimeError):
    """bubblewrap cannot make a sandbox here, and ``--no-sandbox`` was not given."""


def leftover_reason(path: Path):
    """Why a notebook is a workspace leftover and not a submission (None if it is not one)."""
    name = path.name
    if ".ipynb_checkpoints" in path.parts or name.endswith("-checkpoint.ipynb"):
        return "a Jupyter checkpoint"
    if ".course-update" in name:
        return "the course's newer version of an exercise, kept beside the student's own"
    if re.search(r"-Copy\d*\.ipynb$", name) or name.lower().startswith("copy of "):
        return "a copy of a notebook"
    if name.startswith("."):
        return "a hidden file"
    return None


def _metadata(path: Path):
    """The notebook's top-level metadata dict, or (None, reason) -- never raises."""
    try:
        if path.is_symlink() or not path.is_file():
            return None, "it is not a plain file (a link, a folder or a device)"
        size = path.stat().st_size
        if size > MAX_NOTEBOOK_BYTES:
            return None, f"it is too large ({size >> 20} MB)"
        data = json.loads(path.read_bytes().decode("utf-8"))
    except RecursionError:
        return None, "it is not a readable notebook (its JSON is nested too deeply)"
    except (OSError, ValueError, UnicodeDecodeError) as exc:
        return None, f"it is not a readable notebook ({type(exc).__name__})"
    if not isinstance(data, dict) or not isinstance(data.get("cells"), list):
        return None, "it is not a readable notebook (no list of cells)"
    meta = data.get("metadata")
    return (meta if isinstance(meta, dict) else {}), data


def identify(path: Path):
    """(exercise id or None, note, notebook JSON or None) for a notebook file."""
    meta, data = _metadata(path)
    m = _EXACT.fullmatch(path.name)
    note = ""
    if m is None:
        m = _ANY.search(path.name)
        if m is not None:
            note = f"named {path.name!r}, graded as ex{m.group(1)}_{m.group(2)}.ipynb"
    if m is None and meta is not None:
        course = meta.get("gm_course")
        src = course.get("generated_from") if isinstance(course, dict) else None
        if isinstance(src, str):
            m = _ANY.search(src)
            if m is not None:
                note = (f"named {path.name!r}; recognised from its metadata as "
                        f"ex{m.group(1)}_{m.group(2)}.ipynb (please keep the course's file names)")
    if m is None:
        return None, "", (data if meta is not None else None)
    ex_id = f"{int(m.group(1))}.{int(m.group(2))}"
    return ex_id, note, (data if meta is not None else None)


def load_assignment(path):
    """The assignment declaration (see the module docstring), validated."""
    try:
        a = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise ValueError(f"assignment: cannot read {path} ({exc})") from None
    if not isinstance(a, dict):
        raise ValueError("assignment: the file must hold a JSON object")
    exs = a.get("exercises", [])
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
    for k, v in a.get("part_visibility", {}).items():
        _report.check_visibility(v, f"assignment part_visibility[{k!r}]")
    if "max_score" in a and not (isinstance(a["max_score"], (int, float)) and a["max_score"] > 0):
        raise ValueError("assignment: max_score must be a positive number")
    return {**a, "exercises": list(dict.fromkeys(str(e) for e in exs))}


def _submissions(paths):
    """[(label prefix, [(notebook path, relative name)], [skipped notes])] for each argument."""
    out = []
    many = len(paths) > 1
    for p in map(Path, paths):
        found, skipped = [], []
        if p.is_dir():
            base = p
            files = sorted(q for q in p.rglob("*.ipynb") if q.is_file())
        else:
            base = p.parent
            files = [p]
        prefix = ((p.name if p.is_dir() else p.parent.name) + "/") if many else ""
        for q in files:
            rel = prefix + q.relative_to(base).as_posix()
            why = leftover_reason(q.relative_to(base))
            if why:
                skipped.append(f"{rel} skipped: {why}")
            else:
                found.append((q, rel))
        out.append((prefix, found, skipped))
    return out


def _rows_for(ex_id, rel, weights, part_vis, message_of):
    rows = []
    for name, part in REGISTRY[ex_id].parts.items():
        pts = float(weights.get(part.id, weights.get(f"{ex_id}{name}", part.weight)))
        status, msg = message_of(name, part)
        row = {"notebook": rel, "exercise": ex_id, "part": name, "status": status,
               "score": pts if status == PASSED else 0.0, "max_score": pts, "message": msg}
        vis = part_vis.get(part.id, part_vis.get(f"{ex_id}{name}"))
        if vis:
            row["visibility"] = vis
        rows.append(row)
    return rows


def grade(paths, out_dir, weights=None, *, limits=None, sandbox=True, assignment=None,
          visibility="visible", jobs=1):
    """Grade every submission under ``paths``; write results.json and grades.csv; return results."""
    t0 = time.monotonic()
    limits = limits or Limits()
    _report.check_visibility(visibility)
    assignment = assignment or {}
    weights = {**(weights or {}), **assignment.get("weights", {})}
    part_vis = assignment.get("part_visibility", {})
    visibility = assignment.get("visibility", visibility)
    if sandbox:
        problem = sandbox_problem()
        if problem:
            raise SandboxUnavailable(problem)
    subs = _submissions(paths)
    # hidden from every sandbox: the output, the batch, and the folders around each submission
    # (where other students' uploads usually sit, graded in this run or not)
    hide = [str(Path(out_dir).resolve())] + [str(Path(p).resolve()) for p in paths]
    hide += [str(Path(p).resolve().parent) for p in paths]
    hide += [str(q.resolve()) for _, found, _ in subs for q, _ in found]
    salt, plan, lines = secrets.randbits(62), [], []
    expected = assignment.get("exercises")
    for prefix, found, skipped in subs:
        lines += skipped
        chosen = {}
        for path, rel in found:
            ex_id, note, data = identify(path)
            if ex_id is None or ex_id not in REGISTRY:
                why = (f"there is no exercise {ex_id} in this course" if ex_id else
                       "it is not one of the course's exercise notebooks (exN_M.ipynb, e.g. "
                       "ex1_4.ipynb)")
                plan.append(("row", {"notebook": rel, "exercise": "", "part": "", "status": "failed",
                                     "score": 0.0, "max_score": 0.0, "message": f"Not graded: {why}."}))
                lines.append(f"{rel}: not graded ({why})")
                continue
            if expected is not None and ex_id not in expected:
                lines.append(f"{rel}: not graded (exercise {ex_id} is not part of this assignment)")
                continue
            exact = _EXACT.fullmatch(path.name) is not None
            if ex_id in chosen and (chosen[ex_id][3] or not exact):
                lines.append(f"{rel}: not graded (exercise {ex_id} is graded from {chosen[ex_id][1]})")
                continue
            if ex_id in chosen:
                lines.append(f"{chosen[ex_id][1]}: not graded (exercise {ex_id} is graded from {rel})")
            chosen[ex_id] = (path, rel, note, exact, data)
        for ex_id, (path, rel, note, _, data) in sorted(chosen.items()):
            if note:
                lines.append(f"{rel}: {note}")
            plan.append(("run", (path, rel, ex_id, data)))
        for ex_id in expected or []:
            if ex_id not in chosen:
                want = f"{prefix}ex{ex_id.replace('.', '_')}.ipynb"
                msg = (f"{want} was not found in the submission (upload the exercise notebook "
                       "under this name)")
                plan.append(("missing", (want, ex_id, msg)))
                lines.append(msg)
    runs = [item for kind, item in plan if kind == "run" and item[3] is not None]
    done = {}
    with ThreadPoolExecutor(max_workers=max(1, int(jobs))) as pool:
        futures = {pool.submit(run_submission, path, limits=limits, hide=hide, sandbox=sandbox,
                               salt=salt, caps=check_caps(REGISTRY[ex_id], limits.time_limit)): path
                   for path, _, ex_id, _ in runs}
        for fut, path in futures.items():
            try:
                done[path] = fut.result()
            except Exception as exc:  # noqa: BLE001 - the grader's own failure: a row, not a crash
                done[path] = f"the grader could not run it ({type(exc).__name__}: {exc})"[:300]
    ran = [r for r in done.values() if isinstance(r, dict)]
    if ran:
        note = _limits_note(ran, sandbox)
        if note:
            lines.insert(0, note)
    rows = []
    for kind, item in plan:
        if kind == "row":
            rows.append(item)
        elif kind == "missing":
            want, ex_id, msg = item
            rows += _rows_for(ex_id, want, weights, part_vis, lambda n, p, m=msg: ("failed", m))
        else:
            path, rel, ex_id, data = item
            rows += _judge_one(path, rel, ex_id, data, done.get(path), weights, part_vis, lines)
    if not rows:
        lines.insert(0, "No exercise notebook of this course was found in the submission: upload "
                     "the notebooks named exN_M.ipynb (e.g. ex1_4.ipynb) from your workspace.")
    res = _report.write(rows, out_dir, message="\n".join(lines), elapsed=time.monotonic() - t0,
                        visibility=visibility, max_score=assignment.get("max_score"))
    return res


def _limits_note(ran, sandbox):
    """The report's header line when a notebook ran without its own cgroups (else None)."""
    missing = sorted({c for r in ran for c in ("pids", "memory") if c not in r.get("cgroups", [])})
    if not missing:
        return None
    what = {"pids": "the number of its processes was not bounded (RLIMIT_NPROC does not hold "
                    "root)" if os.geteuid() == 0 else "its processes were bounded per user "
                    "(RLIMIT_NPROC), not per notebook",
            "memory": "its memory was limited per process (RLIMIT_AS), not for the whole tree"}
    end = ("the sandbox's pid namespace still ended every process with it" if sandbox else
           "processes that left the kernel's session may have outlived it")
    return (f"Grader note: no {' or '.join(missing)} cgroup could be made here for "
            f"{'a notebook' if len(ran) == 1 else 'the notebooks'}, so "
            + "; ".join(what[c] for c in missing) + f"; {end} (see the README, 'Limits').")


def _judge_one(path, rel, ex_id, data, run, weights, part_vis, lines):
    ex = REGISTRY[ex_id]
    if data is None or not isinstance(run, dict):
        why = run if isinstance(run, str) else _metadata(path)[1]
        msg = f"the notebook could not be graded: {why}"
        lines.append(f"{rel}: {msg}")
        return _rows_for(ex_id, rel, weights, part_vis, lambda n, p: ("failed", msg))
    cells = data.get("cells", [])
    sources = {}
    for i, c in enumerate(cells):
        src = c.get("source", "") if isinstance(c, dict) else ""
        sources[i] = "".join(src) if isinstance(src, list) and all(isinstance(s, str) for s in src) \
            else (src if isinstance(src, str) else "")
    old = channel.probe_salt()
    try:
        channel.set_probe_salt(run["salt"])
        verdicts, problem, notes, where = summarise(run, ex, sources)
    finally:
        channel.set_probe_salt(old)
    if problem:
        lines.append(f"{rel}: {problem}")
    lines += [f"{rel}: {n}" for n in notes]

    def message_of(name, part):
        v, cell = verdicts[name]
        msg = v.message
        if cell is not None:
            msg += f" (checked in {where(cell)})"
        if not v.passed and notes:
            msg += " Note: " + "; ".join(notes) + "."
        return v.status, msg

    return _rows_for(ex_id, rel, weights, part_vis, message_of)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m gm_grader",
                                 description=__doc__.splitlines()[0])
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
    missing = [p for p in args.paths if not Path(p).exists()]
    if missing:
        print(f"grade: no such file or folder: {', '.join(missing)}", file=sys.stderr)
        return 2
    try:
        weights = json.loads(args.weights.read_text()) if args.weights else None
        assignment = load_assignment(args.assignment) if args.assignment else None
        limits = Limits(args.cell_timeout, args.time_limit, args.notebook_timeout, args.memory,
                        args.max_processes)
        results = grade(args.paths, args.out, weights, limits=limits, sandbox=not args.no_sandbox,
                        assignment=assignment, visibility=args.visibility, jobs=args.jobs)
    except SandboxUnavailable as exc:
        print(f"grade: refusing to run student notebooks without a sandbox: {exc}. Install "
              "bubblewrap, or pass --no-sandbox where each submission already runs in its own "
              "container (Gradescope).", file=sys.stderr)
        return 3
    except (ValueError, OSError) as exc:
        print(f"grade: {exc}", file=sys.stderr)
        return 2
    total = sum(t["max_score"] for t in results["tests"])
    n = len({t["name"].split(":")[0] for t in results["tests"] if t["max_score"] > 0})
    print(f"graded {n} notebook(s): {results['score']:g} / {total:g} points; see "
          f"{args.out / 'results.json'} and grades.csv")
    if results.get("output"):
        print(results["output"])
    return 0


__all__ = ["grade", "main", "identify", "leftover_reason", "load_assignment", "SandboxUnavailable"]

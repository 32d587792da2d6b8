"""Grade submitted exercise notebooks: ``python -m gm_core.grade NOTEBOOKS_OR_FOLDERS... --out DIR``.

For each notebook ``exN_M*.ipynb``:

1. it is executed top to bottom in a **fresh kernel** (nbclient), in a temporary folder, with a
   time limit per cell (``--cell-timeout``, default 120 s) and errors allowed, so one broken cell
   costs only the parts that depend on it;
2. the answers are read from the notebook's own check cells (``ex1_4.a.check(exp_left)`` ->
   ``exp_left``) and, in that kernel, each part's *probes* run on them (in the checkers' sandbox,
   under ``--time-limit`` seconds per call); only plain data (numbers, arrays, strings) comes back;
3. every part is **judged here, in the grading process**, from that plain data with this
   process's own, untouched checkers. A notebook that monkeypatches gm_core, replaces the checkers
   or writes "passed" into their progress record changes nothing but its own kernel.

Outputs: ``DIR/results.json`` in Gradescope's format (``score``; ``tests`` with ``name``,
``number``, ``score``, ``max_score``, ``output``, ``visibility``) and ``DIR/grades.csv``, one row
per notebook and part. Points per part: ``Part.weight`` (2 for a computed answer, 1 for a
multiple-choice question) unless ``--weights FILE.json`` maps part ids (``"1.4a"``,
``"1.4 d_rates"``) to points. In nbgrader / otter-grader test cells use
``ex1_4.a.check(answer, strict=True)`` instead.

Limits: a notebook that deliberately computes its answers with the course's own reference code
(gm_core is open) earns the marks those answers deserve; the grader defends the verdict, not
the secrecy of the solutions.
"""
from __future__ import annotations

import argparse
import ast
import csv
import json
import os
import re
import sys
import tempfile
import time
from pathlib import Path

from .checks import exercise_ids
from .checks._core import REGISTRY, Verdict
from .checks._grading import MARKER
from .checks._progress import FAILED, PASSED
from .checks._sandbox import decode_outcome

_PKG_PARENT = str(Path(__file__).resolve().parent.parent)
_NAME = re.compile(r"ex(\d+)_(\d+)")


def exercise_of(path, nb=None):
    """The exercise id of a notebook, from its name (ex1_4*.ipynb) or its generator metadata."""
    m = _NAME.match(Path(path).name)
    if m is None and nb is not None:
        src = nb.metadata.get("gm_course", {}).get("generated_from", "")
        m = _NAME.search(src)
    if m is None:
        return None
    ex_id = f"{m.group(1)}.{m.group(2)}"
    return ex_id if ex_id in REGISTRY else None


def _code(cell_source):
    return "\n".join("" if line.lstrip().startswith(("%", "!")) else line
                     for line in cell_source.splitlines())


def answer_expressions(nb, ex_id):
    """{part name: source of the answer expression} from the notebook's check calls (last wins)."""
    var = "ex" + ex_id.replace(".", "_")
    parts = REGISTRY[ex_id].parts
    found = {}
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        src = _code(cell.source)
        try:
            tree = ast.parse(src)
        except SyntaxError:
            continue
        for node in ast.walk(tree):
            if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                    and node.func.attr == "check" and isinstance(node.func.value, ast.Attribute)
                    and isinstance(node.func.value.value, ast.Name) and node.func.value.value.id == var):
                continue
            name = node.func.value.attr
            if name in parts and node.args:
                seg = ast.get_source_segment(src, node.args[0])
                if seg:
                    found[name] = seg
    return found


def _collector_cell(ex_id, exprs, time_limit):
    """The cell appended to the graded notebook. It loads a *fresh* copy of the course package
    under a private name (so methods the notebook patched on the gm_core it imported are not the
    ones that probe its answers) and prints the plain outcomes after a marker."""
    getters = ", ".join(f"{name!r}: (lambda: ({src}))" for name, src in exprs.items())
    pkg_dir = str(Path(__file__).resolve().parent)
    return ("import sys as __gm_sys, types as __gm_types, importlib as __gm_il\n"
            "__gm_pkg = __gm_types.ModuleType('__gm_fresh_course')\n"
            f"__gm_pkg.__path__ = [{pkg_dir!r}]\n"
            "__gm_sys.modules['__gm_fresh_course'] = __gm_pkg\n"
            "__gm_grading = __gm_il.import_module('__gm_fresh_course.checks._grading')\n"
            f"print({MARKER!r} + __gm_grading.collect_all({ex_id!r}, {{{getters}}}, {time_limit!r}))")


def run_notebook(path, ex_id, cell_timeout=120, time_limit=5.0):
    """Execute the notebook in a fresh kernel; return ({part: evidence}, problem text or "")."""
    import nbformat
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    exprs = answer_expressions(nb, ex_id)
    cell = nbformat.v4.new_code_cell(_collector_cell(ex_id, exprs, time_limit))
    nb.cells.append(cell)
    env_before = dict(os.environ)
    os.environ["PYTHONPATH"] = os.pathsep.join([_PKG_PARENT] + [p for p in env_before.get("PYTHONPATH", "").split(os.pathsep) if p])
    os.environ.pop("GM_COURSE_WORKSPACE", None)
    os.environ.setdefault("MPLBACKEND", "Agg")
    problem = ""
    try:
        with tempfile.TemporaryDirectory(prefix="gm-grade-") as work:
            client = NotebookClient(nb, timeout=cell_timeout, kernel_name="python3", allow_errors=True,
                                    resources={"metadata": {"path": work}})
            try:
                client.execute()
            except Exception as exc:  # noqa: BLE001 - a dead kernel, a timeout in a cell
                problem = f"the notebook could not be run to the end ({type(exc).__name__})"
    finally:
        os.environ.clear()
        os.environ.update(env_before)
    text = "".join(o.get("text", "") for o in cell.get("outputs", []) if o.get("output_type") == "stream")
    evidence = {}
    for line in text.splitlines():
        if line.startswith(MARKER):
            try:
                evidence = json.loads(line[len(MARKER):])
            except ValueError:
                evidence = {}
    if not isinstance(evidence, dict):
        evidence = {}
    if not evidence and not problem:
        problem = "the answers could not be collected from the notebook"
    return evidence, problem


def judge_part(part, evidence):
    """A Verdict for one part from the plain evidence collected in the student's kernel."""
    if not isinstance(evidence, dict):
        return Verdict(FAILED, "no answer was collected for this part", part.title)
    if "missing" in evidence:
        return Verdict(FAILED, str(evidence["missing"])[:300], part.title)
    raw = evidence.get("outcomes")
    if not isinstance(raw, list):
        return Verdict(FAILED, "no answer was collected for this part", part.title)
    output = evidence.get("output") if isinstance(evidence.get("output"), str) else ""
    return part.verdict([decode_outcome(o) for o in raw], output[:2000])


def grade_notebook(path, weights=None, cell_timeout=120, time_limit=5.0):
    """Rows {notebook, exercise, part, status, score, max_score, message} for one notebook."""
    import nbformat

    path = Path(path)
    weights = weights or {}
    try:
        nb = nbformat.read(path, as_version=4)
    except Exception as exc:  # noqa: BLE001
        return [{"notebook": path.name, "exercise": "", "part": "", "status": FAILED, "score": 0.0,
                 "max_score": 0.0, "message": f"not a readable notebook ({type(exc).__name__})"}]
    ex_id = exercise_of(path, nb)
    if ex_id is None:
        return [{"notebook": path.name, "exercise": "", "part": "", "status": FAILED, "score": 0.0,
                 "max_score": 0.0, "message": "not an exercise notebook of this course (exN_M.ipynb)"}]
    evidence, problem = run_notebook(path, ex_id, cell_timeout, time_limit)
    rows = []
    for name, part in REGISTRY[ex_id].parts.items():
        verdict = judge_part(part, evidence.get(name))
        max_score = float(weights.get(part.id, weights.get(f"{ex_id}{name}", part.weight)))
        message = verdict.message if not problem or verdict.passed else f"{verdict.message} ({problem})"
        rows.append({"notebook": str(path), "exercise": ex_id, "part": name, "status": verdict.status,
                     "score": max_score if verdict.status == PASSED else 0.0, "max_score": max_score,
                     "message": message})
    return rows


def notebooks_in(paths):
    out = []
    for p in map(Path, paths):
        if p.is_dir():
            out += [q for q in sorted(p.rglob("ex*.ipynb"))
                    if ".ipynb_checkpoints" not in q.parts]
        else:
            out.append(p)
    return out


def write_results(rows, out_dir, elapsed=0.0):
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    tests = [{"name": f"{r['notebook']}: exercise {r['exercise']} part {r['part']}".strip(),
              "number": f"{r['exercise']}{r['part']}", "score": r["score"], "max_score": r["max_score"],
              "status": "passed" if r["status"] == PASSED else "failed",
              "output": r["message"], "visibility": "visible"} for r in rows]
    results = {"score": sum(r["score"] for r in rows), "execution_time": round(elapsed, 1),
               "visibility": "visible", "stdout_visibility": "hidden", "tests": tests}
    (out_dir / "results.json").write_text(json.dumps(results, indent=1) + "\n", encoding="utf-8")
    with open(out_dir / "grades.csv", "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=["notebook", "exercise", "part", "status", "score",
                                          "max_score", "message"])
        w.writeheader()
        w.writerows(rows)
    return results


def grade(paths, out_dir, weights=None, cell_timeout=120, time_limit=5.0):
    """Grade every notebook under ``paths``; write results.json and grades.csv; return the results."""
    t = time.monotonic()
    rows = []
    for nb in notebooks_in(paths):
        rows += grade_notebook(nb, weights, cell_timeout, time_limit)
    return write_results(rows, out_dir, time.monotonic() - t)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python -m gm_core.grade", description=__doc__.splitlines()[0])
    ap.add_argument("paths", nargs="+", help="exercise notebooks, or folders holding them")
    ap.add_argument("--out", required=True, type=Path, help="folder for results.json and grades.csv")
    ap.add_argument("--weights", type=Path, help="JSON {part id: points}, e.g. {\"1.4a\": 3}")
    ap.add_argument("--cell-timeout", type=float, default=120.0, help="seconds per notebook cell")
    ap.add_argument("--time-limit", type=float, default=5.0, help="seconds per call of student code")
    args = ap.parse_args(argv)
    weights = json.loads(args.weights.read_text()) if args.weights else None
    missing = [p for p in args.paths if not Path(p).exists()]
    if missing:
        print(f"grade: no such file or folder: {', '.join(missing)}", file=sys.stderr)
        return 2
    results = grade(args.paths, args.out, weights, args.cell_timeout, args.time_limit)
    total = sum(t["max_score"] for t in results["tests"])
    print(f"graded {len({t['name'].split(':')[0] for t in results['tests']})} notebook(s): "
          f"{results['score']:g} / {total:g} points; see {args.out / 'results.json'} and grades.csv")
    return 0


__all__ = ["grade", "grade_notebook", "judge_part", "answer_expressions", "exercise_of", "main",
           "exercise_ids"]

if __name__ == "__main__":
    sys.exit(main())

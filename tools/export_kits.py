"""Write otter-grader master notebooks and nbgrader source notebooks from ``solutions/``.

    python tools/export_kits.py [--otter build/kits/otter] [--nbgrader build/kits/nbgrader]
                                [--exercises 1.1 3.1 ...]

The worked solutions are the source of truth (markers ``### BEGIN SOLUTION`` / ``### END
SOLUTION``, starter lines ``#> ...``, see tools/make_exercises.py). Each part's check call
``exN_M.<part>.check(answer)`` says which cells answer which part, and gm_core's registry gives
its points. Three kinds of cells:

* **answer cells**: a code cell with a solution region that has starter lines, or that is not the
  whole cell. Students get the starter, exactly as in ``exercises/``.
* **instructor cells**: a cell that is nothing but one solution region without starter lines (a
  worked explanation, an independent check). They stay in the instructor's notebook and are
  *not* handed to students (no empty "your code here" task appears in their place).
* everything else, copied as is; ``solution_only`` cells are left out.

otter (``otter assign`` format, exception-based tests): one question per part
(``# BEGIN QUESTION`` ... ``# END QUESTION`` raw cells, points from the registry); the answer
cells inside ``# BEGIN SOLUTION`` / ``# END SOLUTION``, their starter in an otter *prompt* block so
``otter assign`` writes it into the student notebook; a test ``def test_<part>(exN_M, <answer
names>)`` that calls ``exN_M.<part>.check(answer, strict=True, quiet=True)``.

nbgrader (``source/exN_M/exN_M.ipynb`` + ``nbgrader_config.py``): answer cells are nbgrader
solution cells with the starter *before* the solution region (the config's code stub is
``# your code here``, so ``generate_assignment`` keeps the starter); every check cell is followed
by a locked autograder test cell whose hidden test calls ``check(..., strict=True, quiet=True)``.
"""
from __future__ import annotations

import argparse
import ast
import hashlib
import json
import re
import sys
from pathlib import Path

import nbformat

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tools"))
from make_exercises import BEGIN, CODE_STUB, END, SOLUTION_ONLY, STARTER, MarkerError  # noqa: E402

CHECK = re.compile(r"^(ex\d+_\d+)\.(\w+)\.check\((.*)\)\s*$")
OTTER_SOLUTION_TAG = "otter_assign_solution_cell"


def _check_call(cell):
    if cell.cell_type != "code":
        return None
    lines = [ln for ln in cell.source.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if len(lines) == 1:
        m = CHECK.match(lines[0].strip())
        if m:
            return m.group(1), m.group(2), m.group(3)
    return None


def split_region(source, where=""):
    """(before, starter, solution, after) line lists of a cell with one top-level solution region,
    or None when the cell has no region."""
    lines = source.splitlines()
    begins = [i for i, ln in enumerate(lines) if BEGIN.match(ln)]
    if not begins:
        return None
    ends = [i for i, ln in enumerate(lines) if END.match(ln)]
    if len(begins) != 1 or len(ends) != 1 or ends[0] < begins[0]:
        raise MarkerError(f"{where}: expected exactly one BEGIN/END SOLUTION pair")
    b, e = begins[0], ends[0]
    if lines[b] != lines[b].lstrip():
        raise MarkerError(f"{where}: the solution region must start at the left margin")
    starter, solution = [], []
    for ln in lines[b + 1:e]:
        m = STARTER.match(ln)
        (starter.append(m.group(1) + m.group(2)) if m else solution.append(ln))
    return lines[:b], starter, solution, lines[e + 1:]


def classify(cell, where=""):
    """"answer", "instructor", "check" or "plain"."""
    if _check_call(cell):
        return "check"
    if cell.cell_type not in ("code", "markdown"):
        return "plain"
    parts = split_region(cell.source, where)
    if parts is None:
        return "plain"
    before, starter, _, after = parts
    whole = not any(ln.strip() for ln in before + after)
    if cell.cell_type == "markdown":
        if not whole:
            raise MarkerError(f"{where}: a markdown solution region must be the whole cell")
        return "instructor"
    return "instructor" if whole and not starter else "answer"


def _weights(ex_id):
    from gm_core.checks.exercise import REGISTRY
    return {name: float(part.weight) for name, part in REGISTRY[ex_id].parts.items()}


def segments(nb, name):
    """[(cells, check cell or None)]: the cells before each check call, and what is left."""
    out, pending = [], []
    for i, cell in enumerate(nb.cells):
        if SOLUTION_ONLY in cell.get("metadata", {}).get("tags", []):
            continue
        kind = classify(cell, f"{name} cell {i}")
        if kind == "check":
            out.append((pending, cell))
            pending = []
        else:
            pending.append((kind, cell))
    out.append((pending, None))
    return out


def _names_in(expr):
    """The variable names an answer expression reads (the test function's parameters)."""
    return {n.id for n in ast.walk(ast.parse(expr, mode="eval")) if isinstance(n, ast.Name)}


def _new(cell_type, source, tags=None, **meta):
    make = {"code": nbformat.v4.new_code_cell, "markdown": nbformat.v4.new_markdown_cell,
            "raw": nbformat.v4.new_raw_cell}[cell_type]
    cell = make(source)
    if tags:
        cell.metadata["tags"] = list(tags)
    cell.metadata.update(meta)
    return cell


def _copy(cell):
    tags = [t for t in cell.get("metadata", {}).get("tags", []) if t != SOLUTION_ONLY]
    return _new(cell.cell_type, cell.source, tags)


def _header(nb, ex_id, tool):
    out = nbformat.v4.new_notebook()
    out.metadata = {k: v for k, v in nb.metadata.items() if k in ("kernelspec", "language_info")}
    out.metadata["gm_course"] = {"generated_from": f"solutions/ex{ex_id.replace('.', '_')}.ipynb",
                                 "note": f"{tool} version written by tools/export_kits.py; edit the solution"}
    return out


# ---- otter ------------------------------------------------------------------------------------

def otter_master(nb, ex_id):
    """otter-grader's master notebook for one solution notebook."""
    stem = "ex" + ex_id.replace(".", "_")
    weights = _weights(ex_id)
    out = _header(nb, ex_id, "otter-grader")
    config = {"name": stem, "init_cell": False, "check_all_cell": False, "export_cell": False,
              "run_tests": True, "tests": {"ok_format": False, "files": False}}
    out.cells.append(_new("raw", "# ASSIGNMENT CONFIG\n" + "\n".join(
        f"{k}: {json.dumps(v)}" for k, v in config.items())))

    def otter_code(cell):
        before, starter, solution, after = split_region(cell.source)
        prompt = starter or [CODE_STUB]
        # otter keeps the prompt in the autograder notebook as a string literal: its quotes must not
        # occur in the prompt (a starter's docstring uses """, which would end the string early)
        quote = next((q for q in ('"""', "'''") if not any(q in line for line in prompt)), None)
        if quote is None:
            raise ValueError(f"exercise {ex_id}: a starter holds both kinds of triple quotes; otter cannot wrap it")
        src = before + [f"{quote} # BEGIN PROMPT"] + prompt + [f"{quote} # END PROMPT"]
        return "\n".join(src + ["# BEGIN SOLUTION NO PROMPT"] + solution + ["# END SOLUTION"] + after)

    def plain(kind, cell):
        if kind == "instructor":
            src = cell.source
            if cell.cell_type == "code":
                src = re.sub(r"^#{3}\s*BEGIN SOLUTION.*$", "# BEGIN SOLUTION NO PROMPT", src, count=1, flags=re.M)
                src = re.sub(r"^#{3}\s*END SOLUTION.*$", "# END SOLUTION", src, count=1, flags=re.M)
            else:
                src = "\n".join(ln for ln in src.splitlines() if not (BEGIN.match(ln) or END.match(ln)))
            return _new(cell.cell_type, src, [OTTER_SOLUTION_TAG])
        if kind == "answer":           # a fill-in outside a question: otter strips it all the same
            return _new("code", otter_code(cell), [OTTER_SOLUTION_TAG])
        return _copy(cell)

    for cells, check in segments(nb, stem):
        answers = [k for k, (kind, _) in enumerate(cells) if kind == "answer"]
        if check is None or not answers:
            out.cells += [plain(kind, c) for kind, c in cells]
            if check is not None:
                out.cells.append(_copy(check))
            continue
        last = answers[-1]
        first = last
        while first > 0 and cells[first - 1][0] in ("answer", "instructor"):
            first -= 1
        while cells[first][0] != "answer":
            first += 1
        start = first
        while start > 0 and cells[start - 1][0] == "plain" and cells[start - 1][1].cell_type == "markdown":
            start -= 1
        out.cells += [plain(kind, c) for kind, c in cells[:start]]
        _, part, expr = _check_call(check)
        out.cells.append(_new("raw", f"# BEGIN QUESTION\nname: {stem}_{part}\npoints: {weights[part]:g}\ncheck_cell: false"))
        out.cells += [_copy(c) for _, c in cells[start:first]]
        out.cells.append(_new("raw", "# BEGIN SOLUTION"))
        for kind, cell in cells[first:last + 1]:
            out.cells.append(_new("code", otter_code(cell)) if kind == "answer" else plain(kind, cell))
        out.cells.append(_new("raw", "# END SOLUTION"))
        names = sorted(_names_in(expr) | {stem})
        out.cells.append(_new("raw", "# BEGIN TESTS"))
        out.cells.append(_new("code", (
            f'""" # BEGIN TEST CONFIG\npoints: {weights[part]:g}\n""" # END TEST CONFIG\n'
            f"def test_{part}({', '.join(names)}):\n"
            f"    {stem}.{part}.check({expr}, strict=True, quiet=True)")))
        out.cells.append(_new("raw", "# END TESTS"))
        out.cells.append(_new("raw", "# END QUESTION"))
        out.cells.append(_copy(check))
    return out


# ---- nbgrader ---------------------------------------------------------------------------------

NBGRADER_CONFIG = '''# nbgrader configuration written by tools/export_kits.py for the course's exercises.
c = get_config()  # noqa: F821
c.CourseDirectory.root = "."
# The starter code stands before each solution region; the region itself becomes this stub.
c.ClearSolutions.code_stub = {"python": "# your code here"}
c.ClearSolutions.text_stub = "*Your answer here.*"
c.ExecutePreprocessor.timeout = 300
'''


def _nbgrader(cell, grade_id, *, solution=False, grade=False, locked=False, points=None):
    meta = {"grade": grade, "grade_id": grade_id, "locked": locked, "schema_version": 3,
            "solution": solution, "task": False}
    if grade:
        meta["points"] = points
    cell.metadata["nbgrader"] = meta
    return cell


def nbgrader_source(nb, ex_id):
    """nbgrader's source notebook (cell metadata) for one solution notebook."""
    stem = "ex" + ex_id.replace(".", "_")
    weights = _weights(ex_id)
    out = _header(nb, ex_id, "nbgrader")
    for cells, check in segments(nb, stem):
        part = _check_call(check)[1] if check is not None else None
        k = 0
        for kind, cell in cells:
            if kind == "instructor":
                continue                     # never a student task; the worked notebook keeps it
            if kind == "answer":
                if part is None:
                    raise MarkerError(f"{stem}: an answer cell after the last check call")
                before, starter, solution, after = split_region(cell.source)
                src = before + starter + ["### BEGIN SOLUTION"] + solution + ["### END SOLUTION"] + after
                k += 1
                out.cells.append(_nbgrader(_new("code", "\n".join(src)), f"{stem}_{part}_answer{k}", solution=True))
            else:
                out.cells.append(_copy(cell))
        if check is not None:
            _, part, expr = _check_call(check)
            out.cells.append(_copy(check))
            test = _new("code", (f"# Autograder test for part ({part}), {weights[part]:g} point(s).\n"
                                 "### BEGIN HIDDEN TESTS\n"
                                 f"{stem}.{part}.check({expr}, strict=True, quiet=True)\n"
                                 "### END HIDDEN TESTS"))
            out.cells.append(_nbgrader(test, f"{stem}_{part}_test", grade=True, locked=True,
                                       points=weights[part]))
    return out


# ---- files ------------------------------------------------------------------------------------

def _ids(exercises):
    known = sorted(p.stem[2:].replace("_", ".") for p in (ROOT / "solutions").glob("ex*_*.ipynb"))
    ids = list(exercises) if exercises else known
    bad = [e for e in ids if e not in known]
    if bad:
        raise ValueError(f"exercises: unknown exercise id(s) {bad}; known: {', '.join(known)}")
    return ids


def _stable_ids(nb, stem):
    """Give every cell an id derived from the exercise, its place and its content (nbformat's new
    cells get random ids), so that exporting the same solutions twice writes the same files."""
    for i, cell in enumerate(nb.cells):
        digest = hashlib.sha1(f"{stem}\n{i}\n{cell.cell_type}\n{cell.source}".encode()).hexdigest()
        cell["id"] = f"{stem.replace('_', '-')}-{i:03d}-{digest[:8]}"


def _write_converted(exercises, convert, path_of):
    """Convert each exercise's solution notebook with ``convert(nb, ex_id)``, validate it and write
    it to ``path_of(stem)``; the paths written."""
    paths = []
    for ex_id in _ids(exercises):
        stem = "ex" + ex_id.replace(".", "_")
        nb = nbformat.read(ROOT / "solutions" / f"{stem}.ipynb", as_version=4)
        out = convert(nb, ex_id)
        _stable_ids(out, stem)
        nbformat.validate(out)
        path = path_of(stem)
        path.parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(out, path)
        paths.append(path)
    return paths


def write_otter(out_dir, exercises=None):
    out_dir = Path(out_dir)
    return _write_converted(exercises, otter_master, lambda stem: out_dir / stem / f"{stem}.ipynb")


def write_nbgrader(course_dir, exercises=None):
    course_dir = Path(course_dir)
    course_dir.mkdir(parents=True, exist_ok=True)
    (course_dir / "nbgrader_config.py").write_text(NBGRADER_CONFIG)
    return _write_converted(exercises, nbgrader_source, lambda stem: course_dir / "source" / stem / f"{stem}.ipynb")


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python tools/export_kits.py", description=__doc__.splitlines()[0])
    ap.add_argument("--otter", type=Path, default=ROOT / "build" / "kits" / "otter")
    ap.add_argument("--nbgrader", type=Path, default=ROOT / "build" / "kits" / "nbgrader")
    ap.add_argument("--exercises", nargs="+", help="exercise ids, e.g. 1.1 3.1 (default all)")
    args = ap.parse_args(argv)
    try:
        o = write_otter(args.otter, args.exercises)
        n = write_nbgrader(args.nbgrader, args.exercises)
    except (ValueError, MarkerError) as exc:
        print(f"export_kits: {exc}", file=sys.stderr)
        return 2
    print(f"otter-grader: {len(o)} master notebook(s) in {args.otter} (run `otter assign` on each)")
    print(f"nbgrader: {len(n)} source notebook(s) in {args.nbgrader}/source "
          f"(run `nbgrader generate_assignment exN_M` there)")
    return 0


if __name__ == "__main__":
    sys.exit(main())

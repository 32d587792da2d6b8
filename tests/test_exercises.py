"""exercises/ is generated from solutions/ by tools/make_exercises.py and must stay in sync.

Also: the generator's marker rules, its determinism, and that every untouched exercise notebook
runs without error and leaves its exercise "unattempted" (read from the record of the one
execution of the notebook, which includes progress() at its end: tests/nbrun.py)."""
import importlib.util
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import nbformat
import nbrun
import pytest

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "make_exercises.py"
spec = importlib.util.spec_from_file_location("make_exercises", SCRIPT)
mk = importlib.util.module_from_spec(spec)
spec.loader.exec_module(mk)

SOLUTIONS = sorted((ROOT / "solutions").glob("ex*.ipynb"))
EXERCISES = sorted((ROOT / "exercises").glob("ex*.ipynb"))


def ex_id(path):
    return path.stem[2:].replace("_", ".")


def test_there_is_one_exercise_per_solution():
    assert SOLUTIONS, "no worked solutions found"
    assert [p.name for p in SOLUTIONS] == [p.name for p in EXERCISES]


def test_exercises_are_up_to_date():
    changes = mk.plan(ROOT / "solutions", ROOT / "exercises")
    assert not changes, ("exercises/ is out of date with solutions/: run `make exercises` "
                         f"({', '.join(p.name for p in changes)})")


@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.name)
def test_exercise_has_no_markers_or_outputs(path):
    text = path.read_text(encoding="utf-8")
    for marker in ("BEGIN SOLUTION", "END SOLUTION", "#> ", "solution_only"):
        assert marker not in text, f"{path.name} contains {marker!r}"
    nb = nbformat.read(path, as_version=4)
    assert all(not c.get("outputs") and c.get("execution_count") is None
               for c in nb.cells if c.cell_type == "code")


@pytest.mark.parametrize("path", SOLUTIONS, ids=lambda p: p.name)
def test_solution_is_committed_without_outputs_and_ends_with_progress(path):
    nb = nbformat.read(path, as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert all(not c.get("outputs") and c.get("execution_count") is None for c in code)
    assert progress_cell(nb).source.strip().endswith("progress()")
    assert f'progress()["{ex_id(path)}"] == "passed"' in code[-1].source


def progress_cell(nb):
    """The notebook's progress cell: its last code cell that the exercise keeps."""
    return [c for c in nb.cells if c.cell_type == "code"
            and mk.SOLUTION_ONLY not in c.get("metadata", {}).get("tags", [])][-1]


#: Runs the progress cell of each notebook named on the command line by itself, in a new
#: namespace of a new Python process, as after a kernel restart; prints what it shows.
_ALONE = """
import ast, json, sys
import nbformat
out = {}
for path in sys.argv[1:]:
    nb = nbformat.read(path, as_version=4)
    cell = [c for c in nb.cells if c.cell_type == "code"
            and "solution_only" not in c.get("metadata", {}).get("tags", [])][-1]
    tree = ast.parse(cell.source)
    last = tree.body.pop() if tree.body and isinstance(tree.body[-1], ast.Expr) else None
    ns = {}
    try:
        exec(compile(tree, path, "exec"), ns)
        value = eval(compile(ast.Expression(last.value), path, "eval"), ns) if last else None
        out[path] = {"type": type(value).__name__, "shown": repr(value),
                     "html": getattr(value, "_repr_html_", lambda: "")()}
    except Exception as exc:
        out[path] = {"error": f"{type(exc).__name__}: {exc}"}
print(json.dumps(out))
"""


def test_the_progress_cell_works_on_its_own_after_a_restart(tmp_path):
    """The last cell of every exercise (and of every solution, before its solution-only assert),
    run alone in a fresh process and namespace, as after a kernel restart: no NameError, and
    what it shows is the progress table (every exercise, in words), never a raw dict."""
    from gm_core.checks.exercise import exercise_ids
    paths = [str(p) for p in EXERCISES + SOLUTIONS]
    env = dict(os.environ, PYTHONPATH=str(ROOT), GM_CHECKS_NO_FORK="")
    env.pop("GM_COURSE_WORKSPACE", None)
    res = subprocess.run([sys.executable, "-c", _ALONE, *paths], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stderr
    shown = json.loads(res.stdout.strip().splitlines()[-1])
    for path in paths:
        got = shown[path]
        assert "error" not in got, f"{Path(path).relative_to(ROOT)}: {got.get('error')}"
        assert got["type"] == "ProgressTable", (path, got["type"])
        text = got["shown"]
        assert text.startswith("Your progress") and "{" not in text, text[:200]
        rows = [line.split() for line in text.splitlines()[2:]]
        assert [r[0] for r in rows] == list(exercise_ids()), text
        assert all(" ".join(r[1:3]) in ("unattempted 0", "in progress", "failed 0", "passed")
                   or r[1] in ("unattempted", "failed", "passed") for r in rows), text
        assert got["html"].count("<tr>") == len(exercise_ids()) + 1, got["html"][:300]


# ------------------------------------------------------------------------ what the student reads
_ANSWER_STUB = re.compile(r"^\*Your answer here\.\*$", re.M)


def answer_cells(nb):
    """[(index, cell)] of the cells a student is asked to fill in."""
    out = []
    for i, c in enumerate(nb.cells):
        text = c.source
        if c.cell_type == "markdown" and _ANSWER_STUB.search(text):
            out.append((i, c))
        elif c.cell_type == "code" and re.search(r"#\s*your (answer|code) here", text, re.I):
            out.append((i, c))
    return out


@pytest.mark.parametrize("path", EXERCISES, ids=lambda p: p.name)
def test_every_answer_cell_answers_a_question_above_it(path):
    """No orphan "Your answer here": every cell the student fills in follows the markdown prompt
    that asks for it (a written answer follows a question), never a check cell or a solution's
    commentary that the exercise left out."""
    nb = nbformat.read(path, as_version=4)
    cells = answer_cells(nb)
    assert cells, f"{path.name} asks for nothing"
    for i, cell in cells:
        before = prompt_of(nb, i)
        assert before is not None and before.cell_type == "markdown", (
            f"{path.name} cell {i} ({cell.source.strip()[:40]!r}) does not follow a prompt: "
            f"{'' if before is None else before.source.strip()[:80]!r}")
        if cell.cell_type == "markdown":
            assert "?" in before.source or re.search(r"\b(Explain|Describe|Say|Why)\b", before.source), (
                f"{path.name} cell {i}: a written answer, but the cell above asks no question")


def prompt_of(nb, i):
    """The cell that asks for answer cell ``i``: the nearest cell above it that is not set-up code
    (set-up code checks nothing and is no answer: symbols, a helper); None at the top."""
    for cell in reversed(nb.cells[:i]):
        if cell.cell_type == "code" and not re.search(r"\.(check|hint)\(|#\s*your (answer|code) here",
                                                      cell.source, re.I):
            continue
        return cell
    return None


def test_the_orphan_rule_catches_an_orphan(tmp_path):
    """The rule above fails on what ex1_2 once had: a solution's commentary after a check cell."""
    v4 = nbformat.v4
    nb = generated(tmp_path, [
        v4.new_markdown_cell("## (a) Give x"),
        v4.new_code_cell("### BEGIN SOLUTION\n#> x = None  # your answer here\nx = 1\n### END SOLUTION"),
        v4.new_code_cell("ex9_9.a.check(x)"),
        v4.new_markdown_cell("<!-- ### BEGIN SOLUTION -->\n**Discussion.** ...\n<!-- ### END SOLUTION -->"),
    ])
    (i, orphan), = [(i, c) for i, c in answer_cells(nb) if c.cell_type == "markdown"]
    assert prompt_of(nb, i).cell_type == "code"            # the check cell: an orphan
    (j, answer), = [(j, c) for j, c in answer_cells(nb) if c.cell_type == "code"]
    assert prompt_of(nb, j).cell_type == "markdown"        # the prompt "(a) Give x"


#: A hint line of an exercise notebook: ``# ex1_2.a.hint()   # ...; hint(2) says more``.
_HINT_LINE = re.compile(r"^#?\s*(ex\d+_\d+)\.(\w+)\.hint\(\)\s*#(.*)$", re.M)


def stated_hints(comment):
    """How many hints a hint line's comment says the part has: its largest hint(k), else 1."""
    return max([int(k) for k in re.findall(r"hint\((\d+)\)", comment)] or [1])


@pytest.mark.parametrize("path", EXERCISES + SOLUTIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_hint_counts_in_the_notebook_are_the_checkers(path):
    """Every part has one hint line, and the number of hints it states is the number the checker
    has; the notebook's prose states no count of its own."""
    from gm_core.checks.exercise import REGISTRY
    ex = REGISTRY[ex_id(path)]
    nb = nbformat.read(path, as_version=4)
    found = {}
    for c in nb.cells:
        if c.cell_type == "code":
            for m in _HINT_LINE.finditer(c.source):
                assert m.group(1) == path.stem, m.group(0)
                assert m.group(2) not in found, f"two hint lines for part {m.group(2)}"
                found[m.group(2)] = stated_hints(m.group(3))
        else:
            assert not re.search(r"hint\(\d+\)", c.source), f"{path.name}: a hint count in prose"
    assert found == {name: len(part.hints) for name, part in ex.parts.items()}


@pytest.mark.parametrize("readme", ["tools/workspace_README.md", "exercises/README.md"])
def test_the_readmes_state_hint_counts_that_hold(readme):
    from gm_core.checks.exercise import REGISTRY
    text = (ROOT / readme).read_text(encoding="utf-8")
    lines = list(_HINT_LINE.finditer(text))
    assert lines
    for m in lines:
        part = REGISTRY[m.group(1)[2:].replace("_", ".")].parts[m.group(2)]
        assert stated_hints(m.group(3)) == len(part.hints), m.group(0)


def test_hint_counts_are_read_from_the_comment():
    assert stated_hints(" uncomment for a hint; hint(2) and hint(3) say more") == 3
    assert stated_hints(" uncomment for a hint; hint(2) says more") == 2
    assert stated_hints(" uncomment for a hint (this part has one)") == 1


#: Maths typed as plain text: Greek letters spelled out, subscripted names, ASCII arrows and
#: relations, R+ for the positive reals, sizes like 2 x 2, sqrt, and function calls like exp(...)
_GREEK = "alpha|beta|gamma|delta|epsilon|theta|lambda|mu|xi|pi|rho|sigma|tau|phi|psi|omega"
_PSEUDO = re.compile(
    rf"\b(?:{_GREEK})(?:\d|_|\b)|\b[A-Za-z]\w*_\w+|\b[A-Za-z][0-9]\b|->|!=|<=|>=|\bR\+"
    r"|\b\d+ ?x ?\d+\b|\bsqrt\b|\b(?:exp|log|log10|sin|cos|tan|diag|sign|sinc)\(")
_LINK_TARGET = re.compile(r"\]\([^)]*\)")
_PATH = re.compile(r"\S*/\S*")


def pseudo_maths(markdown):
    """[snippet] for every piece of maths written as plain text in ``markdown``, outside maths,
    code, comments, link targets and file paths (tests/test_notebook_text.py's prose())."""
    from test_notebook_text import prose
    left = _PATH.sub(" ", _LINK_TARGET.sub("]", prose(markdown)))
    return [left[max(0, m.start() - 25):m.end() + 25].replace("\n", " ") for m in _PSEUDO.finditer(left)]


@pytest.mark.parametrize("path", EXERCISES + SOLUTIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_maths_in_the_exercises_is_written_as_maths(path):
    nb = nbformat.read(path, as_version=4)
    found = [f"cell {i}: ...{s}..." for i, c in enumerate(nb.cells) if c.cell_type == "markdown"
             for s in pseudo_maths(c.source)]
    assert not found, f"{path.relative_to(ROOT)}: maths as plain text (write it in $...$):\n" + "\n".join(found)


@pytest.mark.parametrize("text, n", [
    ("the rotation by -theta and h = diag(h1, h2) in (R+, x), a 2 x 2 matrix", 6),
    ("alpha_dot, t -> exp(t xi) and x != 0, radius sqrt 2", 6),
    (r"$\alpha_1$ and `alpha1` and [exercise 1.3](../workspace/ex1_3.ipynb), <!-- xi -->", 0),
    ("the (1.xii) box, Figure 2.8, SE(2), section 1.6.4", 0),
])
def test_the_plain_text_maths_scanner(text, n):
    assert len(pseudo_maths(text)) == n, pseudo_maths(text)


_MD_LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def _course_file(folder, target):
    """The file a relative link from a notebook in ``folder`` (exercises, solutions or the
    student's workspace) opens; workspace/ holds copies of exercises/ and the workspace README."""
    parts = (ROOT / folder / target).resolve().relative_to(ROOT).parts
    if parts[:1] == ("workspace",):
        name = "/".join(parts[1:])
        return ROOT / "tools" / "workspace_README.md" if name == "README.md" else ROOT / "exercises" / name
    return ROOT.joinpath(*parts)


@pytest.mark.parametrize("path", EXERCISES + SOLUTIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_links_open_something_the_student_has(path):
    """Every relative link in the notebook's markdown opens a file from where the notebook is
    read: solutions/, exercises/ or the student's copy in workspace/."""
    nb = nbformat.read(path, as_version=4)
    links = [t for c in nb.cells if c.cell_type == "markdown" for t in _MD_LINK.findall(c.source)
             if "://" not in t and not t.startswith("#")]
    assert any("../workspace/" in t for t in links), f"{path.name} links to nothing of the student's"
    folders = ("solutions",) if path.parent.name == "solutions" else ("exercises", "workspace")
    for t in links:
        for folder in folders:
            assert _course_file(folder, t.split("#")[0]).is_file(), (path.name, folder, t)


def test_generation_is_deterministic(tmp_path):
    out = tmp_path / "ex"
    assert mk.main(["--exercises", str(out)]) == 0
    first = {p.name: p.read_text() for p in out.glob("*.ipynb")}
    assert mk.main(["--exercises", str(out), "--check"]) == 0
    assert mk.main(["--exercises", str(out)]) == 0
    assert {p.name: p.read_text() for p in out.glob("*.ipynb")} == first


def make_solution(tmp_path, cells):
    nb = nbformat.v4.new_notebook()
    nb.cells = cells
    for i, c in enumerate(nb.cells):
        c["id"] = f"c{i}"
    d = tmp_path / "solutions"
    d.mkdir(exist_ok=True)
    nbformat.write(nb, d / "ex9_9.ipynb")
    return d


def generated(tmp_path, cells):
    src = make_solution(tmp_path, cells)
    assert mk.main(["--solutions", str(src), "--exercises", str(tmp_path / "exercises")]) == 0
    return nbformat.read(tmp_path / "exercises" / "ex9_9.ipynb", as_version=4)


def test_marker_rules(tmp_path):
    v4 = nbformat.v4
    nb = generated(tmp_path, [
        v4.new_code_cell("x = 1\n### BEGIN SOLUTION\n#> answer = None  # your answer here\n"
                         "answer = 42\n### END SOLUTION\nprint(answer)"),
        v4.new_code_cell("def f():\n    ### BEGIN SOLUTION\n    return 3\n    ### END SOLUTION"),
        v4.new_markdown_cell("Intro\n<!-- ### BEGIN SOLUTION -->\nThe secret.\n<!-- ### END SOLUTION -->"),
        v4.new_markdown_cell("### BEGIN SOLUTION\nBare secret\n### END SOLUTION\nafter"),
        v4.new_code_cell("assert True", metadata={"tags": ["solution_only"]}),
    ])
    src = [c.source for c in nb.cells]
    assert src[0] == "x = 1\nanswer = None  # your answer here\nprint(answer)"
    assert src[1] == "def f():\n    # your code here"
    assert src[2] == "Intro\n*Your answer here.*"
    assert src[3] == "*Your answer here.*\nafter"
    assert len(src) == 4  # the solution_only cell is gone
    assert [c["id"] for c in nb.cells] == ["c0", "c1", "c2", "c3"]


@pytest.mark.parametrize("source", ["### BEGIN SOLUTION\nx = 1",
                                    "x = 1\n### END SOLUTION",
                                    "### BEGIN SOLUTION\n### BEGIN SOLUTION\n### END SOLUTION"])
def test_unbalanced_markers_are_an_error(tmp_path, source, capsys):
    src = make_solution(tmp_path, [nbformat.v4.new_code_cell(source)])
    assert mk.main(["--solutions", str(src), "--exercises", str(tmp_path / "ex")]) == 2
    assert "ex9_9.ipynb cell 0" in capsys.readouterr().err


def test_check_mode_detects_stale_and_missing(tmp_path):
    src = make_solution(tmp_path, [nbformat.v4.new_code_cell("x = 1")])
    out = tmp_path / "exercises"
    args = ["--solutions", str(src), "--exercises", str(out)]
    assert mk.main(args + ["--check"]) == 1          # not generated yet
    assert mk.main(args) == 0 and mk.main(args + ["--check"]) == 0
    (out / "ex9_9.ipynb").write_text("{}")
    assert mk.main(args + ["--check"]) == 1          # edited by hand
    (out / "ex8_8.ipynb").write_text("{}")
    assert mk.main(args) == 0 and not (out / "ex8_8.ipynb").exists()  # stale file removed


def test_script_runs_from_the_command_line():
    res = subprocess.run([sys.executable, str(SCRIPT), "--check"], capture_output=True, text=True)
    assert res.returncode == 0, res.stdout + res.stderr


@pytest.mark.parametrize("path", nbrun.params(EXERCISES, id_of=lambda p: p.name))
def test_untouched_exercise_runs_and_is_unattempted(path, notebook_record):
    """From the record of the one execution of the exercise notebook in this run (tests/nbrun.py):
    every cell ran without raising, and progress() at the end calls every exercise unattempted."""
    rec = notebook_record(path)
    assert not rec["errors"], "the untouched exercise raised:\n  " + "\n  ".join(rec["errors"])
    assert rec["complete"], f"{path.name}: its execution did not reach the end"
    status = rec["progress"]
    assert status is not None, f"{path.name} never imported gm_core.checks"
    assert status[ex_id(path)] == "unattempted", status
    assert set(status.values()) == {"unattempted"}


@pytest.mark.parametrize("path", EXERCISES + SOLUTIONS, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_everything_the_notebook_advertises_is_imported(path):
    nb = nbformat.read(path, as_version=4)
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    prose = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    imported = set()
    for line in code.splitlines():
        m = re.match(r"\s*from gm_core\.checks import (.*)", line)
        if m:
            imported |= {n.strip() for n in m.group(1).split(",")}
    for name in ("progress", "progress_widget", "set_time_limit", "reset_progress"):
        if re.search(rf"`{name}\(", prose):
            assert name in imported, f"{path.name} mentions {name}() but does not import it"


def test_solution_links_resolve_from_the_workspace_and_exercises():
    from gm_core.checks.exercise import REGISTRY, exercise_ids
    for ex_id in exercise_ids():
        part = next(iter(REGISTRY[ex_id].parts.values()))
        for folder in ("workspace", "exercises"):
            assert (ROOT / folder / part.solution_path()).resolve().exists(), (ex_id, folder)


def test_exercise_notebooks_point_to_the_workspace_readme():
    for path in EXERCISES:
        text = path.read_text(encoding="utf-8")
        assert "exercises/README.md" not in text, path.name

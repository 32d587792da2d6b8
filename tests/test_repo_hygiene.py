"""Notebooks are committed without outputs, and no solution leaks into exercises/."""
import ast
import json
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def tracked_notebooks():
    try:
        out = subprocess.run(["git", "ls-files", "*.ipynb"], cwd=ROOT, capture_output=True, text=True,
                             check=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        out = []
    if not out:  # not a git checkout (e.g. an sdist): check every notebook in the course folders
        out = [str(p.relative_to(ROOT)) for d in ("book", "exercises", "solutions")
               for p in (ROOT / d).glob("*.ipynb")]
    return out


NOTEBOOKS = tracked_notebooks()


def test_there_are_notebooks():
    assert any(p.startswith("book/") for p in NOTEBOOKS)


@pytest.mark.parametrize("path", NOTEBOOKS)
def test_notebook_has_no_outputs(path):
    nb = json.loads((ROOT / path).read_text())
    dirty = [i for i, c in enumerate(nb["cells"]) if c["cell_type"] == "code"
             and (c.get("outputs") or c.get("execution_count") is not None)]
    assert not dirty, f"{path}: cells {dirty} have outputs; run tools/strip_outputs.py {path}"


@pytest.mark.parametrize("path", [p for p in NOTEBOOKS if p.startswith("exercises/")])
def test_no_solution_markers_in_exercises(path):
    text = (ROOT / path).read_text()
    assert "BEGIN SOLUTION" not in text and "END SOLUTION" not in text, (
        f"{path} contains a solution marker; regenerate with `make exercises`")


BOOK = [p for p in NOTEBOOKS if p.startswith("book/")]
LINK = re.compile(r"\]\((?!https?:|#|mailto:)([^)#\s]+\.(?:ipynb|md))(?:#[^)]*)?\)")


@pytest.mark.parametrize("path", BOOK)
def test_book_links_resolve(path):
    """Relative links in the book point at files that exist; exercise links go to the student's
    workspace/ copy (made from exercises/ by `make lab`), never to the tracked originals."""
    nb = json.loads((ROOT / path).read_text())
    text = "".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
    for target in LINK.findall(text):
        resolved = (ROOT / path).parent / target
        assert "exercises/" not in target, f"{path}: link {target} should point into ../workspace/"
        if "workspace/" in target:
            resolved = ROOT / "exercises" / resolved.name
        assert resolved.exists(), f"{path}: broken link {target}"


def test_ruff_is_clean():
    """`ruff check` passes with the project's configuration (pyproject.toml [tool.ruff])."""
    import shutil
    import sys

    ruff = shutil.which("ruff") or str(Path(sys.executable).parent / "ruff")
    if not Path(ruff).exists():
        pytest.skip("ruff is not installed (it is in the test extra: pip install -e '.[test]')")
    out = subprocess.run([ruff, "check", "--no-cache", "--quiet", "."], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, "ruff check found problems:\n" + out.stdout[-4000:] + out.stderr[-2000:]


# ------------------------------------------------------------------ type hints on the interfaces
def _mypy(*args, cwd=ROOT):
    import sys

    try:
        import mypy  # noqa: F401
    except ImportError:
        pytest.skip("mypy is not installed (it is in the test extra: pip install -e '.[test]')")
    return subprocess.run([sys.executable, "-m", "mypy", *args], cwd=cwd, capture_output=True, text=True)


def _typed_files():
    try:
        import tomllib
    except ModuleNotFoundError:    # Python 3.10
        import tomli as tomllib

    files = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["mypy"]["files"]
    out = []
    for f in files:
        p = ROOT / f
        out += sorted(p.rglob("*.py")) if p.is_dir() else [p]
    return out


#: The interfaces that must be fully annotated: (file, classes or None for the whole module).
INTERFACES = {
    "gm_core/validation.py": None, "gm_core/groups/base.py": None, "gm_core/groups/se2.py": None,
    "gm_core/groups/additive.py": None, "gm_core/groups/rplus.py": None,
    "gm_core/systems/base.py": None, "gm_core/drawing/toolkit/style.py": ("Scene",),
    "gm_core/widgets/base.py": None, "gm_core/checks/parts.py": ("Verdict", "Part", "FunctionPart",
                                                                "TuplePart", "CustomPart"),
    "gm_core/checks/exercise.py": ("Exercise",), "gm_core/checks/choice.py": ("ChoicePart",),
}


def _unannotated(path, classes):
    import ast

    tree = ast.parse(path.read_text(encoding="utf-8"))
    scopes = [n for n in tree.body if isinstance(n, ast.ClassDef) and (classes is None or n.name in classes)]
    funcs = [(f"{c.name}.", f) for c in scopes for f in c.body if isinstance(f, ast.FunctionDef)]
    if classes is None:
        funcs += [("", f) for f in tree.body if isinstance(f, ast.FunctionDef)]
    bad = []
    for prefix, f in funcs:
        if f.name.startswith("_") and f.name not in ("__init__", "__getattr__"):
            continue
        params = [a for a in f.args.posonlyargs + f.args.args + f.args.kwonlyargs if a.arg not in ("self", "cls")]
        params += [a for a in (f.args.vararg, f.args.kwarg) if a is not None]
        if f.returns is None or any(a.annotation is None for a in params):
            bad.append(f"{path.relative_to(ROOT)}: {prefix}{f.name}")
    return bad


def test_the_interfaces_are_annotated():
    assert {str(p.relative_to(ROOT)) for p in _typed_files()} >= set(INTERFACES)
    bad = [b for f, classes in INTERFACES.items() for b in _unannotated(ROOT / f, classes)]
    assert not bad, "public functions without type hints on an interface:\n" + "\n".join(bad)


def test_mypy_passes_on_the_typed_interfaces():
    out = _mypy()
    assert out.returncode == 0, "mypy found problems:\n" + out.stdout[-4000:] + out.stderr[-2000:]


def _public_functions(tree):
    """``(name, node)`` of the public functions of a module and the public methods of its public
    classes (names without a leading underscore)."""
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and not node.name.startswith("_"):
            yield node.name, node
        elif isinstance(node, ast.ClassDef) and not node.name.startswith("_"):
            for f in node.body:
                if isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef)) and not f.name.startswith("_"):
                    yield f"{node.name}.{f.name}", f


def _fully_annotated(f):
    a = f.args
    params = a.posonlyargs + a.args + a.kwonlyargs
    if params and params[0].arg in ("self", "cls"):
        params = params[1:]
    params += [p for p in (a.vararg, a.kwarg) if p is not None]
    return f.returns is not None and all(p.annotation is not None for p in params)


def annotation_shares(skip=()):
    """{folder: (annotated, public)} for gm_core's subpackages, gm_core's loose modules ("gm_core")
    and gm_grader; files named in ``skip`` (paths from the root) are left out."""
    out = {}
    for pkg in ("gm_core", "gm_grader"):
        for p in sorted((ROOT / pkg).rglob("*.py")):
            rel = p.relative_to(ROOT)
            if rel.as_posix() in skip:
                continue
            folder = rel.parts[0] if len(rel.parts) == 2 else "/".join(rel.parts[:2])
            done, total = out.get(folder, (0, 0))
            for _, f in _public_functions(ast.parse(p.read_text(encoding="utf-8"))):
                done, total = done + _fully_annotated(f), total + 1
            out[folder] = (done, total)
    return out


#: The share of fully annotated public functions every folder of gm_core and gm_grader keeps.
ANNOTATION_TARGET = 0.90


def test_public_functions_are_annotated_in_every_folder():
    shares = annotation_shares()
    done = sum(d for d, _ in shares.values())
    total = sum(t for _, t in shares.values())
    print(f"\nfully annotated public functions and methods: {done}/{total} ({done / total:.0%})")
    for folder, (d, t) in sorted(shares.items()):
        print(f"  {folder:24s} {d:4d}/{t:<4d} ({d / max(t, 1):.0%})")
    assert {"gm_core", "gm_core/groups", "gm_core/systems", "gm_core/drawing", "gm_core/widgets",
            "gm_core/checks", "gm_grader"} <= set(shares), sorted(shares)
    low = {f: f"{d}/{t}" for f, (d, t) in shares.items() if t and d / t < ANNOTATION_TARGET}
    assert not low, (f"public functions without full annotations (parameters and return), below "
                     f"{ANNOTATION_TARGET:.0%}: {low}")


def test_the_annotation_count_is_not_blind():
    tree = ast.parse("def f(x: int) -> int: ...\ndef g(x): ...\ndef _h(x): ...\n"
                     "class C:\n    def m(self, *a: int) -> None: ...\n    def n(self, y) -> None: ...\n")
    got = {name: _fully_annotated(f) for name, f in _public_functions(tree)}
    assert got == {"f": True, "g": False, "C.m": True, "C.n": False}


def test_mypy_catches_a_misused_interface(tmp_path):
    """The check can fail: wrong argument types against the annotated interfaces are reported."""
    bad = tmp_path / "misuse.py"
    bad.write_text("from gm_core import SE2\nfrom gm_core.checks.exercise import Exercise\n"
                   "n: int = SE2.exp([0.0, 0.0, 1.0])\nExercise(1.5, 'title', parts=3)\n")
    out = _mypy("--config-file", str(ROOT / "pyproject.toml"), str(bad), cwd=ROOT)
    assert out.returncode == 1 and "misuse.py:3" in out.stdout and "misuse.py:4" in out.stdout, out.stdout


# ------------------------------------------------------------------ the map in CONTRIBUTING.md
def _map_modules(text):
    """The modules the map's code block lists: ``folder/`` lines, then ``  module.py`` lines."""
    block = text.split("## The map", 1)[1].split("```", 2)[1]
    listed, folder = set(), None
    for line in block.splitlines():
        if m := re.match(r"(\S+/)(\s|$)", line):
            folder = m.group(1)
        elif (m := re.match(r"  (\S+\.py)(\s|$)", line)) and folder:
            listed.add(folder + m.group(1))
    return listed


def test_the_map_in_contributing_matches_the_folders():
    actual = {p.relative_to(ROOT).as_posix() for pkg in ("gm_core", "gm_grader")
              for p in (ROOT / pkg).rglob("*.py") if p.name != "__init__.py"}
    listed = _map_modules((ROOT / "CONTRIBUTING.md").read_text(encoding="utf-8"))
    assert not actual - listed, f"modules missing from CONTRIBUTING.md's map: {sorted(actual - listed)}"
    assert not listed - actual, f"CONTRIBUTING.md's map lists modules that do not exist: {sorted(listed - actual)}"


def test_the_map_check_can_fail():
    text = "## The map\n\n```\ngm_core/groups/   x\n  se2.py   SE(2)\n  nothere.py  y\n```\n"
    assert _map_modules(text) == {"gm_core/groups/se2.py", "gm_core/groups/nothere.py"}


def test_the_readme_is_short_and_for_its_readers():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert len(readme) <= 12_000, f"README.md has {len(readme)} characters (at most 12,000)"
    for words in ("make lab", "make test", "gm-grade", "make site", "make gradescope", "make kits"):
        assert words in readme, f"README.md does not say {words!r}"
    dated = re.findall(r"\b20\d\d-\d\d-\d\d\b", readme + (ROOT / "CONTRIBUTING.md").read_text(encoding="utf-8"))
    assert not dated, f"dated log entries in README/CONTRIBUTING: {dated}"

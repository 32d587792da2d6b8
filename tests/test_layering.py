"""The house's one-way flow, read from the source with ``ast`` (nothing is imported).

* math (every module of gm_core except drawing/, widgets/ and checks/) never imports matplotlib,
  ipywidgets, gm_core.drawing or gm_core.widgets -- not even inside a function;
* drawing never imports gm_core.widgets or ipywidgets;
* gm_core has no import cycle (module-level and function-level imports, relative imports,
  ``from package import submodule`` and ``importlib.import_module("constant")`` all count);
* every public name has one home: a module's ``__all__`` lists only what it defines, no
  compatibility modules (``drawing/ch1.py``...) exist, and every ``from gm_core... import name``
  in the package, the tests, benchmarks, tools and notebooks names the module that defines it
  (or a package that lists it in ``__all__``).
"""
import ast
import functools
import json
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = "gm_core"

MATH_FORBIDDEN = ("matplotlib", "ipywidgets", "ipympl", "gm_core.drawing", "gm_core.widgets")
DRAWING_FORBIDDEN = ("ipywidgets", "gm_core.widgets")
NOT_MATH = ("gm_core.drawing", "gm_core.widgets", "gm_core.checks")


def module_name(path):
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def discover():
    """``{module name: (path, is_package)}`` for every .py file of gm_core."""
    return {module_name(p): (p, p.name == "__init__.py") for p in sorted((ROOT / PACKAGE).rglob("*.py"))}


MODULES = discover()


def _resolve_relative(importer, is_package, level, module):
    base = importer.split(".") if is_package else importer.split(".")[:-1]
    if level > 1:
        base = base[: len(base) - (level - 1)]
    return ".".join(base + ([module] if module else []))


def _type_checking_only(tree):
    """The nodes inside ``if TYPE_CHECKING:`` blocks: imports for the type checker, never run."""
    skip = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            skip |= {id(n) for stmt in node.body for n in ast.walk(stmt)}
    return skip


@functools.cache
def _tree(name):
    """Module ``name``'s syntax tree, parsed once, when a test first asks (not at collection, on
    every worker); the tests only read it."""
    path = MODULES[name][0]
    return ast.parse(path.read_text(encoding="utf-8"), filename=str(path))


@functools.cache
def imports_of(name):
    """Every ``(imported module, line)`` that module ``name`` runs, at any depth of the syntax tree
    (imports under ``if TYPE_CHECKING:`` are only read by the type checker and do not count).
    Computed once per module (the callers only read the list)."""
    is_package = MODULES[name][1]
    tree = _tree(name)
    skip = _type_checking_only(tree)
    found = []
    for node in ast.walk(tree):
        if id(node) in skip:
            continue
        if isinstance(node, ast.Import):
            found += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            target = (_resolve_relative(name, is_package, node.level, node.module) if node.level
                      else node.module)
            found.append((target, node.lineno))
            # ``from pkg import sub`` imports the submodule pkg.sub when there is one
            found += [(f"{target}.{a.name}", node.lineno) for a in node.names
                      if f"{target}.{a.name}" in MODULES]
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr == "import_module" and node.args
              and isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
            target = node.args[0].value
            if target.startswith("."):
                level = len(target) - len(target.lstrip("."))
                target = _resolve_relative(name, is_package, level, target.lstrip(".") or None)
            found.append((target, node.lineno))
    return found


def _within(module, prefixes):
    return any(module == p or module.startswith(p + ".") for p in prefixes)


def graph():
    """Import edges between gm_core modules (an import of a package's own ancestor is not an edge:
    Python has already started that package before any of its submodules runs)."""
    edges = {}
    for name in MODULES:
        targets = set()
        for target, _ in imports_of(name):
            if target in MODULES and target != name and not name.startswith(target + "."):
                targets.add(target)
        edges[name] = targets
    return edges


def strongly_connected(edges):
    """Tarjan's algorithm: the strongly connected components with more than one module."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.add(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(frozenset(comp))

    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def a_cycle(edges, comp):
    """One explicit cycle through the component, for the failure message."""
    start = min(comp)
    path, seen = [start], {start}
    while True:
        nxt = sorted(w for w in edges[path[-1]] if w in comp)
        back = [w for w in nxt if w == start]
        if back and len(path) > 1:
            return path + [start]
        fresh = [w for w in nxt if w not in seen]
        if not fresh:
            i = path.index(nxt[0])
            return path[i:] + [nxt[0]]
        path.append(fresh[0])
        seen.add(fresh[0])


# ------------------------------------------------------------------ the tests
@pytest.fixture(scope="module", autouse=True)
def _forget_the_trees():
    """The syntax trees are dropped once this file's tests are done: kept, their ~0.3 million
    objects made every later garbage collection of the worker longer."""
    yield
    _tree.cache_clear()


def test_every_module_is_found_and_parsed():
    assert "gm_core.groups" in MODULES and "gm_core.drawing" in MODULES
    assert all(isinstance(imports_of(m), list) for m in MODULES)


def test_the_analysis_sees_function_level_and_relative_imports():
    src = "def f():\n    from ..drawing import base\n    import matplotlib.pyplot as plt\n"
    tree = ast.parse(src)
    kinds = [type(n).__name__ for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom))]
    assert kinds == ["ImportFrom", "Import"]
    assert _resolve_relative("gm_core.systems.base", False, 2, "drawing") == "gm_core.drawing"
    assert _resolve_relative("gm_core.systems", True, 1, "base") == "gm_core.systems.base"
    assert strongly_connected({"a": {"b"}, "b": {"a"}, "c": {"a"}}) == [frozenset({"a", "b"})]
    assert a_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}, {"a", "b", "c"}) == ["a", "b", "c", "a"]
    typed = ast.parse("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from . import a\nfrom . import b\n")
    skip = _type_checking_only(typed)
    assert [n.names[0].name for n in ast.walk(typed) if isinstance(n, ast.ImportFrom) and id(n) not in skip] == \
        ["TYPE_CHECKING", "b"]


MATH_MODULES = [m for m in MODULES if not _within(m, NOT_MATH)]
DRAWING_MODULES = [m for m in MODULES if _within(m, ("gm_core.drawing",))]


@pytest.mark.parametrize("name", MATH_MODULES)
def test_math_never_imports_drawing_or_widgets(name):
    bad = [f"line {line}: {t}" for t, line in imports_of(name) if _within(t, MATH_FORBIDDEN)]
    assert not bad, f"{name} is a math module but imports " + "; ".join(bad)


@pytest.mark.parametrize("name", DRAWING_MODULES)
def test_drawing_never_imports_widgets(name):
    bad = [f"line {line}: {t}" for t, line in imports_of(name) if _within(t, DRAWING_FORBIDDEN)]
    assert not bad, f"{name} is a drawing module but imports " + "; ".join(bad)


def test_no_import_cycles():
    edges = graph()
    cycles = strongly_connected(edges)
    assert not cycles, "import cycles in gm_core: " + "; ".join(
        " -> ".join(a_cycle(edges, c)) for c in cycles)


def test_the_cycle_finder_sees_a_real_cycle_in_gm_core_shaped_input():
    """The cycle test can fail: an edge back from groups.base to drawing.toolkit closes a cycle."""
    edges = {k: set(v) for k, v in graph().items()}
    assert "gm_core.groups.base" in edges["gm_core.drawing.toolkit.primitives"] | {
        t for m in edges["gm_core.drawing.toolkit.primitives"] for t in edges.get(m, ())}
    edges["gm_core.groups.base"].add("gm_core.drawing.toolkit.primitives")
    assert any("gm_core.groups.base" in c for c in strongly_connected(edges))


# ------------------------------------------------------------------ one home for every public name
#: Modules whose ``__all__`` still lists names they import, with the reason (empty this list).
REEXPORTS_KEPT = {
}


def _defined(tree):
    names = set()
    for n in tree.body:
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(n.name)
        elif isinstance(n, ast.Assign):
            for t in n.targets:
                names |= {e.id for e in ast.walk(t) if isinstance(e, ast.Name)}
        elif isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name):
            names.add(n.target.id)
    return names


def _all_of(tree):
    for n in tree.body:
        if isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in n.targets):
            try:
                return list(ast.literal_eval(n.value))
            except ValueError:      # computed (gm_core.checks): a package, checked at import
                return None
    return None


@functools.cache
def _defined_in(name):
    return _defined(_tree(name))


@pytest.mark.parametrize("name", [m for m, (_, pkg) in MODULES.items() if not pkg and m not in REEXPORTS_KEPT])
def test_a_module_exports_only_what_it_defines(name):
    exported = _all_of(_tree(name)) or []
    foreign = [n for n in exported if n not in _defined_in(name)]
    assert not foreign, f"{name}.__all__ re-exports {foreign}: import them from their home instead"


def test_no_compatibility_modules():
    """The chapter shims are gone: drawings and panels live in topic modules only."""
    shims = [m for m in MODULES if _within(m, ("gm_core.drawing", "gm_core.widgets"))
             and re.fullmatch(r"ch\d+", m.rsplit(".", 1)[1])]
    gone = [m for m in ("gm_core.kinematics", "gm_core.frames", "gm_core.drawing.frames", "gm_core.drawing.base")
            if m in MODULES]
    assert not shims and not gone, f"compatibility or renamed modules still present: {shims + gone}"


def _package_all(pkg):
    """A package's public names: its literal ``__all__``, or (computed, gm_core.checks) its import."""
    names = _all_of(_tree(pkg))
    if names is None:
        import importlib

        names = list(importlib.import_module(pkg).__all__)
    return set(names)


def wrong_homes(source, importer=None, is_package=False):
    """``(line, module, name)`` for every ``from gm_core... import name`` whose module is not the
    name's home (it neither defines it nor, being a package, lists it in ``__all__``)."""
    tree = ast.parse(re.sub(r"^(\s*)(?:%|!(?!=)).*$", r"\1pass", source, flags=re.M))
    bad = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.ImportFrom):
            continue
        mod = (_resolve_relative(importer, is_package, node.level, node.module) if node.level
               else node.module)
        if mod not in MODULES:
            continue
        for a in node.names:
            if f"{mod}.{a.name}" in MODULES or a.name == "*":
                continue            # a submodule
            home = a.name in _defined_in(mod) or (MODULES[mod][1] and a.name in _package_all(mod))
            if not home and mod not in REEXPORTS_KEPT:
                bad.append((node.lineno, mod, a.name))
    return bad


def test_wrong_homes_is_not_blind():
    assert wrong_homes("from gm_core.systems.motion import circle_gait\n") == [(1, "gm_core.systems.motion", "circle_gait")]
    assert wrong_homes("from gm_core.systems.gaits import circle_gait\nfrom gm_core import SE2\n") == []
    assert wrong_homes("from gm_core.drawing.toolkit.style import plane\n") == [(1, "gm_core.drawing.toolkit.style", "plane")]


def _sources():
    for name, (path, pkg) in MODULES.items():
        yield str(path.relative_to(ROOT)), path.read_text(encoding="utf-8"), name, pkg
    for folder in ("tests", "benchmarks", "tools"):
        for path in sorted((ROOT / folder).rglob("*.py")):
            yield str(path.relative_to(ROOT)), path.read_text(encoding="utf-8"), None, False
    for folder in ("book", "exercises", "solutions"):
        for path in sorted((ROOT / folder).glob("*.ipynb")):
            cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
            for i, c in enumerate(cells):
                if c["cell_type"] == "code":
                    yield f"{path.relative_to(ROOT)} cell {i}", "".join(c["source"]), None, False


def test_every_import_names_the_home_of_the_name():
    """Notebooks import maths from the math layer, drawings from their topic module, and so on:
    nothing reaches a name through a module that merely re-imports it."""
    bad = [f"{where} line {line}: {name} from {mod}" for where, src, imp, pkg in _sources()
           for line, mod, name in wrong_homes(src, imp, pkg)]
    assert not bad, "imports through a module that is not the name's home:\n" + "\n".join(bad)


# ------------------------------------------------------------------ the folders show the layers
GRADER = ROOT / "gm_grader"
#: Pages that are not a topic of the book (their drawing and panel need no math module).
PAGE_TOPICS = {"start"}


def _leaf_names(prefix):
    return {m.rsplit(".", 1)[1] for m in MODULES if m.startswith(prefix + ".")
            and m.count(".") == prefix.count(".") + 1}


MATH_NAMES = {m.rsplit(".", 1)[1] for m in MATH_MODULES if m != PACKAGE}


def test_at_most_three_loose_modules_in_gm_core():
    loose = sorted(p.stem for p in (ROOT / PACKAGE).glob("*.py") if p.name != "__init__.py")
    assert len(loose) <= 3, f"gm_core/ holds loose modules {loose}: put them in a topic subpackage"


@pytest.mark.parametrize("topic", sorted(_leaf_names("gm_core.drawing") - {"toolkit"}))
def test_a_drawing_topic_is_named_after_its_math(topic):
    assert topic in MATH_NAMES | PAGE_TOPICS, (
        f"gm_core/drawing/{topic}.py draws no math module named {topic!r}: name it after the module it draws")


@pytest.mark.parametrize("topic", sorted(_leaf_names("gm_core.widgets") - {"base"}))
def test_a_widget_topic_is_named_after_its_drawing(topic):
    assert topic in _leaf_names("gm_core.drawing"), f"gm_core/widgets/{topic}.py has no gm_core/drawing/{topic}.py"
    assert any(t == f"gm_core.drawing.{topic}" for t, _ in imports_of(f"gm_core.widgets.{topic}")), (
        f"gm_core.widgets.{topic} does not draw with gm_core.drawing.{topic}")


def test_the_topic_rules_can_fail():
    assert "nonholonomy" not in MATH_NAMES and "rolling_disk" in MATH_NAMES and "tangent" in MATH_NAMES


def test_gm_core_never_imports_the_grader():
    bad = [f"{m} line {line}" for m in MODULES for t, line in imports_of(m) if _within(t, ("gm_grader",))]
    assert (GRADER / "batch.py").exists() and not bad, f"gm_core imports gm_grader: {bad}"


def test_systems_never_import_the_geometry_layer():
    bad = [f"{m} line {line}: {t}" for m in MODULES if _within(m, ("gm_core.systems",))
           for t, line in imports_of(m) if _within(t, ("gm_core.geometry",))]
    assert not bad, "the systems import the analysis built on them: " + "; ".join(bad)


def test_no_course_file_imports_an_old_module_path():
    """Old paths live in gm_core.renamed for students' old workspaces only."""
    from gm_core.renamed import MOVED_MODULES

    old = re.compile(r"\b(" + "|".join(re.escape(m) for m in MOVED_MODULES) + r")\b(?!\.\w+\.)")
    bad = [where for where, src, _, _ in _sources() if old.search(src)
           and where not in ("gm_core/renamed.py", "tests/test_old_workspaces.py", "tests/test_layering.py")]
    assert not bad, f"imports of old module paths: {bad}"


def _private_imports(source):
    """``(line, module, name)`` for every ``from gm_core... import _name`` / ``from gm_grader... import _name``."""
    tree = ast.parse(re.sub(r"^(\s*)(?:%|!(?!=)).*$", r"\1pass", source, flags=re.M))
    return [(n.lineno, n.module, a.name) for n in ast.walk(tree) if isinstance(n, ast.ImportFrom) and n.module
            and n.module.split(".")[0] in ("gm_core", "gm_grader") for a in n.names if a.name.startswith("_")]


def test_no_private_name_is_imported_across_modules():
    """One copy of every formula is kept through public names: a helper another module needs is
    public in its home (tests may reach private helpers of the module they test)."""
    sources = [(str(p.relative_to(ROOT)), p.read_text(encoding="utf-8"))
               for pkg in ("gm_core", "gm_grader") for p in sorted((ROOT / pkg).rglob("*.py"))]
    bad = [f"{where} line {line}: {name} from {mod}" for where, src in sources for line, mod, name in _private_imports(src)]
    assert not bad, "private names imported across modules:\n" + "\n".join(bad)


def test_the_private_import_check_can_fail():
    assert _private_imports("from gm_core.chains.kernels import _x, y\n") == [(1, "gm_core.chains.kernels", "_x")]

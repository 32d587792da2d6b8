"""The house's one-way flow, read from the source with ``ast`` (nothing is imported).

* math (every module of gm_core except drawing/, widgets/ and checks/) never imports matplotlib,
  ipywidgets, gm_core.drawing or gm_core.widgets -- not even inside a function;
* drawing never imports gm_core.widgets or ipywidgets;
* gm_core has no import cycle (module-level and function-level imports, relative imports,
  ``from package import submodule`` and ``importlib.import_module("constant")`` all count).
"""
import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = "gm_core"

#: Cycles that exist today in modules owned by other engineers, each named by the import that
#: closes it (importer, imported); the cycle test ignores these edges. The lead empties this list
#: once the branches that remove them are merged.
KNOWN_CYCLES_TO_REMOVE: list = []

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


def imports_of(name):
    """Every ``(imported module, line)`` in module ``name``, at any depth of the syntax tree."""
    path, is_package = MODULES[name]
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    found = []
    for node in ast.walk(tree):
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
    for a, b in KNOWN_CYCLES_TO_REMOVE:
        edges[a].discard(b)
    cycles = strongly_connected(edges)
    assert not cycles, "import cycles in gm_core: " + "; ".join(
        " -> ".join(a_cycle(edges, c)) for c in cycles)


def test_known_cycles_still_exist():
    """Fails once a listed cycle is gone, so that KNOWN_CYCLES_TO_REMOVE gets emptied."""
    edges = graph()
    cyclic = strongly_connected(edges)
    gone = [(a, b) for a, b in KNOWN_CYCLES_TO_REMOVE
            if b not in edges[a] or not any(a in c and b in c for c in cyclic)]
    assert not gone, f"remove these from KNOWN_CYCLES_TO_REMOVE, the cycles are gone: {gone}"

"""Rewrite ``from gm_core... import name`` lines so that each names the module that defines the name.

After a name moves to another module (a topic split, a new home), run::

    python tools/rewrite_imports.py            # rewrite .py files and notebooks in place
    python tools/rewrite_imports.py --check    # list the imports that need it; exit 1 if any

It reads gm_core with ``ast`` (nothing is imported), finds every name's home (the one module that
defines it at top level), and splits an import line whose module does not define a name (nor, for
a package, lists it in ``__all__``) into imports from the homes. Notebooks are rewritten cell by
cell; outputs and metadata are left untouched. ``tests/test_layering.py`` fails on any import that
this script would change.
"""
from __future__ import annotations

import argparse
import ast
import json
import re
import sys
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("gm_core", "gm_grader")
FOLDERS = ("gm_core", "gm_grader", "tests", "tools", "benchmarks", "book", "exercises", "solutions")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _defined(tree: ast.Module) -> set[str]:
    names: set[str] = set()
    for n in tree.body:
        if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            names.add(n.name)
        elif isinstance(n, ast.Assign):
            for t in n.targets:
                names |= {e.id for e in ast.walk(t) if isinstance(e, ast.Name)}
        elif isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name):
            names.add(n.target.id)
    return names


def _all(tree: ast.Module, name: str) -> set[str]:
    for n in tree.body:
        if isinstance(n, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "__all__" for t in n.targets):
            try:
                return set(ast.literal_eval(n.value))
            except ValueError:      # computed (gm_core.checks lists its exercises): ask the package
                import importlib

                return set(importlib.import_module(name).__all__)
    return set()


def index() -> tuple[dict[str, set[str]], dict[str, set[str]], dict[str, list[str]]]:
    """(names each module defines, names each package exports, homes of every name)."""
    defined: dict[str, set[str]] = {}
    exported: dict[str, set[str]] = {}
    homes: dict[str, list[str]] = defaultdict(list)
    for pkg in PACKAGES:
        for path in sorted((ROOT / pkg).rglob("*.py")):
            tree = ast.parse(path.read_text(encoding="utf-8"))
            name = _module_name(path)
            defined[name] = _defined(tree)
            if path.name == "__init__.py":
                exported[name] = _all(tree, name)
            else:
                for n in defined[name]:
                    homes[n].append(name)
    return defined, exported, homes


def _fix_source(src: str, defined, exported, homes) -> tuple[str, list[str]]:
    try:
        tree = ast.parse(re.sub(r"^(\s*)(?:%|!(?!=)).*$", r"\1pass", src, flags=re.M))
    except SyntaxError:
        return src, []
    lines = src.splitlines(keepends=True)
    notes, edits = [], []
    for node in ast.walk(tree):
        if not (isinstance(node, ast.ImportFrom) and node.level == 0 and node.module in defined):
            continue
        mod = node.module
        keep, moved = [], defaultdict(list)
        for a in node.names:
            ok = (a.name in defined[mod] or a.name in exported.get(mod, set())
                  or f"{mod}.{a.name}" in defined or a.name == "*")
            text = a.name + (f" as {a.asname}" if a.asname else "")
            if ok:
                keep.append(text)
                continue
            home = [h for h in homes.get(a.name, []) if not a.name.startswith("_") or h.rsplit(".", 1)[0] == mod.rsplit(".", 1)[0]]
            if len(home) != 1:
                notes.append(f"line {node.lineno}: {a.name} from {mod}: no single home ({home})")
                keep.append(text)
                continue
            moved[home[0]].append(text)
        if not moved:
            continue
        indent = re.match(r"\s*", lines[node.lineno - 1]).group(0)
        stmts = ([f"{indent}from {mod} import {', '.join(keep)}"] if keep else [])
        stmts += [f"{indent}from {h} import {', '.join(sorted(ns))}" for h, ns in sorted(moved.items())]
        tail = lines[node.end_lineno - 1]
        comment = tail[tail.index("#"):].rstrip("\n") if "#" in tail and ")" not in tail[tail.index("#"):] else ""
        new = "\n".join(s + (f"  {comment}" if comment and i == 0 else "") for i, s in enumerate(stmts)) + "\n"
        edits.append((node.lineno - 1, node.end_lineno, new))
        notes.append(f"line {node.lineno}: {mod} -> " + ", ".join(sorted(moved)))
    for a, b, new in sorted(edits, reverse=True):
        lines[a:b] = [new]
    return "".join(lines), notes


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="only list what would change; exit 1 if anything would")
    args = ap.parse_args(argv)
    defined, exported, homes = index()
    changed = 0
    for folder in FOLDERS:
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix == ".py":
                src = path.read_text(encoding="utf-8")
                new, notes = _fix_source(src, defined, exported, homes)
                if new != src:
                    changed += 1
                    if not args.check:
                        path.write_text(new, encoding="utf-8")
            elif path.suffix == ".ipynb" and ".ipynb_checkpoints" not in path.parts:
                nb = json.loads(path.read_text(encoding="utf-8"))
                notes = []
                for cell in nb["cells"]:
                    if cell["cell_type"] != "code":
                        continue
                    src = "".join(cell["source"])
                    new, n = _fix_source(src, defined, exported, homes)
                    notes += n
                    if new != src:
                        cell["source"] = new.splitlines(keepends=True)
                if any("->" in n for n in notes):
                    changed += 1
                    if not args.check:
                        path.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
            else:
                continue
            for n in notes:
                print(f"{path.relative_to(ROOT)} {n}")
    print(f"{changed} file(s) {'need' if args.check else 'got'} rewritten imports")
    return 1 if args.check and changed else 0


if __name__ == "__main__":
    sys.exit(main())

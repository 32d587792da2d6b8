"""Where earlier versions of the course kept modules and names, so old student workspaces still run.

A student's workspace notebooks are theirs and are never rewritten. When one of them imports a
module or a name from its earlier home, the import still works and a ``FutureWarning`` names the
new home. This is the only module that knows old names; new code never imports through it.
"""
from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
import warnings
from collections.abc import Sequence
from typing import Any

from typing_extensions import override

#: Old module path -> the module that holds its contents now.
MOVED_MODULES: dict[str, str] = {
    "gm_core.gaits": "gm_core.systems.gaits",
    "gm_core.locomotion": "gm_core.systems.motion",
    "gm_core.three_link_chain": "gm_core.chains.three_link",
    "gm_core.checks.ch4": "gm_core.checks.ex4",
}

#: (old module path, name) -> "new.module:name", for names that moved to a different module.
MOVED_NAMES: dict[tuple[str, str], str] = {
    ("gm_core.locomotion", "circle_gait"): "gm_core.systems.gaits:circle_gait",
    ("gm_core.checks.ch4", "drift_and_turn"): "gm_core.renamed:previous_drift_and_turn",
}


def previous_drift_and_turn(gait: Any, system: Any = None) -> Any:
    """Exercise 4.2's ``drift_and_turn(gait)`` of an earlier version: the exercise's swimmer first."""
    from gm_core.checks.ex4 import swimmer
    from gm_core.geometry import drift_and_turn

    return drift_and_turn(system if system is not None else swimmer(), gait)


def _resolve(target: str) -> Any:
    module, _, name = target.partition(":")
    return getattr(importlib.import_module(module), name)


class _OldModule(types.ModuleType):
    """Stands at an old module path and hands out the new home's names."""

    def __getattr__(self, name: str) -> Any:
        old = self.__name__
        target = MOVED_NAMES.get((old, name))
        if target is not None:
            warnings.warn(f"The course was updated: {name} moved ({target.replace(':', '.')}); "
                          "your import still works.", FutureWarning, stacklevel=2)
            return _resolve(target)
        return getattr(importlib.import_module(MOVED_MODULES[old]), name)


class _MovedFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    def find_spec(self, fullname: str, path: Sequence[str] | None,
                  target: types.ModuleType | None = None) -> importlib.machinery.ModuleSpec | None:
        if fullname not in MOVED_MODULES:
            return None
        return importlib.machinery.ModuleSpec(fullname, self)

    @override
    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        return _OldModule(spec.name)

    def exec_module(self, module: types.ModuleType) -> None:
        new = MOVED_MODULES[module.__name__]
        warnings.warn(f"The course was updated: {module.__name__} is now {new} "
                      f"(import from {new}); your import still works.", FutureWarning, stacklevel=2)


def install() -> None:
    """Put the finder on ``sys.meta_path`` once (``import gm_core`` does this)."""
    if not any(isinstance(f, _MovedFinder) for f in sys.meta_path):
        sys.meta_path.append(_MovedFinder())

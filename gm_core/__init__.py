"""gm_core: the numeric core of the geometric mechanics course companion.

The mathematics sits in topic subpackages that use numpy and scipy only: ``groups``,
``manifolds``, ``calculus``, ``fields``, ``chains``, ``systems``, ``geometry`` (plus the loose
``validation`` and ``printing``). Drawing (``gm_core.drawing``) and widgets (``gm_core.widgets``)
sit on top, a topic keeping its name in every layer, and are imported only when asked for, so the
flow runs one way: math -> drawing -> widgets -> notebooks. The student's exercise checkers are
``gm_core.checks``; CONTRIBUTING.md has the map of every module.
"""
from __future__ import annotations

import importlib
from typing import Any

from gm_core import renamed
from gm_core.groups import (
    ALL_GROUPS,
    R2,
    S1,
    SE2,
    SO2,
    SO3,
    LieGroup,
    R,
    R2xS1,
    Rn,
    RPlus,
    ScaleShift,
    matvec,
    wrap_angle,
)
from gm_core.validation import SingularShapeError

__all__ = [
    "LieGroup", "Rn", "R", "R2", "RPlus", "SO2", "S1", "R2xS1", "SE2", "ScaleShift", "SO3", "ALL_GROUPS", "wrap_angle",
    "matvec", "SingularShapeError",
]

__version__ = "0.1.0"

_SUBMODULES = {"groups", "manifolds", "calculus", "fields", "chains", "systems", "geometry",
               "validation", "printing", "checks", "drawing", "widgets"}

renamed.install()


def __getattr__(name: str) -> Any:
    # Lazy submodules: ``import gm_core; gm_core.chains.three_link_jacobians(...)`` works without
    # importing matplotlib or ipywidgets for code that never draws.
    if name in _SUBMODULES:
        return importlib.import_module(f"gm_core.{name}")
    raise AttributeError(f"module 'gm_core' has no attribute {name!r}")

"""gm_core: the numeric core of the geometric mechanics course companion.

The mathematics (this package's top level, ``groups``, ``calculus``, ``fields``, ``chains``,
``arms``, ``three_link_chain``, ``holonomic``, ``connection``, ``gaits``, ``locomotion``,
``systems``, ``fluids``, ``geometry``, ``manifolds``, ``axioms``, ``observers``, ``printing``) uses numpy and
scipy only. Drawing
(``gm_core.drawing``) and widgets (``gm_core.widgets``) sit on top and are imported only when
asked for, so the flow runs one way: math -> drawing -> widgets -> notebooks.
"""
from __future__ import annotations

import importlib

from ._validate import SingularShapeError
from .groups import ALL_GROUPS, R2, S1, SE2, SO2, LieGroup, R, R2xS1, Rn, RPlus, matvec, wrap_angle

__all__ = [
    "LieGroup", "Rn", "R", "R2", "RPlus", "SO2", "S1", "R2xS1", "SE2", "ALL_GROUPS", "wrap_angle",
    "matvec", "SingularShapeError",
]
__version__ = "0.1.0"

_SUBMODULES = {"groups", "calculus", "fields", "chains", "arms", "three_link_chain", "holonomic", "connection", "gaits",
               "locomotion", "systems", "fluids", "geometry", "manifolds", "axioms", "observers", "printing",
               "checks", "grade", "drawing", "widgets"}


def __getattr__(name):
    # Lazy submodules: ``import gm_core; gm_core.three_link_chain.three_link_jacobians(...)`` works without
    # importing matplotlib or ipywidgets for code that never draws.
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'gm_core' has no attribute {name!r}")

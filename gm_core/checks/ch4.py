"""Old home of the curvature exercises' checkers, kept only for student workspaces of the previous
version: their ex4_2 notebook runs ``from gm_core.checks.ch4 import drift_and_turn``.

The checkers are :mod:`gm_core.checks.curvature`; ``drift_and_turn(system, gait)`` is
:func:`gm_core.geometry.drift_and_turn`. Nothing else lives here.
"""
from __future__ import annotations

import warnings


def _drift_and_turn(gait, system=None):
    """The previous version's call: drift_and_turn(gait) for the exercise's swimmer."""
    from ..geometry import drift_and_turn
    from .curvature import swimmer

    return drift_and_turn(system or swimmer(), gait)


def __getattr__(name):
    if name == "drift_and_turn":
        warnings.warn("The course was updated: drift_and_turn now lives in gm_core.geometry and takes "
                      "the system first: from gm_core.geometry import drift_and_turn; "
                      "drift_and_turn(LowReSwimmer(), gait). Your call still works.",
                      FutureWarning, stacklevel=2)
        return _drift_and_turn
    raise AttributeError(f"module 'gm_core.checks.ch4' has no attribute {name!r} "
                         "(the curvature exercises' checkers are in gm_core.checks.curvature)")

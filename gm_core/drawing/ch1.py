"""Chapter 1 drawings, by topic (a compatibility module: import from the topic modules).

* :mod:`.toolkit`    -- figure standard, PathText, ArrowSet, ticks, Scene
* :mod:`.spaces`     -- section 1.1, configuration spaces (maths: :mod:`gm_core.manifolds`)
* :mod:`.actions`    -- sections 1.2-1.3, groups and SE(2) actions (maths: :mod:`gm_core.axioms`)
* :mod:`.velocities` -- sections 1.4-1.5, vector fields and velocities (maths: :mod:`gm_core.examples`)
* :mod:`.geodesics`  -- section 1.6, geodesics and exp

Every name notebooks and tests imported from here before the split still works.
"""
from __future__ import annotations

from ..axioms import AXIOMS, axiom_residuals
from ..examples import FIELDS, binomial_table, point_velocities
from ..groups import ALL_GROUPS
from ..manifolds import chart_speed, cylinder_xyz, sphere_xyz, torus_xyz, wrap_segments
from .actions import (BODY, BodyPointsScene, CircleIsoScene, ForwardLeftScene, GroupAxiomsScene,
                      LeftRightActionScene, SlideRuleScene)
from .geodesics import (ExpFourWaysScene, HelixScene, PuckArcScene, RPlusGeodesicScene, helix_geometry,
                        puck_vs_arc_animation)
from .spaces import LoopsScene, PoleChartScene, TorusPathScene, configuration_space_gallery, flattened_views
from .toolkit import ArrowSet, PathText, Scene, figure
from .velocities import AdjointScene, LiftedScalarScene, LiftedSE2Scene, VectorFieldScene, VelocityScene

__all__ = [
    "Scene", "figure", "PathText", "ArrowSet", "AXIOMS", "torus_xyz", "sphere_xyz", "cylinder_xyz", "wrap_segments",
    "configuration_space_gallery", "flattened_views", "TorusPathScene", "LoopsScene",
    "PoleChartScene", "chart_speed",
    "axiom_residuals", "GroupAxiomsScene", "SlideRuleScene", "CircleIsoScene",
    "LeftRightActionScene", "ForwardLeftScene", "BodyPointsScene",
    "FIELDS", "VectorFieldScene", "LiftedScalarScene", "LiftedSE2Scene",
    "point_velocities", "VelocityScene", "AdjointScene",
    "HelixScene", "helix_geometry", "PuckArcScene", "puck_vs_arc_animation", "RPlusGeodesicScene",
    "ExpFourWaysScene", "binomial_table", "ALL_GROUPS", "BODY",
]

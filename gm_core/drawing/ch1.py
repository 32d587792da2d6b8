"""Chapter 1 drawings, by topic (a compatibility module: import from the topic modules).

* :mod:`.toolkit`    -- figure standard, PathText, ArrowSet, ticks, Scene
* :mod:`.spaces`     -- section 1.1, configuration spaces (maths: :mod:`gm_core.manifolds`)
* :mod:`.actions`    -- sections 1.2-1.3, groups and SE(2) actions (maths: :mod:`gm_core.axioms`)
* :mod:`.velocities` -- sections 1.4-1.5, vector fields and velocities (maths: :mod:`gm_core.fields`, :mod:`gm_core.frames`)
* :mod:`.geodesics`  -- section 1.6, geodesics (of surfaces, fig. 1.16, and of groups) and exp
* :mod:`.group_or_not` -- section 1.2, the group axioms tried on groups and non-groups
* :mod:`.observer`   -- section 1.5, the adjoint as a change of observer, the Frames box
* :mod:`.tangent`    -- section 1.4, tangent spaces (figs 1.11-1.12)

Every name notebooks and tests imported from here before the split still works.
"""
from __future__ import annotations

from ..axioms import AXIOMS, axiom_residuals
from ..calculus import binomial_table
from ..fields import FIELDS
from ..frames import point_velocities
from ..groups import ALL_GROUPS
from ..manifolds import chart_speed, cylinder_xyz, sphere_xyz, torus_xyz, wrap_segments
from .actions import (
                      BODY,
                      BodyPointsScene,
                      CircleIsoScene,
                      ForwardLeftScene,
                      GroupAxiomsScene,
                      LeftRightActionScene,
                      SlideRuleScene,
)
from .geodesics import (
                      ExpFourWaysScene,
                      HelixScene,
                      PuckArcScene,
                      RPlusGeodesicScene,
                      SurfaceGeodesicsScene,
                      helix_geometry,
                      puck_vs_arc_animation,
)
from .group_or_not import GroupOrNotScene
from .observer import FramesScene, ObserverScene
from .spaces import LoopsScene, PoleChartScene, TorusPathScene, configuration_space_gallery, flattened_views
from .tangent import TangentSpaceScene
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
    "GroupOrNotScene", "ObserverScene", "FramesScene", "TangentSpaceScene", "SurfaceGeodesicsScene",
]

"""Vector fields, integral curves and group geodesics of chapter 1 (numpy + scipy only).

==============================  ===========================================================  ===============
name                            what it is                                                   book
==============================  ===========================================================  ===============
VectorField                     X(q, t) -> q_dot, batched over q; ``on_grid`` for quiver     (1.13)-(1.15)
integral_curve                  flow of X from q0 by scipy's solve_ivp (tight tolerances)    (1.15)-(1.18)
left_invariant_field            X_L(g) = T_e L_g xi (constant body velocity xi)               (1.46)
right_invariant_field           X_R(g) = T_e R_g xi_s (constant spatial velocity xi_s)        (1.47)
group_geodesic                  g0 o exp(t xi) (left) or exp(t xi_s) o g0 (right), or solved  section 1.6.2, 1.6.4
se2_helix                       circle / helix geometry of an SE(2) geodesic                 fig. 1.18, ex. 1.4c
se2_helices                     the family exp(t (v, 0, thetadot)) of fig. 1.18              fig. 1.18
puck_vs_arc                     (R^2 x S^1, +) "spinning puck" path vs the SE(2) arc          fig. 1.19
rplus_geodesics                 accelerating / decelerating geodesics of (R+, x)             fig. 1.17
FIELDS                          the example fields (spiral sink, saddle, loops, van der Pol)  figs. 1.13-1.14
==============================  ===========================================================  ===============

Time-invariant fields are written ``X(q, t)`` anyway, so a field is always a function of (q, t) as
in (1.13)-(1.14); the ``t`` argument is ignored by the invariant fields.

SE(2) geodesic geometry (exercise 1.4c), derived here rather than taken from the draft: for
xi = (vx, vy, w) with w != 0, the left-invariant flow from e has theta(t) = w t and
(x, y)(t) = int_0^t R(w s) (vx, vy) ds = c + R(w t)(-c) with c = (-vy, vx) / w. So the xy-projection
is a circle through the origin, tangent there to (vx, vy), with centre c, radius |v| / |w| and
diameter 2 |v| / |w|, traversed at constant speed |v| = sqrt(vx^2 + vy^2) with period 2 pi / |w|.
In (x, y, theta) space the curve is a circular helix whose pitch (rise of theta per turn) is
2 pi for every xi (the sign of w gives the handedness); the xi-dependent quantities are the radius,
the xy arclength |v| t and the helix slope d theta / d s = w / |v| (theta gained per unit of xy
arclength, the signed curvature of the circle). One unit-time flow (exp(xi) itself) covers
xy arclength |v|, i.e. w / (2 pi) turns. For w = 0 the path is a straight line (radius infinite).

The code is in :mod:`.vector_fields` and :mod:`.geodesics`; import everything from here.
"""
from __future__ import annotations

from gm_core.fields.geodesics import (
                        HelixGeometry,
                        PuckVsArc,
                        group_geodesic,
                        puck_vs_arc,
                        rplus_geodesics,
                        se2_helices,
                        se2_helix,
)
from gm_core.fields.vector_fields import (
                        DEFAULT_ATOL,
                        DEFAULT_METHOD,
                        DEFAULT_RTOL,
                        FIELDS,
                        MAX_EVALUATIONS,
                        MAX_FIELD_DIM,
                        SOLVE_IVP_OPTIONS,
                        IntegralCurve,
                        VectorField,
                        integral_curve,
                        left_invariant_field,
                        right_invariant_field,
)

__all__ = [
    "VectorField", "IntegralCurve", "integral_curve", "left_invariant_field",
    "right_invariant_field", "group_geodesic", "HelixGeometry", "se2_helix", "se2_helices",
    "PuckVsArc", "puck_vs_arc", "rplus_geodesics", "DEFAULT_RTOL", "DEFAULT_ATOL", "FIELDS",
    "DEFAULT_METHOD", "MAX_EVALUATIONS", "MAX_FIELD_DIM", "SOLVE_IVP_OPTIONS",
]

"""Checkers for the chapter 3 exercises (3.1-3.4): Pfaffians and local connections.

Sign convention throughout: the reconstruction equation is xi = -A(r) r_dot, (3.10), and from a
Pfaffian omega = [omega_xi | omega_r] the local connection is A = omega_xi^-1 omega_r, (3.17).
What a right answer is lives in :mod:`gm_core.checks.keys.ex3`, whose references are computed from
the group layer, independently of gm_core.systems.motion.
"""
from __future__ import annotations

import numpy as np

from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import Exercise
from gm_core.checks.parts import FunctionPart, rng_inputs

# ============================================================================ 3.1
ex3_1 = Exercise("3.1", "Differential drive: a holonomic constraint hidden in the Pfaffian", [
    FunctionPart(
        "a", "theta(alpha1, alpha2, R, w): the car's orientation as a function of the wheel angles, "
             "starting from theta = 0 at alpha1 = alpha2 = 0",
        arg_names=("alpha1", "alpha2", "R", "w"), shape=(),
        inputs=rng_inputs(31, 6, lambda rng: (rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(0.2, 2),
                                              rng.uniform(0.2, 2)),
                          edges=[(0.0, 0.0, 1.0, 1.0), (1.0, 1.0, 2.0, 0.5), (0.0, 3.0, 2.0, 1.0)]),
        hints=["Subtract the two no-slip constraints (3.23) and (3.24): the body velocity xi^x drops out.",
               "For a planar rigid body the rotational component of the body velocity is theta_dot "
               "itself (the third row of (1.26)).",
               "theta_dot is a constant combination of the wheel speeds, so it integrates directly."]),
    ChoicePart(
        "b", "Which combination of the constraints (3.23)-(3.25) is integrable?",
        {"a": "All three are integrable, so the car cannot reach every pose in the plane",
         "b": "Only the no-slide constraint (3.25), like the rolling disk's sideways condition",
         "c": "None of them: nonholonomic constraints never hide a holonomic one inside",
         "d": "The difference of the two no-slip constraints; the other combinations are not"},
        hints=["A Pfaffian row integrates when it is the differential of a function; which rows "
               "have constant coefficients in variables whose derivatives they multiply?"]),
])


# ============================================================================ 3.2
ex3_2 = Exercise("3.2", "Pfaffians with fewer or more than three rows", [
    ChoicePart(
        "a", "What changes if the Pfaffian has fewer than 3 rows?",
        {"a": "omega_xi cannot be inverted: the body velocity may drift along its null space",
         "b": "Nothing: a pseudo-inverse of omega_xi gives the same local connection as before",
         "c": "The system becomes overconstrained, so only some shape changes remain possible",
         "d": "The local connection simply gets more columns, one for each missing constraint"},
        hints=["Count equations and unknowns in omega_xi xi = -omega_r r_dot when omega has 2 rows."]),
    ChoicePart(
        "b", "And with more than 3 rows?",
        {"a": "Nothing changes: omega_xi is inverted exactly as in the square 3 x 3 case",
         "b": "The body velocity becomes free to drift along the extra directions",
         "c": "Extra independent rows restrict r_dot; dependent ones can be dropped",
         "d": "The local connection gets one more row for each extra constraint row"},
        hints=["The differential drive car started with four constraints (3.18)-(3.19) for two "
               "wheels. What happened to them?"]),
])


# ============================================================================ 3.3
_ack_inputs = rng_inputs(33, 6, lambda rng: (rng.uniform(-1.3, 1.3, 2), rng.uniform(0.3, 2), rng.uniform(0.5, 3)),
                         edges=[(np.zeros(2), 1.0, 1.0), (np.array([0.0, 0.5]), 1.0, 1.0),
                                (np.array([2.0, -1.0]), 0.5, 2.0)])


def _ack_part(name: str, drive: str) -> FunctionPart:
    return FunctionPart(
        name, f"A(alpha, R, L): local connection (3 x 2) of the {drive}-wheel-drive kinematic bicycle; "
              "alpha = (drive wheel angle, steering angle), wheel radius R, wheelbase L",
        inputs=_ack_inputs, arg_names=("alpha", "R", "L"), shape=(3, 2),
        sympy_names=("alpha1", "alpha2", "R", "L"), sympy_args=lambda al, R, L: (al[0], al[1], R, L),
        hints=["Body frame at the middle of the rear axle, x forward; the front wheel sits at "
               "(L, 0) turned by the steering angle alpha2. Each wheel may not slide sideways; the "
               "driven wheel may not slip: its forward speed is R alpha1_dot.",
               "The front wheel's body velocity is Ad^-1 of (L, 0, alpha2) applied to xi (its "
               "steering rate does not move its contact point).",
               "Stack three independent rows into omega (3 x 5), split it into omega_xi (3 x 3) and "
               "omega_r (3 x 2), and use (3.17)."])


ex3_3 = Exercise("3.3", "Pfaffian and local connection of the Ackerman car (kinematic bicycle)", [
    _ack_part("a", "rear"),
    _ack_part("b", "front"),
])


# ============================================================================ 3.4
_sw_inputs = rng_inputs(34, 6, lambda rng: (float(rng.uniform(-2.5, 2.5)),), edges=[(0.0,), (1.0,), (-2.0,)])


def _swim_part(name: str, regime: str) -> FunctionPart:
    model = ("slender links with drag per unit length 1 (longitudinal) and 2 (lateral), (3.41)-(3.43)"
             if regime == "low" else
             "neutrally buoyant elliptical links, 10:1, with body inertia plus the added mass (3.46) "
             "(rotational term rho pi (a^2 - b^2)^2 / 8)")
    return FunctionPart(
        name, f"A(alpha): local connection (3 x 1) of the two-link swimmer at {regime} Reynolds "
              f"number; links of length 1, {model}",
        inputs=_sw_inputs, arg_names=("alpha",), shape=(3, 1), rtol=1e-5, atol=1e-8,
        hints=["Place the link centres relative to the hinge frame: link 1 at angle -alpha/2 "
               "pointing back, link 2 at +alpha/2 pointing forward; get each link's body Jacobian "
               "as in (2.62).",
               ("Net body-frame force = sum_i J_i^T(xi part) K_i xi_i with K_i the link drag "
                "matrix; setting it to zero is the Pfaffian (3.45)." if regime == "low" else
                "Kinetic energy = 1/2 sum_i xi_i^T (I_i + M_i) xi_i; assemble the 4x4 mass matrix "
                "sum J_i^T (I_i + M_i) J_i and read A from its blocks, (3.40)."),
               "By symmetry two of the three rows vanish: which ones?"])


ex3_4 = Exercise("3.4", "Local connections of two-link swimmers at low and high Reynolds number", [
    _swim_part("a", "low"),
    _swim_part("b", "high"),
    ChoicePart(
        "c", "What net displacement does a periodic stroke alpha(t) of the two-link swimmer produce?",
        {"a": "A forward displacement per cycle, proportional to the stroke amplitude",
         "b": "None: with one shape variable each stroke retraces its path (scallop theorem)",
         "c": "A sideways displacement at low Reynolds number, and none at high Reynolds number",
         "d": "It depends on how fast the stroke is executed: faster strokes travel further"},
        hints=["With one shape variable, the forward and return strokes trace the same path in "
               "shape space, backwards."]),
])

__all__ = ["ex3_1", "ex3_2", "ex3_3", "ex3_4"]

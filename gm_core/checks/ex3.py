"""Checkers for the chapter 3 exercises (3.1-3.4): Pfaffians and local connections.

Sign convention throughout: the reconstruction equation is xi = -A(r) r_dot, (3.10), and from a
Pfaffian omega = [omega_xi | omega_r] the local connection is A = omega_xi^-1 omega_r, (3.17).
References are computed here from the group layer, independently of gm_core.systems.motion.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import Exercise
from gm_core.checks.parts import FunctionPart, rng_inputs
from gm_core.groups import SE2

if TYPE_CHECKING:
    from gm_core.validation import FloatArray


# ============================================================================ 3.1
def _theta_dd(alpha1: float, alpha2: float, R: float, w: float) -> float:
    return R * (alpha2 - alpha1) / (2.0 * w)


ex3_1 = Exercise("3.1", "Differential drive: a holonomic constraint hidden in the Pfaffian", [
    FunctionPart(
        "a", "theta(alpha1, alpha2, R, w): the car's orientation as a function of the wheel angles, "
             "starting from theta = 0 at alpha1 = alpha2 = 0",
        ref=_theta_dd, arg_names=("alpha1", "alpha2", "R", "w"), shape=(),
        inputs=rng_inputs(31, 6, lambda rng: (rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(0.2, 2),
                                              rng.uniform(0.2, 2)),
                          edges=[(0.0, 0.0, 1.0, 1.0), (1.0, 1.0, 2.0, 0.5), (0.0, 3.0, 2.0, 1.0)]),
        mistakes=[(lambda a1, a2, R, w: -_theta_dd(a1, a2, R, w),
                   "your sign is reversed: wheel 1 sits at +w (on the left, (3.20)); turning only the "
                   "right wheel forward turns the car to the left, counterclockwise."),
                  (lambda a1, a2, R, w: 2 * _theta_dd(a1, a2, R, w),
                   "your angle is twice too large: the wheels are 2w apart."),
                  (lambda a1, a2, R, w: (a2 - a1) / (2.0 * w),
                   "your angle is missing the wheel radius R: a wheel turning by alpha rolls R alpha.")],
        hints=["Subtract the two no-slip constraints (3.23) and (3.24): the body velocity xi^x drops out.",
               "For a planar rigid body the rotational component of the body velocity is theta_dot "
               "itself (the third row of (1.26)).",
               "theta_dot is a constant combination of the wheel speeds, so it integrates directly."],
        solution_text="theta = R (alpha2 - alpha1) / (2 w): the holonomic constraint "
                      "theta - R (alpha2 - alpha1)/(2 w) = const."),
    ChoicePart(
        "b", "Which combination of the constraints (3.23)-(3.25) is integrable?",
        {"a": "All three are integrable, so the car cannot reach every pose in the plane",
         "b": "Only the no-slide constraint (3.25), like the rolling disk's sideways condition",
         "c": "None of them: nonholonomic constraints never hide a holonomic one inside",
         "d": "The difference of the two no-slip constraints; the other combinations are not"},
        "d",
        feedback={"d": "Correct: the difference only involves theta_dot and the wheel speeds, whose "
                       "coefficients are constant, so it is an exact differential. The rest still "
                       "lets the car reach any (x, y) by parallel parking.",
                  "a": "Then the car could not parallel park; it can reach every (x, y).",
                  "b": "The no-slide condition is the rolling disk's constraint (3.vi): it does not "
                       "integrate, since the disk can reach any position.",
                  "c": "Exercise 3.1 is the counterexample: look at the difference of (3.23) and (3.24)."},
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
        "a",
        feedback={"a": "Correct: with m < 3 rows, xi = -A r_dot + (any null-space vector of omega_xi): "
                       "the shape velocity no longer fixes the body velocity, and more physics (e.g. "
                       "momentum) is needed to close the equations.",
                  "b": "A pseudo-inverse picks one solution of an underdetermined system; the "
                       "physical motion is not determined by the constraints alone.",
                  "c": "That happens with more rows, not fewer.",
                  "d": "The columns of A count the shape variables; they do not change."},
        hints=["Count equations and unknowns in omega_xi xi = -omega_r r_dot when omega has 2 rows."]),
    ChoicePart(
        "b", "And with more than 3 rows?",
        {"a": "Nothing changes: omega_xi is inverted exactly as in the square 3 x 3 case",
         "b": "The body velocity becomes free to drift along the extra directions",
         "c": "Extra independent rows restrict r_dot; dependent ones can be dropped",
         "d": "The local connection gets one more row for each extra constraint row"},
        "c",
        feedback={"c": "Correct: independent extra rows can only all hold if r_dot satisfies "
                       "compatibility conditions (overconstrained; e.g. a car whose two wheels must "
                       "turn at matched speeds); dependent rows, like the two wheels' shared "
                       "no-slide condition, add nothing, and A comes from 3 independent rows.",
                  "a": "A non-square matrix has no inverse.",
                  "b": "More constraints remove freedom; drift comes with fewer.",
                  "d": "The rows of A are the position directions (3 for SE(2)), however many "
                       "constraints there are."},
        hints=["The differential drive car started with four constraints (3.18)-(3.19) for two "
               "wheels. What happened to them?"]),
])


# ============================================================================ 3.3
def ackerman_rear(alpha: npt.ArrayLike, R: float, L: float) -> FloatArray:
    """Local connection (3, 2) of the rear-wheel-drive kinematic bicycle; -A is (3.9)'s matrix for R = L = 1."""
    a2 = np.asarray(alpha, dtype=float)[1]
    return -np.array([[R, 0.0], [0.0, 0.0], [R * np.tan(a2) / L, 0.0]])


def ackerman_front(alpha: npt.ArrayLike, R: float, L: float) -> FloatArray:
    """Local connection (3, 2) of the front-wheel-drive kinematic bicycle (passive rear wheel)."""
    a2 = np.asarray(alpha, dtype=float)[1]
    return -np.array([[R * np.cos(a2), 0.0], [0.0, 0.0], [R * np.sin(a2) / L, 0.0]])


def ackerman_pfaffian(alpha: npt.ArrayLike, R: float, L: float, drive: str = "rear") -> FloatArray:
    """The 3 x 5 Pfaffian omega acting on (xi, alpha1_dot, alpha2_dot)."""
    a2 = np.asarray(alpha, dtype=float)[1]
    c, s = np.cos(a2), np.sin(a2)
    front_slide = [-s, c, L * c, 0.0, 0.0]
    if drive == "rear":
        return np.array([[1.0, 0.0, 0.0, -R, 0.0], [0.0, 1.0, 0.0, 0.0, 0.0], front_slide])
    return np.array([[c, s, L * s, -R, 0.0], front_slide, [0.0, 1.0, 0.0, 0.0, 0.0]])


_ack_inputs = rng_inputs(33, 6, lambda rng: (rng.uniform(-1.3, 1.3, 2), rng.uniform(0.3, 2), rng.uniform(0.5, 3)),
                         edges=[(np.zeros(2), 1.0, 1.0), (np.array([0.0, 0.5]), 1.0, 1.0),
                                (np.array([2.0, -1.0]), 0.5, 2.0)])


def _neg(f: Callable[..., FloatArray]) -> Callable[..., FloatArray]:
    return lambda *a: -f(*a)


def _ack_part(name: str, drive: str) -> FunctionPart:
    ref = ackerman_rear if drive == "rear" else ackerman_front
    other = ackerman_front if drive == "rear" else ackerman_rear
    return FunctionPart(
        name, f"A(alpha, R, L): local connection (3 x 2) of the {drive}-wheel-drive kinematic bicycle; "
              "alpha = (drive wheel angle, steering angle), wheel radius R, wheelbase L",
        ref=ref, inputs=_ack_inputs, arg_names=("alpha", "R", "L"), shape=(3, 2),
        sympy_names=("alpha1", "alpha2", "R", "L"), sympy_args=lambda al, R, L: (al[0], al[1], R, L),
        mistakes=[(_neg(ref), "your sign is reversed: the book writes xi = -A r_dot (3.10), so A = "
                   "omega_xi^-1 omega_r (3.17); driving forward must give xi^x > 0, i.e. A < 0 there."),
                  (other, f"that is the connection of the {'front' if drive == 'rear' else 'rear'}-"
                   "wheel-drive car."),
                  (lambda al, R, L: ref(al, R, 1.0), "your rotation rate ignores the wheelbase L."),
                  (lambda al, R, L: ref(al, 1.0, L), "your connection ignores the wheel radius R: "
                   "a wheel turning by alpha1 rolls R alpha1.")],
        hints=["Body frame at the middle of the rear axle, x forward; the front wheel sits at "
               "(L, 0) turned by the steering angle alpha2. Each wheel may not slide sideways; the "
               "driven wheel may not slip: its forward speed is R alpha1_dot.",
               "The front wheel's body velocity is Ad^-1 of (L, 0, alpha2) applied to xi (its "
               "steering rate does not move its contact point).",
               "Stack three independent rows into omega (3 x 5), split it into omega_xi (3 x 3) and "
               "omega_r (3 x 2), and use (3.17)."],
        solution_text=("A = -[[R, 0], [0, 0], [R tan(alpha2) / L, 0]], so xi = -A r_dot is (3.9) "
                       "for R = L = 1."
                       if drive == "rear" else
                       "A = -[[R cos(alpha2), 0], [0, 0], [R sin(alpha2) / L, 0]]: no singularity at "
                       "alpha2 = pi/2, where the car pivots about its rear axle."))


ex3_3 = Exercise("3.3", "Pfaffian and local connection of the Ackerman car (kinematic bicycle)", [
    _ack_part("a", "rear"),
    _ack_part("b", "front"),
])


# ============================================================================ 3.4
#: Two-link swimmers of exercise 3.4: link length 1, body frame at the hinge with the mean angle.
LINK = 1.0
ASPECT = 10.0


def two_link_geometry(alpha: float, l: float = LINK) -> tuple[FloatArray, FloatArray]:
    """Link-centre poses (2, 3) in the body frame and their alpha-derivatives (2, 3)."""
    h = 0.5 * float(alpha)
    c, s = np.cos(h), np.sin(h)
    poses = np.array([[-l / 2 * c, l / 2 * s, -h], [l / 2 * c, l / 2 * s, h]])
    d = np.array([[l / 4 * s, l / 4 * c, -0.5], [-l / 4 * s, l / 4 * c, 0.5]])
    return poses, d


def two_link_jacobians(alpha: float, l: float = LINK) -> FloatArray:
    """Body Jacobians (2, 3, 4) of the two link centres in (xi, alpha_dot), as in (2.62)."""
    poses, d = two_link_geometry(alpha, l)
    out = []
    for p, dp in zip(poses, d):
        TR = SE2.right_lifted_action(SE2.inverse(p), p)
        out.append(SE2.Ad_inv(p) @ np.hstack([np.eye(3), (TR @ dp)[:, None]]))
    return np.stack(out)


def low_re_resistance(l: float = LINK, c: float = 1.0) -> FloatArray:
    """Drag matrix of a slender link: c l (longitudinal), 2 c l (lateral), c l^3 / 6 (rotation)."""
    return np.diag([c * l, 2 * c * l, 2 * c * l ** 3 / 12])


def high_re_inertia(l: float = LINK, rho: float = 1.0, aspect: float = ASPECT) -> FloatArray:
    """Body + added inertia of a neutrally buoyant elliptical link, with (3.46)'s rotational term
    corrected to the classical rho pi (a^2 - b^2)^2 / 8."""
    a = l / 2
    b = a / aspect
    m = rho * np.pi * a * b
    body = np.diag([m, m, m * (a * a + b * b) / 4])
    added = np.diag([rho * np.pi * b * b, rho * np.pi * a * a, rho * np.pi * (a * a - b * b) ** 2 / 8])
    return body + added


def swimmer_connection(alpha: float, K: npt.ArrayLike) -> FloatArray:
    """A = M_xx^-1 M_xr for the 4x4 matrix M = sum J_i^T K J_i (drag or mass), shape (3, 1)."""
    J = two_link_jacobians(alpha)
    M = sum(Ji.T @ K @ Ji for Ji in J)
    return np.linalg.solve(M[:3, :3], M[:3, 3:])


def low_re_connection(alpha: float) -> FloatArray:
    """The low-Reynolds two-link swimmer's local connection (3, 1): the reference of 3.4(a)."""
    return swimmer_connection(alpha, low_re_resistance())


def high_re_connection(alpha: float) -> FloatArray:
    """The high-Reynolds two-link swimmer's local connection (3, 1): the reference of 3.4(b)."""
    return swimmer_connection(alpha, high_re_inertia())


_sw_inputs = rng_inputs(34, 6, lambda rng: (float(rng.uniform(-2.5, 2.5)),), edges=[(0.0,), (1.0,), (-2.0,)])


def _swim_part(name: str, regime: str) -> FunctionPart:
    ref = low_re_connection if regime == "low" else high_re_connection
    other = high_re_connection if regime == "low" else low_re_connection
    model = ("slender links with drag per unit length 1 (longitudinal) and 2 (lateral), (3.41)-(3.43)"
             if regime == "low" else
             "neutrally buoyant elliptical links, 10:1, with body inertia plus the added mass (3.46) "
             "(rotational term rho pi (a^2 - b^2)^2 / 8)")
    return FunctionPart(
        name, f"A(alpha): local connection (3 x 1) of the two-link swimmer at {regime} Reynolds "
              f"number; links of length 1, {model}",
        ref=ref, inputs=_sw_inputs, arg_names=("alpha",), shape=(3, 1), rtol=1e-5, atol=1e-8,
        mistakes=[(_neg(ref), "your sign is reversed: xi = -A r_dot (3.10)."),
                  (other, f"that is the {'high' if regime == 'low' else 'low'} Reynolds number "
                   "connection.")],
        hints=["Place the link centres relative to the hinge frame: link 1 at angle -alpha/2 "
               "pointing back, link 2 at +alpha/2 pointing forward; get each link's body Jacobian "
               "as in (2.62).",
               ("Net body-frame force = sum_i J_i^T(xi part) K_i xi_i with K_i the link drag "
                "matrix; setting it to zero is the Pfaffian (3.45)." if regime == "low" else
                "Kinetic energy = 1/2 sum_i xi_i^T (I_i + M_i) xi_i; assemble the 4x4 mass matrix "
                "sum J_i^T (I_i + M_i) J_i and read A from its blocks, (3.40)."),
               "By symmetry two of the three rows vanish: which ones?"],
        solution_text="A = M_xx^-1 M_xr with M = sum_i J_i^T K_i J_i; only the lateral (y) row is "
                      "non-zero, by the swimmer's left-right symmetry.")


ex3_4 = Exercise("3.4", "Local connections of two-link swimmers at low and high Reynolds number", [
    _swim_part("a", "low"),
    _swim_part("b", "high"),
    ChoicePart(
        "c", "What net displacement does a periodic stroke alpha(t) of the two-link swimmer produce?",
        {"a": "A forward displacement per cycle, proportional to the stroke amplitude",
         "b": "None: with one shape variable each stroke retraces its path (scallop theorem)",
         "c": "A sideways displacement at low Reynolds number, and none at high Reynolds number",
         "d": "It depends on how fast the stroke is executed: faster strokes travel further"},
        "b",
        feedback={"b": "Correct: xi = -A(alpha) alpha_dot, and a loop in a one-dimensional shape "
                       "space encloses no area, so both swimmers only wobble back and forth.",
                  "a": "Integrate xi = -A(alpha) alpha_dot over a stroke that goes out and back.",
                  "c": "Both regimes give kinematic systems; the argument is the same for both.",
                  "d": "Kinematic systems are insensitive to pacing (section 3.1)."},
        hints=["With one shape variable, the forward and return strokes trace the same path in "
               "shape space, backwards."]),
])

__all__ = ["ex3_1", "ex3_2", "ex3_3", "ex3_4"]

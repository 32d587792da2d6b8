"""The answer keys of chapter 3's exercises (:mod:`gm_core.checks.ex3`): the references, computed
here from the group layer, independently of gm_core.systems.motion, the known mistakes and the
correct options.

Sign convention throughout: the reconstruction equation is xi = -A(r) r_dot, (3.10), and from a
Pfaffian omega = [omega_xi | omega_r] the local connection is A = omega_xi^-1 omega_r, (3.17).
"""
from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from gm_core.checks.answer_key import ChoiceKey, FunctionKey, provide
from gm_core.checks.ex3 import ex3_1, ex3_2, ex3_3, ex3_4
from gm_core.groups import SE2

if TYPE_CHECKING:
    from gm_core.validation import FloatArray

__all__ = ["ackerman_rear", "ackerman_front", "ackerman_pfaffian", "LINK", "ASPECT",
           "two_link_geometry", "two_link_jacobians", "low_re_resistance", "high_re_inertia",
           "swimmer_connection", "low_re_connection", "high_re_connection"]


# ============================================================================ 3.1
def _theta_dd(alpha1: float, alpha2: float, R: float, w: float) -> float:
    return R * (alpha2 - alpha1) / (2.0 * w)


provide(
    ex3_1,
    a=FunctionKey(
        ref=_theta_dd,
        mistakes=[(lambda a1, a2, R, w: -_theta_dd(a1, a2, R, w),
                   "your sign is reversed: wheel 1 sits at +w (on the left, (3.20)); turning only the "
                   "right wheel forward turns the car to the left, counterclockwise."),
                  (lambda a1, a2, R, w: 2 * _theta_dd(a1, a2, R, w),
                   "your angle is twice too large: the wheels are 2w apart."),
                  (lambda a1, a2, R, w: (a2 - a1) / (2.0 * w),
                   "your angle is missing the wheel radius R: a wheel turning by alpha rolls R alpha.")],
        solution_text="theta = R (alpha2 - alpha1) / (2 w): the holonomic constraint "
                      "theta - R (alpha2 - alpha1)/(2 w) = const."),
    b=ChoiceKey(
        correct="d",
        feedback={"d": "Correct: the difference only involves theta_dot and the wheel speeds, whose "
                       "coefficients are constant, so it is an exact differential. The rest still "
                       "lets the car reach any (x, y) by parallel parking.",
                  "a": "Then the car could not parallel park; it can reach every (x, y).",
                  "b": "The no-slide condition is the rolling disk's constraint (3.vi): it does not "
                       "integrate, since the disk can reach any position.",
                  "c": "Exercise 3.1 is the counterexample: look at the difference of (3.23) and (3.24)."},
        solution_text="d: the difference of the two no-slip constraints (3.23) and (3.24)."),
)


# ============================================================================ 3.2
provide(
    ex3_2,
    a=ChoiceKey(
        correct="a",
        feedback={"a": "Correct: with m < 3 rows, xi = -A r_dot + (any null-space vector of omega_xi): "
                       "the shape velocity no longer fixes the body velocity, and more physics (e.g. "
                       "momentum) is needed to close the equations.",
                  "b": "A pseudo-inverse picks one solution of an underdetermined system; the "
                       "physical motion is not determined by the constraints alone.",
                  "c": "That happens with more rows, not fewer.",
                  "d": "The columns of A count the shape variables; they do not change."},
        solution_text="a: omega_xi cannot be inverted; the body velocity may drift along its null space."),
    b=ChoiceKey(
        correct="c",
        feedback={"c": "Correct: independent extra rows can only all hold if r_dot satisfies "
                       "compatibility conditions (overconstrained; e.g. a car whose two wheels must "
                       "turn at matched speeds); dependent rows, like the two wheels' shared "
                       "no-slide condition, add nothing, and A comes from 3 independent rows.",
                  "a": "A non-square matrix has no inverse.",
                  "b": "More constraints remove freedom; drift comes with fewer.",
                  "d": "The rows of A are the position directions (3 for SE(2)), however many "
                       "constraints there are."},
        solution_text="c: extra independent rows restrict r_dot; dependent ones can be dropped."),
)


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


def _neg(f: Callable[..., FloatArray]) -> Callable[..., FloatArray]:
    return lambda *a: -f(*a)


def _ack_key(drive: str) -> FunctionKey:
    ref = ackerman_rear if drive == "rear" else ackerman_front
    other = ackerman_front if drive == "rear" else ackerman_rear
    return FunctionKey(
        ref=ref,
        mistakes=[(_neg(ref), "your sign is reversed: the book writes xi = -A r_dot (3.10), so A = "
                   "omega_xi^-1 omega_r (3.17); driving forward must give xi^x > 0, i.e. A < 0 there."),
                  (other, f"that is the connection of the {'front' if drive == 'rear' else 'rear'}-"
                   "wheel-drive car."),
                  (lambda al, R, L: ref(al, R, 1.0), "your rotation rate ignores the wheelbase L."),
                  (lambda al, R, L: ref(al, 1.0, L), "your connection ignores the wheel radius R: "
                   "a wheel turning by alpha1 rolls R alpha1.")],
        solution_text=("A = -[[R, 0], [0, 0], [R tan(alpha2) / L, 0]], so xi = -A r_dot is (3.9) "
                       "for R = L = 1."
                       if drive == "rear" else
                       "A = -[[R cos(alpha2), 0], [0, 0], [R sin(alpha2) / L, 0]]: no singularity at "
                       "alpha2 = pi/2, where the car pivots about its rear axle."))


provide(ex3_3, a=_ack_key("rear"), b=_ack_key("front"))


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


def _swim_key(regime: str) -> FunctionKey:
    ref = low_re_connection if regime == "low" else high_re_connection
    other = high_re_connection if regime == "low" else low_re_connection
    return FunctionKey(
        ref=ref,
        mistakes=[(_neg(ref), "your sign is reversed: xi = -A r_dot (3.10)."),
                  (other, f"that is the {'high' if regime == 'low' else 'low'} Reynolds number "
                   "connection.")],
        solution_text="A = M_xx^-1 M_xr with M = sum_i J_i^T K_i J_i; only the lateral (y) row is "
                      "non-zero, by the swimmer's left-right symmetry.")


provide(
    ex3_4,
    a=_swim_key("low"),
    b=_swim_key("high"),
    c=ChoiceKey(
        correct="b",
        feedback={"b": "Correct: xi = -A(alpha) alpha_dot, and a loop in a one-dimensional shape "
                       "space encloses no area, so both swimmers only wobble back and forth.",
                  "a": "Integrate xi = -A(alpha) alpha_dot over a stroke that goes out and back.",
                  "c": "Both regimes give kinematic systems; the argument is the same for both.",
                  "d": "Kinematic systems are insensitive to pacing (section 3.1)."},
        solution_text="b: none; a stroke in a one-dimensional shape space retraces its path "
                      "(scallop theorem)."),
)

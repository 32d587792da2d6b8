"""The answer keys of chapter 1's exercises (:mod:`gm_core.checks.ex1`), with those of exercise
1.4's parts that :mod:`gm_core.checks.exp_routes` builds: the references (the lifted actions, the
SE(2) exp, the helix, the four numerical routes of 1.4(d)), the known mistakes and their messages,
the judges of 1.3(c) and 1.4(d), the correct options and their feedback, and the solution texts."""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from gm_core.checks.answer_key import ChoiceKey, FunctionKey, FunctionMistake, JudgeKey, TupleKey, provide
from gm_core.checks.answers import fmt_value
from gm_core.checks.ex1 import LIFTED_LABELS, PRODUCT_LABELS, ex1_1, ex1_2, ex1_3, ex1_4, ex1_5
from gm_core.checks.exp_routes import ROUTES, Route, route_calls, se2_vec
from gm_core.checks.parts import first_value, outcome_error
from gm_core.checks.sandbox import ProbeOutcome, Unattempted, Wrong
from gm_core.groups import SE2, wrap_angle

if TYPE_CHECKING:
    from gm_core.validation import FloatArray

# ============================================================================ 1.1
provide(
    ex1_1,
    a=ChoiceKey(
        correct="b",
        feedback={
            "b": "Correct: two independent angles, each cyclic when the joint can turn all the way "
                 "round, so the space is the direct product S^1 x S^1 (section 1.1, Figure 1.5).",
            "a": "Two numbers are right, but each one is an angle that comes back to itself after a "
                 "full turn (section 1.1: the cyclic nature decides S^1 versus R^1). R^2 would only "
                 "fit if joint limits stopped both rotations short of a full turn.",
            "c": "Two coordinates, yes, but the sphere is not a product of two circles: on a sphere "
                 "every loop can be shrunk to a point, and the two joint angles give two loops that "
                 "cannot (Figure 1.6).",
            "d": "Count the degrees of freedom: the output shaft's orientation has only two free "
                 "parameters relative to the input, while SO(3) is three-dimensional.",
            "e": "One angle is not enough: the two yokes turn about two different axes.",
        },
        solution_text="(b) T^2 = S^1 x S^1: two independent, unrestricted rotations."),
    b=ChoiceKey(
        correct="c",
        feedback={
            "c": "Correct: the offset is a fixed length, not a degree of freedom. The two joint "
                 "angles still describe every configuration, so the space is still T^2; what "
                 "changes is the map from (angle 1, angle 2) to the output link's pose.",
            "a": "The offset moves the output link, but by an amount fixed by the two angles: it "
                 "adds no new independent coordinate.",
            "b": "The output link's pose does change, but it is determined by the two angles: the "
                 "configuration space counts independent coordinates, not the pose's dimension.",
            "d": "A fixed offset is a constant of the mechanism, not a coordinate that can vary.",
        },
        solution_text="(c) Still T^2; the offset only changes the forward kinematics."),
)


# ============================================================================ 1.2
def _diag(h: npt.ArrayLike, g: npt.ArrayLike) -> FloatArray:
    h = np.asarray(h, dtype=float)
    return np.diag(h)


def _lifted_key() -> FunctionKey:
    """The key of 1.2(b) and 1.2(c): on this commutative group the left and right lifted actions agree."""
    return FunctionKey(
        ref=_diag,
        mistakes=[(lambda h, g: np.diag(g), "you differentiated with respect to h (your matrix "
                   "depends on g); the lifted action is the derivative with respect to g."),
                  (lambda h, g: np.eye(2), "the identity is the lifted action of an additive group "
                   "(1.22); here elements combine by multiplication, compare (1.24)."),
                  (lambda h, g: np.diag(np.asarray(h) * np.asarray(g)), "that is the product h g "
                   "itself, not its derivative with respect to g.")],
        solution_text="T_g L_h = T_g R_h = diag(h1, h2): each axis scales velocities by its factor "
                      "of h, as (1.24)-(1.25) do on (R+, x).")


provide(
    ex1_2,
    a=FunctionKey(
        ref=lambda h, g: np.asarray(h) * np.asarray(g),
        mistakes=[(lambda h, g: np.asarray(h) + np.asarray(g), "you added the parameters; the group "
                   "operation here is matrix multiplication."),
                  (lambda h, g: np.asarray(h) / np.asarray(g), "that is h g^-1, not h g.")],
        solution_text="h g = diag(h1 g1, h2 g2); the group is commutative, so L_h g = R_h g."),
    b=_lifted_key(),
    c=_lifted_key(),
)


# ============================================================================ 1.3
def _rp(ref: Callable[[float], float], mistakes: Sequence[FunctionMistake] = ()) -> FunctionKey:
    """The key of a component of 1.3(a): ``ref(g)`` as the 1 x 1 matrix the part compares."""
    return FunctionKey(ref=lambda g: np.array([[ref(g)]]), mistakes=mistakes)


def _TgL_ginv(g: FloatArray) -> FloatArray:
    return SE2.left_lifted_action(SE2.inverse(g), g)


def _TeL_g(g: FloatArray) -> FloatArray:
    return SE2.left_lifted_action(g, SE2.identity())


def _TgR_ginv(g: FloatArray) -> FloatArray:
    return SE2.right_lifted_action(SE2.inverse(g), g)


def _TeR_g(g: FloatArray) -> FloatArray:
    return SE2.right_lifted_action(g, SE2.identity())


def _swap_msg(i: int, j: int) -> str:
    """The message of lifted action ``j`` given for lifted action ``i`` (their inverse)."""
    a, b = LIFTED_LABELS[i], LIFTED_LABELS[j]
    return f"this is {b}, not {a}: the two are inverses of each other, so check which one you meant."


def _product_judge(outcomes: list[ProbeOutcome]) -> str:
    for i, o in enumerate(outcomes):
        if o["k"] != "ok":
            outcome_error(o, "your products", "")
        free, value = o["v"]
        label = PRODUCT_LABELS[i]
        n = 1 if i < 2 else 3
        value = None if value is None else np.asarray(value, dtype=float)
        right = value is not None and value.size == n * n and np.allclose(
            value.reshape(n, n), np.eye(n), atol=1e-9 if free else 1e-12)
        if free:
            raise Wrong(f"{label} still contains {', '.join(free)}: simplify it (sp.simplify) until "
                        "the symbols cancel; that cancellation is what the exercise shows." + (
                            " (At a random point it is the identity, so only the simplification "
                            "is missing.)" if right else " (At a random point it is not the "
                            "identity: check the order of the factors and parts (a) and (b).)"))
        if not right:
            raise Wrong(f"{label} should simplify to the identity{' matrix' if n == 3 else ' 1'}; "
                        "yours does not. Check the order of the factors and parts (a) and (b).")
    return "Correct: each product simplifies to the identity, so each pair are inverses."


provide(
    ex1_3,
    a=TupleKey(
        components=[
            _rp(lambda g: 1.0 / g, [(lambda g: np.array([[g]]), _swap_msg(0, 1))]),
            _rp(lambda g: g, [(lambda g: np.array([[1.0 / g]]), _swap_msg(1, 0))]),
            _rp(lambda g: 1.0 / g, [(lambda g: np.array([[g]]), _swap_msg(2, 3))]),
            _rp(lambda g: g, [(lambda g: np.array([[1.0 / g]]), _swap_msg(3, 2))])],
        solution_text="T_g L_{g^-1} = T_g R_{g^-1} = 1/g and T_e L_g = T_e R_g = g; their product is 1.",
        wrong=[(lambda g: g, lambda g: g, lambda g: g, lambda g: g)]),
    b=TupleKey(
        components=[
            FunctionKey(ref=_TgL_ginv, mistakes=[(_TeL_g, _swap_msg(0, 1))]),
            FunctionKey(ref=_TeL_g, mistakes=[(_TgL_ginv, _swap_msg(1, 0))]),
            FunctionKey(ref=_TgR_ginv, mistakes=[(_TeR_g, _swap_msg(2, 3))]),
            FunctionKey(ref=_TeR_g, mistakes=[(_TgR_ginv, _swap_msg(3, 2))])],
        solution_text="T_g L_{g^-1} = [[c, s, 0], [-s, c, 0], [0, 0, 1]], T_e L_g = its transpose; "
                      "T_g R_{g^-1} = [[1, 0, y], [0, 1, -x], [0, 0, 1]], T_e R_g = [[1, 0, -y], "
                      "[0, 1, x], [0, 0, 1]]. The products are the identity for every g.",
        wrong=[(_TeL_g, _TeL_g, _TgR_ginv, _TeR_g)]),
    c=JudgeKey(
        judge=_product_judge,
        solution_text="All four products simplify to the identity (1 on (R+, x), I_3 on SE(2)).",
        reference=(1, 1, np.eye(3), np.eye(3)), wrong=[(1, 1, np.eye(3), 2 * np.eye(3))]),
)


# ============================================================================ 1.4 (a), (b): exp
def _exp_ref(xi: npt.ArrayLike) -> FloatArray:
    e = SE2.exp(np.asarray(xi, dtype=float))
    return np.array([e[0], e[1], wrap_angle(e[2])])


def _exp_wrong_sign(xi: npt.ArrayLike) -> FloatArray:
    vx, vy, w = np.asarray(xi, dtype=float)
    return _exp_ref([vx, vy, w]) * np.array([1, 1, 1]) if w == 0 else _exp_ref(
        [vx, vy, -w]) * np.array([1, 1, -1])


_EXP_MISTAKES = [
    (lambda xi: np.array([xi[0], xi[1], wrap_angle(xi[2])]),
     "your function returns xi itself: that is the exponential of the additive group (R^2 x S^1, +), "
     "the straight-line 'hockey puck' path of Figure 1.19, not the SE(2) arc."),
    (_exp_wrong_sign, "the arc bends the wrong way: with a positive rotational velocity the path "
     "curves to the left of its initial direction."),
]


def _exp_key() -> FunctionKey:
    """The key of 1.4(a) and 1.4(b) (:func:`~gm_core.checks.exp_routes.exp_part`): both fields
    give the same point."""
    return FunctionKey(
        ref=_exp_ref, mistakes=_EXP_MISTAKES,
        solution_text="exp(vx, vy, w) = ((vx sin w - vy (1 - cos w))/w, (vx (1 - cos w) + vy sin w)/w, "
                      "w), with the limit (vx, vy, 0) at w = 0. Both fields give the same point.",
        wrong=[lambda xi: np.asarray(xi)])


# ============================================================================ 1.4 (c): the helix
def helix_ref(xi: npt.ArrayLike) -> FloatArray:
    """(pitch, diameter, xy arclength) of the helix exp(t xi), t in [0, 1]: the reference of 1.4(c)."""
    vx, vy, w = np.asarray(xi, dtype=float)
    v = np.hypot(vx, vy)
    return np.array([2 * np.pi * np.sign(w), 2 * v / abs(w), v])


# ============================================================================ 1.4 (d): four routes
_D_NAMES = {"euler_left": "Euler on the left-invariant field", "euler_right": "Euler on the "
            "right-invariant field", "product": "the cumulative product (I + xi^/n)^n",
            "taylor": "the Taylor sum over k < n"}


def _d_close(got: npt.ArrayLike, want: npt.ArrayLike) -> bool:
    d = np.asarray(got, dtype=float) - np.asarray(want, dtype=float)
    if np.isfinite(d[2]):   # a NaN or infinite difference stays so, and fails
        d[2] = wrap_angle(d[2])
    return bool(np.all(np.abs(d) <= 1e-9 + 1e-7 * np.abs(want)))


def _d_vec(f: Route, xi: npt.ArrayLike, n: int) -> FloatArray:
    return se2_vec(f(xi, n), None)


#: wrong routes a student may hand in for each key, with the message each deserves
def _d_mistakes(k: str) -> list[tuple[Route, str]]:
    out: list[tuple[Route, str]] = [
        (EXP_METHODS[o], f"answer[{k!r}] computes {_D_NAMES[o]}, not {_D_NAMES[k]}.") for o in ROUTES if o != k]
    out.append((lambda xi, n: SE2.exp(xi), f"answer[{k!r}] returns the exact exponential for every "
                "n; implement the n-step method itself so that its convergence can be seen."))
    if k == "taylor":
        out.append((lambda xi, n: _taylor(xi, n + 1), "answer['taylor'] sums n + 1 terms (k = 0 ... "
                    "n); the prompt asks for the terms k < n."))
    else:
        def more_steps(xi: npt.ArrayLike, n: int) -> npt.ArrayLike:
            return EXP_METHODS[k](xi, n + 1) if k == "product" else _euler(xi, n + 1, k.split("_")[1])
        out.append((more_steps, f"answer[{k!r}] takes n + 1 steps; take n steps of size 1/n."))
    return out


def routes_judge(outcomes: list[ProbeOutcome]) -> str:
    """The judge of 1.4(d): every route matches its reference step for step, or a message says
    which route is wrong and, for a known mistake, how."""
    first_value(outcomes, "your dict", "")
    calls = route_calls()
    if len(outcomes) != len(calls) + 1:
        raise Wrong("the check could not evaluate every route.")
    results = dict(zip(range(len(calls)), outcomes[1:]))
    by_key: dict[str, list[tuple[FloatArray, int, FloatArray]]] = {k: [] for k in ROUTES}
    for i, (k, xi, n) in enumerate(calls):
        o = results[i]
        label = f"xi = {fmt_value(xi)}, n = {n}"
        if o["k"] != "ok":
            outcome_error(o, f"answer[{k!r}]", label)
        if o["v"] is None:
            raise Unattempted(f"answer[{k!r}] still returns None for {label}.") if all(
                results[j]["k"] == "ok" and results[j]["v"] is None
                for j, c in enumerate(calls) if c[0] == k) else Wrong(
                f"answer[{k!r}] returned None for {label} (a branch without return?).")
        got = np.asarray(o["v"], dtype=float)
        if got.shape != (3,) or not np.all(np.isfinite(got)):
            raise Wrong(f"answer[{k!r}] returned NaN or infinite entries for {label}.")
        by_key[k].append((xi, n, got))
    for k in ROUTES:
        bad = [(xi, n) for xi, n, got in by_key[k] if not _d_close(got, _d_vec(EXP_METHODS[k], xi, n))]
        if not bad:
            continue
        for f, msg in _d_mistakes(k):
            if all(_d_close(got, _d_vec(f, xi, n)) for xi, n, got in by_key[k]):
                raise Wrong(msg)
        xi, n = bad[0]
        raise Wrong(f"answer[{k!r}] gives a different value for xi = {fmt_value(xi)}, n = {n}: it "
                    f"should be {_D_NAMES[k]} with n steps (or terms), starting at e. Try n = 1 by hand.")
    return ("Correct: all four routes match, step for step. Both Euler flows and the cumulative "
            "product converge at first order (error ~ 1/n), the Taylor sum factorially fast.")


def _euler(xi: npt.ArrayLike, n: int, side: str) -> FloatArray:
    xi = np.asarray(xi, dtype=float)
    g = np.zeros(3)
    for _ in range(int(n)):
        if side == "left":
            g = g + SE2.body_to_world(g, xi) / n
        else:
            g = g + SE2.spatial_to_world(g, xi) / n
    return g


def _product(xi: npt.ArrayLike, n: int) -> FloatArray:
    return np.linalg.matrix_power(np.eye(3) + SE2.hat(np.asarray(xi, dtype=float)) / n, int(n))


def _taylor(xi: npt.ArrayLike, n: int) -> FloatArray:
    X = SE2.hat(np.asarray(xi, dtype=float))
    total, term = np.zeros((3, 3)), np.eye(3)
    for k in range(int(n)):
        total = total + term
        term = term @ X / (k + 1)
    return total


#: Reference implementations of the four routes of exercise 1.4d (also used by the tests).
EXP_METHODS: dict[str, Route] = {"euler_left": lambda xi, n: _euler(xi, n, "left"),
               "euler_right": lambda xi, n: _euler(xi, n, "right"),
               "product": _product, "taylor": _taylor}


provide(
    ex1_4,
    a=_exp_key(),
    b=_exp_key(),
    c=FunctionKey(
        ref=helix_ref,
        mistakes=[(lambda xi: helix_ref(xi) * np.array([1, 0.5, 1]),
                   "your second entry is the radius of the projected circle, not its diameter."),
                  (lambda xi: np.array([helix_ref(xi)[0], helix_ref(xi)[1],
                                        np.linalg.norm(np.asarray(xi, dtype=float))]),
                   "your arclength includes the rotational component: that is the length of the "
                   "helix in (x, y, theta) space, not of its projection onto the xy plane."),
                  (lambda xi: np.array([abs(helix_ref(xi)[0]), *helix_ref(xi)[1:]]),
                   "the pitch is signed: a negative w makes theta go down by 2 pi per turn.")],
        solution_text="pitch = 2 pi sign(w) (theta rises one full turn per loop), diameter = "
                      "2 |(vx, vy)| / |w|, xy arclength in unit time = |(vx, vy)|."),
    d=JudgeKey(
        judge=routes_judge,
        solution_text="Euler (both fields) and the product converge like 1/n; the Taylor sum "
                      "converges factorially. See the plot in the worked solution.",
        reference=EXP_METHODS, wrong=[{"euler_left": lambda xi, n: SE2.exp(xi),
                                       "euler_right": lambda xi, n: SE2.exp(xi),
                                       "product": lambda xi, n: SE2.exp(xi),
                                       "taylor": lambda xi, n: SE2.exp(xi)}]),
    d_rates=ChoiceKey(
        correct="d",
        feedback={"d": "Correct: the first three are first-order methods; the Taylor tail is bounded "
                       "by |xi|^n/n!.",
                  "a": "Look at the Taylor curve on a log scale: it drops off a cliff.",
                  "b": "Swap them: the Taylor remainder shrinks like |xi|^n / n!.",
                  "c": "Its error halves when n doubles, like the left field's."},
        solution_text="(d) Euler (both fields) and the cumulative product converge like 1/n; the "
                      "Taylor sum faster than any power of 1/n (its tail is bounded by |xi|^n/n!)."),
    d_meaning=ChoiceKey(
        correct="a",
        feedback={"a": "Correct: each factor is a small step 'from where we are', so the running "
                       "product after k factors approximates exp((k/n) xi), a discretised "
                       "trajectory (compare (1.xxvii)).",
                  "b": "A partial Taylor sum is not even a rigid motion: its 2x2 block is not a "
                       "rotation. It has no meaning as a point on the path.",
                  "c": "Look at what k factors of a unit-time step of length 1/n add up to.",
                  "d": "The body velocity is the same xi at every step; the products are positions."},
        solution_text="(a) The partial products trace the path: after k of the n factors the product "
                      "is close to exp((k/n) xi)."),
)


# ============================================================================ 1.5
provide(
    ex1_5,
    a=ChoiceKey(
        correct="c",
        feedback={"c": "Correct: the log map is an isomorphism (1.xii), so adding lengths in (R, +) "
                       "is multiplying numbers in (R+, x).",
                  "a": "Look at a real C/D scale: the gap from 1 to 2 is much larger than from 9 to 10.",
                  "b": "Exp would turn products into sums the other way round; distances on the rule "
                       "are added, not multiplied.",
                  "d": "One slide, one reading: no repetition involved."},
        solution_text="(c) Each scale marks x at the distance log(x), so sliding adds distances: "
                      "log a + log b = log ab."),
    b=FunctionKey(
        ref=lambda a: np.log10(a),
        mistakes=[(lambda a: np.log(a), "you used the natural logarithm; the scale runs one decade "
                   "(1 to 10), so the fraction is a base-10 logarithm."),
                  (lambda a: (a - 1) / 9, "that is a uniform (linear) scale; slide rule scales are "
                   "logarithmic."),
                  (lambda a: a / 10, "that is a uniform (linear) scale; slide rule scales are "
                   "logarithmic.")],
        solution_text="offset(a) = log10(a)."),
    c=ChoiceKey(
        correct="b",
        feedback={"b": "Correct: the rule computes in the Lie algebra (R, +) of a commutative group, "
                       "where exp(a + b) = exp(a) exp(b). For non-commuting elements the product "
                       "exp(a) exp(b) picks up correction terms (the Lie bracket), so no such rule "
                       "exists on SE(2).",
                  "a": "A bijection must also turn the group operation into addition, (1.x); that "
                       "singles out log up to a constant factor (the base).",
                  "c": "Try it on SE(2): exp of (1, 0, 0) then (0, 0, pi/2) is not exp of their sum.",
                  "d": "log is far from linear; it turns multiplication into addition."},
        solution_text="(b) log is the inverse of the exponential of the commutative group (R+, x); "
                      "on SE(2) exp(a) exp(b) != exp(a + b), so no slide rule works there."),
)

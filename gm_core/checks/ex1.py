"""Checkers for the chapter 1 exercises (1.1-1.5): configuration spaces, lifted actions, exp."""
from __future__ import annotations

from collections.abc import Callable, Iterator, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from gm_core.checks.answers import is_starter, is_sympy, to_numbers
from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import Exercise
from gm_core.checks.exp_routes import (
    EXP_METHODS,
    exp_part,
    helix_inputs,
    helix_ref,
    routes_judge,
    routes_probes,
)
from gm_core.checks.parts import CustomPart, FunctionPart, TuplePart, outcome_error, probe_rng, rng_inputs
from gm_core.checks.sandbox import Probe, ProbeOutcome, Unattempted, Wrong
from gm_core.groups import SE2

if TYPE_CHECKING:
    import ipywidgets

    from gm_core.validation import FloatArray

#: A wrong function a part knows, with the message it deserves (FunctionPart's ``mistakes``).
_Mistakes = Sequence[tuple[Callable[..., npt.ArrayLike], str]]

# ============================================================================ 1.1
ex1_1 = Exercise("1.1", "Configuration spaces of a universal joint and an offset universal joint", [
    ChoicePart(
        "a", "Configuration space of a universal joint (two intersecting revolute axes)",
        {"a": "R^2, the plane",
         "b": "T^2 = S^1 x S^1, the torus",
         "c": "S^2, the sphere",
         "d": "SO(3), all rotations in space",
         "e": "S^1, the circle"},
        "b",
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
        hints=["Count the independent ways the output shaft can move relative to the input shaft.",
               "Each of those motions is a rotation. Section 1.1 says what decides whether a "
               "rotation's space is R^1 or S^1.",
               "A space of two independent cyclic coordinates is a direct product of two circles."],
        solution_text="(b) T^2 = S^1 x S^1: two independent, unrestricted rotations."),
    ChoicePart(
        "b", "Configuration space when the two rotation axes do not intersect",
        {"a": "R^2 x S^1, because the offset between the axes adds a translation",
         "b": "SE(2), because the output shaft now translates as well as rotates",
         "c": "Still T^2: only the forward kinematics (where the output link is) changes",
         "d": "T^2 x R, with one extra dimension that measures the offset between the two axes"},
        "c",
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
        hints=["Does the offset between the axes change while the joint moves?",
               "The configuration space is set by the independent coordinates and their character "
               "(line or circle), not by where the parts end up in space."],
        solution_text="(c) Still T^2; the offset only changes the forward kinematics."),
])


# ============================================================================ 1.2
def _diag(h: npt.ArrayLike, g: npt.ArrayLike) -> FloatArray:
    h = np.asarray(h, dtype=float)
    return np.diag(h)


def _pos_pair(rng: np.random.Generator) -> tuple[FloatArray, FloatArray]:
    return np.exp(rng.uniform(-1.5, 1.5, 2)), np.exp(rng.uniform(-1.5, 1.5, 2))


_ONE = np.ones(2)
_scaling_inputs = rng_inputs(12, 6, _pos_pair,
                             edges=[(_ONE, np.array([2.0, 3.0])), (np.array([0.5, 4.0]), _ONE)])


def _diag_params(out: Any, args: tuple[Any, ...]) -> FloatArray:
    """Accept the two diagonal entries or the full 2x2 matrix (which must be diagonal)."""
    arr = to_numbers(out, "the value your function returned")
    if arr.shape == (2, 2):
        if abs(arr[0, 1]) > 1e-9 or abs(arr[1, 0]) > 1e-9:
            raise Wrong("your product matrix has non-zero off-diagonal entries, so it is not a "
                        "scaling matrix: the set is not closed under your operation.")
        return np.diag(arr).copy()
    return arr


_hg_names = ("h1", "h2", "g1", "g2")


def _hg_flat(h: Sequence[float], g: Sequence[float]) -> tuple[float, float, float, float]:
    return (h[0], h[1], g[0], g[1])


def _lifted_part(name: str, side: str) -> FunctionPart:
    which = "T_g L_h = d(h g)/d g" if side == "left" else "T_g R_h = d(g h)/d g"
    return FunctionPart(
        name, f"The {side} lifted action {which} for the scaling group",
        ref=_diag, inputs=_scaling_inputs, arg_names=("h", "g"), shape=(2, 2),
        sympy_names=_hg_names, sympy_args=_hg_flat,
        mistakes=[(lambda h, g: np.diag(g), "you differentiated with respect to h (your matrix "
                   "depends on g); the lifted action is the derivative with respect to g."),
                  (lambda h, g: np.eye(2), "the identity is the lifted action of an additive group "
                   "(1.22); here elements combine by multiplication, compare (1.24)."),
                  (lambda h, g: np.diag(np.asarray(h) * np.asarray(g)), "that is the product h g "
                   "itself, not its derivative with respect to g.")],
        hints=["Write the action in the two parameters, (g1, g2) -> (h1 g1, h2 g2), then take the "
               "2x2 Jacobian with respect to (g1, g2), as in (1.20)-(1.22).",
               "Each output depends on one input only, so the Jacobian is diagonal; compare the "
               "one-dimensional result (1.24)."],
        solution_text="T_g L_h = T_g R_h = diag(h1, h2): each axis scales velocities by its factor "
                      "of h, as (1.24)-(1.25) do on (R+, x).",
        starter=None)


ex1_2 = Exercise("1.2", "Group and lifted actions of the scaling matrices diag(R+, R+)", [
    FunctionPart(
        "a", "The group action: parameters (h1 g1, h2 g2) of h g for h = diag(h1, h2), g = diag(g1, g2)",
        ref=lambda h, g: np.asarray(h) * np.asarray(g), inputs=_scaling_inputs,
        arg_names=("h", "g"), shape=(2,), postprocess=_diag_params,
        sympy_names=_hg_names, sympy_args=_hg_flat,
        mistakes=[(lambda h, g: np.asarray(h) + np.asarray(g), "you added the parameters; the group "
                   "operation here is matrix multiplication."),
                  (lambda h, g: np.asarray(h) / np.asarray(g), "that is h g^-1, not h g.")],
        hints=["Multiply the two diagonal matrices.",
               "The product of diagonal matrices is diagonal; read off its two entries."],
        solution_text="h g = diag(h1 g1, h2 g2); the group is commutative, so L_h g = R_h g."),
    _lifted_part("b", "left"),
    _lifted_part("c", "right"),
])


# ============================================================================ 1.3
def _rplus_inputs() -> Iterator[tuple[float]]:
    rng = probe_rng(13)
    yield (1.0,)
    yield (0.05,)
    yield (20.0,)
    for _ in range(4):
        yield (float(np.exp(rng.uniform(-2, 2))),)


def _se2_inputs() -> Iterator[tuple[FloatArray]]:
    yield (np.zeros(3),)
    yield (np.array([1.0, 2.0, 0.0]),)
    yield (np.array([0.0, 0.0, np.pi]),)
    rng = probe_rng(31)
    for _ in range(4):
        yield (SE2.random(rng),)


def _rp(ref: Callable[[float], float], label: str, mistakes: _Mistakes = ()) -> tuple[str, FunctionPart]:
    return label, FunctionPart(label, label, ref=lambda g: np.array([[ref(g)]]), inputs=_rplus_inputs,
                               arg_names=("g",), shape=(1, 1), mistakes=mistakes)


def _se(ref: Callable[[FloatArray], FloatArray], label: str,
        mistakes: _Mistakes = ()) -> tuple[str, FunctionPart]:
    return label, FunctionPart(label, label, ref=ref, inputs=_se2_inputs, arg_names=("g",),
                               shape=(3, 3), sympy_names=("x", "y", "theta"),
                               sympy_args=lambda g: (g[0], g[1], g[2]), mistakes=mistakes)


def _TgL_ginv(g: FloatArray) -> FloatArray:
    return SE2.left_lifted_action(SE2.inverse(g), g)


def _TeL_g(g: FloatArray) -> FloatArray:
    return SE2.left_lifted_action(g, SE2.identity())


def _TgR_ginv(g: FloatArray) -> FloatArray:
    return SE2.right_lifted_action(SE2.inverse(g), g)


def _TeR_g(g: FloatArray) -> FloatArray:
    return SE2.right_lifted_action(g, SE2.identity())


_LABELS = ("T_g L_{g^-1}", "T_e L_g", "T_g R_{g^-1}", "T_e R_g")


def _swap_msg(a: str, b: str) -> str:
    return f"this is {b}, not {a}: the two are inverses of each other, so check which one you meant."


_PRODUCT_LABELS = ("T_g L_{g^-1} T_e L_g on (R+, x)", "T_g R_{g^-1} T_e R_g on (R+, x)",
                   "T_g L_{g^-1} T_e L_g on SE(2)", "T_g R_{g^-1} T_e R_g on SE(2)")


def _product_probes() -> list[Probe]:
    """One probe per product of part (c)."""
    def probe_of(i: int) -> Probe:
        return lambda ans: _product_probe(ans, i)
    return [probe_of(i) for i in range(4)]


def _product_probe(answer: Any, i: int) -> list[list[str] | FloatArray | None]:
    """Student side: the i-th product as given: (symbols left in it, its numbers or None)."""
    if is_starter(answer):
        raise Unattempted()
    if not isinstance(answer, (list, tuple)) or len(answer) != 4:
        raise Wrong("give a tuple of the four simplified products, in the order of the prompt.")
    if all(is_starter(a) for a in answer):
        raise Unattempted()
    item = answer[i]
    if is_starter(item):
        raise Wrong(f"{_PRODUCT_LABELS[i]} is still None.")
    symbols = sorted(getattr(item, "free_symbols", ()), key=str) if is_sympy(item) else []
    if symbols:
        # still symbolic: its value at a point drawn from the probe salt says whether it is right
        rng = probe_rng(33)
        point = {x: float(rng.uniform(0.5, 2.0)) for x in symbols}
        try:
            value = to_numbers(item.subs(point), _PRODUCT_LABELS[i])
        except Exception:  # noqa: BLE001 - left symbolic in a way that has no value
            value = None
        return [[str(x) for x in symbols], value]
    return [[], to_numbers(item, _PRODUCT_LABELS[i])]


def _product_judge(outcomes: list[ProbeOutcome]) -> str:
    for i, o in enumerate(outcomes):
        if o["k"] != "ok":
            outcome_error(o, "your products", "")
        free, value = o["v"]
        label = _PRODUCT_LABELS[i]
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


ex1_3 = Exercise("1.3", "T_g L_{g^-1} = (T_e L_g)^-1 and T_g R_{g^-1} = (T_e R_g)^-1", [
    TuplePart(
        "a", "On (R+, x): the four lifted actions as functions of g",
        [_rp(lambda g: 1.0 / g, _LABELS[0], [(lambda g: np.array([[g]]), _swap_msg(_LABELS[0], _LABELS[1]))]),
         _rp(lambda g: g, _LABELS[1], [(lambda g: np.array([[1.0 / g]]), _swap_msg(_LABELS[1], _LABELS[0]))]),
         _rp(lambda g: 1.0 / g, _LABELS[2], [(lambda g: np.array([[g]]), _swap_msg(_LABELS[2], _LABELS[3]))]),
         _rp(lambda g: g, _LABELS[3], [(lambda g: np.array([[1.0 / g]]), _swap_msg(_LABELS[3], _LABELS[2]))])],
        hints=["On (R+, x) the lifted actions of h are multiplication by h, (1.24)-(1.25).",
               "Put h = g^-1 (acting at g) and h = g (acting at e = 1)."],
        solution_text="T_g L_{g^-1} = T_g R_{g^-1} = 1/g and T_e L_g = T_e R_g = g; their product is 1.",
        wrong=[(lambda g: g, lambda g: g, lambda g: g, lambda g: g)],
        starter=(None, None, None, None)),
    TuplePart(
        "b", "On SE(2): the four lifted actions as 3x3 matrices, functions of g = (x, y, theta)",
        [_se(_TgL_ginv, _LABELS[0], [(_TeL_g, _swap_msg(_LABELS[0], _LABELS[1]))]),
         _se(_TeL_g, _LABELS[1], [(_TgL_ginv, _swap_msg(_LABELS[1], _LABELS[0]))]),
         _se(_TgR_ginv, _LABELS[2], [(_TeR_g, _swap_msg(_LABELS[2], _LABELS[3]))]),
         _se(_TeR_g, _LABELS[3], [(_TgR_ginv, _swap_msg(_LABELS[3], _LABELS[2]))])],
        hints=["Use (1.31) for T_g L_h and (1.37) for T_g R_h: they depend only on h (left) or on "
               "h and the angle of g (right).",
               "For the right actions, put h = g^-1 = (-x cos t - y sin t, x sin t - y cos t, -t) "
               "into (1.37) at the point g, and h = g into (1.37) at the point e = (0, 0, 0).",
               "Compare your T_g R_{g^-1} with the first factor of (1.42)."],
        solution_text="T_g L_{g^-1} = [[c, s, 0], [-s, c, 0], [0, 0, 1]], T_e L_g = its transpose; "
                      "T_g R_{g^-1} = [[1, 0, y], [0, 1, -x], [0, 0, 1]], T_e R_g = [[1, 0, -y], "
                      "[0, 1, x], [0, 0, 1]]. The products are the identity for every g.",
        wrong=[(_TeL_g, _TeL_g, _TgR_ginv, _TeR_g)],
        starter=(None, None, None, None)),
    CustomPart(
        "c", "Show the identities: the four products, simplified: (T_g L_{g^-1} T_e L_g, "
             "T_g R_{g^-1} T_e R_g) on (R+, x), then the same two on SE(2)",
        _product_probes, _product_judge,
        hints=["Multiply the pairs from parts (a) and (b) in the order T_g L_{g^-1} times T_e L_g.",
               "sp.simplify(M1 * M2) on SE(2): the sines and cosines combine through "
               "cos^2 + sin^2 = 1."],
        solution_text="All four products simplify to the identity (1 on (R+, x), I_3 on SE(2)).",
        reference=(1, 1, np.eye(3), np.eye(3)), wrong=[(1, 1, np.eye(3), 2 * np.eye(3))],
        starter=(None, None, None, None), weight=1.0),
])


# ============================================================================ 1.4

ex1_4 = Exercise("1.4", "The exponential map on SE(2)", [
    exp_part("a", "left"),
    exp_part("b", "right"),
    FunctionPart(
        "c", "helix(xi) -> (pitch, diameter, arclength) of the exponential's helix",
        ref=helix_ref, inputs=helix_inputs, arg_names=("xi",), shape=(3,),
        mistakes=[(lambda xi: helix_ref(xi) * np.array([1, 0.5, 1]),
                   "your second entry is the radius of the projected circle, not its diameter."),
                  (lambda xi: np.array([helix_ref(xi)[0], helix_ref(xi)[1],
                                        np.linalg.norm(np.asarray(xi, dtype=float))]),
                   "your arclength includes the rotational component: that is the length of the "
                   "helix in (x, y, theta) space, not of its projection onto the xy plane."),
                  (lambda xi: np.array([abs(helix_ref(xi)[0]), *helix_ref(xi)[1:]]),
                   "the pitch is signed: a negative w makes theta go down by 2 pi per turn.")],
        hints=["Project the flow onto the xy plane: its speed |(vx, vy)| is constant and its "
               "heading turns at the constant rate w. What curve is that?",
               "A curve of constant speed v and constant turning rate w is a circle of radius "
               "v/|w|. The pitch is the rise in theta during one full trip round that circle.",
               "In unit time the projected point travels the distance |(vx, vy)|."],
        solution_text="pitch = 2 pi sign(w) (theta rises one full turn per loop), diameter = "
                      "2 |(vx, vy)| / |w|, xy arclength in unit time = |(vx, vy)|."),
    CustomPart(
        "d", "Four numerical routes to exp: dict of functions f(xi, n)", routes_probes, routes_judge,
        hints=["Euler on the left field: g <- g + (1/n) T_e L_g xi, n times. On the right field use "
               "T_e R_g instead.",
               "Cumulative product: multiply n copies of (I + xi_hat / n). Taylor: sum xi_hat^k / k! "
               "for k < n.",
               "Return either (x, y, theta) or the 3x3 matrix; theta is read with arctan2 from a "
               "matrix."],
        solution_text="Euler (both fields) and the product converge like 1/n; the Taylor sum "
                      "converges factorially. See the plot in the worked solution.",
        reference=EXP_METHODS, wrong=[{"euler_left": lambda xi, n: SE2.exp(xi),
                                "euler_right": lambda xi, n: SE2.exp(xi),
                                "product": lambda xi, n: SE2.exp(xi),
                                "taylor": lambda xi, n: SE2.exp(xi)}],
        starter={"euler_left": None, "euler_right": None, "product": None, "taylor": None}),
    ChoicePart(
        "d_rates", "How fast do the methods converge?",
        {"a": "All four converge at the same rate: the error halves when n doubles",
         "b": "Taylor: error ~ 1/n; Euler and the cumulative product converge factorially",
         "c": "Euler on the right-invariant field is exact for every n; the other three converge like 1/n",
         "d": "Euler (both fields) and the product: error ~ 1/n; Taylor: faster than any power of 1/n"},
        "d",
        feedback={"d": "Correct: the first three are first-order methods; the Taylor tail is bounded "
                       "by |xi|^n/n!.",
                  "a": "Look at the Taylor curve on a log scale: it drops off a cliff.",
                  "b": "Swap them: the Taylor remainder shrinks like |xi|^n / n!.",
                  "c": "Its error halves when n doubles, like the left field's."},
        hints=["Plot the error against n on log-log axes: a straight line of slope -1 is first order."]),
    ChoicePart(
        "d_meaning", "What are the intermediate values of the cumulative product?",
        {"a": "Points near the geodesic at times k/n: the partial products trace the path",
         "b": "The partial Taylor sums, not the products, are the points of the geodesic at times k/n",
         "c": "Nothing until all n factors are in: only the complete product approximates exp(xi)",
         "d": "The body velocities at each step, which stay equal to xi all along the product"},
        "a",
        feedback={"a": "Correct: each factor is a small step 'from where we are', so the running "
                       "product after k factors approximates exp((k/n) xi), a discretised "
                       "trajectory (compare (1.xxvii)).",
                  "b": "A partial Taylor sum is not even a rigid motion: its 2x2 block is not a "
                       "rotation. It has no meaning as a point on the path.",
                  "c": "Look at what k factors of a unit-time step of length 1/n add up to.",
                  "d": "The body velocity is the same xi at every step; the products are positions."},
        hints=["What does the product of the first k factors approximate, if all n give exp(xi_hat)?"]),
])


# ============================================================================ 1.5
class SlideRuleExercise(Exercise):
    """Exercise 1.5 comes with an interactive slide rule: ``ex1_5.slide_rule(a, b)``."""

    def slide_rule(self, a: float = 2.0, b: float = 3.0) -> ipywidgets.VBox:
        """Two log scales that slide past each other (ipywidgets; the course's slide rule drawing)."""
        from gm_core.checks.views import slide_rule
        return slide_rule(a, b)


ex1_5 = SlideRuleExercise("1.5", "The slide rule and the isomorphism log: (R+, x) -> (R, +)", [
    ChoicePart(
        "a", "How does a slide rule compute products?",
        {"a": "Its scales are uniform; sliding adds a + b, and a printed table turns sums into products",
         "b": "Each scale marks x at the distance exp(x) from its index, and sliding multiplies distances",
         "c": "Each scale marks x at the distance log(x); sliding adds distances: log a + log b = log ab",
         "d": "It multiplies by repeated addition: the slide is moved along b times by the length of a"},
        "c",
        feedback={"c": "Correct: the log map is an isomorphism (1.xii), so adding lengths in (R, +) "
                       "is multiplying numbers in (R+, x).",
                  "a": "Look at a real C/D scale: the gap from 1 to 2 is much larger than from 9 to 10.",
                  "b": "Exp would turn products into sums the other way round; distances on the rule "
                       "are added, not multiplied.",
                  "d": "One slide, one reading: no repetition involved."},
        hints=["Try the slide rule widget: ex1_5.slide_rule().",
               "Where is the mark '2' on the scale, as a fraction of the distance from 1 to 10?"]),
    FunctionPart(
        "b", "offset(a): how far (as a fraction of the 1-to-10 scale length) to slide the C scale to "
             "multiply by a, for 1 <= a <= 10",
        ref=lambda a: np.log10(a), arg_names=("a",), shape=(),
        inputs=rng_inputs(16, 6, lambda rng: (float(rng.uniform(1, 10)),), edges=[(1.0,), (10.0,), (2.0,)]),
        sympy_names=("a",),
        mistakes=[(lambda a: np.log(a), "you used the natural logarithm; the scale runs one decade "
                   "(1 to 10), so the fraction is a base-10 logarithm."),
                  (lambda a: (a - 1) / 9, "that is a uniform (linear) scale; slide rule scales are "
                   "logarithmic."),
                  (lambda a: a / 10, "that is a uniform (linear) scale; slide rule scales are "
                   "logarithmic.")],
        hints=["The whole scale, from 1 to 10, has length 1. Where is the mark for a?",
               "The mark for 10 is at 1 and the mark for 1 is at 0, and equal ratios are equal "
               "distances."],
        solution_text="offset(a) = log10(a)."),
    ChoicePart(
        "c", "Why is it interesting that the isomorphism is exp/log?",
        {"a": "It is not: any bijection would work equally well; exp and log are only the familiar choice",
         "b": "log inverts the exponential of the commutative group (R+, x); on SE(2) exp(a) exp(b) != exp(a + b)",
         "c": "Because exp(a + b) = exp(a) exp(b) holds on every Lie group, so slide rules exist for every one of them",
         "d": "Because log is a linear function, so it turns the products of numbers into sums of lengths"},
        "b",
        feedback={"b": "Correct: the rule computes in the Lie algebra (R, +) of a commutative group, "
                       "where exp(a + b) = exp(a) exp(b). For non-commuting elements the product "
                       "exp(a) exp(b) picks up correction terms (the Lie bracket), so no such rule "
                       "exists on SE(2).",
                  "a": "A bijection must also turn the group operation into addition, (1.x); that "
                       "singles out log up to a constant factor (the base).",
                  "c": "Try it on SE(2): exp of (1, 0, 0) then (0, 0, pi/2) is not exp of their sum.",
                  "d": "log is far from linear; it turns multiplication into addition."},
        hints=["Compare the unit-time flow on (R+, x) in section 1.6.4 with the slide rule's scales.",
               "Is exp(a) exp(b) = exp(a + b) true on SE(2)? Try a = (1, 0, 0), b = (0, 0, pi/2)."]),
])

__all__ = ["ex1_1", "ex1_2", "ex1_3", "ex1_4", "ex1_5"]

"""Checkers for the chapter 1 exercises (1.1-1.5): configuration spaces, lifted actions, exp.

What a right answer is (references, mistakes, judges, correct options, solution texts) lives in
:mod:`gm_core.checks.keys.ex1`."""
from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from gm_core.checks.answers import is_starter, is_sympy, to_numbers
from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import Exercise
from gm_core.checks.exp_routes import exp_part, helix_inputs, routes_probes
from gm_core.checks.parts import CustomPart, FunctionPart, TuplePart, probe_rng, rng_inputs
from gm_core.checks.sandbox import Probe, Unattempted, Wrong
from gm_core.groups import SE2

if TYPE_CHECKING:
    import ipywidgets

    from gm_core.validation import FloatArray


# ============================================================================ 1.1
ex1_1 = Exercise("1.1", "Configuration spaces of a universal joint and an offset universal joint", [
    ChoicePart(
        "a", "Configuration space of a universal joint (two intersecting revolute axes)",
        {"a": "R^2, the plane",
         "b": "T^2 = S^1 x S^1, the torus",
         "c": "S^2, the sphere",
         "d": "SO(3), all rotations in space",
         "e": "S^1, the circle"},
        hints=["Count the independent ways the output shaft can move relative to the input shaft.",
               "Each of those motions is a rotation. Section 1.1 says what decides whether a "
               "rotation's space is R^1 or S^1.",
               "A space of two independent cyclic coordinates is a direct product of two circles."]),
    ChoicePart(
        "b", "Configuration space when the two rotation axes do not intersect",
        {"a": "R^2 x S^1, because the offset between the axes adds a translation",
         "b": "SE(2), because the output shaft now translates as well as rotates",
         "c": "Still T^2: only the forward kinematics (where the output link is) changes",
         "d": "T^2 x R, with one extra dimension that measures the offset between the two axes"},
        hints=["Does the offset between the axes change while the joint moves?",
               "The configuration space is set by the independent coordinates and their character "
               "(line or circle), not by where the parts end up in space."]),
])


# ============================================================================ 1.2
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
        inputs=_scaling_inputs, arg_names=("h", "g"), shape=(2, 2),
        sympy_names=_hg_names, sympy_args=_hg_flat,
        hints=["Write the action in the two parameters, (g1, g2) -> (h1 g1, h2 g2), then take the "
               "2x2 Jacobian with respect to (g1, g2), as in (1.20)-(1.22).",
               "Each output depends on one input only, so the Jacobian is diagonal; compare the "
               "one-dimensional result (1.24)."],
        starter=None)


ex1_2 = Exercise("1.2", "Group and lifted actions of the scaling matrices diag(R+, R+)", [
    FunctionPart(
        "a", "The group action: parameters (h1 g1, h2 g2) of h g for h = diag(h1, h2), g = diag(g1, g2)",
        inputs=_scaling_inputs,
        arg_names=("h", "g"), shape=(2,), postprocess=_diag_params,
        sympy_names=_hg_names, sympy_args=_hg_flat,
        hints=["Multiply the two diagonal matrices.",
               "The product of diagonal matrices is diagonal; read off its two entries."]),
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


def _rp(label: str) -> tuple[str, FunctionPart]:
    return label, FunctionPart(label, label, inputs=_rplus_inputs, arg_names=("g",), shape=(1, 1))


def _se(label: str) -> tuple[str, FunctionPart]:
    return label, FunctionPart(label, label, inputs=_se2_inputs, arg_names=("g",),
                               shape=(3, 3), sympy_names=("x", "y", "theta"),
                               sympy_args=lambda g: (g[0], g[1], g[2]))


#: The four lifted actions of 1.3(a) and (b), in the order of the answer's tuple.
LIFTED_LABELS = ("T_g L_{g^-1}", "T_e L_g", "T_g R_{g^-1}", "T_e R_g")

#: The four products of 1.3(c), in the order of the answer's tuple.
PRODUCT_LABELS = ("T_g L_{g^-1} T_e L_g on (R+, x)", "T_g R_{g^-1} T_e R_g on (R+, x)",
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
        raise Wrong(f"{PRODUCT_LABELS[i]} is still None.")
    symbols = sorted(getattr(item, "free_symbols", ()), key=str) if is_sympy(item) else []
    if symbols:
        # still symbolic: its value at a point drawn from the probe salt says whether it is right
        rng = probe_rng(33)
        point = {x: float(rng.uniform(0.5, 2.0)) for x in symbols}
        try:
            value = to_numbers(item.subs(point), PRODUCT_LABELS[i])
        except Exception:  # noqa: BLE001 - left symbolic in a way that has no value
            value = None
        return [[str(x) for x in symbols], value]
    return [[], to_numbers(item, PRODUCT_LABELS[i])]


ex1_3 = Exercise("1.3", "T_g L_{g^-1} = (T_e L_g)^-1 and T_g R_{g^-1} = (T_e R_g)^-1", [
    TuplePart(
        "a", "On (R+, x): the four lifted actions as functions of g",
        [_rp(label) for label in LIFTED_LABELS],
        hints=["On (R+, x) the lifted actions of h are multiplication by h, (1.24)-(1.25).",
               "Put h = g^-1 (acting at g) and h = g (acting at e = 1)."],
        starter=(None, None, None, None)),
    TuplePart(
        "b", "On SE(2): the four lifted actions as 3x3 matrices, functions of g = (x, y, theta)",
        [_se(label) for label in LIFTED_LABELS],
        hints=["Use (1.31) for T_g L_h and (1.37) for T_g R_h: they depend only on h (left) or on "
               "h and the angle of g (right).",
               "For the right actions, put h = g^-1 = (-x cos t - y sin t, x sin t - y cos t, -t) "
               "into (1.37) at the point g, and h = g into (1.37) at the point e = (0, 0, 0).",
               "Compare your T_g R_{g^-1} with the first factor of (1.42)."],
        starter=(None, None, None, None)),
    CustomPart(
        "c", "Show the identities: the four products, simplified: (T_g L_{g^-1} T_e L_g, "
             "T_g R_{g^-1} T_e R_g) on (R+, x), then the same two on SE(2)",
        _product_probes,
        hints=["Multiply the pairs from parts (a) and (b) in the order T_g L_{g^-1} times T_e L_g.",
               "sp.simplify(M1 * M2) on SE(2): the sines and cosines combine through "
               "cos^2 + sin^2 = 1."],
        starter=(None, None, None, None), weight=1.0),
])


# ============================================================================ 1.4

ex1_4 = Exercise("1.4", "The exponential map on SE(2)", [
    exp_part("a", "left"),
    exp_part("b", "right"),
    FunctionPart(
        "c", "helix(xi) -> (pitch, diameter, arclength) of the exponential's helix",
        inputs=helix_inputs, arg_names=("xi",), shape=(3,),
        hints=["Project the flow onto the xy plane: its speed |(vx, vy)| is constant and its "
               "heading turns at the constant rate w. What curve is that?",
               "A curve of constant speed v and constant turning rate w is a circle of radius "
               "v/|w|. The pitch is the rise in theta during one full trip round that circle.",
               "In unit time the projected point travels the distance |(vx, vy)|."]),
    CustomPart(
        "d", "Four numerical routes to exp: dict of functions f(xi, n)", routes_probes,
        hints=["Euler on the left field: g <- g + (1/n) T_e L_g xi, n times. On the right field use "
               "T_e R_g instead.",
               "Cumulative product: multiply n copies of (I + xi_hat / n). Taylor: sum xi_hat^k / k! "
               "for k < n.",
               "Return either (x, y, theta) or the 3x3 matrix; theta is read with arctan2 from a "
               "matrix."],
        starter={"euler_left": None, "euler_right": None, "product": None, "taylor": None}),
    ChoicePart(
        "d_rates", "How fast do the methods converge?",
        {"a": "All four converge at the same rate: the error halves when n doubles",
         "b": "Taylor: error ~ 1/n; Euler and the cumulative product converge factorially",
         "c": "Euler on the right-invariant field is exact for every n; the other three converge like 1/n",
         "d": "Euler (both fields) and the product: error ~ 1/n; Taylor: faster than any power of 1/n"},
        hints=["Plot the error against n on log-log axes: a straight line of slope -1 is first order."]),
    ChoicePart(
        "d_meaning", "What are the intermediate values of the cumulative product?",
        {"a": "Points near the geodesic at times k/n: the partial products trace the path",
         "b": "The partial Taylor sums, not the products, are the points of the geodesic at times k/n",
         "c": "Nothing until all n factors are in: only the complete product approximates exp(xi)",
         "d": "The body velocities at each step, which stay equal to xi all along the product"},
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
        hints=["Try the slide rule widget: ex1_5.slide_rule().",
               "Where is the mark '2' on the scale, as a fraction of the distance from 1 to 10?"]),
    FunctionPart(
        "b", "offset(a): how far (as a fraction of the 1-to-10 scale length) to slide the C scale to "
             "multiply by a, for 1 <= a <= 10",
        arg_names=("a",), shape=(),
        inputs=rng_inputs(16, 6, lambda rng: (float(rng.uniform(1, 10)),), edges=[(1.0,), (10.0,), (2.0,)]),
        sympy_names=("a",),
        hints=["The whole scale, from 1 to 10, has length 1. Where is the mark for a?",
               "The mark for 10 is at 1 and the mark for 1 is at 0, and equal ratios are equal "
               "distances."]),
    ChoicePart(
        "c", "Why is it interesting that the isomorphism is exp/log?",
        {"a": "It is not: any bijection would work equally well; exp and log are only the familiar choice",
         "b": "log inverts the exponential of the commutative group (R+, x); on SE(2) exp(a) exp(b) != exp(a + b)",
         "c": "Because exp(a + b) = exp(a) exp(b) holds on every Lie group, so slide rules exist for every one of them",
         "d": "Because log is a linear function, so it turns the products of numbers into sums of lengths"},
        hints=["Compare the unit-time flow on (R+, x) in section 1.6.4 with the slide rule's scales.",
               "Is exp(a) exp(b) = exp(a + b) true on SE(2)? Try a = (1, 0, 0), b = (0, 0, pi/2)."]),
])

__all__ = ["ex1_1", "ex1_2", "ex1_3", "ex1_4", "ex1_5", "LIFTED_LABELS", "PRODUCT_LABELS"]

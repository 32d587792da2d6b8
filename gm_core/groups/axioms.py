"""Group axioms checked numerically on any gm_core group, (1.ii)-(1.v), and repeated products.

numpy only. Nothing here asks which group it is: membership is the group's own
:meth:`~gm_core.groups.LieGroup.contains` and random elements its
:meth:`~gm_core.groups.LieGroup.random`, so a new group needs no change here.
"""
from __future__ import annotations

import itertools
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import check_group
from gm_core.groups.base import LieGroup
from gm_core.validation import FloatArray, check_int

__all__ = ["AXIOMS", "axiom_residuals", "powers", "GROUP_AXIOMS", "Structure", "AxiomReport",
           "STRUCTURES", "structure", "group_structure", "check_axioms", "find_identity", "is_group",
           "try_elements"]

#: The laws whose residuals :func:`axiom_residuals` reports (closure is reported as a bool).
AXIOMS = ("associativity", "identity", "inverse")


def axiom_residuals(G: LieGroup, rng: np.random.Generator | int, n: int = 20, scale: float = 1.0) -> dict[str, Any]:
    """Worst-case residuals of the group axioms (1.ii)-(1.v) over ``n`` random triples of G.

    Returns a dict: ``closure`` (bool: every product and inverse is again an element, by
    ``G.contains``) and, for associativity, identity and inverse, the largest coordinate
    difference (angles compared modulo their period, ``G.difference``) between the two sides of
    the law. ``scale`` stretches the random elements (``G.random(rng, n, scale=scale)``).
    """
    G = check_group(G, "G")
    n = check_int(n, "n", minimum=1, maximum=10**6, what=" (random triples)")
    g1, g2, g3 = (G.random(rng, n, scale=scale) for _ in range(3))
    e = G.identity((n,))
    closure = all(np.all(G.contains(G.compose(a, b))) for a, b in ((g1, g2), (g2, g3), (g1, g3)))
    closure = closure and np.all(G.contains(G.inverse(g1)))
    assoc = G.difference(G.compose(g1, G.compose(g2, g3)), G.compose(G.compose(g1, g2), g3))
    ident = np.maximum(np.abs(G.difference(G.compose(e, g1), g1)),
                       np.abs(G.difference(G.compose(g1, e), g1)))
    inv = np.maximum(np.abs(G.difference(G.compose(G.inverse(g1), g1), e)),
                     np.abs(G.difference(G.compose(g1, G.inverse(g1)), e)))
    return {"closure": bool(closure), "associativity": float(np.max(np.abs(assoc))),
            "identity": float(np.max(ident)), "inverse": float(np.max(inv))}


def powers(G: LieGroup, g: ArrayLike, n: int) -> FloatArray:
    """``(n + 1, dim)``: e, g, g o g, ..., g^n (the repeated step of fig. 1.10)."""
    G = check_group(G, "G")
    numeric = isinstance(n, (int, float, np.integer, np.floating)) and not isinstance(n, (bool, np.bool_))
    if numeric and np.isfinite(n) and (n < 0 or n != int(n)):
        raise ValueError(f"n must be a non-negative integer; got {n!r}")
    n = check_int(n, "n", minimum=0, maximum=10**6)
    g = G.project(g)
    if g.ndim != 1:
        raise ValueError(f"g must be a single element of {G.name} (shape ({G.param_dim},)); got shape {g.shape}")
    out = [G.identity()]
    for _ in range(int(n)):
        out.append(G.compose(out[-1], g))
    return np.array(out)


# ====================================================================== group or not? (1.ii)-(1.v)
#: The four axioms of the group box, in the book's order.
GROUP_AXIOMS = ("closure", "associativity", "identity", "inverse")


class Structure:
    """A set with a binary operation, to be tested against the group axioms (1.ii)-(1.v).

    ``op(a, b)`` combines two elements; ``member(x)`` says whether ``x`` is in the set;
    ``pool`` is a short list of members the axioms are tried on (in that order, so the first
    counterexample found is a readable one); ``solve_right(a, b)`` / ``solve_left(a, b)``
    return the unique ``x`` in the ambient number system (or group) with ``a o x = b`` /
    ``x o a = b``, or None when there is none or not a unique one; ``equal(a, b)`` compares
    elements; ``fmt(x)`` writes one; ``element(s, k)`` turns a slider value ``s`` into the
    ``k``-th element tried by the user (the value itself for numbers). ``symbol`` is the
    operation's sign in formulas and ``set_name`` the set's name. ``integer`` says that every
    member is an integer (a control offering elements should offer whole numbers only).
    """

    def __init__(self, name, set_name, symbol, op, member, pool, solve_right, solve_left,
                 equal=None, fmt=None, element=None, integer=False):
        self.integer = bool(integer)
        self.name, self.set_name, self.symbol = name, set_name, symbol
        self.op, self.member, self.pool = op, member, list(pool)
        self.solve_right, self.solve_left = solve_right, solve_left
        self.equal = equal or (lambda a, b: bool(np.isclose(a, b, rtol=1e-12, atol=1e-12)))
        self.fmt = fmt or _fmt_number
        self.element = element or (lambda s, k: float(s))

    @override
    def __repr__(self):
        return f"Structure({self.name!r})"

    def show(self, a: Any, b: Any) -> str:
        """``'a o b'`` with both elements written out."""
        return f"{self.fmt(a)} {self.symbol} {self.fmt(b)}"


class AxiomReport:
    """One axiom's verdict on a :class:`Structure`: ``holds`` (bool), ``witness`` (the elements of
    a counterexample, or ()), ``why`` (one or two short lines saying what goes wrong or what
    was checked)."""

    def __init__(self, axiom, holds, why, witness=()):
        self.axiom, self.holds, self.why, self.witness = axiom, bool(holds), why, tuple(witness)

    @override
    def __repr__(self):
        return f"AxiomReport({self.axiom!r}, holds={self.holds}, why={self.why!r})"


def _fmt_number(x):
    if x is None:
        return "none"
    x = float(x)
    if x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    return f"{x:.4g}"


def _is_integer(x):
    x = float(x)
    return np.isfinite(x) and x.is_integer()


def _div(b, a):
    return None if a == 0 else b / a


def _number_structure(name, set_name, symbol, op, member, pool, solve_right, solve_left, integer=False):
    return Structure(name, set_name, symbol, op, member, pool, solve_right, solve_left, integer=integer)


def group_structure(G: LieGroup, name: str | None = None, set_name: str | None = None, seed: int = 0,
                    n: int = 4) -> Structure:
    """A :class:`Structure` made from one of gm_core's Lie groups (compose, inverse, contains).

    The pool is ``n`` random elements (seeded); a user's slider value ``s`` becomes the element
    exp(s * xi_k) along one of three fixed Lie-algebra directions, so any group can be tried.
    """
    G = check_group(G, "G")
    seed = check_int(seed, "seed", minimum=0, maximum=2**32)
    n = check_int(n, "n", minimum=1, maximum=1000, what=" (elements in the pool)")
    rng = np.random.default_rng(seed)
    directions = np.random.default_rng(seed + 1).normal(size=(3, G.dim))
    pool = list(G.random(rng, n))

    def fmt(x):
        x = np.asarray(x, float)
        return "(" + ", ".join(f"{v:.2f}" for v in x) + ")" if x.size > 1 else f"{float(x[0]):.3g}"

    return Structure(name or str(G.name), set_name or name or str(G.name), "∘", G.compose, lambda x: bool(np.all(G.contains(x))), pool,
                     lambda a, b: G.compose(G.inverse(a), b), lambda a, b: G.compose(b, G.inverse(a)),
                     equal=lambda a, b: bool(np.all(G.isclose(a, b, atol=1e-9))), fmt=fmt,
                     element=lambda s, k: G.exp(float(s) * directions[k % 3]))


def _structures():
    from gm_core.groups import SE2

    def sub(a, b):
        return a - b

    S = {
        "(ℤ, +)": _number_structure("(ℤ, +)", "ℤ", "+", np.add, _is_integer, [2, 3, -1, 0, 5],
                                    lambda a, b: b - a, lambda a, b: b - a, integer=True),
        "(ℝ⁺, ×)": _number_structure("(ℝ⁺, ×)", "ℝ⁺", "×", np.multiply, lambda x: np.isfinite(x) and x > 0,
                                     [2.0, 0.5, 3.0, 1.0], lambda a, b: _div(b, a), lambda a, b: _div(b, a)),
        "(ℤ, ×)": _number_structure("(ℤ, ×)", "ℤ", "×", np.multiply, _is_integer, [1, 2, 3, -1, 0],
                                    lambda a, b: _div(b, a), lambda a, b: _div(b, a), integer=True),
        "(ℝ⁺, +)": _number_structure("(ℝ⁺, +)", "ℝ⁺", "+", np.add, lambda x: np.isfinite(x) and x > 0,
                                     [2.0, 0.5, 3.0], lambda a, b: b - a, lambda a, b: b - a),
        "(ℝ, −)": _number_structure("(ℝ, −)", "ℝ", "−", sub, lambda x: bool(np.isfinite(x)), [3.0, 2.0, 1.0, 0.5],
                                    lambda a, b: a - b, lambda a, b: b + a),
        "(ℝ, ×)": _number_structure("(ℝ, ×)", "ℝ", "×", np.multiply, lambda x: bool(np.isfinite(x)),
                                    [2.0, -1.0, 0.0, 0.5], lambda a, b: _div(b, a), lambda a, b: _div(b, a)),
        "(odd ℤ, +)": _number_structure("(odd ℤ, +)", "odd ℤ", "+", np.add,
                                        lambda x: _is_integer(x) and int(x) % 2 == 1, [1, 3, -1],
                                        lambda a, b: b - a, lambda a, b: b - a, integer=True),
        "SE(2)": group_structure(SE2, "SE(2)"),
    }
    return S


#: Candidate structures for the "group or not?" explorer: real groups and famous failures.
STRUCTURES = _structures()


def structure(name: str | Structure) -> Structure:
    """The :class:`Structure` called ``name`` (a key of :data:`STRUCTURES`)."""
    if isinstance(name, Structure):
        return name
    if name not in STRUCTURES:
        raise ValueError(f"unknown structure {name!r}: name must be one of {sorted(STRUCTURES)}")
    return STRUCTURES[name]


def _closure(S):
    for a in S.pool:
        for b in S.pool:
            c = S.op(a, b)
            if not S.member(c):
                return AxiomReport("closure", False, f"{S.show(a, b)} = {S.fmt(c)} is not in {S.set_name}", (a, b))
    return AxiomReport("closure", True, f"every a {S.symbol} b tried lands in {S.set_name}")


def _associativity(S):
    n = len(S.pool)
    # distinct triples first: their counterexamples read best, e.g. (3 - 2) - 1 vs 3 - (2 - 1)
    triples = sorted(itertools.product(range(n), repeat=3), key=lambda t: len(set(t)) < 3)
    for i, j, k in triples:
        a, b, c = S.pool[i], S.pool[j], S.pool[k]
        left, right = S.op(S.op(a, b), c), S.op(a, S.op(b, c))
        if not S.equal(left, right):
            return AxiomReport("associativity", False,
                           f"({S.show(a, b)}) {S.symbol} {S.fmt(c)} = {S.fmt(left)}, but\n"
                           f"{S.fmt(a)} {S.symbol} ({S.show(b, c)}) = {S.fmt(right)}", (a, b, c))
    return AxiomReport("associativity", True, "(a∘b)∘c = a∘(b∘c) for every triple tried".replace("∘", S.symbol))


def find_identity(S: Structure) -> tuple[Any, AxiomReport]:
    """``(e, verdict)``: the two-sided identity of ``S`` (None if it has none) and its AxiomReport.

    For each pool element a, the only right identity candidate is the solution of a o x = a and
    the only left one that of x o a = a (``S.solve_right`` / ``S.solve_left``); an identity
    must be one element, the same from both sides for every a, and belong to the set.
    """
    right = [(a, S.solve_right(a, a)) for a in S.pool]
    left = [(a, S.solve_left(a, a)) for a in S.pool]
    right = [(a, x) for a, x in right if x is not None]
    left = [(a, x) for a, x in left if x is not None]
    if not right or not left:
        return None, AxiomReport("identity", False, "a∘x = a has no unique solution")
    (a0, e), sym = right[0], S.symbol
    for a, x in right[1:]:
        if not S.equal(x, e):
            return None, AxiomReport("identity", False, f"{S.fmt(a0)} {sym} x = {S.fmt(a0)} needs x = {S.fmt(e)},\n"
                                 f"but {S.fmt(a)} {sym} x = {S.fmt(a)} needs x = {S.fmt(x)}", (a0, a))
    for a, x in left:
        if not S.equal(x, e):
            return e, AxiomReport("identity", False,
                                 f"{S.fmt(e)} works on the right ({S.fmt(a)} {sym} {S.fmt(e)} = {S.fmt(a)}), but\n"
                                 f"{S.show(e, a)} = {S.fmt(S.op(e, a))} ≠ {S.fmt(a)}: no two-sided identity",
                                 (e, a))
    if not S.member(e):
        return e, AxiomReport("identity", False, f"a {sym} x = a forces x = {S.fmt(e)}, which is not in {S.set_name}",
                          (e,))
    return e, AxiomReport("identity", True, f"e = {S.fmt(e)}: e {sym} a = a {sym} e = a for every a tried")


def _inverse(S, e, identity):
    sym = S.symbol
    if e is None:
        return AxiomReport("inverse", False, "no identity e, so a∘x = e has\nnothing to aim at".replace("∘", sym))
    for a in S.pool:
        x = S.solve_right(a, e)
        if x is None:
            return AxiomReport("inverse", False, f"{S.fmt(a)} {sym} x = {S.fmt(e)} has no solution at all", (a,))
        if not S.member(x):
            lead = "" if identity.holds else f"(even borrowing e = {S.fmt(e)}) "
            return AxiomReport("inverse", False,
                           f"{lead}{S.fmt(a)} {sym} x = {S.fmt(e)} needs x = {S.fmt(x)},\nwhich is not in {S.set_name}",
                           (a, x))
        y = S.solve_left(a, e)
        if y is None or not S.equal(x, y):
            return AxiomReport("inverse", False, f"{S.fmt(a)} is undone by {S.fmt(x)} on the right but not on the left",
                           (a, x))
    if not identity.holds:
        return AxiomReport("inverse", False, "no identity in the set: inverses\nare not defined")
    return AxiomReport("inverse", True, f"every a tried has an a⁻¹ with a {sym} a⁻¹ = a⁻¹ {sym} a = e")


def check_axioms(S: str | Structure) -> dict[str, AxiomReport]:
    """Verdicts ``{axiom: AxiomReport}`` of the four group axioms (1.ii)-(1.v) on a :class:`Structure`
    (or a name from :data:`STRUCTURES`), each failing one with a concrete counterexample from
    the structure's pool. A structure is a group when every verdict holds.
    """
    S = structure(S)
    e, ident = find_identity(S)
    return {"closure": _closure(S), "associativity": _associativity(S), "identity": ident,
            "inverse": _inverse(S, e, ident)}


def is_group(S: str | Structure) -> bool:
    """True if every axiom of :func:`check_axioms` holds on the pool of ``S``."""
    return all(v.holds for v in check_axioms(S).values())


def try_elements(S: str | Structure, a: Any, b: Any, c: Any) -> dict[str, str]:
    """The axioms written out at the user's elements ``a, b, c`` (slider values turned into
    elements by ``S.element``): a dict of one-line strings, each led by "✓" or "✗"."""
    S = structure(S)
    a, b, c = (S.element(v, k) for k, v in enumerate((a, b, c)))
    sym, out = S.symbol, {}
    outside = [f"{n} = {S.fmt(v)}" for n, v in zip("abc", (a, b, c)) if not S.member(v)]
    ab = S.op(a, b)
    if outside:
        out["closure"] = "✗ " + ", ".join(outside) + f" ∉ {S.set_name}"
    else:
        out["closure"] = ("✓ " if S.member(ab) else "✗ ") + f"a {sym} b = {S.fmt(ab)}" + (
            "" if S.member(ab) else f" ∉ {S.set_name}")
    left, right = S.op(ab, c), S.op(a, S.op(b, c))
    out["associativity"] = ("✓ " if S.equal(left, right) else "✗ ") + \
        f"(a{sym}b){sym}c = {S.fmt(left)}, a{sym}(b{sym}c) = {S.fmt(right)}"
    e, ident = find_identity(S)
    if e is None:
        out["identity"] = f"✗ a {sym} x = a has no single answer x"
        out["inverse"] = "✗ no e to undo to"
        return out
    ea, ae = S.op(e, a), S.op(a, e)
    ok = S.equal(ea, a) and S.equal(ae, a) and S.member(e)
    out["identity"] = ("✓ " if ok else "✗ ") + f"e = {S.fmt(e)}: e{sym}a = {S.fmt(ea)}, a{sym}e = {S.fmt(ae)}" + (
        "" if S.member(e) else f"; e ∉ {S.set_name}")
    x = S.solve_right(a, e)
    if x is None:
        out["inverse"] = f"✗ a {sym} x = {S.fmt(e)} has no solution"
    else:
        good = S.member(x) and ident.holds and S.member(a)
        out["inverse"] = ("✓ " if good else "✗ ") + f"a {sym} x = {S.fmt(e)} gives x = {S.fmt(x)}" + (
            "" if S.member(x) else f" ∉ {S.set_name}")
    return out

"""Group axioms checked numerically on any gm_core group, (1.ii)-(1.v), and repeated products.

numpy only. Nothing here asks which group it is: membership is read from the group's own
``log``/``exp`` (:func:`is_element`), and elements are scaled inside the Lie algebra
(:func:`scaled`), so a new group needs no change here.
"""
from __future__ import annotations

import numpy as np

from .groups import check_group

__all__ = ["AXIOMS", "is_element", "scaled", "axiom_residuals", "powers"]

#: The laws whose residuals :func:`axiom_residuals` reports (closure is reported as a bool).
AXIOMS = ("associativity", "identity", "inverse")


def is_element(G, g, tol=1e-9):
    """True if every row of ``g (..., dim)`` is an element of ``G``.

    Provisional, group-agnostic test (until the groups carry their own membership method):
    ``g`` must have the group's coordinate shape, be finite, be accepted by ``G.log`` and
    satisfy ``exp(log g) = g`` to a relative ``tol`` (angles compared modulo their period by
    ``G.difference``). Outside
    the group (a negative number for (R+, x)) ``log`` refuses or returns a non-finite value.
    """
    G = check_group(G, "G")
    g = np.asarray(g, float)
    if g.ndim == 0 or g.shape[-1] != G.dim or not np.all(np.isfinite(g)):
        return False
    try:
        with np.errstate(invalid="ignore", divide="ignore"):
            xi = G.log(g)
        if not np.all(np.isfinite(xi)):
            return False
        # relative tolerance: exp(log g) carries round-off proportional to the size of g
        return bool(np.all(np.abs(G.difference(G.exp(xi), g)) <= tol * (1.0 + np.abs(g))))
    except ValueError:
        return False


def scaled(G, g, s):
    """The element exp(s log g): ``g`` moved ``s`` times as far along its one-parameter subgroup.

    For (R+, x) this is g**s, for the additive groups s*g; used to try the axioms on larger or
    smaller elements.
    """
    G = check_group(G, "G")
    return G.exp(float(s) * G.log(g))


def axiom_residuals(G, rng, n=20, scale=1.0):
    """Worst-case residuals of the group axioms (1.ii)-(1.v) over ``n`` random triples of G.

    Returns a dict: ``closure`` (bool: every product and inverse is again an element, by
    :func:`is_element`) and, for associativity, identity and inverse, the largest coordinate
    difference (angles compared modulo their period, ``G.difference``) between the two sides of
    the law. ``scale`` scales the random elements in the Lie algebra (:func:`scaled`).
    """
    G = check_group(G, "G")
    g1, g2, g3 = (G.random(rng, n) for _ in range(3))
    if scale != 1.0:
        g1, g2, g3 = (scaled(G, g, scale) for g in (g1, g2, g3))
    e = G.identity((n,))
    closure = all(is_element(G, G.compose(a, b)) for a, b in ((g1, g2), (g2, g3), (g1, g3)))
    closure = closure and is_element(G, G.inverse(g1))
    assoc = G.difference(G.compose(g1, G.compose(g2, g3)), G.compose(G.compose(g1, g2), g3))
    ident = np.maximum(np.abs(G.difference(G.compose(e, g1), g1)),
                       np.abs(G.difference(G.compose(g1, e), g1)))
    inv = np.maximum(np.abs(G.difference(G.compose(G.inverse(g1), g1), e)),
                     np.abs(G.difference(G.compose(g1, G.inverse(g1)), e)))
    return {"closure": bool(closure), "associativity": float(np.max(np.abs(assoc))),
            "identity": float(np.max(ident)), "inverse": float(np.max(inv))}


def powers(G, g, n):
    """``(n + 1, dim)``: e, g, g o g, ..., g^n (the repeated step of fig. 1.10)."""
    G = check_group(G, "G")
    if isinstance(n, bool) or int(n) != n or n < 0:
        raise ValueError(f"n must be a non-negative integer; got {n!r}")
    out = [G.identity()]
    for _ in range(int(n)):
        out.append(G.compose(out[-1], g))
    return np.array(out)

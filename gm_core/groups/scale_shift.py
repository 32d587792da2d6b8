"""The scale-shift group R+ x| R of affine maps x -> a x + b of the line, book (1.xviii)-(1.xix) (numpy only).

An element g = (a, b), a > 0, is the map x -> a x + b, with matrix [[a, b], [0, 1]] acting on
[x, 1]. The product is the composition of maps, g o h = (a_g a_h, a_g b_h + b_g): the scale of g
acts on the shift of h, the semi-direct product (1.xix) of (R+, x) with (R, +). These are the
conventions of the author's own code (rlhatton/GeometryOfMotionCodebase), where this group is the
running example of chapters 1 and 2:

* ``Chapter_1_Examples/S275_Construct_RxRplus.py`` and ``Chapter_2_Examples/S500_Construct_RxRplus.py``:
  ``scale_shift_action`` (the product above, coordinates in the order (a, b), identity [1, 0])
  and ``scale_shift_inverse`` (1/a, -b/a);
* ``Chapter_1_Examples/S280_Construct_RxRplus_rep.py``: ``scale_shift_rep`` [[a, b], [0, 1]] and
  ``scale_shift_derep``, which reads (a, b) from the top row (our :meth:`nearest_element`);
* ``geomotion/group.py``: ``L`` is x -> g x and ``R`` is x -> x g; ``geomotion/liegroup.py`` lifts
  them (``TL``, ``TR``), which ``Chapter_2_Examples/E510_scale_shift_lifted_actions.py`` draws
  as the left- and right-invariant fields;
* ``geomotion/representationliegroup.py``: the algebra vector (u, v) is the matrix
  [[u, v], [0, 0]] (the Jacobian of the representation at e), ``exp_L``/``exp_R`` are
  ``scipy.linalg.expm`` of it and ``log`` is ``logm``; ``Chapter_2_Examples/E650_scale_shift_exponentiation.py``
  shows that the left and right flows from e reach the same exp(xi), the group geodesic.

Closed forms (phi(u) = (e^u - 1)/u, computed as ``expm1(u)/u``, with no cancellation near u = 0):
T_g L_h = a_h I, T_g R_h = [[a_h, 0], [b_h, 1]] (1.20)-(1.21); Ad_g = [[1, 0], [-b, a]] (1.40);
exp(u, v) = (e^u, v phi(u)), the closed form of expm (1.49); log(a, b) = (ln a, b ln a / (a - 1));
[xi1, xi2] = (0, u1 v2 - u2 v1).
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups.base import LieGroup, as_rng, check_entries, check_scale
from gm_core.validation import FloatArray, as_array, check_option, check_shape, real_number

__all__ = ["ScaleShift"]


def _phi(u):
    """(e^u - 1)/u with the value 1 at u = 0, accurate to a few ulps for every u (unchecked)."""
    with np.errstate(over="ignore"):
        m = np.expm1(u)
    return m / u if u.all() else np.divide(m, u, out=np.ones_like(u), where=u != 0)


class _ScaleShift(LieGroup):
    """The scale-shift group R+ x| R: elements ``(..., 2)`` = (a, b), a > 0, the maps x -> a x + b.

    Every method refuses a <= 0 by name (:meth:`contains` tells without raising). All maps are
    closed forms vectorized over leading axes.
    """

    name = "R+ x| R"
    label = "R⁺⋉R"
    coords = ("a", "b")
    periods = (None, None)
    param_dim: ClassVar[int] = 2
    tangent_dim: ClassVar[int] = 2
    matrix_size: ClassVar[int] = 2

    @override
    def _element(self, g, name="g"):
        g = super()._element(g, name)
        if np.any(g[..., 0] <= 0):
            raise ValueError(f"{name} must have a positive scale a: elements (a, b) of the scale-shift "
                             f"group are maps x -> a x + b with a > 0")
        return g

    @override
    def _in_domain(self, g):
        return g[..., 0] > 0

    @override
    def _identity_coords(self):
        return np.array([1.0, 0.0])

    def _check_result(self, g, name, what):
        if not (np.all((g[..., 0] > 0) & (g[..., 0] < np.inf)) and np.all(np.isfinite(g[..., 1]))):
            raise ValueError(f"{name} {'are' if ' and ' in name else 'is'} out of range: {what} overflows (or its scale underflows to 0), "
                             f"so it is no element of the scale-shift group")

    @override
    def compose(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """g o h = (a_g a_h, a_g b_h + b_g), the map x -> g(h(x)); book (1.xix)."""
        g = self._element(g)
        h = self._element(h, "h")
        out = np.empty(g.shape if g.shape == h.shape else self._batch(("g", g), ("h", h)) + (2,))
        with np.errstate(over="ignore", under="ignore", invalid="ignore"):
            out[..., 0] = g[..., 0] * h[..., 0]
            out[..., 1] = g[..., 0] * h[..., 1] + g[..., 1]
        self._check_result(out, "g and h", "g o h")
        return out

    @override
    def inverse(self, g: ArrayLike) -> FloatArray:
        """g^-1 = (1/a, -b/a), the map x -> (x - b)/a."""
        g = self._element(g)
        out = np.empty(g.shape)
        with np.errstate(over="ignore", under="ignore", invalid="ignore"):
            np.divide(1.0, g[..., 0], out=out[..., 0])
            np.divide(-g[..., 1], g[..., 0], out=out[..., 1])
        self._check_result(out, "g", "g^-1")
        return out

    @override
    def left_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g L_h = a_h I: d(h g)/dg of (a_h a, a_h b + b_h), book (1.20)."""
        h = self._element(h, "h")
        g = self._element(g)
        M = np.zeros(self._batch(("h", h), ("g", g)) + (2, 2))
        M[..., 0, 0] = h[..., 0]
        M[..., 1, 1] = h[..., 0]
        return M

    @override
    def right_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g R_h = [[a_h, 0], [b_h, 1]]: d(g h)/dg of (a a_h, a b_h + b), book (1.21)."""
        h = self._element(h, "h")
        g = self._element(g)
        M = np.zeros(self._batch(("h", h), ("g", g)) + (2, 2))
        M[..., 0, 0] = h[..., 0]
        M[..., 1, 0] = h[..., 1]
        M[..., 1, 1] = 1.0
        return M

    @override
    def Ad(self, g: ArrayLike) -> FloatArray:
        """Ad_g = T_g R_{g^-1} T_e L_g = [[1, 0], [-b, a]], body to spatial velocity, book (1.40)."""
        g = self._element(g)
        M = np.zeros(g.shape[:-1] + (2, 2))
        M[..., 0, 0] = 1.0
        M[..., 1, 0] = -g[..., 1]
        M[..., 1, 1] = g[..., 0]
        return M

    @override
    def Ad_inv(self, g: ArrayLike) -> FloatArray:
        """Ad_g^-1 = Ad_{g^-1} = [[1, 0], [b/a, 1/a]], spatial to body velocity, book (1.41)."""
        g = self._element(g)
        M = np.zeros(g.shape[:-1] + (2, 2))
        M[..., 0, 0] = 1.0
        with np.errstate(over="ignore", under="ignore", invalid="ignore"):
            M[..., 1, 0] = g[..., 1] / g[..., 0]
            M[..., 1, 1] = 1.0 / g[..., 0]
        if not np.all(np.isfinite(M)):
            raise ValueError("g is out of range: Ad_g^-1 = Ad_{g^-1} overflows (1/a or b/a is too large)")
        return M

    @override
    def bracket(self, xi1: ArrayLike, xi2: ArrayLike) -> FloatArray:
        """[xi1, xi2] = (0, u1 v2 - u2 v1), the vee of the commutator of [[u, v], [0, 0]] matrices."""
        xi1 = self._algebra(xi1, "xi1")
        xi2 = self._algebra(xi2, "xi2")
        out = np.zeros(self._batch(("xi1", xi1), ("xi2", xi2)) + (2,))
        with np.errstate(over="ignore", invalid="ignore"):
            out[..., 1] = xi1[..., 0] * xi2[..., 1] - xi2[..., 0] * xi1[..., 1]
        if not np.all(np.isfinite(out)):
            raise ValueError("xi1 and xi2 are out of range: their bracket u1 v2 - u2 v1 overflows")
        return out

    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        """xi^ = [[u, v], [0, 0]] for xi = (u, v), ``(..., 2, 2)``: the derivative of [[a, b], [0, 1]] at e."""
        xi = self._algebra(xi)
        X = np.zeros(xi.shape[:-1] + (2, 2))
        X[..., 0, :] = xi
        return X

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        """(u, v) from a matrix [[u, v], [0, 0]]; ValueError if the bottom row of X is not zero."""
        X = self._square(X, "X")
        check_entries(X[..., 1, :], 0.0, "X", "a scale-shift algebra matrix [[u, v], [0, 0]]")
        return X[..., 0, :].copy()

    @override
    def exp(self, xi: ArrayLike) -> FloatArray:
        """exp(u, v) = (e^u, v (e^u - 1)/u), the matrix exponential (1.49) of [[u, v], [0, 0]].

        This is the unit-time flow from e along the left-invariant field (1.46) of xi, and along
        the right-invariant field (1.47) of the same xi. (e^u - 1)/u is ``expm1(u)/u`` (1 at u = 0),
        so the result is accurate to a few ulps for every u, including u -> 0. ValueError if e^u
        overflows or underflows to 0 (|u| > about 708) or v (e^u - 1)/u overflows.
        """
        xi = self._algebra(xi)
        u = xi[..., 0]
        out = np.empty(xi.shape)
        with np.errstate(over="ignore", under="ignore", invalid="ignore"):
            np.exp(u, out=out[..., 0])
            out[..., 1] = xi[..., 1] * _phi(u)
        self._check_result(out, "xi", "exp(xi)")
        return out

    @override
    def log(self, g: ArrayLike) -> FloatArray:
        """log(a, b) = (ln a, b ln a / (a - 1)) (b at a = 1), the inverse of :meth:`exp` (scipy's logm).

        No cancellation at a -> 1: a - 1 is exact for a in [1/2, 2] (Sterbenz) and ln a is
        accurate to rounding, so their ratio is accurate to a few ulps for every a > 0.
        """
        g = self._element(g)
        a = g[..., 0]
        u = np.log(a)
        d = a - 1.0
        k = u / d if d.all() else np.divide(u, d, out=np.ones_like(d), where=d != 0)
        out = np.empty(g.shape)
        out[..., 0] = u
        with np.errstate(over="ignore"):
            out[..., 1] = g[..., 1] * k
        if not np.all(np.isfinite(out[..., 1])):
            raise ValueError("g is out of range: the shift part of log(g), b ln a / (a - 1), overflows")
        return out

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        """[[a, b], [0, 1]], so that matrix(g) @ [x, 1] = [a x + b, 1] (``scale_shift_rep``)."""
        g = self._element(g)
        G = np.zeros(g.shape[:-1] + (2, 2))
        G[..., 0, :] = g
        G[..., 1, 1] = 1.0
        return G

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        """(a, b) from [[a, b], [0, 1]]; ValueError unless the bottom row is [0, 1] and a > 0."""
        G = self._square(G, "G")
        check_entries(G[..., 1, :], np.array([0.0, 1.0]), "G", "a scale-shift matrix [[a, b], [0, 1]] with bottom row [0, 1]")
        return self._element(G[..., 0, :], "G").copy()

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        """The top row (a, b) of ``M``, unchecked (``scale_shift_derep``): a partial sum may have a <= 0.

        Taylor partial sums and products (I + A/n)^k of algebra matrices keep the bottom row [0, 1],
        so the top row is the whole of their information.
        """
        return self._square(M, "M")[..., 0, :].copy()

    @override
    def coordinate_matrix(self, q: ArrayLike) -> FloatArray:
        """[[q_a, q_b], [0, 1]] for any finite q, including overshooting Euler states with q_a <= 0."""
        q = as_array(q, "q", (2,), what=" (coordinates (a, b) of the scale-shift group, possibly a <= 0)")
        G = np.zeros(q.shape[:-1] + (2, 2))
        G[..., 0, :] = q
        G[..., 1, 1] = 1.0
        return G

    @override
    def euler_step(self, g: ArrayLike, xi: ArrayLike, dt: float, side: str = "left") -> FloatArray:
        """g + dt (a u, a v) (``side="left"``, (1.46)) or g + dt (a u, b u + v) (``"right"``, (1.47)).

        These are T_e L_g xi = a xi and T_e R_g xi = [[a, 0], [b, 1]] xi; g may be an Euler state
        that overshot to a <= 0 (returned as it is, like that of (R+, x)).
        """
        side = check_option(side, "side", ("left", "right"))
        g = as_array(g, "g", (2,), what=" (an Euler state (a, b) of the scale-shift group, possibly a <= 0)")
        xi = self._algebra(xi)
        dt = real_number(dt, "dt", " (a time step)")
        a, b = g[..., 0], g[..., 1]
        u, v = xi[..., 0], xi[..., 1]
        out = np.empty(self._batch(("g", g), ("xi", xi)) + (2,))
        out[..., 0] = a + dt * (a * u)
        out[..., 1] = b + dt * (a * v if side == "left" else b * u + v)
        return out

    @override
    def random(self, rng: np.random.Generator | int | None, size: int | tuple[int, ...] = (), scale: float = 1.0) -> FloatArray:
        """(e^s, t) with s uniform in (-scale, scale) and t uniform in (-3 scale, 3 scale).

        ValueError if ``scale`` is so large that e^s overflows.
        """
        rng = as_rng(rng)
        size = check_shape(size, "size")
        scale = check_scale(scale)
        out = np.empty(size + (2,))
        with np.errstate(over="ignore", under="ignore"):
            out[..., 0] = np.exp(scale * rng.uniform(-1.0, 1.0, size))
        out[..., 1] = scale * rng.uniform(-3.0, 3.0, size)
        if not np.all((out[..., 0] > 0) & (out[..., 0] < np.inf)):
            raise ValueError(f"scale is too large: e^s with |s| < scale = {scale:g} overflows or underflows")
        return out

    @override
    def _fd_step(self, g, eps):
        # relative in a (so that a - step stays positive), absolute-plus-relative in b
        return np.stack([eps * g[..., 0], eps * (1.0 + np.abs(g[..., 1]))], -1)


ScaleShift = _ScaleShift()

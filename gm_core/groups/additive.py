"""The commutative groups whose operation is (modular) addition: (R^n, +), SO(2), (S^1, + mod k),
(R^2 x S^1, +). Their lifted actions and adjoints are identity matrices, book (1.22), so left and
right coincide, (1.3); their bracket is zero.
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups.base import (
    TWO_PI,
    LieGroup,
    angle_of_block,
    as_rng,
    check_entries,
    check_rotation,
    check_scale,
    eye_batch,
    mod_period,
    rotation_matrix,
    wrap_periodic,
    wrap_unchecked,
)
from gm_core.validation import FloatArray, as_array, check_shape

__all__ = ["Rn", "S1", "MAX_RN_DIM"]

#: Largest n accepted by :class:`Rn` (its matrices are (n+1) x (n+1)).
MAX_RN_DIM = 1000


class _Additive(LieGroup):
    """Groups whose operation is (modular) addition of coordinates."""

    @override
    def _identity_coords(self):
        return np.zeros(self.param_dim)

    @override
    def compose(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """g + h, coordinate-wise (angles are not wrapped), book (1.3)."""
        g = self._element(g)
        h = self._element(h, "h")
        self._batch(("g", g), ("h", h))
        return g + h

    @override
    def inverse(self, g: ArrayLike) -> FloatArray:
        """-g, book (1.v)."""
        return -self._element(g)

    @override
    def left_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """The identity matrix: translations do not turn velocities, book (1.22)."""
        return eye_batch(self.param_dim, self._batch(("h", self._element(h, "h")), ("g", self._element(g))))

    right_lifted_action = left_lifted_action

    @override
    def Ad(self, g: ArrayLike) -> FloatArray:
        """The identity matrix: body and spatial velocities coincide in a commutative group."""
        return eye_batch(self.tangent_dim, self._element(g).shape[:-1])

    Ad_inv = Ad

    @override
    def bracket(self, xi1: ArrayLike, xi2: ArrayLike) -> FloatArray:
        """Zero: the group is commutative."""
        xi1 = self._algebra(xi1, "xi1")
        xi2 = self._algebra(xi2, "xi2")
        return np.zeros(self._batch(("xi1", xi1), ("xi2", xi2)) + (self.tangent_dim,))

    @override
    def exp(self, xi: ArrayLike) -> FloatArray:
        """exp(xi) = xi: the coordinates are exponential coordinates."""
        return self._algebra(xi).copy()

    @override
    def log(self, g: ArrayLike) -> FloatArray:
        """g with its periodic coordinates reduced into (-k/2, k/2]."""
        g = self._element(g).copy()
        for j, p in enumerate(self.periods):
            if p is not None:
                g[..., j] = wrap_periodic(g[..., j], p)
        return g


class Rn(_Additive):
    """The additive group (R^n, +); lifted actions are identities, book (1.22).

    ``n`` is an integer between 1 and :data:`MAX_RN_DIM`.
    """

    def __init__(self, n: int = 1) -> None:
        if isinstance(n, (bool, np.bool_)) or not isinstance(n, (int, np.integer)):
            raise TypeError(f"n must be a positive integer (at most {MAX_RN_DIM}); got "
                            f"{type(n).__name__} {n!r:.40}")
        if not 1 <= n <= MAX_RN_DIM:
            raise ValueError(f"n must be a positive integer (at most {MAX_RN_DIM}); got {n!r}")
        n = int(n)
        # Rn's dimensions depend on n: the class-level ClassVar defaults are shadowed on the
        # instance (setattr, since the type checker rightly forbids assigning a ClassVar here).
        for attr, value in (("param_dim", n), ("tangent_dim", n), ("matrix_size", n + 1)):
            setattr(self, attr, value)
        self.name = "(R, +)" if n == 1 else f"(R^{n}, +)"
        self.label = "R" if n == 1 else ("R²" if n == 2 else f"R^{n}")
        self.coords = ("x",) if n == 1 else tuple(f"x{i + 1}" for i in range(n))
        self.periods = (None,) * n
        super().__init__()

    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        """The translation generator [[0, xi], [0, 0]], ``(..., n+1, n+1)``."""
        xi = self._algebra(xi)
        n = self.param_dim
        X = np.zeros(xi.shape[:-1] + (n + 1, n + 1))
        X[..., :n, n] = xi
        return X

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        X = self._square(X, "X")
        n = self.param_dim
        expected = np.zeros_like(X)
        expected[..., :n, n] = X[..., :n, n]
        check_entries(X, expected, "X", f"a translation generator [[0, xi], [0, 0]] of {self.name}")
        return X[..., :n, n].copy()

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        """The translation matrix [[I, g], [0, 1]], ``(..., n+1, n+1)``."""
        g = self._element(g)
        n = self.param_dim
        G = eye_batch(n + 1, g.shape[:-1])
        G[..., :n, n] = g
        return G

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        G = self._square(G, "G")
        n = self.param_dim
        expected = eye_batch(n + 1, G.shape[:-2])
        expected[..., :n, n] = G[..., :n, n]
        check_entries(G, expected, "G", f"a translation matrix [[I, g], [0, 1]] of {self.name}")
        return G[..., :n, n].copy()

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        """The translation column of ``M``, as it is."""
        M = self._square(M, "M")
        return M[..., : self.param_dim, self.param_dim].copy()


class _SO2(_Additive):
    """Rotations of the plane, elements stored as the angle theta, shape ``(..., 1)``; book (1.1)."""

    name = "SO(2)"
    label = "SO(2)"
    coords = ("theta",)
    periods = (TWO_PI,)
    param_dim: ClassVar[int] = 1
    tangent_dim: ClassVar[int] = 1
    matrix_size: ClassVar[int] = 2

    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        """[[0, -w], [w, 0]], ``(..., 2, 2)``."""
        w = self._algebra(xi)[..., 0]
        z = np.zeros_like(w)
        return np.stack([np.stack([z, -w], -1), np.stack([w, z], -1)], -2)

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        X = self._square(X, "X")
        if not np.all(np.abs(X + np.swapaxes(X, -1, -2)) <= 1e-9):
            raise ValueError("X must be skew-symmetric [[0, -w], [w, 0]] to be in the algebra so(2)")
        return X[..., 1, 0:1].copy()

    @override
    def log(self, g: ArrayLike) -> FloatArray:
        """theta reduced into (-pi, pi], exactly for every finite theta."""
        return wrap_unchecked(self._element(g)).copy()

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        """R(theta) = [[cos, -sin], [sin, cos]], book (1.1)."""
        return rotation_matrix(self._element(g)[..., 0])

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        G = self._square(G, "G")
        check_rotation(G, "G")
        return np.arctan2(G[..., 1, 0], G[..., 0, 0])[..., None]

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        """The angle of the nearest rotation to ``M``."""
        return angle_of_block(self._square(M, "M"))[..., None]


class S1(_Additive):
    """The circle with modular addition (S^1, + mod k), elements in [0, k), book section 1.2.

    ``period`` is the cycle length k (2 pi for radians, 1 for cycles, as in fig. 1.2). With
    ``period = 2 pi`` reductions use the true 2 pi (see :func:`wrap_angle`); any other period is
    reduced by exactly that number.
    """

    coords = ("a",)
    param_dim: ClassVar[int] = 1
    tangent_dim: ClassVar[int] = 1
    matrix_size: ClassVar[int] = 2

    def __init__(self, period: float = TWO_PI) -> None:
        if isinstance(period, (str, bytes)) or period is None:
            raise TypeError(f"period must be a positive number; got {type(period).__name__} {period!r:.40}")
        k = as_array(period, "period", what=" (a positive number)")
        if k.ndim != 0 or not 0 < k <= 1e300:
            raise ValueError(f"period must be a positive number (at most 1e300); got {period!r:.40}")
        self.period = float(k)
        self.periods = (self.period,)
        radians = self.period == TWO_PI
        self.name = "(S^1, + mod 2pi)" if radians else f"(S^1, + mod {period:g})"
        self.label = "S¹ (2π)" if radians else f"S¹ ({period:g})"
        self._scale = TWO_PI / self.period
        super().__init__()

    @override
    def _in_domain(self, g):
        return np.all((g >= 0) & (g < self.period), axis=-1)

    @override
    def project(self, g: ArrayLike) -> FloatArray:
        """The representative of ``g`` in [0, k)."""
        return mod_period(self._element(g), self.period)

    @override
    def compose(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """(a + b) mod k."""
        return mod_period(super().compose(g, h), self.period)

    @override
    def inverse(self, g: ArrayLike) -> FloatArray:
        """(-a) mod k."""
        return mod_period(-self._element(g), self.period)

    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        """so(2) generator of the rotation rate 2 pi xi / k, ``(..., 2, 2)``."""
        return SO2.hat(self._algebra(xi) * self._scale)

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        return SO2.vee(X) / self._scale

    @override
    def exp(self, xi: ArrayLike) -> FloatArray:
        """xi mod k."""
        return mod_period(self._algebra(xi), self.period)

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        """The rotation R(2 pi a / k): the isomorphism S^1 -> SO(2) of (1.xiv)-(1.xvi)."""
        return rotation_matrix(self._element(g)[..., 0] * self._scale)

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        return mod_period(SO2.from_matrix(G) / self._scale, self.period)

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        return mod_period(SO2.nearest_element(M) / self._scale, self.period)

    @override
    def random(self, rng: np.random.Generator | int | None, size: int | tuple[int, ...] = (), scale: float = 1.0) -> FloatArray:
        """Uniform on [0, k) (``scale`` is accepted for the common interface and ignored: the
        circle has no size to stretch)."""
        rng = as_rng(rng)
        check_scale(scale)
        return rng.uniform(0.0, self.period, check_shape(size, "size") + (1,))


class _R2xS1(_Additive):
    """The direct product (R^2 x S^1, +): coordinates add independently, book section 1.3.3."""

    name = "(R^2 x S^1, +)"
    label = "R²×S¹"
    coords = ("x", "y", "theta")
    periods = (None, None, TWO_PI)
    param_dim: ClassVar[int] = 3
    tangent_dim: ClassVar[int] = 3
    matrix_size: ClassVar[int] = 5

    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        """Block-diagonal algebra matrix: a translation block and an so(2) block, ``(..., 5, 5)``."""
        xi = self._algebra(xi)
        X = np.zeros(xi.shape[:-1] + (5, 5))
        X[..., 0, 2] = xi[..., 0]
        X[..., 1, 2] = xi[..., 1]
        X[..., 3, 4] = -xi[..., 2]
        X[..., 4, 3] = xi[..., 2]
        return X

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        X = self._square(X, "X")
        out = np.stack([X[..., 0, 2], X[..., 1, 2], X[..., 4, 3]], -1)
        check_entries(X, self.hat(out), "X", "a block-diagonal generator of (R^2 x S^1, +) (see hat)")
        return out

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        """Block-diagonal ``(..., 5, 5)``: translation [[I, (x, y)], [0, 1]] beside R(theta)."""
        g = self._element(g)
        G = eye_batch(5, g.shape[:-1])
        G[..., 0, 2] = g[..., 0]
        G[..., 1, 2] = g[..., 1]
        G[..., 3:5, 3:5] = rotation_matrix(g[..., 2])
        return G

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        G = self._square(G, "G")
        check_rotation(G[..., 3:5, 3:5], "G")
        out = np.stack([G[..., 0, 2], G[..., 1, 2], np.arctan2(G[..., 4, 3], G[..., 3, 3])], -1)
        expected = eye_batch(5, G.shape[:-2])
        expected[..., 0, 2] = G[..., 0, 2]
        expected[..., 1, 2] = G[..., 1, 2]
        expected[..., 3:5, 3:5] = G[..., 3:5, 3:5]
        check_entries(G, expected, "G", "block-diagonal [[I, (x, y)], [0, 1]] beside a rotation R(theta)")
        return out

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        M = self._square(M, "M")
        return np.stack([M[..., 0, 2], M[..., 1, 2], angle_of_block(M[..., 3:5, 3:5])], -1)


SO2 = _SO2()
R2xS1 = _R2xS1()

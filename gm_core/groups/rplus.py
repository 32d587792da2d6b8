"""The multiplicative group (R+, x) of positive numbers, book (1.23)-(1.25) (numpy only)."""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups.base import LieGroup, as_rng, check_scale
from gm_core.validation import FloatArray, as_array, check_option, check_shape, real_number

__all__ = ["RPlus"]


class _RPlus(LieGroup):
    """The multiplicative group (R+, x): T_g L_h = T_g R_h = h, book (1.23)-(1.25).

    Elements are positive numbers, shape ``(..., 1)``; every method refuses g <= 0 by name
    (:meth:`contains` tells without raising).
    """

    name = "(R+, x)"
    label = "R⁺"
    coords = ("g",)
    periods = (None,)
    param_dim: ClassVar[int] = 1
    tangent_dim: ClassVar[int] = 1
    matrix_size: ClassVar[int] = 1

    @override
    def _element(self, g, name="g"):
        g = super()._element(g, name)
        if np.any(g <= 0):
            raise ValueError(f"{name} must be positive: elements of (R+, x) are numbers > 0")
        return g

    @override
    def _in_domain(self, g):
        return np.all(g > 0, axis=-1)

    @override
    def _identity_coords(self):
        return np.ones(1)

    @override
    def compose(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """g h, book (1.23)."""
        g = self._element(g)
        h = self._element(h, "h")
        self._batch(("g", g), ("h", h))
        with np.errstate(over="ignore", under="ignore"):
            out = g * h
        self._check_result(out, "g and h", "g h")
        return out

    @override
    def inverse(self, g: ArrayLike) -> FloatArray:
        """1 / g."""
        g = self._element(g)
        with np.errstate(over="ignore"):
            out = 1.0 / g
        self._check_result(out, "g", "1/g")
        return out

    @override
    def left_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g L_h = h (a 1x1 matrix), book (1.24); equal to T_g R_h, (1.25)."""
        h = self._element(h, "h")
        g = self._element(g)
        return np.broadcast_to(h, self._batch(("h", h), ("g", g)) + (1,))[..., None].copy()

    right_lifted_action = left_lifted_action

    @override
    def Ad(self, g: ArrayLike) -> FloatArray:
        """1: the group is commutative."""
        return np.ones(self._element(g).shape[:-1] + (1, 1))

    Ad_inv = Ad

    @override
    def bracket(self, xi1: ArrayLike, xi2: ArrayLike) -> FloatArray:
        """Zero: the group is commutative."""
        xi1 = self._algebra(xi1, "xi1")
        xi2 = self._algebra(xi2, "xi2")
        return np.zeros(self._batch(("xi1", xi1), ("xi2", xi2)) + (1,))

    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        return self._algebra(xi)[..., None].copy()

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        return self._square(X, "X")[..., 0].copy()

    @override
    def exp(self, xi: ArrayLike) -> FloatArray:
        """e^xi; ValueError if it overflows or underflows to 0 (|xi| > about 708)."""
        xi = self._algebra(xi)
        with np.errstate(over="ignore", under="ignore"):
            g = np.exp(xi)
        self._check_result(g, "xi", "e^xi")
        return g

    def _check_result(self, g, name, what):
        if not np.all((g > 0) & (g < np.inf)):
            raise ValueError(f"{name} is out of range: {what} is not a positive float (it overflows "
                             f"or underflows to 0), so it is no element of (R+, x)")

    @override
    def log(self, g: ArrayLike) -> FloatArray:
        """ln g."""
        return np.log(self._element(g))

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        return self._element(g)[..., None].copy()

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        return self._element(self._square(G, "G")[..., 0], "G").copy()

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        """The single entry of ``M``, unchecked: a partial sum or an Euler product may be <= 0."""
        return self._square(M, "M")[..., 0].copy()

    @override
    def coordinate_matrix(self, q: ArrayLike) -> FloatArray:
        """[[q]] for any finite number q, including overshooting Euler states q <= 0."""
        return as_array(q, "q", (1,), what=" (coordinates of (R+, x), possibly <= 0)")[..., None].copy()

    @override
    def euler_step(self, g: ArrayLike, xi: ArrayLike, dt: float, side: str = "left") -> FloatArray:
        """g (1 + dt xi): the Euler step of g_dot = g xi (both sides, (1.24)-(1.25)); g may be <= 0."""
        check_option(side, "side", ("left", "right"))
        g = as_array(g, "g", (1,), what=" (an Euler state of (R+, x), possibly <= 0)")
        xi = self._algebra(xi)
        dt = real_number(dt, "dt", " (a time step)")
        return g * (1.0 + dt * xi)

    @override
    def random(self, rng: np.random.Generator | int | None, size: int | tuple[int, ...] = (), scale: float = 1.0) -> FloatArray:
        """e^u with u uniform in (-2 scale, 2 scale)."""
        rng = as_rng(rng)
        size = check_shape(size, "size")
        scale = check_scale(scale)
        g = np.exp(rng.uniform(-2.0, 2.0, size + (1,)))
        return g ** scale if scale != 1.0 else g

    @override
    def _fd_step(self, g, eps):
        return eps * g


RPlus = _RPlus()

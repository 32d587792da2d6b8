"""The special Euclidean group SE(2) of rigid motions of the plane, book (1.2) (numpy only).

Every map is a closed form vectorized over leading axes with no Python loops; exp and log use the
half-angle form V(w) = (sin h / h) R(h), h = w/2, which has no cancellation at any angle.
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups.base import TWO_PI, LieGroup, angle_of_block, check_entries, check_rotation, wrap_unchecked
from gm_core.validation import FloatArray, as_array

__all__ = ["SE2"]


class _SE2(LieGroup):
    """The special Euclidean group SE(2): elements ``(..., 3)`` = (x, y, theta), book (1.2).

    All maps are closed forms, vectorized over leading axes with no Python loops.
    """

    name = "SE(2)"
    label = "SE(2)"
    coords = ("x", "y", "theta")
    periods = (None, None, TWO_PI)
    param_dim: ClassVar[int] = 3
    tangent_dim: ClassVar[int] = 3
    matrix_size: ClassVar[int] = 3

    @override
    def _identity_coords(self):
        return np.zeros(3)

    @override
    def compose(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """g o h = (x + u cos th - v sin th, y + u sin th + v cos th, th + beta), book (1.7)-(1.9)."""
        g = self._element(g)
        h = self._element(h, "h")
        x, y, t = g[..., 0], g[..., 1], g[..., 2]
        u, v, b = h[..., 0], h[..., 1], h[..., 2]
        c, s = np.cos(t), np.sin(t)
        # broadcasting costs microseconds: skip it in the common equal-shapes case
        out = np.empty(g.shape if g.shape == h.shape else self._batch(("g", g), ("h", h)) + (3,))
        out[..., 0] = x + c * u - s * v
        out[..., 1] = y + s * u + c * v
        out[..., 2] = t + b
        return out

    @override
    def bracket(self, xi1: ArrayLike, xi2: ArrayLike) -> FloatArray:
        """[xi1, xi2] = (w2 v1y - w1 v2y, w1 v2x - w2 v1x, 0), the vee of X1 X2 - X2 X1 with (1.54)."""
        xi1 = self._algebra(xi1, "xi1")
        xi2 = self._algebra(xi2, "xi2")
        v1x, v1y, w1 = xi1[..., 0], xi1[..., 1], xi1[..., 2]
        v2x, v2y, w2 = xi2[..., 0], xi2[..., 1], xi2[..., 2]
        out = np.zeros(self._batch(("xi1", xi1), ("xi2", xi2)) + (3,))
        out[..., 0] = -w1 * v2y + w2 * v1y
        out[..., 1] = w1 * v2x - w2 * v1x
        return out

    @override
    def inverse(self, g: ArrayLike) -> FloatArray:
        """g^-1 = (-x cos th - y sin th, x sin th - y cos th, -th), so g^-1 g = e, book (1.10)."""
        g = self._element(g)
        x, y, t = g[..., 0], g[..., 1], g[..., 2]
        c, s = np.cos(t), np.sin(t)
        out = np.empty(g.shape)
        out[..., 0] = -c * x - s * y
        out[..., 1] = s * x - c * y
        out[..., 2] = -t
        return out

    @override
    def left_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g L_h = [[cos b, -sin b, 0], [sin b, cos b, 0], [0, 0, 1]] for h = (u, v, b), book (1.31)."""
        h = self._element(h, "h")
        g = self._element(g)
        b = h[..., 2]
        c, s = np.cos(b), np.sin(b)
        M = np.zeros(self._batch(("h", h), ("g", g)) + (3, 3))
        M[..., 0, 0] = c
        M[..., 0, 1] = -s
        M[..., 1, 0] = s
        M[..., 1, 1] = c
        M[..., 2, 2] = 1.0
        return M

    @override
    def right_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g R_h = [[1, 0, -(u sin th + v cos th)], [0, 1, u cos th - v sin th], [0, 0, 1]], book (1.37)."""
        h = self._element(h, "h")
        g = self._element(g)
        u, v = h[..., 0], h[..., 1]
        t = g[..., 2]
        c, s = np.cos(t), np.sin(t)
        M = np.zeros(self._batch(("h", h), ("g", g)) + (3, 3))
        M[..., 0, 0] = 1.0
        M[..., 1, 1] = 1.0
        M[..., 2, 2] = 1.0
        M[..., 0, 2] = -(u * s + v * c)
        M[..., 1, 2] = u * c - v * s
        return M

    @override
    def Ad(self, g: ArrayLike) -> FloatArray:
        """Ad_g = [[cos th, -sin th, y], [sin th, cos th, -x], [0, 0, 1]], book (1.43)."""
        g = self._element(g)
        M = np.empty(g.shape[:-1] + (3, 3))
        c = np.cos(g[..., 2], out=M[..., 0, 0])     # written straight into the matrix
        s = np.sin(g[..., 2], out=M[..., 1, 0])
        np.negative(s, out=M[..., 0, 1])
        M[..., 0, 2] = g[..., 1]
        M[..., 1, 1] = c
        np.negative(g[..., 0], out=M[..., 1, 2])
        M[..., 2, :2] = 0.0
        M[..., 2, 2] = 1.0
        return M

    @override
    def Ad_inv(self, g: ArrayLike) -> FloatArray:
        """Ad_g^-1 = [[c, s, x s - y c], [-s, c, x c + y s], [0, 0, 1]], book (1.45)."""
        g = self._element(g)
        x, y = g[..., 0], g[..., 1]
        M = np.empty(g.shape[:-1] + (3, 3))
        c = np.cos(g[..., 2], out=M[..., 0, 0])     # written straight into the matrix
        s = np.sin(g[..., 2], out=M[..., 0, 1])
        np.negative(s, out=M[..., 1, 0])
        M[..., 1, 1] = c
        m02, m12 = M[..., 0, 2], M[..., 1, 2]
        np.multiply(x, s, out=m02)                  # same roundings as x s - y c and x c + y s
        tmp = np.multiply(y, c, out=np.empty(g.shape[:-1]))
        m02 -= tmp
        np.multiply(x, c, out=m12)
        np.multiply(y, s, out=tmp)
        m12 += tmp
        M[..., 2, :2] = 0.0
        M[..., 2, 2] = 1.0
        return M

    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        """xi^ = [[0, -w, vx], [w, 0, vy], [0, 0, 0]] for xi = (vx, vy, w), ``(..., 3, 3)``; book (1.54)."""
        xi = self._algebra(xi)
        X = np.zeros(xi.shape[:-1] + (3, 3))
        X[..., 0, 1] = -xi[..., 2]
        X[..., 1, 0] = xi[..., 2]
        X[..., 0, 2] = xi[..., 0]
        X[..., 1, 2] = xi[..., 1]
        return X

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        """(vx, vy, w) from an se(2) matrix; raises ValueError if X is not of the form (1.54)."""
        X = self._square(X, "X")
        out = np.stack([X[..., 0, 2], X[..., 1, 2], X[..., 1, 0]], -1)
        check_entries(X, self.hat(out), "X", "an se(2) matrix [[0, -w, vx], [w, 0, vy], [0, 0, 0]] as in (1.54)")
        return out

    @override
    def exp(self, xi: ArrayLike) -> FloatArray:
        """exp(xi) = (V(w) (vx, vy), w) with V(w) = (sin h / h) R(h), h = w/2; exercise 1.4a.

        This is the unit-time flow from e along the left-invariant field (1.46) of xi (equal to
        that of the right-invariant field (1.47) with xi_s = xi). The half-angle form has no
        cancellation, so it is accurate to about 1e-16 relative for every w, including w -> 0.
        """
        xi = self._algebra(xi)
        vx, vy, w = xi[..., 0], xi[..., 1], xi[..., 2]
        h = 0.5 * w
        c, s = np.cos(h), np.sin(h)
        # sin(h)/h with the value 1 at h = 0; the masked divide only when some h is 0 (faster)
        k = s / h if h.all() else np.divide(s, h, out=np.ones_like(h), where=h != 0)
        out = np.empty(xi.shape)
        out[..., 0] = k * (c * vx - s * vy)
        out[..., 1] = k * (s * vx + c * vy)
        out[..., 2] = w
        return out

    @override
    def log(self, g: ArrayLike) -> FloatArray:
        """log(g) = (V(th)^-1 (x, y), th) with th wrapped to (-pi, pi], inverse of :meth:`exp`.

        V^-1 = (h / sin h) R(-h) with h = th/2 in (-pi/2, pi/2], so it never divides by zero.
        """
        g = self._element(g)
        x, y = g[..., 0], g[..., 1]
        t = wrap_unchecked(g[..., 2])
        h = 0.5 * t
        c, s = np.cos(h), np.sin(h)
        k = s / h if h.all() else np.divide(s, h, out=np.ones_like(h), where=h != 0)
        out = np.empty(g.shape)
        out[..., 0] = (c * x + s * y) / k
        out[..., 1] = (c * y - s * x) / k
        out[..., 2] = t
        return out

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        """Homogeneous matrix [[cos th, -sin th, x], [sin th, cos th, y], [0, 0, 1]], book (1.2)."""
        g = self._element(g)
        t = g[..., 2]
        c, s = np.cos(t), np.sin(t)
        G = np.zeros(g.shape[:-1] + (3, 3))
        G[..., 0, 0] = c
        G[..., 0, 1] = -s
        G[..., 1, 0] = s
        G[..., 1, 1] = c
        G[..., 0, 2] = g[..., 0]
        G[..., 1, 2] = g[..., 1]
        G[..., 2, 2] = 1.0
        return G

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        """(x, y, th) from a homogeneous matrix; ValueError unless it is a proper rigid motion (1.2)."""
        G = self._square(G, "G")
        check_entries(G[..., 2, :], np.array([0.0, 0.0, 1.0]), "G",
                       "a homogeneous SE(2) matrix with last row [0, 0, 1] (1.2)")
        check_rotation(G[..., :2, :2], "G")
        return np.stack([G[..., 0, 2], G[..., 1, 2], np.arctan2(G[..., 1, 0], G[..., 0, 0])], -1)

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        """(x, y) from the translation column and the angle of the nearest rotation to the 2x2 block."""
        M = self._square(M, "M")
        return np.stack([M[..., 0, 2], M[..., 1, 2], angle_of_block(M[..., :2, :2])], -1)

    def act_on_points(self, g: ArrayLike, p: ArrayLike) -> FloatArray:
        """World positions ``(..., 2)`` of body-frame points p ``(..., 2)`` under g, book (1.11)-(1.12)."""
        g = self._element(g)
        p = as_array(p, "p", (2,), what=" (body-frame point coordinates)")
        t = g[..., 2]
        c, s = np.cos(t), np.sin(t)
        out = np.empty(self._batch(("g", g), ("p", p)) + (2,))
        out[..., 0] = g[..., 0] + c * p[..., 0] - s * p[..., 1]
        out[..., 1] = g[..., 1] + s * p[..., 0] + c * p[..., 1]
        return out


SE2 = _SE2()

"""Lie groups of chapter 1 behind one interface (numpy only).

Every group is a singleton object with the same methods, so a formula written once works on
(R, +), (R^n, +), (R+, x), SO(2), S^1, (R^2 x S^1, +) and SE(2):

=====================  ===================================================  ==============
method                 meaning                                              book
=====================  ===================================================  ==============
identity()             the identity element e                               (1.iv)
compose(g, h)          g o h (the left action L_g h, or right action R_h g)  (1.6), (1.9)
inverse(g)             g^-1                                                 (1.10)
left_lifted_action     T_g L_h, the matrix d(hg)/dg                         (1.20), (1.31)
right_lifted_action    T_g R_h, the matrix d(gh)/dg                         (1.21), (1.37)
Ad, Ad_inv             body <-> spatial velocity                           (1.40)-(1.45)
hat, vee               Lie algebra vector <-> matrix                       (1.54)
exp, log               exponential map and its inverse                     section 1.6.4
matrix, from_matrix    matrix representation of an element                 (1.1), (1.2)
=====================  ===================================================  ==============

Elements and velocities are float arrays batched over leading axes: an SE(2) element has shape
``(..., 3)`` holding ``(x, y, theta)``, an element of (R+, x) has shape ``(..., 1)``. Matrices
such as lifted actions have shape ``(..., n, n)``. Batch axes broadcast with numpy's rules.

Angles are carried as real numbers and are not wrapped by ``compose``: that keeps formulas
identical to the book's, e.g. (1.6) ends in ``theta + beta``. Elements whose angles differ by a
multiple of 2 pi are the same element; compare with :meth:`LieGroup.isclose`, and use ``log``
(which wraps to (-pi, pi]) to get the principal coordinates.
"""
from __future__ import annotations

import numpy as np

from ._validate import as_array

__all__ = [
    "LieGroup", "Rn", "R", "R2", "RPlus", "SO2", "S1", "R2xS1", "SE2", "wrap_angle", "matvec",
    "ALL_GROUPS",
]

TWO_PI = 2.0 * np.pi


def wrap_angle(theta):
    """Angle(s) equal to ``theta`` modulo 2 pi, in (-pi, pi]; exact for inputs already there."""
    theta = np.asarray(theta, dtype=float)
    return theta - TWO_PI * np.ceil((theta - np.pi) / TWO_PI)


def matvec(M, v):
    """Batched matrix-vector product ``M @ v`` for ``M: (..., n, m)`` and ``v: (..., m)``."""
    return np.einsum("...ij,...j->...i", M, v)


def _sinc(h):
    """sin(h)/h, evaluated without cancellation and equal to 1 at h = 0."""
    s = np.sin(h)
    return np.divide(s, h, out=np.ones_like(s), where=h != 0)


def _batch(*arrays, tail):
    shape = np.broadcast_shapes(*(a.shape[: a.ndim - tail] for a in arrays))
    return shape


class LieGroup:
    """The interface every group of the course implements.

    Subclasses set ``name``, ``dim`` (number of coordinates), ``coords`` (their names),
    ``angular`` (which coordinates are angles, compared modulo 2 pi) and ``matrix_size``.
    """

    name = "G"
    dim = 1
    coords: tuple = ("g",)
    angular: tuple = (False,)
    matrix_size = 1
    commutative = True

    # ------------------------------------------------------------------ checking
    def _element(self, g, name="g"):
        return as_array(g, name, (self.dim,), what=f" ({', '.join(self.coords)}) of {self.name}")

    def _algebra(self, xi, name="xi"):
        return as_array(xi, name, (self.dim,), what=f", a velocity in the Lie algebra of {self.name}")

    def _square(self, M, name):
        n = self.matrix_size
        return as_array(M, name, (n, n), what=f", a {n}x{n} matrix for {self.name}")

    # ------------------------------------------------------------------ group structure
    def identity(self, batch_shape=()):
        """The identity element e, shape ``batch_shape + (dim,)``; book (1.iv)."""
        raise NotImplementedError

    def compose(self, g, h):
        """The product g o h, shape ``(..., dim)``; book (1.6), (1.9)."""
        raise NotImplementedError

    def inverse(self, g):
        """The inverse g^-1 with g o g^-1 = e, shape ``(..., dim)``; book (1.v), (1.10)."""
        raise NotImplementedError

    def left_lifted_action(self, h, g):
        """T_g L_h = d(h g)/dg, shape ``(..., dim, dim)``; book (1.19)-(1.20)."""
        raise NotImplementedError

    def right_lifted_action(self, h, g):
        """T_g R_h = d(g h)/dg, shape ``(..., dim, dim)``; book (1.21)."""
        raise NotImplementedError

    def Ad(self, g):
        """Adjoint Ad_g = T_g R_{g^-1} T_e L_g, body to spatial velocity, ``(..., dim, dim)``; book (1.40)."""
        g = self._element(g)
        e = self.identity()
        return self.right_lifted_action(self.inverse(g), g) @ self.left_lifted_action(g, e)

    def Ad_inv(self, g):
        """Adjoint inverse Ad_g^-1 = Ad_{g^-1}, spatial to body velocity, ``(..., dim, dim)``; book (1.41)."""
        return self.Ad(self.inverse(self._element(g)))

    # ------------------------------------------------------------------ algebra and exp
    def hat(self, xi):
        """Matrix form of a Lie-algebra vector, ``(..., m, m)``; book (1.54) for SE(2)."""
        raise NotImplementedError

    def vee(self, X):
        """Vector form ``(..., dim)`` of a Lie-algebra matrix; inverse of :meth:`hat`."""
        raise NotImplementedError

    def bracket(self, xi1, xi2):
        """Lie bracket [xi1, xi2] ``(..., tangent_dim)``: the vee of hat(xi1) hat(xi2) - hat(xi2) hat(xi1).

        This matrix commutator is the definition; groups override it with a closed form, and
        abelian groups return zero.
        """
        X1 = self.hat(self._algebra(xi1, "xi1"))
        X2 = self.hat(self._algebra(xi2, "xi2"))
        return self.vee(X1 @ X2 - X2 @ X1)

    def ad(self, xi):
        """Matrix ``(..., dim, dim)`` of ad_xi = [xi, .], so that ad(xi) @ eta = bracket(xi, eta)."""
        xi = self._algebra(xi)
        basis = np.eye(self.dim)
        cols = self.bracket(xi[..., None, :], basis)  # (..., dim[j], dim)
        return np.swapaxes(cols, -1, -2)

    def exp(self, xi):
        """Group exponential: the unit-time flow from e along the invariant field of xi; section 1.6.4."""
        raise NotImplementedError

    def log(self, g):
        """Principal inverse of :meth:`exp`: the algebra vector whose unit flow reaches g."""
        raise NotImplementedError

    def matrix(self, g):
        """Matrix representation of g, ``(..., m, m)``; book (1.1), (1.2)."""
        raise NotImplementedError

    def from_matrix(self, G):
        """Element coordinates ``(..., dim)`` from a matrix representation; inverse of :meth:`matrix`."""
        raise NotImplementedError

    # ------------------------------------------------------------------ velocities, (1.32)-(1.45)
    def world_to_body(self, g, g_dot):
        """Body velocity xi = T_g L_{g^-1} g_dot, ``(..., dim)``; book (1.32), (1.26) for SE(2)."""
        g = self._element(g)
        g_dot = as_array(g_dot, "g_dot", (self.dim,))
        return matvec(self.left_lifted_action(self.inverse(g), g), g_dot)

    def body_to_world(self, g, xi):
        """World velocity g_dot = T_e L_g xi, ``(..., dim)``; book (1.33), (1.28) for SE(2)."""
        g = self._element(g)
        xi = self._algebra(xi)
        return matvec(self.left_lifted_action(g, self.identity()), xi)

    def world_to_spatial(self, g, g_dot):
        """Spatial velocity xi_s = T_g R_{g^-1} g_dot, ``(..., dim)``; book (1.38)."""
        g = self._element(g)
        g_dot = as_array(g_dot, "g_dot", (self.dim,))
        return matvec(self.right_lifted_action(self.inverse(g), g), g_dot)

    def spatial_to_world(self, g, xi_s):
        """World velocity g_dot = T_e R_g xi_s, ``(..., dim)``; book (1.39)."""
        g = self._element(g)
        xi_s = self._algebra(xi_s, "xi_s")
        return matvec(self.right_lifted_action(g, self.identity()), xi_s)

    def body_to_spatial(self, g, xi):
        """Spatial velocity xi_s = Ad_g xi, ``(..., dim)``; book (1.40), (1.43)."""
        return matvec(self.Ad(g), self._algebra(xi))

    def spatial_to_body(self, g, xi_s):
        """Body velocity xi = Ad_g^-1 xi_s, ``(..., dim)``; book (1.41), (1.45)."""
        return matvec(self.Ad_inv(g), self._algebra(xi_s, "xi_s"))

    # ------------------------------------------------------------------ utilities
    def difference(self, g, h):
        """Coordinate difference g - h with angular coordinates wrapped to (-pi, pi]."""
        d = np.asarray(g, dtype=float) - np.asarray(h, dtype=float)
        if any(self.angular):
            d = d.copy()
            mask = np.array(self.angular)
            d[..., mask] = wrap_angle(d[..., mask])
        return d

    def isclose(self, g, h, atol=1e-9):
        """True where g and h are the same element to within ``atol`` (angles modulo 2 pi)."""
        return np.all(np.abs(self.difference(g, h)) <= atol, axis=-1)

    def random(self, rng, size=()):
        """Random elements ``size + (dim,)`` for tests and demos (coordinates of moderate size)."""
        size = (size,) if np.isscalar(size) else tuple(size)
        out = rng.uniform(-3.0, 3.0, size + (self.dim,))
        mask = np.array(self.angular)
        if mask.any():
            out[..., mask] = rng.uniform(-np.pi, np.pi, size + (int(mask.sum()),))
        return out

    def _fd_step(self, g, eps):
        return eps * (1.0 + np.abs(g))

    def _numerical_jacobian(self, f, g, eps):
        g = self._element(g)
        step = self._fd_step(g, eps)
        cols = []
        for j in range(self.dim):
            d = np.zeros_like(g)
            d[..., j] = step[..., j]
            cols.append(self.difference(f(g + d), f(g - d)) / (2.0 * step[..., j : j + 1]))
        return np.stack(cols, axis=-1)

    def numerical_left_lifted_action(self, h, g, eps=1e-6):
        """T_g L_h by central differences of the group operation, an independent route to (1.20)."""
        h = self._element(h, "h")
        return self._numerical_jacobian(lambda x: self.compose(h, x), g, eps)

    def numerical_right_lifted_action(self, h, g, eps=1e-6):
        """T_g R_h by central differences of the group operation, an independent route to (1.21)."""
        h = self._element(h, "h")
        return self._numerical_jacobian(lambda x: self.compose(x, h), g, eps)

    def __repr__(self):
        return self.name


def check_group(group, name="group"):
    """Return ``group`` after checking it is one of gm_core's Lie groups (TypeError otherwise)."""
    if not isinstance(group, LieGroup):
        raise TypeError(
            f"{name} must be one of gm_core's Lie groups (e.g. gm_core.SE2, gm_core.RPlus); "
            f"got {type(group).__name__}"
        )
    return group


def _eye(n, batch):
    return np.broadcast_to(np.eye(n), tuple(batch) + (n, n)).copy()


class _Additive(LieGroup):
    """Groups whose operation is (modular) addition: the lifted actions and adjoints are
    identity matrices, book (1.22), so left and right coincide, (1.3)."""

    def identity(self, batch_shape=()):
        return np.zeros(tuple(batch_shape) + (self.dim,))

    def left_lifted_action(self, h, g):
        return _eye(self.dim, _batch(self._element(h, "h"), self._element(g), tail=1))

    right_lifted_action = left_lifted_action

    def Ad(self, g):
        return _eye(self.dim, self._element(g).shape[:-1])

    Ad_inv = Ad


class Rn(_Additive):
    """The additive group (R^n, +); lifted actions are identities, book (1.22)."""

    def __init__(self, n=1):
        if not isinstance(n, (int, np.integer)) or isinstance(n, bool) or n < 1:
            raise ValueError(f"n must be a positive integer; got {n!r}")
        self.dim = int(n)
        self.name = "(R, +)" if n == 1 else f"(R^{n}, +)"
        self.coords = ("x",) if n == 1 else tuple(f"x{i + 1}" for i in range(n))
        self.angular = (False,) * n
        self.matrix_size = n + 1

    def compose(self, g, h):
        return self._element(g) + self._element(h, "h")

    def inverse(self, g):
        return -self._element(g)

    def hat(self, xi):
        xi = self._algebra(xi)
        X = np.zeros(xi.shape[:-1] + (self.dim + 1, self.dim + 1))
        X[..., : self.dim, self.dim] = xi
        return X

    def vee(self, X):
        X = self._square(X, "X")
        return X[..., : self.dim, self.dim].copy()

    def exp(self, xi):
        return self._algebra(xi).copy()

    def log(self, g):
        return self._element(g).copy()

    def matrix(self, g):
        g = self._element(g)
        G = _eye(self.dim + 1, g.shape[:-1])
        G[..., : self.dim, self.dim] = g
        return G

    def from_matrix(self, G):
        G = self._square(G, "G")
        n = self.dim
        ok = np.allclose(G[..., :n, :n], np.eye(n), atol=1e-8) and np.allclose(
            G[..., n, :], np.eye(n + 1)[n], atol=1e-8
        )
        if not ok:
            raise ValueError(f"G must be a translation matrix [[I, g], [0, 1]] of {self.name}")
        return G[..., :n, n].copy()


class _RPlus(LieGroup):
    """The multiplicative group (R+, x): T_g L_h = T_g R_h = h, book (1.23)-(1.25)."""

    name = "(R+, x)"
    dim = 1
    coords = ("g",)
    angular = (False,)
    matrix_size = 1

    def _element(self, g, name="g"):
        g = super()._element(g, name)
        if np.any(g <= 0):
            raise ValueError(f"{name} must be positive: elements of (R+, x) are numbers > 0")
        return g

    def identity(self, batch_shape=()):
        return np.ones(tuple(batch_shape) + (1,))

    def compose(self, g, h):
        return self._element(g) * self._element(h, "h")

    def inverse(self, g):
        return 1.0 / self._element(g)

    def left_lifted_action(self, h, g):
        h = self._element(h, "h")
        g = self._element(g)
        return np.broadcast_to(h, _batch(h, g, tail=1) + (1,))[..., None].copy()

    right_lifted_action = left_lifted_action

    def Ad(self, g):
        return np.ones(self._element(g).shape[:-1] + (1, 1))

    Ad_inv = Ad

    def hat(self, xi):
        return self._algebra(xi)[..., None].copy()

    def vee(self, X):
        return self._square(X, "X")[..., 0].copy()

    def exp(self, xi):
        return np.exp(self._algebra(xi))

    def log(self, g):
        return np.log(self._element(g))

    def matrix(self, g):
        return self._element(g)[..., None].copy()

    def from_matrix(self, G):
        return self._element(self._square(G, "G")[..., 0], "G").copy()

    def difference(self, g, h):
        return np.asarray(g, dtype=float) - np.asarray(h, dtype=float)

    def random(self, rng, size=()):
        size = (size,) if np.isscalar(size) else tuple(size)
        return np.exp(rng.uniform(-2.0, 2.0, size + (1,)))

    def _fd_step(self, g, eps):
        return eps * g


def _rot(theta):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def _check_rotation(Rm, name):
    RtR = np.swapaxes(Rm, -1, -2) @ Rm
    det = np.linalg.det(Rm)
    if not (np.allclose(RtR, np.eye(2), atol=1e-8) and np.allclose(det, 1.0, atol=1e-8)):
        raise ValueError(
            f"{name} is not a rotation: its 2x2 rotation block must satisfy R^T R = I and det R = +1"
        )


class _SO2(_Additive):
    """Rotations of the plane, elements stored as the angle theta, shape ``(..., 1)``; book (1.1)."""

    name = "SO(2)"
    dim = 1
    coords = ("theta",)
    angular = (True,)
    matrix_size = 2

    def compose(self, g, h):
        """theta_g + theta_h: matrix product R(a) R(b) = R(a + b), book (1.xvi)."""
        return self._element(g) + self._element(h, "h")

    def inverse(self, g):
        return -self._element(g)

    def hat(self, xi):
        w = self._algebra(xi)[..., 0]
        z = np.zeros_like(w)
        return np.stack([np.stack([z, -w], -1), np.stack([w, z], -1)], -2)

    def vee(self, X):
        X = self._square(X, "X")
        if not np.allclose(X + np.swapaxes(X, -1, -2), 0.0, atol=1e-9):
            raise ValueError("X must be skew-symmetric [[0, -w], [w, 0]] to be in the algebra so(2)")
        return X[..., 1, 0:1].copy()

    def exp(self, xi):
        return self._algebra(xi).copy()

    def log(self, g):
        return wrap_angle(self._element(g))

    def matrix(self, g):
        return _rot(self._element(g)[..., 0])

    def from_matrix(self, G):
        G = self._square(G, "G")
        _check_rotation(G, "G")
        return np.arctan2(G[..., 1, 0], G[..., 0, 0])[..., None]


class S1(_Additive):
    """The circle with modular addition (S^1, + mod k), elements in [0, k), book section 1.2.

    ``period`` is the cycle length k (2 pi for radians, 1 for cycles, as in fig. 1.2).
    """

    dim = 1
    coords = ("a",)
    angular = (True,)
    matrix_size = 2

    def __init__(self, period=TWO_PI):
        if isinstance(period, bool) or not np.isscalar(period) or not np.isfinite(period) or period <= 0:
            raise ValueError(f"period must be a positive number; got {period!r}")
        self.period = float(period)
        self.name = "(S^1, + mod 2pi)" if np.isclose(period, TWO_PI) else f"(S^1, + mod {period:g})"

    def _mod(self, a):
        return np.mod(a, self.period)

    def compose(self, g, h):
        return self._mod(self._element(g) + self._element(h, "h"))

    def inverse(self, g):
        return self._mod(-self._element(g))

    def hat(self, xi):
        return SO2.hat(self._algebra(xi) * (TWO_PI / self.period))

    def vee(self, X):
        return SO2.vee(X) * (self.period / TWO_PI)

    def exp(self, xi):
        return self._mod(self._algebra(xi))

    def log(self, g):
        k = self.period
        return np.mod(self._element(g) + k / 2, k) - k / 2

    def matrix(self, g):
        """The rotation R(2 pi a / k): the isomorphism S^1 -> SO(2) of (1.xiv)-(1.xvi)."""
        return _rot(self._element(g)[..., 0] * (TWO_PI / self.period))

    def from_matrix(self, G):
        return self._mod(SO2.from_matrix(G) * (self.period / TWO_PI))

    def difference(self, g, h):
        d = np.asarray(g, dtype=float) - np.asarray(h, dtype=float)
        k = self.period
        return np.mod(d + k / 2, k) - k / 2

    def random(self, rng, size=()):
        size = (size,) if np.isscalar(size) else tuple(size)
        return rng.uniform(0.0, self.period, size + (1,))


class _R2xS1(_Additive):
    """The direct product (R^2 x S^1, +): coordinates add independently, book section 1.3.3."""

    name = "(R^2 x S^1, +)"
    dim = 3
    coords = ("x", "y", "theta")
    angular = (False, False, True)
    matrix_size = 5

    def compose(self, g, h):
        return self._element(g) + self._element(h, "h")

    def inverse(self, g):
        return -self._element(g)

    def hat(self, xi):
        """Block-diagonal algebra matrix: a translation block and an so(2) block, ``(..., 5, 5)``."""
        xi = self._algebra(xi)
        X = np.zeros(xi.shape[:-1] + (5, 5))
        X[..., 0, 2] = xi[..., 0]
        X[..., 1, 2] = xi[..., 1]
        X[..., 3, 4] = -xi[..., 2]
        X[..., 4, 3] = xi[..., 2]
        return X

    def vee(self, X):
        X = self._square(X, "X")
        return np.stack([X[..., 0, 2], X[..., 1, 2], X[..., 4, 3]], -1)

    def exp(self, xi):
        return self._algebra(xi).copy()

    def log(self, g):
        g = self._element(g).copy()
        g[..., 2] = wrap_angle(g[..., 2])
        return g

    def matrix(self, g):
        """Block-diagonal ``(..., 5, 5)``: translation [[I, (x, y)], [0, 1]] beside R(theta)."""
        g = self._element(g)
        G = _eye(5, g.shape[:-1])
        G[..., 0, 2] = g[..., 0]
        G[..., 1, 2] = g[..., 1]
        G[..., 3:5, 3:5] = _rot(g[..., 2])
        return G

    def from_matrix(self, G):
        G = self._square(G, "G")
        _check_rotation(G[..., 3:5, 3:5], "G")
        x, y = G[..., 0, 2], G[..., 1, 2]
        return np.stack([x, y, np.arctan2(G[..., 4, 3], G[..., 3, 3])], -1)


class _SE2(LieGroup):
    """The special Euclidean group SE(2): elements ``(..., 3)`` = (x, y, theta), book (1.2).

    All maps are closed forms, vectorized over leading axes with no Python loops.
    """

    name = "SE(2)"
    dim = 3
    coords = ("x", "y", "theta")
    angular = (False, False, True)
    matrix_size = 3
    commutative = False

    def identity(self, batch_shape=()):
        return np.zeros(tuple(batch_shape) + (3,))

    def compose(self, g, h):
        """g o h = (x + u cos th - v sin th, y + u sin th + v cos th, th + beta), book (1.7)-(1.9)."""
        g = self._element(g)
        h = self._element(h, "h")
        x, y, t = g[..., 0], g[..., 1], g[..., 2]
        u, v, b = h[..., 0], h[..., 1], h[..., 2]
        c, s = np.cos(t), np.sin(t)
        # np.broadcast_shapes costs microseconds: skip it in the common equal-shapes case
        out = np.empty(g.shape if g.shape == h.shape else _batch(g, h, tail=1) + (3,))
        out[..., 0] = x + c * u - s * v
        out[..., 1] = y + s * u + c * v
        out[..., 2] = t + b
        return out

    def bracket(self, xi1, xi2):
        """[xi1, xi2] = (w2 v1y - w1 v2y, w1 v2x - w2 v1x, 0), the vee of X1 X2 - X2 X1 with (1.54)."""
        xi1 = self._algebra(xi1, "xi1")
        xi2 = self._algebra(xi2, "xi2")
        v1x, v1y, w1 = xi1[..., 0], xi1[..., 1], xi1[..., 2]
        v2x, v2y, w2 = xi2[..., 0], xi2[..., 1], xi2[..., 2]
        out = np.zeros(_batch(xi1, xi2, tail=1) + (3,))
        out[..., 0] = -w1 * v2y + w2 * v1y
        out[..., 1] = w1 * v2x - w2 * v1x
        return out

    def inverse(self, g):
        """g^-1 = (-x cos th - y sin th, x sin th - y cos th, -th), so g^-1 g = e, book (1.10)."""
        g = self._element(g)
        x, y, t = g[..., 0], g[..., 1], g[..., 2]
        c, s = np.cos(t), np.sin(t)
        out = np.empty(g.shape)
        out[..., 0] = -c * x - s * y
        out[..., 1] = s * x - c * y
        out[..., 2] = -t
        return out

    def left_lifted_action(self, h, g):
        """T_g L_h = [[cos b, -sin b, 0], [sin b, cos b, 0], [0, 0, 1]] for h = (u, v, b), book (1.31)."""
        h = self._element(h, "h")
        g = self._element(g)
        b = h[..., 2]
        c, s = np.cos(b), np.sin(b)
        M = np.zeros(_batch(h, g, tail=1) + (3, 3))
        M[..., 0, 0] = c
        M[..., 0, 1] = -s
        M[..., 1, 0] = s
        M[..., 1, 1] = c
        M[..., 2, 2] = 1.0
        return M

    def right_lifted_action(self, h, g):
        """T_g R_h = [[1, 0, -(u sin th + v cos th)], [0, 1, u cos th - v sin th], [0, 0, 1]], book (1.37)."""
        h = self._element(h, "h")
        g = self._element(g)
        u, v = h[..., 0], h[..., 1]
        t = g[..., 2]
        c, s = np.cos(t), np.sin(t)
        M = np.zeros(_batch(h, g, tail=1) + (3, 3))
        M[..., 0, 0] = 1.0
        M[..., 1, 1] = 1.0
        M[..., 2, 2] = 1.0
        M[..., 0, 2] = -(u * s + v * c)
        M[..., 1, 2] = u * c - v * s
        return M

    def Ad(self, g):
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

    def Ad_inv(self, g):
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

    def hat(self, xi):
        """xi^ = [[0, -w, vx], [w, 0, vy], [0, 0, 0]] for xi = (vx, vy, w), ``(..., 3, 3)``; book (1.54)."""
        xi = self._algebra(xi)
        X = np.zeros(xi.shape[:-1] + (3, 3))
        X[..., 0, 1] = -xi[..., 2]
        X[..., 1, 0] = xi[..., 2]
        X[..., 0, 2] = xi[..., 0]
        X[..., 1, 2] = xi[..., 1]
        return X

    def vee(self, X):
        """(vx, vy, w) from an se(2) matrix; raises ValueError if X is not of the form (1.54)."""
        X = self._square(X, "X")
        ok = np.allclose(X[..., 2, :], 0.0, atol=1e-9) and np.allclose(
            X[..., 0, 0], 0.0, atol=1e-9) and np.allclose(X[..., 1, 1], 0.0, atol=1e-9) and np.allclose(
            X[..., 0, 1], -X[..., 1, 0], atol=1e-9)
        if not ok:
            raise ValueError("X must be an se(2) matrix [[0, -w, vx], [w, 0, vy], [0, 0, 0]] as in (1.54)")
        return np.stack([X[..., 0, 2], X[..., 1, 2], X[..., 1, 0]], -1)

    def exp(self, xi):
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

    def log(self, g):
        """log(g) = (V(th)^-1 (x, y), th) with th wrapped to (-pi, pi], inverse of :meth:`exp`.

        V^-1 = (h / sin h) R(-h) with h = th/2 in (-pi/2, pi/2], so it never divides by zero.
        """
        g = self._element(g)
        x, y = g[..., 0], g[..., 1]
        t = wrap_angle(g[..., 2])
        h = 0.5 * t
        c, s = np.cos(h), np.sin(h)
        k = s / h if h.all() else np.divide(s, h, out=np.ones_like(h), where=h != 0)
        out = np.empty(g.shape)
        out[..., 0] = (c * x + s * y) / k
        out[..., 1] = (c * y - s * x) / k
        out[..., 2] = t
        return out

    def matrix(self, g):
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

    def from_matrix(self, G):
        """(x, y, th) from a homogeneous matrix; ValueError unless it is a proper rigid motion (1.2)."""
        G = self._square(G, "G")
        if not np.allclose(G[..., 2, :], [0.0, 0.0, 1.0], atol=1e-8):
            raise ValueError("G must have last row [0, 0, 1] to be a homogeneous SE(2) matrix (1.2)")
        _check_rotation(G[..., :2, :2], "G")
        return np.stack([G[..., 0, 2], G[..., 1, 2], np.arctan2(G[..., 1, 0], G[..., 0, 0])], -1)

    def act_on_points(self, g, p):
        """World positions ``(..., 2)`` of body-frame points p ``(..., 2)`` under g, book (1.11)-(1.12)."""
        g = self._element(g)
        p = as_array(p, "p", (2,), what=" (body-frame point coordinates)")
        t = g[..., 2]
        c, s = np.cos(t), np.sin(t)
        out = np.empty(np.broadcast_shapes(g.shape[:-1], p.shape[:-1]) + (2,))
        out[..., 0] = g[..., 0] + c * p[..., 0] - s * p[..., 1]
        out[..., 1] = g[..., 1] + s * p[..., 0] + c * p[..., 1]
        return out


R = Rn(1)
R2 = Rn(2)
RPlus = _RPlus()
SO2 = _SO2()
R2xS1 = _R2xS1()
SE2 = _SE2()

#: Every group of chapter 1, for tests and demos that loop over them.
ALL_GROUPS = {"R": R, "R2": R2, "RPlus": RPlus, "SO2": SO2, "S1": S1(), "S1_cycles": S1(1.0),
              "R2xS1": R2xS1, "SE2": SE2}

"""The abstract Lie-group interface, angle reduction and batching helpers (numpy only).

A group of the course is a singleton object (an instance of a :class:`LieGroup` subclass). Each
subclass declares its dimensions once, as class attributes (or in ``__init__`` for families such
as R^n), the way jaxlie's ``register_lie_group`` does:

* ``coords``       names of the coordinates of an element; ``param_dim = len(coords)``
* ``param_dim``    number of coordinates of an element, the trailing axis of ``g``
* ``tangent_dim``  dimension of the Lie algebra, the trailing axis of ``xi``
* ``matrix_size``  n of the n x n matrix representation
* ``periods``      per coordinate, ``None`` or the period after which it repeats (angles)
* ``principal_radius``  ``None``, or the radius rho of the ball |xi| < rho on which log(exp(xi)) = xi,
  for a group whose principal domain is a ball rather than one period per coordinate (pi for
  SO(3)); tests draw principal algebra vectors from it and ``periods``

and implements the abstract methods (``compose``, ``inverse``, lifted actions, ``hat``/``vee``,
``exp``/``log``, ``matrix``/``from_matrix``, ``nearest_element``). Everything else (adjoints,
velocity conversions, bracket, membership, differences, finite-difference Jacobians) is written
once here in terms of those. Nothing in gm_core asks which group it holds: group-specific
behaviour is a method or attribute of the group.
"""
from __future__ import annotations

import abc
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.validation import BoolArray, FloatArray, as_array, batch_shape, check_option, check_shape, real_number

__all__ = [
    "LieGroup", "wrap_angle", "wrap_periodic", "matvec", "check_group", "TWO_PI",
    # unchecked helpers the groups' modules share
    "wrap_unchecked", "mod_period", "eye_batch", "as_rng", "check_scale", "rotation_matrix",
    "angle_of_block", "check_rotation", "check_entries",
]

TWO_PI = 2.0 * np.pi
_PI = np.pi


# ---------------------------------------------------------------------------------- angles
def wrap_unchecked(t: FloatArray) -> FloatArray:
    """Unchecked :func:`wrap_angle` for a float array (returns ``t`` itself when already in range)."""
    if t.size == 0 or (t.max() <= _PI and t.min() > -_PI):
        return t
    out = np.array(t, dtype=float)
    big = ~((out <= _PI) & (out > -_PI))
    # numpy's sin and cos reduce their argument exactly (to within rounding for every finite
    # double, checked against mpmath up to 1e300 in the tests), so atan2 of them is the reduced
    # angle to within an ulp; there is no 2 pi with only 53 bits to subtract.
    r = np.arctan2(np.sin(out[big]), np.cos(out[big]))
    r[r == -_PI] = _PI
    out[big] = r
    return out


def wrap_angle(theta: ArrayLike) -> FloatArray:
    """Angle(s) equal to ``theta`` modulo 2 pi, in (-pi, pi], accurate to rounding for any finite angle.

    Inputs already in (-pi, pi] come back unchanged (exactly). The interval is that of doubles:
    ``-np.pi`` (the double nearest -pi) maps to ``np.pi``, so -pi and pi give one value. Large
    angles (1e8, 1e300) are reduced exactly, not with a rounded 2 pi.
    """
    t = as_array(theta, "theta", what=" (angles in radians)")
    out = wrap_unchecked(t)
    return out.copy() if out is t else out


def wrap_periodic(x: ArrayLike, period: float) -> FloatArray:
    """Unchecked reduction of a float array ``x`` modulo ``period`` into (-period/2, period/2].

    For ``period == 2 pi`` this is :func:`wrap_angle` (exact reduction by the true 2 pi); for any
    other period the reduction is by that double, exactly (``np.remainder``).
    """
    if period == TWO_PI:
        return wrap_unchecked(np.asarray(x, dtype=float))
    r = np.remainder(x, period)
    return np.where(r > 0.5 * period, r - period, r)


def mod_period(x: FloatArray, period: float) -> FloatArray:
    """Unchecked representative of ``x`` modulo ``period`` in [0, period)."""
    if period == TWO_PI:
        r = wrap_unchecked(x)
        r = np.where(r < 0, r + TWO_PI, r)
    else:
        r = np.remainder(x, period)
    return np.where(r >= period, 0.0, r)      # -1e-20 mod 1 rounds to 1.0, which is 0 mod 1


def matvec(M: ArrayLike, v: ArrayLike) -> FloatArray:
    """Batched matrix-vector product ``M @ v`` for ``M: (..., n, m)`` and ``v: (..., m)``."""
    M = as_array(M, "M", what=" (a batch of matrices (..., n, m))")
    v = as_array(v, "v", what=" (a batch of vectors (..., m))")
    if M.ndim < 2 or v.ndim < 1:
        raise ValueError(f"M must have shape (..., n, m) and v (..., m); got shapes {M.shape} and {v.shape}")
    if M.shape[-1] != v.shape[-1]:
        raise ValueError(f"M has {M.shape[-1]} columns but v has {v.shape[-1]} entries; they must agree")
    batch_shape(("M", M, 2), ("v", v, 1))
    return _matvec(M, v)


def _matvec(M, v):
    return np.einsum("...ij,...j->...i", M, v)


def eye_batch(n: int, batch: tuple[int, ...]) -> FloatArray:
    """``batch`` copies of the n x n identity, shape ``batch + (n, n)``."""
    return np.broadcast_to(np.eye(n), tuple(batch) + (n, n)).copy()


def check_group(group: Any, name: str = "group") -> LieGroup:
    """Return ``group`` after checking it is one of gm_core's Lie groups (TypeError otherwise)."""
    if not isinstance(group, LieGroup):
        raise TypeError(
            f"{name} must be one of gm_core's Lie groups (e.g. gm_core.SE2, gm_core.RPlus); "
            f"got {type(group).__name__}"
        )
    return group


# ---------------------------------------------------------------------------------- the interface
class LieGroup(abc.ABC):
    """The interface every group of the course implements (see the module docstring).

    Elements ``g`` are float arrays ``(..., param_dim)``, algebra vectors ``xi`` ``(..., tangent_dim)``,
    matrices ``(..., matrix_size, matrix_size)``; leading axes are batch axes and broadcast.
    """

    name: str = "G"
    label: str = "G"            # short label for plots, e.g. "R⁺"
    coords: tuple = ()
    periods: tuple = ()
    param_dim: ClassVar[int] = 0
    tangent_dim: ClassVar[int] = 0
    matrix_size: ClassVar[int] = 0
    principal_radius: ClassVar[float | None] = None

    def __init__(self) -> None:
        ok = (self.param_dim >= 1 and self.tangent_dim >= 1 and self.matrix_size >= 1
              and len(self.coords) == self.param_dim and len(self.periods) == self.param_dim)
        if not ok:
            raise TypeError(f"{type(self).__name__} must declare param_dim, tangent_dim, matrix_size, "
                            f"coords (one name per coordinate) and periods")

    @property
    def dim(self) -> int:
        """Number of coordinates, equal to the tangent dimension for every group of the course."""
        if self.param_dim != self.tangent_dim:
            raise AttributeError(f"{self.name} has {self.param_dim} coordinates but a "
                                 f"{self.tangent_dim}-dimensional algebra: use param_dim or tangent_dim")
        return self.param_dim

    @property
    def angular(self) -> tuple[bool, ...]:
        """Which coordinates are periodic (compared modulo their period), a tuple of bools."""
        return tuple(p is not None for p in self.periods)

    @override
    def __repr__(self) -> str:
        return self.name

    # ------------------------------------------------------------------ checking
    def _element(self, g, name="g"):
        """``g`` as a float array ``(..., param_dim)`` of valid elements (ValueError naming ``name``)."""
        return as_array(g, name, (self.param_dim,), what=f" ({', '.join(self.coords)}) of {self.name}")

    def _algebra(self, xi, name="xi"):
        return as_array(xi, name, (self.tangent_dim,), what=f", a velocity in the Lie algebra of {self.name}")

    def _square(self, M, name):
        n = self.matrix_size
        return as_array(M, name, (n, n), what=f", a {n}x{n} matrix for {self.name}")

    def _batch(self, *named):
        """Broadcast batch shape of ``(name, array)`` pairs of elements or algebra vectors."""
        return batch_shape(*((n, a, 1) for n, a in named))

    def contains(self, g: ArrayLike) -> BoolArray:
        """True where ``g`` (any finite array ``(..., param_dim)``) holds the coordinates of an element.

        Shape ``g.shape[:-1]``. Subclasses narrow it: positive numbers for (R+, x), [0, k) for
        (S^1, + mod k). Unlike the other methods this never raises for a well-shaped array of
        numbers: it is the membership test (closure checks, drawing).
        """
        g = as_array(g, "g", (self.param_dim,), allow_nan=True)
        return np.all(np.isfinite(g), axis=-1) & self._in_domain(g)

    def _in_domain(self, g):
        return np.ones(g.shape[:-1], dtype=bool)

    def project(self, g: ArrayLike) -> FloatArray:
        """The canonical coordinates of the element ``g`` (angles of S^1 reduced into [0, k)).

        For groups whose every coordinate vector is an element this is a validated copy.
        """
        return self._element(g).copy()

    def identity(self, batch_shape: int | tuple[int, ...] = ()) -> FloatArray:
        """The identity element e, shape ``batch_shape + (param_dim,)``; book (1.iv)."""
        shape = check_shape(batch_shape, "batch_shape")
        return np.broadcast_to(self._identity_coords(), shape + (self.param_dim,)).copy()

    @abc.abstractmethod
    def _identity_coords(self):
        """Coordinates ``(param_dim,)`` of the identity element."""

    # ------------------------------------------------------------------ group structure
    @abc.abstractmethod
    def compose(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """The product g o h, shape ``(..., param_dim)``; book (1.6), (1.9)."""

    @abc.abstractmethod
    def inverse(self, g: ArrayLike) -> FloatArray:
        """The inverse g^-1 with g o g^-1 = e, shape ``(..., param_dim)``; book (1.v), (1.10)."""

    @abc.abstractmethod
    def left_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g L_h = d(h g)/dg, shape ``(..., param_dim, param_dim)``; book (1.19)-(1.20)."""

    @abc.abstractmethod
    def right_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g R_h = d(g h)/dg, shape ``(..., param_dim, param_dim)``; book (1.21)."""

    def Ad(self, g: ArrayLike) -> FloatArray:
        """Adjoint Ad_g = T_g R_{g^-1} T_e L_g, body to spatial velocity, ``(..., dim, dim)``; book (1.40)."""
        g = self._element(g)
        e = self.identity()
        return self.right_lifted_action(self.inverse(g), g) @ self.left_lifted_action(g, e)

    def Ad_inv(self, g: ArrayLike) -> FloatArray:
        """Adjoint inverse Ad_g^-1 = Ad_{g^-1}, spatial to body velocity, ``(..., dim, dim)``; book (1.41)."""
        return self.Ad(self.inverse(self._element(g)))

    # ------------------------------------------------------------------ algebra and exp
    @abc.abstractmethod
    def hat(self, xi: ArrayLike) -> FloatArray:
        """Matrix form of a Lie-algebra vector, ``(..., m, m)``; book (1.54) for SE(2)."""

    @abc.abstractmethod
    def vee(self, X: ArrayLike) -> FloatArray:
        """Vector form ``(..., tangent_dim)`` of a Lie-algebra matrix; inverse of :meth:`hat`."""

    def bracket(self, xi1: ArrayLike, xi2: ArrayLike) -> FloatArray:
        """Lie bracket [xi1, xi2] ``(..., tangent_dim)``: the vee of hat(xi1) hat(xi2) - hat(xi2) hat(xi1).

        This matrix commutator is the definition; groups override it with a closed form, and
        abelian groups return zero.
        """
        xi1 = self._algebra(xi1, "xi1")
        xi2 = self._algebra(xi2, "xi2")
        self._batch(("xi1", xi1), ("xi2", xi2))
        X1, X2 = self.hat(xi1), self.hat(xi2)
        return self.vee(X1 @ X2 - X2 @ X1)

    def ad(self, xi: ArrayLike) -> FloatArray:
        """Matrix ``(..., dim, dim)`` of ad_xi = [xi, .], so that ad(xi) @ eta = bracket(xi, eta)."""
        xi = self._algebra(xi)
        basis = np.eye(self.tangent_dim)
        cols = self.bracket(xi[..., None, :], basis)  # (..., dim[j], dim)
        return np.swapaxes(cols, -1, -2)

    @abc.abstractmethod
    def exp(self, xi: ArrayLike) -> FloatArray:
        """Group exponential: the unit-time flow from e along the invariant field of xi; section 1.6.4."""

    @abc.abstractmethod
    def log(self, g: ArrayLike) -> FloatArray:
        """Principal inverse of :meth:`exp`: the algebra vector whose unit flow reaches g."""

    @abc.abstractmethod
    def matrix(self, g: ArrayLike) -> FloatArray:
        """Matrix representation of g, ``(..., m, m)``; book (1.1), (1.2)."""

    @abc.abstractmethod
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        """Element coordinates ``(..., param_dim)`` of a group matrix; ValueError if G is not one."""

    @abc.abstractmethod
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        """Coordinates ``(..., param_dim)`` read from a matrix that is only close to a group matrix.

        Truncated Taylor sums and products (I + A/n)^k have scaled rotation blocks; this reads
        translations as they are and the angle of a 2x2 block as that of its rotational part
        (the nearest rotation). Exact group matrices round-trip. Used by ``gm_core.calculus``.
        """

    def coordinate_matrix(self, q: ArrayLike) -> FloatArray:
        """The matrix formula applied to coordinates ``q`` that may lie outside the group.

        Equal to :meth:`matrix` for elements; (R+, x) overrides it so that an Euler state that
        overshot to a number <= 0 still has a (1x1) matrix.
        """
        return self.matrix(self._element(q, "q"))

    def euler_step(self, g: ArrayLike, xi: ArrayLike, dt: float, side: str = "left") -> FloatArray:
        """One forward-Euler step g + dt T_e L_g xi (``side="left"``, (1.46)) or g + dt T_e R_g xi
        (``"right"``, (1.47)) of an invariant field, in coordinates, shape ``(..., param_dim)``.

        The result may leave the group (e.g. a number <= 0 for (R+, x) with dt xi <= -1); it is
        returned as it is, so the failure of too few steps stays visible.
        """
        side = check_option(side, "side", ("left", "right"))
        g = self._element(g)
        xi = self._algebra(xi)
        dt = real_number(dt, "dt", " (a time step)")
        lifted = self.left_lifted_action if side == "left" else self.right_lifted_action
        return g + dt * _matvec(lifted(g, self.identity()), xi)

    # ------------------------------------------------------------------ velocities, (1.32)-(1.45)
    def _velocity_pair(self, g, v, vname):
        g = self._element(g)
        v = as_array(v, vname, (self.param_dim,), what=f", a velocity of an element of {self.name}")
        self._batch(("g", g), (vname, v))
        return g, v

    def world_to_body(self, g: ArrayLike, g_dot: ArrayLike) -> FloatArray:
        """Body velocity xi = T_g L_{g^-1} g_dot, ``(..., dim)``; book (1.32), (1.26) for SE(2)."""
        g, g_dot = self._velocity_pair(g, g_dot, "g_dot")
        return _matvec(self.left_lifted_action(self.inverse(g), g), g_dot)

    def body_to_world(self, g: ArrayLike, xi: ArrayLike) -> FloatArray:
        """World velocity g_dot = T_e L_g xi, ``(..., dim)``; book (1.33), (1.28) for SE(2)."""
        g, xi = self._velocity_pair(g, xi, "xi")
        return _matvec(self.left_lifted_action(g, self.identity()), xi)

    def world_to_spatial(self, g: ArrayLike, g_dot: ArrayLike) -> FloatArray:
        """Spatial velocity xi_s = T_g R_{g^-1} g_dot, ``(..., dim)``; book (1.38)."""
        g, g_dot = self._velocity_pair(g, g_dot, "g_dot")
        return _matvec(self.right_lifted_action(self.inverse(g), g), g_dot)

    def spatial_to_world(self, g: ArrayLike, xi_s: ArrayLike) -> FloatArray:
        """World velocity g_dot = T_e R_g xi_s, ``(..., dim)``; book (1.39)."""
        g, xi_s = self._velocity_pair(g, xi_s, "xi_s")
        return _matvec(self.right_lifted_action(g, self.identity()), xi_s)

    def body_to_spatial(self, g: ArrayLike, xi: ArrayLike) -> FloatArray:
        """Spatial velocity xi_s = Ad_g xi, ``(..., dim)``; book (1.40), (1.43)."""
        g, xi = self._velocity_pair(g, xi, "xi")
        return _matvec(self.Ad(g), xi)

    def spatial_to_body(self, g: ArrayLike, xi_s: ArrayLike) -> FloatArray:
        """Body velocity xi = Ad_g^-1 xi_s, ``(..., dim)``; book (1.41), (1.45)."""
        g, xi_s = self._velocity_pair(g, xi_s, "xi_s")
        return _matvec(self.Ad_inv(g), xi_s)

    # ------------------------------------------------------------------ utilities
    def difference(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """Coordinate difference g - h, periodic coordinates reduced into (-k/2, k/2].

        ``g`` and ``h`` are coordinate arrays ``(..., param_dim)`` (checked for shape and
        finiteness, not for membership, so Euler states that left the group can be compared).
        """
        g = as_array(g, "g", (self.param_dim,), what=f" (coordinates of {self.name})")
        h = as_array(h, "h", (self.param_dim,), what=f" (coordinates of {self.name})")
        self._batch(("g", g), ("h", h))
        d = g - h
        if any(p is not None for p in self.periods):
            for j, p in enumerate(self.periods):
                if p is not None:
                    d[..., j] = wrap_periodic(d[..., j], p)
        return d

    def isclose(self, g: ArrayLike, h: ArrayLike, atol: float = 1e-9) -> BoolArray:
        """True where elements g and h agree to within ``atol`` in every coordinate (angles modulo
        their period); shape the broadcast batch shape."""
        g = self._element(g)
        h = self._element(h, "h")
        atol = as_array(atol, "atol", what=" (a non-negative tolerance)")
        if atol.ndim != 0 or atol < 0:
            raise ValueError(f"atol must be a single non-negative number; got {atol!r}")
        return np.all(np.abs(self.difference(g, h)) <= atol, axis=-1)

    def random(self, rng: np.random.Generator | int | None, size: int | tuple[int, ...] = (), scale: float = 1.0) -> FloatArray:
        """Random elements ``size + (param_dim,)`` for tests and demos.

        Non-periodic coordinates are uniform in (-3 scale, 3 scale), periodic ones uniform over
        one period (-k/2, k/2). ``rng`` is a numpy Generator (or an int seed); ``scale`` stretches
        the coordinates (groups whose coordinates are not a vector space override it).
        """
        rng = as_rng(rng)
        size = check_shape(size, "size")
        scale = check_scale(scale)
        out = rng.uniform(-3.0, 3.0, size + (self.param_dim,))
        mask = np.array(self.angular)
        if mask.any():
            half = 0.5 * np.array([p for p in self.periods if p is not None])
            out[..., mask] = rng.uniform(-half, half, size + (int(mask.sum()),))
        if scale != 1.0:
            out[..., ~mask] *= scale
        return out

    def _fd_step(self, g, eps):
        return eps * (1.0 + np.abs(g))

    def _numerical_jacobian(self, f, g, eps):
        g = self._element(g)
        eps = as_array(eps, "eps", what=" (a finite-difference step)")
        if eps.ndim != 0 or not 0 < eps < 1:
            raise ValueError(f"eps must be a single number in (0, 1); got {eps!r}")
        step = self._fd_step(g, float(eps))
        cols = []
        for j in range(self.param_dim):
            d = np.zeros_like(g)
            d[..., j] = step[..., j]
            cols.append(self.difference(f(g + d), f(g - d)) / (2.0 * step[..., j : j + 1]))
        return np.stack(cols, axis=-1)

    def numerical_left_lifted_action(self, h: ArrayLike, g: ArrayLike, eps: float = 1e-6) -> FloatArray:
        """T_g L_h by central differences of the group operation, an independent route to (1.20)."""
        h = self._element(h, "h")
        self._batch(("h", h), ("g", self._element(g)))
        return self._numerical_jacobian(lambda x: self.compose(h, x), g, eps)

    def numerical_right_lifted_action(self, h: ArrayLike, g: ArrayLike, eps: float = 1e-6) -> FloatArray:
        """T_g R_h by central differences of the group operation, an independent route to (1.21)."""
        h = self._element(h, "h")
        self._batch(("h", h), ("g", self._element(g)))
        return self._numerical_jacobian(lambda x: self.compose(x, h), g, eps)


def as_rng(rng: np.random.Generator | int | None) -> np.random.Generator:
    """``rng`` itself, or a Generator seeded with the non-negative int ``rng`` (TypeError otherwise)."""
    if isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool) and rng >= 0:
        return np.random.default_rng(int(rng))
    raise TypeError(f"rng must be a numpy random Generator (np.random.default_rng(seed)) or a "
                    f"non-negative int seed; got {type(rng).__name__}")


def check_scale(scale: Any) -> float:
    """``scale`` as a float after checking it is one positive number (at most 1e100)."""
    s = as_array(scale, "scale", what=" (a positive size factor)")
    if s.ndim != 0 or s <= 0 or s > 1e100:
        raise ValueError(f"scale must be a single positive number (at most 1e100); got {scale!r:.40}")
    return float(s)


# ---------------------------------------------------------------------------------- shared pieces
def rotation_matrix(theta: ArrayLike) -> FloatArray:
    """Rotation matrices ``(..., 2, 2)`` by the angles ``theta`` (unchecked)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def angle_of_block(B: FloatArray) -> FloatArray:
    """Angle of the rotational part of 2x2 blocks ``(..., 2, 2)`` (nearest rotation, polar decomposition)."""
    return np.arctan2(B[..., 1, 0] - B[..., 0, 1], B[..., 0, 0] + B[..., 1, 1])


#: Absolute tolerance of the structure checks in ``from_matrix`` (entries of size about 1).
MATRIX_ATOL = 1e-8


def check_rotation(Rm: FloatArray, name: str) -> None:
    """ValueError unless every 2x2 block of ``Rm`` is a rotation to within :data:`MATRIX_ATOL`."""
    with np.errstate(over="ignore", invalid="ignore"):     # huge entries fail the check below
        RtR = np.swapaxes(Rm, -1, -2) @ Rm
        det = Rm[..., 0, 0] * Rm[..., 1, 1] - Rm[..., 0, 1] * Rm[..., 1, 0]
    if not (np.all(np.abs(RtR - np.eye(2)) <= MATRIX_ATOL) and np.all(np.abs(det - 1.0) <= MATRIX_ATOL)):
        raise ValueError(
            f"{name} is not a rotation: its 2x2 rotation block must satisfy R^T R = I and det R = +1 "
            f"to within {MATRIX_ATOL:g}"
        )


def check_entries(M: FloatArray, expected: FloatArray | float, name: str, what: str) -> None:
    """ValueError unless ``M`` equals ``expected`` entrywise to within :data:`MATRIX_ATOL`."""
    if not np.all(np.abs(M - expected) <= MATRIX_ATOL):
        raise ValueError(f"{name} must be {what} (entries within {MATRIX_ATOL:g})")

"""The rotation group SO(3) in exponential coordinates (rotation vectors), after Sola et al. 2018 (numpy only).

An element is a rotation vector r = theta u (angle theta about the unit axis u), the exponential
coordinates of the rotation matrix R = exp(r^). Every rotation has a *principal* vector, with
|r| <= pi; the maps return it (``compose`` and ``inverse`` included), and accept any finite r
(an Euler state or a finite-difference probe just past the cut |r| = pi names a rotation too).
At |r| = pi, r and -r are one rotation: :meth:`SO3.difference` and ``isclose`` know it.

Past the cut, the vectors r + 2 pi k u of the same rotation are coordinates too (a chart around
each, up to |r| < 2 pi, where exponential coordinates are singular). Composing with e keeps the
other factor's coordinates as they are, so T_e L_g and T_e R_g, hence invariant fields and Euler
steps, give velocities in g's own chart and a flow integrated in coordinates crosses the cut
smoothly; every other product is principal.

Every formula is written with the unit axis u and the half angle h = theta/2, so nothing is divided
by theta^2 and there is no cancellation at any angle: 1 - cos theta = 2 sin^2 h, sin theta / theta
and sin h / h are computed as they stand. The logarithm of a matrix goes through the unit
quaternion, read from the largest of the trace and the diagonal entries (Shepperd's method), and
theta = 2 atan2(|q_v|, q_w): no arccos or arcsin of a rounded number, so it is accurate near 0 and
near pi alike. The Jacobians are those of Sola, Deray and Atchuthan, "A micro Lie theory for state
estimation in robotics" (2018), (143)-(146).
"""
from __future__ import annotations

from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups.base import MATRIX_ATOL, LieGroup, as_rng, check_entries, check_scale, wrap_unchecked
from gm_core.validation import FloatArray, as_array, check_shape

__all__ = ["SO3"]

_PI = np.pi
#: Largest length of a principal rotation vector: pi, plus a few roundings of |r| itself.
_PI_TOL = _PI * (1.0 + 8.0 * np.finfo(float).eps)
#: ``random`` keeps its angles this far below pi, clear of the cut where r and -r meet.
RANDOM_MARGIN = 1e-3


# ---------------------------------------------------------------------------------- helpers
def _norm(r: FloatArray) -> FloatArray:
    """|r| over the last axis, with no overflow or underflow of the squares (1e300, 1e-300); inf
    only when |r| itself exceeds the largest float."""
    with np.errstate(over="ignore"):
        return np.asarray(np.hypot(np.hypot(r[..., 0], r[..., 1]), r[..., 2]))


def _axis_angle(r: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(u, theta): unit axes ``(..., 3)`` (zero where theta = 0) and angles |r| ``(...)``."""
    theta = _norm(r)
    safe = np.where(theta > 0, theta, 1.0)
    return r / safe[..., None], theta


def _skew(u: FloatArray) -> FloatArray:
    """[u]x ``(..., 3, 3)``, the matrix with [u]x v = u x v."""
    K = np.zeros(u.shape[:-1] + (3, 3))
    K[..., 0, 1], K[..., 0, 2] = -u[..., 2], u[..., 1]
    K[..., 1, 0], K[..., 1, 2] = u[..., 2], -u[..., 0]
    K[..., 2, 0], K[..., 2, 1] = -u[..., 1], u[..., 0]
    return K


def _combine(u: FloatArray, a: FloatArray, b: FloatArray, c: FloatArray) -> FloatArray:
    """a I + b u u^T + c [u]x, ``(..., 3, 3)``: the shape of every matrix of this module."""
    M = b[..., None, None] * (u[..., :, None] * u[..., None, :]) + c[..., None, None] * _skew(u)
    M[..., [0, 1, 2], [0, 1, 2]] += a[..., None]
    return M


def _sinc(h: FloatArray) -> FloatArray:
    """sin(h) / h, equal to 1 at h = 0."""
    return np.divide(np.sin(h), h, out=np.ones_like(h), where=h != 0)


def _check_length(r: FloatArray, name: str) -> FloatArray:
    """``r`` after checking that its length |r|, the rotation angle, is a finite float (ValueError)."""
    if not np.all(np.isfinite(_norm(r))):
        raise ValueError(f"{name} is too large: its length |{name}|, the rotation angle, overflows a float")
    return r


def _principal(r: FloatArray) -> FloatArray:
    """The principal vector (|r| <= pi) of the rotation r (unchecked); ``r`` itself where it already is one.

    Longer vectors keep their axis and get the angle |r| reduced modulo 2 pi into (-pi, pi] by
    :func:`~gm_core.groups.base.wrap_unchecked` (exactly, for any |r|; a negative reduced angle
    turns the axis round).
    """
    u, theta = _axis_angle(r)
    big = theta > _PI_TOL
    if not big.any():
        return r
    out = np.array(r, dtype=float)
    out[big] = wrap_unchecked(theta[big])[..., None] * u[big]
    return out


def _rotvec_of_quaternion(q: FloatArray) -> FloatArray:
    """Principal rotation vectors ``(..., 3)`` of quaternions q = (w, x, y, z) of any non-zero length.

    theta = 2 atan2(|v|, |w|) lies in [0, pi] and is accurate at every angle; the vector is
    theta v / |v| with the sign of w (q and -q are one rotation), zero where v = 0.
    """
    w, v = q[..., 0], q[..., 1:]
    sign = np.where(w < 0, -1.0, 1.0)
    n = _norm(v)
    k = np.divide(np.arctan2(n, np.abs(w)), n, out=np.zeros_like(n), where=n > 0)
    return (2.0 * sign * k)[..., None] * v


def _log_rotation(R: FloatArray) -> FloatArray:
    """Principal rotation vector of matrices ``(..., 3, 3)`` that are (close to) rotations, unchecked.

    Shepperd's method: of the four expressions of 4 q_i q for the unit quaternion q of R, take the
    one whose pivot (1 + tr R, or 1 + 2 R_ii - tr R) is largest, so that no small number is
    divided by and no square root of a rounded small difference is taken.
    """
    tr = R[..., 0, 0] + R[..., 1, 1] + R[..., 2, 2]
    d21, d02, d10 = R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]
    s01, s02, s12 = R[..., 0, 1] + R[..., 1, 0], R[..., 0, 2] + R[..., 2, 0], R[..., 1, 2] + R[..., 2, 1]
    cand = np.stack([
        np.stack([1.0 + tr, d21, d02, d10], -1),
        np.stack([d21, 1.0 + 2.0 * R[..., 0, 0] - tr, s01, s02], -1),
        np.stack([d02, s01, 1.0 + 2.0 * R[..., 1, 1] - tr, s12], -1),
        np.stack([d10, s02, s12, 1.0 + 2.0 * R[..., 2, 2] - tr], -1),
    ], -2)                                                   # (..., 4 candidates, 4)
    pick = np.argmax(np.stack([tr, R[..., 0, 0], R[..., 1, 1], R[..., 2, 2]], -1), axis=-1)
    q = np.take_along_axis(cand, pick[..., None, None], axis=-2)[..., 0, :]
    return _rotvec_of_quaternion(q)


def _rodrigues(r: FloatArray) -> FloatArray:
    """exp(r^) = cos theta I + (1 - cos theta) u u^T + sin theta [u]x, with 1 - cos theta = 2 sin^2(theta/2)."""
    u, theta = _axis_angle(r)
    return _combine(u, np.cos(theta), 2.0 * np.sin(0.5 * theta) ** 2, np.sin(theta))


def _product(g: FloatArray, h: FloatArray) -> FloatArray:
    """The group operation, unchecked: the principal vector of R(g) R(h), except that a factor equal
    to e (exactly zero) returns the other factor's coordinates as they are."""
    out = _log_rotation(_rodrigues(g) @ _rodrigues(h))
    g_is_e, h_is_e = ~np.any(g, axis=-1), ~np.any(h, axis=-1)
    if g_is_e.any() or h_is_e.any():
        out = np.where(g_is_e[..., None], h, np.where(h_is_e[..., None], g, out))
    return out


def _jacobian(r: FloatArray, side: float) -> FloatArray:
    """Right (``side = -1``) or left (``+1``) Jacobian of SO(3) at r, Sola et al. (143)-(145).

    J_r(r) = (sin th / th) I + (1 - sin th / th) u u^T - ((1 - cos th) / th) [u]x; J_l(r) = J_r(-r),
    with (1 - cos th) / th = sin h (sin h / h), h = th / 2. exp(r + d) = exp(r) exp(J_r(r) d) and
    exp(r + d) = exp(J_l(r) d) exp(r) to first order in d.
    """
    u, theta = _axis_angle(r)
    h = 0.5 * theta
    s = _sinc(theta)
    return _combine(u, s, 1.0 - s, side * np.sin(h) * _sinc(h))


def _jacobian_inverse(r: FloatArray, side: float) -> FloatArray:
    """Inverse of :func:`_jacobian` (``side`` -1 right, +1 left), Sola et al. (144)-(146), for |r| < 2 pi.

    J_r^-1(r) = a I + (1 - a) u u^T + (th / 2) [u]x with a = (th / 2) cot(th / 2) = cos h / (sin h / h).
    """
    u, theta = _axis_angle(r)
    h = 0.5 * theta
    a = np.cos(h) / _sinc(h)
    return _combine(u, a, 1.0 - a, -side * h)


# ---------------------------------------------------------------------------------- the group
class _SO3(LieGroup):
    """The rotation group SO(3): elements ``(..., 3)`` = rotation vectors r = theta u, |r| <= pi.

    The algebra so(3) holds body angular velocities omega = (omega_x, omega_y, omega_z), with
    omega^ the skew matrix [omega]x; Ad_g is the rotation matrix itself and the bracket is the
    cross product. Lifted actions are the derivatives of ``compose`` in these coordinates, built
    from the right and left Jacobians J_r, J_l of Sola et al. (2018).
    """

    name = "SO(3)"
    label = "SO(3)"
    coords = ("r_x", "r_y", "r_z")
    periods = (None, None, None)
    param_dim: ClassVar[int] = 3
    tangent_dim: ClassVar[int] = 3
    matrix_size: ClassVar[int] = 3
    principal_radius: ClassVar[float | None] = _PI

    @override
    def _identity_coords(self):
        return np.zeros(3)

    @override
    def _element(self, g, name="g"):
        return _check_length(super()._element(g, name), name)

    @override
    def _algebra(self, xi, name="xi"):
        return _check_length(super()._algebra(xi, name), name)

    @override
    def _in_domain(self, g):
        """``contains``: the principal vectors, |g| <= pi to within a few roundings of |g|."""
        return _norm(g) <= _PI_TOL

    @override
    def project(self, g: ArrayLike) -> FloatArray:
        """The principal vector of the rotation g: g itself if |g| <= pi, else the same axis with the
        angle reduced modulo 2 pi (exactly; a negative reduced angle turns the axis round)."""
        return _principal(self._element(g)).copy()

    # ------------------------------------------------------------------ group structure
    @override
    def compose(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """g o h = log(R(g) R(h)): the principal vector of the product of the rotation matrices.

        A factor equal to e (exactly zero) returns the other factor as it is, so e o g = g o e = g
        holds exactly in coordinates, also for a g past the cut (see the module docstring).
        """
        g = self._element(g)
        h = self._element(h, "h")
        self._batch(("g", g), ("h", h))
        return _product(g, h)

    @override
    def inverse(self, g: ArrayLike) -> FloatArray:
        """g^-1 = -g (the rotation by -theta about the same axis), principal vector."""
        return -_principal(self._element(g))

    @override
    def left_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g L_h = J_r(h o g)^-1 J_r(g), the derivative of h o g in g; book (1.20).

        From R(h) exp(g + d) = R(h) R(g) exp(J_r(g) d) = exp(c + J_r(c)^-1 J_r(g) d) with c = h o g
        as ``compose`` returns it; Sola et al. (143)-(144). At g = e this is J_r(h)^-1, the
        left-invariant field of (1.46) in h's own coordinates.
        """
        h = self._element(h, "h")
        g = self._element(g)
        self._batch(("h", h), ("g", g))
        return _jacobian_inverse(_product(h, g), -1.0) @ _jacobian(g, -1.0)

    @override
    def right_lifted_action(self, h: ArrayLike, g: ArrayLike) -> FloatArray:
        """T_g R_h = J_l(g o h)^-1 J_l(g), the derivative of g o h in g; book (1.21).

        From exp(g + d) R(h) = exp(J_l(g) d) R(g) R(h) = exp(c + J_l(c)^-1 J_l(g) d) with c = g o h;
        Sola et al. (145)-(146). At g = e this is J_l(h)^-1, the right-invariant field of (1.47).
        """
        h = self._element(h, "h")
        g = self._element(g)
        self._batch(("h", h), ("g", g))
        return _jacobian_inverse(_product(g, h), 1.0) @ _jacobian(g, 1.0)

    @override
    def Ad(self, g: ArrayLike) -> FloatArray:
        """Ad_g = R(g), the rotation matrix: a spatial angular velocity is the body one rotated; (1.40)."""
        return _rodrigues(self._element(g))

    @override
    def Ad_inv(self, g: ArrayLike) -> FloatArray:
        """Ad_g^-1 = R(g)^T; (1.41)."""
        return np.swapaxes(_rodrigues(self._element(g)), -1, -2).copy()

    # ------------------------------------------------------------------ algebra and exp
    @override
    def hat(self, xi: ArrayLike) -> FloatArray:
        """omega^ = [[0, -wz, wy], [wz, 0, -wx], [-wy, wx, 0]] for omega = (wx, wy, wz), ``(..., 3, 3)``."""
        return _skew(self._algebra(xi))

    @override
    def vee(self, X: ArrayLike) -> FloatArray:
        """(wx, wy, wz) = (X_21, X_02, X_10) from a skew matrix; ValueError if X is not skew."""
        X = self._square(X, "X")
        out = np.stack([X[..., 2, 1], X[..., 0, 2], X[..., 1, 0]], -1)
        check_entries(X, _skew(out), "X", "a skew-symmetric so(3) matrix [[0, -wz, wy], [wz, 0, -wx], [-wy, wx, 0]]")
        return out

    @override
    def bracket(self, xi1: ArrayLike, xi2: ArrayLike) -> FloatArray:
        """[xi1, xi2] = xi1 x xi2, the vee of the commutator of the skew matrices."""
        xi1 = self._algebra(xi1, "xi1")
        xi2 = self._algebra(xi2, "xi2")
        self._batch(("xi1", xi1), ("xi2", xi2))
        return np.cross(xi1, xi2)

    @override
    def ad(self, xi: ArrayLike) -> FloatArray:
        """ad_xi = xi^, so that ad(xi) @ eta = xi x eta, ``(..., 3, 3)``."""
        return self.hat(xi)

    @override
    def exp(self, xi: ArrayLike) -> FloatArray:
        """exp(xi): the rotation by |xi| about xi / |xi| (Rodrigues' formula, :meth:`matrix`).

        In exponential coordinates this is xi itself, reduced to its principal vector: unchanged
        for |xi| <= pi, exact (angle reduced modulo 2 pi) beyond.
        """
        return _principal(self._algebra(xi)).copy()

    @override
    def log(self, g: ArrayLike) -> FloatArray:
        """The principal vector of g (|log g| <= pi), so that exp(log g) = g; g itself if |g| <= pi."""
        return _principal(self._element(g)).copy()

    @override
    def matrix(self, g: ArrayLike) -> FloatArray:
        """R = cos th I + (1 - cos th) u u^T + sin th [u]x for g = th u (Rodrigues), ``(..., 3, 3)``."""
        return _rodrigues(self._element(g))

    @override
    def from_matrix(self, G: ArrayLike) -> FloatArray:
        """Principal rotation vector of a rotation matrix; ValueError unless G^T G = I and det G = +1."""
        G = self._square(G, "G")
        with np.errstate(over="ignore", invalid="ignore"):     # huge entries fail the check below
            GtG = np.swapaxes(G, -1, -2) @ G
            det = np.linalg.det(G)
        if not (np.all(np.abs(GtG - np.eye(3)) <= MATRIX_ATOL) and np.all(np.abs(det - 1.0) <= MATRIX_ATOL)):
            raise ValueError(f"G is not a rotation: it must satisfy G^T G = I and det G = +1 to within {MATRIX_ATOL:g}")
        return _log_rotation(G)

    @override
    def nearest_element(self, M: ArrayLike) -> FloatArray:
        """Principal vector of the nearest rotation to M, the polar factor U diag(1, 1, det U V^T) V^T of its SVD."""
        M = self._square(M, "M")
        big = np.max(np.abs(M), axis=(-2, -1), keepdims=True)
        U, _, Vt = np.linalg.svd(M / np.where(big > 0, big, 1.0))      # scaled: no overflow at 1e300
        d = np.sign(np.linalg.det(U @ Vt))
        U = U.copy()
        U[..., :, 2] *= d[..., None]
        return _log_rotation(U @ Vt)

    # ------------------------------------------------------------------ utilities
    @override
    def difference(self, g: ArrayLike, h: ArrayLike) -> FloatArray:
        """Coordinate difference a - b' of the principal vectors a of g and b of h, b' being the
        representative of h nearest to a: b, or b - 2 pi b / |b| across the cut.

        Like the angle reduction of the other groups, this is zero for r and -r with |r| = pi (one
        rotation) and, for nearby rotations on either side of the cut, the difference in the chart
        around a, so that finite differences with it are derivatives in coordinates (the numerical
        lifted actions). It is not log(R(h)^T R(g)), which would measure the error in the body frame.
        """
        g = as_array(g, "g", (3,), what=f" (coordinates of {self.name})")
        h = as_array(h, "h", (3,), what=f" (coordinates of {self.name})")
        self._batch(("g", g), ("h", h))
        a, b = _principal(_check_length(g, "g")), _principal(_check_length(h, "h"))
        # |a - b + 2 pi b/|b|| < |a - b|  <=>  (a - b) . b/|b| < -pi  <=>  a . b < |b| (|b| - pi)
        tb = _norm(b)
        across = np.einsum("...i,...i->...", a, b) < tb * (tb - _PI)
        tb = np.broadcast_to(tb, across.shape)
        shift = np.divide(2.0 * _PI, tb, out=np.zeros_like(tb), where=across)
        return a - b + shift[..., None] * b

    @override
    def random(self, rng: np.random.Generator | int | None, size: int | tuple[int, ...] = (), scale: float = 1.0) -> FloatArray:
        """Uniform rotations (Haar measure, from normalised Gaussian quaternions), ``size + (3,)``.

        Draws with an angle above pi - :data:`RANDOM_MARGIN` are drawn again, so elements stay clear
        of the cut |r| = pi (a rotation there has two principal vectors). ``scale < 1`` shrinks
        the angles by that factor (rotations near e); the group is compact, so ``scale >= 1`` is the
        uniform distribution itself.
        """
        rng = as_rng(rng)
        size = check_shape(size, "size")
        scale = check_scale(scale)
        n = int(np.prod(size, dtype=np.int64))
        out = np.empty((n, 3))
        todo = np.arange(n)
        while todo.size:
            r = _rotvec_of_quaternion(rng.normal(size=(todo.size, 4)))
            ok = _norm(r) < _PI - RANDOM_MARGIN
            out[todo[ok]] = r[ok]
            todo = todo[~ok]
        return out.reshape(size + (3,)) * min(scale, 1.0)


SO3 = _SO3()

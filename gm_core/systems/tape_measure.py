"""The tape-measure swimmer: a floating looped chain of a head and two buckled tapes, at high Re (numpy only).

Beyond the draft; the model of sysplotter's ``sysf_symmetricTapeMeasure.m`` and its
``Physics/Inertial/TapeMeasure/tapeMeasure_connectionAndMetric.m`` (OSU-LRAM/GeometricSystemPlotter).
A head (mass m_h, rotational inertia I_h) sends out two tapes, an upper and a lower one, each of fixed
length C (``tape_length``), whose far ends meet at the tip. Each tape buckles once, so it is two straight
segments: segment 1 leaves the head at the opening angle alpha_k to the head-to-tip line, segment 2 runs
from the buckle point to the tip. The body frame is the head's, x towards the tip, which sits at (L, 0).
The loop closes (l1 + l2 = C and the law of cosines in the triangle head, buckle, tip) when

    l1 = (C^2 - L^2) / (2 C - 2 L cos alpha),    l2 = C - l1,    |L| < C,

with the buckle at l1 (cos alpha, +-sin alpha) and segment 2 at the angle -+beta to the x axis,
beta = atan2(l1 sin alpha, L - l1 cos alpha) the angle at the tip. The shape is (alpha, L) for the
symmetric swimmer (both tapes open by alpha) and (alpha1, alpha2, L) for the asymmetric one (upper
tape by alpha1, lower by alpha2, mirrored, so alpha1 = alpha2 is the symmetric body).

Physics in the course's words (section 3.4, the floating snake and the high-Re swimmer): each rigid
part i, the head and the four segments, moves with the body velocity ``xi_i = Ad_{g_i^-1} xi + g_i^-1
dg_i/dr r_dot`` (its pose g_i(r) in the body frame) and carries kinetic energy ``1/2 xi_i^T M_i xi_i``
(3.47): the head ``M = diag(m_h, m_h, I_h)``, a segment of length l in its own frame (x along it)
``diag(mu l, (mu + mu_a) l, iota (l/2)^3 + iota_a (l/2)^4)``, its own mass per length ``mu``
(``mass_rate``) in every direction, the fluid's added mass per length ``mu_a`` (``added_mass_rate``)
only sideways, and the rotational rates ``iota`` and ``iota_a`` with the file's powers of the half
length. The sum ``sum J_i^T M_i J_i`` is the mass matrix of (3.39) on (xi, r_dot); started at rest
the swimmer keeps zero momentum, its top three rows (the Pfaffian), so ``xi = -A r_dot`` with
``A = M_xi^-1 M_xi,r`` (3.40), and twice the kinetic energy is ``r_dot^T M_r r_dot`` with
``M_r = [-A; I]^T M [-A; I]`` (sysplotter's metric).

sysplotter differentiates beta by central differences (step 1e-5); here every derivative is in closed
form: ``dl1/dalpha = -l1 L sin alpha / D``, ``dl1/dL = -(L - l1 cos alpha) / D`` (D = C - L cos alpha) and
``dbeta = (x dy - y dx) / l2^2`` with (x, y) = (L - l1 cos alpha, l1 sin alpha). Both l1 and l2 are
positive for |L| < C (l2 = |C - L e^(i alpha)|^2 / (2 D)): at L = 0 each tape folds back on itself to the
head, for L < 0 the tip lies behind the head (the file's window is 0.43 <= L / C <= 0.80). At |L| >= C
the loop cannot close: every value there is NaN (:meth:`TapeMeasure.singularity` is 0).
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import SE2
from gm_core.systems.base import BalancedSystem, SystemPart, ellipse_outline, rectangle_outline
from gm_core.systems.reframed import body_jacobian
from gm_core.validation import BoolArray, FloatArray, check_int, positive_number

__all__ = ["TapeMeasure", "SEGMENTS"]

#: The four tape segments in the order of their poses (after the head): sysplotter's J1t, J1b, J2t, J2b.
SEGMENTS = ("upper segment 1", "lower segment 1", "upper segment 2", "lower segment 2")


def _side(a: FloatArray, L: FloatArray, C: float) -> tuple[FloatArray, ...]:
    """One tape opened by ``a`` (upper side): l1, l2, beta and their derivatives by (a, L), each (...,)."""
    c, s = np.cos(a), np.sin(a)
    D = C - L * c
    l1 = (C ** 2 - L ** 2) / (2 * D)
    l2 = C - l1
    x, y = L - l1 * c, l1 * s                      # the tip-to-buckle vector of segment 2
    l1_a, l1_L = -l1 * L * s / D, -x / D
    x_a, x_L = l1 * s - l1_a * c, 1 - l1_L * c
    y_a, y_L = l1 * c + l1_a * s, l1_L * s
    beta = np.arctan2(y, x)
    beta_a, beta_L = (x * y_a - y * x_a) / l2 ** 2, (x * y_L - y * x_L) / l2 ** 2
    return l1, l2, beta, l1_a, l1_L, beta_a, beta_L


class TapeMeasure(BalancedSystem):
    """The tape-measure swimmer (sysplotter's symmetric and asymmetric tape measures); see the module docstring.

    ``TapeMeasure()`` is ``sysf_symmetricTapeMeasure.m``, shape (alpha, L); ``TapeMeasure(symmetric=False)``
    has the shape (alpha1, alpha2, L). Offers ``connection(r)``, ``pfaffian(r)``, ``metric(r)`` (the mass
    matrix on (xi, r_dot)), ``shape_metric(r)``, ``segment_lengths(r)``, ``link_poses(r)`` and
    ``link_jacobians(r)`` (head first, then :data:`SEGMENTS`), ``parts()`` and ``part_poses(r)``.
    """

    may_be_singular = True
    singular_description = "the loop cannot close unless |L| < C (the head-to-tip distance below the tape length)"

    def __init__(self, tape_length: float = 1.0, *, symmetric: bool = True, head_mass: float = 0.25,
                 head_inertia: float = 1.0, mass_rate: float = 0.001, rotational_inertia_rate: float = 0.01,
                 added_mass_rate: float = 1.0, added_rotational_inertia_rate: float = 1 / 8,
                 shape_limits: Any = None, tape_pieces: int = 12, name: str | None = None) -> None:
        if not isinstance(symmetric, (bool, np.bool_)):
            raise TypeError(f"symmetric must be True (shape (alpha, L)) or False (shape (alpha1, alpha2, L)); got {symmetric!r:.40}")
        self.tape_length = positive_number(tape_length, "tape_length", maximum=1e6, what=" (C, each tape's length)")
        if self.tape_length < 1e-6:
            raise ValueError(f"tape_length must be at least 1e-6 (its fourth power enters the inertia); got {self.tape_length:g}")
        self.symmetric = bool(symmetric)
        self.head_mass = positive_number(head_mass, "head_mass", maximum=1e12)
        self.head_inertia = positive_number(head_inertia, "head_inertia", maximum=1e12)
        self.mass_rate = positive_number(mass_rate, "mass_rate", allow_zero=True, maximum=1e12, what=" (tape mass per length)")
        self.rotational_inertia_rate = positive_number(rotational_inertia_rate, "rotational_inertia_rate", allow_zero=True,
                                                       maximum=1e12)
        self.added_mass_rate = positive_number(added_mass_rate, "added_mass_rate", allow_zero=True, maximum=1e12,
                                               what=" (sideways added mass per length)")
        self.added_rotational_inertia_rate = positive_number(added_rotational_inertia_rate, "added_rotational_inertia_rate",
                                                             allow_zero=True, maximum=1e12)
        self.tape_pieces = check_int(tape_pieces, "tape_pieces", minimum=2, maximum=200, what=" (pieces per tape when drawn)")
        self.n_shape = 2 if self.symmetric else 3
        self.shape_names = ("alpha", "L") if self.symmetric else ("alpha1", "alpha2", "L")
        C = self.tape_length
        default = ((0.0, np.pi / 2),) * (self.n_shape - 1) + ((0.24 / 0.56 * C, 0.45 / 0.56 * C),)
        self.shape_limits = default if shape_limits is None else tuple(
            (float(lo), float(hi)) for lo, hi in shape_limits)
        self.name = name or f"{'' if self.symmetric else 'a'}symmetric tape-measure swimmer"
        # (alpha_upper, alpha_lower, L) = S r
        self._S = np.array([[1.0, 0.0], [1.0, 0.0], [0.0, 1.0]]) if self.symmetric else np.eye(3)

    # -- geometry ------------------------------------------------------------------------------
    def _geometry(self, r: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
        """Poses (..., 5, 3) of the head and :data:`SEGMENTS`, their derivatives d g_i / d r (..., 5, 3, n), the
        segment lengths (..., 4) and where the loop closes (...,) (elsewhere the values are those of L = C / 2)."""
        r = self._shape(r)
        C = self.tape_length
        q = r @ self._S.T                                          # (..., 3): alpha_upper, alpha_lower, L
        closes = np.abs(q[..., 2]) < C
        L = np.where(closes, q[..., 2], C / 2)
        g = np.zeros(r.shape[:-1] + (5, 3))
        dq = np.zeros(r.shape[:-1] + (5, 3, 3))                    # d g_i / d (alpha_upper, alpha_lower, L)
        lengths = np.zeros(r.shape[:-1] + (4,))
        for k, sign in ((0, 1.0), (1, -1.0)):                      # upper tape, lower tape (mirrored)
            a = q[..., k]
            l1, l2, beta, l1_a, l1_L, beta_a, beta_L = _side(a, L, C)
            c, s = np.cos(a), np.sin(a)
            one, two = 1 + k, 3 + k
            lengths[..., k], lengths[..., 2 + k] = l1, l2
            g[..., one, :] = np.stack([l1 * c / 2, sign * l1 * s / 2, sign * a], -1)
            g[..., two, :] = np.stack([(l1 * c + L) / 2, sign * l1 * s / 2, -sign * beta], -1)
            mid_a = np.stack([(l1_a * c - l1 * s) / 2, sign * (l1_a * s + l1 * c) / 2], -1)
            mid_L = np.stack([l1_L * c / 2, sign * l1_L * s / 2], -1)
            dq[..., one, :2, k], dq[..., one, :2, 2], dq[..., one, 2, k] = mid_a, mid_L, sign
            dq[..., two, :2, k], dq[..., two, :2, 2] = mid_a, mid_L + np.array([0.5, 0.0])
            dq[..., two, 2, k], dq[..., two, 2, 2] = -sign * beta_a, -sign * beta_L
        return g, dq @ self._S, lengths, closes

    @staticmethod
    def _masked(closes: BoolArray, X: FloatArray) -> FloatArray:
        """X (..., *tail) with NaN where the loop cannot close."""
        return np.where(closes.reshape(closes.shape + (1,) * (X.ndim - closes.ndim)), X, np.nan)

    def segment_lengths(self, r: ArrayLike) -> FloatArray:
        """Lengths (..., 4) of :data:`SEGMENTS`: (l1, l1, l2, l2) by alpha (and alpha2); upper plus lower = 2 C."""
        g, _, lengths, closes = self._geometry(r)
        return self._masked(closes, lengths)

    def link_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., 5, 3) of the head (the body frame) and the centres of :data:`SEGMENTS`, x along each."""
        g, _, _, closes = self._geometry(r)
        return self._masked(closes, g)

    def link_jacobians(self, r: ArrayLike) -> FloatArray:
        """Jacobians (..., 5, 3, 3 + n) from (xi, r_dot) to the body velocity of the head and each segment:
        ``[Ad_{g_i^-1}, T L_{g_i^-1} dg_i/dr]`` (section 2.4, as for the links of a chain)."""
        g, dg, _, closes = self._geometry(r)
        return self._masked(closes, np.concatenate([SE2.Ad_inv(g), body_jacobian(g, dg)], -1))

    # -- physics -------------------------------------------------------------------------------
    def link_matrices(self, r: ArrayLike) -> FloatArray:
        """Mass-and-added-mass matrices (..., 5, 3, 3) of the head and :data:`SEGMENTS`, each in its own frame."""
        g, _, lengths, closes = self._geometry(r)
        d = np.zeros(g.shape)
        d[..., 0, :] = (self.head_mass, self.head_mass, self.head_inertia)
        h = lengths / 2
        d[..., 1:, 0] = self.mass_rate * lengths
        d[..., 1:, 1] = (self.mass_rate + self.added_mass_rate) * lengths
        d[..., 1:, 2] = self.rotational_inertia_rate * h ** 3 + self.added_rotational_inertia_rate * h ** 4
        return self._masked(closes, d[..., None] * np.eye(3))

    @override
    def metric(self, r: ArrayLike) -> FloatArray:
        """Mass matrix (..., 3 + n, 3 + n) on (xi, r_dot): ``sum J_i^T M_i J_i`` over head and segments, (3.39), (3.47)."""
        J = self.link_jacobians(r)
        return np.einsum("...kai,...kab,...kbj->...ij", J, self.link_matrices(r), J)

    @override
    def singularity(self, r: ArrayLike) -> FloatArray:
        """Scaled det of the locked inertia (...,): positive where |L| < C, else 0 (the loop cannot close)."""
        return np.nan_to_num(super().singularity(r), nan=0.0)

    # -- drawing -------------------------------------------------------------------------------
    @override
    def parts(self) -> list[SystemPart]:
        """The head and each tape as ``tape_pieces`` short pieces (the segments change length; the tapes do not)."""
        C, n = self.tape_length, self.tape_pieces
        head = SystemPart("head", ellipse_outline(0.06 * C, 0.06 * C), "head")
        return [head] + [SystemPart(f"{side} tape {k + 1}", rectangle_outline(C / n, 0.02 * C), "link")
                         for side in ("upper", "lower") for k in range(n)]

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., 1 + 2 tape_pieces, 3): the head, then the pieces laid along each tape, head to tip."""
        g, _, lengths, closes = self._geometry(r)
        n = self.tape_pieces
        t = (np.arange(n) + 0.5) * self.tape_length / n                 # arc length of each piece's centre
        out = [g[..., :1, :]]
        for k in (0, 1):
            l1 = lengths[..., k, None]
            first = t < l1                                               # on segment 1, else on segment 2
            seg1, seg2 = g[..., 1 + k, None, :], g[..., 3 + k, None, :]
            along = np.where(first, t - l1 / 2, t - l1 - (self.tape_length - l1) / 2)[..., None]
            seg = np.where(first[..., None], seg1, seg2)
            th = seg[..., 2:]
            out.append(np.concatenate([seg[..., :1] + along * np.cos(th), seg[..., 1:2] + along * np.sin(th), th], -1))
        return self._masked(closes, np.concatenate(out, -2))

    @override
    def __repr__(self) -> str:
        return f"TapeMeasure(tape_length={self.tape_length:g}, symmetric={self.symmetric})"

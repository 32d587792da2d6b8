"""A continuous slender swimmer at low Reynolds number whose curvature is given along its length (numpy only).

Beyond the draft (after Hatton & Choset's serpenoid swimmers and Ramasamy & Hatton 2019): a
body of length L, arc length s in [0, L], with curvature ``kappa(s; r)``: either a sum of shape
modes ``kappa = sum_k r_k phi_k(s)`` (the serpenoid pair ``phi_1 = cos(2 pi s / L)``, ``phi_2 =
sin(2 pi s / L)``; any functions of s, optionally with their exact integrals; the centred waves of
:func:`wave_modes`; the piecewise-constant :func:`segment_modes`) or a :class:`GeneralCurvature`,
nonlinear in r, with its derivative d kappa / d r. The shape is r. With ``theta(s) =
int_{L/2}^s kappa`` and ``p(s) = int_{L/2}^s (cos theta, sin theta)`` (the middle frame), the
velocity of the body at s is ``v(s) = xi_xy + xi_theta perp(p(s)) + (dp/dr) r_dot`` and resistive
force theory gives the force per unit length ``-(t t^T + k n n^T) v`` (t, n the tangent and normal,
k = ``drag_ratio``). The drag matrix ``D = int W(s)^T (t t^T + k n n^T) W(s) ds`` (W: v = W (xi,
r_dot)) has the net wrench as its top rows, the Pfaffian.

Body frames: the middle of the body, s = L/2, along its tangent (``"middle"``); the centre of mass
with the mean orientation, both integral means over the body (``"com"``); the end s = 0 (``"tail"``,
its position and tangent); or the plain mean of x, y and theta over ``mean_points`` equally spaced
points s = 0 .. L (``"com-mean"``, sysplotter's frame of that name: not the integral mean). A frame
beta(r) relative to the middle frame changes the drag matrix by ``T^T D T`` with ``T (xi~, r_dot) =
(Ad_beta (xi~ - B_beta r_dot), r_dot)`` (B_beta the body Jacobian of beta), hence the connection by
``A~ = Ad_{beta^-1} A - B_beta`` (see :mod:`gm_core.systems.reframed`).

Quadrature: the body is cut into ``panels`` equal Gauss-Legendre panels of ``order`` nodes, with
extra panel edges at the middle and at ``breaks`` (where the curvature jumps, so that no panel
straddles a jump). theta and p at the panel edges are sums of whole-panel rules from L/2; at any
other point, the edge of its panel nearest the middle plus an ``order``-point rule inside the panel
(exact integrals of the modes where they are known). A chain of N links whose joint angles sample
the same curvature, :func:`chain_approximation`, converges to this body as N grows (at rate 1/N^2;
tested).
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import SE2
from gm_core.systems.base import BalancedSystem, LocomotionSystem, SystemPart, rectangle_outline
from gm_core.systems.reframed import body_jacobian
from gm_core.systems.restricted import AffineRestriction
from gm_core.validation import FloatArray, as_array, check_int, check_option, positive_number

__all__ = ["SlenderBody", "GeneralCurvature", "serpenoid_modes", "wave_modes", "segment_modes", "chain_approximation"]

FRAMES = ("middle", "com", "tail", "com-mean")


def serpenoid_modes(length: float = 1.0) -> tuple[Any, Any]:
    """The serpenoid pair (cos(2 pi s / L), sin(2 pi s / L)) and their integrals from L/2 (exact)."""
    L = positive_number(length, "length")
    w = 2 * np.pi / L
    modes = (lambda s: np.cos(w * s), lambda s: np.sin(w * s))
    integrals = (lambda s: np.sin(w * s) / w, lambda s: -(np.cos(w * s) + 1.0) / w)
    return modes, integrals


def wave_modes(waves: Sequence[int] = (1,), length: float = 1.0, *, scaled: bool = False) -> tuple[Any, Any]:
    """Waves centred on the middle: for each w of ``waves``, ``c cos(2 pi w u / L)`` and ``c sin(2 pi w u / L)``
    with u = s - L/2 and c = w if ``scaled`` else 1, and their exact integrals from L/2 (modes, integrals).

    In u these are sysplotter's ``serpenoid_1/2(s, omega)`` (``scaled``: omega cos(2 pi omega s)) and
    ``serpenoid4_*``; they differ from :func:`serpenoid_modes` by the shift: cos(2 pi u / L) = -cos(2 pi s / L).
    """
    L = positive_number(length, "length")
    if isinstance(waves, (str, bytes)) or not hasattr(waves, "__len__") or len(waves) < 1:
        raise TypeError(f"waves must be a sequence of positive whole numbers of waves; got {waves!r:.60}")
    modes: list[Callable[[Any], Any]] = []
    integrals: list[Callable[[Any], Any]] = []
    for w in (check_int(v, "waves", minimum=1, maximum=1000) for v in waves):
        pair = _wave(2 * np.pi * w / L, float(w if scaled else 1), L / 2)
        modes += pair[0]
        integrals += pair[1]
    return tuple(modes), tuple(integrals)


def _wave(k: float, c: float, mid: float) -> tuple[list[Callable[[Any], Any]], list[Callable[[Any], Any]]]:
    """c cos(k u), c sin(k u) (u = s - mid) and their integrals from mid."""
    def cos(s: Any) -> Any:
        return c * np.cos(k * (s - mid))

    def sin(s: Any) -> Any:
        return c * np.sin(k * (s - mid))

    def int_cos(s: Any) -> Any:
        return c * np.sin(k * (s - mid)) / k

    def int_sin(s: Any) -> Any:
        return c * (1.0 - np.cos(k * (s - mid))) / k
    return [cos, sin], [int_cos, int_sin]


def segment_modes(bounds: ArrayLike) -> tuple[Any, Any, tuple[float, ...]]:
    """Piecewise-constant curvature: mode k is 1 on (b_k, b_{k+1}) of ``bounds`` 0 = b_0 < ... < b_n = L, else 0.

    Returns (modes, integrals, breaks): the integrals from L/2 are exact (theta piecewise linear,
    ``|[L/2, s] cap [b_k, b_{k+1}]|`` with sign), the breaks the interior bounds, for ``SlenderBody(breaks=)``.
    """
    b = as_array(bounds, "bounds", what=" (arc lengths 0 = b_0 < ... < b_n = L of the constant-curvature pieces)")
    if b.ndim != 1 or b.size < 2 or b[0] != 0 or np.any(np.diff(b) <= 0):
        raise ValueError(f"bounds must be increasing arc lengths starting at 0 (0 = b_0 < ... < b_n = L); got {b}")
    mid = b[-1] / 2
    modes = tuple(lambda s, lo=lo, hi=hi: ((s > lo) & (s < hi)).astype(float) for lo, hi in zip(b[:-1], b[1:]))
    integrals = tuple(lambda s, lo=lo, hi=hi: np.clip(s, lo, hi) - np.clip(mid, lo, hi) for lo, hi in zip(b[:-1], b[1:]))
    return modes, integrals, tuple(float(v) for v in b[1:-1])


@dataclass(frozen=True)
class GeneralCurvature:
    """A curvature ``kappa(s, r)`` nonlinear in the shape r, with its derivative ``dkappa(s, r) = d kappa / d r``.

    ``kappa``: s (k,) and r (..., n) -> (..., k); ``dkappa``: -> (..., k, n). ``shape_names`` has n entries.
    """

    kappa: Callable[[FloatArray, FloatArray], ArrayLike]
    dkappa: Callable[[FloatArray, FloatArray], ArrayLike]
    shape_names: tuple[str, ...]
    name: str = "general curvature"

    @property
    def n_shape(self) -> int:
        return len(self.shape_names)


class SlenderBody(BalancedSystem):
    """Continuous slender swimmer (resistive force theory); shape r of its curvature. See the module docstring."""

    may_be_singular = False

    def __init__(self, length: float = 1.0, modes: Any = "serpenoid", *, integrals: Any = None, breaks: ArrayLike = (),
                 drag_ratio: float = 2.0, frame: Any = "middle", panels: int = 8, order: int = 8, segments: int = 40,
                 mean_points: int = 100, shape_limits: Any = None) -> None:
        self.length = positive_number(length, "length", maximum=1e6)
        self.drag_ratio = positive_number(drag_ratio, "drag_ratio", maximum=1e6, what=" (lateral over longitudinal drag)")
        self.frame = check_option(frame, "frame", FRAMES)
        self.panels = check_int(panels, "panels", minimum=1, maximum=512, what=" (Gauss panels along the body)")
        self.order = check_int(order, "order", minimum=2, maximum=64, what=" (Gauss nodes per panel)")
        self.segments = check_int(segments, "segments", minimum=2, maximum=1000, what=" (pieces drawn)")
        self.mean_points = check_int(mean_points, "mean_points", minimum=2, maximum=100000,
                                     what=" (points of the 'com-mean' frame)")
        L = self.length
        self.general: GeneralCurvature | None = None
        if isinstance(modes, GeneralCurvature):
            if integrals is not None:
                raise TypeError("integrals must be None for a GeneralCurvature (it has no modes to integrate)")
            self.general, self.modes = modes, ()
            self.n_shape = modes.n_shape
            self.mode_names: tuple[str, ...] = ()
            self.shape_names = modes.shape_names
            self.name = f"slender body ({modes.name})"
        else:
            if isinstance(modes, str):
                check_option(modes, "modes", ("serpenoid",))
                if integrals is not None:
                    raise TypeError("integrals must be None for modes='serpenoid' (its integrals are built in)")
                self.modes, integrals = serpenoid_modes(L)
                self.mode_names = ("cos", "sin")
            else:
                if isinstance(modes, (bytes, dict)) or not hasattr(modes, "__len__") or len(modes) < 1 \
                        or not all(callable(m) for m in modes):
                    raise TypeError("modes must be 'serpenoid', a GeneralCurvature or a sequence of functions s -> phi(s) "
                                    f"(curvature per unit amplitude along the body, 0 <= s <= length); got {modes!r:.60}")
                if integrals is not None and (not hasattr(integrals, "__len__") or len(integrals) != len(modes)
                                              or not all(callable(f) for f in integrals)):
                    raise TypeError("integrals must be None or one function s -> int_{L/2}^s phi_k per mode; "
                                    f"got {integrals!r:.60}")
                self.modes = tuple(modes)
                self.mode_names = tuple(f"mode {k + 1}" for k in range(len(modes)))
            self.n_shape = len(self.modes)
            self.shape_names = tuple(f"r{k + 1}" for k in range(self.n_shape))
            self.name = f"slender body ({'serpenoid' if self.mode_names == ('cos', 'sin') else f'{self.n_shape} modes'})"
        self.integrals = None if integrals is None else tuple(integrals)
        self.shape_limits = ((-2 * np.pi, 2 * np.pi),) * self.n_shape
        if shape_limits is not None:
            lim = as_array(shape_limits, "shape_limits", (self.n_shape, 2), what=" (a (low, high) window per shape variable)")
            if np.any(lim[:, 0] >= lim[:, 1]):
                raise ValueError(f"shape_limits must have low < high for every shape variable; got {lim.tolist()}")
            self.shape_limits = tuple((float(a), float(b)) for a, b in lim)
        br = as_array(breaks, "breaks", what=" (arc lengths where the curvature jumps)")
        if br.ndim != 1 or np.any((br <= 0) | (br >= L)):
            raise ValueError(f"breaks must be a list of arc lengths strictly inside (0, length={L:g}); got {br}")
        self.breaks = tuple(float(v) for v in np.unique(br))
        # panel edges: 0, the middle, L, the breaks, then the equal panels' edges not already (nearly) there
        edges = sorted({0.0, L / 2, L, *self.breaks})
        for e in np.linspace(0.0, L, self.panels + 1):
            if np.min(np.abs(np.array(edges) - e)) > 1e-9 * L:
                edges.append(float(e))
        self._edges = np.array(sorted(edges))
        E = self._edges.size
        self._mid = int(np.argmin(np.abs(self._edges - L / 2)))
        x, w = np.polynomial.legendre.leggauss(self.order)
        self._gauss = x, w
        a, b = self._edges[:-1, None], self._edges[1:, None]
        self._s = ((a + b) / 2 + (b - a) / 2 * x).ravel()
        self._w = ((b - a) / 2 * w).ravel()
        self._Q = self._s.size
        # C (E, Q): int_{L/2}^{edge e} f = C[e] @ f(nodes), whole panels between the middle and the edge
        C = np.zeros((E, self._Q))
        m = self.order
        for e in range(E):
            lo, hi, sign = (self._mid, e, 1.0) if e > self._mid else (e, self._mid, -1.0)
            C[e, lo * m:hi * m] = sign * self._w[lo * m:hi * m]
        self._C = C
        # the points where the body is evaluated: the nodes, the drawn pieces' centres, the 'com-mean' points
        centres = (np.arange(self.segments) + 0.5) * L / self.segments
        self._draw = slice(self._Q, self._Q + self.segments)
        self._means = slice(self._draw.stop, self._draw.stop + self.mean_points)
        self._X = np.concatenate([self._s, centres, np.linspace(0.0, L, self.mean_points)])
        self._root = self._root_edge(self._X)                                   # (X,)
        self._sub, self._sub_w = self._rule(self._root, self._X)                # (X, m), rule from the root edge to X
        if self.general is None:
            self._Phi_edge = self._mode_integrals(self._edges)                  # (E, n)
            if not np.all(np.isfinite(self._Phi_edge)) or np.abs(self._Phi_edge[self._mid]).max() > 1e-12 * (1 + L):
                raise ValueError("integrals must be the modes' integrals from the middle, int_{L/2}^s phi_k "
                                 f"(zero at s = L/2, finite); at s = L/2 they are {self._Phi_edge[self._mid]}")
            self._Phi = self._mode_integrals(self._X)                           # (X, n)
            self._Phi_sub = self._mode_integrals(self._sub)                     # (X, m, n)
        else:                                                                   # rules from the root edge to each sub-point
            self._sub2, self._sub2_w = self._rule(self._root[:, None], self._sub)   # (X, m, m)

    # -- quadrature of theta and p ------------------------------------------------------------
    def _root_edge(self, t):
        """Index of the edge of each point's panel nearest the middle (the start of its rule)."""
        P = self._edges.size - 1
        panel = np.clip(np.searchsorted(self._edges, t, side="right") - 1, 0, P - 1)
        return np.where(panel < self._mid, panel + 1, panel)

    def _rule(self, root, t):
        """Points (..., m) and signed weights (..., m) of the ``order``-point Gauss rule from edge ``root`` to t."""
        x, w = self._gauss
        a = self._edges[root][..., None]
        h = t[..., None] - a
        return a + h / 2 * (x + 1), h / 2 * w

    def _mode_integrals(self, s):
        """Phi_k(s) = int_{L/2}^s phi_k, (..., n): exact when given, else the panel rules of the body."""
        s = np.asarray(s, dtype=float)
        if self.integrals is not None:
            return np.stack([np.broadcast_to(np.asarray(f(s), dtype=float), s.shape) for f in self.integrals], -1)
        root = self._root_edge(s)
        sub, sub_w = self._rule(root, s)
        edge = self._C @ self._mode_values(self._s)                             # (E, n)
        return edge[root] + (sub_w[..., None] * self._mode_values(sub)).sum(-2)

    def _mode_values(self, s):
        vals = []
        for k, f in enumerate(self.modes):
            v = np.asarray(f(s), dtype=float)
            if v.shape != s.shape or not np.all(np.isfinite(v)):
                raise ValueError(f"modes[{k}] must return one finite curvature per arc length s (an array like s)")
            vals.append(v)
        return np.stack(vals, -1)

    def _kappa(self, r, s):
        """kappa (..., k) and d kappa / d r (..., k, n) of the general curvature at arc lengths s (k,)."""
        g = self.general
        assert g is not None
        k = np.asarray(g.kappa(s, r), dtype=float)
        dk = np.asarray(g.dkappa(s, r), dtype=float)
        return np.broadcast_to(k, r.shape[:-1] + s.shape), np.broadcast_to(dk, r.shape[:-1] + s.shape + (self.n_shape,))

    def _theta(self, r, pts):
        """theta, d theta / d r at the points ``pts`` (a slice of the body's points) ((..., X), (..., X, n)), at their
        rules' points ((..., X, m), (..., X, m, n)) and at the panel edges ((..., E), (..., E, n))."""
        if self.general is None:
            Phi, Phi_sub, Phi_e = self._Phi[pts], self._Phi_sub[pts], self._Phi_edge
            b = r.shape[:-1]
            return (r @ Phi.T, np.broadcast_to(Phi, b + Phi.shape), np.einsum("...n,xmn->...xm", r, Phi_sub),
                    np.broadcast_to(Phi_sub, b + Phi_sub.shape), r @ Phi_e.T, np.broadcast_to(Phi_e, b + Phi_e.shape))
        n, Q = self.n_shape, self._Q
        root, sub, sub_w, sub2, sub2_w = self._root[pts], self._sub[pts], self._sub_w[pts], self._sub2[pts], self._sub2_w[pts]
        kap, dkap = self._kappa(r, np.concatenate([self._s, sub.ravel(), sub2.ravel()]))
        b, ns = r.shape[:-1], sub.size
        k1, dk1 = kap[..., Q:Q + ns].reshape(b + sub.shape), dkap[..., Q:Q + ns, :].reshape(b + sub.shape + (n,))
        k2, dk2 = kap[..., Q + ns:].reshape(b + sub2.shape), dkap[..., Q + ns:, :].reshape(b + sub2.shape + (n,))
        th_e = kap[..., :Q] @ self._C.T                                         # (..., E)
        J_e = np.einsum("eq,...qn->...en", self._C, dkap[..., :Q, :])
        th = th_e[..., root] + (sub_w * k1).sum(-1)
        J = J_e[..., root, :] + (sub_w[..., None] * dk1).sum(-2)
        ths = th_e[..., root, None] + (sub2_w * k2).sum(-1)
        Js = J_e[..., root, None, :] + (sub2_w[..., None] * dk2).sum(-2)
        return th, J, ths, Js, th_e, J_e

    def _curve(self, r, pts=None):
        """The body at its points ``pts`` (a slice; default the quadrature nodes) in the middle frame:
        theta (..., X), p (..., X, 2), d theta / dr (..., X, n), dp/dr (..., X, 2, n), and the same at the edges."""
        nodes = slice(0, self._Q)
        pts = nodes if pts is None else pts
        th, J, ths, Js, th_e, J_e = self._theta(r, pts)
        thn, Jn = (th, J) if pts == nodes else self._theta(r, nodes)[:2]
        # p at the edges by whole panels from the middle; at a point, from its root edge by its own rule
        cn, sn = np.cos(thn), np.sin(thn)
        C = self._C
        p_e = np.stack([cn @ C.T, sn @ C.T], -1)                                           # (..., E, 2)
        dp_e = np.stack([np.einsum("eq,...qn->...en", C, -sn[..., None] * Jn),
                         np.einsum("eq,...qn->...en", C, cn[..., None] * Jn)], -2)         # (..., E, 2, n)
        root, w = self._root[pts], self._sub_w[pts]
        cs, ss = np.cos(ths), np.sin(ths)
        p = p_e[..., root, :] + np.stack([(w * cs).sum(-1), (w * ss).sum(-1)], -1)
        dp = dp_e[..., root, :, :] + np.stack([(w[..., None] * -ss[..., None] * Js).sum(-2),
                                               (w[..., None] * cs[..., None] * Js).sum(-2)], -2)
        return th, p, J, dp, (th_e, p_e, J_e, dp_e)

    def frame_pose(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """The body frame's pose beta (..., 3) relative to the middle frame and d beta / d r (..., 3, n)."""
        r = self._shape(r)
        n = self.n_shape
        if self.frame == "middle":
            return np.zeros(r.shape[:-1] + (3,)), np.zeros(r.shape[:-1] + (3, n))
        if self.frame == "com-mean":
            th, p, J, dp, _ = self._curve(r, self._means)
            return (np.concatenate([p.mean(-2), th.mean(-1)[..., None]], -1),
                    np.concatenate([dp.mean(-3), J.mean(-2)[..., None, :]], -2))
        th, p, J, dp, (th_e, p_e, J_e, dp_e) = self._curve(r)
        if self.frame == "tail":
            return (np.concatenate([p_e[..., 0, :], th_e[..., :1]], -1),
                    np.concatenate([dp_e[..., 0, :, :], J_e[..., :1, :]], -2))
        w = self._w / self.length
        return (np.concatenate([np.einsum("s,...sj->...j", w, p), (th @ w)[..., None]], -1),
                np.concatenate([np.einsum("s,...sjk->...jk", w, dp), np.einsum("s,...sk->...k", w, J)[..., None, :]], -2))

    def quadrature_poses(self, r: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """The body at its quadrature nodes in the middle frame: arc lengths s (Q,), weights (Q,), poses h(s)
        (..., Q, 3) = (p, theta) and their coordinate derivatives d h / d r (..., Q, 3, n)."""
        r = self._shape(r)
        th, p, J, dp, _ = self._curve(r)
        return (self._s.copy(), self._w.copy(), np.concatenate([p, th[..., None]], -1),
                np.concatenate([dp, J[..., None, :]], -2))

    def link_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., segments, 3) of the drawn pieces' centres in the body frame."""
        r = self._shape(r)
        th, p = self._curve(r, self._draw)[:2]
        P = np.concatenate([p, th[..., None]], -1)
        if self.frame == "middle":
            return P
        beta = self.frame_pose(r)[0]
        return SE2.compose(SE2.inverse(beta)[..., None, :], P)

    def link_weights(self) -> FloatArray:
        return np.full(self.segments, 1.0 / self.segments)

    def curvature(self, r: ArrayLike, s: ArrayLike) -> FloatArray:
        """Curvature kappa(s) (..., len(s)) at arc lengths s (k,) for shapes r (..., n)."""
        r = self._shape(r)
        s = as_array(s, "s", what=" (arc lengths along the body)")
        if s.ndim != 1:
            raise ValueError(f"s must be a vector of arc lengths (k,); got shape {s.shape}")
        if self.general is not None:
            return self._kappa(r, s)[0]
        return r @ self._mode_values(s).T

    # -- physics ---------------------------------------------------------------------------------
    @override
    def metric(self, r: ArrayLike) -> FloatArray:
        """Drag matrix (..., 3 + n, 3 + n): ``int W^T (t t^T + k n n^T) W ds`` by the body quadrature.

        Computed in the middle frame; in another frame beta it is ``T^T D T`` with
        ``T (xi~, r_dot) = (Ad_beta (xi~ - B_beta r_dot), r_dot)`` (the same power, other coordinates).
        """
        r = self._shape(r)
        tq, pq, _, dq, _ = self._curve(r)
        n = self.n_shape
        W = np.zeros(tq.shape + (2, 3 + n))
        W[..., 0, 0] = W[..., 1, 1] = 1.0
        W[..., 0, 2], W[..., 1, 2] = -pq[..., 1], pq[..., 0]
        W[..., 3:] = dq
        c, s = np.cos(tq), np.sin(tq)
        ut = c[..., None] * W[..., 0, :] + s[..., None] * W[..., 1, :]      # tangential component of v per column
        un = -s[..., None] * W[..., 0, :] + c[..., None] * W[..., 1, :]
        w = self._w
        D = (np.swapaxes(ut * w[:, None], -1, -2) @ ut
             + self.drag_ratio * (np.swapaxes(un * w[:, None], -1, -2) @ un))
        if self.frame == "middle":
            return D
        beta, dbeta = self.frame_pose(r)
        T = np.zeros(D.shape)
        Ad = SE2.Ad(beta)
        T[..., :3, :3] = Ad
        T[..., :3, 3:] = -Ad @ body_jacobian(beta, dbeta)
        T[..., 3:, 3:] = np.eye(n)
        return np.swapaxes(T, -1, -2) @ D @ T

    @override
    def body_frames(self, bounds: Any = None, *, n: int | None = None, centre_of_mass: bool = True,
                    minimum_perturbation: bool = True) -> dict[str, LocomotionSystem]:
        """{name: system}: the middle of the body and, if asked, the centre of mass (mean
        orientation) and minimum perturbation over ``bounds``."""
        out: dict[str, LocomotionSystem] = {"middle of the body": self.with_frame("middle")}
        if centre_of_mass:
            out["centre of mass"] = self.with_frame("com")
        if minimum_perturbation:
            from gm_core.systems.minimum_perturbation import MinimumPerturbationFrame
            from gm_core.systems.reframed import Reframed

            base = out["middle of the body"]
            out["minimum perturbation"] = Reframed(base, MinimumPerturbationFrame.fit(base, bounds, n),
                                                   name=f"{self.name} (minimum perturbation)")
        return out

    def with_frame(self, frame: str) -> SlenderBody:
        """The same body in another body frame (one of "middle", "com", "tail", "com-mean")."""
        modes = "serpenoid" if self.mode_names == ("cos", "sin") else self.general or self.modes
        return SlenderBody(self.length, modes, integrals=None if modes == "serpenoid" else self.integrals,
                           breaks=self.breaks, drag_ratio=self.drag_ratio, frame=frame, panels=self.panels,
                           order=self.order, segments=self.segments, mean_points=self.mean_points,
                           shape_limits=self.shape_limits)

    # -- drawing ---------------------------------------------------------------------------------
    @override
    def parts(self) -> list[SystemPart]:
        piece = self.length / self.segments
        return [SystemPart(f"piece {i + 1}", rectangle_outline(piece * 1.02, self.length / 30), "link")
                for i in range(self.segments)]

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        return self.link_poses(r)

    @override
    def __repr__(self) -> str:
        what = self.general.name if self.general is not None else self.mode_names
        return (f"SlenderBody(length={self.length:g}, modes={what}, drag_ratio={self.drag_ratio:g}, "
                f"frame={self.frame!r})")


def chain_approximation(body: SlenderBody, n_links: int) -> AffineRestriction:
    """A chain of ``n_links`` equal links of total length L whose joint angles sample ``body``'s curvature.

    Link i's centre sits at s_i = (i - 1/2) L / N and is turned by theta(s_i); joint j therefore
    turns by ``alpha_j = theta(s_{j+1}) - theta(s_j) = sum_k r_k (Phi_k(s_{j+1}) - Phi_k(s_j))``,
    linear in the mode amplitudes (so the body's curvature must be modal, not a GeneralCurvature).
    Returns the low-Re :class:`~gm_core.systems.LinkChain` restricted to those joint angles (an
    :class:`~gm_core.systems.AffineRestriction` with the body's shape variables), in the matching
    frame (middle link or joint, or centre of mass).
    """
    from gm_core.systems.link_chain import LinkChain

    if not isinstance(body, SlenderBody):
        raise TypeError(f"body must be a SlenderBody; got {type(body).__name__}")
    if body.general is not None or body.frame not in ("middle", "com"):
        raise ValueError("body must have modal curvature (not a GeneralCurvature) and the frame 'middle' or 'com'")
    N = check_int(n_links, "n_links", minimum=2, maximum=200, what=" (links of the chain)")
    L = body.length
    sc = (np.arange(N) + 0.5) * L / N
    S = np.diff(body._mode_integrals(sc), axis=0)                            # (N - 1, n)
    chain = LinkChain((L / N,) * N, "low_re", drag_ratio=body.drag_ratio, frame=body.frame)
    return AffineRestriction(chain, S, shape_names=body.shape_names, shape_limits=body.shape_limits,
                             name=f"{N}-link chain sampling the {body.name}")

"""A continuous slender swimmer at low Reynolds number whose curvature is a sum of shape modes (numpy only).

Beyond the draft (after Hatton & Choset's serpenoid swimmers and Ramasamy & Hatton 2019): a
body of length L, arc length s in [0, L], with curvature ``kappa(s) = sum_k r_k phi_k(s)``; the
shape is the mode amplitudes r. The serpenoid pair is ``phi_1 = cos(2 pi s / L)``,
``phi_2 = sin(2 pi s / L)``; any modes may be given as functions of s. The body frame sits at
the middle of the body, s = L/2, along its tangent (``frame="middle"``), or at the centre of
mass with the mean orientation (``frame="com"``). With ``theta(s) = int_{L/2}^s kappa`` and
``p(s) = int_{L/2}^s (cos theta, sin theta)``, the velocity of the body at s is
``v(s) = xi_xy + xi_theta perp(p(s)) + (dp/dr) r_dot`` and resistive force theory gives the
force per unit length ``-(t t^T + k n n^T) v`` (t, n the tangent and normal, k =
``drag_ratio``). The drag matrix ``D = int W(s)^T (t t^T + k n n^T) W(s) ds`` (W: v = W (xi,
r_dot)) has the net wrench as its top rows, the Pfaffian.

Quadrature: ``panels`` Gauss-Legendre panels of ``order`` nodes along the body for the drag
integral, and for p(s) and dp/dr at each node an ``order``-point Gauss rule from L/2 to s
(exact integrals of the modes where they are known, the serpenoid pair; otherwise the same
rule). A chain of N links whose joint angles sample the same curvature,
:func:`chain_approximation`, converges to this body as N grows (at rate 1/N^2; tested).
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import SE2
from gm_core.systems.base import LocomotionSystem, SystemPart, rectangle_outline
from gm_core.systems.connection import connection_from_pfaffian, shape_space_metric
from gm_core.systems.reframed import body_jacobian
from gm_core.systems.restricted import AffineRestriction
from gm_core.validation import FloatArray, as_array, check_int, check_option, positive_number

__all__ = ["SlenderBody", "serpenoid_modes", "chain_approximation"]


def serpenoid_modes(length: float = 1.0) -> tuple[Any, Any]:
    """The serpenoid pair (cos(2 pi s / L), sin(2 pi s / L)) and their integrals from L/2 (exact)."""
    L = positive_number(length, "length")
    w = 2 * np.pi / L
    modes = (lambda s: np.cos(w * s), lambda s: np.sin(w * s))
    integrals = (lambda s: np.sin(w * s) / w, lambda s: -(np.cos(w * s) + 1.0) / w)
    return modes, integrals


class SlenderBody(LocomotionSystem):
    """Continuous slender swimmer (resistive force theory); shape = mode amplitudes. See the module docstring."""

    may_be_singular = False

    def __init__(self, length: float = 1.0, modes: Any = "serpenoid", *, drag_ratio: float = 2.0, frame: Any = "middle",
                 panels: int = 8, order: int = 8, segments: int = 40) -> None:
        self.length = positive_number(length, "length", maximum=1e6)
        self.drag_ratio = positive_number(drag_ratio, "drag_ratio", maximum=1e6, what=" (lateral over longitudinal drag)")
        self.frame = check_option(frame, "frame", ("middle", "com"))
        self.panels = check_int(panels, "panels", minimum=1, maximum=512, what=" (Gauss panels along the body)")
        self.order = check_int(order, "order", minimum=2, maximum=64, what=" (Gauss nodes per panel)")
        self.segments = check_int(segments, "segments", minimum=2, maximum=1000, what=" (pieces drawn)")
        L = self.length
        if isinstance(modes, str):
            check_option(modes, "modes", ("serpenoid",))
            self.modes, integrals = serpenoid_modes(L)
            self.mode_names: tuple[str, ...] = ("cos", "sin")
        else:
            if isinstance(modes, (bytes, dict)) or not hasattr(modes, "__len__") or len(modes) < 1 \
                    or not all(callable(m) for m in modes):
                raise TypeError("modes must be 'serpenoid' or a sequence of functions s -> phi(s) (curvature per unit "
                                f"amplitude along the body, 0 <= s <= length); got {modes!r:.60}")
            self.modes, integrals = tuple(modes), None
            self.mode_names = tuple(f"mode {k + 1}" for k in range(len(modes)))
        self.n_shape = len(self.modes)
        self.shape_names = tuple(f"r{k + 1}" for k in range(self.n_shape))
        self.shape_limits = ((-2 * np.pi, 2 * np.pi),) * self.n_shape
        self.name = f"slender body ({'serpenoid' if integrals else f'{self.n_shape} modes'})"
        # nodes and weights of the drag integral; sub-nodes from L/2 to each node for p(s)
        x, w = np.polynomial.legendre.leggauss(self.order)
        edges = np.linspace(0.0, L, self.panels + 1)
        a, b = edges[:-1, None], edges[1:, None]
        self._s = ((a + b) / 2 + (b - a) / 2 * x).ravel()
        self._w = ((b - a) / 2 * w).ravel()
        # the drawn pieces' centres are quadrature points too (for part_poses)
        sc = (np.arange(self.segments) + 0.5) * L / self.segments
        alls = np.concatenate([self._s, sc])
        half = (alls - L / 2)[:, None]
        self._sub_w = half / 2 * w                                        # (S, m)
        sub = L / 2 + half / 2 * (x + 1)                                   # (S, m)
        self._Phi_sub = self._mode_integrals(sub, integrals)               # (S, m, n) Phi_k(sub)
        self._Phi = self._mode_integrals(alls[:, None], integrals)[:, 0]   # (S, n) theta = r . Phi
        self._Q = self._s.size

    def _mode_integrals(self, s, integrals):
        """Phi_k(s) = int_{L/2}^s phi_k, (..., n): exact when known, else Gauss-Legendre (2 order nodes)."""
        if integrals is not None:
            return np.stack([f(s) for f in integrals], -1)
        x, w = np.polynomial.legendre.leggauss(2 * self.order)
        h = (s - self.length / 2)[..., None]
        t = self.length / 2 + h / 2 * (x + 1)
        vals = []
        for k, f in enumerate(self.modes):
            v = np.asarray(f(t), dtype=float)
            if v.shape != t.shape or not np.all(np.isfinite(v)):
                raise ValueError(f"modes[{k}] must return one finite curvature per arc length s (an array like s)")
            vals.append((h / 2 * w * v).sum(-1))
        return np.stack(vals, -1)

    # -- geometry of the body ----------------------------------------------------------------
    def _curve(self, r, draw=False):
        """theta (..., S), p (..., S, 2), dp/dr (..., S, 2, n) at the quadrature nodes (and, with
        ``draw``, after them the drawn pieces' centres), in the middle frame."""
        S = slice(None) if draw else slice(0, self._Q)
        Phi, Phi_sub, sub_w = self._Phi[S], self._Phi_sub[S], self._sub_w[S]
        th = r @ Phi.T                                                       # (..., S)
        ths = r @ Phi_sub.reshape(-1, self.n_shape).T                       # (..., S * m)
        ths = ths.reshape(ths.shape[:-1] + sub_w.shape)
        wc, ws = sub_w * np.cos(ths), sub_w * np.sin(ths)
        p = np.stack([wc.sum(-1), ws.sum(-1)], -1)
        dpx = np.stack([-(ws * Phi_sub[..., k]).sum(-1) for k in range(self.n_shape)], -1)   # (..., S, n)
        dpy = np.stack([(wc * Phi_sub[..., k]).sum(-1) for k in range(self.n_shape)], -1)
        return th, p, np.stack([dpx, dpy], -2)

    def _frame(self, th, p, dp):
        """The body frame (..., 3) relative to the middle frame and its body Jacobian (..., 3, n)."""
        n = self.n_shape
        if self.frame == "middle":
            z = np.zeros(th.shape[:-1])
            return np.stack([z, z, z], -1), np.zeros(th.shape[:-1] + (3, n))
        w = self._w / self.length
        Q = self._Q
        beta = np.concatenate([np.einsum("s,...sj->...j", w, p[..., :Q, :]), (th[..., :Q] @ w)[..., None]], -1)
        dbeta = np.concatenate([np.einsum("s,...sjk->...jk", w, dp[..., :Q, :, :]),
                                (w @ self._Phi[:Q])[None, :] + np.zeros(th.shape[:-1] + (1, n))], -2)
        return beta, body_jacobian(beta, dbeta)

    def link_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., segments, 3) of the drawn pieces' centres in the body frame."""
        r = self._shape(r)
        th, p, dp = self._curve(r, draw=True)
        Q = self._Q
        P = np.concatenate([p[..., Q:, :], th[..., Q:, None]], -1)
        if self.frame == "middle":
            return P
        beta = self._frame(th, p, dp)[0]
        return SE2.compose(SE2.inverse(beta)[..., None, :], P)

    def link_weights(self) -> FloatArray:
        return np.full(self.segments, 1.0 / self.segments)

    def curvature(self, r: ArrayLike, s: ArrayLike) -> FloatArray:
        """Curvature kappa(s) (..., len(s)) at arc lengths s (k,) for shapes r (..., n)."""
        r = self._shape(r)
        s = as_array(s, "s", what=" (arc lengths along the body)")
        if s.ndim != 1:
            raise ValueError(f"s must be a vector of arc lengths (k,); got shape {s.shape}")
        phi = np.stack([np.broadcast_to(np.asarray(f(s), dtype=float), s.shape) for f in self.modes], -1)
        return r @ phi.T

    # -- physics ---------------------------------------------------------------------------------
    def metric(self, r: ArrayLike) -> FloatArray:
        """Drag matrix (..., 3 + n, 3 + n): ``int W^T (t t^T + k n n^T) W ds`` by the body quadrature.

        Computed in the middle frame; in the centre-of-mass frame it is ``T^T D T`` with
        ``T (xi~, r_dot) = (Ad_beta (xi~ - B_beta r_dot), r_dot)`` (the same power, other coordinates).
        """
        r = self._shape(r)
        th, p, dp = self._curve(r)
        Q = self._Q
        tq, pq, dq = th[..., :Q], p[..., :Q, :], dp[..., :Q, :, :]
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
        beta, Bb = self._frame(th, p, dp)
        T = np.zeros(D.shape)
        Ad = SE2.Ad(beta)
        T[..., :3, :3] = Ad
        T[..., :3, 3:] = -Ad @ Bb
        T[..., 3:, 3:] = np.eye(n)
        return np.swapaxes(T, -1, -2) @ D @ T

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian (..., 3, 3 + n): the net drag wrench, the top rows of :meth:`metric`."""
        return self.metric(r)[..., :3, :]

    @override
    def connection(self, r: ArrayLike) -> FloatArray:
        return connection_from_pfaffian(self.pfaffian(r))

    @override
    def shape_metric(self, r: ArrayLike) -> FloatArray:
        D = self.metric(r)
        return shape_space_metric(D, connection_from_pfaffian(D[..., :3, :]))

    @override
    def body_frames(self, bounds: Any = None, *, n: int | None = None, centre_of_mass: bool = True,
                    minimum_perturbation: bool = True) -> dict[str, LocomotionSystem]:
        """{name: system}: the middle of the body and, if asked, the centre of mass (mean
        orientation) and minimum perturbation over ``bounds``."""
        out = {"middle of the body": self._twin("middle")}
        if centre_of_mass:
            out["centre of mass"] = self._twin("com")
        if minimum_perturbation:
            from gm_core.systems.minimum_perturbation import MinimumPerturbationFrame
            from gm_core.systems.reframed import Reframed

            base = out["middle of the body"]
            out["minimum perturbation"] = Reframed(base, MinimumPerturbationFrame.fit(base, bounds, n),
                                                   name=f"{self.name} (minimum perturbation)")
        return out

    def _twin(self, frame):
        modes = "serpenoid" if self.mode_names == ("cos", "sin") else self.modes
        return SlenderBody(self.length, modes, drag_ratio=self.drag_ratio, frame=frame, panels=self.panels,
                           order=self.order, segments=self.segments)

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
        return (f"SlenderBody(length={self.length:g}, modes={self.mode_names}, drag_ratio={self.drag_ratio:g}, "
                f"frame={self.frame!r})")


def chain_approximation(body: SlenderBody, n_links: int) -> AffineRestriction:
    """A chain of ``n_links`` equal links of total length L whose joint angles sample ``body``'s curvature.

    Link i's centre sits at s_i = (i - 1/2) L / N and is turned by theta(s_i); joint j therefore
    turns by ``alpha_j = theta(s_{j+1}) - theta(s_j) = sum_k r_k (Phi_k(s_{j+1}) - Phi_k(s_j))``,
    linear in the mode amplitudes. Returns the low-Re :class:`~gm_core.systems.LinkChain`
    restricted to those joint angles (an :class:`~gm_core.systems.AffineRestriction` with the
    body's shape variables), in the matching frame (middle link or joint).
    """
    from gm_core.systems.link_chain import LinkChain

    if not isinstance(body, SlenderBody):
        raise TypeError(f"body must be a SlenderBody; got {type(body).__name__}")
    N = check_int(n_links, "n_links", minimum=2, maximum=200, what=" (links of the chain)")
    L = body.length
    sc = (np.arange(N) + 0.5) * L / N
    integrals = serpenoid_modes(L)[1] if body.mode_names == ("cos", "sin") else None
    Phi = body._mode_integrals(sc[:, None], integrals)[:, 0]                # (N, n)
    S = np.diff(Phi, axis=0)                                                 # (N - 1, n)
    chain = LinkChain((L / N,) * N, "low_re", drag_ratio=body.drag_ratio, frame="middle" if body.frame == "middle" else "com")
    return AffineRestriction(chain, S, shape_names=body.shape_names, shape_limits=body.shape_limits,
                             name=f"{N}-link chain sampling the {body.name}")

"""Extensible continuum bodies in the plane: backbone frames g(s; r) and their Jacobians wrt the shape r.

numpy only. Beyond the draft (after the author's ``continuumbody.ContinuumBody`` and his examples
E720, constant curvature, and E727, stretch): a body of reference length L, reference arc length s in
[0, L], whose backbone frames solve the flow ``g'(s) = g(s) h(s; r)`` from ``g(0) = e`` with the body
twist per unit reference length

    h(s; r) = (1 + sigma(s; r), 0, kappa(s; r)),  kappa = sum_k r_k phi_k(s),  sigma = sum_j r_j psi_j(s):

the author's fixed part ``(1, 0, 0)`` plus the shape part, curvature modes phi_k (turning per unit
reference length) and stretch modes psi_j (the local strain: a piece ds of the body has length
``(1 + sigma) ds``). The shape r lists the curvature amplitudes, then the stretch amplitudes. With no
stretch modes this is the inextensible backbone of :class:`gm_core.systems.SlenderBody` (which
starts at its middle instead); with constant kappa and sigma it is the arc ``g(s) = exp(s h)``, the
bend joint of :mod:`gm_core.chains.chain` when sigma = 0.

Because SE(2)'s rotations commute, the flow has the closed form theta(s) = int_0^s kappa and
``p(s) = int_0^s (1 + sigma) (cos theta, sin theta)``; its derivatives in r are
``d theta / d r_k = int_0^s phi_k`` and ``d p / d r`` = ``int_0^s (1 + sigma) (-sin theta, cos theta) d theta / d r_k``
for a curvature amplitude, ``int_0^s psi_j (cos theta, sin theta)`` for a stretch one. Every integral is
a composite Gauss-Legendre rule (``panels`` equal panels plus edges at the ``breaks`` where a mode
jumps, ``order`` nodes each); theta inside the position integrals by the same rule (nested).

Shapes: ``r: (..., n)``, ``s: (k,)``; poses ``(..., k, 3)``; Jacobians ``(..., k, 3, n)``.
"""
from __future__ import annotations

import functools
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.chains.jacobians import world_to_body_jacobian
from gm_core.validation import FloatArray, as_array, check_int, positive_number

__all__ = ["ContinuumBody"]

Mode = Callable[[FloatArray], ArrayLike]


def _constant(c: float, s: FloatArray) -> FloatArray:
    return np.full(np.shape(s), c)


def _modes(modes: Any, name: str) -> tuple[Mode, ...]:
    """Modes as functions of s; a number c is the constant mode c."""
    if isinstance(modes, (str, bytes, dict)) or not hasattr(modes, "__len__"):
        raise TypeError(f"{name} must be a sequence of functions s -> value (or numbers, constant modes); got {modes!r:.60}")
    out: list[Mode] = []
    for k, m in enumerate(modes):
        if callable(m):
            out.append(m)
        elif isinstance(m, (int, float, np.integer, np.floating)) and not isinstance(m, bool) and np.isfinite(m):
            out.append(functools.partial(_constant, float(m)))
        else:
            raise TypeError(f"{name}[{k}] must be a function s -> value or a finite number; got {m!r:.60}")
    return tuple(out)


class ContinuumBody:
    """A planar continuum body with curvature and stretch modes; see the module docstring.

    ``ContinuumBody(curvature_modes=(), stretch_modes=(), length=1.0, *, breaks=(), panels=16, order=8)``:
    each mode a function of the reference arc length s (vectorized) or a number (a constant mode).
    """

    def __init__(self, curvature_modes: Sequence[Any] = (), stretch_modes: Sequence[Any] = (), length: float = 1.0, *,
                 breaks: ArrayLike = (), panels: int = 16, order: int = 8) -> None:
        self.curvature_modes = _modes(curvature_modes, "curvature_modes")
        self.stretch_modes = _modes(stretch_modes, "stretch_modes")
        self.n_curvature, self.n_stretch = len(self.curvature_modes), len(self.stretch_modes)
        self.n_shape = self.n_curvature + self.n_stretch
        if self.n_shape == 0:
            raise ValueError("curvature_modes, stretch_modes: a continuum body needs at least one shape mode")
        self.length = L = positive_number(length, "length", maximum=1e6, what=" (reference length of the body)")
        self.panels = check_int(panels, "panels", minimum=1, maximum=512, what=" (Gauss panels along the body)")
        self.order = check_int(order, "order", minimum=2, maximum=64, what=" (Gauss nodes per panel)")
        br = as_array(breaks, "breaks", what=" (arc lengths where a mode jumps)")
        if br.ndim != 1 or np.any((br <= 0) | (br >= L)):
            raise ValueError(f"breaks must be a list of arc lengths strictly inside (0, length={L:g}); got {br}")
        edges = sorted({0.0, L, *(float(b) for b in br)})
        for e in np.linspace(0.0, L, self.panels + 1):
            if np.min(np.abs(np.array(edges) - e)) > 1e-9 * L:
                edges.append(float(e))
        self._edges = np.array(sorted(edges))
        self._gauss = np.polynomial.legendre.leggauss(self.order)

    # -------------------------------------------------------------------- quadrature
    def _values(self, modes: tuple[Mode, ...], u: FloatArray) -> FloatArray:
        """Mode values (m, len(modes)) at points u (m,)."""
        vals = []
        for k, f in enumerate(modes):
            v = np.broadcast_to(np.asarray(f(u), dtype=float), u.shape)
            if not np.all(np.isfinite(v)):
                raise ValueError(f"modes: mode {k} must return one finite value per arc length s (an array like s)")
            vals.append(v)
        return np.stack(vals, -1) if vals else np.zeros(u.shape + (0,))

    def _integral(self, f: Callable[[FloatArray], FloatArray], t: FloatArray) -> FloatArray:
        """``int_0^t f`` (..., k, d) at t (k,) for f: u (m,) -> (..., m, d), by the composite rule."""
        x, w = self._gauss
        e = self._edges
        P, m = e.size - 1, self.order
        a, b = e[:-1, None], e[1:, None]
        U, W = (a + (b - a) / 2 * (x + 1)).ravel(), ((b - a) / 2 * w)
        F = f(U)
        F = F.reshape(F.shape[:-2] + (P, m, F.shape[-1]))
        panel = np.einsum("pm,...pmd->...pd", W, F)
        E = np.concatenate([np.zeros(panel.shape[:-2] + (1, panel.shape[-1])), np.cumsum(panel, axis=-2)], axis=-2)
        idx = np.clip(np.searchsorted(e, t, side="right") - 1, 0, P - 1)
        lo = e[idx][:, None]
        sub, sw = lo + (t[:, None] - lo) / 2 * (x + 1), (t[:, None] - lo) / 2 * w
        G = f(sub.ravel())
        G = G.reshape(G.shape[:-2] + (t.size, m, G.shape[-1]))
        return E[..., idx, :] + np.einsum("km,...kmd->...kd", sw, G)

    def _shape(self, r: ArrayLike) -> FloatArray:
        return as_array(r, "r", (self.n_shape,),
                        what=f" ({self.n_curvature} curvature then {self.n_stretch} stretch amplitudes)")

    def _points(self, s: ArrayLike | None) -> FloatArray:
        if s is None:
            return np.linspace(0.0, self.length, 33)
        s = np.atleast_1d(as_array(s, "s", what=" (reference arc lengths along the body)"))
        if s.ndim != 1 or np.any((s < 0) | (s > self.length)):
            raise ValueError(f"s must be a list of arc lengths in [0, length={self.length:g}]; got {s}")
        return s

    def _theta(self, r: FloatArray, u: FloatArray) -> tuple[FloatArray, FloatArray]:
        """theta (..., m) and the curvature modes' integrals Phi (m, n_curvature) at u (m,)."""
        Phi = self._integral(lambda v: self._values(self.curvature_modes, v), u)
        return np.einsum("mk,...k->...m", Phi, r[..., :self.n_curvature]), Phi

    # -------------------------------------------------------------------- the model
    def curvature(self, r: ArrayLike, s: ArrayLike | None = None) -> FloatArray:
        """kappa(s; r) = sum_k r_k phi_k(s), ``(..., k)``: turning per unit reference length."""
        r, s = self._shape(r), self._points(s)
        return np.einsum("mk,...k->...m", self._values(self.curvature_modes, s), r[..., :self.n_curvature])

    def stretch(self, r: ArrayLike, s: ArrayLike | None = None) -> FloatArray:
        """sigma(s; r) = sum_j r_j psi_j(s), ``(..., k)``: the local strain, ds stretched to (1 + sigma) ds."""
        r, s = self._shape(r), self._points(s)
        return np.einsum("mk,...k->...m", self._values(self.stretch_modes, s), r[..., self.n_curvature:])

    def frames_and_jacobians(self, r: ArrayLike, s: ArrayLike | None = None,
                             velocity: str = "world") -> tuple[FloatArray, FloatArray]:
        """Backbone poses g(s; r) ``(..., k, 3)`` and their Jacobians wrt r ``(..., k, 3, n)``.

        ``velocity`` "world" gives d g / d r (g_dot = J r_dot); "body" gives T_g L_{g^-1} d g / d r.
        s defaults to 33 evenly spaced points from 0 to L.
        """
        if velocity not in ("world", "body"):
            raise ValueError(f"velocity must be 'world' or 'body'; got {velocity!r}")
        r, s = self._shape(r), self._points(s)
        nc = self.n_curvature
        rs = r[..., nc:]

        def integrand(u: FloatArray) -> FloatArray:
            th, Phi = self._theta(r, u)
            lam = 1.0 + np.einsum("mj,...j->...m", self._values(self.stretch_modes, u), rs)
            c, sn = np.cos(th), np.sin(th)
            psi = self._values(self.stretch_modes, u)
            dc = np.concatenate([(-lam * sn)[..., None] * Phi, c[..., None] * psi], -1)   # d(lam cos th)/dr
            ds = np.concatenate([(lam * c)[..., None] * Phi, sn[..., None] * psi], -1)    # d(lam sin th)/dr
            return np.concatenate([(lam * c)[..., None], (lam * sn)[..., None], dc, ds], -1)

        n = self.n_shape
        out = self._integral(integrand, s)
        th, Phi = self._theta(r, s)
        poses = np.concatenate([out[..., :2], th[..., None]], -1)
        batch = r.shape[:-1]
        dth = np.concatenate([np.broadcast_to(Phi, batch + Phi.shape), np.zeros(batch + s.shape + (self.n_stretch,))], -1)
        J = np.stack([out[..., 2:2 + n], out[..., 2 + n:], dth], -2)
        if velocity == "body":
            J = world_to_body_jacobian(poses, J)
        return poses, J

    def frames(self, r: ArrayLike, s: ArrayLike | None = None) -> FloatArray:
        """Backbone poses g(s; r) ``(..., k, 3)`` from g(0) = e; s defaults to 33 points from 0 to L."""
        return self.frames_and_jacobians(r, s)[0]

    def jacobians(self, r: ArrayLike, s: ArrayLike | None = None, velocity: str = "world") -> FloatArray:
        """Jacobians ``(..., k, 3, n)`` of the backbone poses wrt the shape r (world or body velocity)."""
        return self.frames_and_jacobians(r, s, velocity)[1]

    def __repr__(self) -> str:
        return (f"ContinuumBody({self.n_curvature} curvature and {self.n_stretch} stretch modes, "
                f"length={self.length:g})")

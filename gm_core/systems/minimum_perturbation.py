"""Hatton's minimum-perturbation body frame on a box of shape space of any dimension (numpy/scipy only).

Hatton & Choset (2011, 2015) choose the body frame ``beta(r)`` that makes ``int |A~|^2`` over a
box of shape space as small as possible (:mod:`gm_core.systems.reframed` for how A changes
with the frame): then ``oint A~ dr`` is small, the body-velocity integral and the Stokes
estimate are accurate, and curvature maps read as pictures of net displacement. The theta row
is a Hodge-Helmholtz projection (a Neumann-Poisson problem); once beta_theta is fixed, the
(x, y) rows are a linear least-squares problem. Both are solved with multilinear finite
elements on a grid of ``n`` nodes per axis (bilinear in two dimensions, as sysplotter does),
2 Gauss points per axis and cell, and scipy.sparse; beta between nodes is a biquintic spline in
two dimensions and a tensor-product cubic spline in more.

Feasible here for boxes of dimension 1 to 3 (chains of up to four links; 33 x 33 nodes in 2-D, 13^3
in 3-D, a few seconds) and up to 40 000 nodes; larger problems are refused with a message that
says why (a 9^4 grid for a five-link chain works but takes about two minutes here).
"""
from __future__ import annotations

import itertools
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.systems.base import LocomotionSystem
from gm_core.systems.motion import trusted_dimension
from gm_core.systems.reframed import BodyFrame, body_jacobian
from gm_core.validation import BoolArray, FloatArray, SingularShapeError, as_array

__all__ = ["MinimumPerturbationFrame", "MAX_NODES", "MAX_DIMENSION", "default_nodes", "too_many_dimensions"]

#: Largest finite-element grid (nodes) and box dimension the solver accepts.
MAX_NODES = 40_000
MAX_DIMENSION = 3
_GAUSS = ((1 - 1 / np.sqrt(3)) / 2, (1 + 1 / np.sqrt(3)) / 2)


def too_many_dimensions(argument: str, name: str, d: int) -> str:
    """The message that refuses minimum-perturbation coordinates on a box of dimension d > MAX_DIMENSION."""
    return (f"{argument}: minimum-perturbation coordinates are feasible here for at most {MAX_DIMENSION} shape "
            f"variables (chains of up to {MAX_DIMENSION + 1} links): {name} has {d}, and the finite-element problem "
            f"on a {d}-dimensional box takes minutes (about 2 minutes for 9^4 nodes on this machine). Use "
            "frame='com' (centre of mass, mean orientation), which is close to it for swimmers, or a 2-D slice "
            "(gm_core.systems.shape_slice)")


def default_nodes(dim: int) -> int:
    """Default nodes per axis for a box of dimension ``dim``: 33, 13, 9, then the largest within MAX_NODES."""
    return {1: 129, 2: 33, 3: 13, 4: 9}.get(dim, max(4, int(MAX_NODES ** (1 / dim))))


def _fem_operators(axes):
    """Sparse value and gradient operators from nodal values to the 2^d Gauss points of each cell.

    Returns (points (Q, d), weights (Q,), Phi, [G_1 .. G_d]) with Phi, G_k (Q, N) scipy.sparse,
    nodes numbered in C order over the axes (``i * n2 + j`` in two dimensions).
    """
    import scipy.sparse as sp

    d = len(axes)
    shape = tuple(len(x) for x in axes)
    h = np.array([x[1] - x[0] for x in axes])
    cells = np.stack([c.ravel() for c in np.meshgrid(*[np.arange(m - 1) for m in shape], indexing="ij")], -1)
    nc = cells.shape[0]
    rows, cols, vals, grads, pts = [], [], [], [[] for _ in range(d)], []
    for q, u in enumerate(itertools.product(_GAUSS, repeat=d)):
        u = np.array(u)
        idx = q * nc + np.arange(nc)
        pts.append(np.stack([axes[k][cells[:, k]] + u[k] * h[k] for k in range(d)], -1))
        for corner in itertools.product((0, 1), repeat=d):
            corner = np.array(corner[::-1])            # (0,0), (1,0), (0,1), (1,1) in two dimensions
            f1 = np.where(corner == 1, u, 1 - u)       # 1-D factors
            df = np.where(corner == 1, 1.0, -1.0) / h
            rows.append(idx)
            cols.append(np.ravel_multi_index(tuple((cells + corner).T), shape))
            vals.append(np.full(nc, np.prod(f1)))
            for k in range(d):
                grads[k].append(np.full(nc, np.prod(np.delete(f1, k)) * df[k]))
    Q, N = (2 ** d) * nc, int(np.prod(shape))
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    mk = lambda v: sp.csr_matrix((np.concatenate(v), (rows, cols)), shape=(Q, N))  # noqa: E731
    return np.vstack(pts), np.full(Q, np.prod(h) / 2 ** d), mk(vals), [mk(g) for g in grads]


class _TensorSpline:
    """Interpolating tensor-product spline through values (n_1, ..., n_d, 3) on a grid: value and gradient."""

    def __init__(self, axes, values):
        from scipy.interpolate import BSpline, NdBSpline, RectBivariateSpline, make_interp_spline

        self.d = len(axes)
        if self.d == 2:        # biquintic, as before the n-D solver (the notebooks' numbers)
            # FITPACK's interpolating fit, one per component (its knots depend on the grid only),
            # evaluated as one vector-valued B-spline: the basis is computed once for all three.
            k = 5
            fits = [RectBivariateSpline(axes[0], axes[1], values[..., c], kx=k, ky=k, s=0) for c in range(3)]
            tx, ty = fits[0].get_knots()
            coef = np.stack([f.get_coeffs().reshape(len(tx) - k - 1, len(ty) - k - 1) for f in fits], -1)
            self._nd = NdBSpline((tx, ty), coef, k)
            return
        k = min(3, min(len(x) for x in axes) - 1)
        coef, self._basis = values, []
        for ax, x in enumerate(axes):
            spl = make_interp_spline(x, np.moveaxis(coef, ax, 0), k=k, axis=0)
            coef = np.moveaxis(spl.c, 0, ax)
            eye = BSpline(spl.t, np.eye(spl.c.shape[0]), k, extrapolate=True)
            self._basis.append((eye, eye.derivative()))
        self._coef = coef

    def __call__(self, r, derivative=None):
        """Values (P, 3) at points r (P, d), or d/dr_k of them when ``derivative=k``."""
        if self.d == 2:
            return self._nd(r, nu=(0, 0) if derivative is None else ((1, 0) if derivative == 0 else (0, 1)))
        out = None
        for ax, (b, db) in enumerate(self._basis):
            B = (db if ax == derivative else b)(r[:, ax])      # (P, n_ax)
            if out is None:
                out = (B @ self._coef.reshape(B.shape[1], -1)).reshape((len(r),) + self._coef.shape[1:])
            else:
                rest = out.shape[2:]
                out = (B[:, None, :] @ out.reshape(out.shape[:2] + (-1,)))[:, 0].reshape((len(r),) + rest)
        return out


class MinimumPerturbationFrame(BodyFrame):
    """The minimum-perturbation frame of a system over a box (from :meth:`fit`): pose, Jacobian, domain.

    Attributes: ``bounds`` ((lo, hi) per axis), ``nodes`` (the grid axes), ``beta_nodes``
    (n_1, ..., n_d, 3) (the finite-element solution, beta = 0 at the reference node),
    ``reference`` (the shape where beta vanishes).
    """

    name = "minimum perturbation"
    domain_description = "outside the rectangle (the box) where the minimum-perturbation coordinates were computed"

    @classmethod
    def fit(cls, system: LocomotionSystem, bounds: Any = None, n: int | None = None, *,
            reference: ArrayLike | None = None) -> MinimumPerturbationFrame:
        """Solve the two finite-element problems for ``system`` over ``bounds`` with ``n`` nodes per axis."""
        import scipy.sparse as sp
        import scipy.sparse.linalg as spla

        d = trusted_dimension(system)
        if d > MAX_DIMENSION:
            raise ValueError(too_many_dimensions("system", system.name, d))
        bounds = system.shape_limits if bounds is None else bounds
        B = as_array(bounds, "bounds", (2,), what=f" (a box of shape space: one (lo, hi) per shape variable, {d} here)")
        if B.shape != (d, 2):
            raise ValueError(f"bounds must have shape ({d}, 2), one (lo, hi) per shape variable of "
                             f"{system.name}; got shape {B.shape}")
        if not np.all(B[:, 1] > B[:, 0]):
            raise ValueError(f"bounds must satisfy lo < hi on each axis; got {B.tolist()}")
        n = default_nodes(d) if n is None else n
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 4:
            raise ValueError(f"n must be an integer >= 4 (nodes per axis); got {n!r}")
        if int(n) ** d > MAX_NODES:
            raise ValueError(f"minimum-perturbation coordinates on a {d}-dimensional box with n = {n} nodes per "
                             f"axis need {int(n) ** d} nodes; at most {MAX_NODES} are feasible here (n <= "
                             f"{int(MAX_NODES ** (1 / d))} for {d} shape variables)")
        n = int(n)
        axes = [np.linspace(B[k][0], B[k][1], n) for k in range(d)]
        pts, w, Phi, G = _fem_operators(axes)
        A = system.connection(pts)
        if not np.all(np.isfinite(A)):
            bad = pts[~np.isfinite(A).all(axis=(-1, -2))][0]
            raise SingularShapeError(f"{system.name} is singular at r = ({', '.join(f'{v:.4g}' for v in bad)}) inside "
                                     f"bounds {B.tolist()}: choose a box free of singular shapes")
        N = n ** d
        if reference is None:
            reference = np.where((B[:, 0] <= 0) & (B[:, 1] >= 0), 0.0, B.mean(axis=1))
        ref = as_array(reference, "reference", (d,))
        iref = int(np.ravel_multi_index(tuple(int(np.argmin(np.abs(axes[k] - ref[k]))) for k in range(d)), (n,) * d))
        W = sp.diags(w)
        # theta row: K b = G^T W A_theta, pinned at the reference node (constants are the null space)
        K = sum(Gk.T @ W @ Gk for Gk in G).tocsc()
        rhs = sum(Gk.T @ (w * A[:, 2, k]) for k, Gk in enumerate(G))
        keep = np.arange(N) != iref
        bt = np.zeros(N)
        bt[keep] = spla.spsolve(K[keep][:, keep], rhs[keep])
        # (x, y) rows: residuals A_x - G bx - A_theta Phi by and A_y - G by + A_theta Phi bx
        blocks, rhs_xy = [], []
        for k, Gk in enumerate(G):
            At = sp.diags(A[:, 2, k]) @ Phi
            blocks += [sp.hstack([Gk, At]), sp.hstack([-At, Gk])]
            rhs_xy += [A[:, 0, k], A[:, 1, k]]
        M = sp.vstack(blocks).tocsr()
        wq = np.tile(w, 2 * d)
        Kxy = (M.T @ sp.diags(wq) @ M).tocsc()
        fxy = M.T @ (wq * np.concatenate(rhs_xy))
        scale = abs(Kxy).max()
        bxy = spla.spsolve(Kxy + 1e-13 * scale * sp.identity(2 * N, format="csc"), fxy)
        bn = np.stack([bxy[:N], bxy[N:], bt], -1)  # (N, 3)
        return cls(system, B, axes, bn, iref, (A, w, G))

    def __init__(self, system: LocomotionSystem, bounds: Any, axes: Any, beta_nodes: ArrayLike, iref: int,
                 quadrature: Any) -> None:
        self.system_name = system.name
        self.bounds = tuple(tuple(float(v) for v in row) for row in bounds)
        self.nodes = axes
        n = len(axes[0])
        self.beta_nodes = np.asarray(beta_nodes, dtype=float).reshape((n,) * len(axes) + (3,))
        self.reference = np.array([axes[k][i] for k, i in enumerate(np.unravel_index(iref, (n,) * len(axes)))])
        self._quad, self._bn = quadrature, np.asarray(beta_nodes, dtype=float)
        self._spline = _TensorSpline(axes, self.beta_nodes)
        self._lo, self._hi = np.array(bounds)[:, 0], np.array(bounds)[:, 1]

    def _eval(self, r, derivative=None):
        flat = np.clip(r.reshape(-1, r.shape[-1]), self._lo, self._hi)
        return self._spline(flat, derivative).reshape(r.shape[:-1] + (3,))

    @override
    def pose(self, r: ArrayLike) -> FloatArray:
        return self._eval(np.asarray(r, dtype=float))

    @override
    def jacobian(self, r: ArrayLike) -> FloatArray:
        return self.pose_and_jacobian(r)[1]

    @override
    def pose_and_jacobian(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        r = np.asarray(r, dtype=float)
        beta = self._eval(r)
        d = np.stack([self._eval(r, k) for k in range(r.shape[-1])], -1)
        return beta, body_jacobian(beta, d)

    @override
    def contains(self, r: ArrayLike) -> BoolArray:
        r = np.asarray(r, dtype=float)
        tol = 1e-12 * float(np.max(self._hi - self._lo))
        return np.all((r >= self._lo - tol) & (r <= self._hi + tol), axis=-1)

    def discrete_divergence(self, of: str = "frame") -> FloatArray:
        """Weak divergence (N,) of the theta row at every node, ``sum_k G_k^T W A_theta,k``.

        ``of="frame"``: of the new theta row A~_theta (zero at the optimum: at interior nodes the
        finite-element divergence, at boundary nodes also the outward flux); ``of="base"``: of the
        base system's theta row, for scale.
        """
        A, w, G = self._quad
        At = A[:, 2, :].copy()
        if of == "frame":
            At -= np.stack([Gk @ self._bn[:, 2] for Gk in G], -1)
        elif of != "base":
            raise ValueError(f"of must be 'frame' or 'base'; got {of!r}")
        return sum(Gk.T @ (w * At[:, k]) for k, Gk in enumerate(G))


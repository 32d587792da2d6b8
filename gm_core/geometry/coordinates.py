"""Choice of body frame: a system seen from other coordinates, and Hatton's minimum-perturbation frame.

If the new body frame sits at ``beta(r)`` (an SE(2) pose, (..., 3)) relative to the old one, the
new position is ``g~ = g beta(r)`` and its body velocity is
``xi~ = Ad_{beta^-1} xi + beta^-1 beta_dot`` (the velocity conversions of section 1.5, (1.41)-(1.43)), so with
``xi = -A r_dot`` (3.10) the connection seen from the new frame is

    A~(r) = Ad_{beta^-1} A(r) - T_beta L_{beta^-1} d beta / dr.

Its curvature transforms as ``D(-A~) = Ad_{beta^-1} D(-A)`` and net displacements as
``g~(T) = beta(r0)^-1 g(T) beta(r0)``. Hatton & Choset (2011, 2015) choose beta to make
``int |A~|^2`` over a rectangle of shape space as small as possible: then ``oint A~ dr`` is small,
the body-velocity integral and the Stokes estimate are accurate, and the curvature map can be
read as a picture of the net displacement. The theta row is a Hodge-Helmholtz projection (a
Neumann-Poisson problem); once beta_theta is fixed, the (x, y) rows are an exact linear
least-squares problem because the rotation R(-beta_theta) does not change the norm. Both are
solved with bilinear finite elements (as sysplotter does) and scipy.sparse.
"""
from __future__ import annotations

import numpy as np

from .._validate import SingularShapeError, as_array
from ..gaits import as_gait
from ..groups import SE2
from ..locomotion import net_displacement
from ..systems.base import LocomotionSystem
from .curvature import check_system

__all__ = ["Reframed", "reframe", "centre_of_mass", "centre_of_mass_coordinates", "drift_and_turn", "minimum_perturbation_coordinates",
           "MinimumPerturbationCoordinates", "body_frames"]


class Reframed(LocomotionSystem):
    """``base`` seen from the body frame at ``beta(r)`` (..., 3); ``jacobian(r)`` = d beta / dr (..., 3, n).

    Works wherever a system does (connection, net_displacement, curvature, drawing): parts are
    the base's, placed with ``beta^-1 * base.part_poses(r)``.
    """

    def __init__(self, base, beta, jacobian=None, name=None):
        check_system(base, "base")
        if not callable(beta):
            raise TypeError(f"beta must be a callable r -> (..., 3) pose; got {type(beta).__name__}")
        if jacobian is not None and not callable(jacobian):
            raise TypeError(f"jacobian must be a callable r -> (..., 3, n) or None; got {type(jacobian).__name__}")
        self.base_system = base
        self._beta, self._jac = beta, jacobian
        self.n_shape = base.n_shape
        self.shape_names = base.shape_names
        self.shape_limits = base.shape_limits
        self.may_be_singular = getattr(base, "may_be_singular", False)
        self.singular_description = getattr(base, "singular_description", "")
        self.name = name or f"{base.name} (other frame)"

    def beta(self, r):
        """Pose (..., 3) of the new body frame in the base system's body frame."""
        return np.asarray(self._beta(self._shape(r)), dtype=float)

    def beta_jacobian(self, r):
        """d beta / d r (..., 3, n): the given callable, else central differences."""
        r = self._shape(r)
        if self._jac is not None:
            return np.asarray(self._jac(r), dtype=float)
        h = 1e-6
        cols = []
        for k in range(self.n_shape):
            e = np.zeros(self.n_shape)
            e[k] = h
            cols.append((self.beta(r + e) - self.beta(r - e)) / (2 * h))
        return np.stack(cols, -1)

    def connection(self, r):
        """A~ = Ad_{beta^-1} A - T_beta L_{beta^-1} d beta/dr, (..., 3, n)."""
        r = self._shape(r)
        A = self.base_system.connection(r)
        b = self.beta(r)
        J = self.beta_jacobian(r)
        Adi = SE2.Ad_inv(b)
        c, s = np.cos(b[..., 2]), np.sin(b[..., 2])
        dJ = np.empty(J.shape)
        dJ[..., 0, :] = c[..., None] * J[..., 0, :] + s[..., None] * J[..., 1, :]
        dJ[..., 1, :] = -s[..., None] * J[..., 0, :] + c[..., None] * J[..., 1, :]
        dJ[..., 2, :] = J[..., 2, :]
        return Adi @ A - dJ

    def pfaffian(self, r):
        raise NotImplementedError("a reframed system is defined by its connection")

    def singularity(self, r):
        return self.base_system.singularity(r)

    def is_singular(self, r):
        return self.base_system.is_singular(r)

    def parts(self):
        return self.base_system.parts()

    def part_poses(self, r):
        r = self._shape(r)
        return SE2.compose(SE2.inverse(self.beta(r))[..., None, :], self.base_system.part_poses(r))

    def __repr__(self):
        return f"Reframed({self.base_system!r}, name={self.name!r})"


def reframe(system, beta, jacobian=None, name=None):
    """``system`` seen from the body frame at ``beta(r)``: a :class:`Reframed` system."""
    return Reframed(system, beta, jacobian, name)


def _link_weights(system):
    """Normalised link weights: masses if the system has them, else lengths (slender uniform links)."""
    check_system(system)
    if not callable(getattr(system, "link_poses", None)):
        raise TypeError(f"system must be a three-link system with link_poses(r); got {system!r}")
    w = np.asarray(getattr(system, "masses", None) or system.lengths, dtype=float)
    return w / w.sum()


def centre_of_mass(system, r):
    """Weighted mean ``(..., 3)`` of the link poses of a three-link ``system`` at shapes ``r``,
    in its body frame: (x, y) the centre of mass, theta the mean link orientation.

    Links are weighted by mass if the system has ``masses``, else by length (uniform slender
    links, as for the swimmers).
    """
    w = _link_weights(system)
    return np.einsum("i,...ij->...j", w, system.link_poses(r))


def centre_of_mass_coordinates(system):
    """A three-link ``system`` seen from its centre of mass with the mean link orientation
    (:func:`centre_of_mass`). Hatton & Choset (2011) show this frame is close to the
    minimum-perturbation one for three-link swimmers.
    """
    _link_weights(system)

    def beta(r):
        return centre_of_mass(system, r)

    return Reframed(system, beta, None, name=f"{system.name} (centre of mass, mean orientation)")


def drift_and_turn(system, gait):
    """(net turn angle, distance moved by the centre of mass) over one cycle of ``gait``.

    The shape is the same at the start and the end of a cycle, so the centre of mass sits at the
    same point c of the body frame; the net displacement g(T) carries it from c to g(T) c. Both
    numbers are independent of the choice of body frame.
    """
    _link_weights(system)
    gait = as_gait(gait)
    gT = net_displacement(system, gait)
    c = centre_of_mass(system, gait(np.array([0.0]))[0])[:2]
    return float(gT[2]), float(np.linalg.norm(SE2.act_on_points(gT, c) - c))


# ---------------------------------------------------------------------------------------------
# Minimum-perturbation coordinates (bilinear finite elements)
# ---------------------------------------------------------------------------------------------
_GAUSS = (1 - 1 / np.sqrt(3)) / 2, (1 + 1 / np.sqrt(3)) / 2


def _fem_operators(x1, x2):
    """Sparse value and gradient operators from nodal values to 2x2 Gauss points of each cell.

    Returns (points (Q, 2), weights (Q,), Phi, G1, G2) with Phi, G1, G2 (Q, N) scipy.sparse,
    nodes numbered ``i * n2 + j`` for (x1[i], x2[j]).
    """
    import scipy.sparse as sp

    n1, n2 = len(x1), len(x2)
    h1, h2 = np.diff(x1)[0], np.diff(x2)[0]
    ci, cj = np.meshgrid(np.arange(n1 - 1), np.arange(n2 - 1), indexing="ij")
    ci, cj = ci.ravel(), cj.ravel()
    rows, cols, vals, g1, g2, pts = [], [], [], [], [], []
    q = 0
    for u in _GAUSS:
        for v in _GAUSS:
            idx = q * ci.size + np.arange(ci.size)
            pts.append(np.stack([x1[ci] + u * h1, x2[cj] + v * h2], -1))
            for di, dj, f, fu, fv in ((0, 0, (1 - u) * (1 - v), -(1 - v), -(1 - u)),
                                      (1, 0, u * (1 - v), (1 - v), -u),
                                      (0, 1, (1 - u) * v, -v, (1 - u)),
                                      (1, 1, u * v, v, u)):
                rows.append(idx)
                cols.append((ci + di) * n2 + (cj + dj))
                vals.append(np.full(ci.size, f))
                g1.append(np.full(ci.size, fu / h1))
                g2.append(np.full(ci.size, fv / h2))
            q += 1
    Q, N = 4 * ci.size, n1 * n2
    rows, cols = np.concatenate(rows), np.concatenate(cols)
    mk = lambda v: sp.csr_matrix((np.concatenate(v), (rows, cols)), shape=(Q, N))  # noqa: E731
    return np.vstack(pts), np.full(Q, h1 * h2 / 4), mk(vals), mk(g1), mk(g2)


class MinimumPerturbationCoordinates(Reframed):
    """Result of :func:`minimum_perturbation_coordinates`: a :class:`Reframed` system plus the grid solution.

    Attributes: ``bounds``, ``nodes1``, ``nodes2`` (grid axes), ``beta_nodes`` (n1, n2, 3) (the
    finite-element solution, beta = 0 at the reference node), ``reference`` (the shape where
    beta vanishes). beta between nodes is a biquintic spline through the nodal values, so the
    connection is smooth; outside ``bounds`` it is undefined (NaN, reported as singular).
    """

    def discrete_divergence(self):
        """Weak divergence (N,) of the new theta row at every node: ``G^T W A~_theta``, zero at the optimum.

        At interior nodes this is the finite-element divergence; at boundary nodes it also
        contains the outward flux, so all zeros means divergence-free with no normal flux.
        """
        At = self._A_quad[:, 2, :] - np.stack([self._G1 @ self._bn[:, 2], self._G2 @ self._bn[:, 2]], -1)
        return self._G1.T @ (self._w * At[:, 0]) + self._G2.T @ (self._w * At[:, 1])

    def singularity(self, r):
        r = self._shape(r)
        inside = self._inside(r)
        return np.where(inside, self.base_system.singularity(r), 0.0)

    def is_singular(self, r):
        r = self._shape(r)
        return ~self._inside(r) | self.base_system.is_singular(r)

    def _inside(self, r):
        (a, b), (c, d) = self.bounds
        tol = 1e-12 * max(b - a, d - c)
        return (r[..., 0] >= a - tol) & (r[..., 0] <= b + tol) & (r[..., 1] >= c - tol) & (r[..., 1] <= d + tol)


def minimum_perturbation_coordinates(system, bounds=None, n=33, *, reference=None):
    """Hatton's minimum-perturbation body frame of ``system`` over the rectangle ``bounds``.

    Minimises ``int |A~_theta|^2`` (a Neumann-Poisson problem: A~_theta divergence-free with no
    flux through the boundary), then ``int |A~_x|^2 + |A~_y|^2`` given beta_theta, with bilinear
    finite elements on an ``n x n`` node grid and 2x2 Gauss points per cell. ``bounds``:
    ((lo1, hi1), (lo2, hi2)), default the system's ``shape_limits``; ``reference``: the shape
    where beta_theta = 0 (default the origin if inside, else the centre). Returns a
    :class:`MinimumPerturbationCoordinates` (a system: its ``connection`` can be used
    everywhere). Raises SingularShapeError if the rectangle contains singular shapes.
    """
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla
    from scipy.interpolate import RectBivariateSpline

    check_system(system)
    bounds = system.shape_limits if bounds is None else bounds
    B = as_array(bounds, "bounds", (2,), what=" (((lo1, hi1), (lo2, hi2)), a rectangle of shape space)")
    if B.shape != (2, 2):
        raise ValueError(f"bounds must have shape (2, 2), ((lo1, hi1), (lo2, hi2)); got shape {B.shape}")
    if not np.all(B[:, 1] > B[:, 0]):
        raise ValueError(f"bounds must satisfy lo < hi on each axis; got {B.tolist()}")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 4:
        raise ValueError(f"n must be an integer >= 4 (nodes per axis); got {n!r}")
    x1, x2 = np.linspace(*B[0], n), np.linspace(*B[1], n)
    pts, w, Phi, G1, G2 = _fem_operators(x1, x2)
    A = system.connection(pts)
    if not np.all(np.isfinite(A)):
        bad = pts[~np.isfinite(A).all(axis=(-1, -2))][0]
        raise SingularShapeError(f"{system.name} is singular at r = ({bad[0]:.4g}, {bad[1]:.4g}) inside bounds "
                                 f"{B.tolist()}: choose a rectangle free of singular shapes")
    N = n * n
    if reference is None:
        reference = np.where((B[:, 0] <= 0) & (B[:, 1] >= 0), 0.0, B.mean(axis=1))
    ref = as_array(reference, "reference", (2,))
    iref = int(np.argmin(np.abs(x1 - ref[0]))) * n + int(np.argmin(np.abs(x2 - ref[1])))
    W = sp.diags(w)
    # theta row: K b = G^T W A_theta, pinned at the reference node (constants are the null space)
    K = (G1.T @ W @ G1 + G2.T @ W @ G2).tocsc()
    rhs = G1.T @ (w * A[:, 2, 0]) + G2.T @ (w * A[:, 2, 1])
    keep = np.arange(N) != iref
    bt = np.zeros(N)
    bt[keep] = spla.spsolve(K[keep][:, keep], rhs[keep])
    # (x, y) rows: residuals A_x - G bx - A_theta Phi by and A_y - G by + A_theta Phi bx
    blocks, rhs_xy = [], []
    for k, Gk in enumerate((G1, G2)):
        At = sp.diags(A[:, 2, k]) @ Phi
        blocks += [sp.hstack([Gk, At]), sp.hstack([-At, Gk])]
        rhs_xy += [A[:, 0, k], A[:, 1, k]]
    M = sp.vstack(blocks).tocsr()
    Wq = sp.diags(np.tile(w, 4))
    Kxy = (M.T @ Wq @ M).tocsc()
    fxy = M.T @ (np.tile(w, 4) * np.concatenate(rhs_xy))
    scale = abs(Kxy).max()
    bxy = spla.spsolve(Kxy + 1e-13 * scale * sp.identity(2 * N, format="csc"), fxy)
    bn = np.stack([bxy[:N], bxy[N:], bt], -1)  # (N, 3)
    grid = bn.reshape(n, n, 3)
    splines = [RectBivariateSpline(x1, x2, grid[..., c], kx=5, ky=5, s=0) for c in range(3)]

    def beta(r):
        out = np.stack([s.ev(r[..., 0], r[..., 1]) for s in splines], -1)
        return out

    def jac(r):
        return np.stack([np.stack([s.ev(r[..., 0], r[..., 1], dx=1), s.ev(r[..., 0], r[..., 1], dy=1)], -1)
                         for s in splines], -2)

    out = MinimumPerturbationCoordinates(system, beta, jac, name=f"{system.name} (minimum perturbation)")
    out.bounds = tuple(tuple(float(v) for v in row) for row in B)
    out.shape_limits = out.bounds
    out.nodes1, out.nodes2, out.beta_nodes = x1, x2, grid
    out.reference = np.array([x1[iref // n], x2[iref % n]])
    out._A_quad, out._w, out._G1, out._G2, out._bn = A, w, G1, G2, bn
    out.singular_description = "outside the rectangle where the coordinates were computed"
    inside = out._inside

    def connection(r, _base=Reframed.connection.__get__(out)):
        r = out._shape(r)
        Ac = _base(r)
        return np.where(inside(r)[..., None, None], Ac, np.nan)

    out.connection = connection
    out.may_be_singular = True
    return out


def body_frames(system, bounds=None, *, n=33):
    """Dict of the same system in three frames: 'middle link', 'centre of mass', 'minimum perturbation' (over bounds)."""
    return {"middle link": system, "centre of mass": centre_of_mass_coordinates(system),
            "minimum perturbation": minimum_perturbation_coordinates(system, bounds, n=n)}

"""Added mass of several bodies in one ideal 2-D fluid, coupled through the flow, by a panel method (numpy only).

Beyond the draft, whose high-Re chain (3.47) gives every link the added mass of an ellipse alone
(:func:`~gm_core.systems.fluids.ellipse_added_mass`): here the flow around each link feels the others.

* :func:`ellipse_panels`: a polygon of ``panels`` straight panels through points of an ellipse
  equally spaced in its parameter, with midpoints (the collocation points), unit tangents, outward
  normals and lengths;
* :func:`interacting_added_mass`: the added-mass matrix (N, 3, N, 3) of N ellipses at given poses.
  Every panel carries a constant source density (Hess and Smith's method); the normal velocity of the
  fluid equals that of the surface at every collocation point of every body at once; the fluid's
  kinetic energy ``T = -rho/2 \\oint phi d phi/d n ds`` (n out of the bodies) is the quadratic form
  ``T = 1/2 sum_ij xi_i^T M_ij xi_j`` in the bodies' own body velocities xi_i;
* :class:`InteractingChain`: an N-link chain of ellipses with gaps between them (zero total momentum of
  bodies plus fluid, as :class:`~gm_core.systems.LinkChain` ``"high_re"``, but with this coupled
  added mass): ``sum_ij J_i^T (M_ij + delta_ij M_body,i) J_j`` with J_i the link Jacobians.

sysplotter's own panel method (``getAddedMass_NLinkChain.m``, after Kanso 2004) is the same panel
method with two differences, kept here only to reproduce its numbers (``model="sysplotter"``): the
angle a panel subtends is taken with ``atan`` (wrong by 2 pi where it exceeds pi/2, as next to the
tips of a thin ellipse of 10 panels) and the interaction is lumped onto the links, link i getting
``sum_j M_ij`` (off-diagonal entries averaged between i j and j i) expressed about the common frame,
which is right for rigid motions of the whole chain but not for its shape changes.
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.groups import SE2
from gm_core.systems.base import BalancedSystem, SystemPart, ellipse_outline
from gm_core.systems.link_chain import MAX_LINKS, LinkChain
from gm_core.validation import FloatArray, as_array, check_int, check_option, positive_number

__all__ = ["ellipse_panels", "interacting_added_mass", "InteractingChain", "MODELS"]

#: ``"coupled"``: the kinetic energy of the fluid as a quadratic form in all the links' velocities
#: (the physics); ``"sysplotter"``: sysplotter's lumped form with its atan angle (to reproduce it).
MODELS = ("coupled", "sysplotter")


def ellipse_panels(a: float, b: float, panels: int) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """``(midpoints (P, 2), tangents (P, 2), normals (P, 2), lengths (P,))`` of an ellipse's panels.

    The corners are ``(a cos t, b sin t)`` at t = 2 pi k / P, counter-clockwise (sysplotter's
    ``ellipse``); normals point out of the body.
    """
    a = positive_number(a, "a", maximum=1e100)
    b = positive_number(b, "b", maximum=1e100)
    P = check_int(panels, "panels", minimum=4, maximum=20000, what=" (panels per ellipse)")
    t = np.linspace(0, 2 * np.pi, P + 1)
    corners = np.stack([a * np.cos(t), b * np.sin(t)], -1)
    edge = np.diff(corners, axis=0)
    length = np.linalg.norm(edge, axis=-1)
    tangent = edge / length[:, None]
    return (corners[1:] + corners[:-1]) / 2, tangent, np.stack([tangent[:, 1], -tangent[:, 0]], -1), length


def _influence(points: FloatArray, tangents: FloatArray, normals: FloatArray, lengths: FloatArray,
              exact_angle: bool = True) -> tuple[FloatArray, FloatArray]:
    """``(An, Phi)`` (P, P): normal velocity and minus the potential at midpoint i of a unit source density on panel j.

    Both are 4 pi times the physical values (Kanso's scaling, kept from sysplotter): with
    ``An sigma = v_n`` the potential at the midpoints is ``-Phi sigma``. The angle 2 beta that panel
    j subtends at point i is taken with ``arctan2`` (``exact_angle``) or, as sysplotter does, with
    ``arctan`` of the ratio (2 pi too small where beta > pi/2); on the panel itself it is 2 pi.
    """
    rel = points[:, None, :] - points[None, :, :]
    cn = np.einsum("ijk,jk->ij", rel, normals)
    ct = np.einsum("ijk,jk->ij", rel, tangents)
    d = 0.5 * lengths[None, :]
    plus, minus = (ct + d) ** 2 + cn ** 2, (ct - d) ** 2 + cn ** 2
    vt = np.log(plus / minus)
    num, den = 2 * cn * d, ct ** 2 + cn ** 2 - d ** 2
    with np.errstate(divide="ignore", invalid="ignore"):
        vn = 2 * (np.arctan2(num, den) if exact_angle else np.arctan(num / den))
    np.fill_diagonal(vn, 2 * np.pi)
    vx = vn * normals[None, :, 0] + vt * tangents[None, :, 0]
    vy = vn * normals[None, :, 1] + vt * tangents[None, :, 1]
    An = vx * normals[:, None, 0] + vy * normals[:, None, 1]
    off = 1 - np.eye(len(lengths))
    Phi = -ct * vt - cn * vn * off - d * np.log(plus * minus)
    return An, Phi


def _common_frame_mass(poses: FloatArray, axes: FloatArray, panels: int, exact_angle: bool) -> FloatArray:
    """``rho = 1`` panel integrals ``sum_k phi_(i,a),k v_(j,b),k del_k`` (3N, 3N), velocities (x_dot, y_dot,
    theta_dot) of each body about the common origin in the common frame; not symmetrised."""
    pts, tan, nrm, lens, owner = [], [], [], [], []
    for i, ((x, y, th), (a, b)) in enumerate(zip(poses, axes)):
        p, t, n, ln = ellipse_panels(a, b, panels)
        R = np.array([[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]])
        pts.append(p @ R.T + (x, y))
        tan.append(t @ R.T)
        nrm.append(n @ R.T)
        lens.append(ln)
        owner.append(np.full(panels, i))
    p, t, n, ln, own = (np.concatenate(v) for v in (pts, tan, nrm, lens, owner))
    An, Phi = _influence(p, t, n, ln, exact_angle)
    rigid = np.stack([n[:, 0], n[:, 1], p[:, 0] * n[:, 1] - p[:, 1] * n[:, 0]], -1)       # (P, 3)
    N = len(poses)
    V = np.zeros((len(ln), 3 * N))
    for i in range(N):
        V[own == i, 3 * i:3 * i + 3] = rigid[own == i]
    phi = Phi @ np.linalg.solve(An, V)                      # (P, 3N): minus the potential of each unit motion
    return phi.T @ (V * ln[:, None])


def _check_bodies(poses: ArrayLike, semi_axes: ArrayLike) -> tuple[FloatArray, FloatArray]:
    P = as_array(poses, "poses", (3,), what=" (the bodies' centre poses (x, y, theta))")
    S = as_array(semi_axes, "semi_axes", (2,), what=" (each body's semi-axes (a, b))")
    if P.ndim != 2 or S.shape != P.shape[:1] + (2,) or not 1 <= len(P) <= MAX_LINKS:
        raise ValueError(f"poses (N, 3) and semi_axes (N, 2) must describe the same N bodies, 1 <= N <= {MAX_LINKS}; "
                         f"got shapes {P.shape} and {S.shape}")
    if np.any(S <= 0) or np.any(S > 1e100):
        raise ValueError("semi_axes must be positive (and at most 1e100)")
    return P, S


def interacting_added_mass(poses: ArrayLike, semi_axes: ArrayLike, fluid_density: float = 1.0, *,
                           panels: int = 200) -> FloatArray:
    """Added-mass matrix (N, 3, N, 3) of N ellipses moving in one ideal 2-D fluid, in their own body frames.

    ``poses (N, 3)``: the ellipses' centres and orientations (major axis along their x) in a common
    frame; ``semi_axes (N, 2)``: (a, b). The fluid's kinetic energy is ``1/2 sum_ij xi_i^T M[i, :, j, :] xi_j``
    for body velocities xi_i of the ellipses (Hess-Smith source panels, ``panels`` per ellipse, the
    boundary condition at all of them at once; the symmetric part of the discrete form, whose
    asymmetry vanishes as the panels are refined). For one ellipse it tends to
    :func:`~gm_core.systems.fluids.ellipse_added_mass`; for bodies far apart to a block diagonal.
    """
    P, S = _check_bodies(poses, semi_axes)
    rho = positive_number(fluid_density, "fluid_density", maximum=1e12)
    panels = check_int(panels, "panels", minimum=4, maximum=20000 // len(P), what=" (panels per ellipse)")
    N = len(P)
    Ad = SE2.Ad(P)                                            # (N, 3, 3): body velocity -> velocity about the origin
    M = np.einsum("iak,iajb,jbl->ikjl", Ad, rho * _common_frame_mass(P, S, panels, True).reshape(N, 3, N, 3), Ad)
    M = M.reshape(3 * N, 3 * N)
    return ((M + M.T) / 2).reshape(N, 3, N, 3)


def _sysplotter_lumped(P: FloatArray, S: FloatArray, rho: float, panels: int) -> FloatArray:
    """sysplotter's per-link added mass (N, 3, 3) in the links' frames (getAddedMassByLink + its push-forward)."""
    N = len(P)
    Mc = (rho * _common_frame_mass(P, S, panels, False)).reshape(N, 3, N, 3)
    out = np.zeros((N, 3, 3))
    upper = np.triu(np.ones((3, 3), bool), 1)
    for i in range(N):
        L = np.zeros((3, 3))
        for j in range(N):
            B = Mc[i, :, j, :] if i == j else (Mc[i, :, j, :] + Mc[j, :, i, :]) / 2
            diag = np.diag(np.diag(Mc[i, :, j, :]))
            off = np.where(upper, B, 0.0)
            L += diag + off + off.T
        Ad = SE2.Ad(P[i])
        out[i] = Ad.T @ L @ Ad
    return out


class InteractingChain(BalancedSystem):
    """N ellipse links with gaps, in an ideal fluid whose flow couples them; zero total momentum.

    ``lengths``: the ellipses' major axes l_i (semi-axes l_i / 2 and l_i / (2 ``aspect_ratio``));
    ``separation``: the gap between neighbouring ellipses along the chain (each joint sits halfway
    across it), so the kinematics are those of :class:`~gm_core.systems.LinkChain` with lengths
    l_i + ``separation``, in its ``"middle"`` frame. Bodies of density ``body_density`` (mass
    pi a b rho_b, inertia m (a^2 + b^2) / 4) in a fluid of density ``fluid_density``; added mass by
    :func:`interacting_added_mass` with ``panels`` per ellipse (``model="coupled"``), or
    sysplotter's lumped form (``model="sysplotter"``, see the module docstring).
    """

    def __init__(self, lengths: ArrayLike = (1.0, 1.0, 1.0), *, aspect_ratio: float = 10.0, separation: float = 0.0,
                 fluid_density: float = 1.0, body_density: float = 0.0, panels: int = 200,
                 model: str = "coupled") -> None:
        sep = positive_number(separation, "separation", allow_zero=True, maximum=1e6)
        L = as_array(lengths, "lengths", what=" (the ellipses' major axes)")
        if L.ndim != 1 or not 2 <= len(L) <= MAX_LINKS:
            raise ValueError(f"lengths must be a sequence of N positive lengths, 2 <= N <= {MAX_LINKS}; got {lengths!r:.80}")
        self._chain = LinkChain(tuple(L + sep), "high_re", aspect_ratio=aspect_ratio)
        self.lengths = tuple(float(x) for x in L)
        self.separation = sep
        self.aspect_ratio = self._chain.aspect_ratio
        self.fluid_density = positive_number(fluid_density, "fluid_density", maximum=1e12)
        self.body_density = positive_number(body_density, "body_density", allow_zero=True, maximum=1e12)
        self.model = check_option(model, "model", MODELS)
        self.panels = check_int(panels, "panels", minimum=4, maximum=20000 // len(L), what=" (panels per ellipse)")
        self.n_links, self.n_shape = len(L), len(L) - 1
        self.shape_names = self._chain.shape_names
        self.shape_limits = self._chain.shape_limits
        self.name = f"{self.n_links}-link chain of interacting ellipses" + (" (sysplotter)" if model == "sysplotter" else "")

    def semi_axes(self) -> FloatArray:
        """(N, 2): the ellipses' semi-axes (l_i / 2, l_i / (2 aspect_ratio))."""
        a = np.array(self.lengths) / 2
        return np.stack([a, a / self.aspect_ratio], -1)

    def link_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., N, 3) of the ellipses' centres in the body frame (the middle link or joint)."""
        return self._chain.link_poses(self._shape(r))

    def added_mass(self, r: ArrayLike) -> FloatArray:
        """The links' added mass (..., N, 3, N, 3) at shape r, in their own frames (block diagonal for sysplotter's)."""
        r = self._shape(r)
        poses = self.link_poses(r).reshape(-1, self.n_links, 3)
        S, N = self.semi_axes(), self.n_links
        out = np.zeros((len(poses), N, 3, N, 3))
        for k, P in enumerate(poses):
            if self.model == "coupled":
                out[k] = interacting_added_mass(P, S, self.fluid_density, panels=self.panels)
            else:
                lumped = _sysplotter_lumped(P, S, self.fluid_density, self.panels)
                for i in range(N):
                    out[k, i, :, i, :] = lumped[i]
        return out.reshape(r.shape[:-1] + (N, 3, N, 3))

    @override
    def metric(self, r: ArrayLike) -> FloatArray:
        """Mass matrix (..., 3 + n, 3 + n) of bodies plus fluid: ``sum_ij J_i^T (M_ij + delta_ij M_body,i) J_j``."""
        r = self._shape(r)
        M = self.added_mass(r)
        a, b = self.semi_axes().T
        m = self.body_density * np.pi * a * b
        for i in range(self.n_links):
            M[..., i, :, i, :] += np.diag([m[i], m[i], m[i] * (a[i] ** 2 + b[i] ** 2) / 4])
        J = self._chain.link_jacobians(r)                     # (..., N, 3, 3 + n)
        D = np.einsum("...iak,...iajb,...jbl->...kl", J, M, J)
        return (D + np.swapaxes(D, -1, -2)) / 2

    def mass_matrix(self, r: ArrayLike) -> FloatArray:
        """The same as :meth:`metric` (the book's name for it, (3.39))."""
        return self.metric(r)

    @override
    def parts(self) -> list[SystemPart]:
        return [SystemPart(f"link {i + 1}", ellipse_outline(a, b), "link") for i, (a, b) in enumerate(self.semi_axes())]

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        return self.link_poses(r)

    def with_model(self, model: str, panels: int | None = None) -> InteractingChain:
        """The same chain with another added-mass ``model`` (one of :data:`MODELS`) and ``panels``."""
        return InteractingChain(self.lengths, aspect_ratio=self.aspect_ratio, separation=self.separation,
                                fluid_density=self.fluid_density, body_density=self.body_density,
                                panels=self.panels if panels is None else panels, model=model)

    @override
    def __repr__(self) -> str:
        opts: dict[str, Any] = dict(aspect_ratio=self.aspect_ratio, separation=self.separation, panels=self.panels)
        return (f"InteractingChain(lengths={self.lengths}, " + ", ".join(f"{k}={v:g}" for k, v in opts.items())
                + f", model={self.model!r})")

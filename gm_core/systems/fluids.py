"""Fluid forces on slender and elliptical links (chapter 3, sections 3.4.4-3.4.5; numpy only).

Two regimes, each with a closed form used by :mod:`gm_core.systems` and a numerical route that
notebooks use to show where the closed form comes from:

* **Low Reynolds number** (resistive force theory): a slender link feels drag per unit length
  ``-c u_par`` along itself and ``-k u_perp`` across, k = ``drag_ratio`` * c. Integrated over a
  link of length l this is :func:`slender_link_drag` (the diagonal of (3.41)-(3.43));
  :func:`drag_wrench` integrates the same law numerically (Gauss-Legendre) over any set of links.
* **High Reynolds number** (ideal fluid): an ellipse carries the added mass of
  :func:`ellipse_added_mass` (the corrected (3.46)); :func:`added_mass_bem` recomputes it from the
  potential flow by a boundary method (sources inside the body, Neumann condition on its surface).

Conventions: a link's frame sits at its centre with x along the link; poses ``(..., 3)`` are
(x, y, theta); velocities of link centres are world velocities (x_dot, y_dot, theta_dot).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.validation import FloatArray, as_array, check_int, check_positive, positive_number

__all__ = ["slender_link_drag", "drag_wrench", "ellipse_added_mass", "added_mass_bem"]

# --------------------------------------------------------------------------- low Reynolds number
def slender_link_drag(length: float, drag_ratio: float = 2.0) -> FloatArray:
    """Drag matrix ``diag(l, k l, k l^3 / 12)`` (3, 3) of a slender link, in its centre frame; (3.41)-(3.43).

    The wrench on the link is ``-D xi`` for the link's body velocity xi (longitudinal coefficient
    c = 1, lateral k = ``drag_ratio``); the moment is about the link centre.
    """
    length = positive_number(length, "length", maximum=1e100)
    k = positive_number(drag_ratio, "drag_ratio")
    return np.diag([length, k * length, k * length ** 3 / 12])


def drag_wrench(poses: ArrayLike, velocities: ArrayLike, lengths: ArrayLike, drag_ratio: float = 2.0, *,
                nodes: int | None = 5) -> FloatArray:
    """Total resistive-force drag (F_x, F_y, M) ``(..., 3)`` on a set of slender links, by quadrature.

    poses ``(..., k, 3)``: the link centres (x, y, theta) in some frame; velocities ``(..., k, 3)``:
    their world velocities (x_dot, y_dot, theta_dot) in the same frame; lengths ``(k,)``. At a point
    s along link i the velocity is ``v_i + theta_dot_i s n_i`` and the drag per unit length is
    ``-(v . t) t - k (v . n) n`` (t along the link, n across it); the force and the moment about
    the frame's origin are integrated with ``nodes``-point Gauss-Legendre quadrature, which is exact
    for this law (the integrands are polynomials of degree <= 2 in s) from nodes = 2 on.
    """
    P = as_array(poses, "poses", (3,), what=" (link-centre poses (x, y, theta))")
    V = as_array(velocities, "velocities", (3,), what=" (world velocities of the link centres)")
    if P.ndim < 2:
        raise ValueError(f"poses must have shape (..., k, 3) for k links; got shape {P.shape}")
    L = check_positive(lengths, "lengths")
    if np.any(L > 1e100):
        raise ValueError(f"lengths must be at most 1e100 (their cubes enter the drag); got {L.max():g}")
    if L.ndim != 1 or L.shape[0] != P.shape[-2]:
        raise ValueError(f"lengths must hold one positive length per link of poses ({P.shape[-2]} links); "
                         f"got shape {L.shape}")
    try:
        P, V = np.broadcast_arrays(P, V)
    except ValueError:
        raise ValueError(f"poses and velocities must have the same shape (..., k, 3); got "
                         f"{np.shape(poses)} and {np.shape(velocities)}") from None
    k = positive_number(drag_ratio, "drag_ratio")
    nodes = check_int(nodes, "nodes", minimum=1, maximum=100, what=" (Gauss-Legendre points per link)")
    s0, w0 = np.polynomial.legendre.leggauss(nodes)
    s = s0 * (L[:, None] / 2)                     # (k, q) points along each link
    ws = w0 * (L[:, None] / 2)
    th = P[..., 2]
    t_hat = np.stack([np.cos(th), np.sin(th)], -1)[..., None, :]      # (..., k, 1, 2)
    n_hat = np.stack([-np.sin(th), np.cos(th)], -1)[..., None, :]
    v = V[..., None, :2] + (V[..., 2, None] * s)[..., None] * n_hat   # (..., k, q, 2)
    f = (-np.sum(v * t_hat, -1)[..., None] * t_hat
         - k * np.sum(v * n_hat, -1)[..., None] * n_hat)
    p = P[..., None, :2] + s[..., None] * t_hat
    F = np.einsum("kq,...kqj->...j", ws, f)
    M = np.einsum("kq,...kq->...", ws, p[..., 0] * f[..., 1] - p[..., 1] * f[..., 0])
    return np.concatenate([F, M[..., None]], -1)


# -------------------------------------------------------------------------- high Reynolds number
def _semi_axes(a, b, allow_zero=False):
    a = check_positive(a, "a", allow_zero=allow_zero)
    b = check_positive(b, "b", allow_zero=allow_zero)
    if a.ndim or b.ndim:
        raise ValueError(f"a and b must be numbers (the semi-axes); got shapes {a.shape} and {b.shape}")
    for name, x in (("a", a), ("b", b)):
        if x > 1e100:
            raise ValueError(f"{name} must be at most 1e100 (a semi-axis whose square is finite); got {float(x):g}")
    return float(a), float(b)


def ellipse_added_mass(a: float, b: float, fluid_density: float = 1.0) -> FloatArray:
    """Added-mass matrix (3, 3) of an ellipse (semi-axes a along x, b) in an ideal 2-D fluid.

    ``diag(pi rho b^2, pi rho a^2, pi rho (a^2 - b^2)^2 / 8)``: the corrected (3.46) (the
    draft's rotational entry lacks the factor pi/8), from the potential flow around an ellipse
    (e.g. Lamb, Hydrodynamics, section 72; Newman, Marine Hydrodynamics, table 4.2). a or b may
    be zero (a flat plate).
    """
    a, b = _semi_axes(a, b, allow_zero=True)
    rho = positive_number(fluid_density, "fluid_density")
    return np.diag([np.pi * rho * b ** 2, np.pi * rho * a ** 2, np.pi * rho * (a ** 2 - b ** 2) ** 2 / 8])


def _source_curve(a, b, m):
    """m source points strictly inside the ellipse: on the confocal ellipse halfway (in the
    elliptic coordinate mu) to the focal segment, or on the half-size ellipse for near-circles."""
    if b > a:  # the same construction about the y axis
        return _source_curve(b, a, m)[:, ::-1]
    u = np.linspace(0, 2 * np.pi, m, endpoint=False) + np.pi / m
    if a > b:
        c, mu = np.sqrt(a * a - b * b), 0.5 * np.arctanh(b / a)
        if c * np.cosh(mu) >= a / 2:
            return np.stack([c * np.cosh(mu) * np.cos(u), c * np.sinh(mu) * np.sin(u)], -1)
    return np.stack([a / 2 * np.cos(u), b / 2 * np.sin(u)], -1)


def added_mass_bem(a: float, b: float, fluid_density: float = 1.0, *, n: int = 600, m: int = 300) -> FloatArray:
    """Added-mass matrix (3, 3) of an ellipse computed from the potential flow, for motions (x, y, theta).

    For each unit rigid motion of the body (translation along x, along y, rotation about the
    centre) the flow potential phi solves Laplace's equation outside the ellipse with
    ``d phi / d n = v . n`` on its surface and decays at infinity. phi is written as a sum of m
    two-dimensional sources ``q_j log|p - s_j|`` placed inside the body (zero total strength, so
    no net outflow), fitted by least squares to the boundary condition at n surface points; the
    added mass is ``M_ij = -rho \\oint phi_i (v_j . n) ds`` (twice the fluid's kinetic energy for
    i = j), integrated by the trapezoidal rule in the ellipse's parameter. With the default
    n = 600, m = 300 the result matches :func:`ellipse_added_mass` to ~1e-9 for 1/10 <= a/b <= 10;
    thinner ellipses need more points (n = 1200, m = 600 for a/b = 20).
    """
    a, b = _semi_axes(a, b)
    if not 1e-3 <= a / b <= 1e3:
        raise ValueError(f"a / b must be between 1e-3 and 1e3 for the boundary-element solver (a = {a:g}, "
                         f"b = {b:g}); use ellipse_added_mass for thinner ellipses")
    rho = positive_number(fluid_density, "fluid_density")
    n = check_int(n, "n", minimum=8, maximum=20000, what=" (surface points)")
    m = check_int(m, "m", minimum=4, maximum=20000, what=" (interior sources)")
    if m > n:
        raise ValueError(f"m (sources, {m}) must not exceed n (surface points, {n})")
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    p = np.stack([a * np.cos(t), b * np.sin(t)], -1)
    nrm = np.stack([b * np.cos(t), a * np.sin(t)], -1)     # outward normal times ds/dt
    ds = np.linalg.norm(nrm, axis=-1)
    nrm = nrm / ds[:, None]
    src = _source_curve(a, b, m)
    d = p[:, None, :] - src[None]
    r2 = (d ** 2).sum(-1)
    G = (d * nrm[:, None, :]).sum(-1) / r2                  # normal derivative of log|p - s|
    vel = [np.array([1.0, 0.0]) + 0 * p, np.array([0.0, 1.0]) + 0 * p, np.stack([-p[:, 1], p[:, 0]], -1)]
    vn = np.stack([(v * nrm).sum(-1) for v in vel])         # (3, n) normal speed of the surface
    system = np.vstack([G, np.ones((1, m))])
    q = np.linalg.lstsq(system, np.vstack([vn.T, np.zeros((1, 3))]), rcond=None)[0]   # (m, 3)
    phi = (0.5 * np.log(r2) @ q).T                           # (3, n)
    M = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            M[i, j] = -rho * np.sum(phi[i] * vn[j] * ds) * 2 * np.pi / n
    return M

"""Chains of any number of links swimming or floating, after section 3.4 (numpy only; beyond the draft for N != 3).

N >= 2 links of lengths l_1 .. l_N joined end to end; the shape is r = (alpha_1, ..., alpha_{N-1})
with alpha_j the rotation of link j + 1 relative to link j (chapter 2's convention); each link
frame sits at the link's centre with x along the link towards link N. The poses and Jacobians
are :func:`gm_core.chains.link_chain_poses` and :func:`gm_core.chains.link_chain_jacobians`
(written once, for every N). Physics per link, as in section 3.4 for three links:

* ``"low_re"``: resistive force theory, each link's drag matrix diag(l, k l, k l^3 / 12)
  (:func:`gm_core.systems.fluids.slender_link_drag`, k = ``drag_ratio``); zero net drag wrench;
* ``"high_re"``: ellipses (semi-axes l/2 and l/(2 ``aspect_ratio``)) carrying their added mass
  (:func:`gm_core.systems.fluids.ellipse_added_mass`) plus their own mass (``body_density``); zero momentum;
* ``"floating"``: links of mass m_i (``masses``, default the lengths) and inertia m_i l_i^2 / 12
  (or ``inertias``) in free space; zero momentum.

``link_diagonals`` (N, 3), when given, replaces those link matrices by diag(d_i): measured or
published per-link coefficients, links that carry no load (zero rows; sysplotter's inactive
links), or another tool's coefficients to compare with (:mod:`gm_core.systems.catalog`).

The system matrix ``sum J_i^T M_i J_i`` (:meth:`LinkChain.metric`, (3.39), (3.47)) has the total
wrench or momentum as its top rows: the Pfaffian. No shape is singular (the locked block is
positive definite). Body frames (``frame``, :data:`FRAMES`):

* ``"middle"``: the middle link for odd N; for even N the middle joint, oriented halfway between
  its two links;
* ``"com"``: **the centre of mass with the mean orientation**, the one meaning of "centre of
  mass frame" in this course (exercise 2.3, (2.69); :class:`~gm_core.systems.CentreOfMassFrame`;
  ``body_frames()["centre of mass"]`` of every system made of links): position the weighted mean
  of the link centres, orientation the weighted mean of the link orientations, weights the masses
  if floating, else the lengths;
* ``"com middle"``: the centre of mass with the middle frame's axes, the frame of section 3.4.3
  in which the draft writes the floating snake's connection (3.38) (the default of
  :class:`~gm_core.systems.FloatingSnake`); its theta row is the middle frame's;
* ``"tail"``: the centre of link 1 along that link (sysplotter's ``'tail'`` base frame);
* ``"minimum perturbation"``: Hatton's frame over ``bounds``, composed on top of the middle frame
  (or, through :meth:`LinkChain.with_frame`, of the frame the chain was in;
  :mod:`gm_core.systems.minimum_perturbation`).

Constraint curvature in a frame other than the middle one is the middle frame's moved by gauge
covariance, ``D(-A~) = Ad_{beta^-1} D(-A)`` (:mod:`gm_core.systems.reframed`).
"""
from __future__ import annotations

import copy
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains.kernels import chain_jacobians_T, chain_poses_T, flatten_batch, with_trig
from gm_core.groups import SE2
from gm_core.systems.base import BalancedSystem, LocomotionSystem, SystemPart, ellipse_outline, rectangle_outline
from gm_core.systems.fluids import ellipse_added_mass, slender_link_drag
from gm_core.validation import FloatArray, as_array, check_int, check_option, check_positive, positive_number

__all__ = ["LinkChain", "PHYSICS", "FRAMES", "MAX_LINKS"]

PHYSICS = ("low_re", "high_re", "floating")
FRAMES = ("middle", "com", "com middle", "tail", "minimum perturbation")
#: Suffix of a chain's name when :meth:`LinkChain.with_frame` moves it to these frames.
FRAME_SUFFIX = {"com": " (centre of mass, mean orientation)", "tail": " (tail link)",
                "minimum perturbation": " (minimum perturbation)"}
#: Most links a chain may have (a typo such as 10**6 links must not hang the kernel).
MAX_LINKS = 200
_PHYSICS_NAMES = {"low_re": "low-Reynolds", "high_re": "high-Reynolds", "floating": "floating"}


def _link_diagonals(value, N):
    """``value`` as N triples (d_x, d_y, d_theta) >= 0 whose sum over the links is positive in every entry."""
    d = as_array(value, "link_diagonals", (N, 3), what=" (per link, the diagonal of its drag or mass matrix)")
    if d.ndim != 2:
        raise ValueError(f"link_diagonals must have shape ({N}, 3), one row per link; got shape {d.shape}")
    if np.any(d < 0) or np.any(d.sum(0) <= 0) or np.any(d > 1e12):
        raise ValueError("link_diagonals must be >= 0 (at most 1e12) with every column's sum over the links positive")
    return tuple(tuple(float(x) for x in row) for row in d)


def _per_link(value, name, N, what):
    v = as_array(value, name, (N,), what=what)
    if v.ndim != 1:
        raise ValueError(f"{name} must have shape ({N},), one value per link; got shape {v.shape}")
    check_positive(v, name)
    if np.any(v > 1e6):
        raise ValueError(f"{name} must be at most 1e6 (their cubes enter the drag and inertia); got {float(v.max()):g}")
    return tuple(float(x) for x in v)


class LinkChain(BalancedSystem):
    """An N-link chain with low-Re, high-Re or floating physics; see the module docstring.

    ``LinkChain((1, 1, 1), "low_re")`` is the three-link swimmer of section 3.4.4
    (:class:`gm_core.systems.LowReSwimmer`), ``LinkChain((1,) * 5, "low_re")`` a five-link one.
    Offers ``connection(r)`` (..., 3, N - 1), ``pfaffian(r)``, ``metric(r)``,
    ``link_poses(r)`` (..., N, 3) and ``link_jacobians(r)`` in its body frame, ``parts()`` and
    ``part_poses(r)`` for drawing, ``shape_metric(r)`` (the cost on shape space) and
    ``body_frames()``.
    """

    def __init__(self, lengths: ArrayLike = (1.0, 1.0, 1.0), physics: str = "low_re", *, drag_ratio: float = 2.0,
                 masses: ArrayLike | None = None, inertias: ArrayLike | None = None, aspect_ratio: float = 10.0,
                 fluid_density: float = 1.0, body_density: float = 0.0, link_diagonals: ArrayLike | None = None,
                 frame: Any = "middle", bounds: Any = None, nodes: int | None = None) -> None:
        if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or not 2 <= np.size(lengths) <= MAX_LINKS:
            raise ValueError(f"lengths must be a sequence of N positive link lengths, 2 <= N <= {MAX_LINKS}; "
                             f"got {lengths!r:.80}")
        N = np.size(lengths)
        self.lengths = _per_link(lengths, "lengths", N, " (the link lengths)")
        self.physics = check_option(physics, "physics", PHYSICS)
        self.n_links, self.n_shape = N, N - 1
        self.shape_names = tuple(f"alpha{j + 1}" for j in range(N - 1))
        self.shape_limits = ((-np.pi, np.pi),) * (N - 1)
        self.drag_ratio = positive_number(drag_ratio, "drag_ratio", maximum=1e6, what=" (lateral over longitudinal drag)")
        self.aspect_ratio = positive_number(aspect_ratio, "aspect_ratio", maximum=1e6)
        if self.aspect_ratio < 1:
            raise ValueError(f"aspect_ratio must be >= 1 (semi-major over semi-minor axis); got {aspect_ratio!r}")
        self.fluid_density = positive_number(fluid_density, "fluid_density", maximum=1e12)
        self.body_density = positive_number(body_density, "body_density", allow_zero=True, maximum=1e12)
        self.masses = self.lengths if masses is None else _per_link(masses, "masses", N, " (the link masses)")
        self.inertias = (tuple(m * l ** 2 / 12 for m, l in zip(self.masses, self.lengths)) if inertias is None
                         else _per_link(inertias, "inertias", N, " (the links' moments of inertia about their centres)"))
        self.link_diagonals = None if link_diagonals is None else _link_diagonals(link_diagonals, N)
        self._diag = np.array([np.diag(M) for M in self.link_matrices()])          # (N, 3): all diagonal
        self._L = np.array(self.lengths)
        self._base = (N - 1) // 2                 # the kernels' base: the middle link (odd N), the one before the middle joint
        self.name = f"{N}-link {_PHYSICS_NAMES[self.physics]} chain"
        self._set_frame(frame, bounds, nodes)

    def _set_frame(self, frame, bounds, nodes, base="middle"):
        """Set the body frame; a minimum-perturbation frame is fitted on top of the frame ``base``."""
        self.frame = check_option(frame, "frame", FRAMES)
        self._mp_base = base
        self._mp, self._middle = None, None
        self.shape_limits = ((-np.pi, np.pi),) * self.n_shape
        self.may_be_singular, self.singular_description = False, "never singular"
        if self.frame == "minimum perturbation":
            from gm_core.systems.minimum_perturbation import (
                MAX_DIMENSION,
                MinimumPerturbationFrame,
                too_many_dimensions,
            )

            if self.n_shape > MAX_DIMENSION:
                raise ValueError(too_many_dimensions("frame='minimum perturbation'", self.name, self.n_shape))
            self._mp = MinimumPerturbationFrame.fit(self.with_frame(base), bounds, nodes)
            self.shape_limits = self._mp.bounds
            self.may_be_singular = True
            self.singular_description = self._mp.domain_description
        elif bounds is not None or nodes is not None:
            raise ValueError("bounds and nodes are only for frame='minimum perturbation'")

    # -- construction helpers ----------------------------------------------------------------
    @classmethod
    def tapered(cls, links: int, physics: str = "low_re", *, total_length: float = 3.0, taper: float = 0.0,
                **options: Any) -> LinkChain:
        """``links`` links of total length ``total_length`` shrinking linearly from head to tail:
        link i (1-based) ~ 1 - taper (i - 1) / (N - 1), ``0 <= taper < 1`` (0: equal links)."""
        N = check_int(links, "links", minimum=2, maximum=MAX_LINKS, what=" (the number of links)")
        L = positive_number(total_length, "total_length")
        taper = positive_number(taper, "taper", allow_zero=True)
        if taper >= 1:
            raise ValueError(f"taper must be in [0, 1) (the last link keeps a positive length); got {taper!r}")
        w = 1.0 - taper * np.arange(N) / (N - 1)
        return cls(tuple(L * w / w.sum()), physics, **options)

    def _options(self):
        return dict(physics=self.physics, drag_ratio=self.drag_ratio, masses=self.masses, inertias=self.inertias,
                    aspect_ratio=self.aspect_ratio, fluid_density=self.fluid_density, body_density=self.body_density,
                    link_diagonals=self.link_diagonals)

    def with_frame(self, frame: Any, bounds: Any = None, nodes: int | None = None) -> LinkChain:
        """The same chain (same class, same physics) seen from another body frame (one of
        :data:`FRAMES`); its name gains the suffix of :data:`FRAME_SUFFIX`."""
        new = copy.copy(self)
        new._set_frame(frame, bounds, nodes, self._mp_base if self.frame == "minimum perturbation" else self.frame)
        if new.frame != self.frame:
            new.name = self.name.removesuffix(FRAME_SUFFIX.get(self.frame, "")) + FRAME_SUFFIX.get(new.frame, "")
        return new

    @override
    def body_frames(self, bounds: Any = None, *, n: int | None = None, centre_of_mass: bool = True,
                    minimum_perturbation: bool = True) -> dict[str, LocomotionSystem]:
        """{name: system}: the middle link (or joint), the centre of mass and, if asked and feasible
        (at most MAX_DIMENSION joints), minimum perturbation over ``bounds`` (default
        ``shape_limits``; ``n`` nodes per axis)."""
        from gm_core.systems.minimum_perturbation import MAX_DIMENSION

        middle = "middle link" if self.n_links % 2 else "middle joint"
        out: dict[str, LocomotionSystem] = {middle: self if self.frame == "middle" else self.with_frame("middle")}
        if centre_of_mass:
            out["centre of mass"] = self.with_frame("com")
        if minimum_perturbation and self.n_shape <= MAX_DIMENSION:
            out["minimum perturbation"] = self.with_frame("minimum perturbation", bounds, n)
        return out

    # -- physics -------------------------------------------------------------------------------
    def link_matrices(self) -> list[FloatArray]:
        """The (3, 3) link matrices in the links' centre frames: drag, or mass plus added mass
        (or ``diag(link_diagonals[i])`` when those were given)."""
        if self.link_diagonals is not None:
            return [np.diag(d) for d in self.link_diagonals]
        if self.physics == "low_re":
            return [slender_link_drag(l, self.drag_ratio) for l in self.lengths]
        if self.physics == "floating":
            return [np.diag([m, m, i]) for m, i in zip(self.masses, self.inertias)]
        out = []
        for a, b in self.semi_axes():
            m = self.body_density * np.pi * a * b
            out.append(np.diag([m, m, m * (a ** 2 + b ** 2) / 4]) + ellipse_added_mass(a, b, self.fluid_density))
        return out

    def semi_axes(self) -> list[tuple[float, float]]:
        """[(a_i, b_i)]: the semi-axes l_i / 2 and l_i / (2 aspect_ratio) of the links as ellipses (high Re)."""
        return [(l / 2, l / 2 / self.aspect_ratio) for l in self.lengths]

    def link_weights(self) -> FloatArray:
        """Normalised link weights for the centre of mass: masses if floating, else lengths."""
        w = np.array(self.masses if self.physics == "floating" else self.lengths)
        return w / w.sum()

    # -- kinematics (batch-last arrays, see gm_core.chains.kernels.chain_poses_T) ----------------------
    def _frame_pose(self, P, B, a, frame=None):
        """Pose ``(x, y, theta, cos theta, sin theta)`` (each (M,)) of the body frame (or of ``frame``)
        relative to the kernels' base link (``self._base``) and its body Jacobian ``(Bx, By, Btheta)``
        (each (n, M)), from the kernel's ``P, B`` (:func:`gm_core.chains.kernels.chain_poses_T`); ``a (n, M)``
        the joint angles."""
        frame = frame or self.frame
        if frame == "minimum perturbation":
            beta, Bb = self._frame_pose(P, B, a, self._mp_base)
            r = a.T
            b2, jac = self._mp.pose(r), self._mp.jacobian(r)
            beta = SE2.compose(np.stack(beta[:3], -1), b2)
            Bb = SE2.Ad_inv(b2) @ np.stack(Bb).transpose(2, 0, 1) + jac
            return with_trig(*beta.T), tuple(Bb.transpose(1, 2, 0))
        if frame in ("com", "com middle"):
            w = self.link_weights()[:, None]
            (px, py, th, c, s), (B0, B1, B2) = P, B
            cc, ss = c[:, None], s[:, None]
            x, y = (w * px).sum(0), (w * py).sum(0)
            dx, dy = (w[..., None] * (cc * B0 - ss * B1)).sum(0), (w[..., None] * (ss * B0 + cc * B1)).sum(0)
            if frame == "com middle":      # the middle frame's orientation and its rate
                mid, Bm = self._middle_pose(P, B, a)
                _, _, t, cb, sb = mid
                dt = Bm[2]
            else:
                t = (w * th).sum(0)
                cb, sb = np.cos(t), np.sin(t)
                dt = np.broadcast_to((w[..., None] * B2).sum(0), dx.shape)
            return (x, y, t, cb, sb), (cb * dx + sb * dy, cb * dy - sb * dx, dt)
        if frame == "tail":
            (B0, B1, B2) = B
            return tuple(p[0] for p in P), (B0[0], B1[0], np.broadcast_to(B2[0], B0[0].shape))
        return self._middle_pose(P, B, a)

    def _middle_pose(self, P, B, a):
        """Pose and body Jacobian, batch-last as in :meth:`_frame_pose`, of the middle link (odd N)
        or of the middle joint, oriented halfway between its links (even N)."""
        N = self.n_links
        m = N // 2
        (px, py, th, c, s), (B0, B1, B2) = P, B
        if N % 2:
            return tuple(p[m] for p in P), (B0[m], B1[m], np.broadcast_to(B2[m], B0[m].shape))
        j = m - 1               # the joint between links m and m + 1 (1-based)
        h = self.lengths[j] / 2
        cp, sp = np.cos(a[j] / 2), np.sin(a[j] / 2)      # the step (h, 0, a_j / 2) from link j
        beta = (px[j] + h * c[j], py[j] + h * s[j], th[j] + a[j] / 2, c[j] * cp - s[j] * sp, s[j] * cp + c[j] * sp)
        Bt = np.array(np.broadcast_to(B2[j], B0[j].shape))
        Bx = cp * B0[j] + sp * B1[j] + sp * h * Bt        # Ad_inv of the step
        By = cp * B1[j] - sp * B0[j] + cp * h * Bt
        Bt[j] += 0.5
        return beta, (Bx, By, Bt)

    def _kinematics_T(self, r):
        """(r, batch shape, Q, J) in the batch-last layout of :func:`gm_core.chains.kernels.chain_jacobians_T`.

        The kernels walk the chain out from its middle link (the base of :func:`chain_poses_T`,
        held still), so in the middle frame of an odd chain nothing is re-expressed."""
        r = self._shape(r)
        a, batch = flatten_batch(r)
        P, B = chain_poses_T(a, self._L, self._base)
        frame = (None, None) if self.frame == "middle" and self.n_links % 2 else self._frame_pose(P, B, a)
        Q, J = chain_jacobians_T(P, B, *frame)
        return r, batch, Q, J

    def link_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., N, 3) of the link centres in the body frame."""
        r, batch, Q, J = self._kinematics_T(r)
        return np.stack(Q[:3]).T.reshape(batch + (self.n_links, 3))

    def link_jacobians(self, r: ArrayLike) -> FloatArray:
        """Link Jacobians (..., N, 3, 3 + n) from (xi, r_dot) to each link's body velocity, in the body frame."""
        r, batch, Q, J = self._kinematics_T(r)
        return J.transpose(3, 2, 0, 1).reshape(batch + (self.n_links, 3, 3 + self.n_shape))

    def _middle_chain(self):
        """This chain seen from its middle link (or joint), cached."""
        if self.frame == "middle":
            return self
        if self._middle is None:
            self._middle = self.with_frame("middle")
        return self._middle

    def middle_link_jacobians(self, r: ArrayLike) -> tuple[FloatArray, ...]:
        """(J_1, ..., J_N), each (..., 3, 3 + n): the link Jacobians from (xi_middle, r_dot), with the
        middle link (or joint) as body frame whatever this chain's frame; (2.57)-(2.59) for N = 3."""
        return tuple(np.moveaxis(self._middle_chain().link_jacobians(r), -3, 0))

    def _weighted(self, J, rows, batch):
        """``sum_i (J_i^T M_i J_i)[:rows]`` (batch + (rows, 3 + n)) for the diagonal link matrices M_i,
        from the batch-last J (3, 3 + n, N, M): one contraction over the links and the rows of J."""
        X = np.einsum("rkim,rjim->mkj", J[:, :rows] * self._diag.T[:, None, :, None], J)
        return X.reshape(batch + X.shape[1:])

    @override
    def metric(self, r: ArrayLike) -> FloatArray:
        """System matrix (..., 3 + n, 3 + n): ``sum J_i^T M_i J_i`` over the links (drag or mass matrix)."""
        r, batch, Q, J = self._kinematics_T(r)
        return self._masked(r, self._weighted(J, 3 + self.n_shape, batch))

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian (..., 3, 3 + n): the top rows of :meth:`metric` (total wrench or momentum = 0)."""
        r, batch, Q, J = self._kinematics_T(r)
        return self._masked(r, self._weighted(J, 3, batch))

    @override
    def constraint_curvature(self, r: ArrayLike) -> FloatArray:
        """Constraint curvature D(-A) ((..., 3) for two joints, else (..., 3, n, n)): in the middle
        frame from the connection's derivative, in any other frame moved there by gauge covariance
        ``D(-A~) = Ad_{beta^-1} D(-A)`` with beta the frame's pose in the middle frame."""
        if self.frame == "middle":
            return super().constraint_curvature(r)
        r = self._shape(r)
        F = self._middle_chain().constraint_curvature(r)
        a, batch = flatten_batch(r)
        P, B = chain_poses_T(a, self._L, self._base)
        pose = lambda frame: np.stack(self._frame_pose(P, B, a, frame)[0][:3], -1).reshape(batch + (3,))  # noqa: E731
        Ad = SE2.Ad_inv(SE2.compose(SE2.inverse(pose("middle")), pose(self.frame)))
        F = (Ad @ F[..., None])[..., 0] if self.n_shape == 2 else np.einsum("...ij,...jkl->...ikl", Ad, F)
        return self._masked(r, F)

    def _masked(self, r, X):
        """X (..., *tail) with NaN at the shapes outside the minimum-perturbation frame's box."""
        if self._mp is None:
            return X
        inside = self._mp.contains(r)
        return np.where(inside.reshape(inside.shape + (1,) * (X.ndim - inside.ndim)), X, np.nan)

    @override
    def singularity(self, r: ArrayLike) -> FloatArray:
        """Scaled det(omega_xi) (...,): never zero (the locked block is positive definite), except
        outside a minimum-perturbation frame's box, where it is 0."""
        return self._masked(self._shape(r), super().singularity(r))

    # -- drawing -------------------------------------------------------------------------------
    @override
    def parts(self) -> list[SystemPart]:
        if self.physics == "low_re":
            return [SystemPart(f"link {i + 1}", ellipse_outline(l / 2, l / 24), "link") for i, l in enumerate(self.lengths)]
        if self.physics == "high_re":
            return [SystemPart(f"link {i + 1}", ellipse_outline(a, b), "link") for i, (a, b) in enumerate(self.semi_axes())]
        w = 0.08 * sum(self.lengths) / 3
        return [SystemPart(f"link {i + 1}", rectangle_outline(l, w), "link") for i, l in enumerate(self.lengths)]

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        return self.link_poses(r)

    @override
    def __repr__(self) -> str:
        extra = {"low_re": f"drag_ratio={self.drag_ratio:g}", "high_re": f"aspect_ratio={self.aspect_ratio:g}",
                 "floating": f"masses={self.masses}"}[self.physics]
        return f"LinkChain(lengths={self.lengths}, physics={self.physics!r}, {extra}, frame={self.frame!r})"

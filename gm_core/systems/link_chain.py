"""Chains of any number of links swimming or floating, after section 3.4 (numpy only; beyond the draft for N != 3).

N >= 2 links of lengths l_1 .. l_N joined end to end; the shape is r = (alpha_1, ..., alpha_{N-1})
with alpha_j the rotation of link j + 1 relative to link j (chapter 2's convention); each link
frame sits at the link's centre with x along the link towards link N. The poses and Jacobians
are :func:`gm_core.chains.link_chain_poses` and :func:`gm_core.chains.link_chain_jacobians`
(written once, for every N). Physics per link, as in section 3.4 for three links:

* ``"low_re"``: resistive force theory, each link's drag matrix diag(l, k l, k l^3 / 12)
  (:func:`gm_core.fluids.slender_link_drag`, k = ``drag_ratio``); zero net drag wrench;
* ``"high_re"``: ellipses (semi-axes l/2 and l/(2 ``aspect_ratio``)) carrying their added mass
  (:func:`gm_core.fluids.ellipse_added_mass`) plus their own mass (``body_density``); zero momentum;
* ``"floating"``: links of mass m_i (``masses``, default the lengths) and inertia m_i l_i^2 / 12
  (or ``inertias``) in free space; zero momentum.

The system matrix ``sum J_i^T M_i J_i`` (:meth:`LinkChain.metric`, (3.39), (3.47)) has the total
wrench or momentum as its top rows: the Pfaffian. No shape is singular (the locked block is
positive definite). Body frames (``frame``): ``"middle"`` (the middle link for odd N, the middle
joint, oriented halfway between its two links, for even N), ``"com"`` (the centre of mass --
lengths as weights unless floating -- with the mean link orientation), ``"minimum
perturbation"`` (Hatton's frame over ``bounds``, composed on top of the middle frame, see
:mod:`gm_core.systems.minimum_perturbation`).
"""
from __future__ import annotations

import numpy as np

from .._validate import as_array, check_int, check_option, check_positive, positive_number
from ..chains import link_chain_jacobians, link_chain_poses
from ..connection import connection_from_pfaffian, shape_space_metric
from ..fluids import ellipse_added_mass, slender_link_drag
from ..groups import SE2
from .base import LocomotionSystem, Part, ellipse_outline, rectangle_outline
from .reframed import body_jacobian

__all__ = ["LinkChain", "PHYSICS", "FRAMES", "MAX_LINKS"]

PHYSICS = ("low_re", "high_re", "floating")
FRAMES = ("middle", "com", "minimum perturbation")
#: Most links a chain may have (a typo such as 10**6 links must not hang the kernel).
MAX_LINKS = 200
_PHYSICS_NAMES = {"low_re": "low-Reynolds", "high_re": "high-Reynolds", "floating": "floating"}


def _per_link(value, name, N, what):
    v = as_array(value, name, (N,), what=what)
    if v.ndim != 1:
        raise ValueError(f"{name} must have shape ({N},), one value per link; got shape {v.shape}")
    check_positive(v, name)
    if np.any(v > 1e6):
        raise ValueError(f"{name} must be at most 1e6 (their cubes enter the drag and inertia); got {float(v.max()):g}")
    return tuple(float(x) for x in v)


class LinkChain(LocomotionSystem):
    """An N-link chain with low-Re, high-Re or floating physics; see the module docstring.

    ``LinkChain((1, 1, 1), "low_re")`` is the three-link swimmer of section 3.4.4
    (:class:`gm_core.systems.LowReSwimmer`), ``LinkChain((1,) * 5, "low_re")`` a five-link one.
    Offers ``connection(r)`` (..., 3, N - 1), ``pfaffian(r)``, ``metric(r)``,
    ``link_poses(r)`` (..., N, 3) and ``link_jacobians(r)`` in its body frame, ``parts()`` and
    ``part_poses(r)`` for drawing, ``shape_metric(r)`` (the cost on shape space) and
    ``body_frames()``.
    """

    def __init__(self, lengths=(1.0, 1.0, 1.0), physics="low_re", *, drag_ratio=2.0, masses=None, inertias=None,
                 aspect_ratio=10.0, fluid_density=1.0, body_density=0.0, frame="middle", bounds=None, nodes=None):
        if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or not 2 <= np.size(lengths) <= MAX_LINKS:
            raise ValueError(f"lengths must be a sequence of N positive link lengths, 2 <= N <= {MAX_LINKS}; "
                             f"got {lengths!r:.80}")
        N = len(lengths)
        self.lengths = _per_link(lengths, "lengths", N, " (the link lengths)")
        self.physics = check_option(physics, "physics", PHYSICS)
        self.frame = check_option(frame, "frame", FRAMES)
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
        self._diag = np.array([np.diag(M) for M in self.link_matrices()])          # (N, 3): all diagonal
        self.name = f"{N}-link {_PHYSICS_NAMES[self.physics]} chain"
        self._mp = None
        if self.frame == "minimum perturbation":
            from .minimum_perturbation import MinimumPerturbationFrame

            middle = self.with_frame("middle")
            self._mp = MinimumPerturbationFrame.fit(middle, bounds, nodes)
            self.shape_limits = self._mp.bounds
            self.may_be_singular = True
            self.singular_description = self._mp.domain_description
        elif bounds is not None or nodes is not None:
            raise ValueError("bounds and nodes are only for frame='minimum perturbation'")

    # -- construction helpers ----------------------------------------------------------------
    @classmethod
    def tapered(cls, links, physics="low_re", *, total_length=3.0, taper=0.0, **options):
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
                    aspect_ratio=self.aspect_ratio, fluid_density=self.fluid_density, body_density=self.body_density)

    def with_frame(self, frame, bounds=None, nodes=None):
        """The same chain seen from another body frame (one of :data:`FRAMES`)."""
        return LinkChain(self.lengths, frame=frame, bounds=bounds, nodes=nodes, **self._options())

    def body_frames(self, bounds=None, *, n=None, centre_of_mass=True, minimum_perturbation=True):
        """{name: system}: the middle link (or joint), the centre of mass and, if asked and feasible
        (at most MAX_DIMENSION joints), minimum perturbation over ``bounds`` (default
        ``shape_limits``; ``n`` nodes per axis)."""
        from .minimum_perturbation import MAX_DIMENSION

        middle = "middle link" if self.n_links % 2 else "middle joint"
        out = {middle: self.with_frame("middle")}
        if centre_of_mass:
            out["centre of mass"] = self.with_frame("com")
        if minimum_perturbation and self.n_shape <= MAX_DIMENSION:
            out["minimum perturbation"] = self.with_frame("minimum perturbation", bounds, n)
        return out

    # -- physics -------------------------------------------------------------------------------
    def link_matrices(self):
        """The (3, 3) link matrices in the links' centre frames: drag, or mass plus added mass."""
        if self.physics == "low_re":
            return [slender_link_drag(l, self.drag_ratio) for l in self.lengths]
        if self.physics == "floating":
            return [np.diag([m, m, i]) for m, i in zip(self.masses, self.inertias)]
        out = []
        for l in self.lengths:
            a, b = l / 2, l / 2 / self.aspect_ratio
            m = self.body_density * np.pi * a * b
            out.append(np.diag([m, m, m * (a ** 2 + b ** 2) / 4]) + ellipse_added_mass(a, b, self.fluid_density))
        return out

    def link_weights(self):
        """Normalised link weights for the centre of mass: masses if floating, else lengths."""
        w = np.array(self.masses if self.physics == "floating" else self.lengths)
        return w / w.sum()

    # -- kinematics ----------------------------------------------------------------------------
    def _frame_pose(self, P, B, alpha):
        """Pose (..., 3) of the body frame relative to link 1 and its body Jacobian (..., 3, n)."""
        N = self.n_links
        if self.frame == "com":
            w = self.link_weights()
            th = P[..., 2]
            c, s = np.cos(th)[..., None], np.sin(th)[..., None]
            dp = np.stack([c * B[..., 0, :] - s * B[..., 1, :], s * B[..., 0, :] + c * B[..., 1, :], B[..., 2, :]], -2)
            beta = np.einsum("i,...ij->...j", w, P)
            return beta, body_jacobian(beta, np.einsum("i,...ijk->...jk", w, dp))
        m = N // 2
        if N % 2:
            beta, Bb = P[..., m, :], B[..., m, :, :]
        else:   # the middle joint, between links m and m + 1 (1-based), halfway in orientation
            j = m - 1
            step = np.zeros(P.shape[:-2] + (3,))
            step[..., 0] = self.lengths[j] / 2
            step[..., 2] = alpha[..., j] / 2
            beta = SE2.compose(P[..., j, :], step)
            Bb = SE2.Ad_inv(step) @ B[..., j, :, :]
            Bb[..., 2, j] += 0.5
        if self._mp is not None:
            b2 = self._mp.pose(alpha)
            Bb = SE2.Ad_inv(b2) @ Bb + self._mp.jacobian(alpha)
            beta = SE2.compose(beta, b2)
        return beta, Bb

    def _kinematics(self, r):
        r = self._shape(r)
        P, B = link_chain_poses(r, self.lengths)
        beta, Bb = self._frame_pose(P, B, r)
        Q, J = link_chain_jacobians(P, B, beta, Bb)
        return r, Q, J

    def link_poses(self, r):
        """Poses (..., N, 3) of the link centres in the body frame."""
        return self._kinematics(r)[1]

    def link_jacobians(self, r):
        """Link Jacobians (..., N, 3, 3 + n) from (xi, r_dot) to each link's body velocity, in the body frame."""
        return self._kinematics(r)[2]

    def metric(self, r):
        """System matrix (..., 3 + n, 3 + n): ``sum J_i^T M_i J_i`` over the links (drag or mass matrix)."""
        r, Q, J = self._kinematics(r)
        return self._masked(r, self._weighted(J, J))

    def pfaffian(self, r):
        """Pfaffian (..., 3, 3 + n): the top rows of :meth:`metric` (total wrench or momentum = 0)."""
        r, Q, J = self._kinematics(r)
        return self._masked(r, self._weighted(J[..., :3], J))

    def connection(self, r):
        """Local connection (..., 3, n): xi = -A r_dot (3.10) from the Pfaffian, (3.40)."""
        return connection_from_pfaffian(self.pfaffian(r))

    def shape_metric(self, r):
        """Cost metric on shape space M(r) = [-A; I]^T D [-A; I] (..., n, n) (power or twice kinetic energy)."""
        D = self.metric(r)
        return shape_space_metric(D, connection_from_pfaffian(D[..., :3, :]))

    def _weighted(self, left, J):
        """sum_i left_i^T M_i J_i for diagonal link matrices M_i, as one batched product (..., k, 3 + n)."""
        N = self.n_links
        Jw = (J * self._diag[:, :, None]).reshape(J.shape[:-3] + (3 * N, J.shape[-1]))
        return np.swapaxes(left.reshape(left.shape[:-3] + (3 * N, left.shape[-1])), -1, -2) @ Jw

    def _masked(self, r, X):
        if self._mp is None:
            return X
        return np.where(self._mp.contains(r)[..., None, None], X, np.nan)

    def singularity(self, r):
        r = self._shape(r)
        return np.where(self._mp.contains(r), 1.0, 0.0) if self._mp is not None else np.ones(r.shape[:-1])

    # -- drawing -------------------------------------------------------------------------------
    def parts(self):
        if self.physics == "low_re":
            return [Part(f"link {i + 1}", ellipse_outline(l / 2, l / 24), "link") for i, l in enumerate(self.lengths)]
        if self.physics == "high_re":
            return [Part(f"link {i + 1}", ellipse_outline(l / 2, l / 2 / self.aspect_ratio), "link")
                    for i, l in enumerate(self.lengths)]
        w = 0.08 * sum(self.lengths) / 3
        return [Part(f"link {i + 1}", rectangle_outline(l, w), "link") for i, l in enumerate(self.lengths)]

    def part_poses(self, r):
        return self.link_poses(r)

    def __repr__(self):
        extra = {"low_re": f"drag_ratio={self.drag_ratio:g}", "high_re": f"aspect_ratio={self.aspect_ratio:g}",
                 "floating": f"masses={self.masses}"}[self.physics]
        return f"LinkChain(lengths={self.lengths}, physics={self.physics!r}, {extra}, frame={self.frame!r})"

"""Kinematic chains in the plane: joints, links, forward kinematics and Jacobians three ways (chapter 2).

numpy only. A chain is a product of SE(2) elements (section 2.2): fixed elements that move along
a rigid link, and one-parameter joint elements ``exp(q X)`` with ``X = (0, 0, 1)`` for a
revolute joint (the constraint (2.2)-(2.3)) and ``X = (1, 0, 0)`` for a prismatic one ((2.8)-(2.9)).

Arcs (beyond the draft's chapter 2, after the author's ``kinematicchain.arc_joint``/``arc_link`` and
his example E702): every link is the arc ``exp(t v)``, t in [0, 1], of its twist ``v = (l, a, kappa l)``
(length l, lateral offset a, curvature kappa; a straight link has kappa = 0 and ends at (l, a, 0)), its
medial frame at t = 1/2. An arc joint ``exp(q (1, 0, kappa))`` slides its link a distance q along a
circle of curvature kappa (the author's arc joint, radius 1/kappa). A bend joint makes its own link a
circular arc whose curvature q is the joint variable: ``h = f exp(l (1, 0, q))``; its body velocity
per unit dq is the twist of :meth:`Joint.twist` (closed form, no cancellation at q = 0), and as
q -> 0 the link is a straight one.

Frame names follow the book's note on notation: on link ``i`` the proximal frame is ``f_i``, the
medial (centre) frame ``g_i`` and the distal frame ``h_i``. For a fixed-base arm the book calls the
proximal frame of a rotary link ``g``; here it is always ``f`` (see the "Frame naming" box of
section 2.2). For a prismatic joint the proximal frame of the sliding link sits at the joint
displacement delta from the joint, which is the book's ``g_2`` of (2.10).

For revolute chains of any length, :func:`gm_core.chains.kernels.link_chain_poses` and
:func:`gm_core.chains.kernels.link_chain_jacobians` give the link-centre poses and body Jacobians in
closed form, vectorized over many shapes (the locomotors of :class:`gm_core.systems.LinkChain`;
tests check them against :class:`MobileChain`).

Jacobians are computed three independent ways (section 2.5), which agree to rounding:

``"direct"``  exact product-rule differentiation of the homogeneous-matrix product, (2.16)-(2.20);
``"world"``   iterative assembly with absolute velocities and right lifted actions, (2.21)-(2.31);
``"body"``    iterative assembly with body velocities and adjoints, (2.32)-(2.37).

Shapes: configurations ``alpha: (..., n_joints)``; poses ``(..., 3)`` = (x, y, theta); Jacobians
``(..., 3, m)`` with ``m = n_joints`` for a fixed-base chain and ``m = 3 + n_joints`` for a mobile
one (columns: body velocity xi of the base link, then the joint speeds).

The book's worked examples built on these are in :mod:`gm_core.chains.arms` (fixed-base arms),
:mod:`gm_core.chains.three_link` (the three-link system and generalized body frames) and
:mod:`gm_core.chains.holonomic` (pinned bodies, the accessible manifold).
"""
from __future__ import annotations

import math
from collections.abc import Sized
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains.jacobians import body_to_world_jacobian, relative_pose, world_to_body_jacobian
from gm_core.groups import SE2, matvec
from gm_core.validation import FloatArray, as_array, check_int, check_lengths, positive_number

__all__ = [
    "transported_columns",
    "Joint", "Link", "Chain", "MobileChain", "METHODS",
]

METHODS = ("direct", "world", "body")

_KINDS = {"revolute": "revolute", "r": "revolute", "rotary": "revolute", "pin": "revolute",
          "prismatic": "prismatic", "p": "prismatic", "slider": "prismatic",
          "arc": "arc", "a": "arc", "bend": "bend", "b": "bend"}
_LETTERS = {"revolute": "R", "prismatic": "P", "arc": "A", "bend": "B"}


def _bend_coefficients(theta: FloatArray) -> tuple[FloatArray, FloatArray]:
    """(theta - sin theta) / theta^2 and (1 - cos theta) / theta^2, free of cancellation at every theta.

    The second is (sin h / h)^2 / 2 with h = theta/2; the first is its Taylor series for |theta| < 1
    (ten terms, error below 1e-17 relative) and the plain quotient beyond.
    """
    h = 0.5 * theta
    sinc = np.divide(np.sin(h), h, out=np.ones_like(h), where=h != 0)
    b = 0.5 * sinc * sinc
    t2 = theta * theta
    series = np.zeros_like(theta)
    for k in range(10, 0, -1):  # sum_k (-1)^(k+1) theta^(2k-1) / (2k+1)!, by Horner in theta^2
        series = t2 * series + (-1.0) ** (k + 1) / math.factorial(2 * k + 1)
    series = series * theta
    big = np.abs(theta) >= 1.0
    safe = np.where(big, theta, 1.0)
    a = np.where(big, (safe - np.sin(safe)) / (safe * safe), series)
    return a, b


# --------------------------------------------------------------------------------------- parts
class Joint:
    """A one-degree-of-freedom joint: "revolute" ("R"), "prismatic" ("P"), "arc" ("A") or "bend" ("B").

    The first three are one-parameter subgroups ``exp(q X)``: a rotation by q, ``X = (0, 0, 1)``,
    book (2.3); a slide by q along the proximal link's x axis, ``X = (1, 0, 0)``, book (2.9); a
    slide by arc length q along a circle of curvature kappa, ``X = (1, 0, kappa)``
    (``Joint("arc", curvature=kappa)``, default 1: the author's E702 arc joint of radius 1). Their
    body (and spatial) velocity is ``X q_dot``, the v_i of (2.34). A bend joint is a link of length
    l bent to the curvature q, ``exp(l (1, 0, q))``; it is no subgroup, and its body velocity per unit
    dq, :meth:`twist`, depends on q.
    """

    kind: str
    curvature: float

    def __init__(self, kind: Any = "revolute", curvature: float | None = None) -> None:
        if isinstance(kind, Joint):
            curvature = kind.curvature if curvature is None else curvature
            kind = kind.kind
        if not isinstance(kind, str) or kind.strip().lower() not in _KINDS:
            raise ValueError(f"joints: unknown joint type {kind!r}; use 'revolute' ('R'), 'prismatic' ('P'), "
                             "'arc' ('A') or 'bend' ('B')")
        self.kind = _KINDS[kind.strip().lower()]
        if curvature is not None and self.kind != "arc":
            raise ValueError(f"curvature: only an arc joint has a fixed curvature; got {curvature!r} for a {self.kind} joint")
        kappa = 1.0 if curvature is None else curvature
        if isinstance(kappa, bool) or not isinstance(kappa, (int, float, np.integer, np.floating)) or not np.isfinite(kappa):
            raise ValueError(f"curvature must be a finite number (1 / radius of the arc joint); got {curvature!r}")
        self.curvature = float(kappa) if self.kind == "arc" else 0.0

    @property
    def subgroup(self) -> bool:
        """True when the joint's elements form the one-parameter subgroup exp(q X) (all kinds but "bend")."""
        return self.kind != "bend"

    @property
    def axis(self) -> FloatArray:
        """The generator X of the subgroup exp(q X), ``(3,)``; a bend joint has none (ValueError)."""
        if self.kind == "revolute":
            return np.array([0.0, 0.0, 1.0])
        if self.kind == "prismatic":
            return np.array([1.0, 0.0, 0.0])
        if self.kind == "arc":
            return np.array([1.0, 0.0, self.curvature])
        raise ValueError("joint: a bend joint is not a one-parameter subgroup and has no axis; use twist(q, length=l)")

    def _length(self, length):
        if self.kind != "bend":
            return None
        return positive_number(length, "length", what=" (the arc length of the bent link)")

    def element(self, q: ArrayLike, sign: float = 1.0, length: float | None = None) -> FloatArray:
        """The relative SE(2) element ``(..., 3)``: exp(sign q X), book (2.3), (2.9); for a bend joint
        exp(l (1, 0, q)) of link length ``length`` = l, inverted when sign < 0."""
        q = np.asarray(q, dtype=float)
        ell = self._length(length)
        if ell is None:  # exactly (0, 0, sign q) and (sign q, 0, 0) for the revolute and prismatic joints
            return SE2.exp((sign * q)[..., None] * self.axis)
        E = SE2.exp(ell * np.stack([np.ones_like(q), np.zeros_like(q), q], axis=-1))
        return E if sign > 0 else SE2.inverse(E)

    def twist(self, q: ArrayLike, sign: float = 1.0, length: float | None = None) -> FloatArray:
        """Body velocity ``E^-1 dE/dq`` ``(..., 3)`` of the element E = :meth:`element` per unit dq.

        sign X for a subgroup joint, (2.34). For a bend joint, with theta = l q:
        ``l (l (theta - sin theta) / theta^2, l (1 - cos theta) / theta^2, 1)``, which is
        ``(0, l^2 / 2, l)`` at q = 0 (bending a straight link swings its tip sideways), and
        ``-Ad_E`` of that when the joint is traversed backwards (sign < 0).
        """
        q = np.asarray(q, dtype=float)
        ell = self._length(length)
        if ell is None:
            return np.broadcast_to(sign * self.axis, q.shape + (3,)).copy()
        a, b = _bend_coefficients(ell * q)
        X = ell * np.stack([ell * a, ell * b, np.ones_like(q)], axis=-1)
        if sign > 0:
            return X
        return -matvec(SE2.Ad(self.element(q, 1.0, ell)), X)

    @property
    def letter(self) -> str:
        return _LETTERS[self.kind]

    @override
    def __repr__(self) -> str:
        if self.kind == "arc":
            return f"Joint('arc', curvature={self.curvature!r})"
        return f"Joint({self.kind!r})"

    @override
    def __eq__(self, other: object) -> bool:
        return isinstance(other, Joint) and (other.kind, other.curvature) == (self.kind, self.curvature)

    @override
    def __hash__(self) -> int:
        return hash((self.kind, self.curvature))


@dataclass(frozen=True)
class Link:
    """A rigid link of positive ``length``: the arc exp(t v), t in [0, 1], of ``v = (length, offset, curvature length)``.

    A straight link (curvature 0) has its distal frame at (length, offset, 0) from the proximal one.
    """

    length: float
    offset: float = 0.0
    curvature: float = 0.0

    @property
    def twist(self) -> FloatArray:
        """The twist v with distal frame f exp(v) and medial frame f exp(v / 2), ``(3,)``."""
        return np.array([self.length, self.offset, self.curvature * self.length])


def _joints(joints, name="joints"):
    if isinstance(joints, str):
        letters = joints.strip()
        if all(ch.upper() in "RPAB" for ch in letters) and letters:
            joints = list(letters)
        else:
            joints = [joints]
    try:
        joints = list(joints)
    except TypeError:
        raise ValueError(f"{name} must be a sequence of joint types such as ['R', 'P'] or 'RPAB'; got {joints!r}") from None
    return [Joint(j) for j in joints]


def _config(alpha, n, name="alpha"):
    return as_array(alpha, name, (n,), what=f" (one value per joint: this chain has {n} joints)")


# ------------------------------------------------------------------------- the frame graph
# A chain is stored as a list of nodes; node k is ("fixed", parent, element) or
# ("joint", parent, (j, sign, joint, length)) and its pose is compose(pose[parent], factor), the
# factor of a joint node being joint.element(alpha_j, sign, length) with body velocity
# joint.twist(alpha_j, sign, length) per unit alpha_j_dot. Node 0 is the root: the fixed base for
# an arm, the base link's medial frame for a mobile system.

class _FrameGraph:
    def __init__(self, n_joints, mobile):
        self.n_joints = n_joints
        self.mobile = mobile
        self.nodes = [("root", -1, None)]

    def add_fixed(self, parent, element):
        self.nodes.append(("fixed", parent, np.asarray(element, dtype=float)))
        return len(self.nodes) - 1

    def add_joint(self, parent, j, joint, sign=1.0, length=None):
        self.nodes.append(("joint", parent, (j, float(sign), joint, length)))
        return len(self.nodes) - 1

    @property
    def n_cols(self):
        return self.n_joints + (3 if self.mobile else 0)

    def _factor(self, node, alpha):
        kind, _, data = node
        if kind == "fixed":
            return np.broadcast_to(data, alpha.shape[:-1] + (3,))
        j, sign, joint, length = data
        return joint.element(alpha[..., j], sign, length)

    def _twist(self, node, alpha):
        j, sign, joint, length = node[2]
        return joint.twist(alpha[..., j], sign, length)

    def poses(self, alpha, root):
        out = [np.broadcast_to(root, alpha.shape[:-1] + (3,)).astype(float)]
        for node in self.nodes[1:]:
            out.append(SE2.compose(out[node[1]], self._factor(node, alpha)))
        return out

    # -- method 1: exact differentiation of the product of homogeneous matrices, (2.16)-(2.20)
    def jac_direct(self, alpha, root):
        batch = alpha.shape[:-1]
        m, off = self.n_cols, (3 if self.mobile else 0)
        G = [SE2.matrix(np.broadcast_to(root, batch + (3,)))]
        dG0 = np.zeros(batch + (m, 3, 3))
        if self.mobile:  # the base moves with body velocity xi: dG = G xi^, book (1.54)
            for k in range(3):
                dG0[..., k, :, :] = G[0] @ SE2.hat(np.eye(3)[k])
        dG = [dG0]
        for node in self.nodes[1:]:
            kind, parent, data = node
            F = SE2.matrix(self._factor(node, alpha))
            Gp, dGp = G[parent], dG[parent]
            d = dGp @ F[..., None, :, :]
            if kind == "joint":
                j = data[0]
                dF = F @ SE2.hat(self._twist(node, alpha))  # dF/dq = F X^, X the body twist; exp(s q X): s X
                d[..., off + j, :, :] += Gp @ dF
            G.append(Gp @ F)
            dG.append(d)
        jac = []
        for Gk, dGk in zip(G, dG):
            c, s = Gk[..., 0, 0], Gk[..., 1, 0]
            xd = dGk[..., :, 0, 2]
            yd = dGk[..., :, 1, 2]
            td = c[..., None] * dGk[..., :, 1, 0] - s[..., None] * dGk[..., :, 0, 0]
            jac.append(np.stack([xd, yd, td], axis=-2))
        return jac  # world-velocity Jacobians (..., 3, m)

    # -- method 2: absolute velocities carried by right lifted actions, (2.21)-(2.31)
    def jac_world(self, alpha, root):
        batch = alpha.shape[:-1]
        m, off = self.n_cols, (3 if self.mobile else 0)
        P = self.poses(alpha, root)
        J0 = np.zeros(batch + (3, m))
        if self.mobile:  # g_dot = T_e L_g xi, book (1.28)
            J0[..., :, :3] = SE2.left_lifted_action(P[0], SE2.identity())
        jac = [J0]
        for k, node in enumerate(self.nodes[1:], start=1):
            kind, parent, data = node
            Pp, Pk = P[parent], P[k]
            # equal spatial velocities on a rigid body: g_dot_k = (T_e R_{g_k})(T_{g_p} R_{g_p^-1}) g_dot_p, (2.24)
            M = SE2.right_lifted_action(Pk, SE2.identity()) @ SE2.right_lifted_action(SE2.inverse(Pp), Pp)
            Jk = M @ jac[parent]
            if kind == "joint":
                j = data[0]
                F = self._factor(node, alpha)
                # relative motion at the joint, moved into the world by T_F L_{g_p}: (2.22), (2.26)
                F_dot = matvec(SE2.left_lifted_action(F, SE2.identity()), self._twist(node, alpha))
                Jk[..., :, off + j] += matvec(SE2.left_lifted_action(Pp, F), F_dot)
            jac.append(Jk)
        return jac

    # -- method 3: body velocities and adjoints, (2.36)-(2.37)
    def jac_body(self, alpha, root):
        batch = alpha.shape[:-1]
        m, off = self.n_cols, (3 if self.mobile else 0)
        J0 = np.zeros(batch + (3, m))
        if self.mobile:
            J0[..., :, :3] = np.eye(3)
        jac = [J0]
        for node in self.nodes[1:]:
            kind, parent, data = node
            F = self._factor(node, alpha)
            Jk = SE2.Ad_inv(F) @ jac[parent]  # xi_child = Ad^-1_{child,parent} xi, (2.37)
            if kind == "joint":  # plus the joint's own body twist, v_i of (2.34) (Ad^-1_F X = X on exp(q X))
                Jk[..., :, off + data[0]] += self._twist(node, alpha)
            jac.append(Jk)
        return jac  # body-velocity Jacobians


class _ChainBase:
    """Shared machinery: frame names, forward kinematics, Jacobians by the three methods."""

    @property
    def n_links(self):
        return len(self.lengths)

    def _root(self, g):
        raise NotImplementedError

    @property
    def links(self):
        """The links as :class:`Link` (length, lateral offset of the distal frame, fixed curvature)."""
        offsets = getattr(self, "offsets", np.zeros(self.n_links))
        curvatures = getattr(self, "curvatures", np.zeros(self.n_links))
        return [Link(float(L), float(a), float(k)) for L, a, k in zip(self.lengths, offsets, curvatures)]

    def _stack(self, values, jac):
        axis = -3 if jac else -2
        return {name: np.stack([values[self._index[(name, i)]] for i in range(self.n_links)], axis=axis)
                for name in ("f", "g", "h")}

    def _prepare(self, alpha, g):
        alpha = _config(alpha, self.n_joints)
        root = self._root(g)
        batch = np.broadcast_shapes(alpha.shape[:-1], root.shape[:-1])
        return np.broadcast_to(alpha, batch + alpha.shape[-1:]), np.broadcast_to(root, batch + (3,))

    def frames(self, alpha, g=None):
        """Poses of every link's proximal f, medial g and distal h frames: dict of ``(..., n_links, 3)``; book (2.4)-(2.13).

        alpha: ``(..., n_joints)``; g: pose ``(..., 3)`` of the base link's centre (mobile chains only).
        """
        alpha, root = self._prepare(alpha, g)
        return self._stack(self._graph.poses(alpha, root), jac=False)

    def jacobians(self, alpha, g=None, method="body", velocity="world"):
        """Jacobians of every frame: dict f/g/h of ``(..., n_links, 3, m)``; book (2.16)-(2.37).

        ``method`` is one of ``METHODS`` ("direct", "world", "body"); ``velocity`` is "world"
        (g_dot, as in (2.17)-(2.30)) or "body" (xi = T_g L_{g^-1} g_dot, as in (2.40)-(2.59)).
        """
        if method not in METHODS:
            raise ValueError(f"method must be one of {METHODS}; got {method!r}")
        if velocity not in ("world", "body"):
            raise ValueError(f"velocity must be 'world' or 'body'; got {velocity!r}")
        alpha, root = self._prepare(alpha, g)
        jac = getattr(self._graph, f"jac_{method}")(alpha, root)
        poses = self._graph.poses(alpha, root)
        if method == "body" and velocity == "world":
            jac = [body_to_world_jacobian(p, J) for p, J in zip(poses, jac)]
        elif method != "body" and velocity == "body":
            jac = [world_to_body_jacobian(p, J) for p, J in zip(poses, jac)]
        return self._stack(jac, jac=True)


class Chain(_ChainBase):
    """A fixed-base serial chain: joint i joins the distal frame of link i-1 (the base for i = 1) to link i.

    ``Chain(joints, lengths, offsets=None, base=None, curvatures=None)``: ``joints`` a sequence of
    "R"/"P"/"A"/"B" or :class:`Joint` (or the string "RRP"), ``lengths`` positive link lengths,
    ``offsets`` optional lateral offsets of each link's distal frame (fig. 2.10), ``curvatures``
    optional fixed curvatures of the links (arcs), ``base`` the pose ``(3,)`` of the fixed pivot
    (default e). Link i with twist ``v_i = (l_i, a_i, kappa_i l_i)``: ``f_i = h_{i-1} exp(alpha_i X_i)``,
    ``g_i = f_i exp(v_i / 2)``, ``h_i = f_i exp(v_i)`` (for a straight link ``(l_i/2, a_i/2, 0)`` and
    ``(l_i, a_i, 0)``). A bend joint's link is its own arc: ``f_i = h_{i-1}``,
    ``g_i = f_i exp(l_i/2 (1, 0, alpha_i))``, ``h_i = f_i exp(l_i (1, 0, alpha_i))`` (no offset or fixed curvature).
    """

    def __init__(self, joints: Any, lengths: ArrayLike, offsets: ArrayLike | None = None,
                 base: ArrayLike | None = None, curvatures: ArrayLike | None = None) -> None:
        self.joints = _joints(joints)
        n = len(self.joints)
        if n == 0:
            raise ValueError("joints must name at least one joint")
        self.n_joints = n
        self.lengths = check_lengths(lengths, n)
        if offsets is None:
            offsets = np.zeros(n)
        self.offsets = as_array(offsets, "offsets", (n,), what=" (one lateral offset per link)")
        if curvatures is None:
            curvatures = np.zeros(n)
        self.curvatures = as_array(curvatures, "curvatures", (n,), what=" (one fixed curvature per link)")
        self.base = SE2.identity() if base is None else as_array(base, "base", (3,)).copy()
        gr = _FrameGraph(n, mobile=False)
        self._index = {}
        parent = 0
        for i, (jt, link) in enumerate(zip(self.joints, self.links)):
            if jt.kind == "bend":
                if link.offset or link.curvature:
                    raise ValueError(f"offsets, curvatures: link {i} bends at its joint, so its offset and fixed "
                                     f"curvature must be 0; got {link.offset!r}, {link.curvature!r}")
                f = gr.add_fixed(parent, SE2.identity())
                self._index[("f", i)] = f
                self._index[("g", i)] = gr.add_joint(f, i, jt, length=link.length / 2)
                self._index[("h", i)] = parent = gr.add_joint(f, i, jt, length=link.length)
                continue
            v = link.twist
            f = gr.add_joint(parent, i, jt)
            self._index[("f", i)] = f
            self._index[("g", i)] = gr.add_fixed(f, SE2.exp(v / 2))
            self._index[("h", i)] = parent = gr.add_fixed(f, SE2.exp(v))
        self._graph = gr

    def backbone(self, alpha: ArrayLike, n: int = 16) -> FloatArray:
        """Poses ``(..., n_links, n, 3)`` at n evenly spaced points t in [0, 1] along every link, from f_i to h_i.

        A link is the arc ``f_i exp(t v_i)`` (``f_i exp(t l_i (1, 0, alpha_i))`` for a bend joint): the
        author's ``fractional_position``; t = 1/2 gives g_i and t = 1 gives h_i.
        """
        n = check_int(n, "n", minimum=2, what=" (points per link)")
        alpha = _config(alpha, self.n_joints)
        f = self.frames(alpha)["f"]
        t = np.linspace(0.0, 1.0, n)
        out = []
        for i, (jt, link) in enumerate(zip(self.joints, self.links)):
            if jt.kind == "bend":
                v = link.length * np.stack(np.broadcast_arrays(1.0, 0.0, alpha[..., i]), axis=-1)
            else:
                v = np.broadcast_to(link.twist, alpha.shape[:-1] + (3,))
            pieces = SE2.exp(t[:, None] * v[..., None, :])
            out.append(SE2.compose(f[..., i, None, :], pieces))
        return np.stack(out, axis=-3)

    @override
    def _root(self, g):
        if g is not None:
            raise ValueError("g: a fixed-base chain has no free base pose; set base= in the constructor")
        return self.base

    def end_effector(self, alpha: ArrayLike) -> FloatArray:
        """Pose ``(..., 3)`` of the distal frame of the last link; book (2.7), (2.11)."""
        return self.frames(alpha)["h"][..., -1, :]

    @override
    def __repr__(self) -> str:
        letters = "".join(j.letter for j in self.joints)
        return f"Chain({letters!r}, lengths={self.lengths.tolist()})"


class MobileChain(_ChainBase):
    """A free-floating serial chain with a chosen base link whose medial frame is the body frame (section 2.3).

    ``MobileChain(lengths, joints=None, base_link=None)``: ``n`` links joined by ``n - 1`` joints
    (all revolute by default); joint j joins link j (proximal) to link j + 1 (distal) and alpha_j is
    the motion of link j + 1 relative to link j whatever the base link (the sign convention of
    fig. 2.6). ``base_link`` defaults to the middle link. Jacobians have ``3 + n - 1`` columns:
    the body velocity xi of the base link, then the joint speeds, as in (2.46)-(2.59).
    """

    def __init__(self, lengths: ArrayLike, joints: Any = None, base_link: int | None = None) -> None:
        try:
            n_links = len(cast(Sized, lengths))
        except TypeError:
            raise ValueError(f"lengths must be a sequence of positive link lengths; got {lengths!r}") from None
        if n_links < 1:
            raise ValueError("lengths must name at least one link")
        self.lengths = check_lengths(lengths, n_links)
        self.joints = _joints(["R"] * (n_links - 1) if joints is None else joints)
        self.n_joints = n_links - 1
        if len(self.joints) != self.n_joints:
            raise ValueError(f"joints must have {self.n_joints} entries for {n_links} links; got {len(self.joints)}")
        if any(not jt.subgroup for jt in self.joints):
            raise ValueError("joints: a mobile chain joins its links by 'R', 'P' or 'A' joints; a bend joint is a "
                             "link of its own (use Chain)")
        if base_link is None:
            base_link = (n_links - 1) // 2
        if not isinstance(base_link, (int, np.integer)) or not 0 <= base_link < n_links:
            raise ValueError(f"base_link must be an integer link index in [0, {n_links}); got {base_link!r}")
        self.base_link = b = int(base_link)
        gr = _FrameGraph(self.n_joints, mobile=True)
        L = self.lengths
        idx = {("g", b): 0}
        idx[("f", b)] = gr.add_fixed(0, [-L[b] / 2, 0.0, 0.0])
        idx[("h", b)] = gr.add_fixed(0, [L[b] / 2, 0.0, 0.0])
        for i in range(b + 1, n_links):  # distal side, (2.12)
            f = gr.add_joint(idx[("h", i - 1)], i - 1, self.joints[i - 1], +1.0)
            idx[("f", i)] = f
            idx[("g", i)] = gr.add_fixed(f, [L[i] / 2, 0.0, 0.0])
            idx[("h", i)] = gr.add_fixed(f, [L[i], 0.0, 0.0])
        for i in range(b - 1, -1, -1):  # proximal side: the joint is traversed backwards, exp(-q X)
            h = gr.add_joint(idx[("f", i + 1)], i, self.joints[i], -1.0)
            idx[("h", i)] = h
            idx[("g", i)] = gr.add_fixed(h, [-L[i] / 2, 0.0, 0.0])
            idx[("f", i)] = gr.add_fixed(h, [-L[i], 0.0, 0.0])
        self._index = idx
        self._graph = gr

    @override
    def _root(self, g):
        if g is None:
            return SE2.identity()
        return as_array(g, "g", (3,), what=" (pose of the base link's medial frame)")

    def body_jacobians(self, alpha: ArrayLike, method: str = "body") -> FloatArray:
        """Body-velocity Jacobians of the link centres, ``(..., n_links, 3, 3 + n_joints)``; book (2.46)-(2.59)."""
        return self.jacobians(alpha, method=method, velocity="body")["g"]

    @override
    def __repr__(self) -> str:
        return f"MobileChain(lengths={self.lengths.tolist()}, base_link={self.base_link})"


# ------------------------------------------------------------ columns carried to the tip
def transported_columns(chain: Chain, alpha: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Each joint's unit velocity carried out along a fixed-base chain, column by column; book (2.33)-(2.37).

    Returns ``(frames, columns)``: ``frames (..., 2n, 3)`` the poses f_1, h_1, f_2, h_2, ..., f_n,
    h_n in order along the chain, and ``columns (..., n, 2n, 3)`` where ``columns[..., j, i]`` is the
    body velocity of frame i when only joint j moves, at unit rate. Frames before joint j do not
    move; from f_j outward the links move as one rigid body with f_j, whose body velocity is the
    joint's axis X_j, so frame F has ``Ad^-1_{g_{F, f_j}} X_j`` with ``g_{F, f_j} = f_j^-1 F``
    (:func:`relative_pose`). ``columns[..., j, -1]`` is column j of the end effector's body Jacobian,
    and the sum of the columns times the joint rates is its body velocity (the iterative methods
    of section 2.5 reach the same sum link by link).
    """
    if not isinstance(chain, Chain):
        raise TypeError(f"chain must be a fixed-base gm_core.chains.Chain; got {type(chain).__name__}")
    fr = chain.frames(alpha)
    n = chain.n_joints
    frames = np.stack([fr[k][..., i, :] for i in range(n) for k in ("f", "h")], axis=-2)
    batch = frames.shape[:-2]
    columns = np.zeros(batch + (n, 2 * n, 3))
    if any(not jt.subgroup for jt in chain.joints):
        raise ValueError("chain: transported_columns needs subgroup joints ('R', 'P', 'A'); a bend joint moves h_j, not f_j")
    for j, joint in enumerate(chain.joints):
        outward = frames[..., 2 * j:, :]
        rel = relative_pose(outward, frames[..., 2 * j, None, :])
        columns[..., j, 2 * j:, :] = matvec(SE2.Ad_inv(rel), joint.axis)
    return frames, columns

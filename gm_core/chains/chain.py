"""Kinematic chains in the plane: joints, links, forward kinematics and Jacobians three ways (chapter 2).

numpy only. A chain is a product of SE(2) elements (section 2.2): fixed elements that move along
a rigid link, and one-parameter joint elements ``exp(q X)`` with ``X = (0, 0, 1)`` for a
revolute joint (the constraint (2.2)-(2.3)) and ``X = (1, 0, 0)`` for a prismatic one ((2.8)-(2.9)).

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

from collections.abc import Sized
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains.jacobians import body_to_world_jacobian, relative_pose, world_to_body_jacobian
from gm_core.groups import SE2, matvec
from gm_core.validation import FloatArray, as_array, check_lengths

__all__ = [
    "transported_columns",
    "Joint", "Link", "Chain", "MobileChain", "METHODS",
]

METHODS = ("direct", "world", "body")

_KINDS = {"revolute": "revolute", "r": "revolute", "rotary": "revolute", "pin": "revolute",
          "prismatic": "prismatic", "p": "prismatic", "slider": "prismatic"}
_AXIS = {"revolute": np.array([0.0, 0.0, 1.0]), "prismatic": np.array([1.0, 0.0, 0.0])}


# --------------------------------------------------------------------------------------- parts
class Joint:
    """A one-degree-of-freedom joint: ``Joint("revolute")`` (alias "R") or ``Joint("prismatic")`` ("P").

    The joint's relative transform is the one-parameter subgroup ``exp(q X)``: a rotation by q for a
    revolute joint, book (2.3), and a slide by q along the proximal link's x axis for a prismatic
    joint, book (2.9). Its body (and spatial) velocity is ``X q_dot``, the v_i of (2.34).
    """

    kind: str
    axis: FloatArray

    def __init__(self, kind: Any = "revolute") -> None:
        if isinstance(kind, Joint):
            kind = kind.kind
        if not isinstance(kind, str) or kind.strip().lower() not in _KINDS:
            raise ValueError(f"joints: unknown joint type {kind!r}; use 'revolute' ('R') or 'prismatic' ('P')")
        self.kind = _KINDS[kind.strip().lower()]
        self.axis = _AXIS[self.kind].copy()

    def element(self, q: ArrayLike, sign: float = 1.0) -> FloatArray:
        """The relative SE(2) element exp(sign q X), shape ``(..., 3)``; book (2.3), (2.9)."""
        q = np.asarray(q, dtype=float)
        return (sign * q)[..., None] * self.axis

    @property
    def letter(self) -> str:
        return "R" if self.kind == "revolute" else "P"

    @override
    def __repr__(self) -> str:
        return f"Joint({self.kind!r})"

    @override
    def __eq__(self, other: object) -> bool:
        return isinstance(other, Joint) and other.kind == self.kind

    @override
    def __hash__(self) -> int:
        return hash(self.kind)


@dataclass(frozen=True)
class Link:
    """A rigid link of positive ``length``; its distal frame sits at (length, offset, 0) from the proximal one."""

    length: float
    offset: float = 0.0


def _joints(joints, name="joints"):
    if isinstance(joints, str):
        letters = joints.strip()
        if all(ch.upper() in "RP" for ch in letters) and letters:
            joints = list(letters)
        else:
            joints = [joints]
    try:
        joints = list(joints)
    except TypeError:
        raise ValueError(f"{name} must be a sequence of joint types such as ['R', 'P'] or 'RP'; got {joints!r}") from None
    return [Joint(j) for j in joints]


def _config(alpha, n, name="alpha"):
    return as_array(alpha, name, (n,), what=f" (one value per joint: this chain has {n} joints)")


# ------------------------------------------------------------------------- the frame graph
# A chain is stored as a list of nodes; node k is ("fixed", parent, element) or
# ("joint", parent, (j, sign, axis)) and its pose is compose(pose[parent], factor). Node 0 is the
# root: the fixed base for an arm, the base link's medial frame for a mobile system.

class _FrameGraph:
    def __init__(self, n_joints, mobile):
        self.n_joints = n_joints
        self.mobile = mobile
        self.nodes = [("root", -1, None)]

    def add_fixed(self, parent, element):
        self.nodes.append(("fixed", parent, np.asarray(element, dtype=float)))
        return len(self.nodes) - 1

    def add_joint(self, parent, j, joint, sign=1.0):
        self.nodes.append(("joint", parent, (j, float(sign), joint.axis)))
        return len(self.nodes) - 1

    @property
    def n_cols(self):
        return self.n_joints + (3 if self.mobile else 0)

    def _factor(self, node, alpha):
        kind, _, data = node
        if kind == "fixed":
            return np.broadcast_to(data, alpha.shape[:-1] + (3,))
        j, sign, axis = data
        return (sign * alpha[..., j])[..., None] * axis

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
                j, sign, axis = data
                dF = F @ SE2.hat(sign * axis)  # d/dq exp(s q X) = exp(s q X) s X^
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
                j, sign, axis = data
                F = self._factor(node, alpha)
                # relative motion at the joint, moved into the world by T_F L_{g_p}: (2.22), (2.26)
                F_dot = matvec(SE2.left_lifted_action(F, SE2.identity()), sign * axis)
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
            Jk = jac[parent].copy()
            if kind == "joint":  # xi_{g'} = xi_{h_{i-1}} + v_i, (2.34)
                j, sign, axis = data
                Jk[..., :, off + j] += sign * axis
            jac.append(SE2.Ad_inv(F) @ Jk)  # xi_child = Ad^-1_{child,parent} xi, (2.37)
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
        """The links as :class:`Link` (length, lateral offset of the distal frame)."""
        offsets = getattr(self, "offsets", np.zeros(self.n_links))
        return [Link(float(L), float(a)) for L, a in zip(self.lengths, offsets)]

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

    ``Chain(joints, lengths, offsets=None, base=None)``: ``joints`` a sequence of "R"/"P" (or the
    string "RRP"), ``lengths`` positive link lengths, ``offsets`` optional lateral offsets of each
    link's distal frame (fig. 2.10), ``base`` the pose ``(3,)`` of the fixed pivot (default e).
    Link i: ``f_i = h_{i-1} exp(alpha_i X_i)``, ``g_i = f_i (l_i/2, a_i/2, 0)``, ``h_i = f_i (l_i, a_i, 0)``.
    """

    def __init__(self, joints: Any, lengths: ArrayLike, offsets: ArrayLike | None = None,
                 base: ArrayLike | None = None) -> None:
        self.joints = _joints(joints)
        n = len(self.joints)
        if n == 0:
            raise ValueError("joints must name at least one joint")
        self.n_joints = n
        self.lengths = check_lengths(lengths, n)
        if offsets is None:
            offsets = np.zeros(n)
        self.offsets = as_array(offsets, "offsets", (n,), what=" (one lateral offset per link)")
        self.base = SE2.identity() if base is None else as_array(base, "base", (3,)).copy()
        gr = _FrameGraph(n, mobile=False)
        self._index = {}
        parent = 0
        for i, (jt, L, a) in enumerate(zip(self.joints, self.lengths, self.offsets)):
            f = gr.add_joint(parent, i, jt)
            self._index[("f", i)] = f
            self._index[("g", i)] = gr.add_fixed(f, [L / 2, a / 2, 0.0])
            self._index[("h", i)] = parent = gr.add_fixed(f, [L, a, 0.0])
        self._graph = gr

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
    for j, joint in enumerate(chain.joints):
        outward = frames[..., 2 * j:, :]
        rel = relative_pose(outward, frames[..., 2 * j, None, :])
        columns[..., j, 2 * j:, :] = matvec(SE2.Ad_inv(rel), joint.axis)
    return frames, columns

"""Kinematic chains in the plane: joints, links, forward kinematics and Jacobians (chapter 2).

numpy only. A chain is a product of SE(2) elements (section 2.2): fixed elements that move along
a rigid link, and one-parameter joint elements ``exp(q X)`` with ``X = (0, 0, 1)`` for a
revolute joint (the constraint (2.2)-(2.3)) and ``X = (1, 0, 0)`` for a prismatic one ((2.8)-(2.9)).

Frame names follow the book's note on notation: on link ``i`` the proximal frame is ``f_i``, the
medial (centre) frame ``g_i`` and the distal frame ``h_i``. For a fixed-base arm the book calls the
proximal frame of a rotary link ``g``; here it is always ``f`` (see the "Frame naming" box of
section 2.2). For a prismatic joint the proximal frame of the sliding link sits at the joint
displacement delta from the joint, which is the book's ``g_2`` of (2.10).

Jacobians are computed three independent ways (section 2.5), which agree to rounding:

``"direct"``  exact product-rule differentiation of the homogeneous-matrix product, (2.16)-(2.20);
``"world"``   iterative assembly with absolute velocities and right lifted actions, (2.21)-(2.31);
``"body"``    iterative assembly with body velocities and adjoints, (2.32)-(2.37).

Shapes: configurations ``alpha: (..., n_joints)``; poses ``(..., 3)`` = (x, y, theta); Jacobians
``(..., 3, m)`` with ``m = n_joints`` for a fixed-base chain and ``m = 3 + n_joints`` for a mobile
one (columns: body velocity xi of the base link, then the joint speeds).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._integers import check_int
from ._validate import as_array, check_positive
from .groups import SE2, matvec

__all__ = [
    "Joint", "Link", "Chain", "MobileChain", "METHODS", "world_to_body_jacobian",
    "finite_difference_jacobians", "single_link_frames", "rr_arm_frames", "rr_arm_jacobian",
    "rp_arm_frames", "rp_arm_body_jacobians", "three_link_chain", "three_link_frames",
    "three_link_poses", "three_link_jacobians", "beta_frame_jacobian", "links_from_beta_frame", "com_frame",
    "com_frame_jacobians", "circle_constraints", "sphere_plane_constraints",
    "sample_accessible_manifold", "accessible_circle",
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

    def __init__(self, kind="revolute"):
        if isinstance(kind, Joint):
            kind = kind.kind
        if not isinstance(kind, str) or kind.strip().lower() not in _KINDS:
            raise ValueError(f"joints: unknown joint type {kind!r}; use 'revolute' ('R') or 'prismatic' ('P')")
        self.kind = _KINDS[kind.strip().lower()]
        self.axis = _AXIS[self.kind].copy()

    def element(self, q, sign=1.0):
        """The relative SE(2) element exp(sign q X), shape ``(..., 3)``; book (2.3), (2.9)."""
        q = np.asarray(q, dtype=float)
        return (sign * q)[..., None] * self.axis

    @property
    def letter(self):
        return "R" if self.kind == "revolute" else "P"

    def __repr__(self):
        return f"Joint({self.kind!r})"

    def __eq__(self, other):
        return isinstance(other, Joint) and other.kind == self.kind

    def __hash__(self):
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


def _lengths(lengths, n, name="lengths"):
    arr = check_positive(lengths, name)
    if arr.ndim != 1 or arr.shape[0] != n:
        raise ValueError(f"{name} must be a sequence of {n} positive numbers; got shape {arr.shape}")
    return arr


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


def world_to_body_jacobian(g, J):
    """Body-velocity Jacobian ``T_g L_{g^-1} J`` from a world-velocity one; g: (..., 3), J: (..., 3, m); book (1.32)."""
    g = as_array(g, "g", (3,), what=" (the pose the Jacobian is taken at)")
    J = as_array(J, "J", what=" (a world-velocity Jacobian (..., 3, m))")
    if J.ndim < 2 or J.shape[-2] != 3:
        raise ValueError(f"J must have shape (..., 3, m) (a world-velocity Jacobian); got shape {J.shape}")
    try:
        np.broadcast_shapes(g.shape[:-1], J.shape[:-2])
    except ValueError:
        raise ValueError(f"g and J have incompatible batch shapes {g.shape[:-1]} and {J.shape[:-2]}") from None
    return SE2.left_lifted_action(SE2.inverse(g), g) @ J


def _body_to_world_jacobian(g, J):
    return SE2.left_lifted_action(g, SE2.identity()) @ J


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
            jac = [_body_to_world_jacobian(p, J) for p, J in zip(poses, jac)]
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

    def __init__(self, joints, lengths, offsets=None, base=None):
        self.joints = _joints(joints)
        n = len(self.joints)
        if n == 0:
            raise ValueError("joints must name at least one joint")
        self.n_joints = n
        self.lengths = _lengths(lengths, n)
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

    def _root(self, g):
        if g is not None:
            raise ValueError("g: a fixed-base chain has no free base pose; set base= in the constructor")
        return self.base

    def end_effector(self, alpha):
        """Pose ``(..., 3)`` of the distal frame of the last link; book (2.7), (2.11)."""
        return self.frames(alpha)["h"][..., -1, :]

    def __repr__(self):
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

    def __init__(self, lengths, joints=None, base_link=None):
        try:
            n_links = len(lengths)
        except TypeError:
            raise ValueError(f"lengths must be a sequence of positive link lengths; got {lengths!r}") from None
        if n_links < 1:
            raise ValueError("lengths must name at least one link")
        self.lengths = _lengths(lengths, n_links)
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

    def _root(self, g):
        if g is None:
            return SE2.identity()
        return as_array(g, "g", (3,), what=" (pose of the base link's medial frame)")

    def body_jacobians(self, alpha, method="body"):
        """Body-velocity Jacobians of the link centres, ``(..., n_links, 3, 3 + n_joints)``; book (2.46)-(2.59)."""
        return self.jacobians(alpha, method=method, velocity="body")["g"]

    def __repr__(self):
        return f"MobileChain(lengths={self.lengths.tolist()}, base_link={self.base_link})"


# ------------------------------------------------------------------------ finite differences
def finite_difference_jacobians(fk, alpha, eps=1e-6):
    """World-velocity Jacobian ``(..., k, 3, n)`` of poses ``fk(alpha): (..., k, 3)`` by central differences.

    An independent route to (2.16): angles are differenced modulo 2 pi. ``alpha: (..., n)``.
    """
    alpha = np.atleast_1d(as_array(alpha, "alpha"))
    cols = []
    for j in range(alpha.shape[-1]):
        d = np.zeros(alpha.shape)
        d[..., j] = eps
        cols.append(SE2.difference(fk(alpha + d), fk(alpha - d)) / (2 * eps))
    return np.stack(cols, axis=-1)


# ------------------------------------------------------------------------ book examples
def single_link_frames(alpha, length=1.0):
    """Proximal and distal poses (g, h), each ``(..., 3)``, of the pivoted link of fig. 2.2; book (2.3)-(2.4)."""
    alpha = as_array(alpha, "alpha")
    L = float(check_positive(length, "length"))
    g = np.stack(np.broadcast_arrays(0.0 * alpha, 0.0 * alpha, alpha), -1)
    return g, SE2.compose(g, np.array([L, 0.0, 0.0]))


def rr_arm_frames(alpha, lengths=(1.0, 1.0)):
    """Poses ``(..., 4, 3)`` of g1, h1, g2, h2 of the two-link arm of fig. 2.3; book (2.5)-(2.7)."""
    ch = Chain("RR", lengths)
    fr = ch.frames(alpha)
    return np.stack([fr["f"][..., 0, :], fr["h"][..., 0, :], fr["f"][..., 1, :], fr["h"][..., 1, :]], -2)


def rr_arm_jacobian(alpha, lengths=(1.0, 1.0)):
    """World-velocity Jacobian ``(..., 3, 2)`` of the two-link arm's end effector h2, closed form; book (2.19), (2.30)."""
    alpha = as_array(alpha, "alpha", (2,), what=" (alpha1, alpha2)")
    l1, l2 = _lengths(lengths, 2)
    a1, a12 = alpha[..., 0], alpha[..., 0] + alpha[..., 1]
    J = np.zeros(alpha.shape[:-1] + (3, 2))
    J[..., 0, 0] = -(l1 * np.sin(a1) + l2 * np.sin(a12))
    J[..., 0, 1] = -l2 * np.sin(a12)
    J[..., 1, 0] = l1 * np.cos(a1) + l2 * np.cos(a12)
    J[..., 1, 1] = l2 * np.cos(a12)
    J[..., 2, :] = 1.0
    return J


def _rp_args(alpha, delta, l1, l2, offset):
    alpha = as_array(alpha, "alpha")
    delta = as_array(delta, "delta")
    l1 = float(check_positive(l1, "l1"))
    l2 = float(check_positive(l2, "l2"))
    a = float(as_array(offset, "offset"))
    alpha, delta = np.broadcast_arrays(alpha, delta)
    return alpha, delta, l1, l2, a


def rp_arm_frames(alpha, delta, l1=1.0, l2=1.0, offset=0.0):
    """Poses of g1, h1, g2', g2, h2, dict of ``(..., 3)``, for the rotary-prismatic arm of figs. 2.4 and 2.10; book (2.10)-(2.11).

    g1 is the rotating frame at the pivot, h1 = g1 (l1, offset, 0) the end of link 1 (``offset`` is
    the lateral offset a of fig. 2.10; 0 for fig. 2.4), g2' the frame of link 2 aligned with h1,
    g2 = g2' (delta, 0, 0) and h2 = g2' (delta + l2, 0, 0).
    """
    alpha, delta, l1, l2, a = _rp_args(alpha, delta, l1, l2, offset)
    z = np.zeros_like(alpha)
    g1 = np.stack([z, z, alpha], -1)
    h1 = SE2.compose(g1, np.array([l1, a, 0.0]))
    g2 = SE2.compose(h1, np.stack([delta, z, z], -1))
    h2 = SE2.compose(h1, np.stack([delta + l2, z, z], -1))
    return {"g1": g1, "h1": h1, "g2p": h1.copy(), "g2": g2, "h2": h2}


def rp_arm_body_jacobians(alpha, delta, l1=1.0, l2=1.0, offset=0.0):
    """Body-velocity Jacobians wrt (alpha_dot, delta_dot), dict of ``(..., 3, 2)``; book (2.40)-(2.45), exercise 2.2.

    Keys g1, h1, g2p, g2, h2 as in :func:`rp_arm_frames`. With lateral offset a (fig. 2.10) the
    distal frame of link 1 also moves backwards along its own x axis at -a alpha_dot.
    """
    alpha, delta, l1, l2, a = _rp_args(alpha, delta, l1, l2, offset)

    def J(col_a, col_d):
        out = np.zeros(alpha.shape + (3, 2))
        out[..., :, 0] = np.stack(np.broadcast_arrays(*col_a), -1)
        out[..., :, 1] = col_d
        return out

    zero = np.zeros_like(alpha)
    return {
        "g1": J((zero, zero, zero + 1.0), (0.0, 0.0, 0.0)),                     # (2.40)
        "h1": J((zero - a, zero + l1, zero + 1.0), (0.0, 0.0, 0.0)),            # (2.41)
        "g2p": J((zero - a, zero + l1, zero + 1.0), (1.0, 0.0, 0.0)),           # (2.43)
        "g2": J((zero - a, l1 + delta, zero + 1.0), (1.0, 0.0, 0.0)),           # (2.44)
        "h2": J((zero - a, l1 + delta + l2, zero + 1.0), (1.0, 0.0, 0.0)),      # (2.45)
    }


def three_link_chain(lengths):
    """The three-link mobile system of fig. 2.8 with the middle link as body frame (a :class:`MobileChain`)."""
    if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or len(lengths) != 3:
        raise ValueError(f"lengths must be a length-3 sequence of positive link lengths; got {lengths!r}")
    return MobileChain(lengths, base_link=1)


def three_link_frames(alpha, lengths=(1.0, 1.0, 1.0), g=None):
    """Poses of the three links' f, g, h frames and the two joints, with link 2's centre at g; book (2.12), fig. 2.8.

    alpha: ``(..., 2)``, alpha1 = rotation of link 2 relative to link 1, alpha2 = rotation of link 3
    relative to link 2 (fig. 2.6). g: ``(..., 3)``, default e. Returns a dict with "f", "g", "h"
    of shape ``(..., 3, 3)`` (link index on axis -2) and "joints" ``(..., 2, 2)``, the joint positions.
    """
    fr = three_link_chain(lengths).frames(alpha, g)
    fr["joints"] = fr["h"][..., :2, :2].copy()
    return fr


def _three_link_lengths(lengths):
    if isinstance(lengths, (str, bytes)) or np.ndim(lengths) != 1 or len(lengths) != 3:
        raise ValueError(f"lengths must be a length-3 sequence of positive link lengths; got {lengths!r}")
    return _lengths(lengths, 3)


def three_link_poses(alpha, lengths=(1.0, 1.0, 1.0)):
    """Poses ``(..., 3, 3)`` of the three link centres g1, g2, g3 in the middle link's frame; book (2.12), fig. 2.8.

    The closed form of the chain product ``g1 = (-l2/2, 0, 0) exp(-alpha1) (-l1/2, 0, 0)``,
    ``g2 = e``, ``g3 = (l2/2, 0, 0) exp(alpha2) (l3/2, 0, 0)`` (the link index is on axis -2):
    link 1 sits at heading -alpha1, link 3 at +alpha2. alpha: ``(..., 2)``.
    """
    alpha = as_array(alpha, "alpha", (2,), what=" (alpha1, alpha2)")
    l1, l2, l3 = _three_link_lengths(lengths)
    a1, a2 = alpha[..., 0], alpha[..., 1]
    P = np.zeros(alpha.shape[:-1] + (3, 3))
    P[..., 0, 0] = -l2 / 2 - l1 / 2 * np.cos(a1)
    P[..., 0, 1] = l1 / 2 * np.sin(a1)
    P[..., 0, 2] = -a1
    P[..., 2, 0] = l2 / 2 + l3 / 2 * np.cos(a2)
    P[..., 2, 1] = l3 / 2 * np.sin(a2)
    P[..., 2, 2] = a2
    return P


def three_link_jacobians(alpha, lengths=(1.0, 1.0, 1.0)):
    """Body-velocity Jacobians (J1, J2, J3) of the three links, each ``(..., 3, 5)``; book (2.57)-(2.59), corrected.

    Each maps (xi_x, xi_y, xi_theta, alpha1_dot, alpha2_dot) -- the body velocity of the middle link
    and the joint speeds -- to the body velocity of link i's centre frame g_i. alpha: ``(..., 2)``
    with the sign convention of fig. 2.6 (link 1 sits at -alpha1 relative to link 2, link 3 at
    +alpha2); lengths: three positive numbers. Corrections to the draft (see book/90-errata):
    row 1 of (2.51) has -(xi_y - xi_theta l2/2) sin(alpha1); (2.56) needs the third row
    xi_theta + alpha2_dot, so row 3 of (2.59) is (0, 0, 1, 0, 1).
    """
    alpha = as_array(alpha, "alpha", (2,), what=" (alpha1, alpha2)")
    l1, l2, l3 = _three_link_lengths(lengths)
    c1, s1 = np.cos(alpha[..., 0]), np.sin(alpha[..., 0])
    c2, s2 = np.cos(alpha[..., 1]), np.sin(alpha[..., 1])
    batch = alpha.shape[:-1]
    J1 = np.zeros(batch + (3, 5))
    J1[..., 0, 0], J1[..., 0, 1], J1[..., 0, 2] = c1, -s1, l2 * s1 / 2
    J1[..., 1, 0], J1[..., 1, 1], J1[..., 1, 2], J1[..., 1, 3] = s1, c1, -(l2 * c1 + l1) / 2, l1 / 2
    J1[..., 2, 2], J1[..., 2, 3] = 1.0, -1.0
    J2 = np.zeros(batch + (3, 5))
    J2[..., :, :3] = np.eye(3)
    J3 = np.zeros(batch + (3, 5))
    J3[..., 0, 0], J3[..., 0, 1], J3[..., 0, 2] = c2, s2, l2 * s2 / 2
    J3[..., 1, 0], J3[..., 1, 1], J3[..., 1, 2], J3[..., 1, 4] = -s2, c2, (l2 * c2 + l3) / 2, l3 / 2
    J3[..., 2, 2], J3[..., 2, 4] = 1.0, 1.0
    return J1, J2, J3


# ------------------------------------------------------------------ generalized body frames
def _beta_args(beta, dbeta):
    beta = as_array(beta, "beta", (3,), what=" (pose of the frame relative to the base link)")
    dbeta = as_array(dbeta, "dbeta", (3, np.shape(dbeta)[-1] if np.ndim(dbeta) >= 2 else 0),
                     what=" (d beta / d alpha)")
    return beta, dbeta


def beta_frame_jacobian(beta, dbeta):
    """Body-velocity Jacobian ``(..., 3, 3 + n)`` of the frame g = g_base beta(alpha); book (2.60)-(2.67).

    Maps (xi_base, alpha_dot) to xi_g = Ad_beta^-1 (xi_base + T_beta R_{beta^-1} dbeta alpha_dot).
    beta: ``(..., 3)``, dbeta = d beta / d alpha: ``(..., 3, n)``.
    """
    beta, dbeta = _beta_args(beta, dbeta)
    n = dbeta.shape[-1]
    TR = SE2.right_lifted_action(SE2.inverse(beta), beta)  # (2.61)
    batch = np.broadcast_shapes(beta.shape[:-1], dbeta.shape[:-2])
    M = np.zeros(batch + (3, 3 + n))
    M[..., :, :3] = np.eye(3)
    M[..., :, 3:] = TR @ dbeta
    return SE2.Ad_inv(beta) @ M


def links_from_beta_frame(jacobians, beta, dbeta):
    """Link Jacobians re-expressed with the frame g = g_base beta as body frame: list of ``(..., 3, 3 + n)``; book (2.68).

    ``jacobians`` are Jacobians wrt (xi_base, alpha_dot) (e.g. from :func:`three_link_jacobians`);
    the result maps (xi_g, alpha_dot) using xi_base = Ad_beta xi_g - T_beta R_{beta^-1} dbeta alpha_dot.
    """
    beta, dbeta = _beta_args(beta, dbeta)
    n = dbeta.shape[-1]
    TR = SE2.right_lifted_action(SE2.inverse(beta), beta)
    batch = np.broadcast_shapes(beta.shape[:-1], dbeta.shape[:-2])
    M = np.zeros(batch + (3 + n, 3 + n))
    M[..., :3, :3] = SE2.Ad(beta)
    M[..., :3, 3:] = -(TR @ dbeta)
    M[..., 3:, 3:] = np.eye(n)
    return [np.asarray(J, dtype=float) @ M for J in jacobians]


def com_frame(alpha, lengths=(1.0, 1.0, 1.0), weights=None):
    """The centre-of-mass / mean-orientation frame beta(alpha) ``(..., 3)`` and d beta/d alpha ``(..., 3, 2)``; exercise 2.3a, (2.69).

    beta is the pose relative to the middle link of the three-link system: position the weighted
    mean of the link centres, orientation the weighted mean of the link orientations (-alpha1, 0,
    alpha2). ``weights`` default to the link lengths (uniform mass per unit length); pass
    ``(1, 1, 1)`` for the plain mean.
    """
    alpha = as_array(alpha, "alpha", (2,), what=" (alpha1, alpha2)")
    P = three_link_poses(alpha, lengths)
    l1, l2, l3 = _three_link_lengths(lengths)
    w = np.array([l1, l2, l3]) if weights is None else _lengths(weights, 3, "weights")
    w = w / w.sum()
    a1, a2 = alpha[..., 0], alpha[..., 1]
    c1, s1, c2, s2 = np.cos(a1), np.sin(a1), np.cos(a2), np.sin(a2)
    x, y = np.moveaxis(np.einsum("i,...ij->...j", w, P[..., :2]), -1, 0)
    th = np.einsum("i,...i->...", w, P[..., 2])
    beta = np.stack([x, y, th], -1)
    d = np.zeros(alpha.shape[:-1] + (3, 2))
    d[..., 0, 0] = w[0] * l1 / 2 * s1
    d[..., 0, 1] = -w[2] * l3 / 2 * s2
    d[..., 1, 0] = w[0] * l1 / 2 * c1
    d[..., 1, 1] = w[2] * l3 / 2 * c2
    d[..., 2, 0] = -w[0]
    d[..., 2, 1] = w[2]
    return beta, d


def com_frame_jacobians(alpha, lengths=(1.0, 1.0, 1.0), weights=None):
    """Jacobian of the centre-of-mass frame and the three link Jacobians seen from it; exercise 2.3b-c.

    Returns ``(J_com, (J1, J2, J3))``: J_com ``(..., 3, 5)`` maps (xi_middle, alpha_dot) to the
    body velocity of the frame (2.62); J_i ``(..., 3, 5)`` map (xi_com, alpha_dot) to link i's body
    velocity (2.68).
    """
    beta, dbeta = com_frame(alpha, lengths, weights)
    J_com = beta_frame_jacobian(beta, dbeta)
    return J_com, tuple(links_from_beta_frame(three_link_jacobians(alpha, lengths), beta, dbeta))


# ------------------------------------------------------------------ holonomic constraints
def circle_constraints(p):
    """Constraint values ``(..., 2)``: f1 = z - 1 and f2 = sqrt(x^2 + y^2) - 1; book (2.i)-(2.ii). p: ``(..., 3)``."""
    p = as_array(p, "p", (3,), what=" (points x, y, z)")
    return np.stack([p[..., 2] - 1.0, np.hypot(p[..., 0], p[..., 1]) - 1.0], -1)


def sphere_plane_constraints(p):
    """Constraint values ``(..., 2)``: distance from the origin sqrt(2) and z = 1 (exercise 2.1: same manifold). p: ``(..., 3)``."""
    p = as_array(p, "p", (3,), what=" (points x, y, z)")
    return np.stack([np.linalg.norm(p, axis=-1) - np.sqrt(2.0), p[..., 2] - 1.0], -1)


def sample_accessible_manifold(constraints, n=200, rng=None, box=2.0, dim=3, iters=50, tol=1e-12):
    """Points ``(k, dim)`` on the zero set of ``constraints`` (the accessible manifold), book box (2.i)-(2.ii).

    Random points in ``[-box, box]^dim`` are projected onto ``constraints(p) = 0`` by Gauss-Newton
    steps with a numerical Jacobian; points that do not converge (or hit a singularity) are dropped.
    """
    if not callable(constraints):
        raise TypeError("constraints must be a function p (..., dim) -> values (..., k)")
    n = check_int(n, "n", low=1, high=10 ** 7, what=" (the number of random starting points)")
    dim = check_int(dim, "dim", low=1, high=1000, what=" (the dimension of the ambient space)")
    iters = check_int(iters, "iters", low=1, high=10 ** 6, what=" (Gauss-Newton iterations)")
    box = float(check_positive(box, "box"))
    tol = float(check_positive(tol, "tol"))
    if rng is None:
        rng = np.random.default_rng(0)
    elif not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy Generator (np.random.default_rng(seed)) or None; got {rng!r}")
    p = rng.uniform(-box, box, (n, dim))
    eps = 1e-7
    for _ in range(iters):
        f = constraints(p)
        J = np.stack([(constraints(p + eps * e) - constraints(p - eps * e)) / (2 * eps) for e in np.eye(dim)], -1)
        step = np.einsum("nij,nj->ni", np.linalg.pinv(J), f)
        p = p - step
        if np.all(np.abs(f) < tol):
            break
    ok = np.all(np.abs(constraints(p)) < 1e-9, axis=-1) & np.all(np.isfinite(p), axis=-1)
    return p[ok]


def accessible_circle(n=100):
    """Points ``(n, 3)`` of the accessible manifold of (2.i)-(2.ii): the unit circle in the plane z = 1."""
    n = check_int(n, "n", low=2, high=10 ** 7, what=" (the number of points)")
    t = np.linspace(0.0, 2 * np.pi, n)
    return np.stack([np.cos(t), np.sin(t), np.ones_like(t)], -1)

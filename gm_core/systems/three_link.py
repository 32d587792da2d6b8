"""Shared geometry of the three-link locomotors of section 3.4 (numpy only).

Chapter-2 convention (section 2.5.5, fig. 2.8): links 1, 2, 3 of lengths l1, l2, l3 joined end
to end; alpha1 is the rotation of link 2 relative to link 1, alpha2 that of link 3 relative to
link 2; each link's frame g_i sits at its centre, x along the link towards link 3. The body
frame is the middle link's frame unless a system says otherwise.
"""
from __future__ import annotations

import numpy as np

from .._validate import as_array, check_positive
from .base import LocomotionSystem, Part, rectangle_outline

__all__ = ["ThreeLinkSystem", "three_link_link_poses", "three_link_jacobians_local"]


def three_link_link_poses(alpha, lengths):
    """Poses (..., 3, 3) of the three link centres in the middle link's frame."""
    a1, a2 = alpha[..., 0], alpha[..., 1]
    l1, l2, l3 = lengths
    P = np.zeros(alpha.shape[:-1] + (3, 3))
    P[..., 0, 0] = -l2 / 2 - l1 / 2 * np.cos(a1)
    P[..., 0, 1] = l1 / 2 * np.sin(a1)
    P[..., 0, 2] = -a1
    P[..., 2, 0] = l2 / 2 + l3 / 2 * np.cos(a2)
    P[..., 2, 1] = l3 / 2 * np.sin(a2)
    P[..., 2, 2] = a2
    return P


def three_link_jacobians_local(alpha, lengths):
    """Link body-velocity Jacobians (J1, J2, J3), each (..., 3, 5), middle-link body frame.

    Our own derivation (xi_i = Ad_{h_i}^-1 xi + h_i^-1 dh_i/dr r_dot for the link poses h_i of
    :func:`three_link_link_poses`); it agrees with (2.57)-(2.58), and with (2.59) once the
    draft's misplaced alpha2-dot entry in its last row is moved to the fifth column. Kept as the
    module's own reference and fallback for :func:`gm_core.chains.three_link_jacobians`.
    """
    a1, a2 = alpha[..., 0], alpha[..., 1]
    l1, l2, l3 = lengths
    c1, s1, c2, s2 = np.cos(a1), np.sin(a1), np.cos(a2), np.sin(a2)
    batch = alpha.shape[:-1]
    J1 = np.zeros(batch + (3, 5))
    J1[..., 0, 0], J1[..., 0, 1], J1[..., 0, 2] = c1, -s1, l2 * s1 / 2
    J1[..., 1, 0], J1[..., 1, 1], J1[..., 1, 2] = s1, c1, -(l2 * c1 + l1) / 2
    J1[..., 1, 3] = l1 / 2
    J1[..., 2, 2], J1[..., 2, 3] = 1.0, -1.0
    J2 = np.zeros(batch + (3, 5))
    J2[..., 0, 0] = J2[..., 1, 1] = J2[..., 2, 2] = 1.0
    J3 = np.zeros(batch + (3, 5))
    J3[..., 0, 0], J3[..., 0, 1], J3[..., 0, 2] = c2, s2, l2 * s2 / 2
    J3[..., 1, 0], J3[..., 1, 1], J3[..., 1, 2] = -s2, c2, (l2 * c2 + l3) / 2
    J3[..., 1, 4] = l3 / 2
    J3[..., 2, 2], J3[..., 2, 4] = 1.0, 1.0
    return J1, J2, J3


def _chains_jacobians():
    """gm_core.chains.three_link_jacobians if it exists, else None."""
    try:
        from ..chains import three_link_jacobians
    except Exception:  # noqa: BLE001 - chains.py is written separately; fall back to ours
        return None
    return three_link_jacobians


class ThreeLinkSystem(LocomotionSystem):
    """Base for three-link chains; shape r = (alpha1, alpha2) in the chapter-2 convention."""

    shape_names = ("alpha1", "alpha2")
    frame = "middle"
    #: Which Jacobian implementation to use: "chains" (gm_core.chains, the default when present)
    #: or "local" (:func:`three_link_jacobians_local`).
    jacobian_source = "chains"

    def __init__(self, lengths=(1.0, 1.0, 1.0)):
        lengths = as_array(lengths, "lengths", (3,), what=" (the three link lengths l1, l2, l3)")
        if lengths.ndim != 1:
            raise ValueError(f"lengths must have shape (3,); got shape {lengths.shape}")
        check_positive(lengths, "lengths")
        self.lengths = tuple(float(v) for v in lengths)

    # -- kinematics --------------------------------------------------------------------------
    def link_jacobians(self, r):
        """(J1, J2, J3), each (..., 3, 5): link body velocities from (xi, r_dot), system body frame."""
        r = self._shape(r)
        J = None
        if self.jacobian_source == "chains":
            f = _chains_jacobians()
            if f is not None:
                J = tuple(np.asarray(j, dtype=float) for j in f(r, self.lengths))
        if J is None:
            J = three_link_jacobians_local(r, self.lengths)
        T = self._frame_change(r)
        if T is not None:
            J = tuple(j @ T for j in J)
        return J

    def _frame_change(self, r):
        """(..., 5, 5) map from (xi_frame, r_dot) to (xi_middle, r_dot), or None for the middle frame."""
        return None

    def frame_offset(self, r):
        """Pose (..., 3) of the middle link in the system body frame (zero for the middle frame)."""
        r = self._shape(r)
        return np.zeros(r.shape[:-1] + (3,))

    def link_poses(self, r):
        """Poses (..., 3, 3) of the three link centres in the system body frame."""
        from ..groups import SE2

        r = self._shape(r)
        P = three_link_link_poses(r, self.lengths)
        off = self.frame_offset(r)
        return SE2.compose(off[..., None, :], P)

    part_poses = link_poses

    def _link_width(self):
        return 0.08 * sum(self.lengths) / 3

    def parts(self):
        w = self._link_width()
        return [Part(f"link {i + 1}", rectangle_outline(l, w), "link") for i, l in enumerate(self.lengths)]

    def __repr__(self):
        return f"{type(self).__name__}(lengths={self.lengths})"

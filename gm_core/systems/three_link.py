"""Shared geometry of the three-link locomotors of section 3.4 (numpy only).

Chapter-2 convention (section 2.5.5, fig. 2.8): links 1, 2, 3 of lengths l1, l2, l3 joined end
to end; alpha1 is the rotation of link 2 relative to link 1, alpha2 that of link 3 relative to
link 2; each link's frame g_i sits at its centre, x along the link towards link 3. The link
poses and Jacobians are :func:`gm_core.three_link_chain.three_link_poses` and
:func:`gm_core.three_link_chain.three_link_jacobians` (one copy, there); here they are only moved to
the system's body frame, which is the middle link's frame unless a system says otherwise.
"""
from __future__ import annotations

import numpy as np

from .._validate import as_array, check_positive
from ..connection import metric_from_jacobians, shape_space_metric
from ..groups import SE2
from ..three_link_chain import three_link_jacobians, three_link_poses
from .base import LocomotionSystem, Part, rectangle_outline

__all__ = ["ThreeLinkSystem", "LinkMetricSystem"]



class ThreeLinkSystem(LocomotionSystem):
    """Base for three-link chains; shape r = (alpha1, alpha2) in the chapter-2 convention."""

    shape_names = ("alpha1", "alpha2")
    #: Where the body frame sits: "middle" (the middle link's frame) unless a subclass says otherwise.
    frame = "middle"

    def __init__(self, lengths=(1.0, 1.0, 1.0)):
        lengths = as_array(lengths, "lengths", (3,), what=" (the three link lengths l1, l2, l3)")
        if lengths.ndim != 1:
            raise ValueError(f"lengths must have shape (3,); got shape {lengths.shape}")
        check_positive(lengths, "lengths")
        self.lengths = tuple(float(v) for v in lengths)

    # -- kinematics --------------------------------------------------------------------------
    def middle_link_jacobians(self, r):
        """(J1, J2, J3), each (..., 3, 5): link body velocities from (xi_middle, r_dot), (2.57)-(2.59)."""
        return three_link_jacobians(self._shape(r), self.lengths)

    def link_jacobians(self, r):
        """(J1, J2, J3), each (..., 3, 5): link body velocities from (xi, r_dot), system body frame."""
        r = self._shape(r)
        J = self.middle_link_jacobians(r)
        T = self.frame_change(r)
        return J if T is None else tuple(j @ T for j in J)

    def frame_change(self, r):
        """(..., 5, 5) map from (xi_frame, r_dot) to (xi_middle, r_dot), or None for the middle frame."""
        self._shape(r)
        return None

    def frame_offset(self, r):
        """Pose (..., 3) of the middle link in the system body frame (zero for the middle frame)."""
        r = self._shape(r)
        return np.zeros(r.shape[:-1] + (3,))

    def link_poses(self, r):
        """Poses (..., 3, 3) of the three link centres in the system body frame."""
        r = self._shape(r)
        return SE2.compose(self.frame_offset(r)[..., None, :], three_link_poses(r, self.lengths))

    def part_poses(self, r):
        return self.link_poses(r)

    def link_weights(self):
        """Normalised link weights for the centre of mass: the lengths (uniform slender links)."""
        w = np.array(self.lengths)
        return w / w.sum()

    def body_frames(self, bounds=None, *, n=None, centre_of_mass=True, minimum_perturbation=True):
        """{name: system}: this frame and, if asked, the centre of mass (mean orientation) and
        minimum perturbation over ``bounds`` (default ``shape_limits``, ``n`` nodes per axis)."""
        from .minimum_perturbation import MinimumPerturbationFrame
        from .reframed import CentreOfMassFrame, Reframed

        own = {"middle": "middle link", "com": "centre of mass"}.get(self.frame, self.frame)
        out = {own: self}
        if centre_of_mass and self.frame != "com":
            out["centre of mass"] = Reframed(self, CentreOfMassFrame(self),
                                             name=f"{self.name} (centre of mass, mean orientation)")
        if minimum_perturbation:
            out["minimum perturbation"] = Reframed(self, MinimumPerturbationFrame.fit(self, bounds, n),
                                                   name=f"{self.name} (minimum perturbation)")
        return out

    def _link_width(self):
        return 0.08 * sum(self.lengths) / 3

    def parts(self):
        w = self._link_width()
        return [Part(f"link {i + 1}", rectangle_outline(l, w), "link") for i, l in enumerate(self.lengths)]

    def __repr__(self):
        return f"{type(self).__name__}(lengths={self.lengths})"


class LinkMetricSystem(ThreeLinkSystem):
    """A three-link system whose constraint is a balance over the links, (3.39)-(3.47).

    Each link carries a (3, 3) matrix in its own centre frame (:meth:`link_matrices`: mass and
    inertia, added mass, or drag coefficients); the system matrix is ``sum J_i^T M_i J_i``
    (:meth:`metric`) and its top three rows, the total momentum or drag wrench, are the Pfaffian.
    """

    def link_matrices(self):
        """The (3, 3) link matrices, one per link, in the links' centre frames."""
        raise NotImplementedError

    def metric(self, r):
        """System matrix (..., 5, 5): sum of J_i^T M_i J_i over the links."""
        return metric_from_jacobians(self.link_jacobians(r), self.link_matrices())

    def pfaffian(self, r):
        """Pfaffian (..., 3, 5): the top three rows of :meth:`metric` (total momentum or wrench = 0)."""
        return metric_from_jacobians(self.link_jacobians(r), self.link_matrices(), rows=3)

    def shape_metric(self, r):
        """Cost metric on shape space M(r) = [-A; I]^T D [-A; I] (..., 2, 2) (power or twice kinetic energy)."""
        return shape_space_metric(self.metric(r), self.connection(r))

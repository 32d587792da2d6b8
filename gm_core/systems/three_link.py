"""Shared geometry of the three-link locomotors of section 3.4 that are not a balance over the links (numpy only).

Chapter-2 convention (section 2.5.5, fig. 2.8): links 1, 2, 3 of lengths l1, l2, l3 joined end
to end; alpha1 is the rotation of link 2 relative to link 1, alpha2 that of link 3 relative to
link 2; each link's frame g_i sits at its centre, x along the link towards link 3. The swimmers
and the floating snake are :class:`~gm_core.systems.LinkChain` with N = 3 (their constraint is a
drag or momentum balance over the links); :class:`ThreeLinkSystem` is the base of the systems
whose constraint is something else (the kinematic snake's wheels), with the same link poses and
Jacobians (:func:`gm_core.chains.three_link.three_link_poses`, ``three_link_jacobians``, both
:func:`gm_core.chains.link_chain_poses` in the middle link's frame: one copy for every N).
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains.three_link import three_link_jacobians, three_link_poses
from gm_core.systems.base import LocomotionSystem, SystemPart, rectangle_outline
from gm_core.validation import FloatArray, as_array, check_positive

__all__ = ["ThreeLinkSystem", "three_lengths"]


def three_lengths(lengths: ArrayLike) -> tuple[float, ...]:
    """The three link lengths as a tuple of floats, validated (ValueError naming ``lengths``)."""
    lengths = as_array(lengths, "lengths", (3,), what=" (the three link lengths l1, l2, l3)")
    if lengths.ndim != 1:
        raise ValueError(f"lengths must have shape (3,); got shape {lengths.shape}")
    check_positive(lengths, "lengths")
    return tuple(float(v) for v in lengths)


class ThreeLinkSystem(LocomotionSystem):
    """Base for three-link chains with a constraint of their own (not a balance over the links);
    shape r = (alpha1, alpha2) in the chapter-2 convention, body frame the middle link."""

    shape_names = ("alpha1", "alpha2")
    frame = "middle"

    def __init__(self, lengths: ArrayLike = (1.0, 1.0, 1.0)) -> None:
        self.lengths = three_lengths(lengths)
        self._L = np.array(self.lengths)

    # -- kinematics --------------------------------------------------------------------------
    def middle_link_jacobians(self, r: ArrayLike) -> tuple[FloatArray, ...]:
        """(J1, J2, J3), each (..., 3, 5): link body velocities from (xi_middle, r_dot), (2.57)-(2.59)."""
        return three_link_jacobians(self._shape(r), self.lengths)

    def link_jacobians(self, r: ArrayLike) -> FloatArray:
        """Link Jacobians (..., 3, 3, 5) from (xi, r_dot) to each link's body velocity (the body
        frame is the middle link), stacked on axis -3 like :meth:`LinkChain.link_jacobians`."""
        return np.stack(self.middle_link_jacobians(r), -3)

    def link_poses(self, r: ArrayLike) -> FloatArray:
        """Poses (..., 3, 3) of the three link centres in the body frame (the middle link's)."""
        return three_link_poses(self._shape(r), self.lengths)

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        return self.link_poses(r)

    def link_weights(self) -> FloatArray:
        """Normalised link weights for the centre of mass: the lengths (uniform slender links)."""
        w = np.array(self.lengths)
        return w / w.sum()

    @override
    def body_frames(self, bounds: Any = None, *, n: int | None = None, centre_of_mass: bool = True,
                    minimum_perturbation: bool = True) -> dict[str, LocomotionSystem]:
        """{name: system}: the middle link and, if asked, the centre of mass with the mean
        orientation and minimum perturbation over ``bounds`` (default ``shape_limits``, ``n``
        nodes per axis), both as :class:`~gm_core.systems.Reframed` systems."""
        from gm_core.systems.minimum_perturbation import MinimumPerturbationFrame
        from gm_core.systems.reframed import CentreOfMassFrame, Reframed

        out: dict[str, LocomotionSystem] = {"middle link": self}
        if centre_of_mass:
            out["centre of mass"] = Reframed(self, CentreOfMassFrame(self),
                                             name=f"{self.name} (centre of mass, mean orientation)")
        if minimum_perturbation:
            out["minimum perturbation"] = Reframed(self, MinimumPerturbationFrame.fit(self, bounds, n),
                                                   name=f"{self.name} (minimum perturbation)")
        return out

    def _link_width(self):
        return 0.08 * sum(self.lengths) / 3

    @override
    def parts(self) -> list[SystemPart]:
        w = self._link_width()
        return [SystemPart(f"link {i + 1}", rectangle_outline(l, w), "link") for i, l in enumerate(self.lengths)]

    @override
    def __repr__(self) -> str:
        return f"{type(self).__name__}(lengths={self.lengths})"

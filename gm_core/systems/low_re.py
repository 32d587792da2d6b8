"""Three-link swimmer at low Reynolds number (resistive force theory), book section 3.4.4."""
from __future__ import annotations

from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.systems.link_chain import LinkChain
from gm_core.systems.three_link import three_lengths
from gm_core.validation import FloatArray

__all__ = ["LowReSwimmer"]


class LowReSwimmer(LinkChain):
    """Three slender links in a viscous fluid: ``LinkChain(lengths, "low_re", drag_ratio=...)``
    with N = 3, body frame the middle link; drag balances exactly, so net force and moment vanish.

    Per unit length, each link feels longitudinal drag ``-c u_par`` and lateral drag
    ``-k u_perp`` with ``k = drag_ratio * c`` (resistive force theory; c = 1 here because the
    connection does not depend on it). Integrating over a link of length l (half-length l/2):
    ``F_x = -c l xi_x``, ``F_y = -k l xi_y``, ``M = -k l^3/12 xi_theta`` about the link centre,
    i.e. (3.41)-(3.43) with L = l/2 (:func:`gm_core.systems.fluids.slender_link_drag`). The net wrench in
    the body frame, ``sum J_xi,i^T F_i``, is the corrected (3.44) (it includes the middle link's
    own drag and uses each link's own length); setting it to zero is the Pfaffian (3.45). All of
    it is :class:`~gm_core.systems.LinkChain`'s (one copy for every N).

    What ``drag_ratio = 1`` means: drag is then isotropic, ``-c u`` whatever the direction, so the
    total force is ``-c`` times the velocity of the length-weighted centroid of the links; zero
    force keeps that centroid fixed (it is a point of the swimmer that never moves). The body
    frame, at the middle link, still moves: the middle link swings about the fixed centroid as
    the shape changes, and the whole swimmer can still turn. Net *displacement* over a gait is
    then a rotation about the centroid only. Real slender bodies have drag_ratio near 2, which
    is what lets them swim.
    """

    def __init__(self, lengths: ArrayLike = (1.0, 1.0, 1.0), drag_ratio: float = 2.0) -> None:
        super().__init__(three_lengths(lengths), "low_re", drag_ratio=drag_ratio)
        self.name = "low-Reynolds swimmer"

    def drag_matrix(self, r: ArrayLike) -> FloatArray:
        """Drag matrix (..., 5, 5): sum of J_i^T D_i J_i; its top rows map (xi, r_dot) to -(net wrench)."""
        return self.metric(r)

    @override
    def __repr__(self) -> str:
        return f"LowReSwimmer(lengths={self.lengths}, drag_ratio={self.drag_ratio:g})"

"""Three-link swimmer at low Reynolds number (resistive force theory), book section 3.4.4."""
from __future__ import annotations

import numpy as np

from .._validate import check_positive
from ..locomotion import metric_from_jacobians
from .base import Part, ellipse_outline
from .three_link import ThreeLinkSystem

__all__ = ["LowReSwimmer"]


class LowReSwimmer(ThreeLinkSystem):
    """Three slender links in a viscous fluid; drag balances exactly, so net force and moment vanish.

    Per unit length, each link feels longitudinal drag ``-c u_par`` and lateral drag
    ``-k u_perp`` with ``k = drag_ratio * c`` (resistive force theory; c = 1 here because the
    connection does not depend on it). Integrating over a link of length l (half-length l/2):
    ``F_x = -c l xi_x``, ``F_y = -k l xi_y``, ``M = -k l^3/12 xi_theta`` about the link centre,
    i.e. (3.41)-(3.43) with L = l/2. The net wrench in the body frame, ``sum J_xi,i^T F_i``,
    is the corrected (3.44) (it includes the middle link's own drag and uses each link's own
    length); setting it to zero is the Pfaffian (3.45).
    """

    name = "low-Reynolds swimmer"

    def __init__(self, lengths=(1.0, 1.0, 1.0), drag_ratio=2.0):
        super().__init__(lengths)
        self.drag_ratio = float(check_positive(drag_ratio, "drag_ratio"))

    def link_matrices(self):
        """Link drag matrices diag(l, k l, k l^3/12), each (3, 3), in the links' centre frames."""
        k = self.drag_ratio
        return [np.diag([l, k * l, k * l ** 3 / 12]) for l in self.lengths]

    def drag_matrix(self, r):
        """Drag matrix (..., 5, 5): sum of J_i^T D_i J_i; its top rows map (xi, r_dot) to -(net wrench)."""
        return metric_from_jacobians(self.link_jacobians(r), self.link_matrices())

    def pfaffian(self, r):
        """Pfaffian (..., 3, 5): minus the net drag wrench (F_x, F_y, M) on the swimmer, (3.45)."""
        return metric_from_jacobians(self.link_jacobians(r), self.link_matrices(), rows=3)

    def parts(self):
        return [Part(f"link {i + 1}", ellipse_outline(l / 2, l / 24), "link")
                for i, l in enumerate(self.lengths)]

    def __repr__(self):
        return f"LowReSwimmer(lengths={self.lengths}, drag_ratio={self.drag_ratio:g})"

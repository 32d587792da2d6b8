"""Three-link swimmer at high Reynolds number (ideal fluid, added mass), book section 3.4.5."""
from __future__ import annotations

import numpy as np

from .._validate import positive_number
from ..fluids import ellipse_added_mass
from .base import Part, ellipse_outline
from .three_link import LinkMetricSystem

__all__ = ["HighReSwimmer"]


class HighReSwimmer(LinkMetricSystem):
    """Three elliptical links in an inviscid fluid, starting from rest: total momentum stays zero.

    Each link is an ellipse with semi-major axis a = l/2 and semi-minor axis b = a /
    aspect_ratio. Its effective inertia is the body's ``diag(m, m, m (a^2 + b^2)/4)``
    (``m = body_density * pi a b``) plus the added mass of
    :func:`gm_core.fluids.ellipse_added_mass`, with the flows around the links treated as
    independent (3.47). The local connection comes from the mass matrix as for the floating
    snake, (3.39)-(3.40). Body frame: the middle link.
    """

    name = "high-Reynolds swimmer"

    def __init__(self, lengths=(1.0, 1.0, 1.0), aspect_ratio=10.0, fluid_density=1.0, body_density=0.0):
        super().__init__(lengths)
        ar = positive_number(aspect_ratio, "aspect_ratio")
        if ar < 1:
            raise ValueError(f"aspect_ratio must be >= 1 (semi-major over semi-minor axis); got {aspect_ratio!r}")
        self.aspect_ratio = ar
        self.fluid_density = positive_number(fluid_density, "fluid_density")
        self.body_density = positive_number(body_density, "body_density", allow_zero=True)

    def semi_axes(self):
        """[(a_i, b_i)] for the three links."""
        return [(l / 2, l / 2 / self.aspect_ratio) for l in self.lengths]

    def link_matrices(self):
        """Effective link inertias (3, 3): body mass/inertia plus added mass, in the link frames."""
        out = []
        for a, b in self.semi_axes():
            m = self.body_density * np.pi * a * b
            body = np.diag([m, m, m * (a ** 2 + b ** 2) / 4])
            out.append(body + ellipse_added_mass(a, b, self.fluid_density))
        return out

    def mass_matrix(self, r):
        """Mass matrix (..., 5, 5) of body plus fluid, (3.39) with (3.47)."""
        return self.metric(r)

    def parts(self):
        return [Part(f"link {i + 1}", ellipse_outline(a, b), "link") for i, (a, b) in enumerate(self.semi_axes())]

    def __repr__(self):
        return (f"HighReSwimmer(lengths={self.lengths}, aspect_ratio={self.aspect_ratio:g}, "
                f"fluid_density={self.fluid_density:g}, body_density={self.body_density:g})")

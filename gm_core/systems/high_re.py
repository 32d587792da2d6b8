"""Three-link swimmer at high Reynolds number (ideal fluid, added mass), book section 3.4.5."""
from __future__ import annotations

from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.systems.link_chain import LinkChain
from gm_core.systems.three_link import three_lengths
from gm_core.validation import FloatArray

__all__ = ["HighReSwimmer"]


class HighReSwimmer(LinkChain):
    """Three elliptical links in an inviscid fluid, starting from rest: total momentum stays zero;
    ``LinkChain(lengths, "high_re", ...)`` with N = 3, body frame the middle link.

    Each link is an ellipse with semi-major axis a = l/2 and semi-minor axis b = a /
    aspect_ratio. Its effective inertia is the body's ``diag(m, m, m (a^2 + b^2)/4)``
    (``m = body_density * pi a b``) plus the added mass of
    :func:`gm_core.systems.fluids.ellipse_added_mass`, with the flows around the links treated as
    independent (3.47). The local connection comes from the mass matrix as for the floating
    snake, (3.39)-(3.40).
    """

    def __init__(self, lengths: ArrayLike = (1.0, 1.0, 1.0), aspect_ratio: float = 10.0, fluid_density: float = 1.0,
                 body_density: float = 0.0) -> None:
        super().__init__(three_lengths(lengths), "high_re", aspect_ratio=aspect_ratio,
                         fluid_density=fluid_density, body_density=body_density)
        self.name = "high-Reynolds swimmer"

    def mass_matrix(self, r: ArrayLike) -> FloatArray:
        """Mass matrix (..., 5, 5) of body plus fluid, (3.39) with (3.47)."""
        return self.metric(r)

    @override
    def __repr__(self) -> str:
        return (f"HighReSwimmer(lengths={self.lengths}, aspect_ratio={self.aspect_ratio:g}, "
                f"fluid_density={self.fluid_density:g}, body_density={self.body_density:g})")

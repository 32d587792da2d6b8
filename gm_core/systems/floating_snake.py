"""Floating snake: a three-link chain in free space conserving zero momentum, book section 3.4.3."""
from __future__ import annotations

from typing import Any

from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.systems.base import LocomotionSystem
from gm_core.systems.link_chain import LinkChain
from gm_core.systems.three_link import three_lengths
from gm_core.validation import FloatArray, as_array

__all__ = ["FloatingSnake"]

#: The body frames of section 3.4.3 a floating snake is built in, and the names ``body_frames`` gives them.
FRAME_NAMES = {"com middle": "centre of mass (middle-link axes)", "middle": "middle link",
               "com": "centre of mass", "minimum perturbation": "minimum perturbation"}


def _three(value, name, what):
    if value is None:
        return None
    v = as_array(value, name, (3,), what=what)
    if v.ndim != 1:
        raise ValueError(f"{name} must have shape (3,); got shape {v.shape}")
    return v


class FloatingSnake(LinkChain):
    """Three rigid links in free space (e.g. an astronaut or a falling cat), total momentum zero:
    ``LinkChain(lengths, "floating", masses=..., inertias=...)`` with N = 3.

    The kinetic energy is ``1/2 sum xi_i^T diag(m_i, m_i, I_i) xi_i`` with link body velocities
    ``xi_i = J_i [xi; r_dot]``; its mass matrix has the block form (3.39)-(3.40), so
    ``A = I_locked^-1 (I A)`` (the corrected (3.38)). The Pfaffian is the momentum map, the top
    three rows of the mass matrix.

    ``inertias=None`` means uniform slender rods, ``I_i = m_i l_i^2 / 12``. The body frame is
    fixed at construction (one of :data:`gm_core.systems.link_chain.FRAMES`):

    * ``frame="com middle"`` (default, section 3.4.3): at the system's centre of mass, with the
      middle link's axes; the first two rows of A vanish (the centre of mass does not move) and
      the third is the middle link's turning rate, the draft's (3.38);
    * ``frame="middle"``: the middle link's own frame;
    * ``frame="com"``: the centre of mass with the mass-weighted mean link orientation, what
      "centre of mass frame" means everywhere else in the course (exercise 2.3); its first two
      rows vanish too, its third is (3.38)'s minus the rate of the mean orientation.
    """

    def __init__(self, lengths: ArrayLike = (1.0, 1.0, 1.0), masses: ArrayLike = (1.0, 1.0, 1.0),
                 inertias: ArrayLike | None = None, frame: Any = "com middle") -> None:
        masses = _three(masses, "masses", " (the three link masses)")
        inertias = _three(inertias, "inertias", " (the links' moments of inertia about their centres)")
        super().__init__(three_lengths(lengths), "floating", masses=masses, inertias=inertias, frame=frame)
        self.name = "floating snake"

    def mass_matrix(self, r: ArrayLike) -> FloatArray:
        """Mass matrix (..., 5, 5) of (3.39): sum of J_i^T diag(m_i, m_i, I_i) J_i."""
        return self.metric(r)

    @override
    def body_frames(self, bounds: Any = None, *, n: int | None = None, centre_of_mass: bool = True,
                    minimum_perturbation: bool = True) -> dict[str, LocomotionSystem]:
        """{name: system}: this frame and the other one of section 3.4.3 (the centre of mass with
        the middle link's axes, or the middle link), always listed, as the frames its physics
        defines; if asked, the centre of mass with the mean orientation (``centre_of_mass``) and
        minimum perturbation over ``bounds``."""
        own: dict[str, LocomotionSystem] = {FRAME_NAMES[self.frame]: self}
        for frame in ("com middle", "middle"):
            if frame != self.frame:
                own[FRAME_NAMES[frame]] = self.with_frame(frame)
        if centre_of_mass and self.frame != "com":
            own[FRAME_NAMES["com"]] = self.with_frame("com")
        if minimum_perturbation and self.frame != "minimum perturbation":
            own[FRAME_NAMES["minimum perturbation"]] = self.with_frame("minimum perturbation", bounds, n)
        return own

    @override
    def __repr__(self) -> str:
        return (f"FloatingSnake(lengths={self.lengths}, masses={self.masses}, "
                f"inertias={self.inertias}, frame={self.frame!r})")

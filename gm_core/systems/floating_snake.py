"""Floating snake: a three-link chain in free space conserving zero momentum, book section 3.4.3."""
from __future__ import annotations

import numpy as np

from .._validate import as_array, check_positive
from ..connection import connection_from_pfaffian, metric_from_jacobians
from ..three_link_chain import com_frame
from .three_link import LinkMetricSystem

__all__ = ["FloatingSnake"]


class FloatingSnake(LinkMetricSystem):
    """Three rigid links in free space (e.g. an astronaut or a falling cat), total momentum zero.

    The kinetic energy is ``1/2 sum xi_i^T diag(m_i, m_i, I_i) xi_i`` with link body velocities
    ``xi_i = J_i [xi; r_dot]``; its mass matrix has the block form (3.39)-(3.40), so
    ``A = I_locked^-1 (I A)`` (the corrected (3.38)). The Pfaffian is the momentum map, the top
    three rows of the mass matrix.

    ``inertias=None`` means uniform slender rods, ``I_i = m_i l_i^2 / 12``. ``frame="com"`` puts
    the body frame at the system's centre of mass, oriented with the middle link (then the first
    two rows of A vanish: the centre of mass does not move); ``frame="middle"`` uses the middle
    link's own frame. The frame is fixed at construction.
    """

    name = "floating snake"

    def __init__(self, lengths=(1.0, 1.0, 1.0), masses=(1.0, 1.0, 1.0), inertias=None, frame="com"):
        super().__init__(lengths)
        masses = as_array(masses, "masses", (3,), what=" (the three link masses)")
        if masses.ndim != 1:
            raise ValueError(f"masses must have shape (3,); got shape {masses.shape}")
        check_positive(masses, "masses")
        self.masses = tuple(float(m) for m in masses)
        if inertias is None:
            self.inertias = tuple(m * l ** 2 / 12 for m, l in zip(self.masses, self.lengths))
        else:
            inertias = as_array(inertias, "inertias", (3,), what=" (the links' moments of inertia about their centres)")
            if inertias.ndim != 1:
                raise ValueError(f"inertias must have shape (3,); got shape {inertias.shape}")
            check_positive(inertias, "inertias")
            self.inertias = tuple(float(i) for i in inertias)
        if frame not in ("com", "middle"):
            raise ValueError(f"frame must be 'com' or 'middle'; got {frame!r}")
        self.frame = frame

    # -- centre of mass ----------------------------------------------------------------------
    def _com(self, r):
        """Centre of mass (..., 2) in the middle link's frame and its derivative (..., 2, 2) wrt r."""
        beta, dbeta = com_frame(r, self.lengths, weights=self.masses)
        return beta[..., :2], dbeta[..., :2, :]

    def frame_offset(self, r):
        r = self._shape(r)
        off = np.zeros(r.shape[:-1] + (3,))
        if self.frame == "com":
            off[..., :2] = -self._com(r)[0]
        return off

    def frame_change(self, r):
        if self.frame != "com":
            return None
        r = self._shape(r)
        c, dc = self._com(r)
        T = np.zeros(r.shape[:-1] + (5, 5))
        T[..., 0, 0] = T[..., 1, 1] = T[..., 2, 2] = T[..., 3, 3] = T[..., 4, 4] = 1.0
        # middle link at -c in the COM frame: xi_mid = Ad_{h^-1} xi_com - dc/dr r_dot
        T[..., 0, 2] = c[..., 1]
        T[..., 1, 2] = -c[..., 0]
        T[..., 0:2, 3:5] = -dc
        return T

    def link_matrices(self):
        """Link mass matrices diag(m_i, m_i, I_i), each (3, 3), in the links' centre frames."""
        return [np.diag([m, m, i]) for m, i in zip(self.masses, self.inertias)]

    def mass_matrix(self, r):
        """Mass matrix (..., 5, 5) of (3.39): sum of J_i^T diag(m_i, m_i, I_i) J_i."""
        return self.metric(r)

    def connection(self, r):
        """Local connection (..., 3, 2) from the mass matrix, (3.40).

        Computed in the middle link's frame and then moved to the centre-of-mass frame: with
        the middle link at -c(r) in the COM frame, ``xi_mid = B xi_com - (dc/dr) r_dot`` where
        ``B = [[1, 0, c_y], [0, 1, -c_x], [0, 0, 1]]``, so ``A_com = B^-1 (A_mid - [dc/dr; 0])``.
        """
        r = self._shape(r)
        J = self.middle_link_jacobians(r)
        A = connection_from_pfaffian(metric_from_jacobians(J, self.link_matrices(), rows=3))
        if self.frame == "com":
            c, dc = self._com(r)
            A[..., :2, :] -= dc
            A[..., 0, :] -= c[..., 1, None] * A[..., 2, :]
            A[..., 1, :] += c[..., 0, None] * A[..., 2, :]
        return A

    def link_weights(self):
        """Normalised link weights for the centre of mass: the masses."""
        w = np.array(self.masses)
        return w / w.sum()

    def body_frames(self, bounds=None, *, n=None, centre_of_mass=True, minimum_perturbation=True):
        """{name: system}: this frame and the other one of section 3.4.3 (centre of mass oriented
        with the middle link, or the middle link): the frames its physics defines, always listed;
        ``centre_of_mass`` adds nothing (its centre-of-mass frame is one of them); and, if asked,
        minimum perturbation over ``bounds``."""
        from .minimum_perturbation import MinimumPerturbationFrame
        from .reframed import Reframed

        names = {"com": "centre of mass", "middle": "middle link"}
        other = "middle" if self.frame == "com" else "com"
        out = {names[self.frame]: self, names[other]: FloatingSnake(self.lengths, self.masses, self.inertias, other)}
        if minimum_perturbation:
            out["minimum perturbation"] = Reframed(self, MinimumPerturbationFrame.fit(self, bounds, n),
                                                   name=f"{self.name} (minimum perturbation)")
        return out

    def __repr__(self):
        return (f"FloatingSnake(lengths={self.lengths}, masses={self.masses}, "
                f"inertias={self.inertias}, frame={self.frame!r})")

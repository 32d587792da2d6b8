"""Kinematic snake: three links on wheels that cannot slide sideways, book section 3.4.2."""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from typing_extensions import override

from gm_core.chains.kernels import flatten_batch, middle_frame_kernel
from gm_core.systems.base import SystemPart, rectangle_outline
from gm_core.systems.three_link import ThreeLinkSystem
from gm_core.validation import FloatArray

__all__ = ["KinematicSnake"]


class KinematicSnake(ThreeLinkSystem):
    """Three links whose centres cannot move sideways (a passive wheel under each link).

    The Pfaffian stacks the lateral rows of the three link Jacobians: ``xi_{g_i}^y = 0`` for
    i = 1, 2, 3 (the corrected (3.33)-(3.34)). Its body block has
    ``det omega_xi = (l3 sin a1 - l1 sin a2 + l2 sin(a1 - a2)) / 2``, which vanishes where the
    three link centres lie on one circle (for equal links, on the line a1 = a2): there the
    connection is NaN. Away from it (the corrected (3.36)-(3.37))::

        A = 1/D [[l1 (l3 + l2 cos a2) / 2,  l3 (l1 + l2 cos a1) / 2],
                 [0,                        0                      ],
                 [l1 sin a2,                l3 sin a1              ]],
        D = l3 sin a1 - l1 sin a2 + l2 sin(a1 - a2).
    """

    name = "kinematic snake"
    may_be_singular = True
    singular_description = ("the three link centres lie on one circle, so the three no-slide "
                            "lines meet in a point; for equal links this is the line alpha1 = alpha2")

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """Pfaffian (..., 3, 5): the lateral (y) rows of J1, J2, J3, i.e. no link slides sideways.

        Only those rows are computed, and the result is a view of the kernel's batch-last array
        (shapes on the last axis in memory), the layout in which :func:`connection_from_pfaffian`
        reads each entry of the many 3 x 3 blocks as one contiguous row."""
        r = self._shape(r)
        a, batch = (r, ()) if r.ndim == 1 else flatten_batch(r)       # one shape: the kernel's rows are scalars
        _, J = middle_frame_kernel(a, self._L, (1,))          # J (row, column, link[, M])
        return J[0].T.reshape(batch + (3, 5))

    def _closed_form_parts(self, r):
        """Numerator N (..., 3, 2), denominator D (...,) of the closed form A = N / D and their
        shape derivatives dN (..., 3, 2, 2), dD (..., 2)."""
        a1, a2 = r[..., 0], r[..., 1]
        l1, l2, l3 = self.lengths
        D = l3 * np.sin(a1) - l1 * np.sin(a2) + l2 * np.sin(a1 - a2)
        dD = np.stack([l3 * np.cos(a1) + l2 * np.cos(a1 - a2), -l1 * np.cos(a2) - l2 * np.cos(a1 - a2)], -1)
        N = np.zeros(r.shape[:-1] + (3, 2))
        dN = np.zeros(r.shape[:-1] + (3, 2, 2))
        N[..., 0, 0] = l1 * (l3 + l2 * np.cos(a2)) / 2
        N[..., 0, 1] = l3 * (l1 + l2 * np.cos(a1)) / 2
        N[..., 2, 0] = l1 * np.sin(a2)
        N[..., 2, 1] = l3 * np.sin(a1)
        dN[..., 0, 0, 1] = -l1 * l2 * np.sin(a2) / 2
        dN[..., 0, 1, 0] = -l3 * l2 * np.sin(a1) / 2
        dN[..., 2, 0, 1] = l1 * np.cos(a2)
        dN[..., 2, 1, 0] = l3 * np.cos(a1)
        return N, D, dN, dD

    def connection_closed_form(self, r: ArrayLike) -> FloatArray:
        """The closed form of the class docstring, (..., 3, 2) (an independent check of the solve)."""
        N, D, _, _ = self._closed_form_parts(self._shape(r))
        with np.errstate(divide="ignore", invalid="ignore"):
            A = N / D[..., None, None]
        return np.where(np.isfinite(A), A, np.nan)      # NaN at singular shapes, like connection

    @override
    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(A (..., 3, 2), dA (..., 3, 2, 2))`` with ``dA[..., i, j, k] = d A_ij / d r_k``: the
        quotient rule on the closed form N / D; A is :meth:`connection` (the solve), NaN at
        singular shapes, where dA is NaN too."""
        r = self._shape(r)
        N, D, dN, dD = self._closed_form_parts(r)
        A = self.connection(r)
        with np.errstate(divide="ignore", invalid="ignore"):
            dA = dN / D[..., None, None, None] - N[..., None] * dD[..., None, None, :] / D[..., None, None, None] ** 2
        dA[~np.isfinite(A).all(axis=(-1, -2))] = np.nan
        return A, dA

    @override
    def parts(self) -> list[SystemPart]:
        out = super().parts()
        w = self._link_width()
        # A wheel (drawn across the link) under each link centre: it rolls along the link only.
        out += [SystemPart(f"wheel {i + 1}", rectangle_outline(2.5 * w, 0.8 * w), "wheel") for i in range(3)]
        return out

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        P = self.link_poses(r)
        return np.concatenate([P, P], axis=-2)

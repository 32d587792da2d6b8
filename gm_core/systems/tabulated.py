"""A local connection known only as a table: measured or simulated, interpolated between grid points (numpy/scipy only).

Beyond the draft: when a locomotor's connection comes from experiments or simulations (a robot
in sand, a discrete-element model), it is known at the nodes of a grid of two shape variables.
:class:`TabulatedConnection` interpolates the table linearly (scipy's ``RegularGridInterpolator``,
as MATLAB's ``interpn``) or, with ``method="cubic"``, by interpolating bicubic splines (scipy's
``RectBivariateSpline``, as sysplotter's ``interp2(..., 'spline')``), whose derivatives give a
continuous constraint curvature in closed form (a linear table's curvature jumps from cell to cell).
Either way xi = -A(r) r_dot (3.10) as everywhere in the course, and Pfaffian
``[I, A]`` (so that ``omega_xi^-1 omega_r = A``). Outside the table there is no connection: NaN,
and :meth:`~TabulatedConnection.is_singular` is True there, as for the singular shapes of chapter 3.

Measured tables are noisy; a three-link body with equal end links has four symmetries (swap the
joints, swap and negate them, negate both: a mirror image or the body turned end for end), under
which the connection must transform in known ways. ``symmetry="three link"`` averages the four
lookups, as sysplotter's ``four_way_symmetry.m`` ('3link') does for its granular swimmer:
for the joint swap ``(a1, a2) -> (a2, a1)`` the columns swap and the x and theta rows change sign,
for ``(a1, a2) -> (-a2, -a1)`` the columns swap and the theta row changes sign, and for
``(a1, a2) -> (-a1, -a2)`` the x row changes sign.
"""
from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import RectBivariateSpline, RegularGridInterpolator
from typing_extensions import override

from gm_core.systems.base import LocomotionSystem, SystemPart
from gm_core.validation import BoolArray, FloatArray, as_array, check_option

__all__ = ["TabulatedConnection", "SYMMETRIES", "METHODS"]

SYMMETRIES = ("none", "three link")
#: Interpolations between the nodes: piecewise linear, or interpolating bicubic splines.
METHODS = ("linear", "cubic")

# (point map P, column order, row signs (3, 2)) per lookup of the 'three link' average:
# identity, joint swap, joint swap and negation, negation of both joints.
_THREE_LINK = (
    (np.eye(2), (0, 1), np.array([[1, 1], [1, 1], [1, 1]])),
    (np.array([[0.0, 1.0], [1.0, 0.0]]), (1, 0), np.array([[-1, -1], [1, 1], [-1, -1]])),
    (np.array([[0.0, -1.0], [-1.0, 0.0]]), (1, 0), np.array([[1, 1], [1, 1], [-1, -1]])),
    (-np.eye(2), (0, 1), np.array([[-1, -1], [1, 1], [1, 1]])),
)


class TabulatedConnection(LocomotionSystem):
    """A two-shape system whose connection is the linear interpolation of a table; see the module docstring.

    ``axes``: the two grids of shape values (increasing); ``table`` (3, 2, n1, n2): A at every node
    (rows x, y, theta; one column per shape variable). ``body`` (optional) is a system made of
    links, used only to draw the body at a shape (its parts and part poses).
    """

    may_be_singular = True
    singular_description = "outside the table"

    def __init__(self, axes: Any, table: ArrayLike, *, symmetry: str = "none", body: LocomotionSystem | None = None,
                 name: str = "tabulated connection", method: str = "linear") -> None:
        if not isinstance(axes, (tuple, list)) or len(axes) != 2:
            raise TypeError("axes must be a pair (grid of r1, grid of r2) of increasing sequences")
        grids = []
        for k, g in enumerate(axes):
            a = as_array(g, f"axes[{k}]", what=" (the grid of one shape variable)")
            if a.ndim != 1 or a.size < 2 or np.any(np.diff(a) <= 0):
                raise ValueError(f"axes[{k}] must be an increasing sequence of at least 2 values; got shape {a.shape}")
            grids.append(a)
        T = as_array(table, "table", what=" (the connection at every node, (3, 2, n1, n2))")
        if T.shape != (3, 2, grids[0].size, grids[1].size):
            raise ValueError(f"table must have shape (3, 2, {grids[0].size}, {grids[1].size}); got {T.shape}")
        self.symmetry = check_option(symmetry, "symmetry", SYMMETRIES)
        self.method = check_option(method, "method", METHODS)
        if self.method == "cubic" and min(g.size for g in grids) < 4:
            raise ValueError(f"method='cubic' needs at least 4 nodes per axis; got {grids[0].size} x {grids[1].size}")
        same = grids[0].size == grids[1].size and np.allclose(grids[0], grids[1])
        if self.symmetry == "three link" and not (same and np.allclose(grids[0], -grids[0][::-1])):
            raise ValueError("symmetry='three link' needs the same grid for both joints, symmetric about 0")
        if body is not None and (not isinstance(body, LocomotionSystem) or body.n_shape != 2):
            raise TypeError(f"body must be a locomotion system with two shape variables (for drawing); got {body!r:.60}")
        self.axes, self.table, self.body, self.name = tuple(grids), T.copy(), body, name
        self.n_shape = 2
        self.shape_names = ("alpha1", "alpha2")
        self.shape_limits = tuple((float(g[0]), float(g[-1])) for g in grids)
        self._interp = RegularGridInterpolator(self.axes, np.moveaxis(T.reshape(6, *T.shape[2:]), 0, -1),
                                               method="linear", bounds_error=False, fill_value=np.nan)
        flat = T.reshape(6, *T.shape[2:])
        self._splines = [RectBivariateSpline(*self.axes, f, kx=3, ky=3, s=0) for f in flat] if self.method == "cubic" else []

    def _outside(self, p):
        out = np.zeros(p.shape[:-1], dtype=bool)
        for k, g in enumerate(self.axes):
            out |= ~((p[..., k] >= g[0]) & (p[..., k] <= g[-1]))
        return out

    def _spline(self, p, d1=0, d2=0):
        flat = p.reshape(-1, 2)
        values = np.stack([s.ev(flat[:, 0], flat[:, 1], dx=d1, dy=d2) for s in self._splines], -1)
        values[self._outside(flat)] = np.nan
        return values.reshape(p.shape[:-1] + (3, 2))

    def _lookup(self, r):
        if self.method == "cubic":
            return self._spline(r)
        return self._interp(r).reshape(r.shape[:-1] + (3, 2))

    @override
    def connection(self, r: ArrayLike) -> FloatArray:
        """A(r) (..., 3, 2) by linear interpolation (averaged over the symmetries if asked); NaN outside the table."""
        r = self._shape(r)
        if self.symmetry == "none":
            return self._lookup(r)
        total = np.zeros(r.shape[:-1] + (3, 2))
        for P, cols, signs in _THREE_LINK:
            total += signs * self._lookup(r @ P.T)[..., list(cols)]
        return total / len(_THREE_LINK)

    @override
    def connection_derivative(self, r: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """``(A, dA)`` (..., 3, 2), (..., 3, 2, 2): a cubic table's own spline derivatives (chain rule through
        the symmetries' point maps), a linear table's central differences (it has no derivative on cell edges)."""
        if self.method == "linear":
            return super().connection_derivative(r)
        r = self._shape(r)
        lookups = [(np.eye(2), (0, 1), np.ones((3, 2)))] if self.symmetry == "none" else _THREE_LINK
        A = np.zeros(r.shape[:-1] + (3, 2))
        dA = np.zeros(r.shape[:-1] + (3, 2, 2))
        for P, cols, signs in lookups:
            p = r @ P.T
            c = list(cols)
            A += signs * self._spline(p)[..., c]
            grads = np.stack([self._spline(p, 1, 0)[..., c], self._spline(p, 0, 1)[..., c]], -1)  # d/dp_l
            dA += signs[..., None] * (grads @ P)                                                      # d/dr_k
        return A / len(lookups), dA / len(lookups)

    @override
    def pfaffian(self, r: ArrayLike) -> FloatArray:
        """``[I, A(r)]`` (..., 3, 5): the constraint xi + A r_dot = 0 itself."""
        A = self.connection(r)
        return np.concatenate([np.broadcast_to(np.eye(3), A.shape[:-2] + (3, 3)), A], -1)

    @override
    def singularity(self, r: ArrayLike) -> FloatArray:
        """1 inside the table, 0 outside (where the connection is unknown)."""
        return np.where(self.is_singular(r), 0.0, 1.0)

    @override
    def is_singular(self, r: ArrayLike) -> BoolArray:
        r = self._shape(r)
        inside = np.ones(r.shape[:-1], dtype=bool)
        points = [r] if self.symmetry == "none" else [r @ P.T for P, _, _ in _THREE_LINK]
        for p in points:
            for k, g in enumerate(self.axes):
                inside &= (p[..., k] >= g[0]) & (p[..., k] <= g[-1])
        return ~inside

    @override
    def parts(self) -> list[SystemPart]:
        return [] if self.body is None else self.body.parts()

    @override
    def part_poses(self, r: ArrayLike) -> FloatArray:
        r = self._shape(r)
        if self.body is None:
            return np.zeros(r.shape[:-1] + (0, 3))
        return self.body.part_poses(r)

    @override
    def __repr__(self) -> str:
        n1, n2 = (g.size for g in self.axes)
        return f"TabulatedConnection({n1} x {n2} table, symmetry={self.symmetry!r}, method={self.method!r}, name={self.name!r})"

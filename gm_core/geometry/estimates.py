"""One gait, three answers: the numbers behind notebook 10's panels (numpy only).

* :func:`shaped_gait`: an ellipse gait moved, resized, turned and bent into a bean (two Fourier
  harmonics), the gait a student shapes with sliders;
* :func:`displacement_estimates`: the exact net displacement g(T), the Stokes estimate
  (area integral of D(-A)) and the body-velocity integral (-oint A dr) of one gait, at the
  library's refined accuracy or at a fixed interactive resolution (:data:`INTERACTIVE`);
* :func:`row_scaled`: the three estimates scaled row by row (for bars that never rescale an axis);
* :func:`field_rms`: the root-mean-square size of each row of A over a grid of shapes (what the
  minimum-perturbation frame makes small);
* :func:`frames_of` and :func:`curvature_grid`: the three body frames of a system and its
  curvature over a grid, cached (keys hold the system itself, so a cached value can never be
  handed to another system, as an ``id()`` key could after garbage collection).
"""
from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from gm_core.geometry.curvature import body_velocity_integral, constraint_curvature, stokes_estimate
from gm_core.geometry.optimal import FourierGait, fourier_gait
from gm_core.systems.base import LocomotionSystem
from gm_core.systems.gaits import GaitLike
from gm_core.systems.motion import net_displacement, trusted_dimension
from gm_core.validation import FloatArray, SingularShapeError, as_array, check_int, positive_number, real_number

__all__ = ["FRAMES", "INTERACTIVE", "Estimates", "shaped_gait", "displacement_estimates", "row_scaled",
           "field_rms", "square_grid", "frames_of", "curvature_grid"]

#: The body frames compared in notebook 10, in the order of its toggle buttons.
FRAMES = ("middle link", "centre of mass", "minimum perturbation")

#: Fixed resolutions for interactive use (every slider change costs the same). Exact g(T): 128
#: fourth-order Magnus steps; Stokes: (64, 12) radial-quadrature points; body-velocity integral:
#: 256 trapezoid steps. For the panel's gaits all three agree with the refined values to 1e-7
#: (tests/test_geometry_estimates.py checks it).
INTERACTIVE: Mapping[str, Any] = MappingProxyType({"exact_steps": 128, "stokes_samples": (64, 12), "bvi_samples": 256})


def shaped_gait(c1: float = 0.0, c2: float = 0.0, a: float = 1.0, b: float = 1.0, tilt: float = 0.0, bend: float = 0.0,
                period: float = 1.0) -> FourierGait:
    """An ellipse gait bent into a bean: semi-axes ``a`` (along the tilted u axis) and ``b``,
    turned by ``tilt`` (radians), centred at (c1, c2), plus ``bend`` times cos(2 w t) along v.

    In the tilted frame (u, v) = R(-tilt)(r - c) the gait is u = a cos wt,
    v = b sin wt + bend cos 2wt (w = 2 pi / period), counter-clockwise for positive a and b; a
    large enough |bend| makes the loop non-convex.
    """
    c1, c2, tilt, bend = (real_number(v, n) for v, n in ((c1, "c1"), (c2, "c2"), (tilt, "tilt"), (bend, "bend")))
    a, b = positive_number(a, "a"), positive_number(b, "b")
    c, s = np.cos(tilt), np.sin(tilt)
    R = np.array([[c, -s], [s, c]])
    cos_c = np.array([[a, 0.0], [0.0, bend]])  # rows u, v; columns harmonics 1, 2
    sin_c = np.array([[0.0, 0.0], [b, 0.0]])
    return fourier_gait(R @ cos_c, R @ sin_c, (c1, c2), period=period, name="shaped gait")


@dataclass(frozen=True)
class Estimates:
    """The three answers (each (3,), rows x, y, θ) for the net displacement of one gait."""

    exact: np.ndarray
    stokes: np.ndarray
    body_velocity_integral: np.ndarray

    #: names of the three, in the order of :meth:`as_array`
    NAMES = ("exact g(T)", "Stokes ∬D(−A)", "∫ξ dt")

    def as_array(self) -> FloatArray:
        """(3 methods, 3 rows): exact, Stokes, body-velocity integral."""
        return np.array([self.exact, self.stokes, self.body_velocity_integral])


def displacement_estimates(system: LocomotionSystem, gait: GaitLike, *, interactive: bool = False) -> Estimates:
    """:class:`Estimates` of ``gait`` on ``system``: exact g(T) (``net_displacement``), the Stokes
    estimate and the body-velocity integral.

    ``interactive=False``: each at the library's refined accuracy. ``interactive=True``: at the
    fixed resolutions of :data:`INTERACTIVE` (a few milliseconds in all). A gait that meets a
    singular shape, or leaves the window where a reframed system is defined, raises
    :class:`~gm_core.SingularShapeError` (the gait is checked once, by the Stokes estimate).
    """
    if not isinstance(interactive, (bool, np.bool_)):
        raise TypeError(f"interactive must be True or False; got {interactive!r:.40}")
    if interactive:
        stokes = stokes_estimate(system, gait, samples=INTERACTIVE["stokes_samples"])  # checks the gait
        exact = net_displacement(system, gait, steps=INTERACTIVE["exact_steps"], check=False)
        bvi = body_velocity_integral(system, gait, samples=INTERACTIVE["bvi_samples"], check=False)
    else:
        stokes = stokes_estimate(system, gait)
        exact = net_displacement(system, gait, check=False)
        bvi = body_velocity_integral(system, gait, check=False)
    if not (np.all(np.isfinite(exact)) and np.all(np.isfinite(bvi))):
        raise SingularShapeError(f"the gait reaches a singular shape of {system.name}")
    return Estimates(np.asarray(exact, float), np.asarray(stokes, float), np.asarray(bvi, float))


def row_scaled(values: ArrayLike, floor: float = 0.05) -> FloatArray:
    """``values`` (k methods, m rows) divided row by row by the largest |value| of that row.

    A row whose values are all below ``floor`` times the largest value of any row is divided by
    that floor instead, so a row that is practically zero (2e-4 beside 0.27) stays practically
    zero rather than growing to full height. Every entry lies in [-1, 1].
    """
    vals = as_array(values, "values")
    if vals.ndim != 2 or 0 in vals.shape:
        raise ValueError(f"values must have shape (methods, rows), both at least 1; got shape {vals.shape}")
    floor = real_number(floor, "floor")
    if not 0 <= floor <= 1:
        raise ValueError(f"floor must lie in [0, 1]; got {floor!r}")
    top = np.abs(vals).max(axis=0)
    scale = np.maximum(top, floor * top.max())
    return vals / np.where(scale > 0, scale, 1.0)


def field_rms(system: LocomotionSystem, grid: ArrayLike) -> FloatArray:
    """Root-mean-square size (3,) of the rows x, y, θ of A over the shapes ``grid`` (..., 2).

    Row i contributes sqrt(mean over the grid of |A_i(r)|^2), |.| the Euclidean norm of the row
    (both columns); shapes where A is undefined are left out.
    """
    trusted_dimension(system)
    grid = as_array(grid, "grid", (system.n_shape,), what=f" (shapes of {system.name})")
    if grid.size == 0:
        raise ValueError("grid must hold at least one shape")
    A = np.asarray(system.connection(grid), dtype=float)
    sq = np.sum(A ** 2, axis=-1).reshape(-1, A.shape[-2])
    ok = np.isfinite(sq).all(axis=1)
    if not ok.any():
        raise SingularShapeError(f"the connection of {system.name} is undefined on the whole grid")
    return np.sqrt(sq[ok].mean(axis=0))


def square_grid(limits: Any, n: int) -> FloatArray:
    """Shapes (n, n, 2) at the nodes of an n x n grid over ``limits`` ((lo1, hi1), (lo2, hi2));
    index [j, i] = (alpha1_i, alpha2_j), the order of an image with origin "lower"."""
    (lo1, hi1), (lo2, hi2) = _limits(limits)
    n = check_int(n, "n", 2, 2001)
    a1, a2 = np.meshgrid(np.linspace(lo1, hi1, n), np.linspace(lo2, hi2, n))
    return np.stack([a1, a2], -1)


def _limits(limits):
    lim = as_array(limits, "limits", (2, 2), what=" (((lo1, hi1), (lo2, hi2)))")
    if not np.all(lim[:, 1] > lim[:, 0]):
        raise ValueError(f"limits must have lo < hi on both axes; got {lim.tolist()}")
    return tuple(tuple(map(float, row)) for row in lim)


def frames_of(system: LocomotionSystem, limits: Any, n: int = 33) -> Mapping[str, LocomotionSystem]:
    """The same system in the three :data:`FRAMES` (a read-only mapping), the minimum-perturbation
    frame solved over the rectangle ``limits`` with an n x n mesh; cached (about 0.5 s the first
    time for the swimmer, free after)."""
    return _frames(system, _limits(limits), check_int(n, "n", 5, 257))


@functools.lru_cache(maxsize=8)
def _frames(system, limits, n):
    trusted_dimension(system)
    return MappingProxyType(system.body_frames(limits, n=n))


def curvature_grid(system: LocomotionSystem, limits: Any, n: int) -> FloatArray:
    """Constraint curvature D(-A) (n, n, 3) on :func:`square_grid` (limits, n), cached and read-only."""
    return _curvature(system, _limits(limits), check_int(n, "n", 2, 2001))


@functools.lru_cache(maxsize=32)
def _curvature(system, limits, n):
    F = constraint_curvature(system, square_grid(limits, n))
    F.setflags(write=False)
    return F

"""Optimal order-2 strokes of low-Re chains of 3, 4 and 5 links of the same total length (numbers, not code).

Beyond the draft, after Ramasamy & Hatton (ACC 2017; T-RO 2019): for chains of N equal links of
total length 3, drag ratio 2, seen from the centre of mass with the mean orientation
(``LinkChain((3 / N,) * N, "low_re", frame="com")``), the Fourier gaits of order 2 that
maximise the efficiency (net translation per unit path length in the power metric), found by
:func:`gm_core.geometry.optimize_gait` (the best of runs from travelling-wave starts, slightly
perturbed so that they leave the symmetric saddle points).
tests/test_link_chain_geometry.py checks that each is stationary (the exact gradient vanishes)
and reproduces the stored efficiency and displacement.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from gm_core.geometry.optimal import FourierGait, OptimalGait, fourier_gait, optimize_gait, travelling_wave
from gm_core.systems import LinkChain
from gm_core.systems.base import LocomotionSystem
from gm_core.validation import check_int, positive_number

__all__ = ["CHAIN_STROKES", "chain_swimmer", "chain_stroke", "wave_start", "optimize_chain_gait"]

#: Fourier coefficients (a, b: (N - 1, 2); center: (N - 1,)) and the values they give.
CHAIN_STROKES: dict[int, dict[str, Any]] = {
    3: dict(a=[[1.25806291516, 0.240434185368],
              [0.139719183254, 0.328106592347]],
             b=[[-0.0800170633457, -0.303506727275],
              [1.25763164329, 0.193229900503]],
             center=[-0.180986781244, 0.25686376828],
             efficiency=0.063901, displacement=0.248430),
    4: dict(a=[[-0.0581281264027, 0.0727534620138],
              [-1.4435348234, 0.283605088077],
              [-0.0581569028356, 0.0727701178119]],
             b=[[1.01077025085, -0.236244456274],
              [2.19543216836e-05, -9.55024475503e-06],
              [-1.01076821416, 0.236240312658]],
             center=[-0.0269463715167, -0.368750881827, -0.0269444034496],
             efficiency=0.098861, displacement=0.352349),
    5: dict(a=[[0.660365154215, -0.00502753645253],
              [0.98440920793, 0.352977040816],
              [-0.304945423552, 0.0297932435022],
              [-0.961532571994, -0.280279254503]],
             b=[[-0.703312823065, -0.265475441777],
              [0.549824537546, 0.04720574121],
              [1.07117848445, 0.366453029927],
              [-0.03496892346, -0.0182396489586]],
             center=[-0.214882421511, -0.178075159779, 0.136784197238, 0.208385628518],
             efficiency=0.118703, displacement=0.402340),
}


def chain_swimmer(n_links: int, total_length: float = 3.0) -> LinkChain:
    """The swimmer of :data:`CHAIN_STROKES`: n_links equal links, drag ratio 2, centre-of-mass frame."""
    return LinkChain((total_length / n_links,) * n_links, "low_re", drag_ratio=2.0, frame="com")


def chain_stroke(n_links: int) -> FourierGait:
    """The stored optimal stroke for ``n_links`` (3, 4 or 5) links as a :func:`fourier_gait` (period 2 pi)."""
    if n_links not in CHAIN_STROKES:
        raise ValueError(f"n_links must be one of {sorted(CHAIN_STROKES)}; got {n_links!r}")
    c = CHAIN_STROKES[n_links]
    return fourier_gait(c["a"], c["b"], c["center"], name=f"optimal {n_links}-link stroke (efficiency, order 2)")


def wave_start(n_joints: int, amplitude: float = 0.6, lag: float = 0.8, *, spread: float = 0.05,
               seed: int = 0) -> FourierGait:
    """A start for optimising a chain's gait: the :func:`travelling_wave` (``amplitude``, ``lag``)
    with its Fourier coefficients nudged by a seeded normal ``spread``, so an optimisation leaves
    the symmetric saddle points a perfect wave can sit on (deterministic for a given ``seed``)."""
    w = travelling_wave(n_joints, amplitude, lag)
    spread = positive_number(spread, "spread", allow_zero=True, maximum=1.0)
    rng = np.random.default_rng(check_int(seed, "seed", minimum=0, maximum=2 ** 31))
    return fourier_gait(w.a + spread * rng.standard_normal(w.a.shape), w.b + spread * rng.standard_normal(w.b.shape),
                        name=f"start: wave, amplitude {amplitude:g}, lag {lag:g} rad")


def optimize_chain_gait(system: LocomotionSystem, order: int = 1, *, start: Any = None, maxiter: int = 40,
                        intervals: int = 64, callback: Callable[[int, float], Any] | None = None) -> OptimalGait:
    """The most efficient Fourier gait of ``order`` of a chain of any number of links, from
    :func:`wave_start` (or ``start``), measured in the chain's own body frame (use
    ``frame="com"``): :func:`optimize_gait` with ``objective="efficiency"``,
    ``coordinates="given"``. ``maxiter`` and ``intervals`` default to a live run of a second or
    so; ``callback(iteration, efficiency)`` reports progress. Returns the :class:`OptimalGait`."""
    start = wave_start(system.n_shape) if start is None else start
    return optimize_gait(system, "efficiency", order=order, start=start, coordinates="given", maxiter=maxiter,
                         intervals=intervals, callback=callback)

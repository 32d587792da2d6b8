"""Time the geometry of locomotion: curvature grids, Stokes estimates, coordinates and gait optimisation.

Run: .venv/bin/python benchmarks/geometry.py [--n 101] [--repeat 7]
Prints a table: the constraint curvature on an n x n grid of shapes for every system (target
<= 50 ms), one Stokes estimate, the minimum-perturbation coordinates of the low-Re swimmer, and
order-3 optimisations of sysplotter's low-Re swimmer from a circle (target <= 20 s) with the
values reached against sysplotter's strokes.
"""
from __future__ import annotations

import argparse
import time
import timeit

import numpy as np

from gm_core.geometry import (
    SYSPLOTTER_STROKES,
    constraint_curvature,
    minimum_perturbation_coordinates,
    optimize_gait,
    stokes_estimate,
    sysplotter_swimmer,
)
from gm_core.systems import ALL_SYSTEMS
from gm_core.systems.gaits import circle_gait


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=101, help="grid points per shape axis")
    p.add_argument("--repeat", type=int, default=7, help="timed repetitions (best and median shown)")
    args = p.parse_args(argv)
    print(f"constraint_curvature(system, grid) on a {args.n} x {args.n} grid, {args.repeat} runs")
    print(f"{'system':<20} {'best ms':>9} {'median ms':>10}  target <= 50 ms")
    for name, system in ALL_SYSTEMS.items():
        (lo1, hi1), (lo2, hi2) = system.shape_limits
        a, b = np.meshgrid(np.linspace(lo1, hi1, args.n), np.linspace(lo2, hi2, args.n), indexing="ij")
        grid = np.stack([a, b], -1)
        constraint_curvature(system, grid)
        t = np.array(timeit.repeat(lambda: constraint_curvature(system, grid), number=1, repeat=args.repeat)) * 1e3
        print(f"{name:<20} {t.min():9.2f} {np.median(t):10.2f}  {'ok' if t.min() <= 50 else 'SLOW'}")

    s = sysplotter_swimmer()
    g = circle_gait(1.0, (0.2, -0.1), period=2 * np.pi)
    t = min(timeit.repeat(lambda: stokes_estimate(s, g), number=1, repeat=3)) * 1e3
    print(f"\nstokes_estimate (low-Re swimmer, circle R = 1): {t:.1f} ms")
    t = min(timeit.repeat(lambda: stokes_estimate(s, g, samples=(64, 12)), number=1, repeat=5)) * 1e3
    print(f"stokes_estimate at the panels' fixed resolution samples=(64, 12): {t:.1f} ms")
    t = min(timeit.repeat(lambda: minimum_perturbation_coordinates(s, n=33), number=1, repeat=3)) * 1e3
    print(f"minimum_perturbation_coordinates (33 x 33 nodes):  {t:.1f} ms")

    print("\noptimize_gait(sysplotter's low-Re swimmer, order=3) from the unit circle; target <= 20 s")
    print(f"{'objective':<13} {'seconds':>8} {'iters':>6} {'value':>9} {'sysplotter':>11} {'ratio':>7}")
    for obj in ("displacement", "efficiency"):
        t0 = time.perf_counter()
        res = optimize_gait(s, obj, order=3)
        dt = time.perf_counter() - t0
        val = res.displacement if obj == "displacement" else res.efficiency
        ref = SYSPLOTTER_STROKES[obj][obj]
        print(f"{obj:<13} {dt:8.2f} {res.nit:6d} {val:9.5f} {ref:11.5f} {val / ref:7.4f}  "
              f"{'ok' if dt <= 20 else 'SLOW'}")


if __name__ == "__main__":
    main()

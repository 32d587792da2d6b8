"""Time the local connection of every chapter-3 system on a 101 x 101 grid of shapes.

Run: .venv/bin/python benchmarks/connection_grid.py [--n 101] [--repeat 15]
Prints one row per system: best and median wall time of one ``connection(grid)`` call, and how
many grid shapes are singular (NaN). The target is <= 20 ms per system.
"""
from __future__ import annotations

import argparse
import timeit

import numpy as np

from gm_core.systems import ALL_SYSTEMS


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--n", type=int, default=101, help="grid points per shape axis")
    p.add_argument("--repeat", type=int, default=15, help="timed repetitions (best and median shown)")
    args = p.parse_args(argv)
    print(f"connection(r) on a {args.n} x {args.n} grid of shapes ({args.n ** 2} shapes), "
          f"{args.repeat} runs")
    print(f"{'system':<20} {'best ms':>9} {'median ms':>10} {'singular':>9}  target <= 20 ms")
    for name, system in ALL_SYSTEMS.items():
        (lo1, hi1), (lo2, hi2) = system.shape_limits
        a, b = np.meshgrid(np.linspace(lo1, hi1, args.n), np.linspace(lo2, hi2, args.n), indexing="ij")
        grid = np.stack([a, b], -1)
        A = system.connection(grid)  # warm-up
        times = np.array(timeit.repeat(lambda: system.connection(grid), number=1, repeat=args.repeat)) * 1e3
        singular = int(np.isnan(A).any(axis=(-1, -2)).sum())
        ok = "ok" if times.min() <= 20 else "SLOW"
        print(f"{name:<20} {times.min():9.2f} {np.median(times):10.2f} {singular:9d}  {ok}")


if __name__ == "__main__":
    main()

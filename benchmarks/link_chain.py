"""Time chains of many links (gm_core.systems.LinkChain): connection, net displacement, gait optimisation.

Run: .venv/bin/python benchmarks/link_chain.py [--repeat 7] [--no-optimise]
Prints a table: the local connection of a five-link low-Re chain on 10^4 shapes (goal <= 100 ms),
its net displacement over one travelling-wave gait (goal <= 50 ms), the same for the continuous
slender body on 10^3 shapes, the three-link systems of chapter 3 (LinkChain with N = 3 since
issue 22; goal: no slower than their own closed forms were, ``--three-link`` also times one shape
and 100 shapes), and an order-2 optimisation of the five-link swimmer for efficiency from a circle
(goal <= 60 s), with the efficiency reached against the stored optimum.

Three-link connections before they became LinkChain (main at ee42752, closed forms) against the
chain kernels as they are now (walked out from the middle link, running sums link by link, the
kinematic snake's Pfaffian a batch-last view): process CPU time, best of 6 interleaved runs of
old and new (each the best of 15 repeats) on this shared, loaded 2-core machine (12/2026):

    system            10^4 shapes        100 shapes       1 shape
    kinematic snake   3.63 -> 2.11 ms    74 -> 68 us      46 -> 43 us
    low Re            7.31 -> 5.15 ms    190 -> 93 us     146 -> 64 us
    high Re           7.77 -> 5.22 ms    230 -> 93 us     178 -> 63 us
    floating snake    8.09 -> 6.30 ms    235 -> 162 us    168 -> 115 us

(The first chain kernel, before these changes, had made the kinematic snake about twice as slow
as its closed form: 2.2 -> 4-8 ms on 10^4 shapes, 53 -> 120 us on one; see issue 22.)
"""
from __future__ import annotations

import argparse
import time
import timeit

import numpy as np

from gm_core.geometry import CHAIN_STROKES, chain_swimmer, optimize_gait, travelling_wave
from gm_core.systems import FloatingSnake, HighReSwimmer, KinematicSnake, LinkChain, LowReSwimmer, SlenderBody
from gm_core.systems.motion import net_displacement


def _times(f, repeat):
    f()
    t = np.array(timeit.repeat(f, number=1, repeat=repeat)) * 1e3
    return t.min(), np.median(t)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeat", type=int, default=7, help="timed repetitions (best and median shown)")
    p.add_argument("--no-optimise", action="store_true", help="skip the optimisation (about a minute)")
    p.add_argument("--three-link", action="store_true", help="also time the three-link systems on 1 and 100 shapes")
    args = p.parse_args(argv)
    rng = np.random.default_rng(0)
    five = LinkChain((1.0,) * 5, "low_re")
    R = rng.uniform(-1.5, 1.5, (10_000, 4))
    wave = travelling_wave(4, 0.9, 1.2)
    body = SlenderBody(3.0)
    Rb = rng.uniform(-4, 4, (1_000, 2))
    rows = [
        ("connection, 5 links, 10^4 shapes", lambda: five.connection(R), 100.0),
        ("net_displacement, 5 links, one wave", lambda: net_displacement(five, wave), 50.0),
        ("connection, slender body, 10^3 shapes", lambda: body.connection(Rb), None),
        ("connection, 7 links (high Re), 10^4 shapes",
         lambda: LinkChain((1.0,) * 7, "high_re").connection(rng.uniform(-1, 1, (10_000, 6))), None),
    ]
    R3 = rng.uniform(-1.5, 1.5, (10_000, 2))
    for s3 in (LowReSwimmer(), HighReSwimmer(), FloatingSnake(), KinematicSnake()):
        rows.append((f"connection, {s3.name}, 10^4 shapes", (lambda s3=s3: s3.connection(R3)), None))
        if args.three_link:
            rows.append((f"connection, {s3.name}, 100 shapes", (lambda s3=s3: s3.connection(R3[:100])), None))
            rows.append((f"connection, {s3.name}, 1 shape", (lambda s3=s3: s3.connection(R3[0])), None))
    print(f"{'what':<44} {'best ms':>9} {'median ms':>10} {'goal ms':>8}")
    for name, f, goal in rows:
        best, med = _times(f, args.repeat)
        print(f"{name:<44} {best:9.1f} {med:10.1f} {'' if goal is None else f'{goal:8.0f}'}")
    if not args.no_optimise:
        s = chain_swimmer(5)
        t0 = time.perf_counter()
        res = optimize_gait(s, "efficiency", order=2, coordinates="given", maxiter=200, intervals=256)
        dt = time.perf_counter() - t0
        print(f"{'optimize_gait, 5 links, order 2 (efficiency)':<44} {dt * 1e3:9.0f} {'':>10} {60000:8.0f}")
        print(f"  efficiency {res.efficiency:.5f} (stored optimum {CHAIN_STROKES[5]['efficiency']:.5f}), "
              f"{res.nit} iterations, {res.message}")


if __name__ == "__main__":
    main()

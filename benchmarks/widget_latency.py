"""Slider-to-pixels latency of every registered Panel of the course, in process on Agg.

For each panel (all chapters: ``gm_core.widgets.base.all_panels()`` imports every widgets module,
so panels added later are picked up automatically) this script

1. builds the panel twice (one instance for in-place updates, one for the naive baseline);
2. draws ``--changes`` (default 50) simulated slider changes, drawn from the panel's own
   ``sample_values(rng)`` with a seeded generator, so both instances see the same values;
3. times *compute + draw* for each change. The course path is ``panel.refresh(**values)``,
   exactly what a slider change runs in a live notebook: ``update`` moves the artists, then the
   figure is refreshed by blitting (gm_core.drawing.toolkit.blit: cached background, only the moved
   artists redrawn; a full draw when limits change or new artists start moving). The baseline
   is ``naive_update(**values)`` (clear and re-plot everything) then ``fig.canvas.draw()``.
   ``--no-blit`` times ``update`` + a full ``canvas.draw()`` instead, to show what blitting adds.

Both paths end with the picture complete in the Agg buffer; turning that buffer into PNG bytes
for the browser is the same cost for both and is measured by benchmarks/browser_latency.py.

Prints a table (p50 and p95 of both, and the speed-up p50_naive / p50) and, as the last line,
``worst p95 = X ms`` over all panels. Goal for the course: worst p95 <= 30 ms and at least 3x
faster than the baseline.

Usage::

    .venv/bin/python benchmarks/widget_latency.py
    .venv/bin/python benchmarks/widget_latency.py --panels HelixPanel VelocityPanel
    .venv/bin/python benchmarks/widget_latency.py --clock cpu     # process CPU time (shared machines)
"""
from __future__ import annotations

import argparse
import gc
import os
import sys
import time
import traceback

os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib  # noqa: E402

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))

from gm_core.widgets.base import Panel, all_panels  # noqa: E402

CLOCKS = {"wall": time.perf_counter, "cpu": time.process_time}


def _silence_draw_idle(panel):
    panel.fig.canvas.draw_idle = lambda *args, **kwargs: None


def time_changes(panel, method, values, clock):
    """Seconds for each ``method(**v)`` (+ ``fig.canvas.draw()`` unless method is refresh)."""
    fn = getattr(panel, method)
    canvas = panel.fig.canvas
    draw = method != "refresh"
    out = np.empty(len(values))
    for i, v in enumerate(values):
        t0 = clock()
        fn(**v)
        if draw:
            canvas.draw()
        out[i] = clock() - t0
    return out


def bench_panel(cls, changes, seed, clock, blit=True):
    """Return dict(p50, p95, naive_p50, naive_p95, speedup) in milliseconds for one Panel class."""
    Panel.blit_everywhere = blit
    try:
        fast = cls()
    finally:
        Panel.blit_everywhere = False
    rng = np.random.default_rng(seed)
    values = [fast.sample_values(rng) for _ in range(changes)]
    naive = cls()
    try:
        for p in (fast, naive):
            p.fig.canvas.draw()  # the page load's first full draw
        if fast.blitter is None:
            _silence_draw_idle(fast)
        _silence_draw_idle(naive)
        gc.collect()
        t_fast = time_changes(fast, "refresh" if fast.blitter else "update", values, clock) * 1e3
        gc.collect()
        t_naive = time_changes(naive, "naive_update", values, clock) * 1e3
    finally:
        plt.close(fast.fig)
        plt.close(naive.fig)
    p50, p95 = np.percentile(t_fast, [50, 95])
    n50, n95 = np.percentile(t_naive, [50, 95])
    full = fast.blitter.full_draws - 1 if fast.blitter else changes
    return {"p50": p50, "p95": p95, "naive_p50": n50, "naive_p95": n95, "speedup": n50 / p50,
            "full": full}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--panels", nargs="+", metavar="NAME", help="only these Panel classes (default: all)")
    ap.add_argument("--changes", type=int, default=50, help="simulated slider changes per panel (50)")
    ap.add_argument("--seed", type=int, default=0, help="seed of the value generator (0)")
    ap.add_argument("--clock", choices=sorted(CLOCKS), default="wall",
                    help="wall: perf_counter (default); cpu: process time, steadier on a busy machine")
    ap.add_argument("--no-blit", action="store_true", help="time update + full draw (no blitting)")
    args = ap.parse_args(argv)

    registry = all_panels()
    names = sorted(registry) if not args.panels else args.panels
    unknown = [n for n in names if n not in registry]
    if unknown:
        ap.error(f"unknown panel(s) {unknown}; registered: {', '.join(sorted(registry))}")

    clock = CLOCKS[args.clock]
    header = (f"{'panel':<28} {'p50':>8} {'p95':>8} {'naive p50':>10} {'naive p95':>10} {'speed-up':>9}"
              f" {'full draws':>11}")
    how = "update + full canvas.draw()" if args.no_blit else "refresh (update + blit)"
    print(f"widget latency on Agg: {how} vs naive re-plot + draw; {args.changes} changes, {args.clock} clock, ms")
    print(header)
    print("-" * len(header))
    results, failed = {}, []
    for name in names:
        try:
            r = bench_panel(registry[name], args.changes, args.seed, clock, blit=not args.no_blit)
        except Exception:  # a broken panel must not hide the others' numbers
            failed.append(name)
            print(f"{name:<28} {'ERROR':>8}  (see stderr)")
            traceback.print_exc(file=sys.stderr)
            continue
        results[name] = r
        print(f"{name:<28} {r['p50']:8.1f} {r['p95']:8.1f} {r['naive_p50']:10.1f} {r['naive_p95']:10.1f}"
              f" {r['speedup']:8.1f}x {r['full']:>6d}/{args.changes}")
    print("-" * len(header))
    if results:
        slow = [n for n, r in results.items() if r["p95"] > 30.0]
        weak = [n for n, r in results.items() if r["speedup"] < 3.0]
        print(f"panels over 30 ms at p95: {', '.join(slow) or 'none'}")
        print(f"panels under 3x faster than naive: {', '.join(weak) or 'none'}")
    if failed:
        print(f"failed: {', '.join(failed)}")
    worst = max((r["p95"] for r in results.values()), default=float("nan"))
    print(f"worst p95 = {worst:.1f} ms")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

"""Switching latency of the locomotion lab (notebook 12) over every system it offers, in process on Agg.

For each of :func:`gm_core.drawing.catalog.lab_names` this script times, in process CPU time
(``time.process_time``: the machine may be shared), what a change of the lab's dropdown or sliders
runs: ``LabScene.set(**values)`` and a full ``fig.canvas.draw()`` (the lab never blits):

* ``first``: switching to the system for the first time (its table or slice, curvature grid and
  field computed; nothing cached for it yet);
* ``back``: switching away to three_link_lowRe and back to it (its grids cached);
* ``gait p50`` / ``gait p95``: ``--changes`` (default 8) changes of the gait sliders on it, from a
  seeded generator.

Prints one row per system, then p50 and p95 over all switches (first and back) and over all gait
changes, the figures of issue 37's budget (200 ms p95).

Usage::

    .venv/bin/python benchmarks/lab_latency.py
    .venv/bin/python benchmarks/lab_latency.py --changes 20 serpenoid_lowRe twin_rotor
"""
from __future__ import annotations

import argparse
import os
import sys
import time

os.environ.setdefault("MPLBACKEND", "Agg")

import matplotlib  # noqa: E402

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))

from gm_core.drawing.catalog import LabScene, lab_names  # noqa: E402

HOME = "three_link_lowRe"


def timed(scene: LabScene, values: dict) -> float:
    """Milliseconds of CPU time for ``scene.set(**values)`` and a full draw."""
    t0 = time.process_time()
    scene.set(**values)
    scene.fig.canvas.draw()
    return 1e3 * (time.process_time() - t0)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--changes", type=int, default=8, help="gait changes per system")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("names", nargs="*", help="systems to time (default: every one the lab offers)")
    args = parser.parse_args(argv)
    names = args.names or list(lab_names())
    rng = np.random.default_rng(args.seed)
    scene = LabScene(HOME)
    scene.fig.canvas.draw()
    gait = dict(c1=0.0, c2=0.0, a=0.5, b=0.3, tilt=0.78, phase=0.0)
    switches, changes = [], []
    print(f"{'system':36s} {'first':>8s} {'back':>8s} {'gait p50':>9s} {'gait p95':>9s}   (ms CPU)")
    for name in names:
        first = timed(scene, dict(gait, system=name))
        timed(scene, dict(gait, system=HOME))
        back = timed(scene, dict(gait, system=name))
        mine = [timed(scene, dict(system=name, c1=rng.uniform(-0.3, 0.3), c2=rng.uniform(-0.3, 0.3), a=rng.uniform(0.2, 0.6),
                                  b=rng.uniform(0.1, 0.4), tilt=rng.uniform(-1.5, 1.5), phase=rng.uniform()))
                for _ in range(args.changes)]
        switches += [first, back]
        changes += mine
        print(f"{name:36s} {first:8.0f} {back:8.0f} {np.percentile(mine, 50):9.0f} {np.percentile(mine, 95):9.0f}", flush=True)
    plt.close(scene.fig)
    print(f"switching ({len(switches)}):   p50 {np.percentile(switches, 50):.0f} ms, p95 {np.percentile(switches, 95):.0f} ms, "
          f"max {max(switches):.0f} ms")
    print(f"gait changes ({len(changes)}): p50 {np.percentile(changes, 50):.0f} ms, p95 {np.percentile(changes, 95):.0f} ms, "
          f"max {max(changes):.0f} ms")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

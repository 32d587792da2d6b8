"""Kernel CPU per slider move on ipympl's own canvas, the picture's PNG included, per panel.

benchmarks/widget_latency.py times update + blit on Agg; in a notebook the kernel then turns the
frame into PNG bytes (webagg's difference image: the whole canvas is compressed, unchanged
pixels transparent, so its cost grows with the canvas' area) and, after every comm message,
pyplot's ``draw_all`` asks the browser to redraw any figure the frame left stale (one more round
trip and full draw). Here each panel is built on ipympl's canvas in this process, as if its
browser view had opened; the canvas's two sending methods are replaced by counters (the stand-in
for the browser's connection). For each of ``--changes`` moves of the panel's first slider
(up and down by a fifth of its range) it records the process CPU time of the move, the bytes of
the picture sent, and whether ``draw_all`` would ask for another draw.

    .venv/bin/python benchmarks/frame_cost.py                              # every panel
    .venv/bin/python benchmarks/frame_cost.py --panels ChainSlicePanel GaitPanel

Prints: panel, slider, canvas, CPU ms (p50, p95) per move, PNG kB (p50), "stale": moves that
left the figure stale. A benchmark, not a test.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("module://ipympl.backend_nbagg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from gm_core.widgets.base import all_panels  # noqa: E402


def first_slider(panel):
    for key, c in panel.controls.items():
        if hasattr(c, "min") and hasattr(c, "max") and isinstance(c.value, (int, float)) \
                and not isinstance(c.value, bool) and not getattr(c, "disabled", False):
            return key, c
    return None, None


def measure(cls, changes):
    panel = cls()
    _ = panel.widget                           # the box a notebook shows
    canvas = panel.fig.canvas
    canvas.syncing_data_url = False            # the browser's view has said 'initialized'
    sent: list[int] = []
    canvas.send_binary = lambda data: sent.append(len(data))   # the browser's connection
    canvas.send_json = lambda content: None
    canvas.draw()
    key, c = first_slider(panel)
    if key is None:
        plt.close(panel.fig)
        return None
    lo, hi = float(c.min), float(c.max)
    step = (hi - lo) / 5
    cpu, size, stale = [], [], 0
    v = float(c.value)
    for i in range(changes):
        v = v + step if (i // 4) % 2 == 0 else v - step
        v = min(max(v, lo), hi)
        value = type(c.value)(round(v)) if isinstance(c.value, int) else v
        if value == c.value:
            step = -step
            continue
        sent.clear()
        t0 = time.process_time()
        c.value = value
        cpu.append(time.process_time() - t0)
        size.append(sum(sent))
        stale += bool(panel.fig.stale)
    w, h = canvas.get_width_height()
    plt.close(panel.fig)
    return key, f"{w}x{h}", np.array(cpu) * 1e3, np.array(size) / 1e3, stale


def main(argv=None):
    ap = argparse.ArgumentParser(description=(__doc__ or "").split("\n")[0])
    ap.add_argument("--panels", nargs="+", metavar="NAME", help="only these Panel classes (default: all)")
    ap.add_argument("--changes", type=int, default=24, help="slider moves per panel (24)")
    args = ap.parse_args(argv)
    registry = all_panels()
    names = args.panels or sorted(registry)
    unknown = [n for n in names if n not in registry]
    if unknown:
        ap.error(f"unknown panel(s) {unknown}; registered: {', '.join(sorted(registry))}")
    head = f"{'panel':<28} {'slider':<12} {'canvas':>8} {'cpu p50':>8} {'cpu p95':>8} {'png kB':>7} {'stale':>6}"
    print("kernel CPU per slider move on ipympl's canvas (update, blit, PNG), ms")
    print(head)
    print("-" * len(head))
    for name in names:
        r = measure(registry[name], args.changes)
        if r is None or not len(r[2]):
            print(f"{name:<28} (no slider)")
            continue
        key, canvas, cpu, kb, stale = r
        print(f"{name:<28} {key[:12]:<12} {canvas:>8} {np.median(cpu):8.1f} {np.percentile(cpu, 95):8.1f}"
              f" {np.median(kb):7.1f} {stale:>3d}/{len(cpu)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Write the stored tables of the local connection that the locomotion lab interpolates (gm_core/systems/lab_tables.npz).

As sysplotter does, each table holds A (3, 2, n1, n2) at the nodes of a grid spanning the
file's window (``catalog.sysplotter_files()[name].grid_range``), on the two-shape view the lab uses
(:func:`gm_core.systems.catalog.window_slice`); :func:`gm_core.systems.catalog.tabulated` interpolates it
with bicubic splines. After computing a table the tool checks it against the live system at cell
centres (where interpolation is worst) and refuses to write one that misses
:data:`gm_core.systems.catalog.TABLE_RTOL`.

The systems tabulated (:data:`DEFAULT`) are those whose one gait's numbers cost the live system more
than the lab's budget of 200 ms: the continuous bodies, the panel-method chain and the tape measures
(a second or more) and the chains of 19 links or more (benchmarks/lab_latency.py: 40 to 140 ms for the
numbers alone, and their first switch 0.5 to 1.8 s for the curvature grid: over budget with the drawing).

Usage (options before names)::

    .venv/bin/python tools/lab_tables.py                      # every system of DEFAULT (about 3 minutes)
    .venv/bin/python tools/lab_tables.py serpenoid_lowRe      # only these, the others kept as stored
    .venv/bin/python tools/lab_tables.py --check-only         # compare the stored tables with the live systems
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from gm_core.systems import catalog  # noqa: E402
from gm_core.systems.tabulated import TabulatedConnection  # noqa: E402

OUT = ROOT / "gm_core" / "systems" / catalog.TABLES

#: The systems the lab reads from a table (see the module docstring), in the catalog's order.
DEFAULT = ("asymmetricTapeMeasure", "constantcurv2_lowRe", "constantcurv3_lowRe", "constantcurv4_lowRe", "fishTail_HighRe_tapered",
           "five_mode_CC", "four_mode_CC", "four_mode_serpenoid", "serpenoid4_lowRe", "serpenoid_lowRe", "serpenoid_lowRe_hf",
           "serpenoid_lowRe_hf_AmpPhase", "symmetricTapeMeasure", "three_link_HighRe_30multiEllipses", "three_link_HighRe_panelMethod",
           "three_mode_CC", "triangle_lowRe", "triangle_lowRe_two_waves", "two_mode_CC", "two_mode_serpenoid")

#: Nodes per axis (n1, n2) where 25 x 25 misses the tolerance: the symmetric tape measure's connection
#: rises within 0.1 rad of alpha = 0; the fish tail and the two-wave bodies vary fastest across their windows.
SIZES = {"symmetricTapeMeasure": (161, 25), "fishTail_HighRe_tapered": (41, 41), "serpenoid_lowRe_hf": (41, 41),
         "serpenoid_lowRe_hf_AmpPhase": (57, 57), "triangle_lowRe": (40, 40), "triangle_lowRe_two_waves": (40, 40)}

#: The triangle waves' connection has no limit at the straight shape (it depends on the direction of
#: approach; the live system gives NaN there): their nodes crowd towards it (x = h sinh(k u) / sinh(k),
#: u uniform in [-1, 1], k = 3, an even count so that no node sits on it), and the check leaves out
#: :data:`gm_core.systems.catalog.TABLE_EXCLUDED`'s disc around it.
CLUSTERED = {"triangle_lowRe": 3.0, "triangle_lowRe_two_waves": 3.0}

#: Cell centres at which a new table is checked against the live system.
CHECKS = 48


def grid_axes(name: str, size: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """The table's node values along each shape axis: ``size`` points spanning the file's window
    (evenly, or crowding towards its middle for the systems of :data:`CLUSTERED`)."""
    k = CLUSTERED.get(name, 0.0)
    axes = []
    for (lo, hi), n in zip(catalog.sysplotter_files()[name].grid_range[:2], size):
        u = np.linspace(-1.0, 1.0, n)
        x = np.sinh(k * u) / np.sinh(k) if k else u
        axes.append(np.clip((lo + hi) / 2 + (hi - lo) / 2 * x, lo, hi))
    return axes[0], axes[1]


def table(name: str, size: tuple[int, int] | None = None) -> dict[str, np.ndarray]:
    """The stored arrays of ``name``: A (3, 2, n1, n2) of :func:`~gm_core.systems.catalog.window_slice` at the
    grid's nodes (float32) under ``name``, the nodes under ``name/alpha1`` and ``name/alpha2``."""
    a1, a2 = grid_axes(name, size or SIZES.get(name, (25, 25)))
    nodes = np.stack(np.meshgrid(a1, a2, indexing="ij"), -1)
    A = catalog.window_slice(name).connection(nodes)                     # (n1, n2, 3, 2)
    return {name: np.moveaxis(A, (0, 1), (2, 3)).astype(np.float32), f"{name}/alpha1": a1, f"{name}/alpha2": a2}


def table_error(name: str, arrays: dict[str, np.ndarray], checks: int = CHECKS, seed: int = 0) -> float:
    """max |interpolated - live| / max |live at the nodes| over ``checks`` cell centres chosen with ``seed``,
    leaving out those within :data:`~gm_core.systems.catalog.TABLE_EXCLUDED` of the straight shape."""
    T, a1, a2 = arrays[name], arrays[f"{name}/alpha1"], arrays[f"{name}/alpha2"]
    tab = TabulatedConnection((a1, a2), T, method="cubic")
    rng = np.random.default_rng(seed)
    i, j = rng.integers(0, a1.size - 1, checks), rng.integers(0, a2.size - 1, checks)
    centres = np.stack([(a1[i] + a1[i + 1]) / 2, (a2[j] + a2[j + 1]) / 2], -1)
    centres = centres[np.hypot(*centres.T) > catalog.TABLE_EXCLUDED.get(name, -1.0)]
    live = catalog.window_slice(name).connection(centres)
    return float(np.abs(tab.connection(centres) - live).max() / np.abs(T).max())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--check-only", action="store_true", help="compare the stored tables with the live systems, write nothing")
    parser.add_argument("names", nargs="*", help=f"systems to (re)tabulate (default: all {len(DEFAULT)} of DEFAULT)")
    args = parser.parse_args(argv)
    names = args.names or list(DEFAULT)
    unknown = [n for n in names if n not in catalog.names()]
    if unknown:
        parser.error(f"not catalog names: {', '.join(unknown)}")
    stored: dict[str, np.ndarray] = {}
    if OUT.exists():
        with np.load(OUT) as data:
            stored = {k: data[k] for k in data.files}
    worst, failed = 0.0, []
    for name in names:
        t0 = time.perf_counter()
        arrays = {k: v for k, v in stored.items() if k.split("/")[0] == name} if args.check_only else table(name)
        err = table_error(name, arrays)
        worst = max(worst, err)
        n1, n2 = arrays[name].shape[2:]
        print(f"{name:36s} {n1:4d} x {n2:<4d} error {err:.1e}  ({time.perf_counter() - t0:.1f} s)", flush=True)
        if err > catalog.TABLE_RTOL:
            print(f"  {name}: {err:.1e} > TABLE_RTOL {catalog.TABLE_RTOL:g}: not written; add nodes in SIZES", file=sys.stderr)
            failed.append(name)
            continue
        stored.update(arrays)
    if not args.check_only:
        savez: Any = np.savez_compressed          # its stubs read ** as the allow_pickle flag
        savez(OUT, **dict(sorted(stored.items())))
        print(f"wrote {OUT.relative_to(ROOT)} ({OUT.stat().st_size // 1024} KB, {len(stored) // 3} tables); worst error {worst:.1e}")
    return 1 if failed else 0


if __name__ == "__main__":
    raise SystemExit(main())

"""How long does a student wait for Run All? (goal: every notebook in at most 30 s on a quiet machine)

Executes each notebook top to bottom in a fresh kernel (nbclient), one after the other (never in
parallel: the machine is shared), exactly as a student's Run All would: no test mode, so
animations have all their frames and optimisers run to the end. The kernel imports this checkout's
gm_core (PYTHONPATH is set to the repository root). Prints one row per notebook: wall time of
Run All (kernel start excluded), the CPU time the kernel used meanwhile (on a loaded machine the
wall time grows with the load but the CPU time does not: it is close to what a quiet machine's
wall time would be), the slowest cells, and whether the goal was met (judged on the smaller of
the two times).

    .venv/bin/python benchmarks/notebook_times.py                      # every notebook in book/
    .venv/bin/python benchmarks/notebook_times.py book/09-*.ipynb       # some notebooks
    .venv/bin/python benchmarks/notebook_times.py --cells 5 book/10-*.ipynb   # 5 slowest cells each

The script lowers its own priority (nice 10) so that it disturbs the other users of the machine
as little as possible; times on a loaded machine are longer than a student's.
"""
from __future__ import annotations

import argparse
import os
import sys
import time
from datetime import datetime
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
GOAL_S = 30.0


def _seconds(cell):
    """Execution time of one executed code cell, from nbclient's timing metadata (None if absent)."""
    ex = cell.get("metadata", {}).get("execution", {})
    try:
        start = datetime.fromisoformat(ex["iopub.execute_input"].replace("Z", "+00:00"))
        end = datetime.fromisoformat(ex["shell.execute_reply"].replace("Z", "+00:00"))
    except (KeyError, ValueError):
        return None
    return (end - start).total_seconds()


_CPU = ("import resource as _r; _u = _r.getrusage(_r.RUSAGE_SELF); _c = _r.getrusage(_r.RUSAGE_CHILDREN); "
        "print(_u.ru_utime + _u.ru_stime + _c.ru_utime + _c.ru_stime)")


def _kernel_cpu(client, nb):
    """CPU seconds the kernel (and its children) has used so far, from a cell added to the end of
    ``nb`` for the moment (nbclient stores each executed cell at its index) and removed again."""
    import nbformat

    cell = nbformat.v4.new_code_cell(_CPU)
    nb.cells.append(cell)
    try:
        client.execute_cell(cell, len(nb.cells) - 1)
    finally:
        nb.cells.pop()
    text = "".join(o.get("text", "") for o in cell.outputs if o.get("name") == "stdout")
    return float(text.strip().splitlines()[-1])


def run(path: Path, timeout: float = 600.0):
    """(wall s, kernel CPU s, [(seconds, cell index, first line)], error or None) of Run All of one notebook."""
    import nbformat
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    env_path = os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep)
    os.environ["PYTHONPATH"] = env_path
    os.environ.pop("GM_COURSE_TESTING", None)    # a student's run, not the test suite's
    client = NotebookClient(nb, timeout=timeout, kernel_name="python3", allow_errors=False,
                            record_timing=True, resources={"metadata": {"path": str(path.parent)}})
    error = None
    with client.setup_kernel():
        cpu0 = _kernel_cpu(client, nb)
        t0 = time.perf_counter()
        try:
            for index, cell in enumerate(nb.cells):
                client.execute_cell(cell, index)
        except Exception as e:  # noqa: BLE001 - reported in the table, not raised
            error = f"{type(e).__name__} in cell {index}"
        wall = time.perf_counter() - t0
        cpu = _kernel_cpu(client, nb) - cpu0
    cells = []
    for i, c in enumerate(nb.cells):
        if c.cell_type == "code":
            s = _seconds(c)
            if s is not None:
                first = next((ln for ln in c.source.splitlines() if ln.strip() and not ln.startswith("%")), "")
                cells.append((s, i, first[:40]))
    cells.sort(reverse=True)
    return wall, cpu, cells, error


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("notebooks", nargs="*", type=Path)
    parser.add_argument("--cells", type=int, default=1, help="how many of the slowest cells to list")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per cell")
    args = parser.parse_args(argv)
    try:
        os.nice(10)
    except OSError:
        pass
    paths = args.notebooks or sorted((ROOT / "book").glob("[0-9][0-9]-*.ipynb"))
    try:
        load = os.getloadavg()[0]
    except OSError:
        load = float("nan")
    print(f"Run All of each notebook in a fresh kernel, one at a time (goal {GOAL_S:.0f} s); "
          f"load average at start {load:.2f}")
    print(f"{'notebook':<40} {'wall s':>7} {'CPU s':>7}  {'ok':<4} slowest cells (wall s, [cell] first line)")
    total = total_cpu = 0.0
    for p in paths:
        wall, cpu, cells, error = run(p.resolve(), args.timeout)
        total, total_cpu = total + wall, total_cpu + cpu
        ok = "ERR" if error else ("yes" if min(wall, cpu) <= GOAL_S else "NO")
        slow = "; ".join(f"{s:.1f} [{i}] {line}" for s, i, line in cells[: args.cells])
        print(f"{p.name:<40} {wall:7.1f} {cpu:7.1f}  {ok:<4} {error or slow}", flush=True)
    print(f"{'total':<40} {total:7.1f} {total_cpu:7.1f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

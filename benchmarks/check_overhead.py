"""What the checkers' safety costs: the probe sandbox's round trip and the progress record.

Rows: one ``collect()`` of a trivial probe (fork a keeper in its own session, fork the worker,
read the result, kill the tree); ``check()`` of a multiple-choice part (1.1a) and of a function
part with 14 probes (1.4a), with progress in memory and in a workspace (file lock, fsynced atomic
write); one progress update in a workspace, alone and with three processes updating at once.
Medians over ``--repeat`` runs, in this kernel with numpy, scipy, matplotlib and sympy loaded
(a fork copies the page tables of all of that).

    .venv/bin/python benchmarks/check_overhead.py [--repeat 20] [--root DIR]

``--root`` measures another checkout's gm_core (e.g. ``git archive <commit> gm_core | tar -x -C
/tmp/old`` and ``--root /tmp/old``), to compare before and after a change.
"""
from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def median_ms(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return 1000 * statistics.median(times)


def concurrent_updates(root, ws, n=3, per=100):
    code = ("import sys\nfrom gm_core.checks import store\n"
            f"for i in range({per}): store.record('9.%s' % sys.argv[1], 'p%d' % i, 'passed')\n")
    env = dict(os.environ, PYTHONPATH=str(root), GM_COURSE_WORKSPACE=str(ws))
    t = time.perf_counter()
    procs = [subprocess.Popen([sys.executable, "-c", code, str(w)], env=env) for w in range(n)]
    for p in procs:
        p.wait()
    return n * per / (time.perf_counter() - t)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=20)
    ap.add_argument("--root", type=Path, default=ROOT, help="the checkout whose gm_core to measure")
    args = ap.parse_args(argv)
    root = args.root.resolve()
    sys.path.insert(0, str(root))
    import matplotlib.pyplot  # noqa: F401 - a kernel's usual load
    import scipy.linalg  # noqa: F401
    import sympy  # noqa: F401

    from gm_core import checks
    from gm_core.checks import store
    from gm_core.checks.sandbox import collect
    print(f"gm_core from {Path(checks.__file__).parents[2]}")
    r = args.repeat
    a, f = checks.ex1_1.a, checks.ex1_4.a
    rows = [("collect(), one trivial probe", median_ms(lambda: collect(1, [lambda x: x]), r))]
    os.environ.pop("GM_COURSE_WORKSPACE", None)
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        rows += [("check() 1.1a, progress in memory", median_ms(lambda: a.check("b", quiet=True), r)),
                 ("check() 1.4a, progress in memory", median_ms(lambda: f.check(f.reference, quiet=True), r))]
        ws = Path(tmp) / "workspace"
        ws.mkdir()
        (ws / store.MANIFEST).write_text("{}")
        os.environ["GM_COURSE_WORKSPACE"] = str(ws)
        rows += [("check() 1.1a, progress in a workspace", median_ms(lambda: a.check("b", quiet=True), r)),
                 ("check() 1.4a, progress in a workspace", median_ms(lambda: f.check(f.reference, quiet=True), r)),
                 ("one progress update (lock, read, fsync, rename)",
                  median_ms(lambda: store.record("9.9", "a", "passed"), r))]
        rate = concurrent_updates(root, ws)
        os.environ.pop("GM_COURSE_WORKSPACE")
        os.chdir(ROOT)
    width = max(len(n) for n, _ in rows)
    print(f"{'what':<{width}}  median ms")
    for name, ms in rows:
        print(f"{name:<{width}}  {ms:9.1f}")
    print(f"{'3 processes x 100 updates at once (incl. start-up)':<{width}}  {rate:9.0f} updates/s")


if __name__ == "__main__":
    main()

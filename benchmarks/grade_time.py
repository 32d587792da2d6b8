"""What grading one notebook costs: kernel start, cells, the grader's own calls, CPU, with and
without the sandbox.

For each solution notebook named on the command line (default: three small ones), it is graded
once in the bubblewrap sandbox and once without (``--no-sandbox`` mode), as the grader does: the
notebook's run, then the grader's calls of its checked answers in a second sandbox
(:mod:`gm_grader.probe`). The table gives the seconds from the runner's start to a live kernel,
the seconds the cells took, the seconds of the calls' run and its share of the whole (the number to
compare: the seconds move with the machine's load) and the parts credited (all of them, for a
solution).

    .venv/bin/python benchmarks/grade_time.py
    .venv/bin/python benchmarks/grade_time.py solutions/ex1_4.ipynb solutions/ex3_1.ipynb
"""
from __future__ import annotations

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from gm_core.checks import channel  # noqa: E402
from gm_core.checks.exercise import REGISTRY  # noqa: E402
from gm_core.checks.protocol import Limits, RecordKind  # noqa: E402
from gm_grader import probe  # noqa: E402
from gm_grader.batch import identify  # noqa: E402
from gm_grader.evidence import collect, decide, summarise  # noqa: E402
from gm_grader.isolate import run_submission, sandbox_problem  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("notebooks", nargs="*", type=Path, default=[
        ROOT / "solutions" / n for n in ("ex1_1.ipynb", "ex1_2.ipynb", "ex3_1.ipynb")])
    args = ap.parse_args(argv)
    modes = [("no sandbox", False)] + ([("sandbox", True)] if sandbox_problem() is None else [])
    print(f"{'notebook':<14} {'mode':<11} {'kernel s':>9} {'cells s':>8} {'calls s':>8} "
          f"{'calls/all':>9} {'credited':>9}")
    for nb in args.notebooks:
        ex_id, _, data = identify(nb)
        ex = REGISTRY[ex_id]
        for label, sandbox in modes:
            t = time.monotonic()
            run = run_submission(nb, limits=Limits(), sandbox=sandbox)
            notebook_s = time.monotonic() - t
            calls_nb = probe.notebook(ex.id, collect(run, ex).answers())
            with tempfile.TemporaryDirectory() as tmp:
                path = Path(tmp) / "calls.ipynb"
                path.write_text(json.dumps(calls_nb))
                t = time.monotonic()
                calls = run_submission(path, limits=Limits(), sandbox=sandbox)
                calls_s = time.monotonic() - t
            at = {r.kind: r.at for r in run.records}
            verdicts = decide(ex, summarise(run, ex, {}, judge=False), _judged(calls, ex)).parts
            got = sum(r.verdict.passed for r in verdicts.values())
            kernel = at.get(RecordKind.KERNEL, float("nan"))
            cells = at.get(RecordKind.DONE, float("nan")) - kernel
            print(f"{nb.name:<14} {label:<11} {kernel:9.1f} {cells:8.1f} {calls_s:8.1f} "
                  f"{calls_s / (notebook_s + calls_s):9.2f} {got:>4}/{len(verdicts):<4}")
    return 0


def _judged(run, ex):
    channel.set_probe_salt(run.salt)
    try:
        return summarise(run, ex, {})
    finally:
        channel.set_probe_salt(None)


if __name__ == "__main__":
    sys.exit(main())

"""How long does `make test` take, phase by phase? (goal: the whole course in <= 180 s after set-up)

`make test` is one `pytest` run over tests/, book/, exercises/ and solutions/ (see pyproject.toml).
This script runs the same tests as separate pytest subprocesses, one per phase, one after the
other (never in parallel: the machine is shared), and prints the wall time and the pytest
summary of each:

    set-up      make setup (nothing to do when .venv is up to date; not counted in the total)
    unit        pytest tests -m "not browser"
    notebooks   pytest book exercises solutions          (nbval runs every notebook)
    browser     pytest tests/browser -m browser          (JupyterLab + headless Chromium)

    .venv/bin/python benchmarks/suite_time.py             # all phases
    .venv/bin/python benchmarks/suite_time.py unit browser
    .venv/bin/python benchmarks/suite_time.py --make      # also time one real `make test`

The phases' sum is close to one `make test` but not equal: each phase starts pytest and imports
its plugins once more, while `make test` shares one collection (use --make to see both).
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PY = sys.executable
GOAL_S = 180.0

PHASES = {
    "unit": [PY, "-m", "pytest", "tests", "-m", "not browser", "-q"],
    "notebooks": [PY, "-m", "pytest", "book", "exercises", "solutions", "-q"],
    # tests/browser only: collecting all of tests/ again would count the unit tests' import time twice
    "browser": [PY, "-m", "pytest", "tests/browser", "-m", "browser", "-q"],
}
SUMMARY = re.compile(r"^=*\s*((?:\d+ \w+(?:, )?)+) in [\d.]+s", re.M)
COUNTS = re.compile(r"(\d+) (passed|failed|errors?|skipped|deselected|xfailed|xpassed|warnings?)")


def run(cmd, log):
    t0 = time.monotonic()
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                       env={**os.environ, "PYTHONDONTWRITEBYTECODE": "1"})
    dt = time.monotonic() - t0
    log.write(f"$ {' '.join(cmd)}\n{p.stdout}\n")
    m = SUMMARY.findall(p.stdout)
    summary = m[-1] if m else (p.stdout.strip().splitlines() or ["(no output)"])[-1][:60]
    counts = {k.rstrip("s") if k.startswith(("error", "warning")) else k: int(n) for n, k in COUNTS.findall(summary)}
    return dt, p.returncode, summary, counts


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("phases", nargs="*", metavar="phase",
                    help=f"phases to time, any of {', '.join(PHASES)} (default: all)")
    ap.add_argument("--make", action="store_true", help="also time one full `make test` at the end")
    ap.add_argument("--log", default=str(ROOT / "benchmarks" / "results" / "suite_time.log"),
                    help="where the pytest output goes (default benchmarks/results/, git-ignored)")
    args = ap.parse_args(argv)
    phases = args.phases or list(PHASES)
    unknown = [p for p in phases if p not in PHASES]
    if unknown:
        ap.error(f"unknown phase(s) {unknown}; choose from {list(PHASES)}")
    Path(args.log).parent.mkdir(parents=True, exist_ok=True)
    rows = []
    with open(args.log, "w") as log:
        dt, rc, _, _ = run(["make", "setup"], log)
        rows.append(("set-up", "make setup", dt, rc, "(not counted)", {}))
        for name in phases:
            print(f"  running {name} ...", file=sys.stderr, flush=True)
            dt, rc, summary, counts = run(PHASES[name], log)
            rows.append((name, " ".join(c if c != PY else "python" for c in PHASES[name]), dt, rc, summary, counts))
        if args.make:
            print("  running make test ...", file=sys.stderr, flush=True)
            dt, rc, summary, counts = run(["make", "test"], log)
            rows.append(("make test", "make test (one pytest run)", dt, rc, summary, counts))

    print(f"\n`make test` by phase (sequential pytest runs; output in {args.log})\n")
    hdr = f"{'phase':<10} {'wall s':>7}  {'rc':>2}  {'summary':<44} command"
    print(hdr)
    print("-" * (len(hdr) + 30))
    for name, cmd, dt, rc, summary, _ in rows:
        print(f"{name:<10} {dt:>7.1f}  {rc:>2}  {summary[:44]:<44} {cmd}")
    total = sum(dt for name, _, dt, _, _, _ in rows if name in PHASES)
    print("-" * (len(hdr) + 30))
    verdict = "within" if total <= GOAL_S else "OVER"
    print(f"{'total':<10} {total:>7.1f}  (phases {', '.join(phases)}; goal <= {GOAL_S:.0f} s after set-up: {verdict})")
    failed = [name for name, _, _, rc, _, _ in rows if rc not in (0, 5)]  # 5 = no tests collected
    if failed:
        print(f"failing phases: {', '.join(failed)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

"""The harness's own rules (tests/conftest.py): under CI=true a test skipped because bubblewrap or
Chromium is missing fails instead; elsewhere it skips, saying what is missing."""
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SELF = "tests/test_harness.py::test_a_missing_bubblewrap_fails_under_ci_and_skips_elsewhere"


def _run(ci):
    env = {k: v for k, v in os.environ.items() if k != "CI"}
    env.update(GM_HARNESS_SELFTEST="1", **({"CI": "true"} if ci else {}))
    return subprocess.run([sys.executable, "-m", "pytest", SELF, "-q", "-p", "no:xdist",
                           "-p", "no:randomly"], cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)


def test_a_missing_bubblewrap_fails_under_ci_and_skips_elsewhere():
    if os.environ.get("GM_HARNESS_SELFTEST"):
        pytest.skip("bubblewrap is not installed (the harness's self-test)")
    res = _run(ci=True)
    assert res.returncode == 1 and "1 failed" in res.stdout, res.stdout[-2000:]
    assert "CI=true, where this test must run, but:" in res.stdout
    res = _run(ci=False)
    assert res.returncode == 0 and "1 skipped" in res.stdout, res.stdout[-2000:]

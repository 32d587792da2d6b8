"""Shared fixtures for the unit tests."""
import sys

import pytest


@pytest.fixture(autouse=True)
def _close_figures():
    """Close every matplotlib figure a test opened (panels create figures through pyplot)."""
    yield
    if "matplotlib.pyplot" in sys.modules:
        sys.modules["matplotlib.pyplot"].close("all")


@pytest.fixture
def clean(monkeypatch, tmp_path):
    """A fresh, in-memory checker progress record for one test (no workspace in sight).

    The kernel's working directory is moved to an empty temporary folder and
    GM_COURSE_WORKSPACE is cleared, so nothing reads or writes a real workspace/.progress.json.
    """
    from gm_core.checks import reset_progress

    monkeypatch.delenv("GM_COURSE_WORKSPACE", raising=False)
    monkeypatch.chdir(tmp_path)
    reset_progress()
    yield
    reset_progress()

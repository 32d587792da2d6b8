"""Root pytest configuration: test-mode flag for notebooks, a headless matplotlib backend, and
every course notebook a test item, executed once per run for every test that reads it
(tests/nbrun.py)."""
import os
import sys
from pathlib import Path

import pytest

# Notebooks and drawing code shorten animations when this is set (gm_core.drawing.testing()).
os.environ["GM_COURSE_TESTING"] = "1"
# Unit tests draw off-screen; notebooks choose their own backend with %matplotlib widget.
os.environ.setdefault("MPLBACKEND", "Agg")
# One BLAS thread per process (set before numpy loads; inherited by the xdist workers, the
# notebooks' and JupyterLab's kernels and every subprocess): the workers already keep every core
# busy, and extra BLAS threads would only compete with them. The results are the same.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
sys.path.insert(0, str(Path(__file__).resolve().parent / "tests"))
import nbrun  # noqa: E402


def pytest_configure(config):
    nbrun.configure(config)


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node):
    """pytest-xdist: every worker writes into the controller's run folder."""
    nbrun.configure_node(node)


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(items):
    nbrun.default_groups(items)


def pytest_collect_file(file_path, parent):
    return nbrun.collect(file_path, parent)


def pytest_runtest_logreport(report):
    nbrun.logreport(report)


def pytest_sessionfinish(session):
    nbrun.session_finish(session.config)

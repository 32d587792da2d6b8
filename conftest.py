"""Root pytest configuration: test-mode flag for notebooks, a headless matplotlib backend, and the
plumbing that makes nbval's one execution of every notebook the record every other test reads
(tests/nbrun.py)."""
import os
import sys
from pathlib import Path

import pytest

# Notebooks and drawing code shorten animations when this is set (gm_core.drawing.testing()).
os.environ["GM_COURSE_TESTING"] = "1"
# Unit tests draw off-screen; notebooks choose their own backend with %matplotlib widget.
os.environ.setdefault("MPLBACKEND", "Agg")
# One BLAS thread per process (set before numpy loads; inherited by the xdist workers, nbval's and
# JupyterLab's kernels and every subprocess): the suite already keeps both cores busy with its
# workers, and OpenBLAS's extra threads only fight them (small-matrix routines such as logm ran
# 10-100x slower on two loaded cores). The results are the same.
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
sys.path.insert(0, str(Path(__file__).resolve().parent / "tests"))
import nbrun  # noqa: E402


def pytest_configure(config):
    nbval_defaults(config)
    nbrun.configure(config)


def nbval_defaults(config):
    """nbval's settings for the course (unless given on the command line): lax (outputs compared
    only in cells marked NBVAL_CHECK_OUTPUT), the current environment's kernel, the sanitizers."""
    if not config.pluginmanager.hasplugin("nbval"):
        return
    o = config.option
    if not o.nbval:
        o.nbval_lax = True
    o.nbval_current_env = o.nbval_current_env or not o.nbval_kernel_name
    if o.nbval_sanitize_with is None:
        o.nbval_sanitize_with = str(Path(__file__).resolve().parent / "tests" / "nbval_sanitize.cfg")
    if o.nbval_cell_timeout == 2000:   # nbval's default
        o.nbval_cell_timeout = 300


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node):
    """pytest-xdist: every worker writes into the controller's run folder."""
    nbrun.configure_node(node)


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    return nbrun.make_scheduler(config, log)


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    nbrun.modify_items(config, items)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_call(item):
    steps = nbrun.around_cell(item)
    next(steps)
    try:
        return (yield)
    finally:
        next(steps, None)


def pytest_runtest_logreport(report):
    nbrun.logreport(report)


def pytest_sessionfinish(session):
    nbrun.session_finish(session.config)


"""Shared fixtures for the unit tests, and the rule that under CI a missing tool is a failure."""
import contextlib
import os
import sys
import weakref

import pytest

#: CI=true (GitHub Actions and most CI services set it): every tool the suite needs is installed
CI = os.environ.get("CI", "").strip().lower() in ("true", "1", "yes")
#: words of the skip reasons that mean "a tool the tests need is missing or cannot run here":
#: bubblewrap (the grader's and the checkers' sandbox tests: gm_grader.isolate.sandbox_problem,
#: tests/test_progress.py, tests/test_workspace.py) and Chromium (tests/browser/, tests/test_site.py)
MISSING_TOOL = ("bubblewrap", "bwrap", "no sandbox", "chromium")


def missing_tool(reason: str) -> bool:
    low = reason.lower()
    return any(word in low for word in MISSING_TOOL)


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item, call):
    """Under CI a test skipped because bubblewrap or Chromium is missing (or cannot run) FAILS:
    there the sandbox and browser tests must run. Elsewhere they skip, the reason saying what to
    install."""
    report = yield
    if CI and report.skipped and not hasattr(report, "wasxfail"):
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        if missing_tool(reason):
            report.outcome = "failed"
            report.longrepr = f"CI=true, where this test must run, but: {reason}"
    return report


@pytest.fixture(autouse=True)
def _close_figures():
    """Close every matplotlib figure a test opened (panels create figures through pyplot), except
    one a module-scoped fixture shares between tests and closes itself (``fig.gm_keep_open``)."""
    yield
    plt = sys.modules.get("matplotlib.pyplot")
    if plt is not None:
        for num in plt.get_fignums():
            fig = plt.figure(num)
            if not getattr(fig, "gm_keep_open", False):
                plt.close(fig)


#: The scopes collecting the ipywidgets made while they are open: a test's, a fixture's setup.
_WIDGET_SCOPES: list = []


def _widget_made(widget):
    for made in _WIDGET_SCOPES:
        made.append(weakref.ref(widget))


@contextlib.contextmanager
def _widgets_closed_at_the_end(into=None):
    """Close, at the end, every ipywidget made meanwhile and still open; with ``into`` (a list),
    hand them over there instead (weak references), to be closed later. ipywidgets keeps each
    widget registered until it is closed, and with it a panel's whole figure: unclosed, they piled
    up in a worker of `make test` (about 10^6 objects, every garbage collection walking them, some
    seconds of collecting at exit, and every later fork of the worker -- each checker's sandbox --
    copying their memory)."""
    Widget = _widget_class()
    if Widget is None:              # ipywidgets is not installed: there is nothing to close
        yield
        return
    made: list = []
    _WIDGET_SCOPES.append(made)
    Widget.on_widget_constructed(_widget_made)
    try:
        yield
    finally:
        del _WIDGET_SCOPES[next(i for i, m in enumerate(_WIDGET_SCOPES) if m is made)]   # (==: any empty list)
        if not _WIDGET_SCOPES:
            Widget.on_widget_constructed(None)
        if into is not None:
            into.extend(made)
        else:
            _close(made)


def _close(refs):
    """Close the widgets (weak references) that are still alive and open."""
    for ref in refs:
        w = ref()
        if w is not None and w.comm is not None:
            w.close()


def _widget_class():
    try:
        from ipywidgets import Widget
    except ImportError:
        return None
    return Widget


_FIXTURE_WIDGETS: dict = {}   # id(fixturedef) -> the widgets its setup made (closed when it is finalized)


@pytest.hookimpl(wrapper=True)
def pytest_fixture_setup(fixturedef, request):
    """The ipywidgets a fixture makes are closed when pytest finalizes it (for a fixture shared by
    a module's tests, tests/test_blit.py's panels, after the last of them; for a parametrized
    one, before its next parameter), not left open for the rest of the worker's run."""
    made: list = []
    with _widgets_closed_at_the_end(into=made):
        result = yield
    _FIXTURE_WIDGETS.setdefault(id(fixturedef), []).extend(made)
    return result


def pytest_fixture_post_finalizer(fixturedef, request):
    _close(_FIXTURE_WIDGETS.pop(id(fixturedef), ()))


@pytest.fixture(autouse=True)
def _close_widgets():
    """Close every ipywidget a test made (a panel's sliders and its ipympl canvas), except those
    of a fixture shared by several tests (made before this one starts; closed with the fixture)."""
    with _widgets_closed_at_the_end():
        yield


@pytest.fixture
def clean(monkeypatch, tmp_path):
    """A fresh, in-memory checker progress record for one test (no workspace in sight).

    The kernel's working directory is moved to an empty temporary folder and
    GM_COURSE_WORKSPACE is cleared, so nothing reads or writes a real workspace/.progress.json.
    """
    from gm_core.checks.exercise import reset_progress

    monkeypatch.delenv("GM_COURSE_WORKSPACE", raising=False)
    monkeypatch.chdir(tmp_path)
    reset_progress()
    yield
    reset_progress()


@pytest.fixture(scope="session")
def notebook_record():
    """``get(path)`` -> the record of that notebook's one execution in this run (tests/nbrun.py):
    executed at the first call in this process; the notebook's xdist group keeps its readers on
    the worker that executed it."""
    import nbrun

    return nbrun.record


@pytest.fixture(scope="session")
def playwright():
    """The one Playwright (sync API) of this test process, shared by every test that drives
    Chromium (the JupyterLab tests in tests/browser/, the website tests). The sync API runs an
    event loop of its own; a second ``sync_playwright()`` in the same process while this one is
    alive fails ("Sync API inside the asyncio loop"), so nobody starts their own."""
    pytest.importorskip("playwright.sync_api", reason="the playwright package is missing: pip install -e '.[test]'")
    from playwright.sync_api import sync_playwright

    pw = sync_playwright().start()
    yield pw
    pw.stop()


SELFCHECK_NOTEBOOKS = {
    # too wide, and its title too small, in every frame of an animation
    "anim.ipynb": ["%matplotlib widget\nimport matplotlib.pyplot as plt\n"
                   "from matplotlib.animation import FuncAnimation\n"
                   "fig, ax = plt.subplots(figsize=(10, 3))\nt = ax.set_title('tiny', fontsize=5)\n"
                   "anim = FuncAnimation(fig, lambda k: None, frames=3)\nhtml = anim.to_jshtml()\nplt.close(fig)\n"],
    # a warning on stderr, and one shown as a text result
    "warns.ipynb": ["import warnings\nwarnings.warn('the layout has changed', UserWarning)\n",
                    "import warnings\nwarnings.formatwarning('x', RuntimeWarning, 'f.py', 3)\n"],
    "quiet.ipynb": ["print('all quiet')\n"],
}


@pytest.fixture(scope="session")
def selfcheck_records():
    """Records of generated notebooks executed exactly as the course's are (tests/nbrun.py), so
    the tests reading records can prove they fail on a bad notebook. Its readers are marked
    ``nbrun.SELFCHECK``, so they share one execution."""
    import nbformat
    import nbrun

    d = nbrun.run_dir() / "selfcheck"
    d.mkdir(parents=True, exist_ok=True)
    out = {}
    for name, cells in SELFCHECK_NOTEBOOKS.items():
        nb = nbformat.v4.new_notebook()
        nb.cells = [nbformat.v4.new_code_cell(src) for src in cells]
        nbformat.write(nb, d / name)
        out[name] = nbrun.record(d / name)
    return out

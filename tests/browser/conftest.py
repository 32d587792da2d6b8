"""Fixtures for the real-browser tests: ONE JupyterLab server and ONE headless Chromium per session.

Everything here is marked ``browser`` (``pytest -m browser`` runs only these; ``-m "not browser"``
leaves them out). Without /usr/bin/chromium the tests are skipped with the install hint; the
playwright PyPI package is used with that system Chromium (never ``playwright install``).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import browserlab  # noqa: E402
import labview  # noqa: E402
import student  # noqa: E402

HERE = Path(__file__).resolve().parent
TIMINGS_KEY = pytest.StashKey[dict]()


@pytest.hookimpl(tryfirst=True)  # before -m selects (the module also sets pytestmark)
def pytest_collection_modifyitems(config, items):
    # A test of one course notebook reads that notebook's record (nbrun.params), so it carries the
    # notebook's xdist group: under `--dist loadgroup` it runs on the worker that executes the
    # notebook. The self-checks share the group "browser" (nbrun.default_groups). Each
    # worker starts its own server and Chromium when it first needs them.
    for item in items:
        if HERE in Path(str(item.path)).resolve().parents:
            item.add_marker(pytest.mark.browser)


def pytest_configure(config):
    config.stash[TIMINGS_KEY] = {}


@pytest.fixture(scope="session")
def chromium():
    if not browserlab.chromium_available():
        pytest.skip(browserlab.CHROMIUM_MISSING)
    pytest.importorskip("playwright.sync_api", reason="the playwright package is missing: pip install -e '.[test]'")
    return browserlab.CHROMIUM


# Clean-ups of the session resources, newest last. They run right after the last browser test
# (so the server and Chromium do not idle through the unit tests and notebooks that `make test`
# runs next) or at the end of the session, whichever comes first.
_CLEANUPS: list = []


def _release(request=None):
    t0 = time.monotonic()
    ran = bool(_CLEANUPS)
    while _CLEANUPS:
        fn = _CLEANUPS.pop()
        try:
            fn()
        except Exception as e:  # keep releasing the rest
            print(f"browser tests: clean-up {fn!r} failed: {e}", file=sys.stderr)
    if ran and request is not None:
        request.config.stash[TIMINGS_KEY]["(stop browser + server)"] = {"total": round(time.monotonic() - t0, 2)}


def _on_cleanup(request, fn):
    _CLEANUPS.append(fn)
    request.addfinalizer(_release)


@pytest.fixture(autouse=True)
def _release_after_last_browser_test(request):
    yield
    items = request.session.items
    try:
        i = items.index(request.node)
    except ValueError:
        return
    if not any(_BROWSER_FIXTURES & set(getattr(it, "fixturenames", ())) for it in items[i + 1:]):
        _release(request)


#: the session resources that _release ends (a test asking for any of them needs them alive)
_BROWSER_FIXTURES = {"lab", "lab_server", "browser_context", "chromium"}


@pytest.fixture(scope="session")
def lab_server(chromium, tmp_path_factory, request):
    """JupyterLab on a temporary copy of the course (plus the self-check notebook)."""
    t0 = time.monotonic()
    server = browserlab.LabServer(tmp_path_factory.mktemp("lab"),
                                  extra_notebooks={browserlab.SELFCHECK_PATH: browserlab.selfcheck_notebook(),
                                                   labview.LAYOUT_SELFCHECK_PATH: labview.layout_selfcheck_notebook(),
                                                   student.STUDENT_SELFCHECK_PATH: student.student_selfcheck_notebook()})
    _on_cleanup(request, server.stop)
    server.start()
    request.config.stash[TIMINGS_KEY]["(server start)"] = {"total": round(time.monotonic() - t0, 2)}
    return server


@pytest.fixture(scope="session")
def browser_context(chromium, playwright, tmp_path_factory, request):
    """One headless Chromium (fresh empty profile) shared by every page of the session, with a
    laptop's window (labview.STUDENT_WINDOW, 1366 x 768; the file browser is opened beside the
    notebook on every fresh page load). Started from the process's one Playwright (tests/conftest.py)."""
    t0 = time.monotonic()
    context = browserlab.launch_chromium(playwright, tmp_path_factory.mktemp("chromium-profile"),
                                         viewport=labview.STUDENT_WINDOW)
    _on_cleanup(request, context.close)
    request.config.stash[TIMINGS_KEY]["(browser start)"] = {"total": round(time.monotonic() - t0, 2)}
    return context


@pytest.fixture(scope="session")
def lab(lab_server, browser_context, request):
    """The JupyterLab page shared by the notebooks (reloaded after a failure)."""
    lab = browserlab.LabBrowser(browser_context, lab_server)
    _on_cleanup(request, lab.close)
    return lab


@pytest.fixture
def prestart_next(request, lab_server):
    """Start the kernel of the notebook the next browser test will open (see LabServer.prestart).
    Not under pytest-xdist: there the next test in the list may run on another worker."""
    def prestart():
        if getattr(request.config, "workerinput", None) is not None:
            return None
        items = request.session.items
        try:
            i = items.index(request.node)
        except ValueError:
            return None
        for item in items[i + 1:]:
            nb = getattr(item, "callspec", None) and item.callspec.params.get("notebook")
            if nb is not None:
                rel = Path(nb).relative_to(browserlab.ROOT).as_posix()
                lab_server.prestart(rel)
                return rel
        return None
    return prestart


@pytest.fixture
def record_timing(request):
    """Store per-notebook phase timings; printed in the terminal summary."""
    def record(name, phases):
        request.config.stash[TIMINGS_KEY][name] = phases
        _save_timing(name, phases)
    return record


def _save_timing(name, phases):
    """Also keep the phases in this run's folder (tests/nbrun.py), one file per notebook: under
    pytest-xdist the terminal summary below runs in the workers, whose output is not shown, and
    benchmarks/suite_time.py --last prints these with the rest of the run's times."""
    import json

    import nbrun

    d = nbrun.run_dir()
    if d is None:
        return
    out = d / "browser-timings"
    out.mkdir(exist_ok=True)
    (out / (nbrun.slug(name).strip("()").replace(" ", "-") + ".json")).write_text(
        json.dumps({"name": name, "phases": phases}), encoding="utf-8")


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    timings = config.stash.get(TIMINGS_KEY, {})
    if not timings:
        return
    tr = terminalreporter
    tr.section("browser timings (s)")
    for name, phases in timings.items():
        total = phases.get("total", round(sum(v for k, v in phases.items() if k != "total"), 2))
        detail = ", ".join(f"{k} {v}" for k, v in phases.items() if k != "total")
        tr.write_line(f"{name:<40} {total:7.2f}  {detail}")

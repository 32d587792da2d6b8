"""Drive the course's notebooks in a real JupyterLab with headless Chromium (playwright, sync API).

Used by ``tests/browser/`` (pytest fixtures in conftest.py) and by ``benchmarks/browser_latency.py``.

* :class:`LabServer` copies the course (book/, exercises/, solutions/) to a temporary folder and
  starts ``python -m jupyterlab`` on 127.0.0.1 (free port, random token, fresh runtime/config/data
  dirs, the course's own JupyterLab defaults from jupyter/overrides.json (news prompt and update
  check off, installed by tools/lab_settings.py as `make lab` does), and no user settings of its
  own: the student's JupyterLab). The kernel imports ``gm_core`` from the tree these tests live in (PYTHONPATH), so a
  scratch copy of the repository tests its own code. Stop it with :meth:`LabServer.stop`
  (sessions and kernels deleted over the REST API, then SIGTERM/SIGKILL to the server's process
  group, whose id is the server's PID).
* :func:`launch_chromium` starts /usr/bin/chromium headless with a fresh, empty profile and the
  flags that keep it off the network.
* :class:`LabBrowser` keeps one page with the JupyterLab app (``window.jupyterapp`` is exposed
  with ``--LabApp.expose_app_in_browser``) and opens notebook after notebook in it; after a
  failure the page is dropped and the next notebook gets a fresh page load.
* :class:`NotebookPage` opens one notebook, waits for an idle kernel, runs all cells, checks that
  every code cell ran and nothing failed (cell errors, stderr tracebacks, "Error displaying
  widget", and errors raised in widget callbacks, which JupyterLab does not show in the cell: the
  kernel's iopub channel is watched), and moves a slider of an interactive panel with the
  keyboard, reporting whether the ipympl canvas pixels (``toDataURL``) changed.
* :func:`check_interactive_notebook` is the whole check of one chapter notebook.

Run ``pytest -m browser`` (the tests) or ``benchmarks/browser_latency.py``. Set ``GM_CHROMIUM``
to use another Chromium binary. Failure screenshots go to ``$TMPDIR/gm-browser-failures/``.

Every wait polls (no fixed long sleeps) and fails with a message that says what was seen last and
where a screenshot was written.
"""
from __future__ import annotations

import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CHROMIUM = os.environ.get("GM_CHROMIUM", "/usr/bin/chromium")
CHROMIUM_MISSING = f"chromium not found at {CHROMIUM}: apt-get install chromium"
CHROMIUM_ARGS = [
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking",
    "--disable-component-update", "--no-first-run", "--disable-sync", "--disable-dev-shm-usage",
    "--disable-default-apps", "--disable-extensions", "--no-default-browser-check",
    "--metrics-recording-only", "--disable-breakpad", "--disable-domain-reliability",
]
COURSE_DIRS = ("book", "exercises", "solutions")
#: where failure screenshots go (kept after the run; the path is in the failure message)
FAILURE_DIR = Path(tempfile.gettempdir()) / "gm-browser-failures"


class BrowserTestError(AssertionError):
    """A browser check failed; the message says what was seen and where the screenshot is."""


class CanvasBusy(Exception):
    """A panel's canvas never stood still (an animation?): its slider cannot be judged."""


def chromium_available() -> bool:
    return os.path.isfile(CHROMIUM) and os.access(CHROMIUM, os.X_OK)


def interactive_notebooks(root: Path = ROOT) -> list[Path]:
    """Every book/*.ipynb with ``%matplotlib widget`` in a code cell (found at collection time)."""
    out = []
    for path in sorted((root / "book").glob("*.ipynb")):
        try:
            nb = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue
        for cell in nb.get("cells", []):
            src = cell.get("source", "")
            src = "".join(src) if isinstance(src, list) else src
            if cell.get("cell_type") == "code" and "%matplotlib widget" in src:
                out.append(path)
                break
    return out


# --------------------------------------------------------------------------------------------
# The server
# --------------------------------------------------------------------------------------------

# Per-user settings for the test server (JupyterLab reads <user_settings_dir>/<ext>/<plugin>.jupyterlab-settings).
# The server otherwise gets exactly the student's settings, JupyterLab's defaults plus the course's
# own (jupyter/overrides.json, installed by tools/lab_settings.py as `make lab` does), so the tests
# see what a student sees (notebook windowing included: JupyterLab 4's default "contentVisibility"
# lays off-screen outputs out differently, e.g. a jshtml animation's image) and
# test_student_view.py proves the course's file silences the news prompt. One exception, which
# changes no picture, size or place: the editors' text cursors do not blink. CodeMirror restarts
# its blink (a CSS animation) in every cell's editor whenever the active cell changes (each
# click on a slider, each cell of Run All), and the running animations kept the page drawing
# frames at 60 per second: ~10 % of the browser's CPU in notebook 03's test (Run All and drags).
LAB_SETTINGS: dict = {("@jupyterlab/codemirror-extension", "plugin"): {"defaultConfig": {"cursorBlinkRate": 0}}}


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class LabServer:
    """A JupyterLab server on a temporary copy of the course."""

    def __init__(self, workdir: Path, source_root: Path = ROOT, extra_notebooks: dict | None = None,
                 start_timeout: float = 90.0):
        self.workdir = Path(workdir)
        self.source_root = Path(source_root)
        self.course = self.workdir / "course"
        self.token = secrets.token_hex(24)
        self.port = None
        self.proc = None
        self.log_path = self.workdir / "jupyterlab.log"
        self.extra_notebooks = extra_notebooks or {}
        self.start_timeout = start_timeout
        self._background: list[threading.Thread] = []

    # -- set-up ---------------------------------------------------------------------------
    def _copy_course(self):
        ignore = shutil.ignore_patterns(".ipynb_checkpoints", "__pycache__")
        self.course.mkdir(parents=True, exist_ok=True)
        for d in COURSE_DIRS:
            src = self.source_root / d
            if src.is_dir():
                shutil.copytree(src, self.course / d, ignore=ignore, dirs_exist_ok=True)
        for rel, nb in self.extra_notebooks.items():
            target = self.course / rel
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(json.dumps(nb, indent=1), encoding="utf-8")

    def _app_settings(self) -> Path:
        """JupyterLab's application settings dir for the server: this Python's own (page_config
        etc.) plus the course's overrides, installed by the same tool `make lab` uses."""
        sys.path.insert(0, str(self.source_root / "tools"))
        try:
            import lab_settings
        finally:
            sys.path.pop(0)
        app_settings = self.workdir / "lab-app-settings"
        default = lab_settings.default_settings_dir()
        if default.is_dir():
            shutil.copytree(default, app_settings, dirs_exist_ok=True)
        lab_settings.install(app_settings)
        return app_settings

    def _write_settings(self) -> Path:
        settings = self.workdir / "lab-user-settings"
        for (ext, plugin), values in LAB_SETTINGS.items():
            if values:
                p = settings / ext / f"{plugin}.jupyterlab-settings"
                p.parent.mkdir(parents=True, exist_ok=True)
                p.write_text(json.dumps(values), encoding="utf-8")
        return settings

    def env(self) -> dict:
        env = dict(os.environ)
        for name, sub in (("JUPYTER_RUNTIME_DIR", "runtime"), ("JUPYTER_CONFIG_DIR", "config"),
                          ("JUPYTER_DATA_DIR", "data"), ("IPYTHONDIR", "ipython")):
            (self.workdir / sub).mkdir(parents=True, exist_ok=True)
            env[name] = str(self.workdir / sub)
        env.pop("JUPYTER_PATH", None)
        env.pop("JUPYTER_CONFIG_PATH", None)
        env["JUPYTER_PLATFORM_DIRS"] = "1"
        # the kernel imports gm_core from the tree under test (also when that tree is a scratch copy)
        env["PYTHONPATH"] = os.pathsep.join([str(self.source_root)] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
        env["GM_COURSE_TESTING"] = "1"
        env.pop("MPLBACKEND", None)  # notebooks choose %matplotlib widget themselves
        env["PYTHONUNBUFFERED"] = "1"
        return env

    def command(self, settings: Path) -> list[str]:
        return [
            sys.executable, "-m", "jupyterlab", "--no-browser",
            "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={self.port}", "--ServerApp.port_retries=0",
            f"--IdentityProvider.token={self.token}",
            f"--ServerApp.root_dir={self.course}",
            "--ServerApp.open_browser=False",
            f"--LabApp.app_settings_dir={self.workdir / 'lab-app-settings'}",
            f"--LabApp.user_settings_dir={settings}",
            f"--LabApp.workspaces_dir={self.workdir / 'workspaces'}",
            "--LabApp.expose_app_in_browser=True",
            "--ServerApp.terminals_enabled=False",
            "--MappingKernelManager.cull_idle_timeout=0",
            # A test's kernel is ended at once when its session is deleted, not asked to exit
            # first: no test looks at how a kernel ends, and an orderly exit (Python finalizing
            # the notebook's figures and modules) is work nobody needs.
            "--KernelManager.shutdown_wait_time=0",
        ] + (["--allow-root"] if hasattr(os, "geteuid") and os.geteuid() == 0 else [])

    def start(self):
        self._copy_course()
        settings = self._write_settings()
        self._app_settings()
        (self.workdir / "workspaces").mkdir(exist_ok=True)
        last_err = None
        for _attempt in range(3):  # a port can be taken between free_port() and bind: retry
            self.port = free_port()
            self._log = open(self.log_path, "ab")
            self.proc = subprocess.Popen(self.command(settings), cwd=self.course, env=self.env(),
                                         stdout=self._log, stderr=subprocess.STDOUT,
                                         stdin=subprocess.DEVNULL, start_new_session=True)
            try:
                self._wait_ready()
                return self
            except BrowserTestError as e:
                last_err = e
                self.stop()
                if "exited" not in str(e):
                    break
        raise last_err

    def _wait_ready(self):
        deadline = time.monotonic() + self.start_timeout
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise BrowserTestError(f"jupyter lab exited with code {self.proc.returncode}; "
                                       f"log {self.log_path}:\n{self.log_tail()}")
            try:
                self.api("GET", "/api/status", timeout=2)
                # the lab page itself must be served too (extension assets resolved)
                self.api("GET", "/lab/api/settings", timeout=5)
                return
            except (OSError, urllib.error.URLError):
                time.sleep(0.2)
        raise BrowserTestError(f"jupyter lab did not answer on port {self.port} within "
                               f"{self.start_timeout:.0f} s; log {self.log_path}:\n{self.log_tail()}")

    # -- use --------------------------------------------------------------------------------
    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def lab_url(self, relpath: str) -> str:
        return f"{self.url}/lab/tree/{relpath}?reset&token={self.token}"

    def api(self, method: str, path: str, timeout: float = 10.0, body: dict | None = None):
        data = json.dumps(body).encode() if body is not None else None
        headers = {"Authorization": f"token {self.token}"}
        if data is not None:
            headers["Content-Type"] = "application/json"
        req = urllib.request.Request(self.url + path, method=method, data=data, headers=headers)
        with urllib.request.urlopen(req, timeout=timeout) as r:
            body = r.read()
        return json.loads(body) if body else None

    def delete_sessions(self, path: str | None = None):
        """Shut down the sessions (and their kernels) of ``path``, or every session and kernel."""
        try:
            for s in self.api("GET", "/api/sessions") or []:
                if path is not None and s.get("path") != path:
                    continue
                try:
                    self.api("DELETE", f"/api/sessions/{s['id']}", timeout=30)
                except (OSError, urllib.error.URLError):
                    pass
            if path is None:
                for k in self.api("GET", "/api/kernels") or []:
                    try:
                        self.api("DELETE", f"/api/kernels/{k['id']}", timeout=30)
                    except (OSError, urllib.error.URLError):
                        pass
        except (OSError, urllib.error.URLError, ValueError):
            pass

    def prestart(self, path: str):
        """Start ``path``'s kernel in the background, before the browser opens it.

        JupyterLab joins an existing session of the same path, so the next notebook finds an
        idle kernel instead of waiting for one to boot (the test still waits for "idle")."""
        def start():
            try:
                nb = json.loads((self.course / path).read_text(encoding="utf-8"))
                name = nb.get("metadata", {}).get("kernelspec", {}).get("name") or "python3"
                self.api("POST", "/api/sessions", timeout=60, body={
                    "path": path, "name": Path(path).name, "type": "notebook", "kernel": {"name": name}})
            except Exception:
                pass  # purely an optimisation: JupyterLab starts the kernel itself otherwise
        t = threading.Thread(target=start, daemon=True)
        t.start()
        self._background.append(t)

    def delete_sessions_later(self, path: str):
        """Shut ``path``'s kernel down in the background (the next notebook need not wait for it)."""
        t = threading.Thread(target=self.delete_sessions, args=(path,), daemon=True)
        t.start()
        self._background.append(t)

    def log_tail(self, n: int = 40) -> str:
        try:
            lines = self.log_path.read_text(errors="replace").splitlines()
        except OSError:
            return ""
        return "\n".join(lines[-n:])

    def stop(self):
        if self.proc is None:
            return
        for t in self._background:
            t.join(timeout=30)
        if self.proc.poll() is None:
            self.delete_sessions()
            pid = self.proc.pid  # the server leads its own session: its PID is its process group id
            for sig, wait in ((signal.SIGTERM, 15), (signal.SIGKILL, 5)):
                try:
                    os.killpg(pid, sig)
                except ProcessLookupError:
                    break
                try:
                    self.proc.wait(timeout=wait)
                    break
                except subprocess.TimeoutExpired:
                    continue
            # anything left in the server's process group goes too. (Kernels run in their own
            # sessions: they were shut down over the REST API above, and ipykernel exits by itself
            # when its parent server is gone, JPY_PARENT_PID.)
            try:
                os.killpg(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        try:
            self._log.close()
        except Exception:
            pass
        self.proc = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


# --------------------------------------------------------------------------------------------
# The browser
# --------------------------------------------------------------------------------------------

def launch_chromium(playwright, profile_dir: Path, viewport=(1400, 1000)):
    """A persistent context on a fresh, empty profile (one browser for the whole session)."""
    profile_dir = Path(profile_dir)
    profile_dir.mkdir(parents=True, exist_ok=True)
    if any(profile_dir.iterdir()):
        raise RuntimeError(f"browser profile dir {profile_dir} is not empty")
    return playwright.chromium.launch_persistent_context(
        str(profile_dir), executable_path=CHROMIUM, headless=True, args=CHROMIUM_ARGS,
        viewport={"width": viewport[0], "height": viewport[1]}, accept_downloads=False,
        service_workers="block", timeout=60_000)


# -- JavaScript run in the page ------------------------------------------------------------

_STATUS_JS = r"""
(path) => {
  const out = {phase: 'loading', dialogs: [], errors: [], tracebacks: [], widgetErrors: []};
  for (const d of document.querySelectorAll('.jp-Dialog')) out.dialogs.push(d.innerText.slice(0, 400));
  const app = window.jupyterapp;
  if (!app || !app.shell) return out;
  let panel = null;
  for (const w of app.shell.widgets('main')) {
    if (w.context && w.context.path === path && w.content && w.sessionContext) { panel = w; break; }
  }
  if (!panel) { out.phase = 'nopanel'; return out; }
  out.phase = 'panel';
  out.panelId = panel.id;
  const sc = panel.sessionContext;
  out.ready = !!(panel.context.isReady && sc.isReady);
  const k = sc.session && sc.session.kernel;
  out.kernel = k ? k.status : null;
  out.kernelName = k ? k.name : null;
  out.connection = k ? k.connectionStatus : null;
  // Errors raised in widget callbacks (a slider move) reach the kernel's iopub channel but not
  // the cell's output area (JupyterLab sends them to the log console): listen to iopub directly.
  window.__gmKernelErrors = window.__gmKernelErrors || [];
  if (k && !k.__gmHooked) {
    k.__gmHooked = true;
    k.iopubMessage.connect((_, msg) => {
      const t = msg.header.msg_type, c = msg.content || {};
      // errors of executed cells are in their outputs already; keep the rest (widget callbacks)
      if (msg.parent_header && msg.parent_header.msg_type === 'execute_request') return;
      if (t === 'error') window.__gmKernelErrors.push({path, text: `${c.ename}: ${c.evalue}\n` + (c.traceback || []).join('\n').replace(/\x1b\[[0-9;]*m/g, '').slice(-1500)});
      else if (t === 'stream' && c.name === 'stderr' && String(c.text).includes('Traceback'))
        window.__gmKernelErrors.push({path, text: String(c.text).slice(-1500)});
    });
  }
  for (const e of window.__gmKernelErrors) if (e.path === path) out.errors.push('kernel (widget callback): ' + e.text);
  out.ncode = 0; out.executed = 0; out.running = 0; out.counts = [];
  panel.content.widgets.forEach((cell, i) => {
    if (cell.model.type !== 'code') return;
    out.ncode++;
    const n = cell.model.executionCount;
    if (n !== null && n !== undefined) { out.executed++; out.counts.push(n); }
    if (cell.model.executionState === 'running' || (cell.promptNode && cell.promptNode.textContent.includes('*'))) out.running++;
    const outs = cell.model.outputs.toJSON();
    for (const o of outs) {
      if (o.output_type === 'error') out.errors.push(`cell ${i}: ${o.ename}: ${o.evalue}`);
      if (o.output_type === 'stream' && o.name === 'stderr') {
        const t = Array.isArray(o.text) ? o.text.join('') : String(o.text);
        if (t.includes('Traceback')) out.tracebacks.push(`cell ${i}: ${t.slice(0, 600)}`);
      }
    }
  });
  for (const el of panel.node.querySelectorAll('.jp-OutputArea-output')) {
    const t = el.innerText || '';
    if (t.includes('Error displaying widget')) out.widgetErrors.push(t.slice(0, 300));
    else if (el.matches('[data-mime-type="application/vnd.jupyter.stderr"]') && t.includes('Traceback'))
      out.tracebacks.push(t.slice(0, 600));
    else if (t.includes('Traceback')) out.tracebacks.push(t.slice(0, 600));
  }
  for (const el of panel.node.querySelectorAll('.jupyter-widgets-error-widget, .jupyter-widgets .widget-error'))
    out.widgetErrors.push((el.innerText || 'widget error').slice(0, 300));
  return out;
}
"""

# Tag the first panel (an output area holding an ipywidgets slider and an ipympl canvas).
_FIND_PANEL_JS = r"""
(args) => {
  const [panelId, index] = args;
  const root = document.getElementById(panelId);
  if (!root) return {found: false, why: 'notebook panel not in the DOM'};
  for (const el of root.querySelectorAll('[data-gm-panel]')) el.removeAttribute('data-gm-panel');
  const areas = [...root.querySelectorAll('.jp-Cell .jp-OutputArea')];
  let k = 0, nSliders = 0, nCanvas = 0;
  for (const a of areas) {
    const s = a.querySelector('.widget-slider .noUi-handle');
    const c = a.querySelector('.jupyter-matplotlib canvas, .jupyter-matplotlib-canvas-div canvas');
    if (s) nSliders++;
    if (c) nCanvas++;
    if (s && c) {
      if (k === index) {
        a.setAttribute('data-gm-panel', String(index));
        const cell = a.closest('.jp-Cell');
        const cells = [...root.querySelectorAll('.jp-Cell')];
        return {found: true, cellIndex: cells.indexOf(cell)};
      }
      k++;
    }
  }
  return {found: false, why: `no output area with both a slider and an ipympl canvas (${areas.length} output areas, ${nSliders} with sliders, ${nCanvas} with canvases)`, npanels: k};
}
"""

_SLIDER_VALUE_JS = r"""
([sel, index]) => {
  const s = document.querySelectorAll(sel + ' .widget-slider')[index];
  if (!s) return {};
  const t = s.querySelector('.noUi-target');
  const num = (x) => { const v = Number(Array.isArray(x) ? x[0] : x); return Number.isFinite(v) ? v : null; };
  const label = (s.querySelector('.widget-label') || {}).innerText || '';
  if (t && t.noUiSlider) {
    const r = t.noUiSlider.options.range;
    return {value: num(t.noUiSlider.get()), min: num(r.min), max: num(r.max), label};
  }
  const h = s.querySelector('.noUi-handle');
  if (!h) return {label};
  return {value: num(h.getAttribute('aria-valuenow')), min: num(h.getAttribute('aria-valuemin')),
          max: num(h.getAttribute('aria-valuemax')), label};
}
"""

_SNAPSHOT_JS = r"""
(sel) => {
  const area = document.querySelector(sel);
  if (!area) return null;
  const cs = [...area.querySelectorAll('.jupyter-matplotlib canvas, .jupyter-matplotlib-canvas-div canvas')];
  return cs.map(c => c.width + 'x' + c.height + ':' + c.toDataURL()).join('|');
}
"""

_CANVAS_READY_JS = r"""
(sel) => {
  const area = document.querySelector(sel);
  if (!area) return false;
  const c = area.querySelector('.jupyter-matplotlib canvas, .jupyter-matplotlib-canvas-div canvas');
  if (!c || c.width === 0 || c.height === 0) return false;
  // something has been drawn: the canvas is not uniformly transparent
  const ctx = c.getContext('2d');
  const d = ctx.getImageData(0, 0, c.width, c.height).data;
  for (let i = 3; i < d.length; i += 4 * 97) if (d[i] !== 0) return true;
  return false;
}
"""


@dataclass
class SliderResult:
    changed: bool
    readout_before: str
    readout_after: str
    value_before: float | None
    value_after: float | None
    seconds: float
    presses: int
    detail: str = ""

    @property
    def slider_moved(self) -> bool:
        return (self.readout_before != self.readout_after) or (self.value_before != self.value_after)


@dataclass
class Timings:
    phases: dict = field(default_factory=dict)

    def mark(self, name, t0):
        self.phases[name] = round(time.monotonic() - t0, 2)
        return time.monotonic()


def _short_url(url: str) -> str:
    url = url.split("?token=")[0].split("&token=")[0]
    return url if len(url) < 160 else url[:157] + "..."


def _local_url(url: str, server_url: str) -> bool:
    return url.startswith((server_url, "ws://127.0.0.1", "data:", "blob:", "about:", "chrome", "devtools"))


# Open a document in the running app. Without a kernel, as a saved notebook is read: JupyterLab
# starts the notebook's kernel on opening (its widget factory prefers one), so the session is
# shut down as soon as it exists.
_OPEN_JS = r"""
async ([path, kernel]) => {
  const app = window.jupyterapp;
  await app.started;
  const w = await app.commands.execute('docmanager:open', {path});
  if (!kernel) {
    await w.context.ready;
    try { await w.sessionContext.ready; } catch (e) {}
    if (w.sessionContext.session) await w.sessionContext.shutdown();
  }
  return w.id;
}
"""


class LabBrowser:
    """One browser page running the JupyterLab app, reused for one notebook after another.

    Loading the app costs a few seconds, so notebooks after the first are opened in the running
    app (``docmanager:open``) and closed again (kernel shut down, panel disposed). After any
    failure the page is thrown away and the next notebook starts from a fresh page load.
    """

    def __init__(self, context, server: LabServer):
        self.context = context
        self.server = server
        self.page = None
        self.console_errors: list[str] = []
        #: uncaught JavaScript errors, and requests that failed or left the machine (any page)
        self.page_errors: list[str] = []
        self.request_problems: list[str] = []

    def _on_request_failed(self, request):
        url, why = request.url, request.failure or ""
        # an image the browser stopped loading because a newer one replaced it (ipympl frames,
        # revoked blob: URLs) is not a failure; anything else is
        if url.startswith(("blob:", "data:")) or ("ERR_ABORTED" in why and _local_url(url, self.server.url)):
            return
        self.request_problems.append(f"request failed: {request.method} {_short_url(url)} ({why})")

    def open(self, relpath: str, timeout: float, kernel: bool = True) -> tuple:
        """Show ``relpath`` in the app; returns (page, fresh_page_load). ``kernel=False``: as a
        saved notebook is read, with no kernel (the one JupyterLab starts on opening it is shut
        down at once)."""
        if self.page is not None and not self.page.is_closed():
            try:
                self.page.evaluate(_OPEN_JS, [relpath, kernel])
                return self.page, False
            except Exception:
                self.discard()
        page = self.context.new_page()
        page.on("console", lambda m: m.type == "error" and self.console_errors.append(m.text[:300]))
        page.on("pageerror", lambda e: (self.console_errors.append(f"pageerror: {e}"[:300]),
                                        self.page_errors.append(f"page error: {e}"[:500])))
        page.on("requestfailed", self._on_request_failed)
        page.on("response", lambda r: r.status >= 400 and self.request_problems.append(
            f"request failed: {r.request.method} {_short_url(r.url)} -> HTTP {r.status}"))
        page.on("request", lambda r: not _local_url(r.url, self.server.url) and self.request_problems.append(
            f"request to the network: {r.method} {_short_url(r.url)}"))
        page.on("dialog", lambda d: d.accept())  # beforeunload etc.
        page.set_default_timeout(30_000)
        self.page = page
        page.goto(self.server.lab_url(relpath if kernel else ""), wait_until="domcontentloaded",
                  timeout=timeout * 1000)
        if not kernel:   # the app alone was loaded: open the notebook in it
            page.wait_for_function("() => window.jupyterapp", timeout=timeout * 1000)
            page.evaluate(_OPEN_JS, [relpath, kernel])
        return page, True

    def close_notebook(self, relpath: str):
        """Dispose of the notebook's panel (no save dialog; its kernel is shut down by the caller)."""
        if self.page is None or self.page.is_closed():
            return
        try:
            self.page.evaluate("""(p) => { const app = window.jupyterapp;
                for (const w of [...app.shell.widgets('main')]) {
                  if (w.context && w.context.path === p) { w.context.model.dirty = false; w.dispose(); }
                }
                return true; }""", relpath)
        except Exception:
            self.discard()

    def discard(self):
        if self.page is not None:
            try:
                self.page.close()
            except Exception:
                pass
        self.page = None

    def close(self):
        self.discard()


class NotebookPage:
    """One notebook open in the shared JupyterLab page."""

    def __init__(self, lab: LabBrowser, relpath: str, poll: float = 0.15):
        self.lab = lab
        self.server = lab.server
        self.relpath = relpath
        self.poll = poll
        self.page = None
        self.status = {}
        self.failed = False
        self.dialogs_dismissed: list[str] = []
        self._console_start = len(lab.console_errors)
        self._page_errors_start = len(lab.page_errors)
        self._requests_start = len(lab.request_problems)
        self.timings = Timings()

    @property
    def console_errors(self):
        return self.lab.console_errors[self._console_start:]

    @property
    def page_problems(self) -> list[str]:
        """Uncaught page errors and failed or outside requests since this notebook was opened."""
        return (self.lab.page_errors[self._page_errors_start:]
                + sorted(set(self.lab.request_problems[self._requests_start:])))

    def __enter__(self):
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is not None:
            self.failed = True
        self.close()

    # -- plumbing ----------------------------------------------------------------------------
    def fail(self, what: str):
        self.failed = True
        shot = self.screenshot()
        extra = ""
        if self.console_errors:
            extra += "\nbrowser console errors (last 5):\n  " + "\n  ".join(self.console_errors[-5:])
        if self.dialogs_dismissed:
            extra += "\ndialogs dismissed: " + "; ".join(d[:120] for d in self.dialogs_dismissed)
        raise BrowserTestError(
            f"{self.relpath}: {what}\nlast status: {json.dumps(self.status)[:1500]}"
            f"\nscreenshot: {shot}\nserver log: {self.server.log_path}{extra}")

    def screenshot(self) -> str:
        if self.page is None:
            return "(no page)"
        FAILURE_DIR.mkdir(parents=True, exist_ok=True)
        name = self.relpath.replace("/", "_").replace(".ipynb", "")
        path = FAILURE_DIR / f"{name}-{time.strftime('%Y%m%d-%H%M%S')}-{os.getpid()}.png"
        try:
            self.page.screenshot(path=str(path), full_page=True, timeout=15_000)
            return str(path)
        except Exception as e:  # the page may be gone
            return f"(screenshot failed: {e})"

    def read_status(self) -> dict:
        self.status = self.page.evaluate(_STATUS_JS, self.relpath)
        return self.status

    def dismiss_dialogs(self):
        """Accept JupyterLab dialogs (kernel selection keeps the notebook's/ default kernel)."""
        for text in self.status.get("dialogs", []):
            low = text.lower()
            if "kernel restarting" in low or "dead kernel" in low or "kernel died" in low:
                self.fail(f"the kernel died or restarted: {text!r}")
            self.dialogs_dismissed.append(text)
        dialog = self.page.locator(".jp-Dialog").first
        try:
            btn = dialog.locator("button.jp-mod-accept").first
            if btn.count():
                btn.click(timeout=5_000)
            else:
                dialog.press("Escape", timeout=5_000)
        except Exception:
            pass

    def wait_until(self, predicate, what: str, timeout: float):
        """Poll the page status until ``predicate(status)`` is true; fail fast on errors."""
        deadline = time.monotonic() + timeout
        while True:
            st = self.read_status()
            if st.get("dialogs"):
                self.dismiss_dialogs()
            if st.get("errors") or st.get("tracebacks") or st.get("widgetErrors"):
                self.fail("error output while waiting for " + what + ":\n  " + "\n  ".join(
                    st.get("errors", []) + st.get("tracebacks", []) + st.get("widgetErrors", [])))
            if predicate(st):
                return st
            if time.monotonic() > deadline:
                self.fail(f"timed out after {timeout:.0f} s waiting for {what}")
            self.page.wait_for_timeout(self.poll * 1000)

    # -- steps ---------------------------------------------------------------------------
    def open(self, timeout: float = 90.0, kernel: bool = True):
        """Show the notebook with the file browser open and wait for its kernel to be idle;
        ``kernel=False``: as a saved notebook is read, with no kernel."""
        t0 = time.monotonic()
        self.page, fresh = self.lab.open(self.relpath, timeout, kernel=kernel)
        if fresh:
            t0 = self.timings.mark("load page", t0)
        self.wait_until(lambda s: s["phase"] == "panel", "JupyterLab to show the notebook", timeout)
        if fresh:  # the student's layout: the file browser open beside the notebook
            import labview
            if not labview.show_file_browser(self.page):
                self.fail("could not open the file browser in the left sidebar")
        t0 = self.timings.mark("lab ready", t0)
        if not kernel:
            self.wait_until(lambda s: s["phase"] == "panel" and s.get("ready") and s.get("kernel") is None,
                            "the notebook to open with no kernel", timeout)
            return self
        self.wait_until(lambda s: s["phase"] == "panel" and s.get("ready") and s.get("kernel") == "idle"
                        and s.get("connection") == "connected",
                        "the notebook to open with an idle kernel", timeout)
        self.timings.mark("kernel idle", t0)
        return self

    def run_all(self, timeout: float = 240.0):
        t0 = time.monotonic()
        before = self.read_status()
        if before.get("executed"):
            self.fail(f"{before['executed']} code cells already have an execution count before Run All "
                      "(notebooks are committed without outputs)")
        self.page.evaluate("""(id) => { const app = window.jupyterapp; app.shell.activateById(id);
                               return app.commands.execute('notebook:run-all-cells'); }""", before["panelId"])
        # started: at least one cell got queued/ran; finished: every code cell has a count and the
        # kernel is idle with nothing running (checked twice in a row, so a between-cells idle
        # does not count).
        self.wait_until(lambda s: s.get("executed", 0) > 0 or s.get("running", 0) > 0 or s.get("kernel") == "busy",
                        "Run All to start", 30)
        stable = [0]

        def done(s):
            ok = (s.get("executed") == s.get("ncode") and s.get("running") == 0 and s.get("kernel") == "idle")
            stable[0] = stable[0] + 1 if ok else 0
            return stable[0] >= 2

        st = self.wait_until(done, "Run All to finish (every code cell executed, kernel idle)", timeout)
        counts = st["counts"]
        if len(set(counts)) != len(counts):
            self.fail(f"execution counts are not distinct: {counts}")
        self.timings.mark("run all", t0)
        return st

    def check_no_errors(self, page_problems: bool = True):
        st = self.read_status()
        problems = st.get("errors", []) + st.get("tracebacks", []) + st.get("widgetErrors", [])
        if page_problems:
            problems += self.page_problems
        if problems:
            self.fail("error output:\n  " + "\n  ".join(problems))
        return st

    def panel_count(self) -> int:
        """How many output areas hold both a slider and an ipympl canvas (right now)."""
        res = self.page.evaluate(_FIND_PANEL_JS, [self.read_status().get("panelId"), 10_000])
        return int(res.get("npanels") or 0)

    def find_panel(self, index: int = 0, timeout: float = 60.0) -> str:
        """CSS selector of the ``index``-th output area with a slider and an ipympl canvas."""
        deadline = time.monotonic() + timeout
        panel_id = self.read_status().get("panelId")
        while True:
            res = self.page.evaluate(_FIND_PANEL_JS, [panel_id, index])
            sel = f'[data-gm-panel="{index}"]'
            if res.get("found") and self.page.evaluate(_CANVAS_READY_JS, sel):
                return sel
            if time.monotonic() > deadline:
                why = res.get("why") if not res.get("found") else "the ipympl canvas stayed blank"
                self.fail(f"no interactive panel #{index} after {timeout:.0f} s: {why}")
            self.page.wait_for_timeout(self.poll * 1000)

    def slider_value(self, sel, index: int = 0) -> dict:
        """Exact value, range and label of the panel's ``index``-th slider (noUiSlider API; aria-* are rounded)."""
        return self.page.evaluate(_SLIDER_VALUE_JS, [sel, index])

    def slider_count(self, sel) -> int:
        return self.page.locator(f"{sel} .widget-slider").count()

    def _slider_state(self, sel, index):
        slider = self.page.locator(f"{sel} .widget-slider").nth(index)
        handle = slider.locator(".noUi-handle").first
        readout = slider.locator(".widget-readout").first
        r = readout.inner_text() if readout.count() else ""
        return handle, r, self.slider_value(sel, index).get("value")

    def snapshot(self, sel) -> str:
        return self.page.evaluate(_SNAPSHOT_JS, sel)

    def wait_still(self, sel, still: float = 0.3, timeout: float = 20.0, busy_ok: bool = False):
        """Wait until the panel's canvas has not changed for ``still`` seconds and the kernel is idle
        (so a late initial render is not mistaken for the slider's effect). If it never settles,
        raise :class:`CanvasBusy` when ``busy_ok``, else fail."""
        deadline = time.monotonic() + timeout
        last = self.snapshot(sel)
        since = time.monotonic()
        while time.monotonic() < deadline:
            self.page.wait_for_timeout(50)
            snap = self.snapshot(sel)
            if snap != last:
                last, since = snap, time.monotonic()
            elif time.monotonic() - since >= still and self.read_status().get("kernel") == "idle":
                return last
        msg = (f"the panel's canvas kept changing (or the kernel stayed busy) for {timeout:.0f} s "
               "before any slider was moved")
        if busy_ok:
            raise CanvasBusy(msg)
        self.fail(msg)

    def move_slider(self, sel: str, index: int = 0, fraction: float = 0.05, max_presses: int = 15,
                    change_timeout: float = 20.0) -> SliderResult:
        """Focus the panel's ``index``-th slider handle, press ArrowRight (ArrowLeft when in the
        upper half of the range) until the value moved by ~``fraction`` of the range, and wait up
        to ``change_timeout`` s for the canvas pixels to change."""
        t0 = time.monotonic()
        handle, r0, v0 = self._slider_state(sel, index)
        handle.scroll_into_view_if_needed()
        before = self.wait_still(sel)
        info = self.slider_value(sel, index)
        lo, hi, v = info.get("min"), info.get("max"), info.get("value")
        if None in (lo, hi, v):
            self.fail(f"cannot read slider #{index} of the panel: {info}")
        key = "ArrowRight" if v <= (lo + hi) / 2 else "ArrowLeft"
        target = abs(hi - lo) * fraction
        handle.focus()
        presses = 0
        while presses < max_presses:
            handle.press(key)
            presses += 1
            now = self.slider_value(sel, index).get("value")
            if now is None or abs(now - v) >= target:
                break
        _, r1, v1 = self._slider_state(sel, index)
        changed = False
        deadline = time.monotonic() + change_timeout
        while time.monotonic() < deadline:
            if self.snapshot(sel) != before:
                changed = True
                break
            st = self.read_status()
            if st.get("errors") or st.get("tracebacks") or st.get("widgetErrors"):
                break
            self.page.wait_for_timeout(self.poll * 1000)
        res = SliderResult(changed, r0, r1, v0, v1, round(time.monotonic() - t0, 2), presses,
                           detail=f"slider #{index} {info.get('label', '')!r}: {presses} x {key}")
        self.timings.mark("slider", t0)
        return res

    def close(self):
        t0 = time.monotonic()
        if self.failed:
            self.lab.discard()  # start the next notebook from a fresh page load
            self.server.delete_sessions()  # ... and a clean server
        else:
            self.lab.close_notebook(self.relpath)
            self.server.delete_sessions_later(self.relpath)
        self.timings.mark("close", t0)


def check_interactive_notebook(lab: LabBrowser, relpath: str, change_timeout: float = 20.0, on_open=None,
                               after_run=None):
    """The whole browser check of one chapter notebook; returns (SliderResult, timings dict).

    ``on_open()`` is called once the notebook has an idle kernel (the tests prestart the next
    notebook's kernel there); ``after_run(nbp)`` right after Run All, before any slider moves
    (the layout and panel-state checks of test_notebooks_in_lab)."""
    with NotebookPage(lab, relpath) as nbp:
        nbp.open()
        if on_open is not None:
            on_open()
        nbp.run_all()
        nbp.check_no_errors()
        if after_run is not None:
            after_run(nbp)
        sel = nbp.find_panel(0)
        # A panel whose canvas never stands still (an animation) cannot show the slider's effect:
        # then the next panels (up to three) are used instead.
        busy = []
        for k in range(3):
            try:
                nbp.wait_still(sel, timeout=20.0 if k == 0 else 8.0, busy_ok=True)
                break
            except CanvasBusy as e:
                busy.append(f"panel #{k}: {e}")
                if k + 1 >= min(3, nbp.panel_count()):
                    nbp.fail("no interactive panel with a still canvas: " + "; ".join(busy))
                sel = nbp.find_panel(k + 1)
        # The first slider decides; if it leaves the picture unchanged (e.g. a parameter that only
        # matters in another mode) up to two more sliders of the same panel get a shorter chance.
        tried = []
        for index in range(min(3, nbp.slider_count(sel))):
            res = nbp.move_slider(sel, index, change_timeout=change_timeout if index == 0 else 6.0)
            nbp.check_no_errors()
            tried.append(res)
            if res.changed and res.slider_moved:
                break
        if not any(r.slider_moved for r in tried):
            nbp.fail("no slider of the first panel moved: " + "; ".join(
                f"{r.detail} (readout {r.readout_before!r})" for r in tried))
        res.detail = f"panel #{k}, {res.detail}" + (f" ({'; '.join(busy)})" if busy else "")
        if not (res.changed and res.slider_moved):
            nbp.fail(f"the figure did not change within {change_timeout:.0f} s after moving the panel's "
                     "sliders: " + "; ".join(f"{r.detail}, readout {r.readout_before!r} -> {r.readout_after!r}"
                                             for r in tried))
        return res, nbp.timings.phases


# --------------------------------------------------------------------------------------------
# Self-check notebook: one working panel and one whose callback does nothing
# --------------------------------------------------------------------------------------------

def _code(src, n=None):
    if n is None:
        n = [0]
    n[0] += 1
    return {"cell_type": "code", "execution_count": None, "id": f"selfcheck-{n[0]}", "metadata": {},
            "outputs": [], "source": src}


def selfcheck_notebook() -> dict:
    """A notebook with two ipympl panels: the first slider moves a line, the second's callback
    does nothing. Plain ipywidgets + ipympl (no gm_core), so it tests only the detector."""
    cells = [
        _code("%matplotlib widget\n"
              "import numpy as np\n"
              "import ipywidgets as W\n"
              "import matplotlib.pyplot as plt\n"
              "\n"
              "def panel(live):\n"
              "    with plt.ioff():\n"
              "        fig, ax = plt.subplots(figsize=(4, 3))\n"
              "    fig.canvas.header_visible = fig.canvas.footer_visible = fig.canvas.toolbar_visible = False\n"
              "    ax.set(xlim=(-1.2, 1.2), ylim=(-1.2, 1.2))\n"
              "    (line,) = ax.plot([0, np.cos(0.3)], [0, np.sin(0.3)], lw=3)\n"
              "    theta = W.FloatSlider(value=0.3, min=-3.14, max=3.14, step=0.01, description='theta',\n"
              "                          continuous_update=True)\n"
              "\n"
              "    def update(change):\n"
              "        if live:\n"
              "            t = change['new']\n"
              "            line.set_data([0, np.cos(t)], [0, np.sin(t)])\n"
              "            fig.canvas.draw_idle()\n"
              "        # else: the bug the browser test must catch, the picture never follows the slider\n"
              "\n"
              "    theta.observe(update, names='value')\n"
              "    return W.HBox([W.VBox([theta]), fig.canvas])\n"),
        _code("panel(live=True)"),
        _code("panel(live=False)"),
    ]
    return {"cells": cells, "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python",
                                                        "name": "python3"}},
            "nbformat": 4, "nbformat_minor": 5}


SELFCHECK_PATH = "_browser_selfcheck/selfcheck.ipynb"

"""Install the course's JupyterLab defaults (jupyter/overrides.json) where JupyterLab reads them.

JupyterLab's public mechanism for site-wide defaults is an overrides file in its application
settings directory, ``{sys.prefix}/share/jupyter/lab/settings/``. Each package may drop its own file
into ``overrides.d/`` there (merged in name order, below a user's own ``overrides.json``), so the
course never touches a file someone else owns. Ours turns the "Get notified about official Jupyter
news?" prompt and the update check off (``@jupyterlab/apputils-extension:notification``), and
sends widget messages to the kernel's main shell, not to a subshell
(``@jupyterlab/apputils-extension:kernels-settings``, ``commsOverSubshells``). ipykernel >= 7
serves each subshell on its own thread, so with JupyterLab's default (one subshell per comm target)
ipympl draws a live figure for the browser on that thread while a slider update draws it on the
main thread; matplotlib is not thread-safe, and under load the browser got half-drawn pictures
(issue 19; ipympl issue 610, JupyterLab issue 19719). The setting applies to kernels connected
after JupyterLab starts.

    python tools/lab_settings.py                 # into this Python's JupyterLab (make lab, postBuild)
    python tools/lab_settings.py --into DIR      # into another settings dir (the browser tests)

The browser tests (tests/browser/browserlab.py) start JupyterLab with ``--LabApp.app_settings_dir``
pointing at a temporary folder filled by :func:`install`, so they see exactly what a student sees.
"""
from __future__ import annotations

import argparse
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SOURCE = ROOT / "jupyter" / "overrides.json"
NAME = "gm-course.json"


def default_settings_dir() -> Path:
    """JupyterLab's application settings dir of this Python (``LabApp.app_settings_dir``'s default)."""
    try:
        from jupyterlab.commands import get_app_dir
        return Path(get_app_dir()) / "settings"
    except ImportError:  # JupyterLab not installed yet: its default location
        return Path(sys.prefix) / "share" / "jupyter" / "lab" / "settings"


def install(settings_dir: Path | None = None) -> Path:
    """Copy the course's overrides into ``settings_dir/overrides.d/``; returns the file written."""
    settings_dir = Path(settings_dir) if settings_dir is not None else default_settings_dir()
    target = settings_dir / "overrides.d" / NAME
    target.parent.mkdir(parents=True, exist_ok=True)
    if not target.exists() or target.read_bytes() != SOURCE.read_bytes():
        shutil.copyfile(SOURCE, target)
    return target


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--into", type=Path, default=None, help="settings dir (default: this Python's JupyterLab)")
    args = ap.parse_args(argv)
    print(f"JupyterLab course settings: {install(args.into)}")


if __name__ == "__main__":
    main()

"""Separate virtual environments for the heavy publishing tools, kept out of the course's .venv.

    python tools/venvs.py kits     # .venv-kits: otter-grader, nbgrader (+ the course's core and [lab] deps)
    python tools/venvs.py site     # .venv-site: Jupyter Book 1 / myst-nb, playwright (+ the same)

Each venv lives in the repository (git-ignored) and is made from PyPI with the venv's own pip the
first time it is needed, and again when its package list changes (a stamp file records it). The
course itself is *not* installed into them: the tools run with ``PYTHONPATH`` set to the
repository, so they always see this checkout's gm_core. ``ensure(name)`` returns the venv's
``bin`` folder; it raises ``VenvError`` (with pip's message) when the packages cannot be installed.
"""
from __future__ import annotations

import hashlib
import subprocess
import sys
from pathlib import Path

import tomllib

ROOT = Path(__file__).resolve().parent.parent

TOOLS = {
    "kits": ["otter-grader>=6", "nbgrader>=0.9", "ipympl>=0.9.3"],
    "site": ["jupyter-book>=1.0.4,<2", "playwright>=1.40", "pillow>=10.0"],
}


class VenvError(RuntimeError):
    """The tools of a publishing venv could not be installed."""


def course_requirements():
    """The course's core and [lab] requirements, from pyproject.toml."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    return list(project["dependencies"]) + list(project["optional-dependencies"]["lab"])


def path_of(name: str) -> Path:
    return ROOT / f".venv-{name}"


def ensure(name: str, quiet: bool = True) -> Path:
    if name not in TOOLS:
        raise ValueError(f"name: one of {sorted(TOOLS)}, not {name!r}")
    venv = path_of(name)
    reqs = TOOLS[name] + course_requirements()
    digest = hashlib.sha256("\n".join(reqs).encode()).hexdigest()[:16]
    stamp = venv / ".gm-stamp"
    if stamp.exists() and stamp.read_text().strip() == digest and (venv / "bin" / "python").exists():
        return venv / "bin"
    if not (venv / "bin" / "python").exists():
        subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True)
    pip = [str(venv / "bin" / "python"), "-m", "pip", "install", "--disable-pip-version-check"]
    if quiet:
        pip.append("--quiet")
    res = subprocess.run(pip + reqs, capture_output=True, text=True)
    if res.returncode != 0:
        raise VenvError(f"could not install {name} tools into {venv}: {res.stderr.strip()[-1500:]}")
    stamp.write_text(digest + "\n")
    return venv / "bin"


def main(argv=None):
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1 or args[0] not in TOOLS:
        print(f"usage: python tools/venvs.py {{{','.join(TOOLS)}}}", file=sys.stderr)
        return 2
    try:
        print(ensure(args[0], quiet=False))
    except VenvError as exc:
        print(f"venvs: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Separate virtual environments for the heavy publishing tools, kept out of the course's .venv.

    python tools/venvs.py kits     # .venv-kits: otter-grader, nbgrader (+ the course's core and [lab] deps)
    python tools/venvs.py site     # .venv-site: Jupyter Book 1 / myst-nb, playwright (+ the same),
                                   # and the site's npm files (site/node_modules)
    python tools/venvs.py gradescope   # GRADESCOPE: an autograder folder made by the
                                   # Gradescope kit's own setup.sh (tests/test_gradescope_kit.py)

Each venv lives in the repository (git-ignored) and is made from PyPI with the venv's own pip the
first time it is needed, and again when its package list changes (a stamp file records it). The
course itself is *not* installed into them: the tools run with ``PYTHONPATH`` set to the
repository, so they always see this checkout's gm_core. ``ensure(name)`` returns the venv's
``bin`` folder; it raises ``VenvError`` (with pip's message) when the packages cannot be installed.
``make test`` makes all three in its set-up (a failure there only makes the tests that need them
skip), so the tests themselves install nothing from PyPI.
"""
from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:    # Python 3.10: the same parser from PyPI (tomli, declared for < 3.11)
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent

TOOLS = {
    "kits": ["otter-grader>=6", "nbgrader>=0.9", "ipympl>=0.9.3"],
    "site": ["jupyter-book>=1.0.4,<2", "playwright>=1.40", "pillow>=10.0", 'tomli>=1.1; python_version < "3.11"'],
}


# Installed as part of an extra but left out again: jsonschema's optional checker of the "iri"
# string formats (pulled in through jupyter-events' jsonschema[format-nongpl]) builds a Lark
# grammar at every import of nbformat, 2-3 s of CPU for each otter, nbgrader and Jupyter Book
# command; nothing these tools validate uses those formats (jsonschema skips the check without it).
LEAVE_OUT = ["rfc3987-syntax"]


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
    digest = hashlib.sha256("\n".join(reqs + ["-"] + LEAVE_OUT).encode()).hexdigest()[:16]
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
    subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "uninstall", "--yes", "--quiet", *LEAVE_OUT],
                   capture_output=True, text=True)
    stamp.write_text(digest + "\n")
    return venv / "bin"


#: The Gradescope autograder folder. As root it lives where any user may enter (the grader runs
#: each notebook as a user of its own, which must reach the venv's Python: a clone in a 0700
#: temporary folder would hide it), shared by the clones of this machine; else in the checkout.
GRADESCOPE = (Path("/var/tmp/gm-course-autograder") if os.geteuid() == 0
              else ROOT / ".venv-gradescope")
#: The Python that makes its venv: the system's, as on Gradescope's image (a Python under /root,
#: pyenv's say, cannot be run by the notebooks' own user); else this one.
AUTOGRADER_PYTHON = "/usr/bin/python3" if Path("/usr/bin/python3").exists() else sys.executable


def unpack_kit(kit: Path, root: Path) -> None:
    """Unpack a Gradescope zip into ``root/source`` as Gradescope does (file modes kept)."""
    src = root / "source"
    if src.exists():
        shutil.rmtree(src)
    src.mkdir(parents=True)
    with zipfile.ZipFile(kit) as zf:
        zf.extractall(src)
        for info in zf.infolist():
            os.chmod(src / info.filename, (info.external_attr >> 16) & 0o777)


def run_setup(root: Path) -> subprocess.CompletedProcess:
    """The kit's setup.sh, in ``root`` (GM_AUTOGRADER_ROOT), with this Python making its venv."""
    env = {k: v for k, v in os.environ.items() if k not in {"PYTHONPATH", "VIRTUAL_ENV"}}
    env.update(GM_AUTOGRADER_ROOT=str(root), GM_AUTOGRADER_PYTHON=AUTOGRADER_PYTHON)
    return subprocess.run(["bash", str(root / "source" / "setup.sh")], cwd=root, env=env,
                          capture_output=True, text=True, timeout=1800)


def gradescope() -> Path:
    """An autograder folder (:data:`GRADESCOPE`) whose ``gm-venv`` the Gradescope kit's own
    setup.sh made, in a fresh folder, from the package index: made again whenever the course's
    requirements or setup.sh change. A test unpacks the current zip into it and runs setup.sh
    again (which then only installs the course from the zip), instead of downloading numpy,
    scipy and matplotlib for every run."""
    sys.path.insert(0, str(ROOT / "tools"))
    import gradescope_kit

    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    reqs = list(project["dependencies"]) + list(project["optional-dependencies"]["grader"]) + [gradescope_kit.SETUP_SH]
    digest = hashlib.sha256("\n".join(reqs).encode()).hexdigest()[:16]
    stamp = GRADESCOPE / ".gm-stamp"
    if stamp.exists() and stamp.read_text().strip() == digest and (GRADESCOPE / "gm-venv" / "bin" / "python").exists():
        return GRADESCOPE
    if GRADESCOPE.is_symlink() or (GRADESCOPE.exists() and GRADESCOPE.stat().st_uid != os.geteuid()):
        raise VenvError(f"{GRADESCOPE} is a link or someone else's: remove it by hand")
    if GRADESCOPE.exists():
        shutil.rmtree(GRADESCOPE)
    GRADESCOPE.mkdir(mode=0o755)
    GRADESCOPE.chmod(0o755)
    kit = gradescope_kit.build_kit(GRADESCOPE / "kit.zip", exercises=["1.1"])
    unpack_kit(kit, GRADESCOPE)
    res = run_setup(GRADESCOPE)
    if res.returncode != 0:
        raise VenvError(f"the Gradescope kit's setup.sh failed: {(res.stdout + res.stderr).strip()[-1500:]}")
    stamp.write_text(digest + "\n")
    return GRADESCOPE


def main(argv=None):
    args = sys.argv[1:] if argv is None else argv
    known = [*TOOLS, "gradescope"]
    if not args or any(a not in known for a in args):
        print(f"usage: python tools/venvs.py {{{','.join(known)}}} ...", file=sys.stderr)
        return 2
    for name in args:
        try:
            if name == "gradescope":
                print(gradescope())
            else:
                print(ensure(name, quiet=False))
                if name == "site":
                    sys.path.insert(0, str(ROOT / "tools"))
                    import build_site

                    print(build_site.npm_assets())
        except (VenvError, subprocess.CalledProcessError, OSError) as exc:
            print(f"venvs: {name}: {exc}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Write the course's *student build*: ``python tools/student_build.py`` (``make student-build``).

    python tools/student_build.py [--out build/student] [--wheel]

The student build is the course a graded student installs (for otter-grader or nbgrader
assignments): the packages without the answer keys (``gm_core/checks/keys``, see
``gm_core/checks/answer_key.py``) and without the worked solutions (``solutions/`` is never part
of the packages). In it every check still runs its probes and says that the grader will judge
the answer; ``.reference``, ``.solution()`` and the other routes to a key raise
``AnswerKeyHidden``. It is what the grader's sandbox shows a notebook (``gm_grader/view.py``) and
what a Gradescope notebook meets (its kit closes the keys' folder). Self-study installs
(``make lab``, Binder) keep the keys.

It writes ``<out>/gm-course-student/`` (``pyproject.toml`` with the version marked ``+student``,
``README.md``, ``LICENSE``, ``gm_core/``, ``gm_grader/``), installable with ``pip install
<out>/gm-course-student``; ``--wheel`` also builds ``<out>/gm_course-<version>+student-py3-none-any.whl``
(``pip wheel``, which fetches setuptools from the package index).
"""
from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OUT = ROOT / "build" / "student"
PACKAGES = ("gm_core", "gm_grader")
FILES = ("README.md", "LICENSE")
#: What the student build leaves out of the packages (paths relative to the repository).
LEFT_OUT = ("gm_core/checks/keys",)


def _ignore(folder: str, names: list[str]) -> set[str]:
    here = Path(folder).resolve().relative_to(ROOT).as_posix()
    drop = {n for n in names if n == "__pycache__" or n.endswith((".pyc", ".pyo"))}
    return drop | {n for n in names if f"{here}/{n}" in LEFT_OUT}


def build(out: Path = DEFAULT_OUT) -> Path:
    """Write the student build's source tree under ``out``; return its folder."""
    tree = Path(out) / "gm-course-student"
    if tree.exists():
        shutil.rmtree(tree)
    tree.mkdir(parents=True)
    for pkg in PACKAGES:
        shutil.copytree(ROOT / pkg, tree / pkg, ignore=_ignore)
    for name in FILES:
        shutil.copyfile(ROOT / name, tree / name)
    text = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
    marked, n = re.subn(r'(?m)^version = "([^"+]+)"$', r'version = "\1+student"', text, count=1)
    if n != 1:
        raise ValueError("pyproject.toml: no 'version = \"...\"' line to mark as the student build")
    (tree / "pyproject.toml").write_text(marked, encoding="utf-8")
    for left in LEFT_OUT:
        if (tree / left).exists():
            raise AssertionError(f"the student build still holds {left}")
    return tree


def wheel(tree: Path, out: Path) -> Path:
    """Build the student build's wheel into ``out``; return its path."""
    before = set(out.glob("*.whl"))
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--quiet", "--no-deps",
                    "--disable-pip-version-check", "-w", str(out), str(tree)], check=True)
    made = sorted(set(out.glob("*+student*.whl")) - before) or sorted(out.glob("*+student*.whl"))
    if not made:
        raise RuntimeError(f"pip wheel wrote no student wheel into {out}")
    return made[-1]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT, help="folder to write into")
    ap.add_argument("--wheel", action="store_true", help="also build the wheel (pip wheel)")
    args = ap.parse_args(argv)
    tree = build(args.out)
    print(f"student build (no answer keys, no solutions): {tree}")
    if args.wheel:
        print(f"wheel: {wheel(tree, args.out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

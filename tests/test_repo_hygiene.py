"""Notebooks are committed without outputs, and no solution leaks into exercises/."""
import json
import re
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def tracked_notebooks():
    try:
        out = subprocess.run(["git", "ls-files", "*.ipynb"], cwd=ROOT, capture_output=True, text=True,
                             check=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        out = []
    if not out:  # not a git checkout (e.g. an sdist): check every notebook in the course folders
        out = [str(p.relative_to(ROOT)) for d in ("book", "exercises", "solutions")
               for p in (ROOT / d).glob("*.ipynb")]
    return out


NOTEBOOKS = tracked_notebooks()


def test_there_are_notebooks():
    assert any(p.startswith("book/") for p in NOTEBOOKS)


@pytest.mark.parametrize("path", NOTEBOOKS)
def test_notebook_has_no_outputs(path):
    nb = json.loads((ROOT / path).read_text())
    dirty = [i for i, c in enumerate(nb["cells"]) if c["cell_type"] == "code"
             and (c.get("outputs") or c.get("execution_count") is not None)]
    assert not dirty, f"{path}: cells {dirty} have outputs; run tools/strip_outputs.py {path}"


@pytest.mark.parametrize("path", [p for p in NOTEBOOKS if p.startswith("exercises/")])
def test_no_solution_markers_in_exercises(path):
    text = (ROOT / path).read_text()
    assert "BEGIN SOLUTION" not in text and "END SOLUTION" not in text, (
        f"{path} contains a solution marker; regenerate with `make exercises`")


BOOK = [p for p in NOTEBOOKS if p.startswith("book/")]
LINK = re.compile(r"\]\((?!https?:|#|mailto:)([^)#\s]+\.(?:ipynb|md))(?:#[^)]*)?\)")


@pytest.mark.parametrize("path", BOOK)
def test_book_links_resolve(path):
    """Relative links in the book point at files that exist; exercise links go to the student's
    workspace/ copy (made from exercises/ by `make lab`), never to the tracked originals."""
    nb = json.loads((ROOT / path).read_text())
    text = "".join("".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "markdown")
    for target in LINK.findall(text):
        resolved = (ROOT / path).parent / target
        assert "exercises/" not in target, f"{path}: link {target} should point into ../workspace/"
        if "workspace/" in target:
            resolved = ROOT / "exercises" / resolved.name
        assert resolved.exists(), f"{path}: broken link {target}"


def test_ruff_is_clean():
    """`ruff check` passes with the project's configuration (pyproject.toml [tool.ruff])."""
    import shutil
    import sys

    ruff = shutil.which("ruff") or str(Path(sys.executable).parent / "ruff")
    if not Path(ruff).exists():
        pytest.skip("ruff is not installed (it is in the test extra: pip install -e '.[test]')")
    out = subprocess.run([ruff, "check", "--no-cache", "--quiet", "."], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, "ruff check found problems:\n" + out.stdout[-4000:] + out.stderr[-2000:]

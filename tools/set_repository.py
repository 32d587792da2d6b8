"""Set where the course is published, in its one place, and write every link that derives from it.

    python tools/set_repository.py https://github.com/OWNER/NAME [--branch main]

The repository and branch live in ``pyproject.toml`` under ``[tool.gm-course]``. From them come
the Binder badge and launch link of ``README.md`` (which open ``book/00-start-here.ipynb`` in
JupyterLab), the start page's own Binder and website links, the website's address (GitHub Pages:
``https://OWNER.github.io/NAME/``, where ``.github/workflows/site.yml`` publishes it),
``repository-code`` of ``CITATION.cff``, and, when the site is built, every page's
"open in JupyterLab on Binder" link, the theme's repository button and the links to files that
are not pages (``tools/build_site.py`` reads them). This script rewrites the value and the links
written in files; ``--check`` only reports whether the files agree with it (exit 1 if not).
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:    # Python 3.10: the same parser from PyPI (tomli, declared for < 3.11)
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent
START_PAGE = "book/00-start-here.ipynb"
GITHUB = re.compile(r"https://github\.com/([A-Za-z0-9][A-Za-z0-9-]{0,38})/([A-Za-z0-9._-]{1,100})")
BRANCH = re.compile(r"[A-Za-z0-9][A-Za-z0-9._/-]{0,100}")
# Binder links written in files (any repository, any branch, any path), and the badge around one.
BINDER_LINK = re.compile(r"https://mybinder\.org/v2/gh/[^/\s)]+/[^/\s)]+/[^?\s)]+\?urlpath=lab/tree/[^\s)]+")
# The website's address on GitHub Pages, as written in files.
SITE_LINK = re.compile(r"https://[A-Za-z0-9-]+\.github\.io/[A-Za-z0-9._-]+/")
TOOL_TABLE = re.compile(r"(\[tool\.gm-course\]\n(?:#.*\n)*)repository = \"[^\"]*\"\nbranch = \"[^\"]*\"\n")
CFF_REPO = re.compile(r'^repository-code: "[^"]*"$', re.M)


def read(root: Path = ROOT) -> tuple[str, str]:
    """(repository URL, branch) from pyproject.toml's [tool.gm-course]."""
    tool = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["gm-course"]
    return tool["repository"], tool["branch"]


def binder_url(path: str, root: Path = ROOT, repository: str | None = None, branch: str | None = None) -> str:
    """The Binder link opening ``path`` (relative to the repository) in JupyterLab."""
    if repository is None or branch is None:
        repository, branch = read(root)
    m = GITHUB.fullmatch(repository)
    if not m:
        raise ValueError(f"repository: a https://github.com/OWNER/NAME address, not {repository!r}")
    return f"https://mybinder.org/v2/gh/{m.group(1)}/{m.group(2)}/{branch}?urlpath=lab/tree/{path}"


def site_url(root: Path = ROOT, repository: str | None = None) -> str:
    """The website's address: GitHub Pages of the repository (a project site)."""
    if repository is None:
        repository, _ = read(root)
    m = GITHUB.fullmatch(repository)
    if not m:
        raise ValueError(f"repository: a https://github.com/OWNER/NAME address, not {repository!r}")
    return f"https://{m.group(1).lower()}.github.io/{m.group(2)}/"


def file_url(path: str, root: Path = ROOT) -> str:
    """The repository's page of ``path`` (a file the site does not publish)."""
    repository, branch = read(root)
    return f"{repository}/blob/{branch}/{path}"


def expected(root: Path = ROOT) -> dict[str, list[str]]:
    """{file: the links it must hold} for the current [tool.gm-course]."""
    repository, _ = read(root)
    start, site = binder_url(START_PAGE, root), site_url(root)
    return {"README.md": [start, site], START_PAGE: [start, site],
            "CITATION.cff": [f'repository-code: "{repository}"']}


def problems(root: Path = ROOT) -> list[str]:
    """What disagrees with [tool.gm-course]: a missing link, or a Binder link to anything else."""
    out = []
    start, site = binder_url(START_PAGE, root), site_url(root)
    for name, needs in expected(root).items():
        text = (root / name).read_text()
        out += [f"{name}: missing {n}" for n in needs if n not in text]
        out += [f"{name}: {link} does not derive from [tool.gm-course]"
                for link in BINDER_LINK.findall(text) if link != start]
        out += [f"{name}: {link} does not derive from [tool.gm-course]"
                for link in SITE_LINK.findall(text) if link != site]
    return out


def write(repository: str, branch: str = "main", root: Path = ROOT) -> list[str]:
    """Set [tool.gm-course] and rewrite the links of README.md, the start page and CITATION.cff;
    return the files changed."""
    if not isinstance(repository, str) or not GITHUB.fullmatch(repository.rstrip("/")):
        raise ValueError(f"repository: a https://github.com/OWNER/NAME address (Binder builds GitHub "
                         f"repositories), not {repository!r}")
    repository = repository.rstrip("/").removesuffix(".git")
    if not isinstance(branch, str) or not BRANCH.fullmatch(branch) or ".." in branch:
        raise ValueError(f"branch: a git branch name, not {branch!r}")
    py = root / "pyproject.toml"
    text = py.read_text()
    if not TOOL_TABLE.search(text):
        raise ValueError("pyproject.toml has no [tool.gm-course] table with repository and branch")
    new = {py: TOOL_TABLE.sub(lambda m: f'{m.group(1)}repository = "{repository}"\nbranch = "{branch}"\n', text, count=1)}
    start, site = binder_url(START_PAGE, root, repository, branch), site_url(root, repository)
    for page in (root / "README.md", root / START_PAGE):
        new[page] = SITE_LINK.sub(site, BINDER_LINK.sub(start, page.read_text()))
    cff = root / "CITATION.cff"
    new[cff] = CFF_REPO.sub(f'repository-code: "{repository}"', cff.read_text(), count=1)
    changed = []
    for path, value in new.items():
        if path.read_text() != value:
            path.write_text(value)
            changed.append(path.name)
    return changed


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python tools/set_repository.py", description=__doc__.splitlines()[0])
    ap.add_argument("repository", nargs="?", help="https://github.com/OWNER/NAME")
    ap.add_argument("--branch", default="main")
    ap.add_argument("--check", action="store_true", help="only check that the files agree with pyproject.toml")
    args = ap.parse_args(argv)
    if args.check or not args.repository:
        bad = problems()
        print("\n".join(bad) if bad else f"links agree with [tool.gm-course]: {' '.join(read())}")
        return 1 if bad else 0
    try:
        changed = write(args.repository, args.branch)
    except ValueError as exc:
        print(f"set_repository: {exc}", file=sys.stderr)
        return 2
    print(f"[tool.gm-course] = {args.repository} ({args.branch}); rewrote {', '.join(changed) or 'nothing'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

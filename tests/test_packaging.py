"""Set-up stays consistent: the environment files match pyproject.toml's dependency groups, every
package the code imports is declared, the core installs without the lab or test tools, Binder
gets an exact Python pin and no test tools, and the licences and citation are in place."""
import ast
import functools
import importlib.metadata as md
import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

try:
    import tomllib
except ModuleNotFoundError:    # Python 3.10 (tomli is declared in [test] for it)
    import tomli as tomllib

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())
PROJECT = PYPROJECT["project"]
SELF = PROJECT["name"]

# repo2docker's own pattern for the Python version of an environment.yml
# (repo2docker/buildpacks/conda/__init__.py: PYTHON_REGEX, used with .match on each dependency).
REPO2DOCKER_PYTHON = re.compile(r"python\s*=+\s*([\d\.]*)")

# Peer libraries the SE(2) benchmark and one comparison test use when present (each guarded by an
# ImportError / importorskip); never needed to run or test the course.
OPTIONAL_PEERS = {"jax", "jaxlie", "geomstats"}
TEST_TOOLS = {"pytest", "pytest-xdist", "hypothesis", "playwright", "ruff", "mpmath", "pyyaml"}
# Back-ports imported only where the standard library lacks the module (``except
# ModuleNotFoundError``), declared with a python_version marker: {module: the marker's Python}.
BACKPORTS = {"tomli": "3.11"}


def _parse(req):
    m = re.match(r"^\s*([A-Za-z0-9_.\-]+)\s*(\[[^\]]*\])?\s*(?:>=\s*([0-9][^,;\s]*))?", req)
    return m.group(1).lower().replace("_", "-"), m.group(3)


def _below(req):
    """The Python version a requirement is limited to (``; python_version < "3.11"``), or None."""
    m = re.search(r""";\s*python_version\s*<\s*['"]([\d.]+)['"]\s*$""", req)
    return m.group(1) if m else None


def group(name, python="3.11"):
    """{distribution: lower bound} of the core ("core") or an extra, self-references left out;
    requirements limited to Pythons below ``python`` (the environment files pin 3.11) left out."""
    reqs = PROJECT["dependencies"] if name == "core" else PROJECT["optional-dependencies"][name]
    keep = [r for r in reqs if _parse(r)[0] != SELF
            and not (_below(r) and tuple(map(int, python.split("."))) >= tuple(map(int, _below(r).split("."))))]
    return dict(_parse(r) for r in keep)


def groups(*names):
    out = {}
    for n in names:
        out.update(group(n))
    return out


def env_file(path):
    env = yaml.safe_load((ROOT / path).read_text())
    out = {}
    for dep in env["dependencies"]:
        if isinstance(dep, str):
            name, low = _parse(dep)
            if name not in {"python", "pip", "setuptools"}:
                out[name] = low
    return env, out


def test_extras_the_readme_promises():
    assert set(group("core")) == {"numpy", "scipy", "matplotlib", "typing-extensions"}, (
        "the core is numpy/scipy/matplotlib only (and typing_extensions for @override)")
    assert {"jupyterlab", "ipywidgets", "ipympl", "ipykernel"} <= set(group("lab"))
    assert "nbclient" in group("grader"), "the grader executes notebooks with nbclient"
    assert any(_parse(r)[0] == SELF and "grader" in r for r in PROJECT["optional-dependencies"]["test"]), (
        "[test] includes [grader] (tests/test_grade.py runs the grader)")
    assert TEST_TOOLS - {"pyyaml"} <= set(group("test"))


def test_lower_bounds_everywhere():
    for name, low in groups("core", "lab", "grader", "test").items():
        assert low, f"{name} needs a lower bound in pyproject.toml"


def test_environment_files_match_pyproject():
    expected = {
        "environment.yml": groups("core", "lab"),
        "binder/environment.yml": groups("core", "lab"),
        "environment-dev.yml": groups("core", "lab", "grader", "test"),
    }
    for path, want in expected.items():
        _, conda = env_file(path)
        assert conda == want, (
            f"{path} and pyproject.toml must list the same packages with the same lower bounds:\n"
            f"  only in {path}: {sorted(set(conda.items()) - set(want.items()))}\n"
            f"  only in pyproject: {sorted(set(want.items()) - set(conda.items()))}")


def test_environment_files_are_valid_and_pin_python_for_repo2docker():
    low = re.match(r">=\s*(\d+)\.(\d+)", PROJECT["requires-python"]).groups()
    for path in ("environment.yml", "binder/environment.yml", "environment-dev.yml"):
        env, _ = env_file(path)
        assert env["name"] and env["channels"] == ["conda-forge"], path
        pins = [REPO2DOCKER_PYTHON.match(d) for d in env["dependencies"] if isinstance(d, str)]
        pins = [m.group(1) for m in pins if m]
        assert len(pins) == 1 and re.fullmatch(r"\d+\.\d+", pins[0]), (
            f"{path}: repo2docker reads only an exact pin such as python=3.11 (found {pins})")
        assert tuple(map(int, pins[0].split("."))) >= tuple(map(int, low)), f"{path}: pin below requires-python"
    for path in ("environment.yml", "environment-dev.yml"):
        env, _ = env_file(path)
        assert [d for d in env["dependencies"] if isinstance(d, dict)] == [{"pip": ["-e ."]}], path


def test_binder_image_has_no_test_tools_and_installs_the_course():
    env, conda = env_file("binder/environment.yml")
    assert not TEST_TOOLS & set(conda), "test tools stay out of the student image"
    assert not [d for d in env["dependencies"] if isinstance(d, dict)], "binder/postBuild installs the course"
    post = (ROOT / "binder" / "postBuild").read_text()
    assert "pip install --no-deps" in post and "-e ." in post
    assert "sync_workspace.py" in post and "lab_settings.py" in post
    assert (ROOT / "binder" / "postBuild").stat().st_mode & 0o111, "postBuild must be executable"
    # repo2docker ignores the top-level files once binder/ exists: nothing Binder-only is left there.
    assert not (ROOT / "postBuild").exists()


def test_readme_binder_link_opens_the_start_page_in_jupyterlab():
    sys.path.insert(0, str(ROOT / "tools"))
    import set_repository

    repo = PYPROJECT["tool"]["gm-course"]["repository"]
    branch = PYPROJECT["tool"]["gm-course"]["branch"]
    owner_name = re.fullmatch(r"https://github\.com/([^/]+/[^/]+)", repo).group(1)
    link = f"https://mybinder.org/v2/gh/{owner_name}/{branch}?urlpath=lab/tree/book/00-start-here.ipynb"
    assert set_repository.binder_url("book/00-start-here.ipynb") == link
    readme = (ROOT / "README.md").read_text()
    assert link in readme, f"README needs the Binder launch link {link}"
    assert re.search(r"\[!\[[^\]]*Binder[^\]]*\]\([^)]*badge[^)]*\)\]\(" + re.escape(link) + r"\)", readme), (
        "README needs a Binder badge linking to the start page")
    assert (ROOT / "book" / "00-start-here.ipynb").exists()
    assert set_repository.problems() == [], "README/CITATION links derive from [tool.gm-course]"
    assert "python tools/set_repository.py https://github.com/" in readme, "the README says how to set it"


def test_the_repository_is_set_in_one_place_and_every_link_follows(tmp_path):
    """An instructor runs tools/set_repository.py once: [tool.gm-course] changes and every link
    written in a file (README badge and launch link, CITATION.cff) follows; nothing of the old
    address is left; the site's links are computed from the same value (tests/test_site.py)."""
    sys.path.insert(0, str(ROOT / "tools"))
    import set_repository

    files = ("pyproject.toml", "README.md", "CITATION.cff", set_repository.START_PAGE)
    (tmp_path / "book").mkdir()
    for name in files:
        (tmp_path / name).write_text((ROOT / name).read_text())
    old, _ = set_repository.read(tmp_path)
    changed = set_repository.write("https://github.com/some-university/geomech-2027", "fall27", tmp_path)
    assert sorted(changed) == ["00-start-here.ipynb", "CITATION.cff", "README.md", "pyproject.toml"]
    assert set_repository.read(tmp_path) == ("https://github.com/some-university/geomech-2027", "fall27")
    assert set_repository.problems(tmp_path) == []
    readme = (tmp_path / "README.md").read_text()
    link = "https://mybinder.org/v2/gh/some-university/geomech-2027/fall27?urlpath=lab/tree/book/00-start-here.ipynb"
    assert readme.count(link) == (ROOT / "README.md").read_text().count(set_repository.binder_url("book/00-start-here.ipynb"))
    assert re.search(r"\[!\[[^\]]*Binder[^\]]*\]\([^)]*badge[^)]*\)\]\(" + re.escape(link) + r"\)", readme)
    start = json.loads((tmp_path / set_repository.START_PAGE).read_text())
    start_text = "".join(start["cells"][0]["source"])
    assert f"[Binder]({link})" in start_text, "the start page opens itself on Binder"
    assert "[course website](https://some-university.github.io/geomech-2027/)" in start_text
    old_path = old.removeprefix("https://github.com/")
    for name in files:
        assert old_path not in (tmp_path / name).read_text(), f"{name} still names {old}"
    assert yaml.safe_load((tmp_path / "CITATION.cff").read_text())["repository-code"] == \
        "https://github.com/some-university/geomech-2027"
    tomllib.loads((tmp_path / "pyproject.toml").read_text())       # still valid TOML
    assert set_repository.write("https://github.com/some-university/geomech-2027", "fall27", tmp_path) == []
    # a hand-edited link that does not derive from it is reported
    (tmp_path / "README.md").write_text(readme + "\n[x](https://mybinder.org/v2/gh/a/b/main?urlpath=lab/tree/book/01.ipynb)\n")
    assert any("does not derive" in p for p in set_repository.problems(tmp_path))
    for bad in ("https://gitlab.com/a/b", "github.com/a/b", "https://github.com/a", None, "https://github.com/a/b; rm"):
        with pytest.raises(ValueError, match="repository"):
            set_repository.write(bad, "main", tmp_path)
    with pytest.raises(ValueError, match="branch"):
        set_repository.write("https://github.com/a/b", "../x", tmp_path)


def test_licences_and_citation():
    lic = (ROOT / "LICENSE").read_text()
    assert lic.startswith("MIT License") and "Permission is hereby granted" in lic and "<" not in lic
    assert PROJECT["license"] == "MIT" and "LICENSE" in PROJECT["license-files"]
    text = (ROOT / "LICENSE-text.md").read_text()
    assert "CC BY 4.0" in text and "Creative Commons Attribution 4.0 International Public License" in text
    assert len(text) > 15000, "the full legal code of CC BY 4.0 is included"
    cff = yaml.safe_load((ROOT / "CITATION.cff").read_text())
    assert cff["cff-version"] == "1.2.0" and cff["title"] and cff["authors"] and cff["message"]
    assert cff["version"] == PROJECT["version"]
    assert cff["repository-code"] == PYPROJECT["tool"]["gm-course"]["repository"]
    assert set(cff["license"]) == {"MIT", "CC-BY-4.0"}


# ---- every import declared -------------------------------------------------------------------

def _imports_of_source(src):
    try:
        tree = ast.parse(src)
    except SyntaxError:
        return set()
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
    return names


def _imports(paths):
    names = set()
    for path in paths:
        if path.suffix == ".py":
            names |= _imports_of_source(path.read_text())
        elif path.suffix == ".ipynb":
            for cell in json.loads(path.read_text())["cells"]:
                if cell["cell_type"] == "code":
                    src = "".join(cell["source"])
                    src = "\n".join("" if ln.lstrip().startswith(("%", "!")) else ln for ln in src.splitlines())
                    names |= _imports_of_source(src)
    return names


def _third_party(names):
    local = {p.stem for d in ("gm_core", "gm_grader", "tests", "tools", "benchmarks") for p in (ROOT / d).rglob("*.py")}
    local |= {"gm_core", "gm_grader", "conftest"}
    stdlib = set(sys.stdlib_module_names)
    return {n for n in names if n not in stdlib and n not in local and not n.startswith("_")}


@functools.cache
def _packages_distributions():
    """Top-level module -> distributions: read from every installed distribution's file list,
    once per test process (not once per module looked up)."""
    return md.packages_distributions()


def _distributions(module):
    dists = _packages_distributions().get(module, [])
    return {d.lower().replace("_", "-") for d in dists}


def _check_declared(paths, declared, where):
    missing = []
    for mod in sorted(_third_party(_imports(paths)) - OPTIONAL_PEERS - set(BACKPORTS)):
        dists = _distributions(mod)
        assert dists, f"{where} imports {mod!r}, which no installed distribution provides"
        if not dists & set(declared):
            missing.append(f"{mod} (from {sorted(dists)})")
    assert not missing, f"{where} imports packages not declared in pyproject.toml: {missing}"


def test_every_package_gm_core_imports_is_declared_for_students():
    _check_declared(sorted((ROOT / "gm_core").rglob("*.py")), groups("core", "lab"), "gm_core")


def test_every_package_the_grader_imports_is_declared_in_its_extra():
    _check_declared(sorted((ROOT / "gm_grader").rglob("*.py")), groups("core", "grader"), "gm_grader")


def test_every_package_notebooks_import_is_declared_in_lab():
    nbs = [p for d in ("book", "exercises", "solutions") for p in sorted((ROOT / d).glob("*.ipynb"))]
    _check_declared(nbs, groups("core", "lab"), "the notebooks")


def test_every_package_tests_and_tools_import_is_declared():
    paths = [p for d in ("tests", "tools", "benchmarks") for p in sorted((ROOT / d).rglob("*.py"))]
    paths.append(ROOT / "conftest.py")
    _check_declared(paths, groups("core", "lab", "grader", "test"), "tests/tools/benchmarks")


def test_backports_are_declared_for_old_pythons_and_imported_only_as_fallbacks():
    """requires-python allows 3.10, which has no tomllib: every ``import tomllib`` in the tools and
    tests falls back to tomli, which [test] and the site venv declare for Pythons below 3.11."""
    low = re.match(r">=\s*(\d+\.\d+)", PROJECT["requires-python"]).group(1)
    sys.path.insert(0, str(ROOT / "tools"))
    import venvs

    for mod, below in BACKPORTS.items():
        assert tuple(map(int, low.split("."))) < tuple(map(int, below.split(".")))
        for reqs, where in ((PROJECT["optional-dependencies"]["test"], "[test]"), (venvs.TOOLS["site"], "the site venv")):
            assert [r for r in reqs if _parse(r)[0] == mod and _below(r) == below], f"{where} declares {mod} for < {below}"
    std = {"tomli": "tomllib"}
    paths = [p for d in ("tests", "tools", "benchmarks", "gm_core") for p in sorted((ROOT / d).rglob("*.py"))]
    for path in paths:
        text = path.read_text()
        if not any(name in text for name in std.values()):
            continue                    # no import of it can be in a file that never names it
        tree = ast.parse(text)
        guarded = {id(n) for t in ast.walk(tree) if isinstance(t, ast.Try)
                   and any(isinstance(h.type, ast.Name) and h.type.id in ("ModuleNotFoundError", "ImportError")
                           for h in t.handlers) for n in ast.walk(t)}
        for node in ast.walk(tree):
            if isinstance(node, ast.Import) and any(a.name in std.values() for a in node.names):
                assert id(node) in guarded, f"{path.relative_to(ROOT)}:{node.lineno}: import tomllib without the tomli fallback"


def test_tools_read_pyproject_on_a_python_without_tomllib():
    """What Python 3.10 does: tomllib cannot be imported, tomli (here pip's own copy) is used."""
    code = f"""
import importlib.abc, sys, types
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == 'tomllib':
            raise ModuleNotFoundError('no tomllib (Python 3.10)', name=name)
sys.meta_path.insert(0, Block())
from pip._vendor import tomli          # stands in for the tomli distribution of Python 3.10
sys.modules['tomli'] = tomli
sys.path.insert(0, {str(ROOT / "tools")!r})
import venvs, build_site, set_repository
assert 'tomllib' not in sys.modules
reqs = venvs.course_requirements()
assert 'numpy>=2.0' in reqs and any(r.startswith('ipympl') for r in reqs), reqs
print(set_repository.read()[1])
"""
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.strip() == PYPROJECT["tool"]["gm-course"]["branch"]


def test_the_import_scan_sees_what_it_should():
    seen = _third_party(_imports(sorted((ROOT / "gm_core").rglob("*.py"))))
    assert {"numpy", "scipy", "matplotlib", "ipywidgets", "sympy"} <= seen
    assert _distributions("yaml") == {"pyyaml"}


def test_core_imports_without_lab_grade_or_test_packages():
    """`pip install .` gives numpy/scipy/matplotlib only: the math, the drawing and the checkers'
    registry import with every other package made unimportable."""
    blocked = sorted({"ipywidgets", "IPython", "ipykernel", "ipympl", "jupyterlab", "sympy", "nbclient",
                      "nbformat", "traitlets", "jupyter_client", "pytest", "hypothesis", "mpmath", "yaml"})
    code = f"""
import importlib, importlib.abc, sys
class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split('.')[0] in {blocked!r}:
            raise ModuleNotFoundError('blocked: ' + name, name=name)
sys.meta_path.insert(0, Block())
import pkgutil, gm_core
names = [m.name for m in pkgutil.walk_packages(gm_core.__path__, 'gm_core.')
         if not m.name.startswith('gm_core.widgets')]     # the widgets are the [lab] part
assert 'gm_core.drawing' in names and 'gm_core.checks' in names and len(names) > 40, names
for m in names:
    importlib.import_module(m)
import numpy as np
from gm_core import SE2
assert np.allclose(SE2.compose([1, 1, np.pi / 2], [1, 1, np.pi / 2]), [0, 2, np.pi])
print('ok')
"""
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stderr[-2000:]


def test_math_does_not_import_drawing_libraries():
    """The math packages import without matplotlib or ipywidgets (each is imported: a missing or
    renamed one fails the test rather than being passed over)."""
    code = ("import sys, importlib\n"
            "for m in ('groups', 'calculus', 'fields', 'chains', 'systems', 'geometry', 'manifolds'):\n"
            "    importlib.import_module('gm_core.' + m)\n"
            "bad = [m for m in ('matplotlib', 'ipywidgets') if m in sys.modules]\n"
            "assert not bad, bad\n")
    res = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr[-2000:]


def _make_dry_run(target):
    """The commands ``make -n -B target`` would run (nothing is run)."""
    res = subprocess.run(["make", "-n", "-B", target], cwd=ROOT, capture_output=True, text=True)
    assert res.returncode == 0, res.stderr
    return res.stdout


@pytest.mark.skipif(shutil.which("make") is None, reason="make is not installed")
def test_makefile_installs_lab_and_test_and_ci_uses_the_two_commands():
    assert '-m pip install --quiet -e ".[lab,test]"' in _make_dry_run("setup")
    test_cmd = [ln for ln in _make_dry_run("test").splitlines() if " -m pytest " in ln]
    assert len(test_cmd) == 1 and " -n " in test_cmd[0], test_cmd   # on pytest-xdist workers
    assert "make test" in (ROOT / ".ci" / "run").read_text()
    readme = (ROOT / "README.md").read_text()
    assert "make lab" in readme and "make test" in readme


def test_the_pages_workflow_builds_with_the_makefiles_site_target():
    """The site published to GitHub Pages is the one `make site` builds and checks, from the folder
    tools/build_site.py writes."""
    import yaml

    flow = yaml.safe_load((ROOT / ".github" / "workflows" / "site.yml").read_text())
    steps = [s for job in flow["jobs"].values() for s in job["steps"]]
    runs = [s["run"] for s in steps if "run" in s]
    assert "make site" in runs, runs
    if shutil.which("make") is not None:
        assert "tools/build_site.py" in _make_dry_run("site"), "make site builds with tools/build_site.py"
    upload = next(s for s in steps if s.get("uses", "").startswith("actions/upload-pages-artifact"))
    sys.path.insert(0, str(ROOT / "tools"))
    import build_site

    assert Path(upload["with"]["path"]) == (build_site.DEFAULT_OUT / "_build" / "html").relative_to(ROOT)

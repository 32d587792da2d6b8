"""Set-up stays consistent: environment.yml matches pyproject.toml, and the math never imports
the drawing or widget libraries."""
import re
import subprocess
import sys
from pathlib import Path

import tomllib
import yaml

ROOT = Path(__file__).resolve().parent.parent


def _parse(req):
    m = re.match(r"^\s*([A-Za-z0-9_.\-]+)\s*(?:>=\s*([0-9][^,;\s]*))?", req)
    name = m.group(1).lower().replace("_", "-")
    return name, m.group(2)


def pyproject_requirements():
    data = tomllib.loads((ROOT / "pyproject.toml").read_text())
    reqs = data["project"]["dependencies"] + data["project"]["optional-dependencies"]["test"]
    return dict(_parse(r) for r in reqs)


def environment_requirements():
    env = yaml.safe_load((ROOT / "environment.yml").read_text())
    out = {}
    for dep in env["dependencies"]:
        if isinstance(dep, str):
            name, low = _parse(dep)
            if name not in {"python", "pip"}:
                out[name] = low
    return env, out


def test_environment_yml_matches_pyproject():
    env, conda = environment_requirements()
    assert conda == pyproject_requirements(), (
        "environment.yml and pyproject.toml must list the same packages with the same lower bounds")


def test_environment_yml_is_valid_for_conda_and_binder():
    env, _ = environment_requirements()
    assert env["name"] and env["channels"] == ["conda-forge"]
    pip_sections = [d for d in env["dependencies"] if isinstance(d, dict)]
    assert pip_sections == [{"pip": ["-e ."]}], "the course package itself is installed with pip"
    assert any(isinstance(d, str) and d.startswith("python") for d in env["dependencies"])


def test_lower_bounds_everywhere():
    for name, low in pyproject_requirements().items():
        assert low, f"{name} needs a lower bound in pyproject.toml"


def test_math_does_not_import_drawing_libraries():
    code = ("import sys, gm_core, gm_core.groups\n"
            "import importlib\n"
            "for m in ('calculus', 'fields', 'chains', 'locomotion', 'systems', 'geometry'):\n"
            "    try:\n        importlib.import_module('gm_core.' + m)\n"
            "    except ModuleNotFoundError as e:\n"
            "        if e.name != 'gm_core.' + m: raise\n"
            "bad = [m for m in ('matplotlib', 'ipywidgets') if m in sys.modules]\n"
            "assert not bad, bad\n")
    subprocess.run([sys.executable, "-c", code], check=True, cwd=ROOT)


def test_ci_and_readme_use_the_two_commands():
    assert "make test" in (ROOT / ".ci" / "run").read_text()
    readme = (ROOT / "README.md").read_text()
    assert "make lab" in readme and "make test" in readme

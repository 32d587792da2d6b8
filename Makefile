# The two commands a new user needs (see README.md):
#   make lab    set up .venv, install the course, open JupyterLab on the start page
#   make test   the same set-up, then every unit test and every notebook (pytest)
SHELL := /bin/bash
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed-stamp
LAB_ARGS ?=
# Jupyter refuses to start as root unless told; only then (containers, CI) is the flag added.
ROOT_FLAG := $(if $(filter 0,$(shell id -u)),--ServerApp.allow_root=True,)
PYTEST_ARGS ?=
# make test runs on this many pytest-xdist workers (one per core of the course's 2-core machines),
# `--dist loadgroup`: a notebook and the tests reading its record share an xdist_group, so it
# is executed once (tests/nbrun.py); TEST_WORKERS=0 runs in one process. More workers only add
# JupyterLab servers and browsers (one per worker that runs a browser test) competing for the cores.
TEST_WORKERS ?= 2

.PHONY: setup test-tools lab lab-settings test test-kits exercises workspace bench screenshots gradescope kits student-build site clean help

help:
	@echo "make lab        set up and open JupyterLab on the course (book/00-start-here.ipynb)"
	@echo "make test       set up and run every test and every notebook"
	@echo "make exercises  regenerate exercises/ from solutions/"
	@echo "make bench      print the benchmark tables"
	@echo "make screenshots  a PNG of every figure of the course + index.html in build/screenshots/"
	@echo "make gradescope  the Gradescope autograder zip in build/gradescope/ (EXERCISES=\"1.4 2.1\" for some)"
	@echo "make kits       otter-grader master notebooks and nbgrader source notebooks in build/kits/"
	@echo "make student-build  the course without answer keys, for graded students, in build/student/"
	@echo "make site       the course website, offline, in build/site/_build/html/ (checked in headless Chromium)"

$(PY):
	$(PYTHON) -m venv $(VENV)

# Re-install whenever pyproject.toml changes.
$(STAMP): pyproject.toml | $(PY)
	$(PY) -m pip install --quiet --upgrade pip
	@# setuptools' note about editable installs (not a problem here) is silenced; nothing else is.
	PYTHONWARNINGS="ignore:::setuptools.command.editable_wheel" $(PY) -m pip install --quiet -e ".[lab,test]"
	@# jsonschema's optional "iri" format checker compiles a Lark grammar whenever nbformat is
	@# imported (in every JupyterLab server, test worker and grading command);
	@# nothing the course validates uses that format, so it is left out (as tools/venvs.py does).
	$(PY) -m pip uninstall --yes --quiet rfc3987-syntax
	@# The course is installed editable, so pip compiles none of it: compile it here, once (as pip
	@# does for installed packages), rather than in each of the first kernels and test processes
	@# that import it at the same moment.
	$(PY) -m compileall -q gm_core gm_grader tools tests
	@touch $(STAMP)

setup: $(STAMP)

# Copy new exercises into the student's git-ignored workspace/; never overwrites a file.
workspace: setup
	$(PY) tools/sync_workspace.py

# The course's JupyterLab defaults (jupyter/overrides.json: no news pop-up, no update check),
# installed as JupyterLab's documented settings overrides (overrides.d/) of the venv's JupyterLab.
lab-settings: setup
	$(PY) tools/lab_settings.py

lab: setup workspace lab-settings
	$(VENV)/bin/jupyter lab --config=jupyter/jupyter_server_config.py --ServerApp.ip=127.0.0.1 --ServerApp.root_dir="$(CURDIR)" $(ROOT_FLAG) $(LAB_ARGS) book/00-start-here.ipynb

# The publishing tests' own environments, made from PyPI/npm once and stamped (tools/venvs.py):
# .venv-site (+ site/node_modules), .venv-kits, the Gradescope kit's venv. If this fails (no
# network), only the tests that need them skip -- except under CI (CI=true), where it is an error.
test-tools: setup
	$(if $(CI),,-)$(PY) tools/venvs.py site kits gradescope

# Python may cache compiled modules here even where the machine sets PYTHONDONTWRITEBYTECODE:
# else each of the run's ~150 kernels and helper processes compiles the course from source.
test: setup test-tools
	env -u PYTHONDONTWRITEBYTECODE $(PY) -m pytest -n $(TEST_WORKERS) --dist loadgroup $(PYTEST_ARGS)

# Every exercise through every grading kit (otter-grader, nbgrader, Gradescope), as each
# instructor's tool runs it: tests/kits/, collected only here (each tool runs every notebook).
test-kits: setup test-tools
	GM_TEST_KITS=1 env -u PYTHONDONTWRITEBYTECODE $(PY) -m pytest -n 2 --dist loadgroup tests/kits

exercises: setup
	$(PY) tools/make_exercises.py

bench: setup
	$(PY) benchmarks/se2_batched.py
	$(PY) benchmarks/widget_latency.py
	$(PY) benchmarks/connection_grid.py
	@echo "also: benchmarks/browser_latency.py (needs chromium), benchmarks/suite_time.py (runs the suite)"

# One PNG per figure (real browser when chromium exists, else headless matplotlib) + index.html.
screenshots: setup
	$(PY) tools/screenshots.py

# Gradescope autograder zip (setup.sh + run_autograder installing the course from the zip itself).
EXERCISES ?=
gradescope: setup
	$(PY) tools/gradescope_kit.py $(if $(EXERCISES),--exercises $(EXERCISES),)

# otter-grader / nbgrader versions of the exercises (their tools live in .venv-kits, made from PyPI).
kits: setup
	$(PY) tools/export_kits.py $(if $(EXERCISES),--exercises $(EXERCISES),)
	$(PY) tools/student_build.py --out build/kits/student
	$(PY) tools/venvs.py kits

# The course a graded student installs (otter-grader, nbgrader): no answer keys, no solutions.
student-build: setup
	$(PY) tools/student_build.py --wheel

# The website: Jupyter Book 1 in its own .venv-site (PyPI), front-end files from npm (site/), every
# page executed, built, then opened in headless Chromium with the network blocked (axe-core too).
site: setup
	$(PY) tools/venvs.py site
	PYTHONPATH="$(CURDIR)" nice .venv-site/bin/python tools/build_site.py $(if $(PAGES),--only $(PAGES),)
	PYTHONPATH="$(CURDIR)" .venv-site/bin/python tools/check_site.py

clean:
	rm -rf $(VENV) .hypothesis .venv-site .venv-kits .venv-gradescope site/node_modules build

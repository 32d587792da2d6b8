"""Every exercise through every grading kit, as each instructor's tool runs it (`make test-kits`).

These tests run otter-grader, nbgrader and the Gradescope kit on all the exercises (each tool
executes every notebook several times), so they are collected only when `make test-kits` (which
`.ci/run` calls after `make test`) sets GM_TEST_KITS=1; `make test` covers one exercise per kit.
"""
import os


def pytest_ignore_collect(collection_path, config):
    return os.environ.get("GM_TEST_KITS") != "1"

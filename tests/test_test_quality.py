"""Every test in tests/ can fail: each ``test_*`` function holds an ``assert``, a
``pytest.raises``/``pytest.warns``/``pytest.fail``, an ``assert_*`` call (numpy.testing's), or
calls a helper (a function of tests/, by name) that does. A cheap static check (the AST), no test is run."""
import ast
from pathlib import Path

TESTS = Path(__file__).resolve().parent
CHECKING = {"raises", "warns", "fail", "deprecated_call"}


def _functions():
    for f in sorted(TESTS.rglob("*.py")):
        tree = ast.parse(f.read_text(encoding="utf-8"), filename=str(f))
        for node in ast.walk(tree):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                yield f, node


def _called(fn):
    for n in ast.walk(fn):
        if isinstance(n, ast.Call):
            if isinstance(n.func, ast.Name):
                yield n.func.id
            elif isinstance(n.func, ast.Attribute):
                yield n.func.attr


def _checks_itself(fn):
    return any(isinstance(n, ast.Assert) for n in ast.walk(fn)) or \
        any(c in CHECKING or c.startswith("assert") for c in _called(fn))   # numpy.testing's assert_* too


def _asserting_names(funcs):
    """Names of the functions of tests/ that check something, directly or through one another."""
    names = {fn.name for _, fn in funcs if _checks_itself(fn)}
    while True:
        more = {fn.name for _, fn in funcs if fn.name not in names and any(c in names for c in _called(fn))}
        if not more:
            return names
        names |= more


def test_every_test_function_can_fail():
    funcs = list(_functions())
    asserting = _asserting_names(funcs)
    tests = [(f, fn) for f, fn in funcs if fn.name.startswith("test_") and f.name.startswith("test_")]
    assert len(tests) > 100, "the scan found the tests"
    idle = [f"{f.relative_to(TESTS)}:{fn.lineno} {fn.name}" for f, fn in tests if fn.name not in asserting]
    assert not idle, "tests that check nothing (no assert, pytest.raises/warns/fail or asserting helper):\n" + \
        "\n".join(idle)


def test_the_check_sees_a_test_without_an_assert():
    src = ("def helper(x):\n    assert x\n\n"
           "def test_ok():\n    helper(1)\n\n"
           "def test_idle():\n    print(1)\n")
    funcs = [(None, n) for n in ast.walk(ast.parse(src)) if isinstance(n, ast.FunctionDef)]
    asserting = _asserting_names(funcs)
    assert "test_ok" in asserting and "test_idle" not in asserting

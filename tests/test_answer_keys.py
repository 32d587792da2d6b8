"""Answer keys apart from the parts (issue 38, point 2): every part has a key of its kind, the
probes never need one, and the graded build (the course without ``gm_core/checks/keys``) can
neither judge nor reveal an answer, and tells the grader when a notebook asks."""
import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from gm_core.checks import answer_key, channel
from gm_core.checks.answer_key import (
    KEYS_PACKAGE,
    AnswerKeyHidden,
    ChoiceKey,
    FunctionKey,
    JudgeKey,
    TupleKey,
    provide,
)
from gm_core.checks.choice import ChoicePart
from gm_core.checks.exercise import REGISTRY, Exercise, exercise_ids
from gm_core.checks.parts import FunctionPart, TuplePart, rng_inputs
from gm_core.checks.sandbox import encode

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))
import student_build  # noqa: E402

PARTS = [(ex_id, name) for ex_id in exercise_ids() for name in REGISTRY[ex_id].parts]


def test_every_part_has_a_key_of_its_kind_with_right_and_wrong_answers():
    assert len(PARTS) >= 40
    for ex_id, name in PARTS:
        part = REGISTRY[ex_id].parts[name]
        assert isinstance(part.key, part.key_type), (ex_id, name)
        assert part.reference is not None and part.wrong, (ex_id, name)
        assert part.solution_text.strip(), (ex_id, name)


@pytest.fixture
def scratch_exercise():
    """An exercise of this test's own, taken out of the registry afterwards."""
    ex = Exercise("99.1", "scratch", [
        FunctionPart("a", "a function", rng_inputs(1, 2, lambda rng: (rng.uniform(),)),
                     arg_names=("x",), shape=()),
        ChoicePart("b", "a choice", {"a": "yes", "b": "no"}),
        TuplePart("c", "two functions", [("f", FunctionPart("f", "f", lambda: [(1.0,)], arg_names=("x",), shape=())),
                                         ("g", FunctionPart("g", "g", lambda: [(1.0,)], arg_names=("x",), shape=()))]),
    ])
    try:
        yield ex
    finally:
        del REGISTRY["99.1"]


def test_a_key_that_does_not_fit_its_part_is_refused_by_name(scratch_exercise):
    ex = scratch_exercise
    f = FunctionKey(ref=lambda x: 2 * x)
    with pytest.raises(ValueError, match="no part 'z'"):
        provide(ex, z=f)
    with pytest.raises(TypeError, match="part a must be a FunctionKey, not ChoiceKey"):
        provide(ex, a=ChoiceKey(correct="a"))
    with pytest.raises(ValueError, match="must name options it has"):
        provide(ex, b=ChoiceKey(correct="q"))
    with pytest.raises(ValueError, match="has 1 components; the part has 2"):
        provide(ex, c=TupleKey(components=[f]))
    provide(ex, a=f, b=ChoiceKey(correct="b"), c=TupleKey(components=[f, f]))
    assert ex.a.check(lambda x: 2 * x, quiet=True).passed
    assert not ex.a.check(lambda x: 3 * x, quiet=True).passed
    assert ex.b.check("b", quiet=True).passed and ex.b.wrong == ["a"]
    assert ex.c.reference == (f.ref, f.ref) and ex.c.check((f.ref, f.ref), quiet=True).passed


def test_only_the_key_registry_names_the_keys_package():
    """No module of the course or the grader imports the keys (only answer_key.py names the
    package, to look it up), so the graded build, which lacks it, imports everything else."""
    offenders = []
    for base in ("gm_core", "gm_grader"):
        for path in (ROOT / base).rglob("*.py"):
            if "keys" in path.relative_to(ROOT).parts[:-1] or path.name == "answer_key.py":
                continue
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
                names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                         [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
                if any(n == KEYS_PACKAGE or n.startswith(KEYS_PACKAGE + ".") for n in names):
                    offenders.append(str(path.relative_to(ROOT)))
    assert offenders == []


def test_the_probes_never_consult_a_key(monkeypatch):
    """Every part's probes give the same plain outcomes on its reference answer with the keys
    hidden as with them, and never ask for a key: what runs beside the student's answer in the
    graded build needs nothing of the key."""
    references = {p: REGISTRY[p[0]].parts[p[1]].reference for p in PARTS}

    def outcomes(ex_id, name):
        part = REGISTRY[ex_id].parts[name]
        return json.dumps([encode(probe(references[(ex_id, name)])) for probe in part.probes()],
                          sort_keys=True)

    with_keys = {p: outcomes(*p) for p in PARTS}
    asked = []
    monkeypatch.setattr(answer_key, "_KEYS", {})
    monkeypatch.setattr(answer_key, "keys_installed", lambda: False)
    monkeypatch.setattr(channel, "key_requested", lambda part, what: asked.append((part.id, what)))
    for p in PARTS:
        assert outcomes(*p) == with_keys[p], p
    assert asked == []
    with pytest.raises(AnswerKeyHidden, match="graded build"):
        _ = REGISTRY["1.4"].parts["a"].reference
    assert asked == [("1.4a", "reference")]


GRADED_BUILD_SCRIPT = r"""
import json, os, sys
import gm_core
from gm_core.checks import REGISTRY, exercise_ids, keys_installed, AnswerKeyHidden, channel
from gm_core.checks.parts import SENT_TO_GRADER
from gm_core.checks.protocol import Withheld, decode_evidence
out = {"file": gm_core.__file__, "installed": keys_installed(), "parts": 0, "hidden": 0,
       "sent": 0}
for ex_id in exercise_ids():
    for name, part in REGISTRY[ex_id].parts.items():
        out["parts"] += 1
        part.probes()
        try:
            part.reference
        except AnswerKeyHidden:
            out["hidden"] += 1
        v = part.check(part.starter, quiet=True)
        out["sent"] += v.status == "unattempted" and v.message == SENT_TO_GRADER
r, w = os.pipe()
channel.open_channel(w, "n" * 32, 1)
REGISTRY["1.2"].parts["b"].solution()
os.close(w)
line = os.read(r, 10000).decode().splitlines()[-1]
ev = decode_evidence(line, nonce="n" * 32, exercise="1.2", probes={"b": 1})
out["asked"] = [ev.part, ev.outcomes is Withheld.KEY_ASKED, ev.output]
print(json.dumps(out))
"""


def test_the_graded_build_cannot_judge_or_reveal_and_reports_who_asked(tmp_path):
    """The course without its keys' folder (what the grader's sandbox shows): every part still
    lists its probes, a check says the grader will judge, every key is hidden, and asking
    (here ``solution()``) sends the grader a record saying so."""
    build = student_build.build(tmp_path / "student")
    assert not (build / "gm_core" / "checks" / "keys").exists()
    assert (build / "gm_core" / "checks" / "answer_key.py").exists() and not (build / "solutions").exists()
    env = {**os.environ, "PYTHONPATH": str(build), "MPLBACKEND": "Agg", "GM_CHECKS_NO_FORK": "1"}
    res = subprocess.run([sys.executable, "-c", GRADED_BUILD_SCRIPT], capture_output=True,
                         text=True, env=env, cwd=tmp_path, timeout=300)
    assert res.returncode == 0, res.stderr[-3000:]
    out = json.loads(res.stdout.splitlines()[-1])
    assert out["file"].startswith(str(build)) and out["installed"] is False
    assert out["parts"] == len(PARTS) == out["hidden"] == out["sent"]
    assert out["asked"] == ["b", True, "solution()"]
    assert "graded build" in res.stdout                     # what solution() showed instead


def test_a_keys_defaults_come_from_what_it_declares():
    """A FunctionKey's default reference is its ref, its wrong answers its mistakes' functions
    then the further ones (each once); a JudgeKey judges with its own function."""
    def ref(x):
        return np.asarray(x)

    def w(x):
        return -np.asarray(x)

    key = FunctionKey(ref=ref, mistakes=[(w, "sign")], wrong=[w, np.sin])
    assert key.reference is ref and list(key.wrong) == [w, np.sin]
    assert isinstance(JudgeKey(judge=lambda o: "ok").judge([]), str)


@pytest.mark.slow
def test_the_student_wheel_has_no_keys_and_says_so_in_its_version(tmp_path):
    """`make student-build` (tools/student_build.py --wheel): the wheel a graded student installs
    holds the course without its answer keys, marked +student."""
    import zipfile
    tree = student_build.build(tmp_path)
    whl = student_build.wheel(tree, tmp_path)
    names = zipfile.ZipFile(whl).namelist()
    assert "+student" in whl.name
    assert "gm_core/checks/answer_key.py" in names and "gm_core/checks/parts.py" in names
    assert not [n for n in names if n.startswith("gm_core/checks/keys") or "solutions" in n], names

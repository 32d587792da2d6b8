"""The grader's own calls of the checked answers, outside the student's process.

A graded notebook's ``check(...)`` calls give the student feedback and carry each checked answer,
pickled by value as it was at that call, to the grader (:mod:`gm_core.checks.channel`); their
outcomes carry no weight. After the notebook has ended, however it ended, the grader takes the
last checked answer of every part, chooses new probe inputs (a salt drawn only now, never shown to
the notebook) and runs this module's :func:`notebook` -- one cell per part, nothing of the
student's but the answers -- in a fresh sandbox of its own (:func:`gm_grader.isolate.run_submission`,
same view and limits). Each cell rebuilds one answer and checks it there (:func:`call`); the
plain outcomes come back on that sandbox's evidence channel and the grading process judges them
with its own checkers and answer keys (:func:`gm_grader.evidence.decide`). The grading process
never loads a pickle; only the sandbox does.

So what decides a grade is computed on inputs no code of the submission saw before it ended: a
hook, a thread or a patched emitter in the notebook's kernel is not there, and outcomes forged
there are not read.
"""
from __future__ import annotations

import base64
import pickle
from collections.abc import Mapping
from typing import Any

__all__ = ["dumps", "notebook", "call"]


def dumps(answer: object) -> str:
    """``answer`` pickled by value (`cloudpickle <https://github.com/cloudpipe/cloudpickle>`_:
    functions and lambdas of the notebook with what they refer to, as they are now), as base64
    text: the carrier the runner's hidden cell gives :func:`gm_core.checks.channel.open_channel`."""
    import cloudpickle

    return base64.b64encode(cloudpickle.dumps(answer, protocol=5)).decode("ascii")


def notebook(exercise: str, answers: Mapping[str, str]) -> dict[str, Any]:
    """The probing notebook (nbformat 4, as a dict) for ``answers``: {part name: carried answer}."""
    cells: list[dict[str, Any]] = [{"cell_type": "code", "execution_count": None, "id": f"probe-{i}", "metadata": {},
              "outputs": [],
              "source": f"from gm_grader.probe import call\ncall({exercise!r}, {name!r}, {data!r})"}
             for i, (name, data) in enumerate(sorted(answers.items()))]
    return {"cells": cells, "metadata": {}, "nbformat": 4, "nbformat_minor": 5}


def call(exercise: str, part: str, data: str) -> None:
    """In the probing sandbox's kernel: rebuild ``part``'s carried answer and check it, quietly.

    The check's probes use the inputs of this run's salt and send their outcomes on this run's
    evidence channel; an answer that cannot be rebuilt here sends a stopped check saying why."""
    from gm_core.checks import channel
    from gm_core.checks.exercise import REGISTRY

    channel.stop_carrying_answers()
    the_part = REGISTRY[exercise].parts[part]
    try:
        answer = pickle.loads(base64.b64decode(data, validate=True))
    except KeyboardInterrupt:
        raise
    except BaseException as exc:  # noqa: BLE001 - whatever the pickle holds, say so and go on
        channel.emit(the_part, "stopped", "your answer could not be rebuilt outside the "
                     f"notebook ({type(exc).__name__[:40]} while loading it)")
        return
    the_part.check(answer, quiet=True)

"""Many answers to one checker part, judged in ONE probe sandbox (a test helper).

``Part.check(answer)`` forks a fresh sandbox for every answer (gm_core/checks/sandbox.py: a keeper
and a worker, each a fork of the whole test process, 30-80 ms together in a test process that has
sympy and matplotlib loaded). The junk test of tests/test_checks.py judges 20 inputs for each of
about 40 parts; :func:`check_each` runs every input's probes in turn in one sandboxed worker (the
public :func:`~gm_core.checks.sandbox.collect`, unchanged) and then judges each input's own
outcomes with the part's own ``verdict()``, which is exactly what ``check()`` does with them.

For answers that leave the process as they found them (plain values, pure functions: the junk of
the tests) the outcomes are those of separate sandboxes: each probe still has its own time limit,
each input's printed output is captured on its own, and when a probe times out or the worker dies,
that input and every later one is checked again by ``Part.check`` in a sandbox of its own. The
tests using it also check some inputs with ``Part.check`` directly and require the same verdict.
"""
from __future__ import annotations

import contextlib
import io

from gm_core.checks.sandbox import collect

#: outcome kinds after which the rest of a batch says nothing about its inputs
_STOPPED = ("timeout", "crash", "skipped")


def check_each(part, answers, time_limit=None):
    """``[part.check(a, quiet=True) for a in answers]`` with one sandbox for all of them (see the
    module docstring); the verdicts are not recorded in the progress file."""
    answers = list(answers)
    probes = part.probes()
    n = len(probes)
    buffers = [io.StringIO() for _ in answers]

    def probe_of(i, j):
        def run(_unused):
            with contextlib.redirect_stdout(buffers[i]), contextlib.redirect_stderr(buffers[i]):
                return probes[j](answers[i])
        return run

    def output_of(i):
        return lambda _unused: buffers[i].getvalue()

    combined = []
    for i in range(len(answers)):
        combined += [probe_of(i, j) for j in range(n)] + [output_of(i)]
    outcomes, _ = collect(None, combined, time_limit)
    verdicts = []
    for i in range(len(answers)):
        mine = outcomes[i * (n + 1):(i + 1) * (n + 1)]
        if any(o["k"] in _STOPPED for o in mine):
            # from here on the batch is no evidence: a sandbox per input, as check() does
            verdicts += [part.check(a, quiet=True, time_limit=time_limit) for a in answers[i:]]
            break
        out = mine[-1].get("v") if mine[-1]["k"] == "ok" else ""
        verdicts.append(part.verdict(mine[:-1], out if isinstance(out, str) else ""))
    return verdicts

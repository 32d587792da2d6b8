"""The cell clock of a graded notebook: seconds of *student* time in the running cell.

A cell's limit (``--cell-timeout``) does not count the time its checks' probes take (each probe
has its own per-call limit). The kernel announces a check (a :class:`~gm_core.checks.protocol.CheckBegun`
on the evidence channel) and its end (the evidence record), so a notebook could announce a check and
then sleep, and its clock would stand still. Here every announced check is credited at most
its part's longest honest duration (its probes times the per-call limit, plus the sandbox's own
overhead), a check of a part this notebook does not grade is credited nothing, and all the
checks of one cell together at most ``CELL_BUDGET`` times the longest honest check of every part
once.

The same clock runs twice: in the grader's runner, inside the sandbox (it interrupts the cell),
and in the grading process outside the sandbox, fed by the runner's records as they arrive, on
the grading process's own ``time.monotonic`` (nothing in the sandbox can stop, slow or patch it).
The outer one allows ``OUTER_MARGIN`` seconds more, so it acts only when the runner did not (a
kernel that stopped or confused its runner): then it ends the whole sandbox.
"""
from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

if TYPE_CHECKING:     # the runner imports this module: no checkers loaded there for a hint
    from gm_core.checks.exercise import Exercise

#: All the checks of one cell together are credited at most this many honest checks of every part.
CELL_BUDGET = 3.0
#: Seconds a check may take beyond its probes' limits (fork, encoding, a loaded machine).
CHECK_OVERHEAD, PROBE_OVERHEAD = 5.0, 0.25
#: Seconds the grading process allows beyond the runner's own limit and its grace (by then the
#: runner has killed a kernel that ignored the interrupt, so nothing more is lost).
OUTER_MARGIN = 10.0
#: Seconds from the sandbox's start until the kernel runs (the runner's startup_timeout is 120).
STARTUP_LIMIT = 240.0


def check_caps(exercise: Exercise, time_limit: float) -> dict[str, float]:
    """{"<exercise id>/<part>": seconds} the longest honest check of each part may take."""
    caps: dict[str, float] = {}
    for name, part in exercise.parts.items():
        try:
            n = len(part.probes())
        except Exception:  # noqa: BLE001 - a checker that cannot list its probes gets no credit
            continue
        caps[f"{exercise.id}/{name}"] = n * float(time_limit) + CHECK_OVERHEAD + PROBE_OVERHEAD * n
    return caps


class CellClock:
    """Student seconds since the clock was last restarted, not counting (capped) check time."""

    def __init__(self, caps: Mapping[str, float] | None = None) -> None:
        self.caps = {str(k): float(v) for k, v in (caps or {}).items()}
        self.budget = CELL_BUDGET * sum(self.caps.values())
        self.started, self.credit = 0.0, 0.0
        self.open: tuple[float, float] | None = None

    def restart(self, now: float) -> None:
        self.started, self.credit, self.open = float(now), 0.0, None

    def begin(self, key: str, now: float) -> None:
        """A check of ``key`` ("1.4/a") starts; it is credited until :meth:`end`, at most its cap."""
        self.end(now)
        cap = self.caps.get(str(key), 0.0)
        if cap > 0:
            self.open = (float(now), cap)

    def end(self, now: float) -> None:
        if self.open is not None:
            t0, cap = self.open
            self.credit += min(max(now - t0, 0.0), cap)
            self.open = None

    def credited(self, now: float) -> float:
        c = self.credit
        if self.open is not None:
            t0, cap = self.open
            c += min(max(now - t0, 0.0), cap)
        return min(c, self.budget)

    def seconds(self, now: float) -> float:
        return now - self.started - self.credited(now)

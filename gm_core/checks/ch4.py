"""Checkers for the two exercises of the geometry notebook (book/10): 4.1 and 4.2.

Self-contained on purpose (the checking engine in ``_core`` is being rewritten): a small
check / hint / solution object per part with the same verbs and verdict words as the other
chapters ("passed", "failed", "unattempted"). To register these with the engine, rebuild the
parts as ``_core.ChoicePart`` / ``_core.CustomPart`` inside ``_core.Exercise("4.1", ...)``, add
"4.1" and "4.2" to ``EXERCISE_IDS`` and export ``ex4_1``, ``ex4_2`` from ``checks/__init__``.

References are computed with gm_core.geometry and gm_core.locomotion (never shown to the student).
"""
from __future__ import annotations

import functools
import warnings

import numpy as np

__all__ = ["ex4_1", "ex4_2", "swimmer", "GAITS_4_1", "drift_and_turn"]

PASSED, FAILED, UNATTEMPTED = "passed", "failed", "unattempted"


class _Verdict:
    def __init__(self, status, message, title):
        self.status, self.message, self.title = status, message, title

    def __bool__(self):
        return self.status == PASSED

    @property
    def passed(self):
        return self.status == PASSED

    def __repr__(self):
        label = {PASSED: "Correct", FAILED: "Not yet", UNATTEMPTED: "Unattempted"}[self.status]
        return f"[{label}] ({self.title}) {self.message}"


class _Wrong(Exception):
    pass


class _Part:
    """check(answer) -> verdict (never raises), hint(n), solution()."""

    def __init__(self, ex_id, name, prompt, judge, hints, solution_text, reference=None, wrong=()):
        self.ex_id, self.name, self.prompt = ex_id, name, prompt
        self.judge, self.hints, self.solution_text = judge, list(hints), solution_text
        self.reference, self.wrong = reference, list(wrong)
        self.status = UNATTEMPTED

    @property
    def title(self):
        return f"exercise {self.ex_id}{self.name}"

    def check(self, answer=None, *, quiet=False):
        if answer is None or answer is Ellipsis:
            v = _Verdict(UNATTEMPTED, "You have not answered yet: replace the starter value (still None).",
                         self.title)
        else:
            try:
                with np.errstate(all="ignore"), warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    v = _Verdict(PASSED, self.judge(answer) or "Well done.", self.title)
            except _Wrong as w:
                v = _Verdict(FAILED, str(w), self.title)
            except Exception as exc:  # a checker must never break the notebook
                v = _Verdict(FAILED, f"The checker could not use your answer ({type(exc).__name__}: "
                             f"{str(exc)[:150]}). Check its type against the prompt.", self.title)
        self.status = v.status
        if not quiet:
            print(repr(v))
        return v

    def hint(self, n=1):
        k = min(max(int(n), 1), len(self.hints))
        text = self.hints[k - 1] + (f" (hint {k} of {len(self.hints)})")
        print(f"[Hint] ({self.title}) {text}")
        return text

    def solution(self):
        text = f"{self.solution_text}\nFull derivation: solutions/ex{self.ex_id.replace('.', '_')}.ipynb"
        print(f"[Solution] ({self.title}) {text}")
        return text


class _Exercise:
    def __init__(self, ex_id, title, parts):
        self.id, self.title, self.parts = ex_id, title, {p.name: p for p in parts}
        for p in parts:
            setattr(self, p.name, p)

    def status(self):
        states = [p.status for p in self.parts.values()]
        if FAILED in states:
            return FAILED
        return PASSED if all(s == PASSED for s in states) else UNATTEMPTED

    def __repr__(self):
        return f"<exercise {self.id}: {self.title}; parts {', '.join(self.parts)}>"


def _choice(answer, options):
    key = str(answer).strip().lower().strip("()")
    if key not in options:
        raise _Wrong(f"answer with one of the letters {', '.join(sorted(options))}; got {answer!r}")
    return key


# ============================================================================ shared set-up
@functools.lru_cache(maxsize=1)
def swimmer():
    """The swimmer of both exercises: LowReSwimmer() (links 1, drag ratio 2)."""
    from ..systems import LowReSwimmer

    return LowReSwimmer()


def _gaits():
    from ..locomotion import circle_gait

    return {"A": circle_gait(1.0), "C": circle_gait(2.2)}


GAITS_4_1 = {"A": "circle of radius 1.0 about (0, 0)", "C": "circle of radius 2.2 about (0, 0)"}


@functools.lru_cache(maxsize=1)
def _stokes_A():
    from ..geometry import stokes_estimate

    return float(stokes_estimate(swimmer(), _gaits()["A"])[0])


# ============================================================================ 4.1
_OPT_41A = {"a": "gait A, the smaller circle", "b": "gait C, the larger circle",
            "c": "both the same: they are the same shape", "d": "cannot be told from the curvature map"}


def _judge_41a(answer):
    key = _choice(answer, _OPT_41A)
    if key == "a":
        return "Correct: C encloses more area, but much of it has the opposite sign of x curvature."
    raise _Wrong({"b": "Area alone is not the point: look at the colours inside C's outer ring.",
                  "c": "Both are centred circles, but what matters is the curvature they enclose.",
                  "d": "The map does tell: to leading order the net x motion is the x curvature enclosed."}[key])


def _judge_41b(answer):
    try:
        val = float(answer)
    except (TypeError, ValueError):
        raise _Wrong(f"answer with one number (the x component); got {type(answer).__name__}") from None
    ref = _stokes_A()
    if not np.isfinite(val):
        raise _Wrong("your number is not finite")
    if abs(val + ref) <= 0.02 * abs(ref):
        raise _Wrong("your sign is reversed: a counter-clockwise gait collects +D(-A), and circle_gait "
                     "runs counter-clockwise.")
    if abs(val - ref) > 0.02 * abs(ref):
        raise _Wrong(f"not within 2 % of the area integral of the x curvature over the disc "
                     f"(you have {val:.4f}). Is your grid fine enough, and did you multiply by the cell area?")
    return f"Correct: {val:.4f}; the exact net x displacement in this frame is about -0.149."


_OPT_41C = {"a": "C's outer ring encloses x curvature of the opposite sign, which cancels part of the centre's",
            "b": "larger gaits are run faster, so the swimmer slips more",
            "c": "the Stokes estimate is wrong for large gaits, so the map cannot be used",
            "d": "the x curvature vanishes further than 1 from the origin"}


def _judge_41c(answer):
    key = _choice(answer, _OPT_41C)
    if key == "a":
        return "Correct: the red lobes on the anti-diagonal subtract from the blue band along the diagonal."
    raise _Wrong({"b": "The net displacement of a gait does not depend on its pace (the reparameterization (3.3)).",
                  "c": "It is less accurate for large gaits, yet the exact values show the same ordering.",
                  "d": "Look again at the map: there are strong lobes near (1.5, -1.5) and (-1.5, 1.5)."}[key])


ex4_1 = _Exercise("4.1", "Which gait moves further? Reading a curvature map", [
    _Part("4.1", "a", "Which gait moves the low-Re swimmer further forward per cycle? ('a'-'d')", _judge_41a,
          ["Look at the x map of the low-Re swimmer with both circles drawn on it.",
           "Net x motion ~ (area inside the loop where D(-A)_x is blue) - (area where it is red), weighted."],
          "a: the smaller circle A.", reference="a", wrong=["b", "d"]),
    _Part("4.1", "b", "The x component of the Stokes estimate for gait A, from your own area sum (a number)",
          _judge_41b,
          ["Evaluate constraint_curvature(swimmer, grid) on a fine grid over the square [-1, 1]^2.",
           "Keep the points with a1^2 + a2^2 <= 1, sum their x curvature and multiply by the cell area."],
          "About -0.156 (stokes_estimate(swimmer, circle_gait(1.0))[0]).", reference=None, wrong=[0.156, 0.0]),
    _Part("4.1", "c", "Why does the larger circle move less? ('a'-'d')", _judge_41c,
          ["Compare the colours at radius 1 and at radius 2 on the x map."],
          "a: the enclosed curvature changes sign further out.", reference="a", wrong=["c"]),
])


# ============================================================================ 4.2
def drift_and_turn(gait, system=None):
    """(turn angle, distance moved by the centre of mass) over one cycle of ``gait``.

    The shape is the same at the start and the end of a cycle, so the centre of mass sits at the
    same place c in the body frame; the world moves it from c to g(T) c.
    """
    from ..groups import SE2
    from ..locomotion import as_gait, net_displacement

    system = system or swimmer()
    gait = as_gait(gait)
    r0 = gait(np.array([0.0]))[0]
    w = np.array(system.lengths) / sum(system.lengths)
    c = w @ system.link_poses(r0)[:, :2]
    gT = net_displacement(system, gait)
    return float(gT[2]), float(np.linalg.norm(SE2.act_on_points(gT, c) - c))


def _judge_42a(answer):
    from ..locomotion import Gait

    if not (isinstance(answer, Gait) or callable(answer) or isinstance(answer, (list, tuple, np.ndarray))):
        raise _Wrong(f"hand in a Gait (e.g. circle_gait(...)), a callable t -> r(t) of period 1 or an "
                     f"array of shapes (K, 2); got {type(answer).__name__}")
    turn, drift = drift_and_turn(answer)
    if abs(turn) < 0.2:
        raise _Wrong(f"it turns by only {turn:+.3f} rad per cycle; we want at least 0.2 rad. "
                     "Which part of the theta map would you enclose?")
    if drift > 0.02:
        raise _Wrong(f"it turns by {turn:+.3f} rad, but its centre of mass moves {drift:.3f} per cycle "
                     "(the swimmer is 3 long); we want at most 0.02. Try smaller or shifted loops.")
    return f"Correct: it turns by {turn:+.3f} rad while its centre of mass moves only {drift:.4f}."


_OPT_42B = {"a": "where the theta curvature is strong and of one sign, away from the x and y lobes",
            "b": "centred on the origin, where every curvature is largest",
            "c": "anywhere: the swimmer cannot turn without also moving",
            "d": "on the line alpha1 = -alpha2"}


def _judge_42b(answer):
    key = _choice(answer, _OPT_42B)
    if key == "a":
        return "Correct: enclose theta curvature of one sign while the x and y curvature enclosed cancels."
    raise _Wrong({"b": "A loop centred on the origin encloses theta curvature of both signs: it does not turn.",
                  "c": "It can, approximately: look for loops whose enclosed x and y curvature cancel.",
                  "d": "By the swimmer's symmetry, such loops do not turn it at all."}[key])


def _ref_42():
    from ..locomotion import circle_gait

    return circle_gait(0.5, (1.5, 1.5))


ex4_2 = _Exercise("4.2", "A gait that turns the swimmer in place", [
    _Part("4.2", "a", "A gait of the low-Re swimmer that turns it by >= 0.2 rad per cycle while its centre "
                      "of mass moves <= 0.02", _judge_42a,
          ["On the theta map, where is the curvature strong and of one sign?",
           "Try small circles centred on the diagonal alpha1 = alpha2 (a C-shaped body on average).",
           "Scan centres (c, c) and radii with drift_and_turn(gait) from gm_core.checks.ch4."],
          "For example circle_gait(0.5, (1.5, 1.5)): about -0.26 rad, drift about 0.006.",
          reference=_ref_42, wrong=[]),
    _Part("4.2", "b", "Where on the curvature maps does such a gait sit? ('a'-'d')", _judge_42b,
          ["Turning comes from the theta map, moving from the x and y maps."], "a.", reference="a",
          wrong=["b", "c"]),
])

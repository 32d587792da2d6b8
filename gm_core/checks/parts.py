"""The checking engine: parts, exercises, verdicts and the registry.

Design (after Kaggle's learntools and otter-grader): every exercise part has ``check(answer)``,
``hint(n=1)`` and ``solution()``. A check works in two halves:

1. **collect** -- ``part.probes()`` are small functions ``probe(answer) -> plain data`` (numbers,
   float arrays, strings). They are the only code that touches the student's answer, and they
   run in a separate, killable process under a time limit (:mod:`gm_core.checks.sandbox`).
2. **judge** -- ``part.judge(outcomes)`` compares those plain outcomes with the part's answer
   key (:mod:`gm_core.checks.answer_key`), here, in the checking process. Nothing the student's
   code does can change the judge.

A part holds only what a student may see and what reads the answer; what a right answer is lives
in its key (``part.key``, provided by :mod:`gm_core.checks.keys`), which the graded build lacks.

The grader (:mod:`gm_grader.batch`) uses the same split: the probes run inside the student's
notebook kernel at each check call, the judging in the grading process. ``check`` never raises (unless
``strict=True``, for nbgrader/otter test cells: None on success, AssertionError on failure).

numpy only at import time; sympy is imported only when an answer is a sympy object.
"""
from __future__ import annotations

import copy
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import Any, ClassVar, Literal, NoReturn, TypeVar, overload

import numpy as np
import numpy.typing as npt
from typing_extensions import override

from gm_core.checks import channel, store
from gm_core.checks.answer_key import (
    AnswerKey,
    AnswerKeyHidden,
    FunctionKey,
    JudgeKey,
    Mistake,
    TupleKey,
    ValueKey,
    key_of,
    keys_installed,
)
from gm_core.checks.answers import (
    describe,
    fmt_args,
    fmt_value,
    is_starter,
    is_sympy,
    match_shape,
    sympy_function,
    to_numbers,
)
from gm_core.checks.display import show
from gm_core.checks.exercise import Exercise
from gm_core.checks.sandbox import (
    Probe,
    ProbeOutcome,
    Unattempted,
    Wrong,
    collect,
    decode_outcome,
    safe_text,
)
from gm_core.checks.store import FAILED, PASSED, UNATTEMPTED
from gm_core.checks.wording import differing_entries
from gm_core.groups import wrap_angle

K = TypeVar("K", bound=AnswerKey)

#: What a check says in the graded build, which has no keys to judge with.
SENT_TO_GRADER = ("Sent to the grader: this copy of the course is the graded build, which has no "
                  "answer keys, so the grader judges your answer after the run.")


class Verdict:
    """The result of a check: ``status`` (passed / failed / unattempted) and a message."""

    def __init__(self, status: str, message: str, part: str = "", output: str = "") -> None:
        self.status, self.message, self.part, self.output = status, message, part, output
        self._shown = False

    def __bool__(self) -> bool:
        return self.status == PASSED

    @property
    def passed(self) -> bool:
        return self.status == PASSED

    def show(self) -> Verdict:
        show(self.status, self.part, self.message, self.output)
        self._shown = True
        return self

    def _ipython_display_(self) -> None:
        # check() has already displayed the message; ending a cell with it shows nothing more.
        if not self._shown:
            self.show()

    @override
    def __repr__(self) -> str:
        return f"Verdict({self.part}: {self.status} - {self.message})"


def outcome_error(o: ProbeOutcome, what: str, label: str) -> NoReturn:
    """Raise the readable Wrong/Unattempted for a non-"ok" probe outcome ``o`` (``what`` gave it
    when called with ``label``)."""
    k = o["k"]
    if k == "wrong":
        raise Wrong(o["m"])
    if k == "unattempted":
        raise Unattempted(o["m"])
    if k == "error":
        extra = f": {o['x']}" if o.get("x") else ""
        raise Wrong(f"{what} raised {o['m']}{extra} when called with {label}.")
    if k == "timeout":
        raise Wrong(f"{what} took longer than {o['m']} s when called with {label}, so the check "
                    "stopped it (an endless loop? a very slow method?). Your kernel is fine; "
                    "set_time_limit(seconds) allows more time.")
    if k == "crash":  # the sandbox says how ("x"): a signal, an exit status, a segfault
        how = o.get("x") or "too much memory, or a recursion the interpreter could not survive"
        raise Wrong(f"{what} crashed the Python process it ran in when called with {label} ({how}).")
    raise Wrong(f"{what} could not be checked further after an earlier call stopped.")


def first_value(outcomes: list[ProbeOutcome], what: str, label: str) -> Any:
    """The value of the first probe outcome; :func:`outcome_error` when it is not "ok" (or there
    is none: a crash)."""
    o: ProbeOutcome = outcomes[0] if outcomes else {"k": "crash", "m": ""}
    if o["k"] != "ok":
        outcome_error(o, what, label)
    return o["v"]


# ------------------------------------------------------------------------------ parts
class Part(ABC):
    """One checkable part. Subclasses implement :meth:`probes` and :meth:`judge`.

    A part declares what a student sees (``prompt``, ``hints``, ``starter``: what the exercise
    notebook starts with) and its ``weight`` (grading points); its answer key
    (:attr:`key`, of the part's ``key_type``) says what a right answer is. The tests use the key's
    ``reference`` (a correct answer) and ``wrong`` (plausible wrong answers), also readable as
    ``part.reference`` and ``part.wrong``.
    """

    kind: str = "numeric"
    weight: float = 2.0
    #: The kind of answer key this part is judged with.
    key_type: ClassVar[type[AnswerKey]] = AnswerKey

    def __init__(self, name: str, prompt: str, hints: Sequence[str] = (), starter: Any = None,
                 weight: float | None = None) -> None:
        self.name = name
        self.prompt = prompt
        self.hints = list(hints)
        self.starter = starter
        if weight is not None:
            self.weight = float(weight)
        self.exercise: Exercise | None = None  # set by Exercise

    # -- the answer key (absent in the graded build: AnswerKeyHidden, reported to the grader)
    def key_as(self, kind: type[K], asked: str = "key") -> K:
        """The part's answer key, checked to be a ``kind``."""
        key = key_of(self, asked)
        if not isinstance(key, kind):
            raise TypeError(f"the key of {self.title} is a {type(key).__name__}, not a {kind.__name__}")
        return key

    def check_key(self, key: AnswerKey) -> None:  # noqa: B027 - most parts take any key of their kind
        """Raise ValueError if ``key`` does not fit this part (called by :func:`~.answer_key.provide`)."""

    @property
    def key(self) -> AnswerKey:
        """The part's answer key (:mod:`gm_core.checks.answer_key`)."""
        return self.key_as(self.key_type)

    @property
    def reference(self) -> Any:
        """A correct answer, as a student would give it."""
        return self.key_as(AnswerKey, "reference").correct_answer()

    @property
    def wrong(self) -> list[Any]:
        """Plausible wrong answers (the tests try each)."""
        return list(self.key_as(AnswerKey, "wrong").wrong)

    @property
    def solution_text(self) -> str:
        """The key result ``solution()`` shows."""
        return self.key_as(AnswerKey, "solution()").solution_text

    @property
    def id(self) -> str:
        ex = self.exercise.id if self.exercise is not None else "?"
        return f"{ex}{self.name}" if len(self.name) <= 1 else f"{ex} {self.name}"

    @property
    def title(self) -> str:
        return f"exercise {self.id}"

    @override
    def __repr__(self) -> str:
        return f"<check for exercise {self.id}: {self.prompt}>"

    # -- the two halves
    @abstractmethod
    def probes(self) -> list[Probe]:
        """Functions probe(answer) -> plain data; the only code that touches the answer."""
        raise NotImplementedError

    @abstractmethod
    def judge(self, outcomes: list[ProbeOutcome]) -> str:
        """Return the success message, or raise Wrong / Unattempted, from the probes' outcomes."""
        raise NotImplementedError

    def verdict(self, outcomes: list[ProbeOutcome], output: str = "") -> Verdict:
        """A Verdict from plain outcomes (used by check() and by the grader). Never raises."""
        try:
            if not keys_installed():   # the graded build: the grader judges with its own keys
                return Verdict(UNATTEMPTED, SENT_TO_GRADER, self.title, output)
            if not isinstance(outcomes, list) or len(outcomes) != len(self.probes()):
                raise Wrong("the check could not evaluate your answer completely.")
            message = self.judge(outcomes)
            status = PASSED
        except Unattempted as u:
            status, message = UNATTEMPTED, safe_text(u, 600) or (
                "You have not answered yet: replace the starter value in the cell above (it is "
                "still None). Use .hint() if you are stuck.")
        except Wrong as w:
            status, message = FAILED, safe_text(w, 600)
        except Exception as exc:  # noqa: BLE001 - a checker bug must not break the notebook
            status, message = FAILED, ("The checker could not make sense of your answer "
                                       f"({type(exc).__name__}). Check its type against the "
                                       "prompt, or ask .hint().")
        return Verdict(status, message or "Well done.", self.title, output)

    # -- the three verbs
    @overload
    def check(self, answer: Any = None, *, quiet: bool = False, strict: Literal[False] = False,
              time_limit: float | None = None) -> Verdict: ...

    @overload
    def check(self, answer: Any = None, *, quiet: bool = False, strict: bool,
              time_limit: float | None = None) -> Verdict | None: ...

    def check(self, answer: Any = None, *, quiet: bool = False, strict: bool = False,
              time_limit: float | None = None) -> Verdict | None:
        """Check ``answer``; display and return a :class:`Verdict`. Never raises, unless
        ``strict=True`` (nbgrader / otter-grader test cells): then a passed check returns None
        (a doctest-style cell expects nothing) and a failed one raises AssertionError with the
        same message.

        While the grader runs the notebook, the answer as it is now is also sent, at this call, on
        the grader's evidence channel (:mod:`gm_core.checks.channel`): the grader calls it later,
        on inputs of its own, outside this kernel."""
        channel.begin(self)
        raw = None
        try:
            raw, output = collect(answer, self.probes(), time_limit, raw=True)
            verdict = self.verdict([decode_outcome(o) for o in raw], output)
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # noqa: BLE001 - never let anything escape into the notebook
            verdict = Verdict(FAILED, f"The check stopped unexpectedly ({type(exc).__name__}).",
                              self.title)
        finally:
            channel.emit(self, raw if raw is not None else "stopped", "" if raw is None else output,
                         answer)
        self._record(verdict.status)
        if not quiet:
            try:
                verdict.show()
            except Exception:  # noqa: BLE001
                pass
        if strict:
            if not verdict.passed:
                raise AssertionError(f"{self.title}: {verdict.message}")
            return None
        return verdict

    def hint_text(self, n: int = 1) -> str:
        if not self.hints:
            return "There is no hint for this part; see the section of the book the prompt cites."
        try:
            k = int(n)
        except Exception:  # noqa: BLE001
            k = 1
        k = min(max(k, 1), len(self.hints))
        more = f" (hint {k} of {len(self.hints)}"
        more += f"; ask .hint({k + 1}) for more)" if k < len(self.hints) else ")"
        return self.hints[k - 1] + more

    def hint(self, n: int = 1) -> None:
        """Show hint number ``n`` (1 = gentlest). Shows it once; returns None."""
        show("hint", self.title, self.hint_text(n))

    def solution_path(self) -> str:
        """Where the worked solution is, relative to the notebook's folder (workspace/, exercises/)."""
        ex = self.exercise
        name = f"ex{ex.id.replace('.', '_')}.ipynb" if ex is not None else ""
        return f"../solutions/{name}"

    def solution_text_full(self) -> str:
        return (self.solution_text or "See the worked solution.") + \
            f"\nFull derivation: {self.solution_path()} (the solutions/ folder of the course)"

    def solution(self) -> None:
        """Show the key result and where the worked notebook is (recorded in your progress). The
        graded build has no solutions: it says so (and the grader gives the part no marks)."""
        if self.exercise is not None:
            store.record_solution_view(self.exercise.id, self.name)
        try:
            text = self.solution_text_full()
        except AnswerKeyHidden as exc:
            show(FAILED, self.title, str(exc))
            return
        show("solution", self.title, text)

    def _record(self, status: str) -> None:
        # "unattempted" (the starter, or a choice that names no option) never overwrites a
        # saved verdict: re-running an untouched cell must not erase yesterday's pass
        if self.exercise is not None and status != UNATTEMPTED:
            store.record(self.exercise.id, self.name, status)


class FunctionPart(Part):
    """The answer is a function (or a sympy expression, or a constant) compared with a reference.

    ``inputs()`` yields argument tuples; the key (:class:`~.answer_key.FunctionKey`) gives the
    expected array ``ref(*args)`` and the known mistakes. A sympy answer is evaluated with its
    symbols matched by name to ``sympy_names`` (values ``sympy_args(*args)``). ``angles``: output
    entries compared modulo 2 pi. ``postprocess(out, args)`` normalises a student's output (runs
    with the probes).
    """

    kind = "function"
    key_type = FunctionKey

    def __init__(self, name: str, prompt: str, inputs: Callable[[], Iterable[tuple[Any, ...]]],
                 *, arg_names: Sequence[str], shape: tuple[int, ...], rtol: float = 1e-6, atol: float = 1e-8,
                 postprocess: Callable[[Any, tuple[Any, ...]], Any] | None = None,
                 sympy_names: Sequence[str] | None = None,
                 sympy_args: Callable[..., tuple[Any, ...]] | None = None,
                 sympy_ok: Callable[..., bool] | None = None,
                 angles: Sequence[int] = (), what: str = "your function", **kw: Any) -> None:
        super().__init__(name, prompt, **kw)
        self.inputs = inputs
        self.arg_names = tuple(arg_names)
        self.sympy_names = tuple(sympy_names) if sympy_names is not None else self.arg_names
        self.sympy_args = sympy_args
        self.sympy_ok = sympy_ok
        self.shape = tuple(shape)
        self.rtol, self.atol = rtol, atol
        self.postprocess = postprocess
        self.angles = tuple(angles)
        self.what = what

    # -- student side (runs in the sandbox)
    def as_function(self, answer: Any) -> tuple[Callable[..., Any], str, str]:
        """(callable, kind, description) for an answer: a function, sympy object or constant."""
        if is_starter(answer):
            raise Unattempted()
        if is_sympy(answer) or (isinstance(answer, (list, tuple)) and answer and any(
                is_sympy(a) or isinstance(a, (list, tuple)) and any(is_sympy(b) for b in a)
                for a in answer)):
            f = sympy_function(answer, self.sympy_names, self.sympy_args, "your expression")
            if f is not None:
                return f, "sympy", "your expression"
        if callable(answer) and not isinstance(answer, type):
            return answer, "function", self.what
        if isinstance(answer, (list, tuple)) and answer and all(is_starter(a) for a in answer):
            raise Unattempted()
        if not self.arg_names:
            return (lambda *args: answer), "constant", "your answer"
        raise Wrong(f"your answer is {describe(answer)}; {self.prompt_type} was expected.")

    @property
    def prompt_type(self) -> str:
        return (f"a function of ({', '.join(self.arg_names)})" if self.arg_names
                else "a number or array")

    def student_value(self, answer: Any, args: tuple[Any, ...]) -> np.ndarray | str | None:
        """Student side: the answer's value at ``args`` as a float array of ``shape`` (None: it
        returned the starter; "skip": a sympy answer where ``sympy_ok`` says it cannot be read)."""
        f, kind, what = self.as_function(answer)
        if kind == "sympy" and self.sympy_ok is not None and not self.sympy_ok(*args):
            return "skip"
        out = f(*copy.deepcopy(args))
        if is_starter(out):
            return None
        if self.postprocess is not None:
            out = self.postprocess(out, args)
        got = to_numbers(out, f"the value {what} returned for {self._label(args)}")
        return match_shape(got, self.shape, f"the value {what} returned")

    @override
    def probes(self) -> list[Probe]:
        def probe(args: tuple[Any, ...]) -> Probe:
            return lambda ans: self.student_value(ans, args)
        return [probe(args) for args in self.inputs()]

    # -- judge side
    def close(self, got: npt.ArrayLike, expected: npt.ArrayLike) -> bool:
        """``got`` equals ``expected`` within ``atol + rtol * |expected|`` (``angles`` modulo 2 pi)."""
        got = np.asarray(got, dtype=float)
        expected = np.asarray(expected, dtype=float)
        if got.shape != expected.shape:
            return False
        return not bool(np.any(self.differing(got, expected)))

    def differing(self, got: np.ndarray, expected: np.ndarray) -> np.ndarray:
        """Which entries of ``got`` are not within the tolerance of ``expected`` (same shape): a
        boolean array; ``angles`` are compared modulo 2 pi, and NaN or inf always differ."""
        diff = np.array(got, dtype=float) - np.asarray(expected, dtype=float)
        if self.angles and diff.ndim == 1:
            for i in self.angles:
                if np.isfinite(diff[i]):   # a NaN or infinite difference stays so, and fails
                    diff[i] = wrap_angle(diff[i])
        with np.errstate(all="ignore"):
            return ~(np.abs(diff) <= self.atol + self.rtol * np.abs(expected))

    @property
    def ref(self) -> Callable[..., npt.ArrayLike]:
        """The reference function of the key."""
        return self.key_as(FunctionKey, "ref").ref

    @override
    def judge(self, outcomes: list[ProbeOutcome]) -> str:
        return self.judge_with(self.key_as(FunctionKey), outcomes)

    def judge_with(self, key: FunctionKey, outcomes: list[ProbeOutcome]) -> str:
        """:meth:`judge` with ``key`` (a :class:`TuplePart` judges each component with its own)."""
        all_args = list(self.inputs())
        what = self.what
        got_all: list[Any] = []
        nones = [o["k"] == "ok" and o["v"] is None for o in outcomes]
        if outcomes and all(nones):
            raise Unattempted("Your function still returns None: fill in its body.")
        for args, o in zip(all_args, outcomes):
            label = self._label(args)
            if o["k"] != "ok":
                outcome_error(o, what, label)
            if o["v"] is None:
                raise Wrong(f"{what} returned None for {label} (a branch without a return "
                            "statement?), although it returns a value for other inputs.")
            if isinstance(o["v"], str):
                # "skip": a sympy closed form at its removable 0/0, and only there
                if o["v"] == "skip" and self.sympy_ok is not None and not self.sympy_ok(*args):
                    got_all.append(None)
                    continue
                raise Wrong(f"{what} returned text for {label}; numbers were expected.")
            got = np.asarray(o["v"], dtype=float)
            if got.shape != self.shape:
                raise Wrong(f"the value {what} returned for {label} has shape {got.shape}, but "
                            f"shape {self.shape} was expected.")
            if not np.all(np.isfinite(got)):
                raise Wrong(f"the value {what} returned for {label} contains NaN or infinite "
                            "entries (a division by zero at this input?).")
            got_all.append(got)
        if len(outcomes) != len(all_args) or all(g is None for g in got_all):
            raise Wrong("the check could not evaluate your answer on every input.")
        expected = [np.asarray(key.ref(*a), dtype=float) for a in all_args]
        bad = [i for i, g in enumerate(got_all) if g is not None and not self.close(g, expected[i])]
        if not bad:
            return self.success
        for wrong_f, msg in key.mistakes:
            if self._matches_everywhere(wrong_f, all_args, got_all):
                raise Wrong(msg)
        i = bad[0]
        where = self._where(got_all[i], expected[i])
        raise Wrong(f"{what.capitalize()} gives a different value for {self._label(all_args[i])}"
                    f"{where}. Try this case by hand, or ask .hint().")

    def _matches_everywhere(self, wrong_f: Callable[..., npt.ArrayLike], all_args: list[tuple[Any, ...]],
                            got_all: list[np.ndarray | None]) -> bool:
        for args, got in zip(all_args, got_all):
            if got is None:
                continue
            try:
                w = np.asarray(wrong_f(*copy.deepcopy(args)), dtype=float)
            except Exception:  # noqa: BLE001
                return False
            if w.shape != got.shape or not self.close(got, w):
                return False
        return True

    success = "Correct: your answer matches the reference on random and edge-case inputs."

    def _label(self, args: tuple[Any, ...]) -> str:
        if not self.arg_names:
            return "this part"
        return ", ".join(f"{n}={fmt_args((a,))[1:-1]}" for n, a in zip(self.arg_names, args))

    def _where(self, got: np.ndarray, expected: np.ndarray) -> str:
        """": the second entry differs" (positions counted from 1 and named), or "" for a number."""
        if got.ndim == 0 or got.size == 1:
            return ""
        text = differing_entries(np.argwhere(self.differing(got, expected)), got.shape)
        return f": {text}" if text else ""


class TuplePart(Part):
    """An answer made of several named components, each judged like a :class:`FunctionPart`."""

    kind = "tuple"
    key_type = TupleKey

    def __init__(self, name: str, prompt: str, components: Sequence[tuple[str, FunctionPart]],
                 **kw: Any) -> None:
        super().__init__(name, prompt, **kw)
        self.components = list(components)  # [(label, FunctionPart)]; keys: TupleKey.components

    def _values(self, answer: Any) -> list[Any]:
        labels = [lbl for lbl, _ in self.components]
        if is_starter(answer):
            raise Unattempted()
        if isinstance(answer, dict):
            missing = [lbl for lbl in labels if lbl not in answer]
            if missing:
                raise Wrong(f"your dict is missing the key(s) {', '.join(missing)}.")
            values = [answer[lbl] for lbl in labels]
        elif isinstance(answer, (list, tuple)):
            if len(answer) != len(labels):
                raise Wrong(f"your answer has {len(answer)} components; {len(labels)} were expected "
                            f"({', '.join(labels)}).")
            values = list(answer)
        else:
            raise Wrong(f"your answer is {describe(answer)}; a tuple ({', '.join(labels)}) was "
                        "expected.")
        if all(is_starter(v) for v in values):
            raise Unattempted()
        for label, v in zip(labels, values):
            if is_starter(v):
                raise Wrong(f"{label} is still None; the other components were given.")
        return values

    @override
    def check_key(self, key: AnswerKey) -> None:
        if isinstance(key, TupleKey) and len(key.components) != len(self.components):
            raise ValueError(f"the key of {self.title} has {len(key.components)} components; the "
                             f"part has {len(self.components)}")

    @override
    def probes(self) -> list[Probe]:
        def probe(i: int, part: FunctionPart, args: tuple[Any, ...]) -> Probe:
            return lambda ans: part.student_value(self._values(ans)[i], args)
        out: list[Probe] = [lambda ans: (self._values(ans), "ok")[1]]
        for i, (_, part) in enumerate(self.components):
            out += [probe(i, part, args) for args in part.inputs()]
        return out

    @override
    def judge(self, outcomes: list[ProbeOutcome]) -> str:
        if not outcomes:
            raise Wrong("the check could not evaluate your answer.")
        first = outcomes[0]
        if first["k"] != "ok":
            outcome_error(first, "your answer", "no arguments")
        keys = self.key_as(TupleKey).components
        k = 1
        for (label, part), key in zip(self.components, keys):
            n = len(list(part.inputs()))
            try:
                part.judge_with(key, outcomes[k:k + n])
            except Unattempted:
                raise Wrong(f"{label}: the function still returns None.") from None
            except Wrong as w:
                raise Wrong(f"{label}: {w}") from None
            k += n
        return "Correct: " + ", ".join(lbl for lbl, _ in self.components) + " all match the reference."


class CustomPart(Part):
    """A part with its own probes, ``make_probes() -> [probe]``, judged by its key's own judge
    (:class:`~.answer_key.JudgeKey`)."""

    key_type = JudgeKey

    def __init__(self, name: str, prompt: str, make_probes: Callable[[], list[Probe]],
                 kind: str = "custom", **kw: Any) -> None:
        super().__init__(name, prompt, **kw)
        self._make_probes = make_probes
        self.kind = kind

    @override
    def probes(self) -> list[Probe]:
        return list(self._make_probes())

    @override
    def judge(self, outcomes: list[ProbeOutcome]) -> str:
        return self.key_as(JudgeKey).judge(outcomes)


class ValuePart(Part):
    """A one-value answer (a number, or an array of ``shape``) compared with an expected value
    within a tolerance, declared by class attributes like learntools' problems::

        class DiscArea(ValuePart):
            name = "a"
            prompt = "The area of the unit disc (a number)"
            rtol = 1e-6
            hints = ["The area of a disc of radius r is pi r^2."]

        ex9_1 = Exercise("9.1", "Discs", [DiscArea()])

    and its key in the chapter's key module (:mod:`gm_core.checks.keys`)::

        provide(ex9_1, a=ValueKey(expected=np.pi, solution_text="pi r^2 = pi for r = 1.",
                mistakes=[Mistake(2 * np.pi, "that is the circumference 2 pi r, not the area.")]))

    The probe and the judge come from this class. The probe reads the answer as plain numbers:
    the starter value is unattempted; a bool, text, a function or the wrong number of entries gets
    a message saying what was expected (``expects``, ``wrong_size``). The judge passes a value
    within ``atol + rtol * |expected|`` of the key's expected value (entry by entry for an array)
    with ``success`` (or the key's own success message); otherwise it raises the message of the
    first of the key's mistakes the value is close to, else says how it is off
    (:meth:`far_message`). A value that is not finite gets ``not_finite``.

    ``kind``, ``weight`` and ``starter`` are those of :class:`Part`. Keyword arguments of the
    constructor override the class attributes (``DiscArea(weight=1.0)``).
    """

    kind = "number"
    key_type = ValueKey
    rtol: float = 1e-6
    atol: float = 1e-8
    shape: tuple[int, ...] = ()
    #: What the answer should be, in messages ("one number"); empty: said from ``shape``.
    expects: str = ""
    wrong_size: str = "your answer has {size} numbers (shape {shape}); {expects} was expected."
    not_finite: str = "your answer is not finite (NaN or infinite entries)."
    success: str = "Correct."

    def __init__(self, **overrides: Any) -> None:
        declarable = ("name", "prompt", "hints", "starter", "weight")
        unknown = sorted(set(overrides) - set(declarable))
        if unknown:
            raise TypeError(f"{type(self).__name__}() got unexpected arguments {unknown}; declare "
                            "the rest as class attributes, and what a right answer is in its key")

        def declared(key: str, default: Any = None) -> Any:
            return overrides[key] if key in overrides else getattr(type(self), key, default)

        name, prompt = declared("name"), declared("prompt")
        if not (isinstance(name, str) and isinstance(prompt, str)):
            raise TypeError(f"{type(self).__name__} must declare a name and a prompt (class attributes)")
        super().__init__(name, prompt, hints=declared("hints", ()), starter=declared("starter"),
                         weight=declared("weight"))

    # -- student side (runs in the sandbox)
    def read(self, answer: Any) -> float | np.ndarray:
        """The answer as plain numbers: a float, or an array of ``shape``."""
        if is_starter(answer):
            raise Unattempted()
        if isinstance(answer, (bool, np.bool_)):
            raise Wrong(f"your answer is {describe(answer)}; {self.expects_text} was expected.")
        arr = to_numbers(answer, "your answer")
        if arr.size != int(np.prod(self.shape)):
            raise Wrong(self.wrong_size.format(size=arr.size, shape=arr.shape, expects=self.expects_text))
        if not self.shape:
            return float(arr.reshape(()))
        return match_shape(arr, self.shape, "your answer")

    @override
    def probes(self) -> list[Probe]:
        return [self.read]

    # -- judge side
    @property
    def expects_text(self) -> str:
        """What the answer should be, as the messages say it."""
        if self.expects:
            return self.expects
        return "one number" if not self.shape else f"an array of shape {self.shape}"

    def expected_value(self) -> npt.ArrayLike:
        """The value a right answer is close to (the key's)."""
        return self.key_as(ValueKey, "expected").expected_value()

    def known_mistakes(self, expected: npt.ArrayLike) -> list[Mistake]:
        """The mistakes tried, in order, on a value that is not close to ``expected`` (the key's)."""
        return self.key_as(ValueKey, "mistakes").known_mistakes(expected)

    def close(self, value: npt.ArrayLike, target: npt.ArrayLike, tol: float | None = None) -> bool:
        """``value`` within ``tol`` of ``target`` (default: ``atol + rtol * |target|``), entry by entry."""
        got, want = np.asarray(value, dtype=float), np.asarray(target, dtype=float)
        if got.shape != want.shape:
            return False
        with np.errstate(all="ignore"):
            bound = self.atol + self.rtol * np.abs(want) if tol is None else tol
            return bool(np.all(np.abs(got - want) <= bound))

    def success_message(self, value: float | np.ndarray, expected: npt.ArrayLike) -> str:
        """The message of a right answer (the key's, default: ``success``)."""
        said = self.key_as(ValueKey).success
        return self.success if said is None else said(value, expected)

    def far_message(self, value: float | np.ndarray, expected: npt.ArrayLike) -> str:
        """The message of a value that is neither right nor a known mistake."""
        return (f"your answer {fmt_value(value)} is not the expected value (to a relative tolerance "
                f"of {self.rtol:g}). Check how you computed it, or ask .hint().")

    @override
    def judge(self, outcomes: list[ProbeOutcome]) -> str:
        value = first_value(outcomes, "your answer", "no arguments")
        if not (isinstance(value, float) if not self.shape
                else isinstance(value, np.ndarray) and value.shape == self.shape):
            raise Wrong(f"{self.expects_text} was expected.")
        if not np.all(np.isfinite(value)):
            raise Wrong(self.not_finite)
        expected = self.expected_value()
        if self.close(value, expected):
            return self.success_message(value, expected)
        for mistake in self.known_mistakes(expected):
            if self.close(value, mistake.value, mistake.tol):
                raise Wrong(mistake.message)
        raise Wrong(self.far_message(value, expected))


# ------------------------------------------------------------------------------ input helpers
def probe_rng(seed: int) -> np.random.Generator:
    """The random generator for a checker's inputs: ``seed``, salted by the grader when grading
    (:func:`gm_core.checks.channel.set_probe_salt`), so a graded run's inputs cannot be known in advance."""
    salt = channel.probe_salt()
    return np.random.default_rng(seed if salt is None else [int(seed), salt])


def salted() -> bool:
    """True while the grader has salted the probe inputs (a graded run, or its judging)."""
    return channel.probe_salt() is not None


def rng_inputs(seed: int, n: int, make: Callable[[np.random.Generator], Sequence[Any]],
               edges: Iterable[Sequence[Any]] = ()) -> Callable[[], Iterator[tuple[Any, ...]]]:
    """A function yielding the edge cases first, then ``n`` seeded random argument tuples."""
    def inputs() -> Iterator[tuple[Any, ...]]:
        for e in edges:
            yield tuple(e)
        rng = probe_rng(seed)
        for _ in range(n):
            yield tuple(make(rng))
    return inputs


__all__ = ["Verdict", "Part", "FunctionPart", "TuplePart", "CustomPart", "ValuePart",
           "outcome_error", "rng_inputs", "probe_rng", "salted", "SENT_TO_GRADER"]

"""The checking engine: verdicts, parts, exercises and the per-kernel progress record.

Design (after Kaggle's learntools): every exercise part is an object with ``check(answer)``,
``hint(n=1)`` and ``solution()``. ``check`` never raises: whatever the student hands in (None, a
string, a function that divides by zero, NaN, the wrong shape) it returns a :class:`Verdict` whose
``status`` is ``"passed"``, ``"failed"`` or ``"unattempted"`` and whose message says what is wrong
without giving the answer away. The untouched starter (``None``, ``...`` or a starter function
that still returns ``None``) is "unattempted", never "failed".

numpy only at import time; sympy is imported only when an answer is a sympy object and ipywidgets
only inside the widget helpers (``gm_core.checks._widgets``).
"""
from __future__ import annotations

import html
import math
import warnings
from dataclasses import dataclass, field

import numpy as np

PASSED, FAILED, UNATTEMPTED = "passed", "failed", "unattempted"
EXERCISE_IDS = ("1.1", "1.2", "1.3", "1.4", "1.5", "2.1", "2.2", "2.3", "2.4",
                "3.1", "3.2", "3.3", "3.4")

#: Latest status of each checked part in this kernel: {(exercise id, part name): status}.
_STATE: dict = {}
#: Every registered exercise, by id.
REGISTRY: dict = {}


class Unattempted(Exception):
    """Raised inside a checker when the answer is still the starter value."""


class Wrong(Exception):
    """Raised inside a checker with a friendly message when the answer is wrong."""


# ------------------------------------------------------------------------------ display helpers
def _ipython():
    try:
        from IPython import get_ipython
    except Exception:  # pragma: no cover - IPython is always there with Jupyter
        return None
    ip = get_ipython()
    return ip if ip is not None and hasattr(ip, "kernel") else None


_COLORS = {PASSED: "#1a7f37", FAILED: "#b42318", UNATTEMPTED: "#6e7781", "hint": "#7a5c00",
           "solution": "#0550ae"}
_LABELS = {PASSED: "Correct", FAILED: "Not yet", UNATTEMPTED: "Unattempted", "hint": "Hint",
           "solution": "Solution"}


def show(kind, title, message):
    """Display a coloured message box in a notebook, or print it as plain text elsewhere."""
    label = _LABELS.get(kind, kind)
    if _ipython() is not None:
        try:
            from IPython.display import HTML, display
            color = _COLORS.get(kind, "#333")
            body = html.escape(message).replace("\n", "<br>")
            display(HTML(f'<div style="border-left:4px solid {color};padding:4px 10px;margin:4px 0">'
                         f'<b style="color:{color}">{label}</b> <span style="color:#555">'
                         f'({html.escape(title)})</span><br>{body}</div>'))
            return
        except Exception:
            pass
    print(f"[{label}] ({title}) {message}")


@dataclass
class Verdict:
    """The result of a check: ``status`` (passed / failed / unattempted) and a message."""

    status: str
    message: str
    part: str = ""
    _shown: bool = field(default=False, repr=False, compare=False)

    def __bool__(self):
        return self.status == PASSED

    @property
    def passed(self):
        return self.status == PASSED

    def show(self):
        show(self.status, self.part, self.message)
        self._shown = True
        return self

    def _ipython_display_(self):
        # check() already displayed the message; ending a cell with it must not print it twice.
        if not self._shown:
            self.show()

    def __repr__(self):
        return f"Verdict({self.part}: {self.status} - {self.message})"


# ------------------------------------------------------------------------------ answer helpers
def is_starter(value):
    """True for the untouched starter values None and Ellipsis."""
    return value is None or value is Ellipsis


def is_sympy(value):
    return type(value).__module__.split(".")[0] == "sympy"


def describe(value):
    t = type(value).__name__
    if isinstance(value, np.ndarray):
        return f"a numpy array of shape {value.shape}"
    if isinstance(value, (list, tuple)):
        return f"a {t} of length {len(value)}"
    if isinstance(value, str):
        return f"the string {value[:40]!r}"
    return f"a {t}"


def to_array(value, what="your answer"):
    """Convert numbers, lists, numpy arrays and sympy numbers/matrices to a float array.

    Raises :class:`Wrong` with a readable message for anything else (strings, symbols left in a
    sympy expression, ragged lists) and for NaN or infinite entries.
    """
    if is_starter(value):
        raise Unattempted()
    if isinstance(value, (str, bytes)):
        raise Wrong(f"{what} is {describe(value)}; a number or an array of numbers was expected.")
    if isinstance(value, dict) or callable(value) and not is_sympy(value):
        raise Wrong(f"{what} is {describe(value)}; a number or an array of numbers was expected.")
    if is_sympy(value):
        free = getattr(value, "free_symbols", set())
        if free:
            names = ", ".join(sorted(str(s) for s in free))
            raise Wrong(f"{what} still contains the symbol(s) {names}; a number was expected here.")
        try:
            value = np.array(value.tolist() if hasattr(value, "tolist") else value, dtype=float)
        except Exception:
            raise Wrong(f"{what} is a sympy object that could not be turned into numbers.") from None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            arr = np.array(value, dtype=float)
    except Exception:
        raise Wrong(f"{what} is {describe(value)}, which is not a number or a (rectangular) array "
                    "of numbers.") from None
    if arr.size and not np.all(np.isfinite(arr)):
        raise Wrong(f"{what} contains NaN or infinite entries.")
    return arr


def match_shape(got, expected_shape, what="your answer"):
    """Return ``got`` reshaped to ``expected_shape`` if it only differs by singleton axes."""
    if got.shape == tuple(expected_shape):
        return got
    if got.size == int(np.prod(expected_shape)) and (
            tuple(s for s in got.shape if s != 1) == tuple(s for s in expected_shape if s != 1)):
        return got.reshape(expected_shape)
    if got.ndim == 2 and len(expected_shape) == 2 and got.shape == tuple(expected_shape)[::-1] \
            and got.shape[0] != got.shape[1]:
        raise Wrong(f"{what} has shape {got.shape}, but shape {tuple(expected_shape)} was expected: "
                    "is it transposed?")
    raise Wrong(f"{what} has shape {got.shape}, but shape {tuple(expected_shape)} was expected.")


def close(got, expected, rtol=1e-6, atol=1e-8):
    got = np.asarray(got, dtype=float)
    expected = np.asarray(expected, dtype=float)
    if got.shape != expected.shape:
        return False
    with np.errstate(all="ignore"):
        return bool(np.all(np.abs(got - expected) <= atol + rtol * np.abs(expected)))


def call_student(func, args, what="your function"):
    """Call a student's function; turn any exception into a :class:`Wrong` message."""
    try:
        with np.errstate(all="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return func(*args)
    except (Wrong, Unattempted):
        raise
    except RecursionError:
        raise Wrong(f"{what} recursed without end when called with {fmt_args(args)}.") from None
    except Exception as exc:  # the student's code may raise anything
        raise Wrong(f"{what} raised {type(exc).__name__}: {str(exc)[:200]} when called with "
                    f"{fmt_args(args)}.") from None


def fmt_args(args):
    def one(a):
        if isinstance(a, np.ndarray):
            return np.array2string(a, precision=4, separator=", ")
        if isinstance(a, float):
            return f"{a:.4g}"
        return repr(a)
    return "(" + ", ".join(one(a) for a in args) + ")"


def sympy_callable(expr, names, what="your expression"):
    """Turn a sympy expression in the symbols ``names`` into a numeric function of those names.

    Symbols are matched by name (so ``symbols('x')`` and ``symbols('x', real=True)`` both work);
    an unexpected symbol gives a :class:`Wrong` message naming it.
    """
    import sympy as sp

    free = {str(s): s for s in getattr(expr, "free_symbols", set())}
    extra = sorted(set(free) - set(names))
    if extra:
        raise Wrong(f"{what} contains the symbol(s) {', '.join(extra)}; only "
                    f"{', '.join(names)} may appear.")
    args = [free.get(n, sp.Symbol(n)) for n in names]
    try:
        f = sp.lambdify(args, expr, modules="numpy")
    except Exception as exc:
        raise Wrong(f"{what} could not be evaluated numerically ({type(exc).__name__}).") from None
    return f


# ------------------------------------------------------------------------------ parts
class Part:
    """One checkable part of an exercise. Subclasses implement :meth:`_check`.

    Attributes used by the tests (and by :meth:`solution`): ``reference`` (a correct answer),
    ``wrong`` (a list of plausible wrong answers) and ``starter`` (what the exercise notebook
    starts with).
    """

    kind = "numeric"

    def __init__(self, name, prompt, hints=(), solution_text="", reference=None, wrong=(),
                 starter=None):
        self.name = name
        self.prompt = prompt
        self.hints = list(hints)
        self.solution_text = solution_text
        self.reference = reference
        self.wrong = list(wrong)
        self.starter = starter
        self.exercise = None  # set by Exercise

    # -- identity
    @property
    def id(self):
        ex = self.exercise.id if self.exercise is not None else "?"
        return f"{ex}{self.name}" if len(self.name) <= 1 else f"{ex} {self.name}"

    @property
    def title(self):
        return f"exercise {self.id}"

    def __repr__(self):
        return f"<check for exercise {self.id}: {self.prompt}>"

    # -- the three verbs
    def check(self, answer=None, *, quiet=False):
        """Check ``answer``; display and return a :class:`Verdict`. Never raises."""
        try:
            with np.errstate(all="ignore"), warnings.catch_warnings():
                warnings.simplefilter("ignore")
                message = self._check(answer)
            verdict = Verdict(PASSED, message or "Well done.", self.title)
        except Unattempted as u:
            verdict = Verdict(UNATTEMPTED, str(u) or (
                "You have not answered yet: replace the starter value in the cell above (it is "
                "still None). Use .hint() if you are stuck."), self.title)
        except Wrong as w:
            verdict = Verdict(FAILED, str(w), self.title)
        except Exception as exc:  # a bug in a checker must not break the notebook
            verdict = Verdict(FAILED, "The checker could not make sense of your answer "
                              f"({type(exc).__name__}: {str(exc)[:150]}). Check its type against "
                              "the prompt, or ask .hint().", self.title)
        self._record(verdict.status)
        if not quiet:
            try:
                verdict.show()
            except Exception:
                pass
        return verdict

    def hint(self, n=1):
        """Show hint number ``n`` (1 = gentlest); returns its text."""
        if not self.hints:
            text = "There is no hint for this part; see the section of the book the prompt cites."
        else:
            try:
                k = int(n)
            except Exception:
                k = 1
            k = min(max(k, 1), len(self.hints))
            more = f" (hint {k} of {len(self.hints)}"
            more += f"; ask .hint({k + 1}) for more)" if k < len(self.hints) else ")"
            text = self.hints[k - 1] + more
        show("hint", self.title, text)
        return text

    def solution(self):
        """Show the worked solution's key result and where the full notebook is; returns the text."""
        ex = self.exercise
        path = f"solutions/ex{ex.id.replace('.', '_')}.ipynb" if ex is not None else "solutions/"
        text = (self.solution_text or "See the worked solution.") + f"\nFull derivation: {path}"
        show("solution", self.title, text)
        return text

    # -- internals
    def _record(self, status):
        if self.exercise is not None:
            _STATE[(self.exercise.id, self.name)] = status

    def _check(self, answer):  # pragma: no cover - abstract
        raise NotImplementedError


class FunctionPart(Part):
    """The answer is a function (or a sympy expression, or a constant) compared with a reference.

    ``ref(*args)`` gives the expected array; ``inputs()`` yields argument tuples (random and edge
    cases). A sympy answer is evaluated with its symbols matched by name to ``arg_names``; the
    ``arg_names`` also label arguments in messages. ``mistakes`` is a list of
    ``(wrong_function, message)`` pairs for common slips that deserve a specific message.
    ``shape`` is the expected output shape. ``postprocess(out, args)`` may normalise a student's
    output (for example a 3x3 matrix to (x, y, theta)).
    """

    kind = "function"

    def __init__(self, name, prompt, ref, inputs, *, arg_names, shape, rtol=1e-6, atol=1e-8,
                 mistakes=(), postprocess=None, sympy_names=None, sympy_args=None, sympy_ok=None,
                 what="your function", **kw):
        super().__init__(name, prompt, **kw)
        self.ref = ref
        self.inputs = inputs
        self.arg_names = tuple(arg_names)
        # A sympy answer is an expression in the symbols ``sympy_names``; ``sympy_args(*args)``
        # maps the function arguments to their values, ``sympy_ok(*args)`` skips inputs where a
        # closed form legitimately reads 0/0 (e.g. theta = 0).
        self.sympy_names = tuple(sympy_names) if sympy_names is not None else self.arg_names
        self.sympy_args = sympy_args
        self.sympy_ok = sympy_ok
        self.shape = tuple(shape)
        self.rtol, self.atol = rtol, atol
        self.mistakes = list(mistakes)
        self.postprocess = postprocess
        self.what = what

    def _as_function(self, answer):
        if is_starter(answer):
            raise Unattempted()
        if is_sympy(answer) and hasattr(answer, "free_symbols"):
            f = sympy_callable(answer, self.sympy_names, "your expression")
            flat = self.sympy_args or (lambda *a: a)
            return _SympyFunction(f, flat), "your expression"
        if callable(answer) and not isinstance(answer, type):
            return answer, self.what
        if isinstance(answer, (list, tuple)) and answer and all(is_starter(a) for a in answer):
            raise Unattempted()
        if not self.arg_names:
            return (lambda *args: answer), "your answer"
        raise Wrong(f"your answer is {describe(answer)}; {self.prompt_type} was expected.")

    @property
    def prompt_type(self):
        return (f"a function of ({', '.join(self.arg_names)})" if self.arg_names
                else "a number or array")

    def _evaluate(self, f, what, args):
        out = call_student(f, args, what)
        if is_starter(out):
            raise Unattempted("Your function still returns None: fill in its body.")
        if self.postprocess is not None:
            out = self.postprocess(out, args)
        got = to_array(out, f"the value {what} returned for {fmt_args(args)}")
        return match_shape(got, self.shape, f"the value {what} returned")

    def _check(self, answer):
        f, what = self._as_function(answer)
        for args in self.inputs():
            if isinstance(f, _SympyFunction) and self.sympy_ok is not None and not self.sympy_ok(*args):
                continue
            expected = np.asarray(self.ref(*args), dtype=float)
            # hand the student copies, so a function that edits its input in place cannot
            # change the checker's edge cases
            got = self._evaluate(f, what, tuple(np.array(a) if isinstance(a, np.ndarray) else a
                                                for a in args))
            if not close(got, expected, self.rtol, self.atol):
                for wrong_f, msg in self.mistakes:
                    try:
                        w = np.asarray(wrong_f(*args), dtype=float)
                    except Exception:
                        continue
                    if w.shape == got.shape and close(got, w, self.rtol, self.atol) and not close(
                            w, expected, self.rtol, self.atol):
                        raise Wrong(msg)
                where = self._where(got, expected)
                raise Wrong(f"{what.capitalize()} gives a different value for {self._label(args)}"
                            f"{where}. Try the edge cases by hand, or ask .hint().")
        return self.success

    success = "Correct: your answer matches the reference on random and edge-case inputs."

    def _label(self, args):
        if not self.arg_names:
            return "this part"
        return ", ".join(f"{n}={fmt_args((a,))[1:-1]}" for n, a in zip(self.arg_names, args))

    def _where(self, got, expected):
        if got.ndim == 0 or got.size == 1:
            return ""
        with np.errstate(all="ignore"):
            bad = np.abs(got - expected) > self.atol + self.rtol * np.abs(expected)
        idx = [tuple(int(i) for i in ix) for ix in np.argwhere(bad)]
        if not idx:
            return ""
        shown = ", ".join(str(i if len(i) > 1 else i[0]) for i in idx[:4])
        return f" (entries {shown} differ)"


class _SympyFunction:
    """A lambdified sympy answer called with the part's arguments."""

    def __init__(self, f, flat):
        self.f, self.flat = f, flat

    def __call__(self, *args):
        out = self.f(*self.flat(*args))
        if isinstance(out, (list, tuple)):
            out = np.array(np.broadcast_arrays(*[np.asarray(o, dtype=float) for o in out])
                           if out and not isinstance(out[0], (list, tuple)) else
                           [np.broadcast_arrays(*[np.asarray(o, dtype=float) for o in row])
                            for row in out], dtype=float)
        return out


class TuplePart(Part):
    """An answer made of several named components, each checked by a :class:`FunctionPart`."""

    kind = "tuple"

    def __init__(self, name, prompt, components, **kw):
        super().__init__(name, prompt, **kw)
        self.components = list(components)  # [(label, FunctionPart)]

    def _check(self, answer):
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
        notes = []
        for (label, part), value in zip(self.components, values):
            if is_starter(value):
                raise Wrong(f"{label} is still None; the other components were given.")
            try:
                part._check(value)
            except Unattempted:
                raise Wrong(f"{label}: the function still returns None.") from None
            except Wrong as w:
                raise Wrong(f"{label}: {w}") from None
            notes.append(label)
        return "Correct: " + ", ".join(notes) + " all match the reference."


class ChoicePart(Part):
    """A multiple-choice question. The answer is an option letter (or the option's text)."""

    kind = "choice"

    def __init__(self, name, prompt, options, correct, feedback=None, **kw):
        super().__init__(name, prompt, **kw)
        self.options = dict(options)  # letter -> text
        self.correct = set(correct) if not isinstance(correct, str) else {correct}
        self.feedback = dict(feedback or {})
        if self.reference is None:
            self.reference = sorted(self.correct)[0]
        if not self.wrong:
            self.wrong = [k for k in self.options if k not in self.correct][:1]

    def _normalise(self, answer):
        if is_starter(answer):
            raise Unattempted()
        if isinstance(answer, (int, np.integer)) and not isinstance(answer, bool):
            letters = list(self.options)
            if 0 <= int(answer) < len(letters):
                return letters[int(answer)]
        if isinstance(answer, str):
            a = answer.strip().strip("().").lower()
            if a == "":
                raise Unattempted()
            for k, text in self.options.items():
                if a == k.lower() or a == text.strip().lower():
                    return k
        raise Wrong(f"your answer is {describe(answer)}; give one of the letters "
                    f"{', '.join(repr(k) for k in self.options)}.")

    def _check(self, answer):
        k = self._normalise(answer)
        if k in self.correct:
            return self.feedback.get(k, "Correct.")
        raise Wrong(self.feedback.get(k, "Not this one: reread the section the prompt cites."))

    def widget(self):
        """Radio buttons, a Check button and feedback (ipywidgets)."""
        from ._widgets import choice_widget
        return choice_widget(self)


class CustomPart(Part):
    """A part with its own check function ``judge(answer) -> message`` (raising Wrong/Unattempted)."""

    def __init__(self, name, prompt, judge, **kw):
        super().__init__(name, prompt, **kw)
        self.judge = judge

    def _check(self, answer):
        if is_starter(answer):
            raise Unattempted()
        return self.judge(answer)


# ------------------------------------------------------------------------------ exercises
class Exercise:
    """An exercise of the book: its parts are attributes (``ex1_4.a``, ``ex1_4.d``, ...)."""

    def __init__(self, id, title, parts):
        self.id = id
        self.title = title
        self.parts = {}
        for p in parts:
            p.exercise = self
            self.parts[p.name] = p
            setattr(self, p.name, p)
        REGISTRY[id] = self

    def __repr__(self):
        names = ", ".join(self.parts)
        return f"<exercise {self.id}: {self.title}; parts {names}>"

    def status(self):
        """passed if every part passed, failed if any part's latest check failed, else unattempted."""
        states = [_STATE.get((self.id, name)) for name in self.parts]
        if any(s == FAILED for s in states):
            return FAILED
        if states and all(s == PASSED for s in states):
            return PASSED
        return UNATTEMPTED

    def check(self, answers=None):
        """Check several parts at once from a dict {part name: answer}; returns the verdicts."""
        if not isinstance(answers, dict):
            show(FAILED, f"exercise {self.id}", "Pass a dict {part name: answer}, or check one part "
                 f"at a time, e.g. ex{self.id.replace('.', '_')}.{next(iter(self.parts))}.check(...).")
            return {}
        return {name: self.parts[name].check(a) for name, a in answers.items() if name in self.parts}


def progress():
    """{exercise id: "passed" | "failed" | "unattempted"} for all 13 exercises, in this kernel."""
    return {ex_id: (REGISTRY[ex_id].status() if ex_id in REGISTRY else UNATTEMPTED)
            for ex_id in EXERCISE_IDS}


def part_progress():
    """{exercise id: {part name: latest status}} (parts never checked are "unattempted")."""
    return {ex_id: {name: _STATE.get((ex_id, name), UNATTEMPTED) for name in REGISTRY[ex_id].parts}
            for ex_id in EXERCISE_IDS if ex_id in REGISTRY}


def reset_progress():
    """Forget every check made in this kernel (used by the tests)."""
    _STATE.clear()


# ------------------------------------------------------------------------------ input helpers
def rng_inputs(seed, n, make, edges=()):
    """A function yielding the edge cases first, then ``n`` seeded random argument tuples."""
    def inputs():
        for e in edges:
            yield tuple(e)
        rng = np.random.default_rng(seed)
        for _ in range(n):
            yield tuple(make(rng))
    return inputs


def isfinite_number(x):
    try:
        return math.isfinite(float(x))
    except Exception:
        return False

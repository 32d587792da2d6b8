"""A gait answer as plain data, for the gait exercises (4.2 and 5.1): one probe, one judge helper.

The probe samples the student's gait (a Gait, a callable t -> r(t), or an array of shapes (K, J);
:func:`gm_core.checks.answers.sample_gait`) at ``N_SAMPLES + 1`` equal time steps over one period -- what the judge measures -- and then at
``N_EXTRA`` further times inside the period. Those further times are drawn from the probe salt
(:func:`gm_core.checks.parts.probe_rng`): fixed in the student's kernel, chosen afresh by the grader for every
graded run. The judge asks each of them to lie on the loop between its two neighbouring samples,
so a "gait" that only knows the checker's sample times (a table of them) is not taken for a loop.
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt
from typing_extensions import override

from gm_core.checks.answers import describe, fmt_value, sample_gait
from gm_core.checks.parts import probe_rng
from gm_core.checks.sandbox import Wrong
from gm_core.validation import FloatArray

N_SAMPLES = 256
N_EXTRA = 16
_SEED = 42


class LazyGait:
    """A gait t -> r(t) that ``make()`` builds the first time it is called (so a key module that
    lists reference and wrong gaits imports nothing heavy), shown as ``label``."""

    def __init__(self, make: Callable[[], Callable[[npt.ArrayLike], FloatArray]], label: str) -> None:
        self.make, self.label = make, label
        self._gait: Callable[[npt.ArrayLike], FloatArray] | None = None

    def __call__(self, t: npt.ArrayLike) -> FloatArray:
        if self._gait is None:
            self._gait = self.make()
        return self._gait(t)

    @override
    def __repr__(self) -> str:
        return self.label


def extra_fractions() -> np.ndarray:
    """The further sample times, as fractions of the period (salted when grading)."""
    return np.sort(probe_rng(_SEED).uniform(0.0, 1.0, N_EXTRA))


def sample(answer: Any, joints: int, example: str) -> np.ndarray:
    """Student side: the gait at the N_SAMPLES + 1 grid times, then at the N_EXTRA further times."""
    return sample_gait(answer, joints, example, N_SAMPLES, extra_fractions())


def grid(r: object, joints: int, about: str = "") -> np.ndarray:
    """Judge side: check the shape of the samples and that the further ones lie on the loop;
    return the N_SAMPLES + 1 grid samples. Raises Wrong with a readable message."""
    n = N_SAMPLES + 1
    if not isinstance(r, np.ndarray) or r.ndim != 2 or r.shape[0] != n + N_EXTRA:
        shape = r.shape if isinstance(r, np.ndarray) else describe(r)
        raise Wrong(f"your gait returned shapes of shape {shape} for {n + N_EXTRA} times; "
                    f"({n + N_EXTRA}, {joints}) was expected ({joints} joint angles at each time).")
    if r.shape[1] != joints:
        raise Wrong(f"your gait has {r.shape[1]} joint angles per time; {joints} were expected{about}.")
    if not np.all(np.isfinite(r)):
        raise Wrong("your gait returned NaN or infinite joint angles at some times.")
    samples, extra = r[:n], r[n:]
    scale = max(1.0, float(np.max(np.abs(samples))))
    for u, q in zip(extra_fractions(), extra):
        k = min(int(u * N_SAMPLES), N_SAMPLES - 1)
        a, b = samples[k], samples[k + 1]
        ab = b - a
        s = float(np.clip(np.dot(q - a, ab) / max(float(np.dot(ab, ab)), 1e-300), 0.0, 1.0))
        off = float(np.linalg.norm(q - (a + s * ab)))
        if off > float(np.linalg.norm(ab)) + 1e-6 * scale:
            raise Wrong(f"your gait gives {fmt_value(np.round(q, 4))} at {u:.4f} of its period, far "
                        f"from its shapes just before and after ({fmt_value(np.round(a, 4))}, "
                        f"{fmt_value(np.round(b, 4))}): a gait must be one continuous loop of shapes.")
    return samples

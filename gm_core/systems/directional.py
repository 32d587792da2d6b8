"""The four functions of the box "Directional linearity" ((3.i)-(3.iv)) as toy locomotors (numpy only).

Each example is a map b from a shape velocity a = r_dot (..., 2) to a position velocity x_dot
(...,), so it drives a one-dimensional position x along a shape path: x_dot = b(r_dot).

* (a) directionally linear, not linear: b = (a1^3 + a2^3) / |a|^2 (linear along each line
  through 0, (3.ii)-(3.iii), but b(a + a') != b(a) + b(a'));
* (b) linear: b = a1 - a2 / 2, (3.iv);
* (c) not directionally linear: b = (a1^3 + a2^3) / |a| grows like |a|^2 along each ray,
  violating (3.ii);
* (d) not directionally linear: b = (|a1|^3 + a2^3) / |a|^2 is linear along each ray but not
  across 0, violating (3.iii).

Replaying a shape path at another pace k (:func:`replay`) leaves x's path unchanged exactly when
b(k a) = k b(a) for k > 0 (3.ii): (a), (b), (d). Running it backwards retraces x's path exactly
when b(-a) = -b(a) (3.iii): (a), (b), (c); only (a) and (b) do both.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from gm_core.validation import FloatArray, positive_number, real_number

__all__ = ["RATE_MAPS", "rate_map", "replay", "rate_map_properties"]


def _norm2(a):
    return np.sum(a * a, axis=-1)


def _safe(num, den):
    out = np.zeros(np.broadcast_shapes(np.shape(num), np.shape(den)))
    np.divide(num, den, out=out, where=den > 0)
    return out


RATE_MAPS = {
    "(a) directionally linear": lambda a: _safe(a[..., 0] ** 3 + a[..., 1] ** 3, _norm2(a)),
    "(b) linear": lambda a: a[..., 0] - 0.5 * a[..., 1],
    "(c) grows like |ṙ|²": lambda a: _safe(a[..., 0] ** 3 + a[..., 1] ** 3, np.sqrt(_norm2(a))),
    "(d) one-sided": lambda a: _safe(np.abs(a[..., 0]) ** 3 + a[..., 1] ** 3, _norm2(a)),
}


def rate_map(name: str) -> Callable[[FloatArray], FloatArray]:
    """The map b (callable on (..., 2) arrays) of example ``name``, a key of :data:`RATE_MAPS`."""
    if name not in RATE_MAPS:
        raise ValueError(f"name must be one of {list(RATE_MAPS)}; got {name!r}")
    return RATE_MAPS[name]


#: Size of the demo shape path (its shape speed |dr/ds| is about 1 at pace 1).
PATH_SCALE = 0.25


def _unit_path(s):
    """The demo shape path r(s) = c (cos 3 pi s / 2, 0.6 sin 3 pi s / 2), c = PATH_SCALE, s in [0, 1]; (r, dr/ds)."""
    w = 1.5 * np.pi * s
    r = PATH_SCALE * np.stack([np.cos(w), 0.6 * np.sin(w)], -1)
    rd = PATH_SCALE * 1.5 * np.pi * np.stack([-np.sin(w), 0.6 * np.cos(w)], -1)
    return r, rd


def replay(name: str, pace: float = 1.0, reverse: bool = False, x0: float = 0.0,
           n: int = 2000) -> tuple[FloatArray, FloatArray]:
    """(s, x): position x of the toy locomotor ``name`` along the demo shape path at ``pace``.

    The shape path r(s), s in [0, 1], is run in time 1 / pace (so r_dot = pace * dr/ds), forwards
    or, with ``reverse``, from its end back to its start. Returns the fraction of the path
    covered s (n + 1,) (for ``reverse``, the path parameter, running from 1 down to 0) and x
    there, by the midpoint rule on x_dot = b(r_dot) (exact to O(1/n^2)).
    """
    b = rate_map(name)
    k = positive_number(pace, "pace")
    x0 = real_number(x0, "x0", what=" (the starting position)")
    s = np.linspace(0.0, 1.0, int(n) + 1)
    mid = 0.5 * (s[1:] + s[:-1])
    if reverse:
        mid = 1.0 - mid
        s = 1.0 - s
    _, rd = _unit_path(mid)
    sign = -1.0 if reverse else 1.0
    # dt = ds / k and r_dot = sign * k * dr/ds
    dx = b(sign * k * rd) / k / n
    return s, x0 + np.concatenate([[0.0], np.cumsum(dx)])


def rate_map_properties(name: str, rng: np.random.Generator | None = None,
                        samples: int = 200) -> dict[str, float]:
    """Largest violations (dict) over random shape velocities of (3.ii) positive scaling,
    (3.iii) odd symmetry and additivity; 0 (to rounding) where the property holds."""
    b = rate_map(name)
    rng = np.random.default_rng(0) if rng is None else rng
    a, a2 = rng.normal(size=(2, samples, 2))
    k = rng.uniform(0.1, 5.0, samples)
    return {"scaling (3.ii)": float(np.max(np.abs(b(k[:, None] * a) - k * b(a)))),
            "odd (3.iii)": float(np.max(np.abs(b(-a) + b(a)))),
            "additive (3.iv)": float(np.max(np.abs(b(a + a2) - b(a) - b(a2))))}

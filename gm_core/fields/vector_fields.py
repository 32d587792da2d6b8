"""Vector fields, integral curves, invariant fields and the example fields of figs. 1.13-1.14
(numpy + scipy only). Re-exported by :mod:`gm_core.fields`, whose docstring is the map."""
from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp
from typing_extensions import override

from gm_core.groups import LieGroup, check_group, matvec
from gm_core.validation import FloatArray, as_array, check_int

#: Largest configuration-space dimension of a :class:`VectorField`.
MAX_FIELD_DIM = 10_000
#: Keyword arguments :func:`integral_curve` passes on to scipy's solve_ivp.
SOLVE_IVP_OPTIONS = frozenset({"method", "rtol", "atol", "dense_output", "events", "vectorized",
                               "first_step", "max_step", "min_step", "jac", "jac_sparsity",
                               "lband", "uband"})

__all__ = [
    "VectorField", "IntegralCurve", "integral_curve", "left_invariant_field", "right_invariant_field",
    "FIELDS", "DEFAULT_RTOL", "DEFAULT_ATOL", "check_flow_side", "check_solve_ivp_kw", "check_time",
]

#: solve_ivp defaults used by :func:`integral_curve` (override with rtol=..., atol=...).
DEFAULT_RTOL = 1e-10
DEFAULT_ATOL = 1e-12
DEFAULT_METHOD = "DOP853"
#: Default cap on field evaluations in :func:`integral_curve` (DOP853 uses 12 per step).
MAX_EVALUATIONS = 50_000

#: A field as a function ``(q, t) -> q_dot``: ``q`` of shape (..., dim) (or (dim,) for a field that
#: is not vectorized) and a float time ``t``; the result has the shape of ``q``.
FieldFunction = Callable[[FloatArray, float], ArrayLike]


def check_flow_side(side: str) -> str:
    if not isinstance(side, str) or side not in ("left", "right"):  # a longer message than check_option's
        raise ValueError(
            f"side must be 'left' (left-invariant field, body velocity, (1.46)) or 'right' "
            f"(right-invariant field, spatial velocity, (1.47)); got {side!r}"
        )
    return side


def check_solve_ivp_kw(kw: Mapping[str, object], where: str) -> None:
    unknown = sorted(set(kw) - SOLVE_IVP_OPTIONS)
    if unknown:
        raise TypeError(f"{where} got unknown keyword argument(s) {', '.join(unknown)}; "
                        f"solve_ivp options are {', '.join(sorted(SOLVE_IVP_OPTIONS))}")


def check_time(t: ArrayLike, name: str = "t") -> FloatArray:
    t = as_array(t, name, what=" (times)")
    return t


# ---------------------------------------------------------------------------------- vector fields
class VectorField:
    """A (possibly time-varying) vector field X: (q, t) -> q_dot on R^dim, (1.13)-(1.15).

    Parameters
    ----------
    func : callable
        ``func(q, t)`` with ``q`` of shape ``(..., dim)`` and a float ``t``, returning an array of
        the same shape. With ``vectorized=False`` it is called once per point with ``q`` of shape
        ``(dim,)`` and the results are stacked.
    dim : int
        Dimension of the configuration space.
    name : str
        A label for plots and error messages.
    group : LieGroup, optional
        The group the field lives on (set by the invariant-field constructors); informational.

    Calling ``X(q, t=0.0)`` validates ``q`` (shape ``(..., dim)``, finite) and returns ``q_dot``.
    """

    def __init__(self, func: FieldFunction, dim: int, *, name: str = "X", vectorized: bool = True,
                 group: LieGroup | None = None) -> None:
        if not callable(func):
            raise TypeError(f"func must be a callable (q, t) -> q_dot; got {type(func).__name__}")
        if isinstance(dim, bool) or not isinstance(dim, (int, np.integer)):
            raise TypeError(f"dim must be a positive integer; got {type(dim).__name__} {dim!r:.40}")
        if not 1 <= dim <= MAX_FIELD_DIM:
            raise ValueError(f"dim must be a positive integer (at most {MAX_FIELD_DIM}); got {dim!r}")
        self.func = func
        self.dim = int(dim)
        self.name = str(name)
        self.vectorized = bool(vectorized)
        self.group = group

    @override
    def __repr__(self) -> str:
        return f"VectorField({self.name!r}, dim={self.dim})"

    def _eval(self, q, t):
        what = f" (the value of field {self.name!r})"
        if self.vectorized:
            out = as_array(self.func(q, t), "X(q, t)", what=what, allow_nan=True)
            if out.shape != q.shape and out.ndim and out.shape[-1] == self.dim:
                try:  # e.g. a constant field returning one (dim,) vector for every q
                    out = np.broadcast_to(out, q.shape)
                except ValueError:
                    pass
        else:
            flat = q.reshape(-1, self.dim)
            vals = [as_array(self.func(p, t), "X(q, t)", what=what, allow_nan=True) for p in flat]
            if any(v.shape != (self.dim,) for v in vals):
                raise ValueError(f"field {self.name!r} must return a vector of shape ({self.dim},) per point")
            out = np.stack(vals).reshape(q.shape) if vals else np.empty(q.shape)
        if out.shape != q.shape:
            raise ValueError(
                f"field {self.name!r} returned shape {out.shape} for q of shape {q.shape}; "
                f"it must return one velocity per configuration"
            )
        return out

    def __call__(self, q: ArrayLike, t: float = 0.0) -> FloatArray:
        q = as_array(q, "q", (self.dim,), what=f", a configuration for field {self.name!r}")
        t = as_array(t, "t", what=" (a time)")
        if t.ndim != 0:
            raise ValueError(f"t must be a single time; got shape {t.shape}")
        return self._eval(q, float(t))

    def on_grid(self, *axes_values: ArrayLike, t: float = 0.0, axes: Iterable[int] | None = None,
                at: ArrayLike | None = None) -> tuple[FloatArray, ...]:
        """Evaluate the field on a grid for ``quiver``: returns ``(*meshes, *components)``.

        ``axes_values`` are 1-D arrays of coordinate values, one per plotted coordinate; ``axes``
        says which coordinates they are (default ``0, 1, ...``); the other coordinates are held at
        ``at`` (a full configuration, default zeros; e.g. theta for a planar slice of SE(2)). For a
        2-D slice this returns ``X, Y, U, V`` with ``X, Y = meshgrid(xs, ys)``.
        """
        if not axes_values:
            raise ValueError("on_grid needs at least one 1-D array of coordinate values")
        vals = [as_array(v, f"axes_values[{i}]", what=" (1-D coordinate values)")
                for i, v in enumerate(axes_values)]
        for i, v in enumerate(vals):
            if v.ndim != 1:
                raise ValueError(f"axes_values[{i}] must be a 1-D array; got shape {v.shape}")
        if axes is None:
            axes = tuple(range(len(vals)))
        else:
            if isinstance(axes, (str, bytes)) or not hasattr(axes, "__iter__"):
                raise TypeError(f"axes must be a sequence of coordinate indices; got {axes!r:.40}")
            axes = tuple(check_int(a, "axes[i]", minimum=0, maximum=self.dim - 1) for a in axes)
        if len(axes) != len(vals) or len(set(axes)) != len(axes) or not all(0 <= a < self.dim for a in axes):
            raise ValueError(
                f"axes must name {len(vals)} distinct coordinates in 0..{self.dim - 1}; got {axes}"
            )
        base = np.zeros(self.dim) if at is None else as_array(at, "at", (self.dim,))
        if base.ndim != 1:
            raise ValueError(f"at must be one configuration of shape ({self.dim},); got shape {base.shape}")
        meshes = np.meshgrid(*vals, indexing="xy")
        q = np.broadcast_to(base, meshes[0].shape + (self.dim,)).copy()
        for a, m in zip(axes, meshes):
            q[..., a] = m
        qdot = self(q, t)
        return (*meshes, *(qdot[..., a] for a in axes))


def _as_field(field, dim=None):
    if isinstance(field, VectorField):
        return field
    if callable(field):
        if dim is None:
            raise ValueError("a plain callable field needs the dimension; wrap it in VectorField(func, dim)")
        return VectorField(field, dim, name=getattr(field, "__name__", "X"))
    raise TypeError(f"field must be a VectorField or a callable (q, t) -> q_dot; got {type(field).__name__}")


@dataclass(frozen=True)
class IntegralCurve:
    """Samples of an integral curve gamma of a field, (1.16)-(1.18).

    ``t`` (m,) are the times, ``q`` (m, ..., dim) the configurations gamma(t); ``solution`` is
    scipy's OdeResult (``.sol`` is a dense interpolant when ``dense_output=True``).
    Unpacks as ``t, q = integral_curve(...)``.
    """

    t: np.ndarray
    q: np.ndarray
    solution: object

    def __iter__(self) -> Iterator[np.ndarray]:
        yield self.t
        yield self.q


class _TooManyEvaluations(Exception):
    pass


def integral_curve(field: VectorField | FieldFunction, q0: ArrayLike, t_span: ArrayLike,
                   t_eval: ArrayLike | None = None, *, max_evaluations: int = MAX_EVALUATIONS,
                   **solve_ivp_kw: Any) -> IntegralCurve:
    """Integral curve of ``field`` from ``q0``: solves q_dot = X(q, t), q(t_span[0]) = q0, (1.15).

    ``field`` is a :class:`VectorField` (or a callable ``(q, t)`` if ``q0`` fixes the dimension).
    ``q0`` may be a batch ``(..., dim)`` of starting points; they are integrated together as one
    system and ``q`` comes back with shape ``(len(t), ..., dim)``. ``t_span = (t0, t1)`` (t1 < t0
    integrates backwards); ``t_eval`` selects output times inside the span. Keyword arguments go
    to :func:`scipy.integrate.solve_ivp`; defaults are ``method="DOP853"``, ``rtol=1e-10``,
    ``atol=1e-12``. Raises ``RuntimeError`` if the solver fails, and ``ValueError`` naming
    ``t_span`` if it needs more than ``max_evaluations`` evaluations of the field (a span far
    longer than the field's time scale would otherwise run for hours).
    """
    q0_arr = as_array(q0, "q0", what=" (a starting configuration)")
    if q0_arr.ndim == 0:
        q0_arr = q0_arr.reshape(1)
    X = _as_field(field, dim=q0_arr.shape[-1])
    q0_arr = as_array(q0_arr, "q0", (X.dim,), what=f", a starting configuration for field {X.name!r}")
    span = as_array(t_span, "t_span", (2,), what=" (start and end times)")
    if span.ndim != 1:
        raise ValueError(f"t_span must be a pair (t0, t1); got shape {span.shape}")
    if span[0] == span[1]:
        raise ValueError(f"t_span must have t0 != t1; got {tuple(span)}")
    if t_eval is not None:
        t_eval = as_array(t_eval, "t_eval", what=" (output times)")
        t_eval = np.atleast_1d(t_eval)
        if t_eval.ndim != 1 or t_eval.size == 0:
            raise ValueError(f"t_eval must be a non-empty 1-D array of times; got shape {t_eval.shape}")
        lo, hi = min(span), max(span)
        tol = 1e-12 * max(1.0, abs(lo), abs(hi))
        if np.any(t_eval < lo - tol) or np.any(t_eval > hi + tol):
            raise ValueError(f"t_eval must lie inside t_span {tuple(span)}")
        t_eval = np.clip(t_eval, lo, hi)
    batch = q0_arr.shape[:-1]
    shape = q0_arr.shape

    calls = [0]

    def rhs(t, y):
        calls[0] += 1
        if calls[0] > max_evaluations:
            raise _TooManyEvaluations
        return X._eval(y.reshape(shape), t).ravel()

    check_solve_ivp_kw(solve_ivp_kw, "integral_curve")
    max_evaluations = check_int(max_evaluations, "max_evaluations", minimum=1, maximum=10**9)
    kw = {"method": DEFAULT_METHOD, "rtol": DEFAULT_RTOL, "atol": DEFAULT_ATOL}
    kw.update(solve_ivp_kw)
    try:
        with np.errstate(over="ignore", invalid="ignore"):   # overflow shows as failure below
            sol = solve_ivp(rhs, (float(span[0]), float(span[1])), q0_arr.ravel(), t_eval=t_eval, **kw)
    except _TooManyEvaluations:
        raise ValueError(
            f"t_span ({span[0]:g}, {span[1]:g}) is too long for field {X.name!r} at these tolerances: the solver "
            f"needed more than max_evaluations={max_evaluations} evaluations; shorten t_span or "
            f"raise max_evaluations"
        ) from None
    if not sol.success:
        raise RuntimeError(f"integral_curve: solve_ivp failed for field {X.name!r}: {sol.message}")
    if not np.all(np.isfinite(sol.y)):
        raise RuntimeError(f"integral_curve: the curve of field {X.name!r} from q0 overflowed (blew up)")
    q = sol.y.T.reshape((len(sol.t),) + batch + (X.dim,))
    return IntegralCurve(t=sol.t, q=q, solution=sol)


# ---------------------------------------------------------------------------------- invariant fields
def _field_value(v, g, name):
    if v.shape != np.shape(g):
        raise ValueError(f"{name} (shape {v.shape[:-1] + v.shape[-1:]}) gives velocities of shape {v.shape} "
                         f"at configurations of shape {np.shape(g)}: its batch must broadcast to g's")
    return v


def left_invariant_field(group: LieGroup, xi: ArrayLike) -> VectorField:
    """Left-invariant field X_L(g) = T_e L_g xi of the body velocity ``xi``, (1.46).

    ``xi`` is a Lie-algebra vector ``(dim,)`` (or a batch broadcasting against g). Its flows have
    constant body velocity xi; from g0 the flow is g0 o exp(t xi).
    """
    group = check_group(group)
    xi = as_array(xi, "xi", (group.dim,), what=f", a body velocity in the Lie algebra of {group.name}")
    e = group.identity()

    def X_L(g, t=0.0):
        return _field_value(matvec(group.left_lifted_action(g, e), xi), g, "xi")

    return VectorField(X_L, group.dim, name=f"X_L[{group.name}]", group=group)


def right_invariant_field(group: LieGroup, xi_s: ArrayLike) -> VectorField:
    """Right-invariant field X_R(g) = T_e R_g xi_s of the spatial velocity ``xi_s``, (1.47).

    Its flows have constant spatial velocity xi_s; from g0 the flow is exp(t xi_s) o g0.
    """
    group = check_group(group)
    xi_s = as_array(xi_s, "xi_s", (group.dim,),
                    what=f", a spatial velocity in the Lie algebra of {group.name}")
    e = group.identity()

    def X_R(g, t=0.0):
        return _field_value(matvec(group.right_lifted_action(g, e), xi_s), g, "xi_s")

    return VectorField(X_R, group.dim, name=f"X_R[{group.name}]", group=group)



# ---------------------------------------------------------------------------------- example fields
def _spiral(q, t=0.0):
    x, y = q[..., 0], q[..., 1]
    return np.stack([-0.25 * x - y, x - 0.25 * y], -1)


def _saddle(q, t=0.0):
    return np.stack([q[..., 0], -q[..., 1]], -1)


def _rotation(q, t=0.0):
    return np.stack([-q[..., 1], q[..., 0]], -1)


def _van_der_pol(q, t=0.0):
    x, y = q[..., 0], q[..., 1]
    return np.stack([y, (1.0 - x * x) * y - x], -1)


#: The example vector fields of figs. 1.13-1.14, as functions ``(q (..., 2), t) -> q_dot``.
FIELDS = {"spiral sink": _spiral, "saddle": _saddle, "closed loops": _rotation,
          "limit cycle (van der Pol)": _van_der_pol}

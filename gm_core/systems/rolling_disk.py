"""Nonholonomy made visible: a rolling disk parallel-parks, a radially constrained point cannot
(book, box "Nonholonomic constraints", (3.v)-(3.ix)); numpy only.

The disk (a coin rolling upright, seen from above) has pose g in SE(2) and may only roll along
its heading and turn: its body velocity is xi = (v, 0, w), the no-slide constraint
c_body = xi^y = 0 (3.vi), or c_world = y' cos(theta) - x' sin(theta) = 0 (3.v). Every allowed
motion is a sequence of *moves* (v, w, duration) with constant body velocity, so each move is
exactly g <- g exp(T (v, 0, w)) (section 1.6). The cycle drive d, turn phi, drive -d, turn -phi
nevertheless ends displaced sideways, by about d phi [X_drive, X_turn] for small loops (the
group commutator; [., .] is the se(2) bracket): the constraint restricts velocities, not the
places the disk can reach.

The constraint (3.viii) on a point q = (x, y) of the plane, x x' + y y' = 0, allows only the
directions of X1 = (-y, x) (and of any multiple f(q) X1, e.g. X2 = X1 / |q|). Flows of both are
rotations about the origin, which commute: every loop of allowed moves returns exactly to its
start, and the point never leaves its circle |q| = R, the level set (3.ix).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from gm_core.groups import SE2
from gm_core.validation import FloatArray, as_array, positive_number, real_number

__all__ = ["DISK_DRIVE", "DISK_TURN", "disk_body_velocity", "disk_constraint_world", "disk_moves_path",
           "parallel_park_moves", "parallel_park_displacement", "bracket_estimate", "radial_point_path",
           "radial_loop_moves"]

#: Unit moves of the disk as body velocities: roll forward, turn in place.
DISK_DRIVE = np.array([1.0, 0.0, 0.0])
DISK_TURN = np.array([0.0, 0.0, 1.0])


def disk_body_velocity(v: ArrayLike, w: ArrayLike) -> FloatArray:
    """Body velocity (..., 3) of the disk rolling at speed v and turning at rate w: (v, 0, w), (3.vi)."""
    v = as_array(v, "v", what=" (the rolling speed)")
    w = as_array(w, "w", what=" (the turning rate)")
    v, w = np.broadcast_arrays(v, w)
    return np.stack([v, np.zeros_like(v), w], -1)


def disk_constraint_world(g: ArrayLike, g_dot: ArrayLike) -> FloatArray:
    """c_world = y' cos(theta) - x' sin(theta) (...,) of (3.v): zero for every allowed disk motion."""
    g = as_array(g, "g", (3,), what=" (a pose (x, y, theta))")
    g_dot = as_array(g_dot, "g_dot", (3,), what=" (a world velocity (x', y', theta'))")
    return g_dot[..., 1] * np.cos(g[..., 2]) - g_dot[..., 0] * np.sin(g[..., 2])


def _moves(moves):
    m = as_array(moves, "moves", (3,), what=" (rows (v, w, duration): a move at constant body velocity)")
    if m.ndim != 2 or m.shape[0] < 1:
        raise ValueError(f"moves must have shape (k, 3), one row (v, w, duration) per move; got {m.shape}")
    if np.any(m[:, 2] < 0):
        raise ValueError("moves: every duration (third column) must be >= 0")
    return m


def disk_moves_path(moves: ArrayLike, g0: ArrayLike = (0.0, 0.0, 0.0),
                    n_per_move: int = 25) -> tuple[FloatArray, FloatArray]:
    """Poses (k * n_per_move + 1, 3) of the disk along the moves (v, w, duration), exact.

    Within a move the body velocity is constant, so g(t) = g_start exp(t (v, 0, w)); the
    samples are equally spaced in time within each move. Returns (t, g).
    """
    m = _moves(moves)
    g = as_array(g0, "g0", (3,), what=" (the starting pose)")
    n = int(n_per_move)
    if n < 1:
        raise ValueError(f"n_per_move must be a positive integer; got {n_per_move!r}")
    s = np.linspace(0.0, 1.0, n + 1)[1:]
    ts, gs, t0 = [np.zeros(1)], [g[None]], 0.0
    for v, w, T in m:
        xi = disk_body_velocity(v, w)
        seg = SE2.compose(g, SE2.exp((s * T)[:, None] * xi))
        ts.append(t0 + s * T)
        gs.append(seg)
        g, t0 = seg[-1], t0 + T
    return np.concatenate(ts), np.vstack(gs)


def parallel_park_moves(d: float, phi: float, speed: float = 1.0, turn_rate: float = 1.0) -> FloatArray:
    """The cycle drive d, turn phi, drive back d, turn back phi as moves (4, 3) of (v, w, duration)."""
    d = real_number(d, "d", what=" (the drive distance)")
    phi = real_number(phi, "phi", what=" (the turn angle)")
    v = positive_number(speed, "speed")
    w = positive_number(turn_rate, "turn_rate")
    sd, sp = np.sign(d) or 1.0, np.sign(phi) or 1.0
    Td, Tp = abs(d) / v, abs(phi) / w
    return np.array([[sd * v, 0.0, Td], [0.0, sp * w, Tp], [-sd * v, 0.0, Td], [0.0, -sp * w, Tp]])


def parallel_park_displacement(d: float, phi: float) -> FloatArray:
    """Net displacement (3,) of one parallel-parking cycle, exp(d X) exp(phi Y) exp(-d X) exp(-phi Y).

    X = :data:`DISK_DRIVE`, Y = :data:`DISK_TURN`; each factor is one allowed move (its body
    velocity has no sideways part), yet the product moves the disk sideways.
    """
    d = real_number(d, "d", what=" (the drive distance)")
    phi = real_number(phi, "phi", what=" (the turn angle)")
    E = SE2.exp(np.array([d * DISK_DRIVE, phi * DISK_TURN, -d * DISK_DRIVE, -phi * DISK_TURN]))
    g = E[0]
    for e in E[1:]:
        g = SE2.compose(g, e)
    return g


def bracket_estimate(d: float, phi: float) -> FloatArray:
    """The small-loop estimate d phi [X_drive, X_turn] (3,) of the cycle's net displacement.

    The loop (d, phi) -> (d, phi) in the plane of move amounts encloses the signed area d phi;
    for a small loop the commutator of the two flows is exp(area [X, Y]) up to third order.
    """
    d = real_number(d, "d", what=" (the drive distance)")
    phi = real_number(phi, "phi", what=" (the turn angle)")
    return d * phi * SE2.bracket(DISK_DRIVE, DISK_TURN)


def radial_loop_moves(a: float, b: float) -> FloatArray:
    """The loop 'a along X1, b along X2, back a along X1, back b along X2' for (3.viii), as (4, 2) rows (field, amount)."""
    a = real_number(a, "a", what=" (the amount along X1)")
    b = real_number(b, "b", what=" (the amount along X2)")
    return np.array([[1.0, a], [2.0, b], [1.0, -a], [2.0, -b]])


def radial_point_path(moves: ArrayLike, q0: ArrayLike = (1.0, 0.0), n_per_move: int = 25) -> FloatArray:
    """Points (k * n_per_move + 1, 2) of a point obeying x x' + y y' = 0 (3.viii), exact.

    ``moves`` rows (field, amount): field 1 is X1 = (-y, x), whose flow for time s turns the
    point by s about the origin; field 2 is X2 = X1 / |q|, whose flow turns it by s / |q|. Both
    keep |q| fixed, so the point stays on its circle (3.ix) and every loop closes exactly.
    """
    m = as_array(moves, "moves", (2,), what=" (rows (field 1 or 2, amount))")
    if m.ndim != 2 or not np.all(np.isin(m[:, 0], (1.0, 2.0))):
        raise ValueError("moves must have shape (k, 2) with rows (field, amount), field 1 or 2")
    q = as_array(q0, "q0", (2,), what=" (the starting point (x, y))")
    R = float(np.hypot(*q))
    if not R > 0:
        raise ValueError("q0 must not be the origin (there the constraint allows every direction)")
    phase = float(np.arctan2(q[1], q[0]))
    s = np.linspace(0.0, 1.0, int(n_per_move) + 1)[1:]
    out = [np.array([phase])]
    for field, amount in m:
        turn = amount if field == 1.0 else amount / R
        out.append(out[-1][-1] + s * turn)
    ang = np.concatenate(out)
    return R * np.stack([np.cos(ang), np.sin(ang)], -1)

"""Lie groups of chapter 1 behind one interface (numpy only).

Every group is a singleton object with the same methods, so a formula written once works on
(R, +), (R^n, +), (R+, x), SO(2), S^1, (R^2 x S^1, +), SE(2), the scale-shift group R+ x| R and SO(3):

=====================  ===================================================  ==============
method                 meaning                                              book
=====================  ===================================================  ==============
identity()             the identity element e                               (1.iv)
compose(g, h)          g o h (the left action L_g h, or right action R_h g)  (1.6), (1.9)
inverse(g)             g^-1                                                 (1.10)
left_lifted_action     T_g L_h, the matrix d(hg)/dg                         (1.20), (1.31)
right_lifted_action    T_g R_h, the matrix d(gh)/dg                         (1.21), (1.37)
Ad, Ad_inv             body <-> spatial velocity                           (1.40)-(1.45)
hat, vee               Lie algebra vector <-> matrix                       (1.54)
bracket, ad            Lie bracket [xi1, xi2] and its matrix ad_xi          (1.54) commutator
exp, log               exponential map and its inverse                     section 1.6.4
matrix, from_matrix    matrix representation of an element                 (1.1), (1.2)
contains, project      membership test, canonical coordinates               section 1.2
=====================  ===================================================  ==============

Elements and velocities are float arrays batched over leading axes: an SE(2) element has shape
``(..., 3)`` holding ``(x, y, theta)``, an element of (R+, x) has shape ``(..., 1)``. Matrices
such as lifted actions have shape ``(..., n, n)``. Batch axes broadcast with numpy's rules. Each
group declares ``param_dim`` (coordinates), ``tangent_dim`` (algebra), ``matrix_size`` and
``periods``; ``dim`` is the common value of the first two.

Angles are carried as real numbers and are not wrapped by ``compose``: that keeps formulas
identical to the book's, e.g. (1.6) ends in ``theta + beta``. Elements whose angles differ by a
multiple of 2 pi are the same element; compare with :meth:`LieGroup.isclose`, and use ``log``
(which wraps to (-pi, pi], exactly for every finite angle) to get the principal coordinates.
SO(3) is the exception: its coordinates are a rotation vector r, and every map returns the
principal one, |r| <= pi (``principal_radius``), since no single coordinate carries the angle.

Files: ``base.py`` (the abstract interface, angle reduction), ``additive.py`` (R^n, SO(2), S^1,
R^2 x S^1), ``rplus.py`` ((R+, x)), ``se2.py`` (SE(2)), ``scale_shift.py`` (R+ x| R, the affine
maps x -> a x + b of the line), ``so3.py`` (SO(3) in rotation vectors). A new group subclasses
:class:`LieGroup`, declares its dimensions and implements the abstract methods.
"""
from __future__ import annotations

from gm_core.groups.additive import MAX_RN_DIM, S1, SO2, R2xS1, Rn
from gm_core.groups.base import TWO_PI, LieGroup, check_group, matvec, wrap_angle, wrap_periodic
from gm_core.groups.rplus import RPlus
from gm_core.groups.scale_shift import ScaleShift
from gm_core.groups.se2 import SE2
from gm_core.groups.so3 import SO3

__all__ = [
    "LieGroup", "Rn", "R", "R2", "RPlus", "SO2", "S1", "R2xS1", "SE2", "ScaleShift", "SO3", "wrap_angle", "matvec",
    "ALL_GROUPS", "check_group", "wrap_periodic", "TWO_PI", "MAX_RN_DIM",
]

R = Rn(1)
R2 = Rn(2)

#: Every group of chapter 1 (and SO(3)), for tests and demos that loop over them.
ALL_GROUPS = {"R": R, "R2": R2, "RPlus": RPlus, "SO2": SO2, "S1": S1(), "S1_cycles": S1(1.0),
              "R2xS1": R2xS1, "SE2": SE2, "ScaleShift": ScaleShift, "SO3": SO3}

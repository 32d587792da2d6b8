"""Multiplicative calculus and the exponential map computed four ways (numpy + scipy only).

This module is the numeric side of the book's *Multiplicative Calculus* box ((1.xx)-(1.xxxii)) and
of section 1.6.4 / exercise 1.4d:

==========================  ==========================================================  =============
function                    what it computes                                            book
==========================  ==========================================================  =============
product_integral            prod (I + v(x_k) dx), left or right ordering, with history  (1.xxi), (1.xxiv), (1.xxvi)-(1.xxvii)
quotient_derivative         v_L = F' F^-1 or v_R = F^-1 F', by central differences      (1.xxv), (1.xxviii)-(1.xxx)
exp_closed_form             the group's closed-form exp (reference)                    section 1.6.4, ex. 1.4a/b
exp_taylor                  partial sums  sum_{k<n} A^k / k!                            (1.51)
exp_product                 cumulative product (I + A/n)^n                              (1.49)
exp_euler                   n Euler steps along the invariant field of xi               (1.46), (1.47)
exp_four_ways               all four at once, as a dict                                 ex. 1.4d
se2_exp_study               every method and side for xi = (1, 0, thetadot), several rates  ex. 1.4d
==========================  ==========================================================  =============

Left and right
--------------
``side`` in the exponential functions names the *invariant vector field* being followed, as in
``gm_core.fields``: ``"left"`` is the left-invariant field g_dot = T_e L_g xi of a body velocity xi,
(1.46); ``"right"`` is the right-invariant field g_dot = T_e R_g xi_s of a spatial velocity xi_s,
(1.47). In matrix form the left-invariant flow is g_dot = g xi^, so its Euler / cumulative-product
steps append new factors on the right: that is the *right* product integral (1.xxvi)-(1.xxvii).
Conversely the right-invariant flow g_dot = xi_s^ g is the *left* product integral (1.xxiv). The
function :func:`product_integral` uses the product-integral names (its ``side`` says where new
factors go). From the identity both exponential flows reach the same element exp(xi); the
intermediate values of the Euler integration differ (see :meth:`ExpHistory.path`), while the
cumulative products of a constant matrix coincide (powers of one matrix commute). (Exercise 1.4a/b
as drafted pair the body velocity xi with the right-invariant field and xi_s with the left one,
the reverse of (1.46)-(1.47); this module follows (1.46)-(1.47).)

The binomial step between (1.50) and (1.51) needs the coefficient C(n, k) = n! / (k! (n - k)!);
the draft prints n^k / k!, which is only its large-n limit (see :func:`binomial_terms`).

The code is in two modules: :mod:`.products` (product integral, quotient derivative, binomial
terms) and :mod:`.exp` (the exponential four ways); import everything from here.
"""
from __future__ import annotations

from gm_core.calculus.arguments import MAX_STEPS
from gm_core.calculus.exp import (
                  DEFAULT_N,
                  EXP_METHODS,
                  ExpHistory,
                  ExpPath,
                  convergence_order,
                  exp_closed_form,
                  exp_euler,
                  exp_four_ways,
                  exp_history,
                  exp_product,
                  exp_taylor,
                  se2_exp_study,
)
from gm_core.calculus.products import (
                  RunningProduct,
                  binomial_table,
                  binomial_terms,
                  element_from_matrix,
                  product_integral,
                  quotient_derivative,
)

__all__ = [
    "product_integral", "RunningProduct", "quotient_derivative",
    "ExpHistory", "ExpPath", "exp_closed_form", "exp_taylor", "exp_product", "exp_euler",
    "exp_four_ways", "exp_history", "convergence_order", "binomial_terms", "binomial_table",
    "element_from_matrix", "se2_exp_study", "EXP_METHODS", "DEFAULT_N", "MAX_STEPS",
]

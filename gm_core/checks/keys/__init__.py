"""The answer keys of every exercise, one module per chapter (:mod:`gm_core.checks.answer_key`).

Importing this package provides every key. The graded build of the course leaves the package
out: there no part can say what a right answer is, and the grader judges with its own copy.
"""
from gm_core.checks.keys import ex1, ex2, ex3, ex4, ex5

__all__ = ["ex1", "ex2", "ex3", "ex4", "ex5"]

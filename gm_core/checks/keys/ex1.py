"""The answer keys of chapter 1's exercises (:mod:`gm_core.checks.ex1`)."""

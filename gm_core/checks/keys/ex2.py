"""The answer keys of chapter 2's exercises (:mod:`gm_core.checks.ex2`)."""

"""The answer keys of chapter 4's exercises (:mod:`gm_core.checks.ex4`)."""

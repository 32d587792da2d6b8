"""The answer keys of chapter 3's exercises (:mod:`gm_core.checks.ex3`)."""

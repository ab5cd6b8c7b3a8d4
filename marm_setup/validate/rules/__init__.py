"""Validation rule families; every `check_*` function returns a list of `Finding`s.

Rule ids are stable (`<family>.<what>`, e.g. `srdf.unknown-link`); `validate.py` runs them all.
"""

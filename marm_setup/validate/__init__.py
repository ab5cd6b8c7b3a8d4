"""Validating a config package: discovery of its files, reading them, the rule families (`rules/`), the runner and the runtime (planning) checks."""

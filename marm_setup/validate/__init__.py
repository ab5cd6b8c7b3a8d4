"""Validating a config package (read once by `marm_setup.package`): the rule families
(`rules/`), the runner and the runtime (planning) checks.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "runner": "validate validate_package validate_read matrix_settings Validation ValidatedPackage",
        "runtime": "check_runtime PlannedPair",
    },
)

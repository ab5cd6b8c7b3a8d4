"""Validating a config package (read once by `marm_setup.package`): the rule families
(`rules/`), the runner and the runtime (planning) checks.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "runner": (
        "check_given_xacro_args load_package_robot matrix_proofs matrix_settings validate validate_package "
        "validate_read ValidatedPackage Validation"
    ),
    "runtime": "check_runtime PlannedPair",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.validate.runner import ValidatedPackage as ValidatedPackage
    from marm_setup.validate.runner import Validation as Validation
    from marm_setup.validate.runner import check_given_xacro_args as check_given_xacro_args
    from marm_setup.validate.runner import load_package_robot as load_package_robot
    from marm_setup.validate.runner import matrix_proofs as matrix_proofs
    from marm_setup.validate.runner import matrix_settings as matrix_settings
    from marm_setup.validate.runner import validate as validate
    from marm_setup.validate.runner import validate_package as validate_package
    from marm_setup.validate.runner import validate_read as validate_read
    from marm_setup.validate.runtime import PlannedPair as PlannedPair
    from marm_setup.validate.runtime import check_runtime as check_runtime

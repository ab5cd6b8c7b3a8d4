"""Validating a config package (read once by `marm_setup.package`): the rule families
(`rules/`), the runner and the runtime (planning) checks.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "runner": (
        "check_given_xacro_args load_package_robot validate validate_package "
        "validate_read ValidatedPackage Validation"
    ),
    "runtime": "check_runtime PlannedPair",
    "registry": "all_rules allows rule rule_families rule_family severity_of",
    "registry.catalogue": "rules_json rules_markdown rules_text",
    "sarif": "format_sarif",
    "junit": "format_junit",
    "locate": "finding_uri location_base",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.validate.junit import format_junit as format_junit
    from marm_setup.validate.locate import finding_uri as finding_uri
    from marm_setup.validate.locate import location_base as location_base
    from marm_setup.validate.registry import all_rules as all_rules
    from marm_setup.validate.registry import allows as allows
    from marm_setup.validate.registry import rule as rule
    from marm_setup.validate.registry import rule_families as rule_families
    from marm_setup.validate.registry import rule_family as rule_family
    from marm_setup.validate.registry import severity_of as severity_of
    from marm_setup.validate.registry.catalogue import rules_json as rules_json
    from marm_setup.validate.registry.catalogue import rules_markdown as rules_markdown
    from marm_setup.validate.registry.catalogue import rules_text as rules_text
    from marm_setup.validate.runner import ValidatedPackage as ValidatedPackage
    from marm_setup.validate.runner import Validation as Validation
    from marm_setup.validate.runner import check_given_xacro_args as check_given_xacro_args
    from marm_setup.validate.runner import load_package_robot as load_package_robot
    from marm_setup.validate.runner import validate as validate
    from marm_setup.validate.runner import validate_package as validate_package
    from marm_setup.validate.runner import validate_read as validate_read
    from marm_setup.validate.runtime import PlannedPair as PlannedPair
    from marm_setup.validate.runtime import check_runtime as check_runtime
    from marm_setup.validate.sarif import format_sarif as format_sarif

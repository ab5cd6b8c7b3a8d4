"""The registry of validate's rules: every rule id marm-setup can emit, with its family, its
severity, what MoveIt does with the defect and where MoveIt does it (rules.yaml, read once).

`rule(id)` / `severity_of(id)` / `allows(id, severity)` look one up; `rule_families()` names the
rule families (`srdf`, `controller`, ...) with one line each, `rule_family(name)` one of them.
tests/unit/test_rule_registry.py keeps the table equal to what marm_setup/ emits; `catalogue`
prints it (`marm-setup rules`, docs/rules.md).
"""

from marm_setup.validate.registry.table import (
    Family,
    Rule,
    all_rules,
    allows,
    rule,
    rule_families,
    rule_family,
    severity_of,
)

__all__ = ["Family", "Rule", "all_rules", "allows", "rule", "rule_families", "rule_family", "severity_of"]

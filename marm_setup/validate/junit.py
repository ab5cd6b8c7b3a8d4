"""validate's findings as JUnit XML (what GitLab CI, Jenkins and most CI dashboards read).

One `<testsuite>` per package, one `<testcase>` per rule family of the registry (so a clean family
shows as passed): its errors (and, with `strict`, its warnings) as one `<failure>`, its other
warnings in `<system-out>`, a crash of validate itself (`internal.error`) as an `<error>`.
The element and attribute names are those JUnit readers share (Ant's junit task schema).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from xml.etree import ElementTree as ET

from marm_setup.findings import INTERNAL, Finding, sort_findings
from marm_setup.validate.registry import rule_families

SUITES = "marm-setup validate"


def format_junit(packages: Sequence[tuple[str, Iterable[Finding]]], *, strict: bool = False) -> str:
    """The JUnit XML document of each (package as the user named it, its findings)."""
    root = ET.Element("testsuites", name=SUITES)
    totals = {"tests": 0, "failures": 0, "errors": 0}
    for name, findings in packages:
        suite = _suite(name, sort_findings(findings), strict)
        root.append(suite)
        for key in totals:
            totals[key] += int(suite.get(key, "0"))
    for key, value in totals.items():
        root.set(key, str(value))
    ET.indent(root)
    return '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def _suite(package: str, findings: list[Finding], strict: bool) -> ET.Element:
    families = sorted({f.name for f in rule_families()} | {_family(f) for f in findings})
    suite = ET.Element("testsuite", name=package, tests=str(len(families)))
    failures = errors = 0
    for family in families:
        case = ET.SubElement(suite, "testcase", classname=package, name=family)
        mine = [f for f in findings if _family(f) == family]
        crashes = [f for f in mine if f.rule == INTERNAL]
        failing = [f for f in mine if f.rule != INTERNAL and (f.is_error or strict)]
        passing = [f for f in mine if f.rule != INTERNAL and not (f.is_error or strict)]
        if crashes:
            errors += 1
            _child(case, "error", crashes, "validate crashed")
        if failing:
            failures += 1
            _child(case, "failure", failing, _counted(failing))
        if passing:
            ET.SubElement(case, "system-out").text = "\n".join(_line(f) for f in passing) + "\n"
    suite.set("failures", str(failures))
    suite.set("errors", str(errors))
    suite.set("skipped", "0")
    return suite


def _child(case: ET.Element, tag: str, findings: list[Finding], message: str) -> None:
    child = ET.SubElement(case, tag, message=message, type=findings[0].rule)
    child.text = "\n".join(_line(f) for f in findings) + "\n"


def _family(f: Finding) -> str:
    return f.rule.split(".", 1)[0]


def _counted(findings: list[Finding]) -> str:
    errors = sum(1 for f in findings if f.is_error)
    warnings = len(findings) - errors
    parts = [
        f"{n} {word}{'' if n == 1 else 's'}" for n, word in ((errors, "error"), (warnings, "warning")) if n
    ]
    return ", ".join(parts)


def _line(f: Finding) -> str:
    """`<severity> <file>: <element>: <message> [<rule>]` (and the hint), as the text format says it."""
    where = ": ".join(part for part in (f.file, f.element) if part)
    line = (
        f"{f.severity} {where}: {f.message} [{f.rule}]" if where else f"{f.severity} {f.message} [{f.rule}]"
    )
    return f"{line}\n  hint: {f.hint}" if f.hint else line

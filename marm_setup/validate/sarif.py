"""validate's findings as SARIF 2.1.0 (what GitHub code scanning and other review tools read).

One run; `tool.driver.rules` is the whole rule registry (rules.yaml), each result names its rule
by id and index. Locations are URIs the caller computed (validate/locate.py), relative to the
repository root; a finding whose element starts with `line N` gets a region. Field names and
required properties follow the OASIS SARIF 2.1.0 schema (sarif-schema-2.1.0.json: `run`
requires `tool`; `reportingDescriptor` requires `id`; `result` requires `message`).
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable

from marm_setup import __version__
from marm_setup.findings import INTERNAL, Finding, sort_findings
from marm_setup.validate.registry import Rule, all_rules

SCHEMA = "https://docs.oasis-open.org/sarif/sarif/v2.1.0/errata01/os/schemas/sarif-schema-2.1.0.json"
SHORT_CHARS = 120  # of a rule's shortDescription (SARIF §3.49.9: a concise description)
LINE = re.compile(r"line (\d+)(?::|$)")


def line_of(element: str) -> int | None:
    """N when the finding's element is `line N` or starts `line N: ...`, else None."""
    found = LINE.match(element)
    return int(found.group(1)) if found and int(found.group(1)) > 0 else None


def format_sarif(located: Iterable[tuple[Finding, str]]) -> str:
    """A SARIF log (indented JSON) of `located`: each finding with its artifact URI."""
    return json.dumps(sarif_log(located), indent=2) + "\n"


def sarif_log(located: Iterable[tuple[Finding, str]]) -> dict:
    """The SARIF log as plain data: one run, the registry's rules, one result per finding
    (sorted by URI, then as `sort_findings` orders them)."""
    rules = all_rules()
    index = {r.id: i for i, r in enumerate(rules)}
    by_uri: dict[str, list[Finding]] = {}
    for finding, uri in located:
        by_uri.setdefault(uri, []).append(finding)
    results = [
        _result(f, uri, index.get(f.rule)) for uri in sorted(by_uri) for f in sort_findings(by_uri[uri])
    ]
    driver = {
        "name": "marm-setup",
        "version": __version__,
        "rules": [_descriptor(r) for r in rules],
    }
    crashed = any(f.rule == INTERNAL for found in by_uri.values() for f in found)
    run = {
        "tool": {"driver": driver},
        "invocations": [{"executionSuccessful": not crashed}],
        "columnKind": "unicodeCodePoints",
        "results": results,
    }
    return {"$schema": SCHEMA, "version": "2.1.0", "runs": [run]}


def _descriptor(r: Rule) -> dict:
    """A rule as a SARIF reportingDescriptor (§3.49): what MoveIt does with the defect, and where."""
    return {
        "id": r.id,
        "shortDescription": {"text": _short(r.moveit_does)},
        "fullDescription": {"text": f"{r.moveit_does[:1].upper()}{r.moveit_does[1:]} (source: {r.source})."},
        "defaultConfiguration": {"level": r.severities[0]},
        "properties": {"family": r.family, "severity": r.severity, "source": r.source},
    }


def _short(text: str) -> str:
    if len(text) <= SHORT_CHARS:
        return text
    return text[: SHORT_CHARS - 3].rsplit(" ", 1)[0] + "..."


def _result(f: Finding, uri: str, rule_index: int | None) -> dict:
    """A finding as a SARIF result (§3.27): level, message (element, message, hint) and location."""
    text = f"{f.element}: {f.message}" if f.element else f.message
    location: dict = {"artifactLocation": {"uri": uri}}
    line = line_of(f.element)
    if line is not None:
        location["region"] = {"startLine": line}
    out: dict = {"ruleId": f.rule}
    if rule_index is not None:
        out["ruleIndex"] = rule_index
    out["level"] = f.severity.value
    out["message"] = {"text": f"{text} (hint: {f.hint})" if f.hint else text}
    out["locations"] = [{"physicalLocation": location}]
    return out

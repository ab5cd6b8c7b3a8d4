"""Validation findings: the `Finding` value, its order, and text/json formatting (strings only)."""

from __future__ import annotations

import enum
import json
from collections.abc import Iterable
from dataclasses import asdict, dataclass, field

from marm_setup.untrusted import excerpt


class Severity(str, enum.Enum):
    """An error is what MoveIt (or its launcher, driver or controller manager) would fail on or
    do wrong; a warning what MoveIt warns about, or a likely mistake (DESIGN §5)."""

    ERROR = "error"
    WARNING = "warning"

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)


ERROR = Severity.ERROR
WARNING = Severity.WARNING
SEVERITIES = tuple(Severity)
INTERNAL = "internal.error"  # a crash inside validate itself (exit 2), never the package's fault

_COLOURS = {ERROR: "\x1b[31m", WARNING: "\x1b[33m"}
_BOLD = "\x1b[1m"
_RESET = "\x1b[0m"


@dataclass(frozen=True, slots=True)
class Evidence:
    """A robot state that shows a finding: the links involved (e.g. two in contact) and the
    active joints' values [rad or m], in the robot's active-joint order."""

    links: tuple[str, ...]
    state: tuple[tuple[str, float], ...]

    @classmethod
    def of(cls, links: Iterable[str], names: Iterable[str], values: Iterable[float]) -> Evidence:
        """Evidence of `links` at the state giving each of `names` its value in `values`."""
        return cls(tuple(links), tuple((n, float(v)) for n, v in zip(names, values, strict=True)))

    def as_dict(self) -> dict:
        return {"links": list(self.links), "state": dict(self.state)}


@dataclass(frozen=True, slots=True)
class Location:
    """Where a finding is, as data (its `element` is the same for people): the kind of element
    (`group`, `group_state`, `virtual_joint`, `end_effector`, `kinematics`, ...) and its name;
    `refers` the element it names that does not exist or cannot be used (`("group", "arm")` for
    an unknown group), so callers decide by these, never by parsing text."""

    kind: str = ""
    name: str = ""
    refers: tuple[str, str] | None = None


MAX_TEXT = 2000  # characters of a finding's message or hint (names from a package can be any size)
MAX_PATH = 500  # of its file or element


@dataclass(frozen=True, slots=True)
class Finding:
    """One problem: a stable rule id (`srdf.unknown-link`), severity, where it is, what, and a fix;
    `evidence` (not part of its identity) a state that shows it, where one does."""

    rule: str
    severity: Severity
    file: str  # relative to the package (or the path the user gave for files outside it)
    element: str  # e.g. `group[arm]/chain`, `panda_arm.kinematics_solver`, `line 12`
    message: str
    hint: str = ""
    evidence: Evidence | None = field(default=None, compare=False)
    location: Location = Location()

    def __post_init__(self) -> None:
        if self.severity not in SEVERITIES:
            raise ValueError(
                f"severity must be one of {[s.value for s in SEVERITIES]}, got {self.severity!r}"
            )
        object.__setattr__(self, "severity", Severity(self.severity))
        for name, limit in (
            ("file", MAX_PATH),
            ("element", MAX_PATH),
            ("message", MAX_TEXT),
            ("hint", MAX_TEXT),
        ):
            value = getattr(self, name)  # package content reaches messages: printable and bounded
            if len(value) > limit or not value.isprintable():
                object.__setattr__(self, name, excerpt(value, limit))

    @property
    def is_error(self) -> bool:
        return self.severity == ERROR


def error(
    rule: str,
    file: str,
    element: str,
    message: str,
    hint: str = "",
    evidence: Evidence | None = None,
    at: Location = Location(),
) -> Finding:
    return Finding(rule, ERROR, file, element, message, hint, evidence, at)


def warning(
    rule: str,
    file: str,
    element: str,
    message: str,
    hint: str = "",
    evidence: Evidence | None = None,
    at: Location = Location(),
) -> Finding:
    return Finding(rule, WARNING, file, element, message, hint, evidence, at)


def sort_findings(findings: Iterable[Finding]) -> list[Finding]:
    """Sorted by file, then element, then rule and message; exact duplicates dropped."""
    return sorted(
        set(findings), key=lambda f: (f.file, f.element, f.rule, f.message, f.severity.value, f.hint)
    )


def count(findings: Iterable[Finding]) -> tuple[int, int]:
    """(errors, warnings)."""
    items = list(findings)
    errors = sum(1 for f in items if f.is_error)
    return errors, len(items) - errors


def summary(findings: Iterable[Finding]) -> str:
    """`2 errors, 1 warning` (or `no findings`)."""
    errors, warnings = count(findings)
    if not errors and not warnings:
        return "no findings"
    return f"{_plural(errors, 'error')}, {_plural(warnings, 'warning')}"


def _plural(n: int, word: str) -> str:
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


def format_text(findings: Iterable[Finding], *, color: bool = False, checked: str = "") -> str:
    """Findings grouped by file, one line each (hint on the next line), then `checked` (a line
    saying what was validated) and a summary line."""
    items = sort_findings(findings)
    lines: list[str] = []
    current = None
    for f in items:
        if f.file != current:
            current = f.file
            lines.append(f"{_BOLD}{f.file}{_RESET}" if color else f.file)
        sev = f"{_COLOURS[f.severity]}{f.severity}{_RESET}" if color else f.severity
        pad = " " * (len(WARNING) - len(f.severity))
        where = f"{f.element}: " if f.element else ""
        lines.append(f"  {sev}{pad} {where}{f.message} [{f.rule}]")
        if f.hint:
            lines.append(f"          hint: {f.hint}")
    if checked:
        lines.append(checked)
    lines.append(summary(items))
    return "\n".join(lines) + "\n"


def format_json(findings: Iterable[Finding], *, checked: dict | None = None) -> str:
    """`{"findings": [...], "errors": n, "warnings": n}` (and `"validated": checked` when given)
    as indented JSON."""
    items = sort_findings(findings)
    errors, warnings = count(items)
    doc = {"findings": [finding_dict(f) for f in items], "errors": errors, "warnings": warnings}
    if checked is not None:
        doc["validated"] = checked
    return json.dumps(doc, indent=2) + "\n"


def finding_dict(f: Finding) -> dict:
    """A finding as plain data; `evidence` only where the finding has one, `location` only
    where it says something."""
    keys = ("rule", "severity", "file", "element", "message", "hint")
    out: dict = {key: getattr(f, key) for key in keys}
    if f.evidence is not None:
        out["evidence"] = f.evidence.as_dict()
    if f.location != Location():
        out["location"] = {k: v for k, v in asdict(f.location).items() if v not in ("", None)}
    return out

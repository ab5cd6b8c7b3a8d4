"""rules.yaml as values: `Rule` and `Family` rows, read once, and the lookups over them."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from importlib import resources

import yaml

from marm_setup.names import did_you_mean

# our own data files: libyaml's safe loader where PyYAML has it (10x faster than the Python one)
SAFE_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

SEVERITY_SETS = ("error", "warning", "error|warning")
FIELDS = ("id", "severity", "moveit_does", "source")


@dataclass(frozen=True, slots=True)
class Family:
    """A rule family: the prefix of its rules' ids (`srdf`) and what its rules check."""

    name: str
    description: str


@dataclass(frozen=True, slots=True)
class Rule:
    """One rule id; `severity` is `error`, `warning` or `error|warning` (then `why` says when
    which); `moveit_does` what MoveIt does with the defect, `source` where it does it."""

    id: str
    severity: str
    moveit_does: str
    source: str
    why: str = ""

    @property
    def family(self) -> str:
        return self.id.split(".", 1)[0]

    @property
    def severities(self) -> tuple[str, ...]:
        return tuple(self.severity.split("|"))


@dataclass(frozen=True, slots=True)
class Table:
    families: tuple[Family, ...]
    rules: tuple[Rule, ...]


@functools.cache
def _table() -> Table:
    text = resources.files(__package__).joinpath("rules.yaml").read_text(encoding="utf-8")
    return parse_table(yaml.load(text, Loader=SAFE_LOADER))


def parse_table(data: dict) -> Table:
    """The table in `data` (rules.yaml's document), sorted by name and id; ValueError when a row
    lacks a field, has an unknown severity or family, or says no why for two severities."""
    families = tuple(Family(str(k), str(v)) for k, v in sorted(data["families"].items()))
    names = {f.name for f in families}
    rows = []
    for row in data["rules"]:
        missing = [key for key in FIELDS if not str(row.get(key) or "").strip()]
        if missing:
            raise ValueError(f"rules.yaml: {row.get('id', row)}: no {', '.join(missing)}")
        found = Rule(**{key: " ".join(str(value).split()) for key, value in row.items()})
        if found.severity not in SEVERITY_SETS:
            raise ValueError(f"rules.yaml: {found.id}: severity must be one of {SEVERITY_SETS}")
        if (len(found.severities) > 1) != bool(found.why):
            raise ValueError(f"rules.yaml: {found.id}: a why exactly when it has two severities")
        if found.family not in names:
            raise ValueError(f"rules.yaml: {found.id}: unknown family '{found.family}'")
        rows.append(found)
    ids = [r.id for r in rows]
    if len(set(ids)) != len(ids):
        raise ValueError(f"rules.yaml: ids listed twice: {sorted({i for i in ids if ids.count(i) > 1})}")
    return Table(families, tuple(sorted(rows, key=lambda r: r.id)))


def all_rules() -> tuple[Rule, ...]:
    """Every rule, by id."""
    return _table().rules


def rule_families() -> tuple[Family, ...]:
    """Every rule family, by name."""
    return _table().families


@functools.cache
def _by_id() -> dict[str, Rule]:
    return {r.id: r for r in all_rules()}


def rule(rule_id: str) -> Rule:
    """The rule `rule_id`; KeyError (naming close ids) when the registry has none."""
    found = _by_id().get(rule_id)
    if found is None:
        raise KeyError(_unknown(f"no rule '{rule_id}' in the registry", did_you_mean(rule_id, _by_id())))
    return found


def severity_of(rule_id: str) -> str:
    """`error`, `warning` or `error|warning` (KeyError for an unknown id)."""
    return rule(rule_id).severity


def allows(rule_id: str, severity: str) -> bool:
    """Whether the registry lets `rule_id` be emitted with `severity` (False for an unknown id)."""
    found = _by_id().get(rule_id)
    return found is not None and str(severity) in found.severities


def rule_family(name: str) -> Family:
    """The family `name` (`srdf`); KeyError (naming close ones) when there is none: what the
    runner's `guarded(family, ...)` should check its names against."""
    found = _families_by_name().get(name)
    if found is None:
        raise KeyError(_unknown(f"no rule family '{name}'", did_you_mean(name, _families_by_name())))
    return found


@functools.cache
def _families_by_name() -> dict[str, Family]:
    return {f.name: f for f in rule_families()}


def _unknown(message: str, hint: str) -> str:
    return f"{message}; {hint}" if hint else message

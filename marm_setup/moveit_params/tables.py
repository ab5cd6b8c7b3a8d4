"""The declared-parameter tables (data/<family>.yaml, built by regenerate.py) as values: what
parameters MoveIt's move_group and servo nodes declare or read per distro family, with type,
validators, default, what a wrong value does, and the source line; and the plugin classes
each family's pluginlib files export.

Families: `jazzy` (also kilted and rolling: moveit2's generate_parameter_library files are
byte-identical on the jazzy, kilted and main branches), `humble`, `noetic` (MoveIt 1).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import yaml

# our own data files: libyaml's safe loader where PyYAML has it (10x faster than the Python one)
SAFE_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

DATA = Path(__file__).with_name("data")
FAMILIES = {
    "jazzy": ("jazzy", "kilted", "rolling"),
    "humble": ("humble",),
    "noetic": ("noetic",),
}
PLACEHOLDER = re.compile(r"<(\w+)>")
# on_wrong values: what MoveIt does with a value of the wrong type or out of its validators
THROWS, DROPS, LOGS = "throws", "drops", "logs"


@dataclass(frozen=True, slots=True)
class ParamRow:
    """One declared parameter; `name` may hold placeholders (`<controller>`, `<joint>`, ...)."""

    node: str  # move_group | servo
    name: str
    type: str  # bool, int, double, number (int or double), string, string_array, double_array, ...
    on_wrong: str  # throws | drops | logs
    source: str  # repo path:line at the pinned commit (or a third-party reference)
    default: object = None
    validation: tuple[tuple[str, tuple], ...] = ()  # (validator, arguments), gpl names
    note: str = ""

    @property
    def pattern(self) -> re.Pattern[str]:
        return _pattern(self.name)

    def bindings(self, name: str) -> dict[str, str] | None:
        """The placeholders' values when `name` is an instance of this row, else None."""
        found = self.pattern.fullmatch(name)
        return found.groupdict() if found else None


@dataclass(frozen=True, slots=True)
class Table:
    family: str
    distros: tuple[str, ...]
    pinned: tuple[tuple[str, str, str], ...]  # (repo, ref, commit)
    parameters: tuple[ParamRow, ...]
    owned: tuple[tuple[str, str], ...]  # (namespace prefix with placeholders, source)
    plugins: dict[str, tuple[tuple[str, str], ...]]  # kind -> (class, source)
    third_party: dict[str, tuple[tuple[str, str], ...]]
    ompl_planners: tuple[tuple[str, str], ...] = ()  # (planner type OMPL registers, source)

    def rows(self, node: str) -> tuple[ParamRow, ...]:
        return tuple(r for r in self.parameters if r.node == node)

    def classes(self, kind: str) -> tuple[str, ...]:
        """MoveIt's own and the known third-party classes of a plugin kind."""
        return tuple(c for c, _ in (*self.plugins.get(kind, ()), *self.third_party.get(kind, ())))


def family_of(distro: str | None) -> str | None:
    """The table family of a distro name (None: unknown)."""
    return next((f for f, distros in FAMILIES.items() if distro in distros), None)


@cache
def load_table(family: str) -> Table:
    data = yaml.load((DATA / f"{family}.yaml").read_text(encoding="utf-8"), Loader=SAFE_LOADER)
    return Table(
        family=data["family"],
        distros=tuple(data["distros"]),
        pinned=tuple((repo, ref, sha) for repo, refs in data["pinned"].items() for ref, sha in refs.items()),
        parameters=tuple(row_of(r) for r in data["parameters"]),
        owned=tuple((o["prefix"], o["source"]) for o in data["owned"]),
        plugins=_classes(data["plugins"]),
        third_party=_classes(data["third_party"]),
        ompl_planners=tuple((r["type"], r["source"]) for r in data.get("ompl_planners", ())),
    )


def row_of(data: dict) -> ParamRow:
    """A table row (one mapping of a data file's `parameters`) as a ParamRow."""
    validation = tuple((str(k), _args(v)) for k, v in (data.get("validation") or {}).items())
    return ParamRow(
        node=data["node"],
        name=data["name"],
        type=data["type"],
        on_wrong=data["on_wrong"],
        source=data["source"],
        default=data.get("default"),
        validation=validation,
        note=data.get("note", ""),
    )


def _args(value: object) -> tuple:
    """A validator's arguments (gpl writes `gt<>: [0.0]`, sometimes `gt<>: 0.0` or nothing)."""
    if value is None:
        return ()
    return tuple(value) if isinstance(value, list) else (value,)


def _classes(data: dict) -> dict[str, tuple[tuple[str, str], ...]]:
    return {kind: tuple((r["class"], r["source"]) for r in rows) for kind, rows in data.items()}


@cache
def _pattern(name: str) -> re.Pattern[str]:
    parts = PLACEHOLDER.split(name)  # literal, placeholder, literal, ...
    regex = "".join(re.escape(p) if i % 2 == 0 else f"(?P<{p}>[^.]+)" for i, p in enumerate(parts))
    return re.compile(regex)

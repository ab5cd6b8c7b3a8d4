"""Where a value of a package file sits, and the plain values the file readers give.

Every value a reader takes from a file keeps its `Where`: the file (relative to the package),
its key path in the file (as findings and the port report name it: `robot_description_planning.
joint_limits.joint_1.max_velocity`, `controller_list[0]`) and, when known, its line.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from marm_setup.safe_yaml import KeyPath

# A value as YAML gives it, frozen: a scalar, a tuple of values (a list), or a FrozenMapping of
# (key, value) pairs. int and float stay apart (ROS 2 parameters are typed).
Value = str | int | float | bool | None | tuple["Value", ...]


class FrozenMapping(tuple):
    """A YAML mapping as a value: a tuple of (key, value) pairs, told apart from a list."""


@dataclass(frozen=True, slots=True)
class Where:
    """A file of the package, a key path inside it, and the line (1-based) when known."""

    file: str
    keys: tuple[str, ...] = ()
    line: int | None = None

    @property
    def element(self) -> str:
        """The dotted key path (`prefix.key1.key2`), as findings name an element."""
        return ".".join(k for k in self.keys if k)

    def child(self, *keys: object, line: int | None = None) -> Where:
        return Where(self.file, (*self.keys, *(str(k) for k in keys if str(k))), line)

    def __str__(self) -> str:
        """`file: element` (or the file alone), as the port report names a source."""
        return f"{self.file}: {self.element}" if self.element else self.file


@dataclass(frozen=True, slots=True)
class Param:
    """One key of a file and its value, where it is written."""

    key: str
    value: Value
    where: Where

    @property
    def number(self) -> float | None:
        """The value as a finite float, or None when it is no number (bools are not numbers)."""
        return finite_number(self.value)

    @property
    def flag(self) -> bool | None:
        """The value as ROS reads a bool parameter: True/False, or None for anything else."""
        if isinstance(self.value, bool):
            return self.value
        return (
            {"true": True, "false": False}.get(str(self.value).lower())
            if isinstance(self.value, str)
            else None
        )


def finite_number(value: object) -> float | None:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return None
    try:
        number = float(value)
    except OverflowError:
        return None
    return number if math.isfinite(number) else None


def freeze(value: Any) -> Value:
    """A parsed YAML value as a `Value`: lists become tuples, mappings tuples of pairs."""
    if isinstance(value, Mapping):
        return FrozenMapping((str(k), freeze(v)) for k, v in value.items())
    if isinstance(value, list | tuple):
        return tuple(freeze(v) for v in value)
    if value is None or isinstance(value, str | int | float | bool):
        return value
    return str(value)


def thaw(value: Value) -> Any:
    """A `Value` as YAML gave it: FrozenMappings become dicts, tuples lists."""
    if isinstance(value, FrozenMapping):
        return {k: thaw(v) for k, v in value}
    if isinstance(value, tuple):
        return [thaw(v) for v in value]
    return value


@dataclass(frozen=True, slots=True)
class Located:
    """A parsed YAML mapping of one file with its key path: what a reader walks (internal to
    the readers; they hand out typed values, never this)."""

    where: Where
    data: Any
    lines: Mapping[KeyPath, int]
    raw: KeyPath = ()  # the key path of `data` in the file, for line look-ups

    def get(self, key: object) -> Located:
        """The value at `key` (None data when absent or when this is not a mapping)."""
        data = self.data.get(key) if isinstance(self.data, dict) else None
        return self._at(key, data, str(key))

    def items_of_list(self) -> list[Located]:
        """The items of a list, each named `key[i]` after the list's own key; [] for anything else."""
        if not isinstance(self.data, list):
            return []
        last = self.where.keys[-1] if self.where.keys else ""
        parent = Where(self.where.file, self.where.keys[:-1])
        out = []
        for i, data in enumerate(self.data):
            raw = (*self.raw, i)
            out.append(Located(parent.child(f"{last}[{i}]", line=self.lines.get(raw)), data, self.lines, raw))
        return out

    def _at(self, raw_key: object, data: Any, label: str) -> Located:
        raw = (*self.raw, raw_key if isinstance(raw_key, int) else str(raw_key))
        return Located(self.where.child(label, line=self.lines.get(raw)), data, self.lines, raw)

    def items(self) -> list[tuple[str, Located]]:
        """(key, value) pairs of a mapping, in file order; [] for anything else."""
        if not isinstance(self.data, dict):
            return []
        return [(str(k), self.get(k)) for k in self.data]

    def params(self, flat: bool = True) -> tuple[Param, ...]:
        """Every key of a mapping as a Param (nested mappings flattened to `a.b` keys, unless
        not `flat`: then a nested mapping is one FrozenMapping value)."""
        out: list[Param] = []
        for key, value in self.items():
            if flat and isinstance(value.data, dict) and value.data:
                out += [Param(f"{key}.{p.key}", p.value, p.where) for p in value.params()]
            else:
                out.append(Param(key, freeze(value.data), value.where))
        return tuple(out)

    def param(self, key: str) -> Param | None:
        """The key as a Param, or None when absent (or null)."""
        value = self.get(key)
        return None if value.data is None else Param(key, freeze(value.data), value.where)

    @property
    def is_mapping(self) -> bool:
        return isinstance(self.data, dict)


def unwrap_parameters(doc: Located) -> Located:
    """A ROS 2 parameter file's `{node: {ros__parameters: X}}` (or `/**`) -> X, keeping its key
    path; anything else unchanged."""
    if doc.is_mapping and len(doc.data) == 1:
        ((_node, body),) = doc.items()
        if body.is_mapping and body.get("ros__parameters").is_mapping:
            return body.get("ros__parameters")
    return doc

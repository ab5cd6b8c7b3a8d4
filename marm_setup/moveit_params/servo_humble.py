"""Humble's hand-written moveit_servo declarations as table rows: each
`declare_parameter(ns + ".<name>", ParameterValue{ parameters.<field> }, ...)` of
moveit_servo/src/servo_parameters.cpp, typed by `<field>`'s declaration in servo_parameters.h."""

from __future__ import annotations

import re

CPP = "moveit_ros/moveit_servo/src/servo_parameters.cpp"
HEADER = "moveit_ros/moveit_servo/include/moveit_servo/servo_parameters.h"
_DECLARE = re.compile(
    r'declare_parameter\(\s*ns \+ "\.([\w.]+)",\s*ParameterValue\{\s*parameters\.(\w+)\s*\}'
)
_FIELD = re.compile(r"^\s*(bool|double|int|std::string)\s+(\w+)\s*(?:=\s*)?\{\s*([^}]*)\}", re.M)
_TYPES = {"bool": "bool", "double": "double", "int": "int", "std::string": "string"}


def servo_rows(cpp: str, header: str) -> list[dict]:
    """One row per declared servo parameter (name relative to the `moveit_servo` namespace)."""
    fields = {m[2]: (_TYPES[m[1]], _default(m[1], m[3])) for m in _FIELD.finditer(header)}
    rows = []
    for match in _DECLARE.finditer(cpp):
        name, field = match[1], match[2]
        type_, default = fields[field]
        line = cpp.count("\n", 0, match.start()) + 1
        row = {"node": "servo", "name": name, "type": type_}
        if default is not None:
            row["default"] = default
        row |= {"on_wrong": "throws", "source": f"{CPP}:{line}"}
        rows.append(row)
    return rows


def _default(cpp_type: str, literal: str) -> object:
    text = literal.strip()
    if cpp_type == "std::string":
        return text[1:-1] if text.startswith('"') and text.endswith('"') else None
    if cpp_type == "bool":
        return text == "true"
    try:
        return float(text) if cpp_type == "double" else int(text)
    except ValueError:
        return None

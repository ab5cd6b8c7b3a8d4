"""load_robot: URDF/xacro file -> frozen RobotModel (xacro, package map, mesh resolution).

`expand_xacro` (robot/xacro_expand.py) is re-exported here for its callers."""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Iterable, Mapping
from pathlib import Path

from lxml import etree

from marm_setup.errors import InputError
from marm_setup.robot.model import RobotModel
from marm_setup.robot.ros2_control import HardwareArg, MockSwitch, systems_in_urdf
from marm_setup.robot.ros_packages import find_packages
from marm_setup.robot.text_input import read_text
from marm_setup.robot.tinyxml import tinyxml_comments
from marm_setup.robot.urdf import parse_urdf
from marm_setup.robot.xacro_expand import expand_xacro, run_xacro

__all__ = ["expand_xacro", "load_robot", "parse_xacro_args", "parse_xml", "xml_syntax_message"]


def parse_xacro_args(items: Iterable[str], option: str = "--xacro-arg") -> dict[str, str]:
    """`NAME:=VALUE` strings (of `option`) -> mapping; a malformed item is an InputError."""
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition(":=")
        if not sep or not name:
            raise InputError(f"expected NAME:=VALUE, got '{item}'", element=option)
        out[name] = value
    return out


def load_robot(
    path: str | Path,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
) -> RobotModel:
    """Load a `.urdf` or xacro file into a RobotModel; every failure is an InputError. The
    model records the arguments its xacro takes (`xacro_args`, None for a plain URDF)."""
    shown = str(path)
    file = Path(path)
    if file.is_dir():
        raise InputError("is a folder; expected a .urdf or .xacro file", path=shown)
    if not file.is_file():
        raise InputError("file not found", path=shown)
    packages = find_packages(package_paths, near=file)
    args = dict(xacro_args or {})
    expanded = run_xacro(file, args, packages, shown=shown) if file.suffix == ".xacro" else None
    xml = expanded.xml if expanded is not None else read_text(file, shown=shown)
    declared = tuple(sorted(expanded.declared)) if expanded is not None else None
    root = parse_xml(xml, shown=shown)
    robot = parse_urdf(root, xml, file.parent, packages, shown=shown)
    switch: MockSwitch | None = None
    hardware_args: tuple[HardwareArg, ...] = ()
    if expanded is not None and (systems := systems_in_urdf(xml)):
        from marm_setup.robot.hardware_args import find_hardware_args
        from marm_setup.robot.mock_switch import find_mock_switch

        def expand(values: Mapping[str, str]) -> str:
            return run_xacro(file, values, packages, shown=shown).xml

        known = dict(expanded.values)
        switch = find_mock_switch(expand, args, known)
        real = (switch.real, {**args, switch.arg: "false"}) if switch else (systems, args)
        hardware_args = find_hardware_args(
            expand, real[1], known, real[0], frozenset({switch.arg} if switch else ())
        )
    used = tuple((u.name, u.path, u.found_by) for u in sorted(packages.used.values(), key=lambda u: u.name))
    unset = expanded.env_defaults if expanded is not None else ()
    return dataclasses.replace(
        robot,
        packages=used,
        xacro_args=declared,
        mock_switch=switch,
        hardware_args=hardware_args,
        env_defaults=unset,
    )


def parse_xml(text: str, *, shown: str) -> etree._Element:
    """Parse URDF text as urdfdom does (`tinyxml_comments`); syntax errors become InputError
    with the line number."""
    try:
        parser = etree.XMLParser(remove_comments=True)
        return etree.fromstring(tinyxml_comments(text).encode("utf-8"), parser)
    except etree.XMLSyntaxError as exc:
        raise InputError(
            f"malformed XML: {xml_syntax_message(exc)}", path=shown, element=f"line {exc.lineno}"
        ) from None


def xml_syntax_message(exc: etree.XMLSyntaxError) -> str:
    """libxml2's message on one line, without the position it repeats (the element names the line)."""
    text = " ".join(str(exc.msg).split())
    return re.sub(r"\s*,?\s*line \d+, column \d+$", "", text)

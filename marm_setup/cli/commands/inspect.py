"""`marm-setup inspect`: print the kinematic tree of a URDF/xacro."""

from __future__ import annotations

import json
from typing import Annotated

import typer

from marm_setup.cli.common import (
    OutputFormat,
    PackagePaths,
    UrdfArg,
    XacroArgs,
    load_robot_from_cli,
)


def inspect(
    urdf: UrdfArg,
    xacro_arg: XacroArgs = None,
    package_path: PackagePaths = None,
    format: Annotated[OutputFormat, typer.Option("--format", help="text or json.")] = OutputFormat.text,
) -> None:
    """Print the kinematic tree: joints (type, limits, mimic) and links (with/without geometry)."""
    from marm_setup.robot import describe_robot, format_tree

    robot = load_robot_from_cli(urdf, xacro_arg, package_path)
    if format is OutputFormat.json:
        typer.echo(json.dumps(describe_robot(robot), indent=2))
    else:
        typer.echo(format_tree(robot))

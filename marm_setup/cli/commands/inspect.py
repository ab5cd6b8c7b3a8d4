"""`marm-setup inspect`: print the kinematic tree of a URDF/xacro."""

from __future__ import annotations

import json
from typing import Annotated

import typer

from marm_setup.cli.common import ROBOT, OutputFormat, load_robot_from_cli
from marm_setup.cli.option_groups import takes
from marm_setup.flows import RobotInput


@takes("robot", ROBOT.of("urdf", "xacro_arg", "package_path"))
def inspect(
    robot: RobotInput,
    format: Annotated[OutputFormat, typer.Option("--format", help="text or json.")] = OutputFormat.text,
) -> None:
    """Print the kinematic tree: joints (type, limits, mimic) and links (with/without geometry)."""
    from marm_setup.robot import describe_robot, format_tree

    model = load_robot_from_cli(robot)
    if format is OutputFormat.json:
        typer.echo(json.dumps(describe_robot(model), indent=2))
    else:
        typer.echo(format_tree(model))

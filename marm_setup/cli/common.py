"""Options and helpers shared by the CLI commands (kept free of heavy imports)."""

from __future__ import annotations

import enum
from pathlib import Path
from typing import Annotated

import typer

UrdfArg = Annotated[
    Path, typer.Argument(help="Robot description: .urdf, .xacro or .urdf.xacro.", metavar="URDF")
]
XacroArgs = Annotated[
    list[str] | None,
    typer.Option("--xacro-arg", help="xacro argument NAME:=VALUE (repeatable).", metavar="NAME:=VALUE"),
]
PackagePaths = Annotated[
    list[Path] | None,
    typer.Option(
        "--package-path",
        help="Folder holding ROS packages, or a package (repeatable); ROS_PACKAGE_PATH is also read.",
        metavar="DIR",
    ),
]


class OutputFormat(str, enum.Enum):
    text = "text"
    json = "json"


def load_robot_from_cli(urdf: Path, xacro_args: list[str] | None, package_paths: list[Path] | None):
    """Load a robot from command-line options (the import stays out of --help)."""
    from marm_setup.robot.load import load_robot, parse_xacro_args

    return load_robot(urdf, parse_xacro_args(xacro_args or []), package_paths or [])


def one_line(text: str) -> str:
    """`text` with control characters (newlines too) escaped, so a message stays one line."""
    return "".join(c if c.isprintable() or c == " " else repr(c)[1:-1] for c in text)


def echo_err(message: str) -> None:
    """Print one line to stderr."""
    typer.echo(one_line(message), err=True)

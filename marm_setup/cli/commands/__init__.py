"""CLI commands, one module each; `marm_setup.cli.app` registers them in --help order.

Command modules import heavy libraries (coal, trimesh, scipy) inside their bodies, so that
`marm-setup --help` stays fast.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable

# (command name, module in marm_setup.cli.commands, function name), in --help order.
COMMAND_SPECS = (
    ("init", "init", "init"),
    ("collisions", "collisions", "collisions"),
    ("render", "render", "render"),
    ("validate", "validate", "validate"),
    ("report", "report", "report"),
    ("plan", "plan", "plan"),
    ("inspect", "inspect", "inspect"),
    ("rules", "rules", "rules"),
)


def load_commands() -> list[tuple[str, Callable]]:
    """(name, function) of every command."""
    return [
        (name, getattr(importlib.import_module(f"marm_setup.cli.commands.{module}"), func))
        for name, module, func in COMMAND_SPECS
    ]

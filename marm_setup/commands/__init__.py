"""CLI commands, one module each; registered on the app by `marm_setup.cli`."""

from __future__ import annotations

import importlib

# (command name, module in marm_setup.commands, function name), in --help order.
COMMAND_SPECS = [
    ("init", "init", "init"),
    ("collisions", "collisions", "collisions"),
    ("render", "render", "render"),
    ("validate", "validate", "validate"),
    ("plan", "plan", "plan"),
    ("inspect", "inspect", "inspect"),
]


def load_commands():
    """(name, function) for every command module present."""
    out = []
    for name, module, func in COMMAND_SPECS:
        try:
            mod = importlib.import_module(f"marm_setup.commands.{module}")
        except ModuleNotFoundError as exc:
            if exc.name != f"marm_setup.commands.{module}":
                raise
            continue  # not written yet
        out.append((name, getattr(mod, func)))
    return out

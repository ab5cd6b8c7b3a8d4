"""CLI commands, one module each; registered on the app by `marm_setup.cli`."""

from marm_setup.commands.inspect import inspect

COMMANDS = [
    ("inspect", inspect),
]

"""The Typer app: shared options, the one MarmError -> exit code mapping, command registry.

Each command lives in `marm_setup/cli/commands/<name>.py` and imports heavy modules (coal,
trimesh, scipy) inside its body, so `marm-setup --help` stays fast.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Annotated, ParamSpec, TypeVar

import typer

from marm_setup import __version__
from marm_setup.cli.common import echo_err
from marm_setup.errors import MarmError

app = typer.Typer(
    name="marm-setup",
    help="Headless MoveIt Setup Assistant: collision matrix, config packages, validation, planning.",
    no_args_is_help=True,
    pretty_exceptions_show_locals=False,
    add_completion=False,
    rich_markup_mode=None,  # plain help: rendering it with rich costs ~130 ms of imports
)

P = ParamSpec("P")
R = TypeVar("R")


def handle_errors(fn: Callable[P, R]) -> Callable[P, R]:
    """Turn a MarmError into one `error: ...` line on stderr and its exit code."""

    @functools.wraps(fn)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return fn(*args, **kwargs)
        except MarmError as exc:
            echo_err(f"error: {exc}")
            raise typer.Exit(exc.exit_code) from None

    return wrapper


def _version(value: bool) -> None:
    if value:
        typer.echo(f"marm-setup {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Print the version.")
    ] = False,
) -> None:
    """Headless MoveIt Setup Assistant."""


def _register() -> None:
    from marm_setup.cli.commands import load_commands

    for name, fn in load_commands():
        app.command(name)(handle_errors(fn))


_register()


def main() -> None:
    app(prog_name="marm-setup")


if __name__ == "__main__":  # pragma: no cover
    main()

"""The Typer app: shared options, the one MarmError -> exit code mapping, command registry.

Each command lives in `marm_setup/cli/commands/<name>.py` and imports heavy modules (coal,
trimesh, scipy) inside its body, so `marm-setup --help` stays fast.
"""

from __future__ import annotations

import functools
import os
import sys
from collections.abc import Callable
from typing import Annotated, ParamSpec, TypeVar

import typer

from marm_setup import __version__
from marm_setup.cli.closed_stdout import tolerate_closed_stdout
from marm_setup.cli.common import echo_err
from marm_setup.errors import MarmError, permission_error, remedy

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


def debugging() -> bool:
    """Whether the running command line has the global `--debug` (its root context's option;
    False outside a command line)."""
    from typer.main import get_current_context

    ctx = get_current_context(silent=True)
    return bool(ctx and ctx.find_root().params.get("debug"))


def handle_errors(fn: Callable[P, R], command: str | None = None) -> Callable[P, R]:
    """Turn a MarmError into one `error: ...` line on stderr (with what to do about what it
    needs, as `command` takes it) and its exit code, and any other exception (a bug) into one
    `error: internal error: ...` line with exit 2; the traceback only with the global `--debug`."""

    @functools.wraps(fn)
    def wrapper(*args: P.args, **kwargs: P.kwargs) -> R:
        try:
            return fn(*args, **kwargs)
        except MarmError as exc:
            echo_err(error_line(exc, command))
            raise typer.Exit(exc.exit_code) from None
        except PermissionError as exc:  # a file or folder of the user's we may not read: input
            echo_err(f"error: {permission_error(exc)}")
            raise typer.Exit(2) from None
        except (typer.Exit, typer.Abort, typer.TyperException):  # click-style exits and usage errors
            raise
        except KeyboardInterrupt:
            echo_err(interrupted_line(command))
            raise typer.Exit(INTERRUPTED) from None
        except Exception as exc:
            if debugging():
                if getattr(exc, "detail", ""):  # e.g. the traceback a worker process sent
                    typer.echo(exc.detail, err=True)  # type: ignore[attr-defined]
                raise
            echo_err(
                f"error: internal error: {internal_error_text(exc)} (please report; --debug shows where)"
            )
            raise typer.Exit(2) from None

    return wrapper


INTERRUPTED = 130  # 128 + SIGINT, as a shell reports a Ctrl-C


def interrupted_line(command: str | None) -> str:
    """What a Ctrl-C left: every writer replaces its file (init and render: the whole package)
    in one atomic rename (render/writer.py, render/switch.py), so nothing is half-written."""
    what = f"marm-setup {command}" if command else "marm-setup"
    return (
        f"error: interrupted (Ctrl-C): {what} stopped; every file it writes was left as it was or "
        "written whole (each write is one atomic rename), nothing half-written"
    )


def error_line(exc: MarmError, command: str | None) -> str:
    """`error: <path>: <element>: <message> (<remedy>)`: the remedy names an option only when
    `command` has it (errors.remedy), so no message sends a user to an option that is not there."""
    fix = remedy(exc.needs, command_options(command) if command else None)
    return f"error: {exc} ({fix})" if fix else f"error: {exc}"


def command_options(command: str) -> frozenset[str]:
    """The options (`--urdf`) and argument names (`URDF`) of `command`, as the app defines them."""
    import typer.main

    click_command = typer.main.get_command(app).commands[command]  # type: ignore[attr-defined]
    return frozenset(
        name for p in click_command.params for name in (*p.opts, *p.secondary_opts, p.metavar or "") if name
    )


def internal_error_text(exc: BaseException) -> str:
    """`RecursionError: maximum recursion depth exceeded`, cut to a readable length."""
    text = f"{type(exc).__name__}: {exc}" if str(exc) else type(exc).__name__
    return text if len(text) <= 300 else text[:297] + "..."


def _version(value: bool) -> None:
    if value:
        typer.echo(f"marm-setup {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Print the version.")
    ] = False,
    debug: Annotated[
        bool, typer.Option("--debug", help="Show the traceback of an internal error (for bug reports).")
    ] = False,
) -> None:
    """Headless MoveIt Setup Assistant. (`--debug` is read from the context: `debugging`.)"""


def _register() -> None:
    from marm_setup.cli.commands import load_commands

    for name, fn in load_commands():
        app.command(name)(handle_errors(fn, name))


_register()


def one_blas_thread() -> None:
    """One OpenBLAS thread unless the user chose: our matrices are 4x4 poses and point sets of a
    few hundred rows, too small for BLAS threads to pay, while starting one per core costs
    about 60 ms of CPU at numpy's import (a third of `--help`'s whole run) and they compete
    with our own worker processes (`--jobs`). Set before numpy is imported."""
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def main() -> None:
    """The console script. A usage error (an unknown option, a bad choice, a missing argument)
    is one `error: ... (see '... --help')` line with exit 2, like every other bad input, instead
    of click's usage block."""
    try:
        os.getcwd()
    except FileNotFoundError:  # every relative path would fail: say why, once
        echo_err(
            "error: the current folder no longer exists (deleted or replaced, e.g. by a write of the "
            "package it was); cd into it again"
        )
        sys.exit(2)
    tolerate_closed_stdout()
    one_blas_thread()
    try:
        code = app(prog_name="marm-setup", standalone_mode=False)
    except typer.TyperException as exc:  # the errors of the click typer bundles: usage errors
        ctx = getattr(exc, "ctx", None)
        if ctx is not None and str(exc) == ctx.get_help():  # no arguments at all: the help, as click
            typer.echo(str(exc), err=True)
        else:
            echo_err(usage_error_line(exc))
        sys.exit(exc.exit_code if isinstance(exc.exit_code, int) and exc.exit_code else 2)
    except typer.Abort as exc:
        if isinstance(exc.__cause__, KeyboardInterrupt):  # a Ctrl-C outside a command's body
            echo_err(interrupted_line(None))
            sys.exit(INTERRUPTED)
        echo_err("error: aborted")
        sys.exit(1)
    sys.exit(code if isinstance(code, int) else 0)


def usage_error_line(exc: Exception) -> str:
    """`error: <what click says> (see '<command> --help')` on one line."""
    message = " ".join(getattr(exc, "format_message", exc.__str__)().split())
    ctx = getattr(exc, "ctx", None)
    hint = f" (see '{ctx.command_path} --help')" if ctx is not None else ""
    return f"error: {message}{hint}"


if __name__ == "__main__":  # pragma: no cover
    main()

"""The one error root and its exit codes; only cli/ turns these into output.

One class per kind of failure: callers (validate's rules, the CLI's exit code) decide by the
type, never by the message text.
"""

from __future__ import annotations

from collections.abc import Collection
from os import PathLike


class MarmError(Exception):
    """A user-facing failure: `error: <path>: <element>: <message>`."""

    exit_code = 2

    def __init__(
        self,
        message: str,
        *,
        path: str | PathLike | None = None,
        element: str | None = None,
        needs: str | None = None,
    ):
        super().__init__(message)
        self.message = message
        self.path = None if path is None else str(path)
        self.element = element
        self.needs = needs  # what would fix it, a key of REMEDIES: the CLI says how its command takes it

    def __str__(self) -> str:
        parts = [p for p in (self.path, self.element) if p]
        return ": ".join([*parts, self.message])

    def __reduce__(self):
        """Picklable whatever a subclass's __init__ takes (errors cross from xacro's child process)."""
        return (_rebuild, (type(self), self.args, dict(self.__dict__)))


def _rebuild(cls: type[MarmError], args: tuple, state: dict) -> MarmError:
    error = cls.__new__(cls)
    Exception.__init__(error, *args)
    error.__dict__.update(state)
    return error


# What to do about an error's `needs`: an option (said only by a command that has it), or a key
# of the setup file the command reads the robot from.
REMEDIES = {
    "--urdf": "pass --urdf URDF",
    "--package-path": "add --package-path DIR",
    "--xacro-arg": "pass --xacro-arg NAME:=VALUE",
    "--setup": "in a SPEC: --setup SPEC",
    "robot.package_paths": "add its folder to robot.package_paths in marm_setup.yaml",
    "robot.xacro_args": "set it in robot.xacro_args of marm_setup.yaml",
}
URDF_ARGUMENT = "give the robot's URDF as the URDF argument"  # the --urdf of a command with a URDF argument


def remedy(needs: str | None, options: Collection[str] | None = None) -> str:
    """How to give what an error needs with a command whose options and argument names are
    `options` (None: every option, as for validate's findings); '' when that command has no way."""
    if needs is None:
        return ""
    if options is None or needs in options or not needs.startswith("-"):
        return REMEDIES[needs]
    return URDF_ARGUMENT if needs == "--urdf" and "URDF" in options else ""


class InputError(MarmError):
    """Bad input: malformed file, unknown name, value out of range, existing output."""


class PackageNotFound(InputError):
    """A ROS package (`package://pkg/...`, `$(find pkg)`) that no package path holds."""

    def __init__(self, message: str, *, package: str, path: str | None = None, element: str | None = None):
        super().__init__(message, path=path, element=element, needs="--package-path")
        self.package = package


class MeshNotFound(InputError):
    """A mesh file that does not exist; `uri` as the URDF wrote it."""

    def __init__(self, message: str, *, uri: str, path: str | None = None, element: str | None = None):
        super().__init__(message, path=path, element=element)
        self.uri = uri


class ConflictError(MarmError):
    """A refused overwrite of a hand-edited file."""


class PlanningFailed(MarmError):
    """The planner could not produce a valid trajectory."""

    exit_code = 1


def permission_error(exc: PermissionError) -> InputError:
    """A file or folder we may not read or write, as the one-line input error naming it."""
    return InputError(f"permission denied ({exc.strerror or 'not allowed'})", path=exc.filename or None)

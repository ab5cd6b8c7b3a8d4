"""The one error root and its exit codes; only cli.py turns these into output."""

from __future__ import annotations

from os import PathLike


class MarmError(Exception):
    """A user-facing failure: `error: <path>: <element>: <message>`."""

    exit_code = 2

    def __init__(self, message: str, *, path: str | PathLike | None = None, element: str | None = None):
        super().__init__(message)
        self.message = message
        self.path = None if path is None else str(path)
        self.element = element

    def __str__(self) -> str:
        parts = [p for p in (self.path, self.element) if p]
        return ": ".join([*parts, self.message])


class InputError(MarmError):
    """Bad input: malformed file, unknown name, value out of range, existing output."""


class ConflictError(MarmError):
    """A refused overwrite of a hand-edited file."""


class PlanningFailed(MarmError):
    """The planner could not produce a valid trajectory."""

    exit_code = 1

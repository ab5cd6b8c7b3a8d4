"""A reader that stops early (`marm-setup init ... | head`) must not stop the command.

When the pipe behind stdout closes, the rest of the output goes to /dev/null and the command
finishes its work (a package is still written whole), as if nobody were reading. Without this a
print raised BrokenPipeError mid-command: an internal error, and the work left undone.
"""

from __future__ import annotations

import os
import sys
from typing import Any, TextIO


class ClosedPipeTolerantStdout:
    """`stream`, except that a write or flush into a closed pipe silences stdout instead."""

    def __init__(self, stream: TextIO):
        self._stream = stream

    def write(self, text: str) -> int:
        try:
            return self._stream.write(text)
        except BrokenPipeError:
            _stdout_to_devnull()
            return len(text)

    def flush(self) -> None:
        try:
            self._stream.flush()
        except BrokenPipeError:
            _stdout_to_devnull()
            self._stream.flush()  # what the buffer held now goes to /dev/null

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def _stdout_to_devnull() -> None:
    """File descriptor 1 becomes /dev/null (Python's own flush at exit then succeeds too)."""
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.__stdout__.fileno() if sys.__stdout__ else 1)
    os.close(devnull)


def tolerate_closed_stdout() -> None:
    """Install the tolerant stdout (once)."""
    if not isinstance(sys.stdout, ClosedPipeTolerantStdout) and sys.stdout is not None:
        sys.stdout = ClosedPipeTolerantStdout(sys.stdout)

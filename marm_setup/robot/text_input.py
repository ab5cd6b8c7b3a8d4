"""A text input file read within the XML bound, its failures as one InputError."""

from __future__ import annotations

from pathlib import Path

from marm_setup import bounded_read
from marm_setup.errors import InputError


def read_text(file: Path, *, shown: str) -> str:
    """The UTF-8 text of `file` (at most XML_BYTES); unreadable, too large or non-UTF-8 content
    is an InputError."""
    try:
        return bounded_read.read_text(file, bounded_read.XML_BYTES, shown=shown)
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=shown) from None
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", path=shown) from None

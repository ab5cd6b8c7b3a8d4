"""Size-checked reading of input files: every file marm-setup reads goes through here.

Robot descriptions, setup files, SRDFs, launch and package files and meshes come from downloads
and pull requests, and a sparse file of 6 GB costs its author nothing. Each read measures the
opened file (fstat: the file read is the file measured, whatever the name points at by then)
against the bound of its kind before reading a byte, and never reads more than that bound, so a
FIFO, a /proc file or a file growing meanwhile cannot get past it. Over the bound is one
`FileTooLarge` line naming the file.
"""

from __future__ import annotations

import os
from os import PathLike

from marm_setup.errors import InputError

MiB = 1 << 20
# The bounds, by kind of file, each far above any real one (the largest URDF in the shared
# real-world packages is 0.1 MB, the largest mesh 3 MB, the largest YAML 20 kB).
XML_BYTES = 64 * MiB  # URDF, xacro, SRDF, launch, package.xml, and what xacro expands them to
YAML_BYTES = 16 * MiB  # YAML files (safe_yaml bounds their nesting and aliases as well)
JSON_BYTES = 16 * MiB  # the writer's own manifest and commit record
MESH_BYTES = 256 * MiB  # mesh files (robot/meshes.py bounds their triangles as well)


class FileTooLarge(InputError):
    """A file over the size bound of its kind."""


def read_bytes(
    path: str | PathLike, limit: int, *, shown: str | None = None, element: str | None = None
) -> bytes:
    """The bytes of the file at `path` when it holds at most `limit` bytes; else FileTooLarge
    naming `shown` (default: `path`). OSError as `open` raises it."""
    with open(path, "rb") as stream:
        size = os.fstat(stream.fileno()).st_size
        if size > limit:
            raise too_large(size, limit, shown=shown or str(path), element=element)
        data = stream.read(limit + 1)
    if len(data) > limit:  # grew while read, or a file whose size fstat does not tell
        raise too_large(None, limit, shown=shown or str(path), element=element)
    return data


def read_text(
    path: str | PathLike, limit: int, *, shown: str | None = None, element: str | None = None
) -> str:
    """The UTF-8 text of the file at `path` (at most `limit` bytes, see `read_bytes`);
    UnicodeDecodeError when it is not UTF-8."""
    return read_bytes(path, limit, shown=shown, element=element).decode("utf-8")


def check_text_size(text: str, limit: int, *, shown: str, element: str | None = None) -> None:
    """FileTooLarge when `text` made in memory (xacro's output) has over `limit` characters."""
    if len(text) > limit:
        raise too_large(len(text), limit, shown=shown, element=element)


def too_large(size: int | None, limit: int, *, shown: str, element: str | None = None) -> FileTooLarge:
    """The one-line refusal: how large the file is (when known) and the bound of its kind."""
    what = f"too large ({format_size(size)}; " if size is not None else "too large ("
    return FileTooLarge(f"{what}at most {format_size(limit)} is read)", path=shown, element=element)


def format_size(n: int) -> str:
    """`6 GiB`, `1.5 MiB`, `512 bytes`."""
    for unit, scale in (("GiB", 1 << 30), ("MiB", MiB), ("KiB", 1 << 10)):
        if n >= scale:
            return f"{n / scale:.1f} {unit}".replace(".0 ", " ")
    return f"{n} bytes"

"""The build folders a whole-package switch makes beside the package, and their records.

A switch builds the new package in `.<pkg>.marm-setup-<token>` next to it. Before that folder
is made, a record file of the same name plus `.record` is made (exclusively), and it goes only
after the folder is gone: a killed run leaves the pair, and the next write removes the folder
its record names. A folder without its record (a user's, whatever its name) is never removed.
"""

from __future__ import annotations

import contextlib
import os
import re
import secrets
from pathlib import Path

from marm_setup.render.safe_fs import remove_tree

RECORD_SUFFIX = ".record"
TOKEN = "[a-z0-9_]+"  # what `new_stage` puts after the prefix (and what mkdtemp did)


def _prefix(real: Path) -> str:
    return f".{real.name}.marm-setup-"


def new_stage(real: Path) -> Path:
    """A new empty build folder beside the package folder `real`, recorded first; OSError when
    the folder holding `real` cannot be written."""
    while True:
        stage = real.parent / f"{_prefix(real)}{secrets.token_hex(6)}"
        record = stage.with_name(stage.name + RECORD_SUFFIX)
        os.close(os.open(record, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW, 0o600))
        try:
            os.mkdir(stage, 0o700)
            return stage
        except FileExistsError:  # not ours: leave it, and its name
            record.unlink()


def drop_stage(stage: Path) -> None:
    """Remove a build folder, then its record (kept while the folder could not be removed)."""
    remove_tree(stage)
    if not os.path.lexists(stage):
        with contextlib.suppress(OSError):
            os.unlink(stage.with_name(stage.name + RECORD_SUFFIX))


def drop_recorded_stages(real: Path) -> None:
    """Remove the build folders beside `real` that a killed run recorded (nothing else)."""
    try:
        names = os.listdir(real.parent)
    except OSError:
        return
    pattern = re.escape(_prefix(real)) + TOKEN + re.escape(RECORD_SUFFIX)
    for name in names:
        if re.fullmatch(pattern, name):
            drop_stage(real.parent / name[: -len(RECORD_SUFFIX)])

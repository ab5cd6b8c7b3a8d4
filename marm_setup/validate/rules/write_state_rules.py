"""The writer's own state in a package: an interrupted marm-setup write (its commit record,
`.marm_setup/commit.json`, still there) leaves some files of the new version staged but not
moved in, so the package on disk mixes the old version and the new one.

Rule `package.half-written` (warning): MoveIt loads whatever is on disk, which may be a mix of
two setups (say an SRDF of the new one with kinematics of the old one); the next write
(`render`, `init --force`, `collisions DIR`) completes the interrupted one first.
"""

from __future__ import annotations

import os
from pathlib import Path

from marm_setup.errors import InputError
from marm_setup.findings import Finding, warning
from marm_setup.render import COMMIT, read_commit


def check_pending_write(root: Path) -> list[Finding]:
    """A warning when the package at `root` has a commit record (see the module docstring)."""
    if not os.path.lexists(root / COMMIT):
        return []
    try:
        record = read_commit(root, str(root))
    except InputError as exc:
        message = f"a commit record marm-setup did not write ({exc.message})"
        return [warning("package.half-written", COMMIT, exc.element or "", message)]
    if record is None:
        return []
    stage, files, _removals = record
    pending = [rel for rel in files if (stage / rel).exists()]
    shown = ", ".join(pending[:5]) + (f" and {len(pending) - 5} more" if len(pending) > 5 else "")
    what = f"{len(pending)} file{'' if len(pending) == 1 else 's'} staged but not moved in ({shown})"
    message = (
        f"an interrupted marm-setup write left this package half-written: {what}; "
        "the next write (marm-setup render) completes it"
    )
    return [warning("package.half-written", COMMIT, "", message, "run marm-setup render on the package")]

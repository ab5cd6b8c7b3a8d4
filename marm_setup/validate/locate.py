"""Where a finding's file is for review tools: a URI relative to the git repository holding the
package (else to the current folder), as GitHub code scanning and GitLab resolve them."""

from __future__ import annotations

import os
from pathlib import Path

from marm_setup.findings import Finding


def repository_root(folder: Path) -> Path | None:
    """The nearest folder at or above `folder` holding `.git` (a folder, or a worktree's file)."""
    here = folder.resolve()
    for candidate in (here, *here.parents):
        if (candidate / ".git").exists():
            return candidate
    return None


def location_base(package: Path) -> Path:
    """What URIs are relative to: the package's repository root, else the current folder."""
    return repository_root(package) or Path.cwd().resolve()


def finding_path(finding: Finding, package: Path) -> Path:
    """The file a finding names: relative to the package, or the path the user gave (absolute, or
    relative to the current folder) for a file outside it; the package's package.xml (else the
    package) for a finding on the package as a whole."""
    if not finding.file:
        manifest = package / "package.xml"
        return manifest if manifest.is_file() else package
    given = Path(finding.file)
    if given.is_absolute():
        return given
    inside = package / given
    return inside if inside.exists() or not given.exists() else given


def finding_uri(finding: Finding, package: Path, base: Path) -> str:
    """`finding_path` relative to `base` with `/` separators; a file URI when it lies outside `base`."""
    given = Path(os.path.abspath(finding_path(finding, package)))
    path = given.parent.resolve() / given.name  # as `base`, without following the file's own link
    try:
        return path.relative_to(base).as_posix()
    except ValueError:
        return path.as_uri()

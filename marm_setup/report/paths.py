"""Paths as the page shows them: relative to the package folder, never the machine's folders.

A page is shared (mailed, attached to a review): `/tmp/...` or `/home/alice/...` means nothing
to its reader. Inside the package's parent folder (the package, its siblings in a workspace's
`src`) a path is shown relative to the package (`config/x.srdf`, `../x_description/urdf/x.urdf`);
a file of another ROS package as `package://name/rel`; anything else by its last two parts
(`…/shims/python3`).
"""

from __future__ import annotations

import dataclasses
import os
import re
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from marm_setup.validate import Validation

PackageOf = Callable[[Path], "str | None"]  # folder -> the ROS package it holds (package.xml <name>)

ABSOLUTE = re.compile(r"(?<![\w./~+@-])/(?:[\w.+@~-]+/)*[\w.+@~-]+")  # a POSIX path in free text
TAIL_PARTS = 2  # parts kept of a path outside the workspace and any ROS package


def page_path(path: str | Path, package_root: Path, package_of: PackageOf) -> str:
    """`path` (absolute, or relative to the working directory) as the page shows it (module doc);
    `package_of(folder)` the ROS package a folder holds (its package.xml `<name>`), or None."""
    file = Path(os.path.abspath(path))
    root = Path(os.path.abspath(package_root))
    if file.is_relative_to(root.parent):
        return Path(os.path.relpath(file, root)).as_posix()
    for folder in file.parents:
        name = package_of(folder) if folder != folder.parent else None
        if name:
            return f"package://{name}/{file.relative_to(folder).as_posix()}"
    return "…/" + "/".join(file.parts[-TAIL_PARTS:])


def relative_text(text: str, package_root: Path, package_of: PackageOf) -> str:
    """`text` with every absolute path in it that names a folder of this machine shown as
    `page_path` shows it (a ROS name such as `/robot_description` or `/move_group/x` is kept)."""

    def shown(m: re.Match[str]) -> str:
        path = m.group(0)
        top = path.split("/")[1]
        machine = path.count("/") > 1 and Path("/", top).is_dir()
        return page_path(path, package_root, package_of) if machine else path

    return ABSOLUTE.sub(shown, text)


def relative_content(content: dict, package_root: Path, package_of: PackageOf) -> dict:
    """The page's content (`content.page_content`) with its people-readable text (the summary,
    the findings, the states' titles and notes) free of absolute paths."""

    def fix(text: str | None) -> str | None:
        return None if text is None else relative_text(text, package_root, package_of)

    out = dict(content)
    out["summary"] = {k: fix(v) if isinstance(v, str) else v for k, v in content["summary"].items()}
    keys = ("file", "element", "message", "hint")
    out["findings"] = [{**f, **{k: fix(f[k]) for k in keys if k in f}} for f in content["findings"]]
    out["states"] = [{**s, "title": fix(s["title"]), "note": fix(s["note"])} for s in content["states"]]
    return out


def with_page_urdf(
    validation: Validation, package_root: Path, package_of: PackageOf, urdf: Path | None
) -> Validation:
    """`validation` with its robot description named as the page shows it (the summary line
    otherwise names it as typed, relative to the working directory)."""
    if urdf is None:
        return validation
    return dataclasses.replace(validation, urdf=page_path(urdf, package_root, package_of))

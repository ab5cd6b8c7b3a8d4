"""Launch XML files (ROS 1 roslaunch and ROS 2 launch_xml), parsed once with lxml."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error
from marm_setup.package.substitution import Scope, SubstitutionError, substitute, truth

if TYPE_CHECKING:
    from lxml import etree

LAUNCH_SUFFIXES = (".launch", ".xml")


@dataclass(frozen=True, eq=False)
class LaunchXml:
    """One launch XML file: its package-relative path and root element (None when unreadable,
    with the finding saying why)."""

    file: str
    root: etree._Element | None
    problem: Finding | None = None


def parse_launch(path: Path, rel: str) -> LaunchXml:
    from lxml import etree

    from marm_setup.bounded_read import XML_BYTES, FileTooLarge, read_bytes
    from marm_setup.robot import xml_syntax_message

    try:
        data = read_bytes(path, XML_BYTES, shown=rel)
        root = etree.fromstring(data, etree.XMLParser(remove_comments=True), base_url=str(path))
        return LaunchXml(rel, root)
    except etree.XMLSyntaxError as exc:
        message = f"not well-formed XML: {xml_syntax_message(exc)}"
        return LaunchXml(rel, None, error("launch.malformed", rel, f"line {exc.lineno or 0}", message))
    except OSError as exc:
        return LaunchXml(rel, None, error("launch.malformed", rel, "", f"cannot read: {exc}"))
    except FileTooLarge as exc:
        return LaunchXml(rel, None, error("launch.malformed", rel, "", f"cannot read: {exc.message}"))


def launch_file_names(root: Path) -> tuple[str, ...]:
    """`launch/**/*.launch` and `*.xml` (ROS 1 and ROS 2 XML launch files), sorted."""
    folder = root / "launch"
    if not folder.is_dir():
        return ()
    files = [p for p in folder.rglob("*") if p.is_file() and p.suffix in LAUNCH_SUFFIXES]
    return tuple(sorted(p.relative_to(root).as_posix() for p in files))


def python_launch_names(root: Path) -> tuple[str, ...]:
    """`launch/**/*.launch.py` (and other `.py` there), sorted."""
    folder = root / "launch"
    if not folder.is_dir():
        return ()
    return tuple(sorted(p.relative_to(root).as_posix() for p in folder.rglob("*.py") if p.is_file()))


def package_relative(path: str, root: Path) -> str | None:
    """`path` (absolute, or relative to `root`) relative to the package, or None outside it."""
    rel = os.path.relpath(os.path.normpath(os.path.join(str(root), path)), root)
    return None if rel.startswith("..") else rel.replace(os.sep, "/")


def substituted(text: str | None, scope: Scope) -> str | None:
    """`text` with its `$(...)` evaluated in `scope`, or None (no text, or not evaluable)."""
    if text is None:
        return None
    try:
        return substitute(text, scope)
    except SubstitutionError:
        return None


def package_file(attr: str | None, scope: Scope, root: Path) -> str | None:
    """The package-relative path an attribute names, or None (outside the package, unresolvable)."""
    text = substituted(attr, scope) if attr else None
    return package_relative(text, root) if text else None


def condition(elem: etree._Element, scope: Scope) -> bool | None:
    """True / False from an element's `if` / `unless` (roslaunch and launch_xml read them alike),
    None when it cannot be decided (an unknown arg, a value that is no truth value)."""
    for attr, wanted in (("if", True), ("unless", False)):
        text = elem.get(attr)
        if text is None:
            continue
        value = truth(substituted(text, scope) or "")
        if value is None:
            return None
        if value is not wanted:
            return False
    return True

"""Porting what surrounds the settings: package metadata (package.xml, `.setup_assistant`), the
robot description's location, and every file of the source package the port does not read
(each reported, so nothing goes silently)."""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from marm_setup.package import MoveItPackage
from marm_setup.port.pipelines import PIPELINE_FILE
from marm_setup.port.port_log import PortLog, where
from marm_setup.ros import Target
from marm_setup.setup import Author, RobotSource

LICENSE = "BSD-3-Clause"  # templates/<target>/package.xml.j2
METADATA_TAGS = ("version", "description", "url", "author")


def robot_source(pkg: MoveItPackage, out: Path, user_paths: tuple[Path, ...], log: PortLog) -> RobotSource:
    """The URDF relative to the new package, the package's xacro args and the folders holding the
    description's packages (the user's --package-path, then marm_setup.yaml's)."""
    from marm_setup.package import marm_package_paths
    from marm_setup.render import robot_reference

    paths = [*user_paths, *marm_package_paths(pkg.root, pkg.marm_setup)]
    urdf, rel_list = robot_reference(
        pkg.description_file, out, list(dict.fromkeys(_relative(p, out) for p in paths))
    )
    log.carried("robot.urdf", pkg.urdf_origin, f"{urdf} (relative to the new package)", "robot")
    for name, value in pkg.xacro_args:
        log.carried(f"robot.xacro_args.{name}", pkg.urdf_origin, value, "robot")
    return RobotSource(urdf=urdf, xacro_args=tuple(pkg.xacro_args), package_paths=tuple(rel_list))


def _relative(path: Path, base: Path) -> str:
    return Path(os.path.relpath(Path(path).resolve(), base.resolve())).as_posix()


def port_author(pkg: MoveItPackage, log: PortLog) -> Author:
    """`.setup_assistant`'s author (`CONFIG`, or MoveIt 2's `package_settings`), else package.xml's
    first maintainer, else marm_setup.yaml's."""
    sa = pkg.setup_assistant
    if sa is not None and sa.author_name and sa.author_email:
        log.carried("author", f".setup_assistant: {sa.author_key}", f"{sa.author_name} <{sa.author_email}>")
        return Author(sa.author_name, sa.author_email)
    people = pkg.package_xml.maintainers if pkg.package_xml is not None else ()
    if people:
        (name, email), *rest = people
        log.carried("author", "package.xml: maintainer", f"{name} <{email}>")
        for n, e in rest:
            log.dropped("author", "package.xml: maintainer", f"{n} <{e}>: marm_setup.yaml holds one author")
        return Author(name, email)
    if pkg.marm_setup is not None and pkg.marm_setup.author is not None:
        return Author(*pkg.marm_setup.author)
    log.changed("author", "package.xml", "no maintainer found: the default author is written")
    return Author()


def report_metadata(pkg: MoveItPackage, name: str, target: Target, log: PortLog) -> None:
    """Package name, licence, version, description, urls and dependencies."""
    xml = pkg.package_xml
    src = xml.file if xml is not None else "package.xml"
    if name == pkg.name:
        log.carried("package_name", src, name)
    else:
        log.changed("package_name", src, f"{pkg.name} -> {name} (--name)")
    if xml is None or not xml.parsed:
        return
    for text in xml.licenses:
        if text == LICENSE:
            log.carried("license", src, text)
        else:
            log.changed(
                "license", src, f"{text} -> {LICENSE}: marm_setup.yaml has no licence key; edit package.xml"
            )
    for tag in METADATA_TAGS:
        for found, text in xml.metadata:
            if found == tag:
                log.dropped(
                    f"package.xml {tag}",
                    src,
                    f"{_short(text)!r}: the new package.xml is generated; copy it by hand",
                )
    if xml.dependencies:
        detail = f"{len(xml.dependencies)} dependencies replaced by the {target} package's own list"
        log.changed("package.xml dependencies", src, detail)


def _short(text: str) -> str:
    return text if len(text) <= 60 else text[:57] + "..."


def report_leftovers(pkg: MoveItPackage, read: set[str], log: PortLog) -> None:
    """Every file of the source package the port did not read, with what to do about it."""
    for rel in pkg.files:
        if rel in read or PIPELINE_FILE.match(rel):
            continue
        log.add(*_leftover(rel))


# (what a file is, by its path) -> (status, setting, detail, area) of its report line; the first
# that matches, else `file` dropped.
LEFTOVERS: tuple[tuple[Callable[[str, str], bool], tuple[str, str, str, str]], ...] = (
    (
        lambda rel, name: rel.startswith("launch/"),
        (
            "todo",
            "launch",
            "launch files are written anew for the target; port custom nodes and args by hand",
            "files",
        ),
    ),
    (
        lambda rel, name: name.startswith("sensors") or "sensor" in name,
        (
            "dropped",
            "sensors",
            "not read as move_group's 3D sensors (no launch file loads it): copy its settings by hand",
            "perception",
        ),
    ),
    (
        lambda rel, name: rel == "CMakeLists.txt" or rel.startswith(".marm_setup/"),
        ("changed", "", "written anew for the target", "files"),
    ),
    (
        lambda rel, name: name.endswith((".rviz", ".rviz2")),
        ("changed", "rviz", "the new package has its own RViz configuration", "files"),
    ),
    (
        lambda rel, name: name.endswith(".ros2_control.xacro"),
        (
            "todo",
            "ros2_control",
            "the new package writes mock hardware: port this hardware description by hand",
            "driver",
        ),
    ),
    (
        lambda rel, name: rel.startswith("config/") and name.endswith(".urdf.xacro"),
        (
            "changed",
            "robot description wrapper",
            "the new package wraps the robot description in its own",
            "robot",
        ),
    ),
    (
        lambda rel, name: "cartesian_limits" in name,
        (
            "changed",
            "cartesian_limits",
            "the target's Pilz cartesian limits are written with MoveIt's defaults",
            "limits",
        ),
    ),
)


def _leftover(rel: str) -> tuple[str, str, str, str, str]:
    """(status, setting, source, detail, area) of a file the port did not read."""
    name = Path(rel).name
    for matches, (status, setting, detail, area) in LEFTOVERS:
        if matches(rel, name):
            return status, setting or rel, rel, detail, area
    return "dropped", "file", rel, "not read by the port: copy or port it by hand if it matters", "files"


def read_files(pkg: MoveItPackage) -> set[str]:
    """The package files the port reads: every file the model read a kind from, the SRDF,
    package.xml, `.setup_assistant` and marm_setup.yaml."""
    names = {"package.xml", ".setup_assistant", "marm_setup.yaml", *(s.file for s in pkg.sources)}
    names.update(c.where.file for c in pkg.alt_moveit_controllers)
    names.update(s.where.file for s in pkg.servo)
    return names


def report_marm_setup(pkg: MoveItPackage, log: PortLog) -> None:
    """marm_setup.yaml keys no rendered file holds (the collision sampling, default_acceleration,
    the ros1 driver)."""
    marm = pkg.marm_setup
    for key in marm.kept_keys if marm is not None else ():
        log.carried(key, where("marm_setup.yaml", key), "kept from the source's marm_setup.yaml")

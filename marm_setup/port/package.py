"""Porting what surrounds the settings: package metadata (package.xml, `.setup_assistant`), the
robot description's location, the planning pipelines in use, and every file of the source
package the port does not read (each reported, so nothing goes silently)."""

from __future__ import annotations

import os
import re
from pathlib import Path
from typing import Any

from marm_setup.bounded_read import XML_BYTES, YAML_BYTES, FileTooLarge, read_bytes, read_text
from marm_setup.port.report import PortLog, where
from marm_setup.safe_yaml import load_yaml
from marm_setup.setup.model import Author, RobotSource
from marm_setup.validate.discovery import ConfigPackage

# Pipelines each target's templates write (templates/<target>/config and launch).
TARGET_PIPELINES = {"ros1": ("ompl",), "ros2": ("ompl", "pilz_industrial_motion_planner")}
PIPELINE_FILE = re.compile(r"^(?:config|launch)/([a-z0-9_]+?)_planning(?:_pipeline\.launch\.xml|\.yaml)$")
KNOWN_PIPELINES = ("ompl", "chomp", "stomp", "lerp", "trajopt", "pilz_industrial_motion_planner", "pilz")
LICENSE = "BSD-3-Clause"  # templates/<target>/package.xml.j2
MARM_KEYS = ("collision", "default_acceleration", "author")


def robot_source(pkg: ConfigPackage, out: Path, user_paths: tuple[Path, ...], log: PortLog) -> RobotSource:
    """The URDF relative to the new package, the package's xacro args and the folders holding the
    description's packages (the user's --package-path, then marm_setup.yaml's)."""
    from marm_setup.render.package import robot_reference
    from marm_setup.validate.sources import marm_package_paths

    marm = pkg.marm_setup.data if pkg.marm_setup is not None else None
    paths = [*user_paths, *marm_package_paths(pkg.root, marm)]
    urdf, rel_list = robot_reference(
        Path(pkg.urdf), out, list(dict.fromkeys(_relative(p, out) for p in paths))
    )
    rel_paths = tuple(rel_list)
    log.carried("robot.urdf", pkg.urdf_origin, f"{urdf} (relative to the new package)")
    for name, value in pkg.xacro_args:
        log.carried(f"robot.xacro_args.{name}", pkg.urdf_origin, value)
    return RobotSource(urdf=urdf, xacro_args=tuple(pkg.xacro_args), package_paths=rel_paths)


def _relative(path: Path, base: Path) -> str:
    return Path(os.path.relpath(Path(path).resolve(), base.resolve())).as_posix()


def port_author(pkg: ConfigPackage, log: PortLog) -> Author:
    """`.setup_assistant` CONFIG author, else package.xml's first maintainer, else marm_setup.yaml's."""
    sa = _setup_assistant_config(pkg)
    name, email = sa.get("author_name"), sa.get("author_email")
    if name and email:
        log.carried("author", ".setup_assistant: CONFIG", f"{name} <{email}>")
        return Author(str(name), str(email))
    people = _package_people(pkg)
    if people:
        (name, email), *rest = people
        log.carried("author", "package.xml: maintainer", f"{name} <{email}>")
        for n, e in rest:
            log.dropped("author", "package.xml: maintainer", f"{n} <{e}>: marm_setup.yaml holds one author")
        return Author(name, email)
    marm = pkg.marm_setup.data if pkg.marm_setup is not None else {}
    author = marm.get("author") if isinstance(marm, dict) else None
    if isinstance(author, dict) and author.get("name") and author.get("email"):
        return Author(str(author["name"]), str(author["email"]))
    log.changed("author", "package.xml", "no maintainer found: the default author is written")
    return Author()


def _setup_assistant_config(pkg: ConfigPackage) -> dict:
    import yaml

    file = pkg.root / ".setup_assistant"
    try:
        data = load_yaml(read_text(file, YAML_BYTES)) if file.is_file() else None
    except (OSError, UnicodeDecodeError, yaml.YAMLError, FileTooLarge):
        return {}
    config = data.get("moveit_setup_assistant_config") if isinstance(data, dict) else None
    entry = config.get("CONFIG", config.get("config")) if isinstance(config, dict) else None
    return entry if isinstance(entry, dict) else {}


def _package_xml(pkg: ConfigPackage) -> Any:
    from lxml import etree

    if pkg.package_xml is None:
        return None
    try:
        return etree.fromstring(read_bytes(pkg.path(pkg.package_xml), XML_BYTES))
    except (OSError, etree.XMLSyntaxError, FileTooLarge):
        return None


def _package_people(pkg: ConfigPackage) -> list[tuple[str, str]]:
    root = _package_xml(pkg)
    if root is None:
        return []
    return [
        ((e.text or "").strip(), e.get("email", "").strip())
        for e in root.iterchildren("maintainer")
        if (e.text or "").strip() and e.get("email")
    ]


def report_metadata(pkg: ConfigPackage, name: str, target: str, log: PortLog) -> None:
    """Package name, licence, version, description, urls and dependencies."""
    src = pkg.package_xml or "package.xml"
    if name == pkg.name:
        log.carried("package_name", src, name)
    else:
        log.changed("package_name", src, f"{pkg.name} -> {name} (--name)")
    root = _package_xml(pkg)
    if root is None:
        return
    licenses = [(e.text or "").strip() for e in root.iterchildren("license")]
    for text in licenses:
        if text == LICENSE:
            log.carried("license", src, text)
        else:
            log.changed(
                "license", src, f"{text} -> {LICENSE}: marm_setup.yaml has no licence key; edit package.xml"
            )
    for tag in ("version", "description", "url", "author"):
        for e in root.iterchildren(tag):
            log.dropped(
                f"package.xml {tag}", src, f"{_text(e)!r}: the new package.xml is generated; copy it by hand"
            )
    deps = sorted({(e.text or "").strip() for e in root if str(e.tag).endswith("depend")})
    if deps:
        log.changed(
            "package.xml dependencies",
            src,
            f"{len(deps)} dependencies replaced by the {target} package's own list",
        )


def _text(elem: Any) -> str:
    text = " ".join("".join(elem.itertext()).split())
    return text if len(text) <= 60 else text[:57] + "..."


def report_pipelines(pkg: ConfigPackage, target: str, log: PortLog) -> None:
    """The planning pipelines the source package configures, and whether the new one has them."""
    found: dict[str, list[str]] = {}
    for rel in _files(pkg.root):
        m = PIPELINE_FILE.match(rel)
        if m and m.group(1) in KNOWN_PIPELINES + ("ompl-chomp",):
            found.setdefault(m.group(1), []).append(rel)
    if pkg.ompl is not None:
        found.setdefault("ompl", []).append(pkg.ompl.file)
    ours = TARGET_PIPELINES[target]
    for name, files in sorted(found.items()):
        src = ", ".join(sorted(set(files)))
        if name in ours or (name == "pilz" and "pilz_industrial_motion_planner" in ours):
            log.carried(f"planning_pipelines.{name}", src, "the new package configures it")
        else:
            log.dropped(
                f"planning_pipelines.{name}",
                src,
                f"marm-setup writes the {', '.join(ours)} pipeline{'s' if len(ours) > 1 else ''} for {target}; "
                f"configure {name} by hand",
            )


def report_leftovers(pkg: ConfigPackage, read: set[str], log: PortLog) -> None:
    """Every file of the source package the port did not read, with what to do about it."""
    for rel in _files(pkg.root):
        if rel in read or PIPELINE_FILE.match(rel):
            continue
        log.add(*_leftover(rel))


def _leftover(rel: str) -> tuple[str, str, str, str]:
    name = Path(rel).name
    if rel.startswith("launch/"):
        return (
            "todo",
            "launch",
            rel,
            "launch files are written anew for the target; port custom nodes and args by hand",
        )
    if name.startswith("sensors") or "sensor" in name:
        return (
            "dropped",
            "sensors",
            rel,
            "3D perception settings: marm-setup writes none; copy them by hand",
        )
    if rel == "CMakeLists.txt" or rel.startswith(".marm_setup/"):
        return ("changed", rel, rel, "written anew for the target")
    if name.endswith((".rviz", ".rviz2")):
        return ("changed", "rviz", rel, "the new package has its own RViz configuration")
    if name.endswith(".ros2_control.xacro"):
        return (
            "todo",
            "ros2_control",
            rel,
            "the new package writes mock hardware: port this hardware description by hand",
        )
    if rel.startswith("config/") and name.endswith(".urdf.xacro"):
        return (
            "changed",
            "robot description wrapper",
            rel,
            "the new package wraps the robot description in its own",
        )
    if "cartesian_limits" in name:
        return (
            "changed",
            "cartesian_limits",
            rel,
            "the target's Pilz cartesian limits are written with MoveIt's defaults",
        )
    return ("dropped", "file", rel, "not read by the port: copy or port it by hand if it matters")


def _files(root: Path) -> list[str]:
    out = []
    for p in sorted(root.rglob("*")):
        rel = p.relative_to(root).as_posix()
        if p.is_file() and not rel.startswith(".git/") and "__pycache__" not in rel:
            out.append(rel)
    return out


def read_files(pkg: ConfigPackage) -> set[str]:
    """The package files the port reads (its sections, SRDF, package.xml, .setup_assistant)."""
    names = {"package.xml", ".setup_assistant", "marm_setup.yaml"}
    if pkg.srdf_path:
        names.add(pkg.srdf_path)
    for field in (
        "kinematics",
        "joint_limits",
        "ompl",
        "moveit_controllers",
        "fake_controllers",
        "ros2_controllers",
        "ros_controllers",
        "arbotix",
        "initial_positions",
    ):
        section = getattr(pkg, field)
        if section is not None:
            names.add(section.file)
    names.update(s.file for s in pkg.alt_moveit_controllers)
    return names


def report_marm_setup(pkg: ConfigPackage, log: PortLog) -> dict:
    """marm_setup.yaml keys no rendered file holds (the collision sampling, default_acceleration,
    the ros1 driver)."""
    data = pkg.marm_setup.data if pkg.marm_setup is not None else None
    if not isinstance(data, dict):
        return {}
    out = {k: data[k] for k in ("collision", "default_acceleration", "driver") if k in data}
    for key in out:
        log.carried(key, where("marm_setup.yaml", key), "kept from the source's marm_setup.yaml")
    return out

"""The ROS packages the port's robot description lives in and uses: each must exist, as a
package, built for the target's ROS, holding the file the new package includes. What does not
is a `todo` of the port report naming the package and what to do (the new package depends on
it: package.xml `exec_depend`, `$(find pkg)` in its launch files and wrapper xacro)."""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

from marm_setup.port.port_log import PortLog
from marm_setup.robot import RobotModel
from marm_setup.ros import Target

# The build type a target's workspace builds: colcon builds no catkin package into a ROS 2
# install (ament_index has no entry, so `$(find-pkg-share pkg)` fails), catkin no ament one.
BUILT_FOR = {Target.ROS1: "catkin", Target.ROS2: "ament"}


@dataclass(frozen=True, slots=True)
class DescriptionPackage:
    """A package the description needs: where the port found it, how, and the file the new
    package includes from it (None: only meshes or includes of the description)."""

    name: str
    folder: Path
    has_manifest: bool
    included: str | None = None


def description_packages(urdf: Path, robot: RobotModel) -> list[DescriptionPackage]:
    """The package holding the URDF (with the path inside it) and every package the description
    used (`$(find)`, `package://`), by name."""
    from marm_setup.render import description_package

    found = {
        name: DescriptionPackage(name, Path(path), how == "package.xml") for name, path, how in robot.packages
    }
    own = description_package(urdf)
    if own is not None:
        folder = urdf.resolve()
        for _ in Path(own[1]).parts:
            folder = folder.parent
        found[own[0]] = DescriptionPackage(own[0], folder, True, own[1])
    return [found[name] for name in sorted(found)]


def report_description_packages(
    packages: list[DescriptionPackage],
    target: Target,
    distro: str,
    log: PortLog,
    environ: Mapping[str, str],
    shown: Callable[[Path], str],
) -> None:
    """A `todo` for each package that is no ROS package, is built for the other ROS, or whose
    target-ROS install (the sourced environment's) lacks the file the new package includes;
    `shown` gives a folder as the user would type it."""
    for p in packages:
        problem = _problem(p, target, distro, environ, shown(p.folder))
        if problem is not None:
            log.todo(f"description package {p.name}", shown(p.folder), problem, "robot")


def _problem(
    p: DescriptionPackage, target: Target, distro: str, environ: Mapping[str, str], folder: str
) -> str | None:
    """What keeps the new package's launch from the package: the sourced target install (which
    its launch will use) lacks the included file; else the port's copy is no package or is built
    for the other ROS."""
    installed = _installed(p.name, target, environ)
    if installed is not None:
        if p.included and not (installed / p.included).is_file():
            return (
                f"the sourced {distro} install ({installed}) has no {p.included}, which the new package "
                f"includes: its launch fails; build {p.name} from {folder} in your workspace, or point "
                "robot.urdf at that install's description"
            )
        return None
    if not p.has_manifest:
        return (
            f"found only as a folder named {p.name} (no package.xml): no ROS workspace builds it, so the "
            f"new package's $(find {p.name}) fails at launch; make it a package or install {p.name} for {distro}"
        )
    build = _build_type(p.folder)
    if build is not None and build != BUILT_FOR[target]:
        file = f" and check it holds {p.included}" if p.included else ""
        return (
            f"a {build} package: it is not built for {distro}, so the new package's $(find {p.name}) fails "
            f"at launch; install its {distro} release (e.g. ros-{distro}-{p.name.replace('_', '-')}){file}, "
            f"or port it to {BUILT_FOR[target]}"
        )
    return None


def _build_type(folder: Path) -> str | None:
    """ament or catkin from the folder's package.xml (package/setup_files.py PackageXml.build_type)."""
    from marm_setup.package import read_package_xml

    try:
        text = (folder / "package.xml").read_text(encoding="utf-8", errors="replace")
    except OSError:
        return None
    return read_package_xml("package.xml", text).build_type


def _installed(name: str, target: Target, environ: Mapping[str, str]) -> Path | None:
    """The package's folder in the sourced target ROS (AMENT_PREFIX_PATH's share/ for ROS 2,
    ROS_PACKAGE_PATH for ROS 1), where its launch files will find it; None if not sourced there."""
    if target == Target.ROS2:
        prefixes = environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep)
        folders = [Path(p) / "share" / name for p in prefixes if p]
    else:
        folders = [Path(p) / name for p in environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    return next((f for f in folders if (f / "package.xml").is_file()), None)

"""Where a config package's robot description and SRDF are, and which ROS it targets.

URDF: `--urdf`, else `marm_setup.yaml`'s, else the file MoveItConfigsBuilder loads (a launch
file's `.robot_description(file_path)`, else `config/<robot>.urdf.xacro`, paired by the builder's
or the SRDF's robot name), else `.setup_assistant`'s, else the one a launch file of another
package sets when it starts MoveIt with this package (`package.bringup`). SRDF: `--srdf`, `marm_setup.yaml`'s, the
builder's `.robot_description_semantic(file_path)`, the one a launch file sets as `*_semantic`
(with the xacro args it passes: what move_group loads), `.setup_assistant`'s,
`config/<robot>.srdf` of the builder, then by name among `config/*.srdf`, `srdf/*.srdf`, their
`.srdf.xacro` forms and those one folder below `config/` (`config/srdf/<robot>.srdf`, where a
launch computes the file from its args at run time): a `.srdf.xacro` another of them includes
is a macro library (xacro loads it only through its includer), and one whose `<robot name>` is
the user's robot (`--urdf`, `--srdf`) comes first.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.findings import Finding, warning
from marm_setup.package.setup_files import MarmSetupFile, PackageXml, SetupAssistantFile
from marm_setup.ros import Target
from marm_setup.untrusted import relative_inside

if TYPE_CHECKING:
    from marm_setup.package.bringup import BringupRobot

SRDF_GLOBS = (
    "config/*.srdf",
    "srdf/*.srdf",
    "config/*.srdf.xacro",
    "srdf/*.srdf.xacro",
    "config/*/*.srdf",
    "config/*/*.srdf.xacro",
)
MARM_MOVEIT_YAML = "config/moveit.yaml"


@dataclass(frozen=True, slots=True)
class Description:
    """The robot description: its file (None when only the run time gives it, or when the file
    named cannot be read: `origin` says why), where that choice came from, its xacro args."""

    urdf: Path | None
    origin: str
    xacro_args: tuple[tuple[str, str], ...]
    unreadable: bool = False  # named, but its package or file is not there (a finding says so)
    bringup: BringupRobot | None = None  # the bringup launch file of another package it came from


def detect_target(root: Path, package_xml: PackageXml | None, marm: MarmSetupFile | None) -> Target:
    """ros2 for ament packages, ros1 for catkin; falls back on marm_setup.yaml and file names."""
    build = package_xml.build_type if package_xml is not None else None
    if build is not None:
        return Target.ROS2 if build == "ament" else Target.ROS1
    if marm is not None and marm.target is not None:
        return marm.target
    ros2_files = ("config/moveit_controllers.yaml", "config/ros2_controllers.yaml", MARM_MOVEIT_YAML)
    return Target.ROS2 if any((root / f).is_file() for f in ros2_files) else Target.ROS1


SrdfChoice = tuple[str, tuple[tuple[str, str], ...]]  # (relative path, xacro args)
# How an SRDF only its name chose is shown (validate/srdf_fit.py refits it to the robot loaded).
SRDF_GUESSED = "chosen by its name among the package's SRDFs (no file or launch names one statically)"


def choose_srdf(
    root: Path,
    marm: MarmSetupFile | None,
    sa: SetupAssistantFile | None,
    named: tuple[SrdfChoice | None, SrdfChoice | None, str | None],
    problems: list[Finding],
    refused: Callable[[str, str, str], bool] = lambda _rel, _file, _element: False,
    robots: tuple[str, ...] = (),
) -> tuple[str | None, tuple[tuple[str, str], ...], bool]:
    """(relative SRDF path or None, its xacro args, whether only its name chose it: no file or
    launch names it) in the order of the module docstring;
    `named` is (the builder's explicit file, the launch files' `*_semantic` file, the builder's
    default). A `.setup_assistant` naming a missing SRDF is an error in `problems`: the Setup
    Assistant cannot load the package. `refused(rel, file, element)` says whether a path that
    `file`'s `element` names leads outside the package (then it is not a candidate); `robots`
    are the robot names the user's --urdf / --srdf give."""
    builder_file, launch_file, builder_default = named
    candidates: list[SrdfChoice] = []
    if marm is not None and marm.robot_name:
        rel = f"config/{marm.robot_name}.srdf"
        if not refused(rel, "marm_setup.yaml", "robot_name"):
            candidates.append((rel, ()))
    if builder_file is not None:
        candidates.append(builder_file)
    if launch_file is not None:
        candidates.append(launch_file)
    if sa is not None and sa.srdf_path is not None:
        if refused(sa.srdf_path, ".setup_assistant", f"{sa.srdf_key}.relative_path"):
            pass
        elif (root / sa.srdf_path).is_file():
            candidates.append((sa.srdf_path, ()))
        else:
            problems.append(_missing_sa_srdf(sa))
    if builder_default is not None:
        candidates.append((builder_default, ()))
    named_count = len(candidates)
    candidates += [(rel, ()) for rel in srdfs_by_name(root, robots)]
    found = (
        (*c, i >= named_count)
        for i, c in enumerate(candidates)
        if (root / c[0]).is_file() and not refused(c[0], c[0], "")
    )
    return next(found, (None, (), False))


def srdfs_by_name(root: Path, robots: tuple[str, ...] = ()) -> list[str]:
    """The package's SRDFs found by name (SRDF_GLOBS, in order), but the `.srdf.xacro` macro
    libraries another of them includes (xacro:include), those of a robot in `robots` first."""
    from marm_setup.package.srdf_file import srdf_includes, srdf_robot_name

    found = [p.relative_to(root).as_posix() for pattern in SRDF_GLOBS for p in sorted(root.glob(pattern))]
    included = {rel for top in found for rel in srdf_includes(root, top)}
    tops = [rel for rel in found if rel not in included] or found
    return sorted(tops, key=lambda rel: srdf_robot_name(root, rel) not in robots) if robots else tops


def _missing_sa_srdf(sa: SetupAssistantFile) -> Finding:
    """Only the Setup Assistant reads `.setup_assistant` (moveit/moveit `moveit_setup_assistant/
    src/tools/moveit_config_data.cpp` `inputSetupAssistantYAML`); move_group takes the SRDF its
    launch files load, so a stale name there (often beside a `.srdf.xacro`) is a warning."""
    msg = (
        f"names the SRDF '{sa.srdf_path}', which does not exist: the Setup Assistant cannot load this "
        "package (move_group never reads this file)"
    )
    return warning("srdf.missing", ".setup_assistant", f"{sa.srdf_key}.relative_path", msg, "fix the path")


def find_description(
    root: Path,
    shown: str,
    name: str,
    given: tuple[Path | None, tuple[tuple[str, str], ...]],
    marm: MarmSetupFile | None,
    sa: SetupAssistantFile | None,
    paths: tuple[Path, ...],
    robot_names: tuple[str | None, ...],
    builder: tuple[str | None, tuple[tuple[str, str], ...] | None, str],
    refused: Callable[[str, str, str], bool] = lambda _rel, _file, _element: False,
    launched_by: Callable[[], Description | None] = lambda: None,
) -> Description:
    """The robot description (see the module docstring); InputError when there is none, except
    for a ROS 2 package whose Python launch files take it at run time (`RUNTIME_ONLY`).
    `given` is (--urdf, --xacro-arg pairs); `builder` the builder's (explicit file, mappings,
    where it was named); `refused` as for `choose_srdf` (a package's own description file
    leading outside it is not taken); `launched_by` the description a bringup launch file of
    another package gives when the package names none itself."""
    urdf, args = given
    if urdf is not None:
        if not Path(urdf).is_file():
            raise InputError("file not found", path=str(urdf), element="--urdf")
        return Description(Path(urdf), "--urdf", args)
    if marm is not None and marm.urdf is not None:
        return _marm_description(root, marm, paths, args)
    explicit, mappings, how = builder
    if explicit is not None and (root / explicit).is_file() and not refused(explicit, explicit, ""):
        return Description(root / explicit, how, args or mappings or ())
    found = sorted((root / "config").glob("*.urdf.xacro"))
    xacros = [c for c in found if not refused(f"config/{c.name}", f"config/{c.name}", "")]
    named = [c for c in xacros for name in robot_names if name and c.name == f"{name}.urdf.xacro"]
    if named or (len(xacros) == 1 and not any(robot_names)):
        return Description((named or xacros)[0], "config/<robot>.urdf.xacro", args or mappings or ())
    if sa is not None and sa.urdf_package and sa.urdf_path:
        return setup_assistant_description(sa, paths, shown, args or mappings or sa.urdf_xacro_args)
    bringup = launched_by()
    if bringup is not None:
        return bringup
    runtime = _runtime_only(root, marm, sa)
    if runtime is not None:
        return Description(None, runtime, args)
    raise InputError(
        f"cannot find the robot description of package '{name}' ({_why_no_urdf(root, marm, sa)})",
        path=shown,
        element="robot description",
        needs="--urdf",
    )


def _marm_description(
    root: Path, marm: MarmSetupFile, paths: tuple[Path, ...], args: tuple[tuple[str, str], ...]
) -> Description:
    from marm_setup.robot import description_file

    assert marm.urdf is not None  # a package:// no package path holds raises PackageNotFound
    file = description_file(marm.urdf, root, (*paths, *marm_package_paths(root, marm)))
    return Description(file, "marm_setup.yaml", args or marm.xacro_args)


def setup_assistant_description(
    sa: SetupAssistantFile, paths: tuple[Path, ...], shown: str, args: tuple[tuple[str, str], ...]
) -> Description:
    """The description `.setup_assistant` names (its URDF package and relative_path);
    InputError when the package is not found."""
    from marm_setup.robot import find_package, find_packages

    where = str(Path(shown) / ".setup_assistant")
    relative_inside(str(sa.urdf_path), shown=where, element="URDF.relative_path")
    pkg_dir = find_package(str(sa.urdf_package), find_packages(paths), path=where, element="URDF.package")
    return Description(pkg_dir / str(sa.urdf_path), SETUP_ASSISTANT_ORIGIN, args)


# Only the Setup Assistant reads .setup_assistant; move_group takes what the launch files load.
SETUP_ASSISTANT_ORIGIN = ".setup_assistant (no launch file names a robot description)"


RUNTIME_ONLY = (
    "no description file validate can read: no marm_setup.yaml, .setup_assistant or "
    "config/<robot>.urdf.xacro, and the Python launch files name none (at run time it comes from "
    "the /robot_description topic or another package's launch command)"
)


SETUP_ASSISTANT_OUTSIDE = (
    "no description file validate can read: .setup_assistant names no package (the Setup "
    "Assistant then reads relative_path as a file outside any package) and the launch files load "
    "none (at run time another package's launch file loads /robot_description)"
)


def _runtime_only(root: Path, marm: MarmSetupFile | None, sa: SetupAssistantFile | None) -> str | None:
    """Why the robot description comes only at run time, or None. A package with Python launch
    files and nothing else naming its robot description: MoveIt 2 takes it at run time
    (moveit/moveit2 moveit_configs_utils/moveit_configs_builder.py `robot_description`,
    l.213-243: a file that does not exist leaves robot_description unset, "The robot description
    will be loaded from /robot_description topic"), or the launch file builds it from another
    package. A `.setup_assistant` naming no package names a file outside any package (moveit/moveit
    moveit_setup_assistant/src/tools/moveit_config_data.cpp l.1730-1734), which move_group never
    reads: with ROS 1 launch files that load no description, move_group takes /robot_description as
    something else sets it (moveit/moveit moveit_ros/planning/rdf_loader/src/rdf_loader.cpp
    l.67: searchParam/getParam, whoever loaded it)."""
    if marm is not None or (root / "marm_setup.yaml").exists():
        return None
    if sa is None and not (root / ".setup_assistant").exists():
        return RUNTIME_ONLY if any(root.glob("launch/*.py")) else None
    outside = sa is not None and sa.readable and sa.urdf_package is None and bool(sa.urdf_path)
    # ROS 1 launch files only: MoveIt 2's MoveItConfigsBuilder asks the ament index for the
    # empty package (moveit_configs_builder.py l.180-183) and stops the launch
    return SETUP_ASSISTANT_OUTSIDE if outside and any(root.glob("launch/*.launch")) else None


def _why_no_urdf(root: Path, marm: MarmSetupFile | None, sa: SetupAssistantFile | None) -> str:
    """Why none of the robot description sources gave a URDF, naming the files that exist."""
    for rel, read in (("marm_setup.yaml", marm), (".setup_assistant", sa)):
        if (root / rel).is_file() and (read is None or not read.readable):
            return f"{rel} is not readable YAML"
    if (root / ".setup_assistant").is_file():
        return ".setup_assistant gives no URDF package and relative_path"
    if (root / "marm_setup.yaml").is_file():
        return "marm_setup.yaml gives no robot.urdf"
    return "no marm_setup.yaml, .setup_assistant or config/<robot>.urdf.xacro"


def marm_package_paths(root: Path, marm: MarmSetupFile | None) -> tuple[Path, ...]:
    """`robot.package_paths` of marm_setup.yaml (relative to the package) that exist: a package
    copied into a workspace finds its description next to it instead."""
    if marm is None:
        return ()
    found = ((root / p).resolve() for p in marm.package_paths)
    return tuple(p for p in found if p.is_dir())

"""What MoveIt 2's MoveItConfigsBuilder loads for a package, from the calls its Python launch
files make (`launch_python`) and its own defaults.

moveit/moveit2 `moveit_configs_utils/moveit_configs_utils/moveit_configs_builder.py` (the same
on humble and jazzy): the robot name is the first constructor argument and the package
`package_name` or `<robot_name>_moveit_config`; the URDF is `config/<robot_name>.urdf.xacro` when
it exists, else the one `.setup_assistant` names, with `mappings` (else `.setup_assistant`'s
xacro_args); the SRDF `.setup_assistant`'s, else `config/<robot_name>.srdf`; kinematics
`config/kinematics.yaml`, joint limits `config/joint_limits.yaml`, sensors
`config/sensors_3d.yaml`, Pilz `config/pilz_cartesian_limits.yaml` (`to_moveit_configs`, each
method's `file_path` default). `trajectory_execution` without a file takes the only
`config/*_controllers.yaml`, else `moveit_controllers.yaml`, `moveit2_controllers.yaml`,
`<robot_name>_controllers.yaml` in that order (and raises when none of those exists);
`planning_pipelines` without `pipelines` loads every `config/*_planning.yaml` plus MoveIt's own
defaults (ompl, chomp, pilz_industrial_motion_planner; stomp on jazzy).

Only a MoveItConfigsBuilder imported from moveit_configs_utils follows these conventions. Another
module's (xarm_ros2's `from uf_ros_lib.moveit_configs_builder import MoveItConfigsBuilder`: its
own constructor, its own config folders and defaults merged in, controller lists wrapped under
moveit_simple_controller_manager and renamed with a prefix) is `foreign`: validate follows the
description and SRDF file paths it is given (`.robot_description(file_path=...)`: what a robot
description is, whoever builds it) and reads nothing else through it (`opaque`).
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.package.launch_python import BuilderCall
from marm_setup.package.launch_xml import package_relative

if TYPE_CHECKING:
    from marm_setup.package.setup_files import SetupAssistantFile

CONTROLLERS_FILE = re.compile(r"^(.*)_controllers\.yaml$")
PLANNING_FILE = re.compile(r"^(.*)_planning\.yaml$")
DEFAULT_FILES = {
    "robot_description_kinematics": "config/kinematics.yaml",
    "joint_limits": "config/joint_limits.yaml",
    "sensors_3d": "config/sensors_3d.yaml",
    "pilz_cartesian_limits": "config/pilz_cartesian_limits.yaml",
}


@dataclass(frozen=True, slots=True)
class Chosen:
    """A file the builder loads (relative to the package) and why it is that one."""

    file: str
    how: str


DESCRIPTION_METHODS = ("robot_description", "robot_description_semantic")


@dataclass(frozen=True)
class BuilderFiles:
    robot_name: str
    calls: tuple[BuilderCall, ...]  # this package's MoveIt builder calls (launch files sorted)
    others: tuple[str, ...] = ()  # other robots the package's launch files build (not read)
    foreign: tuple[BuilderCall, ...] = ()  # builders of another module (launch files sorted)
    rivals: tuple[BuilderCall, ...] = ()  # this package's builder calls of the `others`

    def explicit(self, method: str) -> Chosen | None:
        """The file the first launch file naming one passes to `method`, if any (a foreign
        builder's only for the robot description and SRDF)."""
        for call in (*self.calls, *(self.foreign if method in DESCRIPTION_METHODS else ())):
            path = call.file(method)
            if path is not None:
                whose = "MoveItConfigsBuilder" if call.is_moveit else f"{call.origin}.MoveItConfigsBuilder"
                return Chosen(path, f"{whose}.{method}(file_path) in {call.launch}")
        return None

    def opaque(self, method: str) -> BuilderCall | None:
        """The first foreign builder call that calls `method` (what it loads for it, validate
        cannot see), when no MoveIt builder call of the package does."""
        if any(method in c.methods for c in self.calls):
            return None
        return next((c for c in self.foreign if method in c.methods), None)

    def computed(self, method: str) -> str | None:
        """The launch file of the first call passing `method` a file_path only the run time
        computes (`"config/controllers/controllers" + suffix + ".yaml"`), if any."""
        return next((c.launch for c in self.calls if method in c.computed), None)

    def mappings(self, method: str) -> tuple[tuple[str, str], ...] | None:
        return next((m for c in self.calls if (m := c.mapping(method)) is not None), None)

    def unread_args(self, method: str) -> tuple[str, ...]:
        """The args of `method`'s mappings (the same call as `mappings`) whose value is unknown."""
        return next((c.unread_args(method) for c in self.calls if c.mapping(method) is not None), ())

    @property
    def pipelines(self) -> tuple[str, ...] | None:
        return next((c.pipelines for c in self.calls if c.pipelines is not None), None)


def builder_files(
    calls: tuple[BuilderCall, ...],
    package: str,
    wanted: tuple[str, ...] = (),
    foreign: tuple[BuilderCall, ...] = (),
) -> BuilderFiles:
    """The calls that build this package's config (its own name, or the default package name of
    their robot name), and the robot name they use. A package whose launch files build several
    robots (one launch file each) is read for one: the first of `wanted` (the robot names the
    user's --srdf / --urdf suggest) it builds, else the first of a launch file that starts
    move_group (the robot MoveIt loads: a controller_manager.launch.py building another name
    for ros2_control_node alone sorts first, and move_group never sees it), else the first
    launch file's."""
    mine = tuple(
        c
        for c in calls
        if (c.package_name or (f"{c.robot_name}_moveit_config" if c.robot_name else None)) in (package, None)
    )
    robots = [c.robot_name for c in mine if c.robot_name]
    movers = [c.robot_name for c in mine if c.robot_name and c.starts_move_group]
    robot = next((r for r in (*wanted, *movers, *robots) if r in robots), None)
    rivals = tuple(c for c in mine if c.robot_name not in (robot, None))
    mine = tuple(c for c in mine if c.robot_name in (robot, None))
    default = package[: -len("_moveit_config")] if package.endswith("_moveit_config") else package
    others = tuple(sorted(set(robots) - {robot}))
    return BuilderFiles(robot or default, mine, others, foreign, rivals)


def builds_same_robot(builder: BuilderFiles, other: str, root: Path, sa: SetupAssistantFile | None) -> bool:
    """The calls of robot name `other` load the description (file and xacro mappings) and the
    SRDF the chosen robot's calls load: the same robot under another name."""
    theirs = BuilderFiles(other, tuple(c for c in builder.rivals if c.robot_name == other))
    return _robot_files(builder, root, sa) == _robot_files(theirs, root, sa)


def _robot_files(builder: BuilderFiles, root: Path, sa: SetupAssistantFile | None) -> tuple[object, ...]:
    """(URDF, its mappings, SRDF) as MoveItConfigsBuilder picks them: a `file_path` given, else
    `config/<robot_name>.urdf.xacro` when it exists, else `.setup_assistant`'s URDF (with its
    xacro_args), else `config/<robot_name>.urdf`; the SRDF a `file_path`, else
    `.setup_assistant`'s, else `config/<robot_name>.srdf` (moveit2 moveit_configs_utils
    moveit_configs_builder.py l.163-210, robot_description l.213-240)."""
    name = builder.robot_name
    urdf, srdf = builder.explicit("robot_description"), builder.explicit("robot_description_semantic")
    modified = f"config/{name}.urdf.xacro"
    if urdf is not None:
        description = package_relative(urdf.file, root) or urdf.file
    elif (root / modified).is_file():
        description = modified
    elif sa is not None and sa.urdf_package and sa.urdf_path:
        description = f"{sa.urdf_package}/{sa.urdf_path}"
    else:
        description = f"config/{name}.urdf"
    mappings = (builder.mappings("robot_description"), builder.unread_args("robot_description"))
    if srdf is not None:
        semantic = package_relative(srdf.file, root) or srdf.file
    else:
        semantic = sa.srdf_path if sa is not None and sa.srdf_path else f"config/{name}.srdf"
    return description, mappings, semantic


def chosen_file(builder: BuilderFiles, method: str, root: Path) -> Chosen | None:
    """The file `method` loads: the launch file's `file_path`, else the builder's default."""
    found = builder.explicit(method)
    if found is not None:
        rel = package_relative(found.file, root)
        return Chosen(rel, found.how) if rel is not None else None
    default = DEFAULT_FILES.get(method)
    return Chosen(default, f"MoveItConfigsBuilder's default for {method}") if default else None


def controllers_file(builder: BuilderFiles, root: Path) -> Chosen | None:
    """trajectory_execution's file: explicit, else the builder's guess among `*_controllers.yaml`."""
    found = chosen_file(builder, "trajectory_execution", root)
    if found is not None or builder.computed("trajectory_execution"):
        return found  # a file_path given at run time: the builder guesses nothing
    config = root / "config"
    names = sorted(
        m.group(1) for p in config.glob("*_controllers.yaml") if (m := CONTROLLERS_FILE.match(p.name))
    )
    how = "MoveItConfigsBuilder.trajectory_execution's choice among config/*_controllers.yaml"
    if len(names) == 1:
        return Chosen(f"config/{names[0]}_controllers.yaml", how)
    for name in ("moveit", "moveit2", builder.robot_name):
        if name in names:
            return Chosen(f"config/{name}_controllers.yaml", how)
    return None


def planning_pipelines(builder: BuilderFiles, root: Path) -> tuple[str, ...]:
    """The pipelines the builder loads whose file is in the package (`config/<name>_planning.yaml`)."""
    named = builder.pipelines
    found = sorted(
        m.group(1) for p in (root / "config").glob("*_planning.yaml") if (m := PLANNING_FILE.match(p.name))
    )
    return tuple(n for n in (named if named is not None else found) if n in found)

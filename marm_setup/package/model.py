"""MoveItPackage: one MoveIt config package, read once (`package.read.read_package`).

Each MoveIt file kind is a typed value (`kinematics_file`, `joint_limits_file`,
`planning_file`, `controllers_file`, `driver_file`, `srdf_file`, `setup_files`,
`perception_files`) whose values keep their file and key path; `sources` says which file each
kind was read from and why (which launch file loads it, or which convention). validate's rules,
the port and the planner read only this.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.findings import Finding
from marm_setup.package.control_manager import managed_controllers
from marm_setup.package.controllers_file import ControllersFile
from marm_setup.package.driver_file import ArbotixFile, DriverFile, InitialPositions, Ros2ControlFile
from marm_setup.package.joint_limits_file import JointLimitsFile
from marm_setup.package.kinematics_file import KinematicsFile
from marm_setup.package.launch_ros1 import LaunchParam
from marm_setup.package.launch_xml import LaunchXml
from marm_setup.package.perception_files import SensorsFile, ServoConfig
from marm_setup.package.planning_file import PlanningPipeline
from marm_setup.package.setup_files import MarmSetupFile, PackageXml, SetupAssistantFile
from marm_setup.package.srdf_file import SrdfFile
from marm_setup.package.where import Param
from marm_setup.ros import Distro, Target

if TYPE_CHECKING:
    from marm_setup.setup import Srdf


@dataclass(frozen=True, slots=True)
class Source:
    """Which file a kind was read from (relative to the package), and why that one."""

    kind: str  # kinematics, joint_limits, pipeline:ompl, moveit_controllers, ...
    file: str
    how: str


@dataclass(frozen=True)
class MoveItPackage:
    root: Path  # absolute
    shown: str  # the folder as the user typed it
    name: str  # package.xml <name>, or the folder name
    target: Target  # ros1 (catkin, MoveIt 1) | ros2 (ament, MoveIt 2)
    layout: str  # moveit1 | moveit2 | marm_ros2 (our single config/moveit.yaml)
    urdf: Path | None  # the robot description; None when only the run time gives it
    urdf_origin: (
        str  # --urdf, marm_setup.yaml, .setup_assistant, config/<robot>.urdf.xacro, ... (or why None)
    )
    xacro_args: tuple[tuple[str, str], ...] = ()
    launch_args: tuple[tuple[str, str], ...] = ()  # given to the launch files (--launch-arg)
    description_unreadable: bool = False  # the description named is not there (urdf is None)
    unread_xacro_args: tuple[str, ...] = ()  # the launch files pass these with run-time values
    package_paths: tuple[Path, ...] = ()  # for $(find): this package first, then the user's, ...
    package_xml: PackageXml | None = None
    setup_assistant: SetupAssistantFile | None = None
    marm_setup: MarmSetupFile | None = None
    srdf_file: SrdfFile | None = None
    kinematics: KinematicsFile | None = None
    joint_limits: JointLimitsFile | None = None
    pipelines: tuple[PlanningPipeline, ...] = ()
    moveit_controllers: ControllersFile | None = None
    alt_moveit_controllers: tuple[ControllersFile, ...] = ()  # files a launch may load instead
    # MoveIt 1: the launch file that makes the simple controller manager move_group's manager when
    # no launch file loads a controller list at all ('' otherwise)
    controller_list_unloaded: str = ""
    # MoveIt 1: the moveit_controller_manager params set on branches the launch defaults take
    controller_managers: tuple[LaunchParam, ...] = ()
    fake_controllers: ControllersFile | None = None
    ros2_controllers: DriverFile | None = None
    ros_controllers: DriverFile | None = None
    arbotix: ArbotixFile | None = None
    initial_positions: InitialPositions | None = None
    move_group: tuple[Param, ...] | None = None  # move_group's own parameters (our moveit.yaml)
    sensors: SensorsFile | None = None
    servo: tuple[ServoConfig, ...] = ()
    # what a MoveItConfigsBuilder not from moveit_configs_utils loads, which validate did not read
    # (one summary line per launch file's builder; package/builder.py)
    opaque: tuple[str, ...] = ()
    opaque_methods: tuple[str, ...] = ()  # its methods those files come from (trajectory_execution, ...)
    launch: tuple[LaunchXml, ...] = ()  # the XML launch files, parsed
    launch_params: tuple[LaunchParam, ...] = ()  # ROS 1 `<param name value>`s, as roslaunch sets them
    python_launch_files: tuple[str, ...] = ()
    ros2_control_files: tuple[Ros2ControlFile, ...] = ()  # config/*.ros2_control.xacro
    files: tuple[str, ...] = ()  # every file of the package
    sources: tuple[Source, ...] = ()
    problems: tuple[Finding, ...] = field(default=())
    distro_given: Distro | None = None  # validate --ros-distro, over marm_setup.yaml's

    @property
    def managed_controllers(self) -> ControllersFile | None:
        """MoveIt's controllers as its manager finds them: the file's list, or with MoveIt 2's
        Ros2ControlManager the ros2_control controllers it has a handle for (`control_manager`)."""
        if self.moveit_controllers is None or self.target != Target.ROS2:
            return self.moveit_controllers
        return managed_controllers(self.moveit_controllers, self.ros2_controllers)

    @property
    def srdf(self) -> Srdf | None:
        return self.srdf_file.srdf if self.srdf_file is not None else None

    @property
    def srdf_path(self) -> str | None:
        return self.srdf_file.path if self.srdf_file is not None else None

    @property
    def srdf_text(self) -> str | None:
        return self.srdf_file.text if self.srdf_file is not None else None

    @property
    def ompl(self) -> PlanningPipeline | None:
        return next((p for p in self.pipelines if p.name == "ompl"), None)

    @property
    def launch_files(self) -> tuple[str, ...]:
        return tuple(t.file for t in self.launch)

    @property
    def ros_distro(self) -> Distro | None:
        """The distro the package is checked for: --ros-distro, else marm_setup.yaml's
        `ros_distro`, else None."""
        if self.distro_given is not None:
            return self.distro_given
        return self.marm_setup.ros_distro if self.marm_setup is not None else None

    def for_distro(self, name: str | None) -> MoveItPackage:
        """The package checked for `name` (None: as it says); InputError naming the distros of
        its target when `name` is none of them."""
        from dataclasses import replace

        from marm_setup.ros import distros_of

        if name is None:
            return self
        if name not in distros_of(self.target):
            valid = ", ".join(distros_of(self.target))
            raise InputError(
                f"'{name}' is not a {self.target} distro (valid: {valid})", element="--ros-distro"
            )
        return replace(self, distro_given=name)

    @property
    def description_file(self) -> Path:
        """The robot description file; InputError (pass --urdf) when only the run time gives it
        (planning and porting need the robot; validate runs what it can without it)."""
        if self.urdf is None:
            raise InputError(
                f"cannot find the robot description of package '{self.name}' ({self.urdf_origin})",
                path=self.shown,
                element="robot description",
                needs="--urdf",
            )
        return self.urdf

    def source(self, kind: str) -> Source | None:
        return next((s for s in self.sources if s.kind == kind), None)

    def path(self, rel: str) -> Path:
        return self.root / rel

    def user_path(self, rel: str | None) -> str:
        """A package file as the user would type it (`DIR/rel`), for error messages."""
        return str(Path(self.shown) / rel) if rel else self.shown

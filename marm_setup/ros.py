"""The ROS versions a package is for: its target (ROS 1 / MoveIt 1 or ROS 2 / MoveIt 2) and the
ROS distro of that target it is written for, one row of `DISTROS` per distro.

`Target` is a `str` enum written and compared as its value (`ros2`). A distro is its row's name
(`jazzy`): code asks the row what the distro's MoveIt, ros2_control and ros2_controllers read
(`distro_row(name).servo_executable`), never compares names; adding a distro is adding a row.

Sources of the rows (each difference from Jazzy cited where it is):
- moveit/moveit2 humble 2b2030dd, jazzy 4d841063, kilted 4373855, main (Rolling) 8fcb5d2: every
  generate_parameter_library file (planning_pipeline_parameters, default_request_adapter_params,
  default_response_adapter_params, kinematics_parameters, servo_parameters) and every plugin
  description file of kilted and main equals jazzy's, so Kilted and Rolling read Jazzy's tables.
- ros-controls/ros2_control jazzy 9ffbf97, kilted cbe7d2c, master (Rolling) 53b9999: the
  controller_manager parameters (update_rate int, `<name>.type`), the /robot_description topic,
  mock_components/GenericSystem and its parameters, mimic joints from the URDF: as Jazzy.
- ros-controls/ros2_controllers jazzy ed360c9, kilted 0f8eb14, master (Rolling) 94e74de:
  joint_trajectory_controller reads the same joints / command_interfaces / state_interfaces /
  allow_nonzero_velocity_at_trajectory_end. Kilted removed gripper_controllers (0095ef1 "Remove
  deprecated gripper_controller (#1652)"): the gripper is parallel_gripper_controller's
  `parallel_gripper_action_controller/GripperActionController` (ros_control_plugins.xml l.3),
  serving control_msgs ParallelGripperCommand on `<name>/gripper_cmd`
  (parallel_gripper_action_controller.hpp l.97, parallel_gripper_action_controller_impl.hpp
  l.409-410), which moveit_simple_controller_manager takes as type `ParallelGripperCommand`
  (moveit2 kilted and main, moveit_simple_controller_manager.cpp l.185). Rolling also removed
  position_controllers (27ea539 "Remove deprecated controller specializations (#2016)"): servo's
  forward position controller is forward_command_controller/ForwardCommandController with
  `interface_name` (forward_command_controller_parameters.yaml l.2-17).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from marm_setup.errors import InputError


class _Named(str, enum.Enum):
    """A str enum whose str() and format() are its value, on every Python version."""

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)


class Target(_Named):
    ROS2 = "ros2"  # ament packages, MoveIt 2
    ROS1 = "ros1"  # catkin packages, MoveIt 1


Distro = str  # the name of a DISTROS row
AdapterValue = float | tuple[str, ...]
TARGETS = (Target.ROS2, Target.ROS1)  # the default first


@dataclass(frozen=True, slots=True)
class ControllerKind:
    """A ros2_controllers controller a package runs: its type (controller_manager's
    `<name>.type`), the package that exports it, the moveit_simple_controller_manager handle type
    MoveIt drives it with ('' for none) and the `interface_name` it needs ('' where its type fixes
    the interface)."""

    type: str
    package: str
    moveit_type: str = ""
    interface_name: str = ""


@dataclass(frozen=True, slots=True)
class DistroRow:
    """What one ROS distro's MoveIt, ros2_control and ros2_controllers read."""

    name: str
    target: Target
    # which table of MoveIt's declared parameters applies: noetic | humble | jazzy (planning
    # pipeline format, servo parameters, marm_setup.moveit_params tables)
    params: str
    # per planning pipeline (setup name): the adapters marm-setup writes by default and the
    # adapters' own settings; the prefixes of the adapter plugins its MoveIt exports (a name of
    # another prefix cannot be loaded)
    adapter_defaults: tuple[tuple[str, tuple[tuple[str, AdapterValue], ...]], ...] = ()
    adapter_families: tuple[str, ...] = ()
    planners: tuple[str, ...] = ()  # planning pipelines (setup names) in its MoveIt binaries
    planners_from_source: tuple[str, ...] = ()  # ... a user may build from MoveIt's source
    # move_group reads a pipeline's capabilities only in the top-level `capabilities` string
    top_level_capabilities: bool = False
    servo_executable: str = ""
    servo_publish_period: float = 0.0  # [s] moveit_servo's default publish_period
    servo_starts_paused: bool = False  # a start_servo service call must start it
    servo_needs_kinematics: bool = False  # servo refuses a group with no kinematics solver
    # controller kind (FollowJointTrajectory, GripperCommand, forward_position) -> controller
    controllers: tuple[tuple[str, ControllerKind], ...] = ()
    control_packages: tuple[str, ...] = ()  # what every package depends on for ros2_control
    mock_plugins: frozenset[str] = frozenset()  # ros2_control hardware plugins that are mocks
    urdf_mimic: bool = False  # ros2_control takes a mimic joint's coupling from the URDF <mimic>
    # controller_manager takes the URDF from robot_state_publisher's /robot_description topic
    # (else from its robot_description parameter)
    robot_description_topic: bool = False
    # move_group finds a group's IK solver at `<group>.kinematics_solver` among its own top-level
    # parameters too, not only at `robot_description_kinematics.<group>.kinematics_solver`
    kinematics_top_level: bool = False
    launch_frontend: str = ""  # whose launch / launch_ros the ROS 2 consumer runs: humble | jazzy

    def controller(self, kind: str) -> ControllerKind:
        """The controller of `kind`; InputError naming the kinds this distro has."""
        found = dict(self.controllers).get(kind)
        if found is None:
            known = ", ".join(k for k, _ in self.controllers) or "none"
            raise InputError(f"{self.name} has no {kind} controller (it has: {known})", element="ros_distro")
        return found

    def adapters(self, pipeline: str) -> tuple[tuple[str, AdapterValue], ...]:
        """The adapter parameters marm-setup writes for `pipeline` where the setup gives none."""
        return dict(self.adapter_defaults).get(pipeline, ())


MOCK = "mock_components/GenericSystem"
_REQUEST, _RESPONSE = "default_planning_request_adapters/", "default_planning_response_adapters/"
_HUMBLE_REQUEST = "default_planner_request_adapters/"
HUMBLE_ADAPTERS = tuple(
    _HUMBLE_REQUEST + a
    for a in (
        "AddTimeOptimalParameterization", "ResolveConstraintFrames", "FixWorkspaceBounds",
        "FixStartStateBounds", "FixStartStateCollision", "FixStartStatePathConstraints",
    )
)  # fmt: skip
JAZZY_REQUESTS = tuple(
    _REQUEST + a
    for a in ("ResolveConstraintFrames", "ValidateWorkspaceBounds", "CheckStartStateBounds", "CheckStartStateCollision")
)  # fmt: skip
JAZZY_RESPONSES = tuple(
    _RESPONSE + a for a in ("AddTimeOptimalParameterization", "ValidateSolution", "DisplayMotionPath")
)
_HUMBLE_FIX = (("start_state_max_bounds_error", 0.1), ("jiggle_fraction", 0.05))
TRAJECTORY = ControllerKind(
    "joint_trajectory_controller/JointTrajectoryController",
    "joint_trajectory_controller",
    "FollowJointTrajectory",
)
GRIPPER = ControllerKind(
    "position_controllers/GripperActionController", "gripper_controllers", "GripperCommand"
)
PARALLEL_GRIPPER = ControllerKind(
    "parallel_gripper_action_controller/GripperActionController",
    "parallel_gripper_controller",
    "ParallelGripperCommand",
)
FORWARD_POSITION = ControllerKind("position_controllers/JointGroupPositionController", "position_controllers")
FORWARD_COMMAND = ControllerKind(
    "forward_command_controller/ForwardCommandController",
    "forward_command_controller",
    interface_name="position",
)
_CONTROL = ("controller_manager", "joint_state_broadcaster", "joint_trajectory_controller", "ros2_control")

_NOETIC = DistroRow(
    "noetic", Target.ROS1, params="noetic", planners=("ompl", "chomp", "pilz"), servo_publish_period=0.034
)
_HUMBLE = DistroRow(
    "humble",
    Target.ROS2,
    params="humble",
    # MoveIt's own defaults (moveit_configs_utils/default_configs/*_planning.yaml, humble: OMPL and
    # CHOMP with the six adapters, start_state_max_bounds_error 0.1 and jiggle_fraction 0.05)
    adapter_defaults=(
        ("ompl", (("request_adapters", HUMBLE_ADAPTERS), *_HUMBLE_FIX)),
        ("chomp", (("request_adapters", HUMBLE_ADAPTERS), *_HUMBLE_FIX)),
        ("stomp", (("request_adapters", HUMBLE_ADAPTERS),)),
        ("pilz", (("request_adapters", ()),)),
    ),
    adapter_families=(_HUMBLE_REQUEST,),
    planners=("ompl", "chomp", "pilz"),
    planners_from_source=("stomp",),  # moveit2's humble branch has no moveit_planners/stomp
    top_level_capabilities=True,  # move_group.cpp humble l.139, l.151 (moveit/moveit2#1393)
    servo_executable="servo_node_main",
    servo_publish_period=0.034,
    servo_starts_paused=True,
    controllers=(
        ("FollowJointTrajectory", TRAJECTORY),
        ("GripperCommand", GRIPPER),
        ("forward_position", FORWARD_POSITION),
    ),  # fmt: skip
    control_packages=(*_CONTROL, "gripper_controllers"),
    mock_plugins=frozenset({MOCK, "fake_components/GenericSystem"}),
    # kinematics_plugin_loader.cpp humble l.306-319: `<group>.kinematics_solver` first, then
    # `robot_description_kinematics.<group>...`; jazzy l.258-272 (kilted, main l.260) only the latter
    kinematics_top_level=True,
    launch_frontend="humble",
)
_JAZZY = DistroRow(
    "jazzy",
    Target.ROS2,
    params="jazzy",
    # MoveIt's own defaults (moveit_configs_utils/default_configs/*_planning.yaml, jazzy 4d84106:
    # ompl l.4-12, chomp l.5-13, stomp l.3-11 and pilz_industrial_motion_planner l.4-11 all end
    # their responses with ValidateSolution, so no path reaches execution unchecked; Pilz has no
    # time parameterization: its planner times the trajectory itself)
    adapter_defaults=(
        ("ompl", (("request_adapters", JAZZY_REQUESTS), ("response_adapters", JAZZY_RESPONSES))),
        ("chomp", (("request_adapters", JAZZY_REQUESTS), ("response_adapters", JAZZY_RESPONSES))),
        ("stomp", (("request_adapters", JAZZY_REQUESTS), ("response_adapters", JAZZY_RESPONSES))),
        ("pilz", (("request_adapters", JAZZY_REQUESTS), ("response_adapters", JAZZY_RESPONSES[1:]))),
    ),
    adapter_families=(_REQUEST, _RESPONSE),
    planners=("ompl", "chomp", "pilz", "stomp"),
    servo_executable="servo_node",
    servo_publish_period=0.01,
    servo_needs_kinematics=True,
    controllers=_HUMBLE.controllers,
    control_packages=_HUMBLE.control_packages,
    mock_plugins=frozenset({MOCK}),
    urdf_mimic=True,
    robot_description_topic=True,
    launch_frontend="jazzy",
)
_KILTED = DistroRow(
    **{
        **{f: getattr(_JAZZY, f) for f in DistroRow.__dataclass_fields__},
        "name": "kilted",
        # gripper_controllers removed (ros2_controllers 0095ef1, #1652)
        "controllers": (
            ("FollowJointTrajectory", TRAJECTORY),
            ("GripperCommand", PARALLEL_GRIPPER),
            ("forward_position", FORWARD_POSITION),
        ),  # fmt: skip
        "control_packages": (*_CONTROL, "parallel_gripper_controller"),
    }
)
_ROLLING = DistroRow(
    **{
        **{f: getattr(_KILTED, f) for f in DistroRow.__dataclass_fields__},
        "name": "rolling",
        # position_controllers removed (ros2_controllers master 27ea539, #2016)
        "controllers": (
            ("FollowJointTrajectory", TRAJECTORY),
            ("GripperCommand", PARALLEL_GRIPPER),
            ("forward_position", FORWARD_COMMAND),
        ),  # fmt: skip
    }
)
# Every distro, each target's default first within it.
DISTROS: dict[str, DistroRow] = {r.name: r for r in (_NOETIC, _HUMBLE, _JAZZY, _KILTED, _ROLLING)}


def distros_of(target: Target | str) -> tuple[str, ...]:
    """The distros of `target`, its default first."""
    return tuple(name for name, row in DISTROS.items() if row.target == target)


def default_distro(target: Target | str) -> str:
    return distros_of(target)[0]


def distro_row(name: str | None, target: Target | str | None = None) -> DistroRow:
    """The row of `name` (None: the target's default); InputError naming the known distros."""
    if name is None:
        name = default_distro(target or Target.ROS2)
    row = DISTROS.get(str(name))
    if row is None or (target is not None and row.target != target):
        known = ", ".join(distros_of(target)) if target is not None else ", ".join(DISTROS)
        of = f"{target} " if target is not None else ""
        raise InputError(f"'{name}' is not a known {of}distro (valid: {known})", element="ros_distro")
    return row

"""SetupModel: the one source of truth for a robot's MoveIt setup (`marm_setup.yaml`).

Values are frozen dataclasses; collections are tuples (sorted by name where order carries no
meaning), so equality and output order are deterministic.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from marm_setup.collision import DisabledPair, DisabledReason, UnprovedPair
from marm_setup.moveit_params import (
    DEFAULT_PIPELINES,
    DEFAULT_PLANNER,
    DRIVER_ACTION_NS,
    KDL_PLUGIN,
    MOCK_HARDWARE,
    MoveGroupValue,
    PipelineParameterValue,
)
from marm_setup.ros import Distro, DistroRow, Target, default_distro, distro_row

# The targets and their distros (marm_setup.ros). Humble and Jazzy differ in MoveIt's planning
# pipeline parameters (DESIGN §4): Humble's PlanningPipeline reads one `planning_plugin` string
# and `request_adapters` as one space-separated string (moveit2 humble, moveit_ros/planning/
# planning_pipeline/src/planning_pipeline.cpp l.58-77); Jazzy's reads the `planning_plugins`,
# `request_adapters` and `response_adapters` lists (moveit2 jazzy, same file,
# PlanningPipeline::configure, via planning_pipeline_parameters).


@dataclass(frozen=True, slots=True)
class Author:
    name: str = "marm-setup user"
    email: str = "user@example.com"


@dataclass(frozen=True, slots=True)
class RobotSource:
    """Where the URDF is: `urdf` relative to the package dir (or absolute), plus xacro args."""

    urdf: str
    xacro_args: tuple[tuple[str, str], ...] = ()
    package_paths: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class VirtualJoint:
    name: str
    type: str  # fixed | floating | planar
    parent_frame: str
    child_link: str


@dataclass(frozen=True, slots=True)
class Chain:
    base: str
    tip: str


@dataclass(frozen=True, slots=True)
class Group:
    """A planning group: any of a chain, joints, links and subgroups (as the SRDF allows)."""

    name: str
    chain: Chain | None = None
    joints: tuple[str, ...] = ()
    links: tuple[str, ...] = ()
    subgroups: tuple[str, ...] = ()


@dataclass(frozen=True, slots=True)
class GroupState:
    """A named pose: joint values in [rad] or [m], in the group's joint order."""

    name: str
    group: str
    values: tuple[tuple[str, float], ...]
    # joints with several values (a planar or floating virtual joint: x y theta / x y z qx qy qz qw),
    # kept as srdfdom reads them; no pose math looks at them
    multi_dof: tuple[tuple[str, tuple[float, ...]], ...] = ()


@dataclass(frozen=True, slots=True)
class StartPose:
    """The named pose a group's joints start at in the demo (ros1: fake_controllers.yaml
    `initial`; ros2: initial_positions.yaml)."""

    group: str
    pose: str


@dataclass(frozen=True, slots=True)
class EndEffector:
    name: str
    group: str
    parent_link: str
    parent_group: str | None = None


@dataclass(frozen=True, slots=True)
class CollisionSettings:
    """How the self-collision matrix was computed, and its disabled pairs (sorted). `prove`:
    how its Never pairs were proved (off, on, exhaustive; None: not recorded); `unproved`: the
    Never pairs whose proof did not finish (each one's SRDF entry carries a note); `proof_key`:
    ties the proofs to the robot they were made for (collision/proof_summary.py proof_key)."""

    seed: int = 0
    trials: int = 10000
    min_collision_fraction: float = 0.95
    disabled: tuple[DisabledPair, ...] = ()
    prove: str | None = None
    unproved: tuple[UnprovedPair, ...] = ()
    proof_key: str | None = None

    def note(self, pair: DisabledPair) -> str | None:
        """The SRDF note of a disabled pair: for an unproved Never pair, else None."""
        if pair.reason is not DisabledReason.NEVER:
            return None
        found = next((u for u in self.unproved if u.pair == pair.pair), None)
        return None if found is None else found.note(self.trials)


# A solver option's value: MoveIt hands each to the plugin as the typed parameter it is.
OptionValue = str | int | float | bool


@dataclass(frozen=True, slots=True)
class Kinematics:
    """Per-group IK solver settings (`kinematics.yaml`); resolution in [rad], timeout in [s];
    `options` the solver plugin's own keys, written as given (KDL's `position_only_ik`,
    TRAC-IK's `solve_type`, bio_ik's `mode`, ...)."""

    group: str
    solver: str = KDL_PLUGIN
    search_resolution: float = 0.005
    timeout: float = 0.05
    attempts: int = 3  # kept for old files; MoveIt >= 1.0 reads no attempts, so none is rendered
    options: tuple[tuple[str, OptionValue], ...] = ()


@dataclass(frozen=True, slots=True)
class PlannerDefaults:
    """Per-group OMPL defaults (`ompl_planning.yaml`)."""

    group: str
    default_planner: str = DEFAULT_PLANNER
    longest_valid_segment_fraction: float = 0.005


@dataclass(frozen=True, slots=True)
class Controller:
    """A trajectory controller: MoveIt's and the driver's side share name, action_ns, joints."""

    name: str
    type: str  # FollowJointTrajectory | GripperCommand
    action_ns: str
    joints: tuple[str, ...]
    group: str | None = None
    default: bool = True


@dataclass(frozen=True, slots=True)
class ArbotixJoint:
    """ArbotiX servo settings for one joint; max_speed in [deg/s]."""

    joint: str
    id: int
    max_speed: float | None = None


@dataclass(frozen=True, slots=True)
class Ros2ControlHardware:
    """The hardware of the generated ros2_control system (ros2 target): its plugin, the plugin's
    `<param>`s, and every joint's command and state interfaces. The demo's `use_mock_hardware`
    (true by default) swaps the plugin for mock_components/GenericSystem, same interfaces."""

    plugin: str = MOCK_HARDWARE
    parameters: tuple[tuple[str, str], ...] = ()
    command_interfaces: tuple[str, ...] = ("position",)
    state_interfaces: tuple[str, ...] = ("position", "velocity")


@dataclass(frozen=True, slots=True)
class JointLimitOverride:
    """Overrides for `joint_limits.yaml`; None keeps the URDF value (or no limit). Positions in
    [rad] or [m] (MoveIt reads them whenever given), rates per [s], [s^2], [s^3]."""

    joint: str
    max_velocity: float | None = None
    max_acceleration: float | None = None
    max_jerk: float | None = None
    min_position: float | None = None
    max_position: float | None = None


@dataclass(frozen=True, slots=True)
class CollisionPair:
    """An SRDF `<enable_collisions>` entry (reason is free text there)."""

    link1: str
    link2: str
    reason: str = ""


@dataclass(frozen=True, slots=True)
class JointProperty:
    """An SRDF `<joint_property joint_name property_name value>`."""

    joint: str
    property: str
    value: str


@dataclass(frozen=True, slots=True)
class SphereApprox:
    """One sphere of a `<link_sphere_approximation>`: center in [m] (link frame), radius in [m]."""

    center: tuple[float, float, float]
    radius: float


@dataclass(frozen=True, slots=True)
class LinkSpheres:
    link: str
    spheres: tuple[SphereApprox, ...] = ()


@dataclass(frozen=True, slots=True)
class SrdfExtras:
    """SRDF elements the setup does not edit, kept verbatim from an imported SRDF."""

    enable_collisions: tuple[CollisionPair, ...] = ()
    disable_default_collisions: tuple[str, ...] = ()
    joint_properties: tuple[JointProperty, ...] = ()
    link_sphere_approximations: tuple[LinkSpheres, ...] = ()


@dataclass(frozen=True, slots=True)
class ServoScale:
    """moveit_servo's `scale`: the speed a full unitless command means, linear [m/s], rotational
    [rad/s] and joint [rad/s or m/s]; None keeps the distro's moveit_servo default."""

    linear: float | None = None
    rotational: float | None = None
    joint: float | None = None


@dataclass(frozen=True, slots=True)
class Servo:
    """MoveIt Servo for one group (`setup.servo` fills in what is None).

    `command_out` is `trajectory` (trajectory_msgs/JointTrajectory to a FollowJointTrajectory
    controller's command topic) or `position` (std_msgs/Float64MultiArray to a forward position
    controller added to ros2_controllers.yaml, ros2 only); `controller` names that controller."""

    group: str
    command_out: str = "trajectory"
    controller: str | None = None
    planning_frame: str | None = None
    ee_frame: str | None = None
    command_frame: str | None = None
    command_in_type: str | None = None
    scale: ServoScale = field(default_factory=ServoScale)
    publish_period: float | None = None  # [s]
    check_collisions: bool | None = None


@dataclass(frozen=True, slots=True)
class Sensor:
    """A 3D sensor feeding MoveIt's octomap: its occupancy map updater's parameters (None: MoveIt's
    default for the type, `setup.sensors`); distances in [m], rates in [Hz]."""

    name: str
    type: str  # pointcloud | depth_image
    topic: str
    max_range: float | None = None  # pointcloud
    point_subsample: int | None = None  # pointcloud
    queue_size: int | None = None  # depth_image
    near_clipping_plane_distance: float | None = None  # depth_image
    far_clipping_plane_distance: float | None = None  # depth_image
    shadow_threshold: float | None = None  # depth_image
    skip_vertical_pixels: int | None = None  # depth_image
    skip_horizontal_pixels: int | None = None  # depth_image
    padding_offset: float | None = None
    padding_scale: float | None = None
    max_update_rate: float | None = None
    filtered_cloud_topic: str | None = None
    ns: str | None = None


@dataclass(frozen=True, slots=True)
class SetupModel:
    package_name: str
    robot_name: str
    robot: RobotSource
    target: Target = Target.ROS2
    ros_distro: Distro | None = None  # None: the target's default (marm_setup.ros default_distro)
    driver: str | None = None  # ros1: the hardware driver whose files to write (arbotix), or none
    author: Author = field(default_factory=Author)
    virtual_joints: tuple[VirtualJoint, ...] = ()
    groups: tuple[Group, ...] = ()
    group_states: tuple[GroupState, ...] = ()
    # the demo's start: each listed group at its pose, every other joint at its default (as
    # fake_controllers.yaml `initial`); None: every group at its `home`, else its first pose
    start_poses: tuple[StartPose, ...] | None = None
    end_effectors: tuple[EndEffector, ...] = ()
    passive_joints: tuple[str, ...] = ()
    collision: CollisionSettings = field(default_factory=CollisionSettings)
    kinematics: tuple[Kinematics, ...] = ()
    planners: tuple[PlannerDefaults, ...] = ()
    # MoveIt planning pipelines (moveit_params.vocabulary.PIPELINES), the first is move_group's default
    planning_pipelines: tuple[str, ...] = DEFAULT_PIPELINES
    # per pipeline (a planning_pipelines name): parameters of its namespace over marm-setup's
    # defaults (moveit_params.pipeline_params: the names each distro's MoveIt reads)
    pipeline_parameters: tuple[tuple[str, tuple[tuple[str, PipelineParameterValue], ...]], ...] = ()
    # move_group's own parameters over marm-setup's defaults, by MoveIt 2 name
    # (moveit_params.move_group_params: trajectory_execution.*, publish_*, moveit_manage_controllers, ...)
    move_group_parameters: tuple[tuple[str, MoveGroupValue], ...] = ()
    controllers: tuple[Controller, ...] = ()
    arbotix_joints: tuple[ArbotixJoint, ...] = ()
    ros2_control: Ros2ControlHardware | None = None  # None: mock hardware, position command
    joint_limits: tuple[JointLimitOverride, ...] = ()
    default_velocity_scaling: float = 0.1
    default_acceleration_scaling: float = 0.1
    default_acceleration: float = 1.0  # [rad/s^2] or [m/s^2] where the URDF gives none
    # MoveIt Servo per group; None: one for every arm group (setup.servo.default_servos), (): none
    servo: tuple[Servo, ...] | None = None
    sensors: tuple[Sensor, ...] = ()  # 3D sensors; none: no perception files
    octomap_resolution: float | None = None  # [m]; None: setup.sensors.DEFAULT_OCTOMAP_RESOLUTION
    octomap_frame: str | None = None  # None: the planning frame (what move_group builds it in)
    srdf_extras: SrdfExtras = field(default_factory=SrdfExtras)

    @property
    def distro(self) -> Distro:
        """The ROS distro the package is written for."""
        return self.ros_distro or default_distro(self.target)

    @property
    def row(self) -> DistroRow:
        """What the distro's MoveIt, ros2_control and ros2_controllers read (InputError: unknown)."""
        return distro_row(self.distro, self.target)

    def group(self, name: str) -> Group:
        return next(g for g in self.groups if g.name == name)

    @property
    def driver_key(self) -> str | None:
        """Whose action namespaces the controllers must use: `ros2` (ros2_control) or the ros1 driver."""
        return Target.ROS2 if self.target == Target.ROS2 else self.driver

    def served_action_ns(self, kind: str) -> str | None:
        """The action_ns the driver serves for a controller type, or None when any will do."""
        return DRIVER_ACTION_NS.get((self.driver_key, kind)) if self.driver_key else None

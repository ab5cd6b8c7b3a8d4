"""Derived data the package templates need: joint limits, controller wiring, ArbotiX servos, ...

Pure functions of (SetupModel, RobotModel); templates loop over these values and format them.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass
from pathlib import PurePosixPath

from marm_setup.errors import InputError
from marm_setup.moveit_params import (
    ARBOTIX_GRIPPER_ACTION_NS,
    FOLLOW_JOINT_TRAJECTORY,
    GRIPPER_COMMAND,
    MOCK_HARDWARE,
    MOVEIT_CONTROLLER_TYPES,
    OMPL_PLANNERS,
    PIPELINES,
    move_group_values,
)
from marm_setup.names import name_problem
from marm_setup.robot import Joint, RobotModel
from marm_setup.ros import ControllerKind, Target
from marm_setup.setup import (
    Controller,
    GroupState,
    Kinematics,
    PlannerDefaults,
    Ros2ControlHardware,
    SetupModel,
    VirtualJoint,
    active_group_joints,
    forward_controllers,
    groups_by_name,
    joint_limits,
    model_start_values,
    plan_perception,
    plan_servos,
    root_virtual_joint,
    start_pose,
)

XACRO_ARG_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

# Pilz / MoveIt defaults for cartesian limits ([m/s], [m/s^2], [rad/s]).
CARTESIAN_LIMITS = (
    ("max_trans_vel", 1.0),
    ("max_trans_acc", 2.25),
    ("max_trans_dec", -5.0),
    ("max_rot_vel", 1.57),
)


DESCRIPTION_COPY_DIR = "description"


@dataclass(frozen=True, slots=True)
class DescriptionRef:
    """How launch files find the URDF: `$(find package)/path`; package None: a copy in our own
    package at `path` (a URDF in no ROS package: ament installs only share/<pkg>, so a path
    climbing out of our package breaks once installed)."""

    package: str | None
    path: str
    is_xacro: bool
    xacro_args: tuple[tuple[str, str], ...] = ()


@dataclass(frozen=True, slots=True)
class GroupInfo:
    name: str
    active_joints: tuple[str, ...]
    kinematics: Kinematics | None
    planner: PlannerDefaults
    initial_pose: GroupState | None

    @property
    def projection_joints(self) -> tuple[str, ...]:
        """OMPL's projection for KPIECE, BKPIECE, LBKPIECE, EST, SBL: the first two active joints,
        as the Setup Assistant writes it; a one-joint group gets none."""
        return self.active_joints[:2] if len(self.active_joints) >= 2 else ()


@dataclass(frozen=True, slots=True)
class ControllerInfo:
    """A setup controller and the distro's ros2_controllers controller that serves it."""

    controller: Controller
    kind: ControllerKind

    @property
    def ros2_type(self) -> str:
        return self.kind.type

    @property
    def moveit_type(self) -> str:
        """The moveit_simple_controller_manager handle type (ParallelGripperCommand for a
        parallel gripper controller's GripperCommand kind)."""
        return self.kind.moveit_type

    @property
    def name(self) -> str:
        return self.controller.name


@dataclass(frozen=True, slots=True)
class ArbotixServo:
    """An ArbotiX joint: angles in [deg] (revolute only), max_speed in [deg/s]."""

    joint: str
    id: int
    min_angle: float | None
    max_angle: float | None
    max_speed: float | None


@dataclass(frozen=True, slots=True)
class GripperNode:
    """An arbotix_controllers gripper_controller node serving `<name>/gripper_action`."""

    name: str
    joint: str
    lower: float
    upper: float


@dataclass(frozen=True, slots=True)
class Ros2ControlJoint:
    """A joint of the generated ros2_control system; a mimic or passive joint has no command."""

    joint: str
    initial: float
    mimic: str | None = None
    multiplier: float = 1.0
    offset: float = 0.0
    commanded: bool = True


def description_ref(model: SetupModel, robot: RobotModel, package: tuple[str, str] | None) -> DescriptionRef:
    """Where launch files load the URDF from: `package` = (name, path inside it) when known."""
    urdf = model.robot.urdf
    is_xacro = urdf.endswith(".xacro")
    if package is not None:
        ref = DescriptionRef(package[0], package[1], is_xacro, model.robot.xacro_args)
    else:
        ref = DescriptionRef(None, f"{DESCRIPTION_COPY_DIR}/{copy_name(urdf)}", False)
    check_description_ref(ref)
    return ref


def copy_name(urdf: str) -> str:
    """The file name of the description's copy: a xacro is copied expanded (`arm.urdf.xacro`,
    `arm.xacro` -> `arm.urdf`), a URDF as it is."""
    name = PurePosixPath(urdf).name
    if name.endswith(".xacro"):
        name = name[: -len(".xacro")]
        return name if name.endswith(".urdf") else f"{name}.urdf"
    return name


def check_description_ref(ref: DescriptionRef) -> None:
    """Launch files and xacro read these verbatim: no substitution (`$`), quote or space may hide in them."""
    if ref.package is not None and (problem := name_problem("package", ref.package)):
        raise InputError(f"the URDF's package: {problem}", element="robot.urdf")
    if not ref.path.isprintable() or set(ref.path) & set("$'\"`\\"):
        raise InputError(
            f"{ref.path!r}: a URDF path that launch files can hold has no control characters, quotes, '$' or '\\'",
            element="robot.urdf",
        )
    for name, value in ref.xacro_args:
        if not XACRO_ARG_NAME.fullmatch(name):
            raise InputError(f"{name!r} is not a valid xacro argument name", element="robot.xacro_args")
        if name_problem("link", value) and value != "":
            raise InputError(
                f"{value!r}: launch files pass xacro arguments unquoted (no spaces, quotes, '$' or '\\')",
                element=f"robot.xacro_args.{name}",
            )


def group_infos(model: SetupModel, robot: RobotModel) -> list[GroupInfo]:
    """Per group (model order): active joints, kinematics, OMPL defaults and initial pose."""
    by_name = groups_by_name(model.groups)
    kin = {k.group: k for k in model.kinematics}
    planners = {p.group: p for p in model.planners}
    return [
        GroupInfo(
            name=g.name,
            active_joints=active_group_joints(g, by_name, robot, model.passive_joints),
            kinematics=kin.get(g.name),
            planner=planners.get(g.name, PlannerDefaults(g.name)),
            initial_pose=start_pose(model, g.name),
        )
        for g in model.groups
    ]


def controller_infos(model: SetupModel) -> list[ControllerInfo]:
    """ros2: each controller with the distro's ros2_controllers controller of its type."""
    if model.target != Target.ROS2:
        return []
    row = model.row
    return [
        ControllerInfo(c, row.controller(c.type))
        for c in model.controllers
        if c.type in MOVEIT_CONTROLLER_TYPES
    ]


def _servo(joint: Joint, servo_id: int, max_speed: float | None) -> ArbotixServo:
    revolute = joint.type in ("revolute", "continuous")
    lo, hi = joint.bounds
    if max_speed is None and revolute and joint.velocity:
        max_speed = round(math.degrees(joint.velocity), 3)
    angle = (lambda v: round(math.degrees(v), 3)) if revolute else (lambda v: None)
    return ArbotixServo(joint.name, servo_id, angle(lo), angle(hi), max_speed)


def arbotix_servos(model: SetupModel, robot: RobotModel) -> list[ArbotixServo]:
    """One servo per active controller joint, in tree order; ids from the setup, else the
    smallest ids the setup does not use (1, 2, ...)."""
    given = {a.joint: a for a in model.arbotix_joints}
    used = {a.id for a in model.arbotix_joints}
    free = (i for i in itertools.count(1) if i not in used)
    wanted = {j for c in model.controllers for j in c.joints}
    joints = [j for j in robot.joints_in_tree_order if j.name in wanted and j.is_active]
    servos = []
    for joint in joints:
        spec = given.get(joint.name)
        servos.append(_servo(joint, spec.id if spec else next(free), spec.max_speed if spec else None))
    return servos


def gripper_nodes(model: SetupModel, robot: RobotModel) -> list[GripperNode]:
    """An ArbotiX gripper_controller node per GripperCommand controller (its first active joint)."""
    nodes = []
    for c in model.controllers:
        active = [j for j in c.joints if j in robot.joint_map and robot.joint(j).is_active]
        if c.type == GRIPPER_COMMAND and active:
            lo, hi = robot.joint(active[0]).bounds
            nodes.append(GripperNode(c.name, active[0], lo, hi))
    return nodes


def ros2_control_joints(model: SetupModel, robot: RobotModel) -> list[Ros2ControlJoint]:
    """Every actuated joint no `<ros2_control>` of the description covers, in tree order, so each
    joint gets a state (TF) whether or not a controller drives it; mimic joints carry their
    factors (and are left out when their leader is the description's), mimic and passive joints
    get no command interface. Each starts at the demo's start state."""
    from marm_setup.robot import described_joints

    covered = described_joints(robot)
    start = model_start_values(model, robot)
    out = []
    for joint in robot.joints_in_tree_order:
        if joint.name in covered or not joint.is_actuated:
            continue
        if joint.mimic is not None and joint.mimic.joint in covered:
            continue  # mock hardware resolves a mimic within its own system; robot_state_publisher follows it
        if joint.mimic is not None:
            m = joint.mimic
            out.append(
                Ros2ControlJoint(
                    joint.name, start[joint.name], m.joint, m.multiplier, m.offset, commanded=False
                )
            )
        else:
            commanded = joint.name not in model.passive_joints
            out.append(Ros2ControlJoint(joint.name, start[joint.name], commanded=commanded))
    return out


def trajectory_demo(model: SetupModel, robot: RobotModel) -> dict | None:
    """The arm controller the demo script drives, with its home and goal positions."""
    arm = next((c for c in model.controllers if c.type == FOLLOW_JOINT_TRAJECTORY), None)
    if arm is None:
        return None
    joints = [j for j in arm.joints if j in robot.joint_map and robot.joint(j).is_active]
    states = [s for s in model.group_states if set(dict(s.values)) & set(joints)]
    home = next((s for s in states if s.name == "home"), None)
    goal = next((s for s in states if s is not home), None)
    base = {j: robot.joint(j).default_position for j in joints}
    home_q = {**base, **dict(home.values)} if home else base
    goal_q = {**base, **dict(goal.values)} if goal else {j: v + 0.3 for j, v in base.items()}
    clamp = {j: robot.joint(j).bounds for j in joints}
    # a pose may span more joints than the controller (an arm + hand pose): only its joints count
    goal_values = [min(max(goal_q[j], clamp[j][0]), clamp[j][1]) for j in joints]
    return {
        "controller": arm,
        "joints": joints,
        "home": [home_q[j] for j in joints],
        "goal": goal_values,
        "goal_name": goal.name if goal else "offset",
    }


def rviz_view(model: SetupModel, robot: RobotModel) -> dict:
    """The RViz config's MotionPlanning group (the first with an IK solver: an arm, else the first
    group) and fixed frame (the parent of the virtual joint MoveIt builds, else the root link: a
    skipped virtual joint's parent frame is in no TF tree)."""
    solved = {k.group for k in model.kinematics}
    groups = [g.name for g in model.groups]
    group = next((g for g in groups if g in solved), groups[0] if groups else "")
    root_vj = root_virtual_joint(model.virtual_joints, robot)
    frame = root_vj.parent_frame if root_vj is not None else robot.root
    return {"group": group, "fixed_frame": frame}


def static_tfs(model: SetupModel, robot: RobotModel) -> list[VirtualJoint]:
    """The virtual joints the demo publishes an identity TF for: the Setup Assistant's demo does
    so for each one, whatever its type; only the one MoveIt builds here (setup.root_virtual_joint),
    so every link keeps one TF parent (none for an identity onto itself, which tf2 refuses)."""
    vj = root_virtual_joint(model.virtual_joints, robot)
    return [vj] if vj is not None and vj.parent_frame != vj.child_link else []


def ros2_control_macro(robot_name: str) -> str:
    """The Setup Assistant's `<robot>_ros2_control` macro name, behind an '_' where the robot's
    name starts with a digit (`2dof_arm`), which no XML name may."""
    prefix = "_" if robot_name[:1].isdigit() else ""
    return f"{prefix}{robot_name}_ros2_control"


def hardware_context(
    model: SetupModel, robot: RobotModel, own_joints: list[Ros2ControlJoint], ref: DescriptionRef
) -> dict:
    """The ros2_control hardware the templates switch with use_mock_hardware (render/hardware.py)."""
    from marm_setup.render.hardware import (
        command_comment,
        description_command,
        description_hardware,
        description_launch_args,
        use_mock_hardware_help,
    )

    hw = description_hardware(robot, model.distro)
    own = model.ros2_control or Ros2ControlHardware()
    args = (
        description_launch_args(hw, ref.xacro_args, robot.hardware_args)
        if ref.package and ref.is_xacro
        else []
    )
    return {
        "hardware": own,
        "description_hardware": hw,
        "description_args": args,
        "description_command": description_command(hw, model.package_name, model.robot_name, args),
        "description_command_comment": command_comment(hw),
        "use_mock_hardware_help": use_mock_hardware_help(hw, own, bool(own_joints)),
    }


def pipeline_context(model: SetupModel) -> dict:
    """ros2: every pipeline as moveit.yaml writes it, and Humble's top-level capabilities."""
    if model.target != Target.ROS2:
        return {}
    from marm_setup.render.pipelines import pipeline_infos, top_level_capabilities

    infos = pipeline_infos(model)
    return {"ros2_pipelines": infos, "capabilities": top_level_capabilities(infos)}


def build_context(model: SetupModel, robot: RobotModel, package: tuple[str, str] | None = None) -> dict:
    """Everything the templates read, keyed by the names they use."""
    servos = plan_servos(model, robot)
    own_joints = ros2_control_joints(model, robot)
    ref = description_ref(model, robot, package)
    return {
        **hardware_context(model, robot, own_joints, ref),
        "model": model,
        "robot": robot,
        "pkg": model.package_name,
        "distro": model.distro,
        "distro_row": model.row,
        "robot_name": model.robot_name,
        "ros2_control_macro": ros2_control_macro(model.robot_name),
        "description": ref,
        "groups": group_infos(model, robot),
        "joint_limits": joint_limits(model, robot),
        "controllers": controller_infos(model),
        "follow_controllers": [c for c in model.controllers if c.type == FOLLOW_JOINT_TRAJECTORY],
        "arbotix_servos": arbotix_servos(model, robot),
        "gripper_nodes": gripper_nodes(model, robot),
        "ros2_control_joints": own_joints,
        "trajectory_demo": trajectory_demo(model, robot) if model.target == Target.ROS1 else None,
        "static_tfs": static_tfs(model, robot),
        "rviz": rviz_view(model, robot),
        "pipelines": [(name, PIPELINES[name]) for name in model.planning_pipelines],
        **pipeline_context(model),
        "mock_hardware": MOCK_HARDWARE,
        "ompl_planners": OMPL_PLANNERS,
        "cartesian_limits": CARTESIAN_LIMITS,
        "arbotix_gripper_action_ns": ARBOTIX_GRIPPER_ACTION_NS,
        "servos": servos,
        "forward_controllers": forward_controllers(servos, model.row) if model.target == Target.ROS2 else [],
        "perception": plan_perception(model, robot),
        "move_group": move_group_values(model.move_group_parameters),
    }

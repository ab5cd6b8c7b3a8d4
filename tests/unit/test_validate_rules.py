"""Break-one-thing tests: copy a good package, break exactly one thing, expect exactly that finding.

Good packages: the shared panda packages (MoveIt 1 and MoveIt 2 Setup Assistant output) and
the marm packages `init` writes (ros1: ArbotiX; ros2: single config/moveit.yaml). A case
passes when the rule fires with the expected severity and no error beyond the package's
baseline comes from any other rule than the ones the case names.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from tests.helpers import urdf
from tests.validate_helpers import (
    Good,
    copy_package,
    edit_yaml,
    generate_marm,
    panda,
    replace_text,
    run,
)

SRDF1 = "config/panda.srdf"
KIN = "config/kinematics.yaml"
LIM = "config/joint_limits.yaml"
OMPL = "config/ompl_planning.yaml"
SIMPLE = "config/simple_moveit_controllers.yaml"
FAKE = "config/fake_controllers.yaml"
R2C = "config/ros2_controllers.yaml"
MC2 = "config/moveit_controllers.yaml"


@dataclass(frozen=True)
class Case:
    id: str
    base: str  # ros1 | ros2 | marm_ros1 | marm_ros2
    edit: Callable[[Path], None]
    rule: str
    severity: str = "error"
    also: tuple[str, ...] = ()  # other error rules this break may legitimately cause
    match: str = ""  # substring of the finding's element or message
    kwargs: dict = field(default_factory=dict)


def text(rel: str, old: str, new: str) -> Callable[[Path], None]:
    return lambda pkg: replace_text(pkg, rel, old, new)


def ydata(rel: str, fn) -> Callable[[Path], None]:
    return lambda pkg: edit_yaml(pkg, rel, fn)


def delete(rel: str) -> Callable[[Path], None]:
    return lambda pkg: (pkg / rel).unlink()


def _drop_controller(name):
    def edit(data):
        data["controller_list"] = [c for c in data["controller_list"] if c["name"] != name]

    return edit


def _set_controller(name, key, value):
    def edit(data):
        for c in data["controller_list"]:
            if c["name"] == name:
                if value is None:
                    del c[key]
                else:
                    c[key] = value

    return edit


def _r2c_manager(fn):
    return ydata(R2C, lambda d: fn(d["controller_manager"]["ros__parameters"]))


def _rename_key(mapping, old, new):
    mapping[new] = mapping.pop(old)


SRDF_CASES = [
    Case(
        "duplicate-group",
        "marm_ros1",
        text(
            "config/marm.srdf",
            '<group name="gripper">',
            '<group name="gripper"/>\n    <group name="gripper">',
        ),
        "srdf.duplicate-group",
        match="defined 2 times",
    ),
    Case(
        "empty-group",
        "marm_ros1",
        text(
            "config/marm.srdf",
            '<group name="gripper">',
            '<group name="nothing"/>\n    <group name="gripper">',
        ),
        "srdf.empty-group",
        severity="warning",
        match="group[nothing]",
    ),
    Case(
        "robot-name", "ros1", text(SRDF1, '<robot name="panda">', '<robot name="pandas">'), "srdf.robot-name"
    ),
    Case(
        "group-unknown-link",
        "ros1",
        text(SRDF1, '<link name="panda_hand"/>', '<link name="panda_hnd"/>'),
        "srdf.unknown-link",
        match="group[hand].link",
    ),
    Case(
        "group-unknown-joint",
        "ros1",
        text(SRDF1, '<link name="panda_hand"/>', '<link name="panda_hand"/><joint name="panda_joint9"/>'),
        "srdf.unknown-joint",
        match="panda_joint9",
    ),
    Case(
        "chain-base-is-tip",
        "ros1",
        text(
            SRDF1,
            'base_link="panda_link0" tip_link="panda_link8"',
            'base_link="panda_link8" tip_link="panda_link8"',
        ),
        "srdf.chain-empty",
        severity="warning",
        also=(
            "pose.joint-not-in-group",
            "srdf.ee-parent-not-in-parent-group",
            "kinematics.kdl-needs-chain",
            "pose.collision",  # the arm has no joints, so `initial` ready moves nothing: it starts folded
        ),
    ),
    Case(
        "virtual-joint-below-own-link",
        "ros1",
        text(
            SRDF1,
            'parent_frame="world" child_link="panda_link0"',
            'parent_frame="panda_link3" child_link="panda_link0"',
        ),
        "srdf.virtual-joint-parent",
    ),
    Case(
        "unknown-subgroup",
        "ros1",
        text(SRDF1, '<group name="hand"/>', '<group name="hands"/>'),
        "srdf.unknown-subgroup",
    ),
    Case(
        "subgroup-cycle",
        "ros1",
        text(SRDF1, '<link name="panda_hand"/>', '<link name="panda_hand"/><group name="panda_arm_hand"/>'),
        "srdf.subgroup-cycle",
        also=("srdf.ee-parent-in-group", "pose.missing-joint"),
    ),
    Case(
        "ee-unknown-group",
        "ros1",
        text(SRDF1, 'group="hand" parent_group', 'group="hando" parent_group'),
        "srdf.ee-unknown-group",
    ),
    Case(
        "ee-unknown-parent-link",
        "ros1",
        text(SRDF1, 'parent_link="panda_link8"', 'parent_link="panda_link88"'),
        "srdf.unknown-link",
    ),
    Case(
        "ee-parent-in-group",
        "ros1",
        text(SRDF1, 'parent_link="panda_link8"', 'parent_link="panda_leftfinger"'),
        "srdf.ee-parent-in-group",
        severity="warning",  # the Setup Assistant's own check is commented out
        also=("srdf.ee-parent-not-in-parent-group",),
    ),
    Case(
        "ee-parent-not-in-parent-group",
        "ros1",
        text(SRDF1, 'parent_group="panda_arm"', 'parent_group="hand"'),
        "srdf.ee-parent-not-in-parent-group",
    ),
    Case(
        "ee-unknown-parent-group",
        "ros1",
        text(SRDF1, 'parent_group="panda_arm"', 'parent_group="arm"'),
        "srdf.ee-unknown-parent-group",
    ),
    Case(
        "virtual-joint-child",
        "ros1",
        text(SRDF1, 'child_link="panda_link0"', 'child_link="panda_link1"'),
        "srdf.virtual-joint-child",
        severity="warning",  # MoveIt skips a fixed one with a warning
    ),
    Case(
        "virtual-joint-child-floating",
        "ros1",
        text(
            SRDF1,
            'type="fixed" parent_frame="world" child_link="panda_link0"',
            'type="floating" parent_frame="world" child_link="panda_link1"',
        ),
        "srdf.virtual-joint-child",
    ),
    Case(
        "virtual-joint-type",
        "ros1",
        text(SRDF1, 'type="fixed" parent_frame', 'type="prismatic" parent_frame'),
        "srdf.virtual-joint-type",
    ),
    Case(
        "passive-unknown-joint",
        "ros1",
        text(SRDF1, "</robot>", '<passive_joint name="nope"/></robot>'),
        "srdf.unknown-joint",
        match="passive_joint[nope]",
    ),
    Case(
        "disable-unknown-link",
        "ros1",
        text(SRDF1, 'link1="panda_link0" link2="panda_link4"', 'link1="panda_link0" link2="panda_link44"'),
        "srdf.unknown-link",
        severity="warning",  # srdfdom warns and drops the pair
        match="disable_collisions",
    ),
    Case(
        "duplicate-pair",
        "ros1",
        text(
            SRDF1,
            "</robot>",
            '<disable_collisions link1="panda_link4" link2="panda_link0" reason="Never"/></robot>',
        ),
        "srdf.duplicate-pair",
        severity="warning",
        match="panda_link0 panda_link4",
    ),
    Case("srdf-malformed", "ros1", text(SRDF1, "</robot>", "</robt>"), "srdf.parse"),
    Case(
        "srdf-missing",
        "ros1",
        lambda pkg: (delete(SRDF1)(pkg), text(".setup_assistant", "SRDF:", "SRDF_NOT_READ:")(pkg)),
        "srdf.missing",
        also=("launch.missing-file",),
    ),
    Case(  # only the Setup Assistant reads .setup_assistant: move_group loads the SRDF that exists
        "srdf-missing-setup-assistant-name",
        "ros1",
        text(".setup_assistant", "relative_path: config/panda.srdf", "relative_path: config/gone.srdf"),
        "srdf.missing",
        severity="warning",
    ),
    Case(
        "ros2-srdf-xacro-unknown-group",
        "ros2",
        text("config/panda_arm_hand.srdf.xacro", 'group="hand" parent_group', 'group="hando" parent_group'),
        "srdf.ee-unknown-group",
    ),
]

POSE_CASES = [
    Case(
        "pose-missing-joint",
        "ros1",
        text(SRDF1, '<joint name="panda_joint7" value="0.785"/>', ""),
        "pose.missing-joint",
        severity="warning",  # MoveIt warns
        match="panda_joint7",
    ),
    Case(
        "pose-out-of-limits",
        "ros1",
        text(
            SRDF1, '<joint name="panda_joint4" value="-2.356"/>', '<joint name="panda_joint4" value="-3.5"/>'
        ),
        "pose.out-of-limits",
        also=("pose.collision",),  # ready is the demo's initial state other poses are checked from
        match="group_state[ready].joint[panda_joint4]",
    ),
    Case(
        "pose-unknown-joint",
        "ros1",
        text(
            SRDF1,
            '<joint name="panda_finger_joint2" value="0.035"/>',
            '<joint name="panda_finger_joint9" value="0.035"/>',
        ),
        "pose.unknown-joint",
    ),
    Case(
        "pose-joint-not-in-group",
        "ros1",
        text(
            SRDF1,
            '<joint name="panda_finger_joint2" value="0.035"/>',
            '<joint name="panda_finger_joint2" value="0.035"/><joint name="panda_joint1" value="0"/>',
        ),
        "pose.joint-not-in-group",
    ),
    Case(
        "pose-unknown-group",
        "ros1",
        text(SRDF1, 'name="extended" group="panda_arm"', 'name="extended" group="arm"'),
        "pose.unknown-group",
    ),
    Case(
        "pose-collision",
        "ros1",
        text(SRDF1, '<joint name="panda_joint6" value="1.571"/>', '<joint name="panda_joint6" value="0"/>'),
        "pose.collision",
        match="panda_link5 - panda_link7",
    ),
    Case(
        "matrix-stale",
        "ros1",
        text(
            SRDF1,
            "</robot>",
            '<disable_collisions link1="panda_link1" link2="panda_link5" reason="Never"/></robot>',
        ),
        "matrix.stale",
        severity="warning",  # MoveIt never checks a disabled pair: evidence, not an error
        match="panda_link1 panda_link5",
    ),
    Case(
        "ros2-initial-out-of-limits",
        "ros2",
        text("config/initial_positions.yaml", "panda_joint4: -2.356", "panda_joint4: 1.0"),
        "pose.initial-out-of-limits",
        also=("pose.collision",),  # the initial state is what other poses are checked from
    ),
    Case(
        "marm-ros2-initial-unknown-joint",
        "marm_ros2",
        ydata("config/initial_positions.yaml", lambda d: d["initial_positions"].update(joint9=0.0)),
        "pose.initial-unknown-joint",
        severity="warning",  # the ros2_control xacro looks up only the joints it lists: nothing fails
    ),
    Case(
        "marm-pose-out-of-limits",
        "marm_ros1",
        text("config/marm.srdf", '<joint name="joint2" value="0.0"/>', '<joint name="joint2" value="4"/>'),
        "pose.out-of-limits",
        also=("pose.collision",),
    ),
    Case(
        "marm-matrix-missing-adjacent",
        "marm_ros1",
        text("config/marm.srdf", '<disable_collisions link1="link2" link2="link3" reason="Adjacent"/>', ""),
        "matrix.always-colliding",
        match="link2 link3",
        also=("pose.collision",),  # every pose collides in the pair too
    ),
]

KINEMATICS_CASES = [
    Case(
        "kin-unknown-group",
        "ros1",
        text(KIN, "panda_arm:", "panda_armm:"),
        "kinematics.unknown-group",
        severity="warning",
    ),
    Case(
        "kin-unknown-solver",
        "ros1",
        text(KIN, "kdl_kinematics_plugin/KDLKinematicsPlugin", "my_ik/MyPlugin"),
        "kinematics.unknown-solver",
        severity="warning",
    ),
    Case(
        "kin-solver-typo",
        "ros1",
        text(KIN, "kdl_kinematics_plugin/KDLKinematicsPlugin", "kdl_kinematics_plugin/KDLKinematicPlugin"),
        "kinematics.unknown-solver",
        match="exports no solver",
    ),
    Case(
        "ros1-controller-manager-typo",
        "ros1",
        text(
            "launch/simple_moveit_controller_manager.launch.xml",
            "MoveItSimpleControllerManager",
            "MoveItSimpleControlerManager",
        ),
        "params.plugin",
        match="no controller manager",
    ),
    Case(
        "kin-attempts-ignored",
        "ros1",
        text(
            KIN,
            "kinematics_solver_timeout: 0.05",
            "kinematics_solver_timeout: 0.05\n  kinematics_solver_attempts: 3",
        ),
        "kinematics.attempts-ignored",
        severity="warning",
    ),
    Case(
        "kin-kdl-on-hand",
        "ros1",
        ydata(
            KIN, lambda d: d.update(hand={"kinematics_solver": "kdl_kinematics_plugin/KDLKinematicsPlugin"})
        ),
        "kinematics.kdl-needs-chain",
        match="hand",
    ),
    Case(
        "kin-timeout",
        "ros1",
        text(KIN, "kinematics_solver_timeout: 0.05", "kinematics_solver_timeout: 0"),
        "kinematics.non-positive",
    ),
    Case(
        "kin-resolution",
        "ros1",
        text(KIN, "kinematics_solver_search_resolution: 0.005", "kinematics_solver_search_resolution: -1"),
        "kinematics.non-positive",
    ),
    Case(
        "kin-missing-solver",
        "ros1",
        text(KIN, "kinematics_solver: ", "solver: "),
        "kinematics.missing-solver",
    ),
    Case(
        "marm-ros2-kin-in-moveit-yaml",
        "marm_ros2",
        text("config/moveit.yaml", "kdl_kinematics_plugin/KDLKinematicsPlugin", "nope/Nope"),
        "params.plugin",  # a class pluginlib cannot load: no IK solver for the group
        match="robot_description_kinematics.arm",
    ),
]

LIMIT_CASES = [
    Case(
        "limits-missing-joint",
        "ros1",
        ydata(LIM, lambda d: d["joint_limits"].pop("panda_joint7")),
        "limits.missing-joint",
        severity="warning",
        match="panda_joint7",
    ),
    Case(
        "limits-non-positive",
        "ros1",
        ydata(LIM, lambda d: d["joint_limits"]["panda_joint1"].update(max_velocity=0.0)),
        "limits.non-positive",
    ),
    Case(
        "limits-nan",
        "ros1",
        ydata(LIM, lambda d: d["joint_limits"]["panda_joint1"].update(max_velocity=float("nan"))),
        "limits.non-positive",
    ),
    Case(
        "limits-missing-value",
        "ros1",
        ydata(LIM, lambda d: d["joint_limits"]["panda_joint1"].pop("max_acceleration")),
        "limits.missing-value",
    ),
    Case(
        "limits-above-urdf",
        "ros1",
        ydata(LIM, lambda d: d["joint_limits"]["panda_joint1"].update(max_velocity=5.0)),
        "limits.above-urdf",
        severity="warning",
    ),
    Case(
        "limits-unknown-joint",
        "ros1",
        ydata(LIM, lambda d: d["joint_limits"].update(nope={"has_velocity_limits": False})),
        "limits.unknown-joint",
        severity="warning",
    ),
    Case(
        "limits-int-in-ros2",
        "ros2",
        ydata(LIM, lambda d: d["joint_limits"]["panda_joint1"].update(has_jerk_limits=True, max_jerk=300)),
        "limits.not-float",
        match="panda_joint1.max_jerk",
    ),
    Case(
        "marm-ros2-limits-int",
        "marm_ros2",
        ydata(
            "config/moveit.yaml",
            lambda d: d["/**"]["ros__parameters"]["robot_description_planning"]["joint_limits"][
                "joint1"
            ].update(max_velocity=2),
        ),
        "limits.not-float",
    ),
]

CONTROLLER_CASES = [
    Case(
        "ctrl-unknown-joint",
        "ros1",
        ydata(
            SIMPLE,
            _set_controller("hand_controller", "joints", ["panda_finger_joint1", "panda_finger_joint3"]),
        ),
        "controller.unknown-joint",
        also=("controller.driver-joints",),
    ),
    Case(
        "ctrl-uncovered",
        "ros1",
        ydata(SIMPLE, _drop_controller("hand_controller")),
        "controller.uncovered-joint",
        match="panda_finger_joint1",
    ),
    Case(
        "ctrl-unknown-type",
        "ros1",
        ydata(SIMPLE, _set_controller("hand_controller", "type", "JointTrajectory")),
        "controller.unknown-type",
    ),
    Case(
        "ctrl-missing-action-ns",
        "ros1",
        ydata(SIMPLE, _set_controller("arm_controller", "action_ns", None)),
        "controller.missing-action-ns",
        also=("controller.uncovered-joint",),  # MoveIt skips the controller: its joints go uncovered
    ),
    Case(
        "ctrl-implausible-action-ns",
        "ros1",
        ydata(SIMPLE, _set_controller("arm_controller", "action_ns", "gripper_action")),
        "controller.action-ns",
        severity="warning",
        also=("controller.driver-action",),
    ),
    Case(
        "ros1-driver-type",
        "ros1",
        ydata(
            "config/ros_controllers.yaml",
            lambda d: d["hand_controller"].update(type="position_controllers/GripperActionController"),
        ),
        "controller.driver-type",
    ),
    Case(
        "ros2-driver-missing",
        "ros2",
        _r2c_manager(lambda m: _rename_key(m, "panda_arm_controller", "arm_controller")),
        "controller.driver-missing",
        match="panda_arm_controller",
    ),
    Case(
        "ros2-driver-type",
        "ros2",
        _r2c_manager(
            lambda m: m["panda_arm_controller"].update(type="position_controllers/GripperActionController")
        ),
        "controller.driver-type",
    ),
    Case(
        "ros2-driver-action",
        "ros2",
        text(MC2, "action_ns: follow_joint_trajectory", "action_ns: joint_trajectory"),
        "controller.driver-action",
    ),
    Case(
        "ros2-driver-joints",
        "ros2",
        ydata(R2C, lambda d: d["panda_arm_controller"]["ros__parameters"]["joints"].pop()),
        "controller.driver-joints",
    ),
    Case(
        "ros2-uncovered-without-alternative",
        "ros2",
        delete("config/gripper_moveit_controllers.yaml"),
        "controller.uncovered-joint",
        match="panda_finger_joint1",
    ),
    Case(
        "no-controllers-at-all",
        "ros1",
        lambda pkg: [(pkg / rel).unlink() for rel in (SIMPLE, FAKE)],
        "controller.none",
        severity="warning",
        also=("launch.missing-file", "pose.collision"),  # launch files load them; no initial state
    ),
    Case(
        "fake-uncovered",
        "ros1",
        ydata(FAKE, lambda d: d.update(controller_list=d["controller_list"][:1])),
        "controller.fake-uncovered",
    ),
    Case(
        "fake-initial-pose",
        "ros1",
        text(FAKE, "pose: ready", "pose: readyy"),
        "controller.fake-initial-pose",
        also=("pose.collision",),  # without `ready` the arm starts folded (all zeros)
    ),
    Case(
        "arbotix-action-name",
        "marm_ros1",
        text(
            "config/arbotix.yaml",
            "action_name: arm_controller/follow_joint_trajectory",
            "action_name: follow_joint_trajectory",
        ),
        "controller.driver-action",
    ),
    Case(
        "arbotix-joints",
        "marm_ros1",
        ydata("config/arbotix.yaml", lambda d: d["controllers"]["arm_controller"]["joints"].pop()),
        "controller.driver-joints",
    ),
    Case(
        "arbotix-missing-controller",
        "marm_ros1",
        ydata("config/arbotix.yaml", lambda d: _rename_key(d["controllers"], "arm_controller", "arm")),
        "controller.driver-missing",
        also=("servo.no-controller",),  # arm_servo.yaml's output topic is /arm_controller/command
    ),
    Case(
        "arbotix-gripper-node-joint",
        "marm_ros1",
        text(
            "launch/arbotix.launch",
            '<param name="joint" value="finger_joint1"/>',
            '<param name="joint" value="joint6"/>',
        ),
        "controller.gripper-joint",
    ),
    Case(
        "arbotix-gripper-node-name",
        "marm_ros1",
        text("launch/arbotix.launch", '<node name="gripper_controller"', '<node name="gripper"'),
        "controller.driver-missing",
    ),
    Case(
        "marm-ros2-driver-type",
        "marm_ros2",
        _r2c_manager(
            lambda m: m["gripper_controller"].update(
                type="joint_trajectory_controller/JointTrajectoryController"
            )
        ),
        "controller.driver-type",
    ),
]

OMPL_CASES = [
    Case(
        "ompl-unknown-group",
        "ros1",
        text(OMPL, "\npanda_arm_hand:\n", "\npanda_arm_hando:\n"),
        "ompl.unknown-group",
        severity="warning",
    ),
    Case(
        "ompl-unknown-config",
        "ros1",
        text(OMPL, "    - SBL\n", "    - SBLX\n"),
        "ompl.unknown-planner-config",
    ),
    Case(
        "ompl-unknown-default",
        "ros1",
        text(OMPL, "default_planner_config: RRTConnect", "default_planner_config: RRTConect"),
        "ompl.unknown-default-planner",
        severity="warning",  # MoveIt plans with RRTConnect instead (ompl_interface.cpp l.224-238)
    ),
    Case(
        "ompl-unknown-type-of-the-default",
        "ros1",
        text(OMPL, "type: geometric::RRTConnect", "type: geometric::RRTConect"),
        "ompl.unknown-planner-type",
        match="the group's default config",
    ),
    Case(
        "ompl-unknown-type-listed",
        "ros1",
        text(OMPL, "type: geometric::SBL\n", "type: geometric::SBLX\n"),
        "ompl.unknown-planner-type",
        severity="warning",
    ),
    Case(
        "ompl-projection-joint-outside-the-group",
        "ros1",
        text(OMPL, "joints(panda_joint1,panda_joint2)", "joints(panda_joint1,panda_joint9)"),
        "ompl.projection-invalid",
        severity="warning",
        match="'panda_joint9' (not a joint of the group)",
    ),
    Case(
        "ompl-projection-none-left-for-kpiece",
        "ros1",
        lambda pkg: (
            replace_text(
                pkg,
                OMPL,
                "panda_arm:\n  default_planner_config: RRTConnect",
                "panda_arm:\n  default_planner_config: KPIECE",
            ),
            replace_text(pkg, OMPL, "joints(panda_joint1,panda_joint2)", "link(panda_link99)"),
        ),
        "ompl.projection-invalid",
        match="every plan fails",
    ),
    Case(
        "ros2-ompl-unknown-config",
        "ros2",
        text(OMPL, "    - TrajOptDefault\n", "    - TrajOpt\n"),
        "ompl.unknown-planner-config",
    ),
]

LAUNCH_CASES = [
    Case("launch-malformed", "ros1", text("launch/demo.launch", "</launch>", "</lunch>"), "launch.malformed"),
    Case(
        "launch-own-package-misspelt",
        "ros1",
        text(
            "launch/planning_context.launch",
            "$(find moveit_resources_panda_moveit_config)/config/panda.srdf",
            "$(find moveit_resources_panda_moveit_confg)/config/panda.srdf",
        ),
        "srdf.package-missing",
        match="which does not exist",
        also=("ros1.launch",),
    ),
    Case(
        "launch-missing-file",
        "ros1",
        text("launch/planning_context.launch", "config/panda.srdf", "config/panda2.srdf"),
        "launch.missing-file",
        match="panda2.srdf",
    ),
    Case(
        "launch-missing-include",
        "ros1",
        text("launch/demo.launch", '"$(dirname)/move_group.launch"', '"$(dirname)/move_grp.launch"'),
        "launch.missing-file",
    ),
    Case(
        "launch-undefined-arg",
        "ros1",
        text("launch/move_group.launch", 'value="$(arg pipeline)"', 'value="$(arg pipelin)"'),
        "launch.undefined-arg",
        match="pipelin",
    ),
    Case(
        "launch-undefined-arg-eval",
        "ros1",
        text("launch/demo.launch", "arg('moveit_controller_manager')", "arg('controller_manager')"),
        "launch.undefined-arg",
    ),
    Case(
        "launch-arg-only-passed-to-include",
        "ros1",
        text("launch/demo.launch", '<arg name="debug" default="false" />', ""),
        "launch.undefined-arg",
        match="'debug'",
    ),
    Case(
        "ros2-description-type",
        "marm_ros2",
        text("launch/move_group.launch.xml", 'marm.srdf\')" type="str"', "marm.srdf')\""),
        "launch.description-type",
    ),
    Case(
        "ros2-launch-missing-file",
        "marm_ros2",
        text("launch/demo.launch.xml", "config/marm.urdf.xacro", "config/marm2.urdf.xacro"),
        "launch.missing-file",
    ),
    Case(
        "package-xml-invalid",
        "ros1",
        text("package.xml", "<license>BSD</license>", ""),
        "package.invalid",
    ),
    # without its package.xml, $(find its name) is the original's folder: roslaunch loads that SRDF
    Case("package-xml-missing", "ros1", delete("package.xml"), "package.missing", also=("pose.collision",)),
    Case("yaml-malformed", "ros1", text(KIN, "panda_arm:", "panda_arm: [\n"), "yaml.parse"),
]

CASES = (
    SRDF_CASES + POSE_CASES + KINEMATICS_CASES + LIMIT_CASES + CONTROLLER_CASES + OMPL_CASES + LAUNCH_CASES
)


@pytest.fixture(scope="session")
def goods(tmp_path_factory):
    marm_root = tmp_path_factory.mktemp("marm")
    cache: dict[str, Good] = {}

    def get(base: str) -> Good:
        if base not in cache:
            cache[base] = (
                panda(base) if base in ("ros1", "ros2") else Good(generate_marm(marm_root, base[5:]))
            )
        return cache[base]

    return get


@pytest.fixture(scope="session")
def baseline(goods, tmp_path_factory):
    cache: dict[str, set] = {}

    def get(base: str) -> set:
        if base not in cache:
            good = goods(base)
            cache[base] = set(run(good.path, good))
        return cache[base]

    return get


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_break_one_thing(case: Case, goods, baseline, tmp_path_factory):
    good = goods(case.base)
    pkg = copy_package(good, tmp_path_factory.mktemp("case"))
    case.edit(pkg)
    found = run(pkg, good, **case.kwargs)
    hits = [f for f in found if f.rule == case.rule and f not in baseline(case.base)]
    assert hits, f"{case.rule} not found in {[(f.rule, f.element, f.message) for f in found]}"
    assert {f.severity for f in hits} == {case.severity}
    if case.match:
        assert any(case.match in f.element or case.match in f.message for f in hits), hits
    new_errors = {f for f in found if f.is_error} - baseline(case.base)
    unexpected = {f.rule for f in new_errors} - {case.rule, *case.also}
    assert not unexpected, [f for f in found if f.rule in unexpected]


@pytest.mark.parametrize(
    ("base", "old", "new", "severities"),
    [
        ("ros1", "default_planner_config: RRTConnect", 'default_planner_config: ""', []),
        ("ros2", "\npanda_arm:\n", '\npanda_arm:\n  default_planner_config: ""\n', ["warning"]),
    ],
)
def test_an_empty_default_planner_config_is_none_chosen_on_moveit_1(
    goods, tmp_path, base, old, new, severities
):
    """MoveIt 1 reads '' as `planner_configs/`, which roscpp cleans to the planner_configs map
    itself (names.cpp clean): loadPlannerConfiguration finds it, logs nothing, and the group gets
    RRTConnect as with no key (ompl_interface.cpp noetic l.135, l.224-238). MoveIt 2 lists
    `planner_configs.` + '', finds nothing and logs 'Could not find the planner configuration'
    (moveit2 ompl_interface.cpp l.132-138)."""
    good = goods(base)
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, OMPL, old, new)
    found = [f for f in run(pkg, good) if f.rule == "ompl.unknown-default-planner"]
    assert [str(f.severity) for f in found] == severities


def test_a_fake_controller_on_the_srdf_virtual_joint_names_a_joint_moveit_knows(goods, tmp_path):
    """The Setup Assistant lists a group's active joints in fake_controllers.yaml, the SRDF's
    planar or floating virtual joint too (moveit_config_data.cpp outputFakeControllersYAML
    l.551-567); MoveIt's model has it as its root joint, and the fake controller manager takes
    any name (moveit_fake_controller_manager.cpp l.83-122)."""
    good = goods("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, SRDF1, 'name="virtual_joint" type="fixed"', 'name="virtual_joint" type="planar"')
    replace_text(pkg, FAKE, "      - panda_joint1\n", "      - virtual_joint\n      - panda_joint1\n")
    found = [f for f in run(pkg, good) if f.rule == "controller.unknown-joint"]
    assert found == []
    replace_text(pkg, FAKE, "      - virtual_joint\n", "      - no_such_joint\n")
    assert [f.message for f in run(pkg, good) if f.rule == "controller.unknown-joint"] == [
        "unknown joint 'no_such_joint'"
    ]


@pytest.mark.parametrize(
    ("base", "tip"), [("panda_link8", "panda_link0"), ("panda_rightfinger", "panda_link3")]
)
def test_a_chain_through_the_common_root_is_what_moveit_builds(goods, baseline, tmp_path, base, tip):
    """A tip that is not below its base: MoveIt walks up from both ends to where they meet
    (robot_model.cpp addJointModelGroup), so the reversed panda arm chain is the arm again."""
    good = goods("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(
        pkg, SRDF1, 'base_link="panda_link0" tip_link="panda_link8"', f'base_link="{base}" tip_link="{tip}"'
    )
    found = set(run(pkg, good))
    assert not [f for f in found if f.rule.startswith("srdf.chain")]
    if base == "panda_link8":
        assert {f for f in found if f.is_error} <= baseline("ros1")


def test_urdf_mesh_missing(tmp_path):
    import shutil

    from tests.conftest import FIXTURES

    good = Good(generate_marm(tmp_path, "ros1"))
    robot_pkg = tmp_path / "marm_description"
    shutil.copytree(FIXTURES / "marm", robot_pkg)
    (robot_pkg / "meshes" / "link6.stl").unlink()
    found = run(good.path, good, urdf=robot_pkg / "urdf" / "marm.urdf.xacro")
    assert [f.rule for f in found] == ["urdf.mesh-missing"]
    assert "link6.stl" in found[0].message


def test_urdf_load_error(tmp_path):
    good = Good(generate_marm(tmp_path, "ros2"))
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='marm'><link name='a'>", encoding="utf-8")
    found = run(good.path, good, urdf=broken)
    assert [(f.rule, f.file) for f in found] == [("urdf.load", str(broken))]


WRONG_SHAPES = [
    "[1, 2]\n",
    "initial: [1]\ncontroller_list: [1, {name: x}]\njoint_limits: {a: 1}\npanda_arm: 3\n",
]


@pytest.mark.parametrize("shape", WRONG_SHAPES, ids=["list", "mixed"])
@pytest.mark.parametrize("rel", [KIN, LIM, OMPL, SIMPLE, FAKE, "config/ros_controllers.yaml"])
def test_wrong_yaml_shapes_are_findings_not_crashes(rel, shape, goods, tmp_path_factory):
    good = goods("ros1")
    pkg = copy_package(good, tmp_path_factory.mktemp("shape"))
    (pkg / rel).write_text(shape, encoding="utf-8")
    found = run(pkg, good, matrix_trials=0)
    assert any(f.file == rel for f in found)


def test_own_matrix_is_fresh_for_its_urdf_whatever_the_seed_and_trials(tmp_path):
    """Resampling uses the matrix's own seed and at most its trials: an unchanged URDF passes."""
    from typer.testing import CliRunner

    from marm_setup.cli.app import app
    from tests.conftest import MARM_URDF
    from tests.validate_helpers import validate_package

    out = tmp_path / "pkg"
    args = ["init", str(MARM_URDF), "--out", str(out), "--trials", "200", "--seed", "7"]
    assert CliRunner().invoke(app, args).exit_code == 0
    assert [f for f in validate_package(out, plan=False) if f.rule == "matrix.stale"] == []


def _set(keys, value):
    def edit(data):
        for key in keys[:-1]:
            data = data[key]
        data[keys[-1]] = value

    return edit


NESTED_WRONG_SHAPES = [  # (base, file, keys, value, whether it is an error)
    ("ros1", FAKE, ("initial", 0, "group"), {}, True),
    ("ros1", FAKE, ("initial",), 3, True),
    ("ros1", OMPL, ("panda_arm", "planner_configs", 0), {}, True),
    # a list is no config name: MoveIt plans the group with RRTConnect (a warning, not an error)
    ("ros1", OMPL, ("panda_arm", "default_planner_config"), [], False),
    ("ros2", MC2, ("moveit_simple_controller_manager", "controller_names", 0), {}, True),
    # an alternative controllers file is only consulted for coverage: no finding, no crash
    (
        "ros2",
        "config/gripper_moveit_controllers.yaml",
        ("moveit_simple_controller_manager", "controller_names", 0),
        {},
        False,
    ),
    ("ros2", R2C, ("panda_arm_controller", "ros__parameters"), 3, True),
    ("ros2", R2C, ("controller_manager",), "x", True),
    ("marm_ros1", "config/arbotix.yaml", ("controllers",), ["arm_controller"], True),
]


@pytest.mark.parametrize(("base", "rel", "keys", "value", "is_error"), NESTED_WRONG_SHAPES)
def test_wrong_nested_yaml_shapes_are_findings_not_crashes(
    base, rel, keys, value, is_error, goods, tmp_path_factory
):
    good = goods(base)
    pkg = copy_package(good, tmp_path_factory.mktemp("nested"))
    edit_yaml(pkg, rel, _set(keys, value))
    found = run(pkg, good, matrix_trials=0)
    new_errors = {f for f in found if f.is_error} - set(run(good.path, good, matrix_trials=0))
    assert bool(new_errors) == is_error, found


LINK = '<link name="base"><collision><geometry><mesh filename="{uri}"/></geometry></collision></link>'


@pytest.mark.parametrize(
    "body, rule, hinted",
    [
        (LINK.format(uri="meshes/nope.stl"), "urdf.mesh-missing", False),
        (LINK.format(uri="package://nopkg/meshes/base.stl"), "urdf.package-missing", True),  # PackageNotFound
        # text that mentions a mesh, "not found" and a package, but the error is an unknown link
        ('<link name="a"/><joint name="mesh not found" type="fixed"><parent link="a"/>'
         '<child link="package_link"/></joint>', "urdf.load", False),
    ],
)  # fmt: skip
def test_urdf_rule_and_hint_come_from_the_error_type(tmp_path, body, rule, hinted):
    good = Good(generate_marm(tmp_path, "ros2"))
    broken = tmp_path / "robot.urdf"
    broken.write_text(urdf(body, name="marm"), encoding="utf-8")
    (found,) = run(good.path, good, urdf=broken)
    assert found.rule == rule
    assert bool(found.hint) == hinted, found


def test_a_mesh_in_a_package_no_path_holds_is_a_warning_not_an_error(tmp_path):
    """MoveIt resolves `package://` where ROS has the package installed: validate, holding no
    path to it, cannot tell it is missing (as for the description's own package); a mesh file
    missing from a package at hand stays an error."""
    good = Good(generate_marm(tmp_path, "ros1"))
    broken = tmp_path / "robot.urdf"
    broken.write_text(urdf(LINK.format(uri="package://nopkg/meshes/base.stl"), name="marm"), encoding="utf-8")
    (found,) = run(good.path, good, urdf=broken)
    assert (found.rule, str(found.severity)) == ("urdf.package-missing", "warning")
    assert "(the folder holding nopkg)" in found.hint
    broken.write_text(urdf(LINK.format(uri="meshes/nope.stl"), name="marm"), encoding="utf-8")
    (found,) = run(good.path, good, urdf=broken)
    assert (found.rule, str(found.severity)) == ("urdf.mesh-missing", "error")


def test_a_ros1_driver_file_without_action_controllers_is_not_moveits_driver(tmp_path):
    """A ros_controllers.yaml with only a joint_state_controller beside the hardware interface:
    MoveIt's action servers come from another package's driver (nothing here serves one), so
    no controller.driver-missing; a trajectory controller in the file makes it the driver."""
    good = Good(generate_marm(tmp_path, "ros1"))
    driver = good.path / "config" / "ros_controllers.yaml"
    state = "joint_state_controller:\n  type: joint_state_controller/JointStateController\n"
    driver.write_text(state, encoding="utf-8")
    assert "controller.driver-missing" not in {f.rule for f in run(good.path, good)}
    trajectory = "other:\n  type: position_controllers/JointTrajectoryController\n  joints: [joint1]\n"
    driver.write_text(state + trajectory, encoding="utf-8")
    assert "controller.driver-missing" in {f.rule for f in run(good.path, good) if f.is_error}


def test_a_solver_of_a_package_the_package_depends_on_is_not_unknown(tmp_path):
    """pluginlib finds a solver among every installed package's plugins: one whose name starts
    with a package package.xml depends on (a third-party solver such as OPW) is installed with
    the package, so no kinematics.unknown-solver; the same name without the dependency is."""
    good = Good(generate_marm(tmp_path, "ros1"))
    replace_text(
        good.path, "config/kinematics.yaml", "kdl_kinematics_plugin/KDLKinematicsPlugin", "my_ik/MyIk"
    )
    assert "kinematics.unknown-solver" in {f.rule for f in run(good.path, good)}
    replace_text(
        good.path, "package.xml", "<exec_depend>", "<exec_depend>my_ik</exec_depend>\n  <exec_depend>"
    )
    assert "kinematics.unknown-solver" not in {f.rule for f in run(good.path, good)}


def test_a_global_controller_name_is_valid_in_a_moveit1_list(tmp_path):
    """MoveIt 1's simple manager connects to `<name>/<action_ns>` (action_based_controller_handle.h
    l.140-145): a global name such as Baxter's `/robot/limb/right` is a valid ROS name there."""
    good = Good(generate_marm(tmp_path, "ros1"))
    replace_text(good.path, "config/controllers.yaml", "name: arm_controller", "name: /arm_controller")
    assert "names.invalid" not in {f.rule for f in run(good.path, good)}
    replace_text(good.path, "config/controllers.yaml", "name: /arm_controller", "name: /arm controller")
    assert "names.invalid" in {f.rule for f in run(good.path, good)}


def test_a_trailing_slash_in_a_moveit1_controller_name_is_valid(tmp_path):
    """roscpp cleans the action name `<name>/<action_ns>` it resolves (ros_comm names.cpp
    `resolve` l.177 -> `clean` l.99-116: '//' collapsed, a trailing '/' dropped): MoveIt's own
    prbt_moveit_config names `prbt/manipulator_joint_trajectory_controller/`."""
    good = Good(generate_marm(tmp_path, "ros1"))
    replace_text(good.path, "config/controllers.yaml", "name: arm_controller", "name: arm_controller/")
    assert "names.invalid" not in {f.rule for f in run(good.path, good)}
    replace_text(good.path, "config/controllers.yaml", "name: arm_controller/", "name: arm-controller/")
    assert "names.invalid" in {f.rule for f in run(good.path, good)}

"""Inference for `init`: the marm course setup, the shared panda, inline robots, SPEC merging."""

from __future__ import annotations

import dataclasses

import pytest

from marm_setup.errors import InputError
from marm_setup.inference.infer import derive_group_settings
from marm_setup.inference.infer import infer_setup as infer
from marm_setup.inference.limb_tips import tool_frame
from marm_setup.robot.load import load_robot
from marm_setup.setup.checks import check_setup
from marm_setup.setup.model import Chain, Controller, EndEffector, Group, GroupState, RobotSource
from tests.conftest import MARM_URDF, realworld
from tests.helpers import ARM, FINGERS, build_file_tree, fixed_link, urdf

SOURCE = RobotSource("robot.urdf")


def test_marm_matches_the_course_setup():
    robot = load_robot(MARM_URDF)
    model = infer(robot, package_name="marm_moveit_config", source=SOURCE, target="ros1").model
    model = derive_group_settings(dataclasses.replace(model, driver="arbotix"), robot)
    assert model.groups == (
        Group("arm", chain=Chain("base_link", "grasping_frame")),
        Group(
            "gripper",
            joints=("finger_joint1", "finger_joint2"),
            links=("gripper_finger_link1", "gripper_finger_link2"),
        ),
    )
    assert model.end_effectors == (EndEffector("gripper", "gripper", "grasping_frame", "arm"),)
    assert model.group_states == (
        GroupState("home", "arm", tuple((f"joint{i}", 0.0) for i in range(1, 7))),
        GroupState("home", "gripper", (("finger_joint1", 0.0),)),
    )
    arm, gripper = model.controllers
    assert arm == Controller(
        "arm_controller",
        "FollowJointTrajectory",
        "follow_joint_trajectory",
        tuple(f"joint{i}" for i in range(1, 7)),
        "arm",
    )
    assert gripper == Controller(
        "gripper_controller", "GripperCommand", "gripper_action", ("finger_joint1",), "gripper"
    )
    (kin,) = model.kinematics
    assert (kin.group, kin.solver, kin.search_resolution, kin.timeout) == (
        "arm",
        "kdl_kinematics_plugin/KDLKinematicsPlugin",
        0.005,
        0.05,
    )
    assert [a.joint for a in model.arbotix_joints][-1] == "finger_joint1"
    check_setup(model, robot, "x")


def test_ros2_gripper_action_is_gripper_cmd_and_no_arbotix():
    model = infer(load_robot(MARM_URDF), package_name="p", source=SOURCE, target="ros2").model
    assert model.controllers[1].action_ns == "gripper_cmd"
    assert model.arbotix_joints == ()


def test_ros1_without_a_driver_has_no_arbotix_servos_and_any_gripper_action():
    model = infer(load_robot(MARM_URDF), package_name="p", source=SOURCE, target="ros1").model
    assert model.driver is None and model.arbotix_joints == ()
    assert model.controllers[1].action_ns == "gripper_cmd"


def test_marm_without_gripper_has_arm_only():
    robot = load_robot(MARM_URDF, {"with_gripper": "false"})
    model = infer(robot, package_name="p", source=SOURCE).model
    assert [g.name for g in model.groups] == ["arm"]
    assert model.groups[0].chain == Chain("base_link", "grasping_frame")
    assert model.end_effectors == ()


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_shared_panda_arm_to_flange_and_hand_group(target):
    root = realworld(target)
    if target == "ros1":
        robot = load_robot(root / "panda_description/urdf/panda_arm_hand.urdf.xacro", package_paths=[root])
    else:
        robot = load_robot(root / "panda_description/urdf/panda.urdf")
    model = infer(robot, package_name="p", source=SOURCE, target=target).model
    arm, hand = model.groups
    assert arm.chain == Chain("panda_link0", "panda_link8")
    assert hand.joints == ("panda_finger_joint1", "panda_finger_joint2")
    assert hand.links[:3] == ("panda_hand", "panda_leftfinger", "panda_rightfinger")
    assert model.end_effectors[0].parent_link == "panda_link8"
    assert len(model.group_states[0].values) == 7
    check_setup(model, robot, "x")


PANDA_LIKE = (
    ARM
    + fixed_link("l3", "flange")
    + fixed_link("flange", "hand", True)
    + fixed_link("hand", "hand_tcp")
    + FINGERS
)


def _model(tmp_path, body: str):
    build_file_tree(tmp_path, {"r.urdf": urdf(body)})
    robot = load_robot(tmp_path / "r.urdf")
    return robot, infer(robot, package_name="p", source=SOURCE).model


def test_an_arm_ends_at_its_tcp_past_the_hands_fixed_links(tmp_path):
    """As MoveIt's panda_manipulator (panda_moveit_config, config/panda.srdf.xacro: chain to
    panda_hand_tcp, end effector on it): the tip is the tool frame below the hand; the hand group
    holds the hand and its fingers, not the flange, the TCP or a camera (its body or frames)."""
    camera = fixed_link("hand", "camera_link", True) + fixed_link("camera_link", "camera_color_optical_frame")
    robot, model = _model(tmp_path, PANDA_LIKE + camera + fixed_link("hand", "hand_motor", True))
    arm, hand = model.groups
    assert arm == Group("arm", chain=Chain("base", "hand_tcp"))
    assert hand.links == ("hand", "finger_l", "finger_r", "hand_motor")  # a motor's body is the hand's
    assert model.end_effectors == (EndEffector("hand", "hand", "hand_tcp", "arm"),)
    check_setup(model, robot, "x")


@pytest.mark.parametrize(
    ("frames", "tip"),
    [
        # no tool frame past the hand: the geometry-less frames after the last link (a flange)
        (fixed_link("l3", "flange") + fixed_link("flange", "hand", True), "flange"),
        # UR, Fanuc: flange, then tool0 (a tool frame before a flange)
        (fixed_link("l3", "flange") + fixed_link("flange", "tool0"), "tool0"),
        # a grasp frame in the hand before a tool frame at the wrist
        (fixed_link("l3", "tool0") + fixed_link("tool0", "hand", True) + fixed_link("hand", "grasping_frame"), "grasping_frame"),
        # a gripper frame (Baxter's right_gripper) but not the gripper's body; no fingertip
        (fixed_link("l3", "gripper_base", True) + fixed_link("gripper_base", "gripper") + fixed_link("l3", "finger_tip", True), "gripper"),
        # an end effector frame; a camera's frame is none
        (fixed_link("l3", "camera_tool_frame") + fixed_link("l3", "end_effector_link"), "end_effector_link"),
        # Kinova's tool_frame (its gripper's TCP, kortex_description gen3_lite_2f_macro.xacro) below
        # its end_effector_link: the farther of two frames named alike
        (fixed_link("l3", "end_effector_link") + fixed_link("end_effector_link", "tool_frame"), "tool_frame"),
    ],
)  # fmt: skip
def test_the_tool_frame_is_the_best_named_frame_fixed_below_the_arm(tmp_path, frames, tip):
    _, model = _model(tmp_path, ARM + frames)
    assert model.groups[0].chain == Chain("base", tip)
    assert tool_frame(load_robot(tmp_path / "r.urdf"), "l3") == tip


def test_home_keeps_off_the_joint_limits_and_a_hand_at_its_own(tmp_path):
    """Zero for a joint whose limits leave room around it; else the nearest value a tenth of the
    range (at most 0.3) inside the limits; a gripper's home stays where its range ends (closed)."""
    _, model = _model(tmp_path, PANDA_LIKE)
    home = {(s.group, j): v for s in model.group_states if s.name == "home" for j, v in s.values}
    assert home == {
        ("arm", "j1"): 0.55,
        ("arm", "j2"): -0.2127,
        ("arm", "j3"): 0.0,
        ("hand", "finger_joint_l"): 0.0,
    }


def test_robot_without_actuated_joints_is_an_input_error(tmp_path):
    body = '<link name="a"/><link name="b"/><joint name="f" type="fixed"><parent link="a"/><child link="b"/></joint>'
    build_file_tree(tmp_path, {"r.urdf": urdf(body)})
    with pytest.raises(InputError, match="no actuated joints that form a limb.*docs/setup-file.md"):
        infer(load_robot(tmp_path / "r.urdf"), package_name="p", source=SOURCE)


def test_a_spec_patches_the_setup_by_key_and_by_item_name():
    """`collision: {trials}` keeps the other collision keys, a named item replaces the one of its
    name, a list of unnamed values replaces the list; the patch is typed as marm_setup.yaml is."""
    from marm_setup.inference.assemble import apply_patch
    from marm_setup.setup.model import Author, GroupState, RobotSource, SetupModel
    from marm_setup.setup.yaml_io import patch_from_dict

    base = SetupModel(
        "p",
        "r",
        RobotSource("x"),
        author=Author("a", "e"),
        group_states=(GroupState("home", "arm", (("j", 0.0),)),),
        passive_joints=("x",),
    )
    spec = {
        "author": {"name": "b"},
        "collision": {"trials": 2000},
        "group_states": [
            {"name": "forward", "group": "arm", "values": {"j": 0.4}},
            {"name": "home", "group": "arm", "values": {"j": 0.1}},
        ],
        "passive_joints": ["y"],
    }
    merged = apply_patch(base, patch_from_dict(spec, "spec.yaml"))
    assert merged.author == Author("b", "e")
    assert (merged.collision.trials, merged.collision.seed) == (2000, base.collision.seed)
    assert [s.name for s in merged.group_states] == ["home", "forward"]
    assert merged.group_states[0].values == (("j", 0.1),)
    assert merged.passive_joints == ("y",)
    with pytest.raises(InputError, match="collision.trials"):
        patch_from_dict({"collision": {"trials": "many"}}, "spec.yaml")

"""Inference on kinematic trees: synthetic fixtures (dual-arm table, humanoid, legged base with an
arm, wheeled manipulator, and the cases inference once got wrong), inline trees, the real robots
of ../shared/realworld*, and collision-free poses."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.scene import CollisionScene
from marm_setup.inference.infer import infer_setup as infer
from marm_setup.inference.poses import infer_poses
from marm_setup.robot.limb_words import tokens
from marm_setup.robot.load import load_robot
from marm_setup.setup.groups import active_group_joints, groups_by_name
from marm_setup.setup.model import Chain, CollisionSettings, Group, RobotSource
from marm_setup.setup.srdf import read_srdf
from tests import synthetic_robots
from tests.conftest import FIXTURES, REALWORLD, realworld
from tests.helpers import build_file_tree, urdf

SYNTHETIC = FIXTURES / "synthetic"
SOURCE = RobotSource("robot.urdf")


def _infer(robot):
    return infer(robot, package_name="p", source=SOURCE)


def test_fixture_files_are_current():
    for name, build in synthetic_robots.ROBOTS.items():
        assert (SYNTHETIC / f"{name}.urdf").read_text(encoding="utf-8") == build(), (
            "run `python -m tests.synthetic_robots`"
        )


EXPECTED = {
    "dual_arm_table": (
        ["left_arm", "left_gripper", "right_arm", "right_gripper", "arms", "whole_body"],
        ("fixed", "world", "table"),
    ),
    "humanoid": (
        ["torso", "head", "left_arm", "left_hand", "right_arm", "right_hand", "left_leg", "right_leg"]
        + ["arms", "legs", "whole_body"],
        ("floating", "odom", "pelvis"),
    ),
    "legged_arm": (
        ["front_left_leg", "front_right_leg", "hind_left_leg", "hind_right_leg", "arm", "gripper"]
        + ["legs", "whole_body"],
        ("floating", "odom", "base"),
    ),
    "wheeled_manipulator": (
        ["torso", "arm", "gripper", "whole_body"],
        ("planar", "odom", "base_footprint"),
    ),
}


@pytest.mark.parametrize("name", list(EXPECTED))
def test_synthetic_robots_groups_and_base(name):
    groups, (kind, parent, child) = EXPECTED[name]
    result = _infer(load_robot(SYNTHETIC / f"{name}.urdf"))
    model = result.model
    assert [g.name for g in model.groups] == groups
    (vj,) = model.virtual_joints
    assert (vj.type, vj.parent_frame, vj.child_link) == (kind, parent, child)
    hands = [g.name for g in model.groups if "gripper" in g.name or "hand" in g.name]
    assert sorted(e.group for e in model.end_effectors) == sorted(hands)
    assert all(e.parent_group for e in model.end_effectors)
    # one controller per limb and hand; a gripper of one joint and its mimic: GripperCommand
    kinds = {c.group: c.type for c in model.controllers}
    assert all(kinds[h] == "GripperCommand" for h in hands)
    assert not {"arms", "legs", "whole_body"} & set(kinds)


# Robots inference once got wrong: (groups, virtual joint (type, parent, child)).
ONCE_WRONG = {
    # FR/FL/RR/RL: front/rear first, then the side; legs to their foot links on fixed joints
    "unitree_quadruped": (
        ["front_right_leg", "front_left_leg", "rear_right_leg", "rear_left_leg", "legs", "whole_body"],
        ("floating", "odom", "base"),
    ),
    # limbs with visual shapes or none are limbs all the same; a pan-tilt camera mount is not
    "bare_humanoid": (
        ["right_leg", "left_leg", "torso", "head", "right_arm", "left_arm", "arms", "legs", "whole_body"],
        ("floating", "odom", "base_link"),
    ),
    # `wrist_roll` moves a link called `gripper`: still the arm's
    "wrist_gripper_arm": (["arm", "gripper"], ("fixed", "world", "base")),
    # suspension + wheel chains and two-joint casters belong to the base
    "suspended_base": (["torso", "arm", "gripper", "whole_body"], ("planar", "odom", "base_footprint")),
    # four unnamed fingers on a palm: one hand, no arms
    "finger_hand": (["hand"], ("fixed", "world", "palm")),
    # rotors: a flying base, and no group
    "rotor_arm": (["arm"], ("floating", "odom", "body")),
}


@pytest.mark.parametrize("name", list(ONCE_WRONG))
def test_robots_inference_once_got_wrong(name):
    groups, (kind, parent, child) = ONCE_WRONG[name]
    model = _infer(load_robot(SYNTHETIC / f"{name}.urdf")).model
    assert [g.name for g in model.groups] == groups
    (vj,) = model.virtual_joints
    assert (vj.type, vj.parent_frame, vj.child_link) == (kind, parent, child)


def test_legs_end_at_their_foot_or_sole_frame_geometry_or_not():
    by_name = groups_by_name(_infer(load_robot(SYNTHETIC / "unitree_quadruped.urdf")).model.groups)
    assert [by_name[f"{c}_leg"].chain.tip for c in ("front_right", "rear_left")] == ["FR_foot", "RL_foot"]
    robot = load_robot(SYNTHETIC / "bare_humanoid.urdf")
    by_name = groups_by_name(_infer(robot).model.groups)
    assert (by_name["right_leg"].chain.tip, by_name["left_leg"].chain.tip) == ("r_sole", "l_sole")


def test_limbs_without_collision_geometry_are_limbs_and_a_camera_mount_is_not():
    robot = load_robot(SYNTHETIC / "bare_humanoid.urdf")
    result = _infer(robot)
    by_name = groups_by_name(result.model.groups)
    assert by_name["right_arm"].chain.base == "chest" and by_name["head"].chain.tip == "NECK_LINK2"
    assert not any(robot.link(x).has_geometry for x in robot.subtree_links("RLEG_LINK1"))
    assert "left out of every group: single joints pan_joint, tilt_joint (not a limb)" in result.notes


def test_a_wrist_joint_stays_in_the_arm_and_a_one_joint_gripper_gets_gripper_command():
    model = _infer(load_robot(SYNTHETIC / "wrist_gripper_arm.urdf")).model
    arm, gripper = model.groups
    assert arm.chain == Chain("base", "gripper_frame") and gripper.joints == ("gripper",)
    controllers = {c.group: (c.type, c.joints) for c in model.controllers}
    assert controllers["arm"][1][-1] == "wrist_roll"
    assert controllers["gripper"] == ("GripperCommand", ("gripper",))


def test_suspensions_wheels_and_casters_are_the_base():
    result = _infer(load_robot(SYNTHETIC / "suspended_base.urdf"))
    grouped = {j for c in result.model.controllers for j in c.joints}
    assert not {j for j in grouped if "wheel" in j or "suspension" in j or "caster" in j}
    base = "suspension_right_joint, wheel_right_joint, suspension_left_joint, wheel_left_joint"
    assert f"left out of every group: wheel joints {base}, caster_1_joint, caster_2_joint" in result.notes


def test_a_bare_hand_is_one_hand_group_with_every_finger():
    model = _infer(load_robot(SYNTHETIC / "finger_hand.urdf")).model
    (hand,) = model.groups
    assert hand.joints == tuple(f"joint_{i}" for i in range(16))
    assert model.end_effectors == ()
    (controller,) = model.controllers
    assert controller.type == "FollowJointTrajectory"


def test_rotors_make_a_flying_base_and_no_group():
    result = _infer(load_robot(SYNTHETIC / "rotor_arm.urdf"))
    assert [c.joints for c in result.model.controllers] == [("arm_joint1", "arm_joint2")]
    assert "guessed: a flying base (4 rotor joints): floating virtual joint odom -> body" in result.notes


# -- inline trees ----------------------------------------------------------------------------------

BOX = '<collision><geometry><box size="0.02 0.02 0.02"/></geometry></collision>'


def _tree(tmp_path, rows, *, name="test_robot", bare=(), step=0.1):
    """A robot from (joint, type, parent, child) rows: each link a small box unless in `bare`,
    each joint `step` [m] after its parent link."""
    links = dict.fromkeys(x for _, _, parent, child in rows for x in (parent, child))
    body = [f'<link name="{x}">{"" if x in bare else BOX}</link>' for x in links]
    for joint, kind, parent, child in rows:
        limit = {"fixed": "", "continuous": '<limit velocity="1" effort="1"/>'}.get(
            kind, '<limit lower="-1" upper="1" velocity="1" effort="1"/>'
        )
        body.append(
            f'<joint name="{joint}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f'<origin xyz="0 0 {step}"/><axis xyz="0 1 0"/>{limit}</joint>'
        )
    build_file_tree(tmp_path, {"r.urdf": urdf("\n".join(body), name)})
    return load_robot(tmp_path / "r.urdf")


def _serial(names, first, link="l"):
    """Revolute rows for `names` in a chain from link `first`; links `<link>1`, `<link>2`, ..."""
    parents = [first, *(f"{link}{i}" for i in range(1, len(names)))]
    return [(n, "revolute", p, f"{link}{i}") for i, (n, p) in enumerate(zip(names, parents, strict=True), 1)]


ARM = ["shoulder_pitch", "shoulder_roll", "elbow", "wrist_pitch"]


def test_a_wrist_moving_a_link_called_hand_is_the_arms(tmp_path):
    """`l_wrist_yaw` moves `l_hand` (no fingers after it): the arm's last joint, no hand group."""
    rows = [*_serial(ARM, "base"), ("l_wrist_yaw", "revolute", "l4", "l_hand")]
    rows += [("grip", "fixed", "l_hand", "l_gripper"), ("dh", "fixed", "l_hand", "l_hand_dh_frame")]
    model = _infer(_tree(tmp_path, rows, bare={"l_gripper", "l_hand_dh_frame"})).model
    assert model.groups == (Group("arm", chain=Chain("base", "l_gripper")),)
    rows = [*_serial([*ARM, "WristYaw", "LeftGripperYaw"], "base"), ("nub", "fixed", "l6", "leftNub")]
    model = _infer(_tree(tmp_path, rows)).model
    assert [(c.group, c.type, c.joints[-1]) for c in model.controllers] == [
        ("arm", "FollowJointTrajectory", "LeftGripperYaw")
    ]


def test_a_leg_on_a_wheel_keeps_its_leg_and_gives_the_wheel_to_the_base(tmp_path):
    rows = []
    for i in (1, 2):
        rows += _serial([f"hip_yaw_{i}", f"knee_pitch_{i}", f"ankle_pitch_{i}"], "pelvis", f"leg{i}_")
        rows.append((f"j_wheel_{i}", "continuous", f"leg{i}_3", f"wheel_{i}"))
    result = _infer(_tree(tmp_path, rows))
    assert [g.name for g in result.model.groups] == ["leg_1", "leg_2", "legs", "whole_body"]
    assert [c.joints[-1] for c in result.model.controllers] == ["ankle_pitch_1", "ankle_pitch_2"]
    assert result.model.virtual_joints[0].type == "floating"
    assert "left out of every group: wheel joints j_wheel_1, j_wheel_2" in result.notes


def test_short_unnamed_fingers_make_a_hand_and_long_chains_do_not(tmp_path):
    rows = [r for f in range(3) for r in _serial([f"j{f}{i}" for i in range(3)], "base_link", f"f{f}_")]
    model = _infer(_tree(tmp_path, rows, step=0.03)).model
    assert [(g.name, len(g.joints)) for g in model.groups] == [("hand", 9)]
    model = _infer(_tree(tmp_path, rows, step=0.15)).model
    assert "hand" not in [g.name for g in model.groups]


def test_a_base_named_flying_floats(tmp_path):
    rows = [("mount", "fixed", "base", "flying_arm_base"), *_serial(["arm_j1", "arm_j2"], "flying_arm_base")]
    (vj,) = _infer(_tree(tmp_path, rows)).model.virtual_joints
    assert (vj.type, vj.parent_frame) == ("floating", "odom")


def test_a_named_limb_without_geometry_counts_and_a_transmission_does_not(tmp_path):
    """alexander's `SPINE_Z` moves a torso with no collision geometry: a torso; PR2's
    `torso_lift_motor_screw_joint` moves nothing visible either: no limb."""
    rows = [("SPINE_Z", "revolute", "PELVIS", "TORSO_LINK"), *_serial(ARM, "PELVIS")]
    rows.append(("torso_lift_motor_screw_joint", "continuous", "PELVIS", "screw_link"))
    result = _infer(_tree(tmp_path, rows, bare={"TORSO_LINK", "screw_link"}))
    assert [g.name for g in result.model.groups] == ["torso", "arm", "whole_body"]
    assert any("torso_lift_motor_screw_joint (not a limb)" in n for n in result.notes)


def test_wheels_and_single_sensor_joints_are_left_out_and_said():
    result = _infer(load_robot(SYNTHETIC / "wheeled_manipulator.urdf"))
    assert "left out of every group: wheel joints left_wheel_joint, right_wheel_joint" in result.notes
    assert any("camera_tilt_joint" in n for n in result.notes)
    assert result.notes[-1].endswith("(see docs/setup-file.md)")


def test_tokens_split_the_usual_naming_styles():
    assert tokens("LShoulderPitch") == ["l", "shoulder", "pitch"]
    assert tokens("arm_left_joint_1_s") == ["arm", "left", "joint", "1", "s"]
    assert tokens("LF_HAA") == ["lf", "haa"]
    assert tokens("panda_1_joint7") == ["panda", "1", "joint", "7"]


def test_root_world_gets_no_virtual_joint(tmp_path):
    body = """
    <link name="world"/><link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
    <link name="b"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
    <joint name="fix" type="fixed"><parent link="world"/><child link="a"/></joint>
    <joint name="j" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.2"/>
      <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
    """
    build_file_tree(tmp_path, {"r.urdf": urdf(body)})
    assert _infer(load_robot(tmp_path / "r.urdf")).model.virtual_joints == ()


# -- the real robots -------------------------------------------------------------------------------

REAL = {
    # name: (urdf, shipped srdf, package path, xacro args)
    "pr2": (
        "realworld/ros1/pr2_description/urdf/robot.xml",
        "realworld/ros1/pr2_description/srdf/robot.xml",
        "",
        {},
    ),
    "dual_panda": (
        "realworld2/moveit_resources_master/panda_description/urdf/dual_panda.urdf.xacro",
        "realworld2/moveit_resources_master/dual_panda_moveit_config/config/panda.srdf",
        "realworld2/moveit_resources_master",
        {},
    ),
    "sda10f": (
        "realworld2/motoman/motoman_sda10f_support/urdf/sda10f.xacro",
        "realworld2/motoman/motoman_sda10f_moveit_config/config/motoman_sda10f.srdf",
        "realworld2/motoman",
        {},
    ),
    "ur5e": (
        "realworld2/universal_robot/ur_description/urdf/ur5e.xacro",
        "realworld2/universal_robot/ur5e_moveit_config/config/ur5e.srdf",
        "realworld2/universal_robot",
        {},
    ),
    "j2n6s300": (
        "realworld2/kinova-ros/kinova_description/urdf/j2n6s300_standalone.xacro",
        "realworld2/kinova-ros/kinova_moveit/robot_configs/j2n6s300_moveit_config/config/j2n6s300.srdf",
        "realworld2/kinova-ros",
        {},
    ),
    "panda": (
        "realworld/ros1/panda_description/urdf/panda_arm_hand.urdf.xacro",
        "realworld/ros1/panda_moveit_config/config/panda.srdf",
        "realworld/ros1",
        {},
    ),
}


def _shared(rel: str):
    path = REALWORLD.parent / rel
    if not path.exists():
        pytest.skip(f"{path} not present")
    return path


def _limb_joint_sets(groups, robot, ees):
    """Active joint sets of the limb groups: no subgroups, not an end effector, two or more joints."""
    by_name = groups_by_name(groups)
    hands = {e.group for e in ees}
    sets = [
        frozenset(active_group_joints(g, by_name, robot))
        for g in groups
        if not g.subgroups and g.name not in hands
    ]
    return {s for s in sets if len(s) > 1}


@pytest.mark.parametrize("name", list(REAL))
def test_real_robot_limbs_match_the_shipped_srdf(name):
    rel_urdf, rel_srdf, rel_pkg, args = REAL[name]
    packages = [_shared(rel_pkg)] if rel_pkg else []
    robot = load_robot(_shared(rel_urdf), args, packages)
    model = _infer(robot).model
    shipped = read_srdf(_shared(rel_srdf))
    ours = _limb_joint_sets(model.groups, robot, model.end_effectors)
    theirs = _limb_joint_sets(shipped.groups, robot, shipped.end_effectors)
    assert theirs <= ours


def test_pr2_is_a_wheeled_two_armed_robot():
    robot = load_robot(realworld("ros1", "pr2_description/urdf/robot.xml"))
    model = _infer(robot).model
    by_name = groups_by_name(model.groups)
    assert by_name["right_arm"].chain.base == "torso_lift_link"
    assert by_name["right_arm"].chain.tip == "r_gripper_tool_frame"  # the TCP past its palm
    assert model.virtual_joints[0].type == "planar"
    assert {e.parent_link for e in model.end_effectors} == {"l_gripper_tool_frame", "r_gripper_tool_frame"}
    assert not any("caster" in j for c in model.controllers for j in c.joints)


# -- poses ----------------------------------------------------------------------------------------

LYING_ARM = """
<link name="base"><collision><geometry><box size="1 1 0.1"/></geometry></collision></link>
<link name="l1"><collision><origin xyz="0 0 0.025"/><geometry><box size="0.05 0.05 0.05"/></geometry></collision></link>
<link name="l2"><collision><origin xyz="0.5 0 0"/><geometry><box size="0.6 0.02 0.12"/></geometry></collision></link>
<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.05"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
<joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.05"/><axis xyz="0 1 0"/>
  <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
"""


def test_home_moves_off_zeros_that_collide_and_ready_is_free(tmp_path):
    build_file_tree(tmp_path, {"r.urdf": urdf(LYING_ARM)})
    robot = load_robot(tmp_path / "r.urdf")
    model = _infer(robot).model
    adjacent = tuple(
        DisabledPair.of(a, b, DisabledReason.ADJACENT.value) for a, b in robot.adjacent_geometry_pairs()
    )
    model = dataclasses.replace(model, collision=CollisionSettings(disabled=adjacent))
    scene = CollisionScene(robot)
    result = infer_poses(model, robot, scene, seed=0)
    home, ready = result.states
    assert (home.name, ready.name) == ("home", "ready")
    assert dict(home.values)["j2"] != 0.0
    assert any("zeros are in collision (base - l2)" in n for n in result.notes)
    pairs = scene.enabled_pairs([p.pair for p in adjacent])
    for state in (home, ready):
        values = dict(state.values)
        assert scene.first_collisions(np.array([[values["j1"], values["j2"]]]), pairs) == [None]
    assert result == infer_poses(model, robot, scene, seed=0)  # seeded


# -- --from-srdf keeps what the shipped SRDF holds ------------------------------------------------

GEN3 = (
    "realworld2/ros2_kortex/kortex_description/robots/gen3.xacro",
    "realworld2/ros2_kortex/kortex_moveit_config/kinova_gen3_6dof_robotiq_2f_85_moveit_config/config/gen3.srdf",
    "realworld2/ros2_kortex",
    {"gripper": "robotiq_2f_85", "dof": "6"},
)
SHIPPED = {
    **REAL,
    "panda_ros2": (
        "realworld/ros2/panda_description/urdf/panda.urdf",
        "realworld/ros2/panda_moveit_config/config/panda.srdf",
        "",
        {},
    ),
    "fanuc": (
        "realworld2/fanuc/fanuc_cr7ia_support/urdf/cr7ia.xacro",
        "realworld2/fanuc/moveit_cfgs/fanuc_cr7ia_moveit_config/config/fanuc_cr7ia.srdf",
        "realworld2/fanuc",
        {},
    ),
    "gen3": GEN3,
}


@pytest.mark.parametrize("name", list(SHIPPED))
def test_from_srdf_rerender_keeps_every_semantic_element(tmp_path, name):
    from pathlib import Path

    from marm_setup.flows import InitRequest, RobotInput, build_setup
    from marm_setup.render.package import render_package
    from marm_setup.setup.srdf import parse_srdf_string

    rel_urdf, rel_srdf, rel_pkg, args = SHIPPED[name]
    packages = [_shared(rel_pkg)] if rel_pkg else []
    if name == "gen3":
        packages.append(_shared("realworld2/ros2_robotiq_gripper"))
    urdf_path, srdf_path = _shared(rel_urdf), _shared(rel_srdf)
    robot = load_robot(urdf_path, args, packages)
    request = InitRequest(
        RobotInput.parse(
            urdf_path,
            xacro_args=tuple(f"{k}:={v}" for k, v in args.items()),
            package_paths=tuple(Path(p) for p in packages),
        ),
        out=tmp_path / "pkg",
        from_srdf=srdf_path,
    )
    model = build_setup(request, robot)
    files = {f.path: f.content for f in render_package(model, robot)}
    (srdf_file,) = [p for p in files if p.endswith(".srdf")]
    ours, theirs = parse_srdf_string(files[srdf_file]), read_srdf(srdf_path)
    for kind in ("groups", "group_states", "end_effectors", "virtual_joints", "passive_joints"):
        assert getattr(ours, kind) == getattr(theirs, kind), kind
    assert ours.disabled == theirs.disabled


MOBILE_SRDF = """<?xml version="1.0"?>
<robot name="dual">
  <virtual_joint name="world_joint" type="planar" parent_frame="odom" child_link="base"/>
  <group name="base"><joint name="world_joint"/></group>
  <group name="nothing"/>
  <group_state name="origin" group="base"><joint name="world_joint" value="0 0.5 1.2"/></group_state>
</robot>
"""


def test_from_srdf_keeps_multi_dof_values_and_empty_groups_through_marm_setup_yaml(tmp_path):
    """srdfdom reads a value list for a multi-DOF joint and keeps a group that names nothing
    (MoveIt warns): init imports both, warns about the empty group, and render keeps them."""
    from typer.testing import CliRunner

    from marm_setup.cli.app import app
    from marm_setup.setup.yaml_io import load_setup
    from tests.cli.test_init import _dual_arm_urdf

    build_file_tree(tmp_path, {"dual.urdf": _dual_arm_urdf(), "dual.srdf": MOBILE_SRDF})
    out = tmp_path / "pkg"
    args = [
        "init",
        str(tmp_path / "dual.urdf"),
        "--from-srdf",
        str(tmp_path / "dual.srdf"),
        "--out",
        str(out),
    ]
    result = CliRunner().invoke(app, [*args, "--trials", "50"])
    assert result.exit_code == 0, result.output
    assert "warning: group 'nothing' holds no chain, joints, links or subgroups" in result.stdout
    state = load_setup(out / "marm_setup.yaml").group_states[0]
    assert state.multi_dof == (("world_joint", (0.0, 0.5, 1.2)),)
    assert CliRunner().invoke(app, ["render", str(out)]).exit_code == 0
    srdf = read_srdf(out / "config" / "dual.srdf")
    original = read_srdf(tmp_path / "dual.srdf")
    assert (srdf.groups, srdf.group_states, srdf.virtual_joints) == (
        original.groups,
        original.group_states,
        original.virtual_joints,
    )

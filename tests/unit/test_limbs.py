"""Inference on kinematic trees: synthetic fixtures (dual-arm table, humanoid, legged base with an
arm, wheeled manipulator), the real robots of ../shared/realworld*, and collision-free poses."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.scene import CollisionScene
from marm_setup.robot.load import load_robot
from marm_setup.setup.groups import active_group_joints, groups_by_name
from marm_setup.setup.infer import infer
from marm_setup.setup.limbs import tokens
from marm_setup.setup.model import CollisionSettings, RobotSource
from marm_setup.setup.poses import infer_poses
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
    assert by_name["right_arm"].chain.tip == "r_wrist_roll_link"
    assert model.virtual_joints[0].type == "planar"
    assert {e.parent_link for e in model.end_effectors} == {"l_wrist_roll_link", "r_wrist_roll_link"}
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

    from marm_setup.pipeline import InitRequest, build_setup
    from marm_setup.render.package import render_package
    from marm_setup.setup.srdf import parse_srdf_string

    rel_urdf, rel_srdf, rel_pkg, args = SHIPPED[name]
    packages = [_shared(rel_pkg)] if rel_pkg else []
    if name == "gen3":
        packages.append(_shared("realworld2/ros2_robotiq_gripper"))
    urdf_path, srdf_path = _shared(rel_urdf), _shared(rel_srdf)
    robot = load_robot(urdf_path, args, packages)
    request = InitRequest(
        urdf=urdf_path,
        out=tmp_path / "pkg",
        from_srdf=srdf_path,
        xacro_args=tuple(f"{k}:={v}" for k, v in args.items()),
        package_paths=tuple(Path(p) for p in packages),
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

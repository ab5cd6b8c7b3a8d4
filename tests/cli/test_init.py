"""`marm-setup init`: inference printed, package written atomically, every model-check error is
one stderr line with exit 2 and leaves DIR as it was; golden marm setup and SRDF."""

from __future__ import annotations

import json
import re

import pytest
import yaml
from lxml import etree
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.setup.srdf import read_srdf
from marm_setup.setup.yaml_io import load_setup
from tests.conftest import FIXTURES, MARM_URDF, realworld
from tests.helpers import build_file_tree

runner = CliRunner()
SPEC = FIXTURES / "marm" / "marm_setup.yaml"
TRIALS = ["--trials", "1000"]


def _init(out, *args):
    return runner.invoke(app, ["init", str(MARM_URDF), "--out", str(out), *TRIALS, *args])


def test_init_marm_prints_inference_and_writes_the_package(tmp_path):
    out = tmp_path / "marm_moveit_config"
    result = _init(out)
    assert result.exit_code == 0, result.output
    assert "group arm: chain base_link -> grasping_frame" in result.stdout
    assert (
        "group gripper: joints finger_joint1, finger_joint2; links gripper_finger_link1, gripper_finger_link2"
        in (result.stdout)
    )
    assert "end effector gripper: group gripper, parent link grasping_frame" in result.stdout
    assert "controller gripper_controller/gripper_cmd (GripperCommand): finger_joint1" in result.stdout
    assert "create    config/marm.srdf" in result.stdout
    model = load_setup(out / "marm_setup.yaml")
    assert (model.package_name, model.target, model.collision.trials) == ("marm_moveit_config", "ros2", 1000)
    srdf = read_srdf(out / "config" / "marm.srdf")
    assert srdf.groups == model.groups and srdf.disabled == model.collision.disabled
    assert model.robot.urdf == "package://marm_description/urdf/marm.urdf.xacro"
    from marm_setup.robot.ros_packages import description_file

    assert description_file(
        model.robot.urdf, out, [out / p for p in model.robot.package_paths]
    ).resolve() == (MARM_URDF.resolve())


def test_a_package_copied_into_a_workspace_renders_and_validates_there(tmp_path):
    """The setup names the description by ROS package: a copy of the config package next to a
    copy of the description package (a catkin/colcon workspace) finds it there."""
    import shutil

    out = tmp_path / "made" / "marm_moveit_config"
    assert runner.invoke(app, ["init", str(MARM_URDF), "--out", str(out), "--trials", "200"]).exit_code == 0
    src = tmp_path / "ws" / "src"
    shutil.copytree(FIXTURES / "marm", src / "marm_description")
    shutil.copytree(out, src / "marm_moveit_config")
    shutil.rmtree(tmp_path / "made")
    moved = src / "marm_moveit_config"
    (moved / "marm_setup.yaml").write_text(
        (moved / "marm_setup.yaml").read_text().replace("package_paths:", "package_paths:\n  - ../../gone")
    )
    result = runner.invoke(app, ["render", str(moved)])
    assert result.exit_code == 0, result.output
    result = runner.invoke(app, ["validate", str(moved)])
    assert result.exit_code == 0, result.output
    assert str(src / "marm_description" / "urdf" / "marm.urdf.xacro") in result.stdout
    elsewhere = tmp_path / "alone"
    shutil.copytree(moved, elsewhere)
    args = ["--urdf", str(MARM_URDF)]
    assert runner.invoke(app, ["render", str(elsewhere), *args]).exit_code == 0
    assert runner.invoke(app, ["validate", str(elsewhere), "--no-plan", *args]).exit_code == 0


def test_init_with_course_spec_ros1(tmp_path):
    out = tmp_path / "pkg"
    result = _init(out, "--setup", str(SPEC), "--name", "course_config")
    assert result.exit_code == 0, result.output
    assert (
        "pose forward (arm): joint1=0, joint2=0.4285, joint3=0.7672, joint4=0, joint5=-0.4487"
        in result.stdout
    )
    model = load_setup(out / "marm_setup.yaml")
    assert (model.package_name, model.target) == ("course_config", "ros1")
    assert model.controllers[1].action_ns == "gripper_action"
    assert (out / "config" / "arbotix.yaml").is_file()
    assert [s.name for s in model.group_states] == ["home", "forward"]


def test_init_is_deterministic_and_seeded(tmp_path):
    texts = []
    for name in ("a", "b"):
        assert _init(tmp_path / name, "--seed", "3").exit_code == 0
        texts.append((tmp_path / name / "config" / "marm.srdf").read_text())
    assert texts[0] == texts[1]
    assert "seed: 3" in (tmp_path / "a" / "marm_setup.yaml").read_text()


def test_refuses_non_empty_dir_without_force(tmp_path):
    out = tmp_path / "pkg"
    build_file_tree(out, {"keep.txt": "mine\n"})
    result = _init(out)
    assert result.exit_code == 2
    assert (
        result.stderr.strip()
        == f"error: {out}: directory exists and is not empty (use --force to write into it)"
    )
    assert sorted(p.name for p in out.iterdir()) == ["keep.txt"]
    result = _init(out, "--force")
    assert result.exit_code == 0, result.output
    assert (out / "keep.txt").read_text() == "mine\n" and (out / "marm_setup.yaml").is_file()


def test_init_into_existing_empty_dir(tmp_path):
    (tmp_path / "pkg").mkdir()
    assert _init(tmp_path / "pkg").exit_code == 0


def test_from_srdf_imports_the_shared_panda_setup(tmp_path):
    root = realworld("ros1")
    urdf = root / "panda_description/urdf/panda_arm_hand.urdf.xacro"
    srdf = root / "panda_moveit_config/config/panda.srdf"
    out = tmp_path / "panda_cfg"
    args = ["init", str(urdf), "--out", str(out), "--package-path", str(root), "--from-srdf", str(srdf)]
    result = runner.invoke(app, [*args, "--target", "ros1"])
    assert result.exit_code == 0, result.output
    assert "group panda_arm: chain panda_link0 -> panda_link8" in result.stdout
    assert "disabled pairs" in result.stdout and "as given (SRDF / SPEC), not recomputed" in result.stdout
    assert "10000 trials" not in result.stdout  # no sampling was run
    assert "controller hand_controller/gripper_cmd (GripperCommand): panda_finger_joint1" in result.stdout
    model = load_setup(out / "marm_setup.yaml")
    original = read_srdf(srdf)
    assert model.groups == original.groups and model.collision.disabled == original.disabled
    assert read_srdf(out / "config" / "panda.srdf").group_states == original.group_states


ARM_CHAIN = {"name": "arm", "chain": {"base": "base_link", "tip": "grasping_frame"}}
HOME = {"joint1": 0, "joint2": 0, "joint3": 0, "joint4": 0, "joint5": 0, "joint6": 0}
BAD_SPECS = {
    "unknown joint": (
        {"groups": [{"name": "gripper", "joints": ["finger_joint1", "finger_jiont2"]}]},
        "groups[gripper].joints[1]: unknown joint 'finger_jiont2' (did you mean 'finger_joint2', 'finger_joint1'?)",
    ),
    "unknown link": (
        {"end_effectors": [{"name": "robot_gripper", "group": "gripper", "parent_link": "grasp_frame"}]},
        "end_effectors[robot_gripper].parent_link: unknown link 'grasp_frame' (did you mean 'grasping_frame'?)",
    ),
    "author email catkin rejects": (
        {"author": {"name": "Ann", "email": "not-an-email"}},
        'author.email: Invalid email "not-an-email" for person "Ann": catkin_pkg rejects package.xml with it',
    ),
    "a rate too small to time": (
        {"default_acceleration": 5e-324},
        "default_acceleration: must be at least 1e-06 (no trajectory could be timed), got 4.94066e-324",
    ),
    "virtual joint below a link of the robot": (
        {
            "virtual_joints": [
                {"name": "v", "type": "fixed", "parent_frame": "link3", "child_link": "base_link"}
            ]
        },
        "virtual_joints[v].parent_frame: parent frame 'link3' is one of the robot's own links: TF would form a loop",
    ),
    "chain to an unknown link": (
        {"groups": [{"name": "arm", "chain": {"base": "base_link", "tip": "link9"}}]},
        "groups[arm].chain.tip: unknown link 'link9' (did you mean 'link6', 'link5', 'link4'?)",
    ),
    "subgroup cycle": (
        {"groups": [{"name": "a", "subgroups": ["b"]}, {"name": "b", "subgroups": ["a"]}]},
        "groups[a].subgroups: subgroups form a cycle: a -> b -> a",
    ),
    "unknown subgroup": (
        {"groups": [{"name": "both", "subgroups": ["arm", "grippr"]}]},
        "groups[both].subgroups[1]: unknown group 'grippr' (did you mean 'gripper'?)",
    ),
    "pose outside limits": (
        {"group_states": [{"name": "forward", "group": "arm", "values": {**HOME, "joint2": 3.0}}]},
        "group_states[forward].values.joint2: value 3 is outside the limits [-2.35, 2.35]",
    ),
    "pose joint not in group": (
        {"group_states": [{"name": "forward", "group": "arm", "values": {**HOME, "finger_joint1": 0.01}}]},
        "group_states[forward].values.finger_joint1: joint 'finger_joint1' is not part of group 'arm'",
    ),
    "pose of unknown group": (
        {"group_states": [{"name": "up", "group": "manipulator", "values": HOME}]},
        "group_states[up].group: unknown group 'manipulator' (known: arm, gripper)",
    ),
    "duplicate group": (
        {"groups": [ARM_CHAIN, ARM_CHAIN]},
        "groups[arm]: group 'arm' defined 2 times",
    ),
    "duplicate pose": (
        {"group_states": [{"name": "home", "group": "arm", "values": HOME}] * 2},
        "group_states[home]: duplicate name 'home' in group 'arm'",
    ),
    "unknown controller joint": (
        {
            "controllers": [
                {
                    "name": "arm_controller",
                    "type": "FollowJointTrajectory",
                    "action_ns": "x",
                    "joints": ["j1"],
                }
            ]
        },
        "controllers[arm_controller].joints[0]: unknown joint 'j1'",
    ),
    "controller without joints": (
        {
            "controllers": [
                {
                    "name": "gripper_controller",
                    "type": "GripperCommand",
                    "action_ns": "gripper_cmd",
                    "joints": [],
                }
            ]
        },
        "controllers[gripper_controller].joints: a controller needs at least one joint",
    ),
    "controller commanding a mimic joint": (
        {
            "controllers": [
                {
                    "name": "gripper_controller",
                    "type": "GripperCommand",
                    "action_ns": "gripper_cmd",
                    "joints": ["finger_joint2"],
                }
            ]
        },
        "controllers[gripper_controller].joints[0]: 'finger_joint2' mimics 'finger_joint1': command that joint instead",
    ),
    "controller commanding a fixed joint": (
        {
            "controllers": [
                {
                    "name": "arm_controller",
                    "type": "FollowJointTrajectory",
                    "action_ns": "follow_joint_trajectory",
                    "joints": ["joint1", "grasping_frame_joint"],
                }
            ]
        },
        "controllers[arm_controller].joints[1]: 'grasping_frame_joint' is a fixed joint: nothing to command",
    ),
    "unknown key": (
        {"groups": [{"name": "arm", "chian": {"base": "base_link", "tip": "link1"}}]},
        "groups[arm].chian: unknown key 'chian' (did you mean 'chain'?)",
    ),
    "wrong type": (
        {"groups": [{"name": "gripper", "joints": ["finger_joint1", 2]}]},
        "groups[gripper].joints[1]: expected a string, got an integer (2)",
    ),
    "bad target": ({"target": "ros3"}, "target: 'ros3' is not one of: ros2, ros1"),
    "virtual joint not at the root": (
        {
            "virtual_joints": [
                {"name": "virtual_joint", "type": "floating", "parent_frame": "world", "child_link": "link1"}
            ]
        },
        "virtual_joints[virtual_joint].child_link: child link 'link1' is not the URDF's root link 'base_link': "
        "MoveIt skips it and the base's floating motion",
    ),
    "robot name not the URDF's": (
        {"robot_name": "foo"},
        "robot_name: 'foo' is not the URDF's robot name 'marm'",
    ),
    "duplicate servo id": (
        {"target": "ros1", "driver": "arbotix", "arbotix_joints": [{"joint": "joint2", "id": 1}]},
        "arbotix_joints[joint2].id: servo id 1 is also joint1's",
    ),
    "negative IK timeout": (
        {"kinematics": [{"group": "arm", "timeout": -0.05}]},
        "kinematics[arm].timeout: must be > 0, got -0.05",
    ),
    "velocity scaling above 1": (
        {"default_velocity_scaling": 2},
        "default_velocity_scaling: must be in (0, 1], got 2",
    ),
    "bad package name": (
        {"package_name": "Marm MoveIt"},
        "package_name: 'Marm MoveIt' is not a valid ROS package name: lowercase letters, digits and '_', "
        "starting with a letter (e.g. 'marm_moveit')",
    ),
    "gripper action the driver does not serve": (
        {
            "target": "ros1",
            "driver": "arbotix",
            "controllers": [
                {
                    "name": "gripper_controller",
                    "type": "GripperCommand",
                    "action_ns": "gripper_cmd",
                    "joints": ["finger_joint1"],
                }
            ],
        },
        "controllers[gripper_controller].action_ns: 'gripper_cmd' is not served by the arbotix driver: "
        "a GripperCommand controller serves 'gripper_controller/gripper_action' (set action_ns: gripper_action)",
    ),
    "servo of an unknown group": (
        {"servo": [{"group": "amr"}]},
        "servo[amr].group: unknown group 'amr' (did you mean 'arm'?)",
    ),
    "servo planning frame that is no link": (
        {"servo": [{"group": "arm", "planning_frame": "world"}]},
        "servo[arm].planning_frame: 'world' is not a link of the robot: moveit_servo computes its transform "
        "from the robot model",
    ),
    "sensor parameter of another type": (
        {"sensors": [{"name": "cam", "type": "pointcloud", "topic": "/cam/points", "queue_size": 3}]},
        "sensors[cam].queue_size: a pointcloud sensor has no 'queue_size' "
        "(occupancy_map_monitor/PointCloudOctomapUpdater does not read it; a depth_image sensor does)",
    ),
}


@pytest.mark.parametrize("case", list(BAD_SPECS))
def test_model_check_errors_are_one_line_and_leave_dir_unchanged(case, tmp_path):
    spec, expected = BAD_SPECS[case]
    spec_path = tmp_path / "spec.yaml"
    spec_path.write_text(yaml.safe_dump(spec))
    out = tmp_path / "pkg"
    out.mkdir()
    result = _init(out, "--setup", str(spec_path))
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert lines == [f"error: {spec_path}: {expected}"]
    assert "Traceback" not in result.output
    assert list(out.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pkg", "spec.yaml"]  # no staging dir left


@pytest.mark.parametrize(
    "text, expected",
    [
        ("<robot name='marm'><group name='arm'>", "not well-formed XML"),
        ("<robot name='marm'><group name='a'><joint name='joint1'/><joint name='joint3'/></group>"
         "<group_state name='p' group='a'><joint name='joint1' value='9'/><joint name='joint3' value='0'/>"
         "</group_state></robot>", "group_state[p].joint[joint1]: value 9 is outside the limits"),
    ],
)  # fmt: skip
def test_bad_srdf_import_is_one_line(tmp_path, text, expected):
    path = tmp_path / "in.srdf"
    path.write_text(text)
    out = tmp_path / "pkg"
    result = _init(out, "--from-srdf", str(path))
    assert result.exit_code == 2, result.output
    (line,) = result.stderr.strip().splitlines()
    assert line.startswith(f"error: {path}: ") and expected in line
    assert not out.exists()


def test_srdf_import_leaves_out_what_moveit_skips(tmp_path):
    """srdfdom skips a group member, pose value or end effector naming what the URDF lacks, and
    MoveIt a pose value of a joint outside the group: the import does too, one warning each."""
    srdf = tmp_path / "in.srdf"
    srdf.write_text(
        "<robot name='marn'><group name='arm'><chain base_link='base_link' tip_link='grasping_frame'/>"
        "<joint name='joint9'/></group><group name='hand'><joint name='finger_joint1'/></group>"
        "<group_state name='home' group='arm'><joint name='joint1' value='0'/><joint name='finger_joint1' value='0'/>"
        "<joint name='jointX' value='0'/></group_state><group_state name='open' group='nohand'/>"
        "<end_effector name='e' group='hand' parent_link='grasp_frame'/></robot>"
    )  # fmt: skip
    out = tmp_path / "pkg"
    result = _init(out, "--from-srdf", str(srdf))
    assert result.exit_code == 0, result.output
    warned = [line for line in result.stdout.splitlines() if line.strip().startswith(f"warning: {srdf}")]
    assert [w.split(": ", 2)[2].split(" (as MoveIt")[0] for w in warned] == [
        "robot: 'marn' is not the URDF's robot name 'marm'",
        "group[arm].joint: unknown joint 'joint9'",
        "group_state[home].joint[finger_joint1]: not part of group 'arm'",
        "group_state[home].joint[jointX]: unknown joint",
        "group_state[open]: group 'nohand' is not loaded",
        "end_effector[e]: unknown parent link 'grasp_frame'",
    ]
    written = (out / "config" / "marm.srdf").read_text()
    assert "joint9" not in written and "jointX" not in written and "end_effector" not in written


def test_golden_marm_setup_and_srdf(tmp_path, assert_golden):
    out = tmp_path / "pkg"
    result = _init(out, "--setup", str(SPEC), "--target", "ros1")
    assert result.exit_code == 0, result.output
    setup_text = (out / "marm_setup.yaml").read_text()
    assert "  urdf: package://marm_description/urdf/marm.urdf.xacro\n" in setup_text
    setup_text = re.sub(r"(?m)^  - \S*/fixtures$", "  - <FIXTURES>", setup_text)  # relative to tmp_path
    assert_golden("init/marm/marm_setup.yaml", setup_text)
    srdf_text = (out / "config" / "marm.srdf").read_text()
    etree.fromstring(srdf_text.encode())
    assert_golden("init/marm/marm.srdf", srdf_text)


def test_missing_spec_and_out_that_is_a_file(tmp_path):
    result = _init(tmp_path / "pkg", "--setup", str(tmp_path / "nope.yaml"))
    assert result.exit_code == 2 and result.stderr.startswith(f"error: {tmp_path / 'nope.yaml'}: cannot read")
    (tmp_path / "file").write_text("x")
    result = _init(tmp_path / "file")
    assert result.exit_code == 2
    assert result.stderr.strip() == f"error: {tmp_path / 'file'}: exists and is not a directory"
    assert not (tmp_path / "pkg").exists()


def test_xacro_args_are_recorded_and_shape_the_inference(tmp_path):
    out = tmp_path / "pkg"
    result = _init(out, "--xacro-arg", "with_gripper:=false")
    assert result.exit_code == 0, result.output
    assert "group gripper" not in result.stdout and "end effector" not in result.stdout
    model = load_setup(out / "marm_setup.yaml")
    assert model.robot.xacro_args == (("with_gripper", "false"),)
    assert [g.name for g in model.groups] == ["arm"]


def test_out_below_a_file_is_one_line(tmp_path):
    (tmp_path / "file").write_text("x")
    result = _init(tmp_path / "file" / "pkg")
    assert result.exit_code == 2, result.output
    assert result.stderr.strip() == (
        f"error: {tmp_path / 'file' / 'pkg'}: cannot create it: '{tmp_path / 'file'}' is not a directory"
    )


def test_bad_name_option_is_one_line_and_robot_names_become_valid_package_names(tmp_path):
    result = _init(tmp_path / "pkg", "--name", "marm-config")
    assert result.exit_code == 2, result.output
    assert result.stderr.strip() == (
        "error: --name: 'marm-config' is not a valid ROS package name: lowercase letters, digits and '_', "
        "starting with a letter (e.g. 'marm_config')"
    )
    assert not (tmp_path / "pkg").exists()
    urdf = tmp_path / "arm.urdf"
    urdf.write_text(
        "<robot name='My-Arm'><link name='a'/><link name='b'/>"
        "<joint name='j' type='revolute'><parent link='a'/><child link='b'/>"
        "<limit lower='-1' upper='1' velocity='1' effort='1'/></joint></robot>"
    )
    result = runner.invoke(app, ["init", str(urdf), "--out", str(tmp_path / "pkg"), "--trials", "10"])
    assert result.exit_code == 0, result.output
    assert load_setup(tmp_path / "pkg" / "marm_setup.yaml").package_name == "my_arm_moveit_config"


def _dual_arm_urdf() -> str:
    """Two 2-joint arms on one base, named by nothing but their side."""
    from tests.helpers import urdf

    body = ['<link name="base"/>']
    for side in ("l", "r"):
        for i, parent in ((1, "base"), (2, f"{side}1")):
            body.append(
                f'<link name="{side}{i}"/><joint name="{side}_j{i}" type="revolute"><parent link="{parent}"/>'
                f'<child link="{side}{i}"/><origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>'
                '<limit lower="-1" upper="1" velocity="1" effort="1"/></joint>'
            )
    return urdf("\n".join(body), name="dual")


def test_spec_gives_the_groups_inference_only_guesses(tmp_path):
    spec = {
        "groups": [
            {"name": "left", "chain": {"base": "base", "tip": "l2"}},
            {"name": "right", "chain": {"base": "base", "tip": "r2"}},
        ]
    }
    build_file_tree(tmp_path, {"dual.urdf": _dual_arm_urdf(), "spec.yaml": yaml.safe_dump(spec)})
    args = ["init", str(tmp_path / "dual.urdf"), "--trials", "10"]

    result = runner.invoke(app, [*args, "--out", str(tmp_path / "a")])
    assert result.exit_code == 0, result.output
    assert "guessed: l_j1, l_j2, r_j1, r_j2 are limbs (nothing else moves)" in result.stdout
    assert "(see docs/setup-file.md)" in result.stdout
    model = load_setup(tmp_path / "a" / "marm_setup.yaml")
    assert [g.name for g in model.groups] == ["chain_1", "chain_2", "whole_body"]

    result = runner.invoke(app, [*args, "--out", str(tmp_path / "b"), "--setup", str(tmp_path / "spec.yaml")])
    assert result.exit_code == 0, result.output
    model = load_setup(tmp_path / "b" / "marm_setup.yaml")
    assert [g.name for g in model.groups] == ["left", "right"]
    assert [(c.name, c.joints) for c in model.controllers] == [
        ("left_controller", ("l_j1", "l_j2")),
        ("right_controller", ("r_j1", "r_j2")),
    ]
    assert [k.group for k in model.kinematics] == ["left", "right"]
    assert [p.group for p in model.planners] == ["left", "right"]

    (tmp_path / "empty.yaml").write_text("author: {name: me}\n")
    fixed = _dual_arm_urdf().replace('type="revolute"', 'type="fixed"')
    build_file_tree(tmp_path, {"fixed.urdf": fixed})
    args = ["init", str(tmp_path / "fixed.urdf"), "--out", str(tmp_path / "c")]
    result = runner.invoke(app, [*args, "--setup", str(tmp_path / "empty.yaml")])
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        f"error: {tmp_path / 'empty.yaml'}: groups: no planning groups: no limb to infer, "
        "and the SPEC / SRDF gives none (see docs/setup-file.md)"
    )
    assert not (tmp_path / "c").exists()


def test_spec_collision_seed_and_trials_apply_unless_given_on_the_command_line(tmp_path):
    spec = tmp_path / "spec.yaml"
    spec.write_text("collision: {trials: 300, seed: 5}\n")
    base = ["init", str(MARM_URDF), "--setup", str(spec)]
    result = runner.invoke(app, [*base, "--out", str(tmp_path / "a")])
    assert result.exit_code == 0, result.output
    assert "300 trials, seed 5" in result.stdout
    collision = load_setup(tmp_path / "a" / "marm_setup.yaml").collision
    assert (collision.trials, collision.seed) == (300, 5)
    result = runner.invoke(app, [*base, "--out", str(tmp_path / "b"), "--trials", "200", "--seed", "0"])
    assert result.exit_code == 0, result.output
    collision = load_setup(tmp_path / "b" / "marm_setup.yaml").collision
    assert (collision.trials, collision.seed) == (200, 0)


def test_jobs_and_suffixed_trials_reach_the_matrix_and_do_not_change_it(tmp_path):
    texts = []
    for jobs in ("1", "2"):
        out = tmp_path / jobs
        args = ["init", str(MARM_URDF), "--out", str(out), "--trials", "1.2k", "--jobs", jobs]
        result = runner.invoke(app, args)
        assert result.exit_code == 0, result.output
        assert "1200 trials, seed 0" in result.stdout
        texts.append((out / "config" / "marm.srdf").read_text())
    assert texts[0] == texts[1]
    result = runner.invoke(app, ["init", str(MARM_URDF), "--out", str(tmp_path / "o"), "--jobs", "0"])
    assert result.exit_code == 2 and result.stderr.strip() == "error: --jobs: must be >= 1, got 0"


def test_run_init_reports_matrix_progress(tmp_path):
    from marm_setup.flows import InitRequest, MatrixSettings, RobotInput, run_init
    from marm_setup.robot.load import load_robot

    calls = []
    request = InitRequest(
        RobotInput.parse(MARM_URDF), out=tmp_path / "o", matrix=MatrixSettings(trials=2500, jobs=2)
    )
    run_init(request, load_robot(MARM_URDF), lambda done, total: calls.append((done, total)))
    assert calls[0] == (0, 2500) and calls[-1] == (2500, 2500)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)


def test_negative_seed_is_one_line(tmp_path):
    result = CliRunner().invoke(app, ["init", str(MARM_URDF), "--out", str(tmp_path / "o"), "--seed", "-1"])
    assert result.exit_code == 2
    assert result.stderr.strip() == "error: --seed: must be >= 0, got -1"
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize(
    ("args", "env", "expected"),
    [
        ([], {}, "humble"),  # the ros2 default
        ([], {"ROS_DISTRO": "jazzy"}, "jazzy"),  # the shell's distro when it is a ros2 one
        ([], {"ROS_DISTRO": "noetic"}, "humble"),  # ... and not when it is not
        (["--ros-distro", "jazzy"], {"ROS_DISTRO": "humble"}, "jazzy"),  # the option wins
        (["--target", "ros1"], {"ROS_DISTRO": "jazzy"}, "noetic"),
    ],
)
def test_ros_distro_option_env_and_defaults(tmp_path, args, env, expected):
    out = tmp_path / "pkg"
    result = runner.invoke(app, ["init", str(MARM_URDF), "--out", str(out), *TRIALS, *args], env=env)
    assert result.exit_code == 0, result.output
    assert load_setup(out / "marm_setup.yaml").ros_distro == expected
    moveit = out / "config" / "moveit.yaml"
    if moveit.exists():
        ompl = yaml.safe_load(moveit.read_text())["/**"]["ros__parameters"]["ompl"]
        assert ("planning_plugin" in ompl) == (expected == "humble")


def test_a_distro_of_another_target_is_one_line(tmp_path):
    out = tmp_path / "pkg"
    result = _init(out, "--target", "ros1", "--ros-distro", "jazzy")
    assert result.exit_code == 2
    assert result.stderr.strip() == "error: --ros-distro: 'jazzy' is not a ros1 distro (valid: noetic)"
    assert not out.exists()
    spec = tmp_path / "spec.yaml"
    spec.write_text("target: ros2\nros_distro: noetic\n")
    result = _init(out, "--setup", str(spec))
    assert result.exit_code == 2
    assert (
        result.stderr.strip()
        == f"error: {spec}: ros_distro: 'noetic' is not a ros2 distro (valid: humble, jazzy, kilted, rolling)"
    )


CYCLE = '<group name="a"><group name="b"/></group><group name="b"><group name="a"/></group>'


def test_one_subgroup_cycle_rule_for_validate_init_and_render(tmp_path):
    """The same SRDF cycle: a validate finding, and the one-line error of init --from-srdf (SRDF
    element names) and of render (marm_setup.yaml key paths), with one message."""
    from tests.validate_helpers import generate_marm

    pkg = generate_marm(tmp_path, "ros1")
    srdf = pkg / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text().replace('<robot name="marm">', f'<robot name="marm">{CYCLE}', 1))
    message = "subgroups form a cycle: a -> b -> a"

    doc = json.loads(runner.invoke(app, ["validate", str(pkg), "--no-plan", "--format", "json"]).stdout)
    cycles = [(f["rule"], f["element"], f["message"]) for f in doc["findings"] if "cycle" in f["message"]]
    assert cycles == [
        ("srdf.subgroup-cycle", "group[a]", message),
        ("srdf.subgroup-cycle", "group[b]", "subgroups form a cycle: b -> a -> b"),
    ]

    # srdfdom drops groups whose subgroups never all load, a cycle's among them: so does the import
    result = _init(tmp_path / "out", "--from-srdf", str(srdf))
    assert result.exit_code == 0, result.output
    for group in ("a", "b"):
        assert f"warning: {srdf}: group[{group}]: subgroups that do not all load" in result.stdout
    assert 'group name="a"' not in (tmp_path / "out" / "config" / "marm.srdf").read_text()

    setup = pkg / "marm_setup.yaml"
    groups = "groups:\n- name: a\n  subgroups: [b]\n- name: b\n  subgroups: [a]\n"
    setup.write_text(setup.read_text().replace("groups:\n", groups, 1))
    result = runner.invoke(app, ["render", str(pkg)])
    assert (result.exit_code, result.stderr) == (2, f"error: {setup}: groups[a].subgroups: {message}\n")


@pytest.mark.parametrize(
    "trials, message",
    [
        ("0", "must be between 1 and 1e+12, got 0"),
        ("-5", "must be between 1 and 1e+12, got -5"),
        ("abc", "expected a count like 10000, 100k or 1M, got 'abc'"),
    ],
)
def test_init_and_collisions_give_the_same_trials_error(tmp_path, trials, message):
    out = tmp_path / "pkg"
    init = runner.invoke(app, ["init", str(MARM_URDF), "--out", str(out), "--trials", trials])
    collisions = runner.invoke(app, ["collisions", str(MARM_URDF), "--trials", trials])
    for result in (init, collisions):
        assert (result.exit_code, result.stdout, result.stderr) == (2, "", f"error: --trials: {message}\n")
    assert not out.exists()


@pytest.mark.parametrize("robot", ["dual_arm_table", "wheeled_manipulator"])
def test_inferred_package_of_a_tree_validates_and_plans_a_pose_pair_per_arm(tmp_path, robot):
    out = tmp_path / robot
    urdf = FIXTURES / "synthetic" / f"{robot}.urdf"
    result = runner.invoke(app, ["init", str(urdf), "--out", str(out), "--trials", "300"])
    assert result.exit_code == 0, result.output
    result = runner.invoke(app, ["validate", str(out)])
    assert result.exit_code == 0, result.output
    summary = result.stdout.splitlines()[-2]
    arms = [g.name for g in load_setup(out / "marm_setup.yaml").groups if g.name.endswith("arm")]
    assert f"planned {2 * len(arms)} pose pairs" in summary
    assert result.stdout.splitlines()[-1] == "no findings"


def test_init_with_an_old_setup_computes_the_matrix_again_unless_told_to_keep_it(tmp_path):
    """`init --force --setup pkg/marm_setup.yaml` after a URDF change must not keep a stale matrix:
    it recomputes (User pairs kept); --keep-matrix takes the pairs as they are."""
    pkg = tmp_path / "pkg"
    assert _init(pkg).exit_code == 0
    spec = tmp_path / "old.yaml"
    data = yaml.safe_load((pkg / "marm_setup.yaml").read_text())
    data["collision"]["disabled"] = [
        {"link1": "base_link", "link2": "link6", "reason": "Never"},
        {"link1": "link1", "link2": "link5", "reason": "User"},
    ]
    spec.write_text(yaml.safe_dump(data))
    result = runner.invoke(app, ["init", str(MARM_URDF), "--out", str(pkg), "--force", "--setup", str(spec)])
    assert result.exit_code == 0, result.output
    pairs = {
        (p.link1, p.link2): p.reason.value for p in load_setup(pkg / "marm_setup.yaml").collision.disabled
    }
    assert pairs[("link1", "link5")] == "User" and len(pairs) > 2
    result = runner.invoke(
        app, ["init", str(MARM_URDF), "--out", str(pkg), "--force", "--setup", str(spec), "--keep-matrix"]
    )
    assert result.exit_code == 0 and "as given (SRDF / SPEC), not recomputed" in result.stdout
    assert len(load_setup(pkg / "marm_setup.yaml").collision.disabled) == 2

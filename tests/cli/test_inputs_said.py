"""Issue 23, "inputs never silently ignored, guesses said out loud": an SRDF xacro is expanded,
an SRDF that yields no group is refused, a `--xacro-arg` nothing reads is an error, and every
message names an option of the command that prints it."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import FIXTURES, MARM_URDF, realworld
from tests.helpers import build_file_tree

runner = CliRunner()
TRIALS = ["--trials", "300", "--jobs", "1"]

SRDF_XACRO = {
    "marm.srdf.xacro": """
        <robot name="marm" xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:arg name="arm_group" default="arm"/>
          <xacro:include filename="groups.xacro"/>
          <xacro:arm_group name="$(arg arm_group)"/>
        </robot>""",
    "groups.xacro": """
        <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:macro name="arm_group" params="name">
            <group name="${name}"><chain base_link="base_link" tip_link="grasping_frame"/></group>
            <group_state name="folded" group="${name}">
              <joint name="joint2" value="0.5"/><joint name="joint3" value="0.5"/>
            </group_state>
          </xacro:macro>
        </robot>""",
}


def _one_error_line(result) -> str:
    assert result.exit_code == 2, result.output
    (line,) = result.stderr.strip().splitlines()
    assert "Traceback" not in result.output
    return line


def test_init_expands_an_srdf_xacro_with_the_xacro_args(tmp_path):
    srdf = build_file_tree(tmp_path / "srdf", SRDF_XACRO) / "marm.srdf.xacro"
    out = tmp_path / "pkg"
    args = ["init", str(MARM_URDF), "--out", str(out), "--from-srdf", str(srdf), *TRIALS]
    result = runner.invoke(app, [*args, "--xacro-arg", "arm_group:=manipulator"])
    assert result.exit_code == 0, result.output
    assert "group manipulator: chain base_link -> grasping_frame" in result.stdout
    assert "warning" not in result.stdout
    assert '<group_state name="folded" group="manipulator">' in (out / "config" / "marm.srdf").read_text()


def test_init_refuses_an_srdf_whose_groups_all_fail_to_load(tmp_path):
    """An SRDF of another robot (or a xacro read as it is) names nothing of this one: every group
    is left out as MoveIt would; planning with it is impossible, so init says so and stops."""
    srdf = tmp_path / "other.srdf"
    srdf.write_text(
        "<robot name='marm'><group name='arm'><chain base_link='$(arg id)_link0' tip_link='$(arg id)_link8'/>"
        "</group><group name='both'><group name='arm'/></group></robot>"
    )
    out = tmp_path / "pkg"
    result = runner.invoke(
        app, ["init", str(MARM_URDF), "--out", str(out), "--from-srdf", str(srdf), *TRIALS]
    )
    line = _one_error_line(result)
    assert line == (
        f"error: {srdf}: groups: none of its 2 groups holds a joint or link of robot 'marm' as MoveIt loads it "
        "(first: group[arm].chain: unknown link in '$(arg id)_link0' -> '$(arg id)_link8')"
    )
    assert not out.exists()


def test_init_imports_the_shared_moveit2_panda_srdf_xacro(tmp_path):
    root = realworld("ros2")
    srdf = root / "panda_moveit_config/config/panda_arm_hand.srdf.xacro"
    out = tmp_path / "pkg"
    urdf = root / "panda_description/urdf/panda.urdf"
    args = ["init", str(urdf), "--out", str(out), "--package-path", str(root), "--from-srdf", str(srdf)]
    result = runner.invoke(app, [*args, *TRIALS])
    assert result.exit_code == 0, result.output
    assert "warning" not in result.stdout
    for line in (
        "group panda_arm: chain panda_link0 -> panda_link8",
        "group panda_arm_hand: subgroups panda_arm, hand",
        "end effector hand: group hand, parent link panda_link8",
    ):
        assert line in result.stdout


@pytest.mark.parametrize("command", ["init", "inspect", "collisions"])
def test_a_misspelled_xacro_arg_is_an_error_naming_the_declared_ones(tmp_path, command):
    extra = {"init": ["--out", str(tmp_path / "pkg"), *TRIALS], "collisions": TRIALS}.get(command, [])
    result = runner.invoke(app, [command, str(MARM_URDF), "--xacro-arg", "with_griper:=false", *extra])
    assert _one_error_line(result) == (
        f"error: {MARM_URDF}: --xacro-arg with_griper: not an argument of this xacro "
        "(did you mean 'with_gripper'?); it takes: with_gripper"
    )
    assert not (tmp_path / "pkg").exists()


def test_init_takes_an_arg_of_the_srdf_xacro_and_refuses_one_of_neither(tmp_path):
    srdf = build_file_tree(tmp_path / "srdf", SRDF_XACRO) / "marm.srdf.xacro"
    args = ["init", str(MARM_URDF), "--out", str(tmp_path / "pkg"), "--from-srdf", str(srdf), *TRIALS]
    result = runner.invoke(app, [*args, "--xacro-arg", "arm_gruop:=x"])
    assert _one_error_line(result) == (
        f"error: {MARM_URDF}: --xacro-arg arm_gruop: not an argument of this xacro or {srdf} "
        "(did you mean 'arm_group'?); they take: arm_group, with_gripper"
    )


def test_a_xacro_arg_for_a_plain_urdf_is_an_error(tmp_path):
    urdf = FIXTURES / "synthetic" / "dual_arm_table.urdf"
    result = runner.invoke(app, ["inspect", str(urdf), "--xacro-arg", "hand:=true"])
    assert _one_error_line(result) == (
        f"error: {urdf}: --xacro-arg hand: a plain URDF takes no xacro argument (it is not a xacro file)"
    )


def test_render_refuses_a_xacro_arg_of_marm_setup_yaml_the_xacro_does_not_take(tmp_path):
    out = tmp_path / "pkg"
    made = runner.invoke(
        app, ["init", str(MARM_URDF), "--out", str(out), "--xacro-arg", "with_gripper:=true", *TRIALS]
    )
    assert made.exit_code == 0, made.output
    setup = out / "marm_setup.yaml"
    setup.write_text(setup.read_text().replace("with_gripper: 'true'", "with_griper: 'false'"))
    result = runner.invoke(app, ["render", str(out)])
    assert _one_error_line(result) == (
        f"error: {setup}: robot.xacro_args.with_griper: not an argument of the robot's xacro "
        "(did you mean 'with_gripper'?); it takes: with_gripper"
    )

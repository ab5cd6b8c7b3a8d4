"""`marm-setup render DIR`: re-render from marm_setup.yaml; hand edits are conflicts (exit 2)."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.render.package import render_package
from marm_setup.render.writer import apply_writes, plan_writes
from tests.render_helpers import inferred_marm

runner = CliRunner()


def make_package(tmp_path: Path, target: str = "ros1") -> Path:
    out = tmp_path / "marm_moveit_config"
    model, robot = inferred_marm(target, out)
    apply_writes(plan_writes(render_package(model, robot), out), out)
    return out


def snapshot(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_rerender_of_unchanged_setup_is_a_noop(tmp_path, target):
    pkg = make_package(tmp_path, target)
    before = snapshot(pkg)
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert all(line.startswith("unchanged ") for line in lines[:-1])
    assert "config/marm.srdf" in result.stdout and "marm_setup.yaml" not in result.stdout
    assert snapshot(pkg) == before


def test_hand_edit_is_a_conflict_then_force_overwrites(tmp_path):
    pkg = make_package(tmp_path)
    edited = pkg / "config" / "kinematics.yaml"
    original = edited.read_text()
    edited.write_text(original + "# my tuning\n")
    setup = pkg / "marm_setup.yaml"
    setup.write_text(setup.read_text().replace("timeout: 0.05", "timeout: 0.1"))

    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 2
    assert "conflict  config/kinematics.yaml" in result.stdout
    assert result.stderr.count("\n") == 1 and "Traceback" not in result.output
    assert "config/kinematics.yaml" in result.stderr and "--force" in result.stderr
    assert edited.read_text() == original + "# my tuning\n"

    result = runner.invoke(app, ["render", str(pkg), "--force"])
    assert result.exit_code == 0, result.output
    assert "kinematics_solver_timeout: 0.1\n" in edited.read_text()
    assert "# my tuning" not in edited.read_text()
    assert runner.invoke(app, ["render", str(pkg)]).exit_code == 0  # manifest now trusts it


def test_setup_edit_updates_untouched_files(tmp_path):
    pkg = make_package(tmp_path)
    setup = pkg / "marm_setup.yaml"
    setup.write_text(
        setup.read_text().replace("default_velocity_scaling: 0.1", "default_velocity_scaling: 0.5")
    )
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 0, result.output
    assert "update    config/joint_limits.yaml" in result.stdout
    assert "default_velocity_scaling_factor: 0.5" in (pkg / "config/joint_limits.yaml").read_text()


def test_dry_run_writes_nothing(tmp_path):
    pkg = make_package(tmp_path)
    (pkg / "launch" / "demo.launch").unlink()
    (pkg / "package.xml").write_text("<package/>\n")
    before = snapshot(pkg)
    result = runner.invoke(app, ["render", str(pkg), "--dry-run"])
    assert result.exit_code == 0, result.output
    assert "create    launch/demo.launch" in result.stdout
    assert "conflict  package.xml" in result.stdout
    assert "dry run: nothing written" in result.stdout
    assert snapshot(pkg) == before


def test_missing_setup_is_input_error(tmp_path):
    result = runner.invoke(app, ["render", str(tmp_path)])
    assert result.exit_code == 2
    assert "marm_setup.yaml" in result.stderr and "Traceback" not in result.output
    assert result.stderr.count("\n") == 1


def test_bad_setup_names_file_and_key(tmp_path):
    pkg = make_package(tmp_path)
    setup = pkg / "marm_setup.yaml"
    setup.write_text(setup.read_text().replace("package_name:", "package_nmae:"))
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 2
    assert "marm_setup.yaml" in result.stderr and "Traceback" not in result.output


def test_pose_edited_out_of_limits_is_refused_and_nothing_written(tmp_path):
    pkg = make_package(tmp_path)
    setup = pkg / "marm_setup.yaml"
    setup.write_text(setup.read_text().replace("joint2: 0.4285", "joint2: 9.0"))
    before = snapshot(pkg)
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 2
    line = result.stderr.strip()
    assert line.startswith(f"error: {setup}: group_states[forward]") and "joint2" in line, line
    assert "\n" not in line
    assert snapshot(pkg) == before


def test_switching_target_reports_stale_files(tmp_path):
    pkg = make_package(tmp_path, "ros1")
    setup = pkg / "marm_setup.yaml"
    text = setup.read_text().replace("target: ros1", "target: ros2").replace("gripper_action", "gripper_cmd")
    text = text.replace("ros_distro: noetic", "ros_distro: jazzy")
    setup.write_text(text)
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 0, result.output
    assert "create    config/moveit.yaml" in result.stdout
    assert "stale     launch/demo.launch (no longer generated; left in place)" in result.stdout
    assert (pkg / "launch" / "demo.launch").is_file()


def test_switching_target_without_the_drivers_action_ns_is_refused(tmp_path):
    pkg = make_package(tmp_path, "ros1")
    setup = pkg / "marm_setup.yaml"
    setup.write_text(setup.read_text().replace("target: ros1", "target: ros2"))
    before = snapshot(pkg)
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 2  # the distro must change with the target
    assert (
        result.stderr.strip()
        == f"error: {setup}: ros_distro: 'noetic' is not a ros2 distro (valid: humble, jazzy, kilted, rolling)"
    )
    setup.write_text(setup.read_text().replace("ros_distro: noetic", "ros_distro: humble"))
    before = snapshot(pkg)
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        f"error: {setup}: controllers[gripper_controller].action_ns: 'gripper_action' is not served by "
        "the ros2 driver: a GripperCommand controller serves 'gripper_controller/gripper_cmd' "
        "(set action_ns: gripper_cmd)"
    )
    assert snapshot(pkg) == before


def test_render_of_an_edited_pipeline_setup_warns_and_rewrites_moveit_yaml(tmp_path):
    """An edit adding STOMP and parameters to a Humble package: one warning line for STOMP (not in
    Humble's binaries), the parameters in moveit.yaml; an unknown one is one error line."""
    pkg = make_package(tmp_path, "ros2")
    setup = pkg / "marm_setup.yaml"
    text = setup.read_text().replace(
        "- pilz\n", "- pilz\n- stomp\npipeline_parameters:\n  stomp: {num_timesteps: 50}\n", 1
    )
    setup.write_text(text)
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 0, result.output
    (warning,) = [line for line in result.stdout.splitlines() if line.startswith("warning:")]
    assert "'stomp' is not in MoveIt's humble binaries" in warning
    assert "update    config/moveit.yaml" in result.stdout
    assert "      num_timesteps: 50\n" in (pkg / "config" / "moveit.yaml").read_text()
    setup.write_text(text.replace("num_timesteps: 50", "timesteps: 50"))
    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 2
    assert result.stderr.startswith(
        f"error: {setup}: pipeline_parameters.stomp.timesteps: unknown parameter 'timesteps'"
    )


def test_a_refused_render_says_of_each_file_that_it_was_not_written_and_why(tmp_path):
    pkg = make_package(tmp_path)
    edited = pkg / "config" / "kinematics.yaml"
    edited.write_text(edited.read_text() + "# my tuning\n")
    setup = pkg / "marm_setup.yaml"
    setup.write_text(
        setup.read_text().replace("default_velocity_scaling: 0.1", "default_velocity_scaling: 0.2")
    )
    before = snapshot(pkg)

    result = runner.invoke(app, ["render", str(pkg)])
    assert result.exit_code == 2
    lines = result.stdout.splitlines()
    assert "update    config/joint_limits.yaml (not written: a hand-edited file stopped the render)" in lines
    assert "conflict  config/kinematics.yaml (edited by hand: not overwritten)" in lines
    assert result.stderr.startswith(f"error: {pkg}: nothing written: 1 file(s) edited by hand")
    assert snapshot(pkg) == before
    dry = runner.invoke(app, ["render", str(pkg), "--dry-run"])  # a plan, not a refusal
    assert "update    config/joint_limits.yaml" in dry.stdout.splitlines()


def test_render_loads_the_robot_with_the_given_xacro_args_and_package_paths(tmp_path):
    pkg = make_package(tmp_path)
    assert runner.invoke(app, ["render", str(pkg), "--package-path", str(tmp_path)]).exit_code == 0
    wrong = runner.invoke(app, ["render", str(pkg), "--xacro-arg", "nope:=1"])
    assert wrong.exit_code == 2
    assert "--xacro-arg nope: not an argument of this xacro; it takes: with_gripper" in wrong.stderr
    no_gripper = runner.invoke(app, ["render", str(pkg), "--xacro-arg", "with_gripper:=false"])
    assert no_gripper.exit_code == 2  # the setup's gripper group names joints this robot lacks
    assert "finger_joint1" in no_gripper.stderr

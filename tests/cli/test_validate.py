"""`marm-setup validate DIR`: exit 0 clean, 1 with errors (or warnings under --strict), 2 unreadable."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import MARM_URDF
from tests.validate_helpers import copy_package, generate_marm, panda, replace_text

runner = CliRunner()


def test_clean_marm_package_exits_0(tmp_path):
    pkg = generate_marm(tmp_path, "ros1")
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan"])
    assert result.exit_code == 0, result.output
    assert result.stdout.endswith("\nno findings\n")  # after one line saying what was validated
    urdf = MARM_URDF.resolve()
    assert result.stdout.splitlines() == [
        f"validated marm_moveit_config (ros1, moveit1 layout) with robot 'marm' from {urdf} "
        "(marm_setup.yaml), SRDF config/marm.srdf (set as the semantic description by launch/planning_context.launch); "
        "runtime planning skipped; launch files: static rules only (MARM_SETUP_ROSLAUNCH is empty)",
        "no findings",
    ]


def test_says_what_was_validated_and_how_many_pose_pairs_were_planned(tmp_path):
    good = panda("ros2")
    args = ["validate", str(good.path), "--package-path", str(good.package_paths[0])]
    text = runner.invoke(app, args).stdout.splitlines()
    assert text[-2] == (
        f"validated moveit_resources_panda_moveit_config (ros2, moveit2 layout) with robot 'panda' "
        f"from {good.path / 'config/panda.urdf.xacro'} (config/<robot>.urdf.xacro), SRDF "
        "config/panda_arm_hand.srdf.xacro (chosen by its name); planned 4 pose pairs; "
        "launch files: static rules only (MARM_SETUP_ROS2_PYTHON is empty)"
    )
    assert text[-1] == "1 error, 4 warnings"  # test_validate_packages says which
    doc = json.loads(runner.invoke(app, [*args, "--format", "json", "--no-plan"]).stdout)
    assert doc["validated"] == {
        "package": "moveit_resources_panda_moveit_config",
        "target": "ros2",
        "layout": "moveit2",
        "urdf": str(good.path / "config/panda.urdf.xacro"),
        "urdf_origin": "config/<robot>.urdf.xacro",
        "robot": "panda",
        "planned_pairs": None,
        "launched_by": "static rules only (MARM_SETUP_ROS2_PYTHON is empty)",
        "srdf": "config/panda_arm_hand.srdf.xacro",
        "srdf_origin": "chosen by its name",
        "xacro_args": {},
        "env_defaults": [],
        "launch_args": {},
        "skipped": [],
    }
    assert (doc["errors"], doc["warnings"]) == (1, 3)


def test_errors_exit_1_text_grouped_by_file(tmp_path):
    pkg = copy_package(panda("ros1"), tmp_path)
    replace_text(
        pkg, "config/kinematics.yaml", "kinematics_solver_timeout: 0.05", "kinematics_solver_timeout: -1"
    )
    args = ["validate", str(pkg), "--no-plan", "--package-path", str(panda("ros1").package_paths[0])]
    result = runner.invoke(app, args)
    assert result.exit_code == 1
    lines = result.stdout.splitlines()
    assert "config/kinematics.yaml" in lines
    assert any("kinematics.non-positive" in line and line.startswith("  error") for line in lines)
    assert "\x1b[" not in result.stdout  # no colour when not a TTY
    assert lines[-1].endswith("2 warnings")  # launch.missing-file (moveit.rviz), controller.list-not-loaded


def test_warnings_pass_unless_strict(tmp_path):
    good = panda("ros2")
    base = ["validate", str(good.path), "--no-plan", "--package-path", str(good.package_paths[0])]
    pkg = copy_package(good, tmp_path)
    # remove the one real error (transport pose) so only the controller warning is left
    replace_text(
        pkg,
        "config/panda_arm.xacro",
        '<joint name="panda_joint6" value="0" />',
        '<joint name="panda_joint6" value="1.571" />',
    )
    base[1] = str(pkg)
    assert runner.invoke(app, base).exit_code == 0
    assert runner.invoke(app, [*base, "--strict"]).exit_code == 1


def test_json_output(tmp_path):
    pkg = generate_marm(tmp_path, "ros2")
    replace_text(
        pkg,
        "config/marm.srdf",
        'type="fixed" parent_frame="world" child_link="base_link"',
        'type="floating" parent_frame="world" child_link="link1"',
    )
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan", "--format", "json"])
    assert result.exit_code == 1
    doc = json.loads(result.stdout)
    assert doc["errors"] == 1
    (finding,) = doc["findings"]
    assert finding["rule"] == "srdf.virtual-joint-child"
    assert finding["file"] == "config/marm.srdf"
    assert finding["element"] == "virtual_joint[virtual_joint]"


def test_explicit_urdf(tmp_path):
    pkg = generate_marm(tmp_path, "ros1")
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan", "--urdf", str(MARM_URDF)])
    assert result.exit_code == 0, result.output


def test_launch_args_reach_the_launch_files_and_the_summary(tmp_path):
    pkg = generate_marm(tmp_path, "ros1")
    result = runner.invoke(
        app, ["validate", str(pkg), "--no-plan", "--launch-arg", "debug:=true", "--format", "json"]
    )
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["validated"]["launch_args"] == {"debug": "true"}
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan", "--launch-arg", "debug"])
    assert (
        result.exit_code == 2
        and result.stderr.strip() == "error: --launch-arg: expected NAME:=VALUE, got 'debug'"
    )


def test_unreadable_input_exits_2_with_one_line(tmp_path):
    for target in (tmp_path / "nope", tmp_path):
        result = runner.invoke(app, ["validate", str(target)])
        assert result.exit_code == 2
        assert len(result.stderr.strip().splitlines()) == 1
        assert result.stderr.startswith(f"error: {target}: ")
        assert "Traceback" not in result.output


def test_a_description_package_no_path_holds_is_a_warning_not_exit_2(tmp_path):
    pkg = copy_package(panda("ros1"), tmp_path)
    result = runner.invoke(app, ["validate", str(pkg), "--format", "json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    (found,) = [f for f in doc["findings"] if f["rule"] == "urdf.package-missing"]
    assert (found["file"], found["element"]) == ("launch/planning_context.launch", "robot_description")
    assert "moveit_resources_panda_description" in found["message"] and "--package-path" in found["hint"]
    assert doc["validated"]["robot"] is None


def test_missing_explicit_urdf_exits_2(tmp_path):
    pkg = generate_marm(tmp_path, "ros1")
    result = runner.invoke(app, ["validate", str(pkg), "--urdf", "nothere.urdf"])
    assert result.exit_code == 2
    assert result.stderr == "error: nothere.urdf: --urdf: file not found\n"


def test_copied_ros2_panda_names_the_unknown_xacro_package(tmp_path):
    """config/panda.urdf.xacro's $(find ...) fails: one clean finding, not xacro's wrapped repr; a
    warning, as for a description package no path holds (the ROS 1 copy above)."""
    pkg = copy_package(panda("ros2"), tmp_path)
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan", "--format", "json"])
    assert result.exit_code == 0, result.output
    (finding,) = json.loads(result.stdout)["findings"]
    assert (finding["rule"], finding["file"]) == ("urdf.package-missing", "config/panda.urdf.xacro")
    assert (finding["severity"], finding["element"]) == (
        "warning",
        "$(find moveit_resources_panda_description)",
    )
    assert finding["message"].startswith("loads package 'moveit_resources_panda_description'")
    assert "<class" not in finding["message"] and str(tmp_path) not in finding["message"]


def test_a_stale_setup_assistant_urdf_is_not_what_move_group_loads(tmp_path):
    """MoveIt 1 takes robot_description from the launch files; .setup_assistant only the Setup
    Assistant reads (a stale path there is no move_group error)."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, ".setup_assistant", "urdf/panda_arm_hand.urdf.xacro", "urdf/gone.urdf.xacro")
    args = [
        "validate",
        str(pkg),
        "--package-path",
        str(good.package_paths[0]),
        "--format",
        "json",
        "--no-plan",
    ]
    doc = json.loads(runner.invoke(app, args).stdout)
    assert doc["validated"]["urdf_origin"] == "robot_description in launch/planning_context.launch"
    assert doc["validated"]["urdf"].endswith("urdf/panda_arm_hand.urdf.xacro")
    assert not [f for f in doc["findings"] if f["rule"] == "urdf.missing"]


def test_marm_package_moved_away_from_its_urdf(tmp_path):
    """marm_setup.yaml names the description by package (package://marm_description/...): moved
    where no package path holds that package, validate says which package it needs (MoveIt finds
    it where ROS has it installed: a warning), the rules needing the robot skipped."""
    pkg = generate_marm(tmp_path, "ros1")
    moved = tmp_path / "deeper" / "still" / "pkg"
    moved.parent.mkdir(parents=True)
    pkg.rename(moved)
    result = runner.invoke(app, ["validate", str(moved), "--format", "json"])
    assert result.exit_code == 0, result.output
    (finding,) = json.loads(result.stdout)["findings"]
    assert (finding["rule"], finding["file"], finding["element"]) == (
        "urdf.package-missing",
        "marm_setup.yaml",
        "robot.urdf",
    )
    assert "'marm_description'" in finding["message"] and "--package-path" in finding["hint"]
    assert "package:/" not in result.stdout


def test_a_generated_package_copied_to_another_depth_validates_with_its_package_path(tmp_path):
    """Issue 31: init the marm description (a ROS package) into a/b/pkg, copy the package to x/pkg:
    its robot.urdf (package://marm_description/...) is found through --package-path, whatever the
    relative robot.package_paths written at a/b/pkg now point at."""
    import shutil

    fixtures = tmp_path / "fixtures"
    shutil.copytree(MARM_URDF.parents[2], fixtures)
    urdf = fixtures / MARM_URDF.relative_to(MARM_URDF.parents[2])
    made = tmp_path / "a" / "b" / "pkg"
    result = runner.invoke(app, ["init", str(urdf), "--out", str(made), "--trials", "200", "--jobs", "1"])
    assert result.exit_code == 0, result.output
    assert "urdf: package://marm_description/urdf/marm.urdf.xacro" in (made / "marm_setup.yaml").read_text()
    copy = tmp_path / "x" / "pkg"
    shutil.copytree(made, copy)
    shutil.rmtree(tmp_path / "a")
    args = ["validate", str(copy), "--package-path", str(fixtures), "--format", "json", "--no-plan"]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert [f for f in doc["findings"] if f["rule"].startswith("urdf.")] == []
    assert doc["validated"]["urdf"] == str(urdf)


def test_a_package_with_one_pose_per_group_says_why_nothing_was_planned(tmp_path):
    spec = tmp_path / "spec.yaml"
    spec.write_text(
        "group_states: [{name: home, group: arm, values: {joint1: 0, joint2: 0, joint3: 0, "
        "joint4: 0, joint5: 0, joint6: 0}}]\n"
    )
    pkg = tmp_path / "marm"
    result = runner.invoke(
        app, ["init", str(MARM_URDF), "--out", str(pkg), "--setup", str(spec), "--trials", "300"]
    )
    assert result.exit_code == 0, result.output
    result = runner.invoke(app, ["validate", str(pkg)])
    assert result.exit_code == 0, result.output
    assert "; planned 0 pose pairs (no group has two usable named poses);" in result.stdout.splitlines()[-2]


def test_json_is_printed_even_when_the_package_cannot_be_read(tmp_path):
    result = runner.invoke(app, ["validate", str(tmp_path / "nope"), "--format", "json"])
    assert result.exit_code == 2
    (finding,) = json.loads(result.stdout)["findings"]
    assert finding["rule"] == "input.unreadable"
    assert result.stderr.startswith("error: ")


def test_a_crashing_rule_family_is_a_finding_of_its_own_and_exit_2(tmp_path, monkeypatch):
    """A bug in one family (simulated: the OMPL rules raise) leaves the others running; json
    still prints JSON and the exit code says validate itself failed."""
    from marm_setup.validate import runner as validate_runner

    def crash(*_args):
        raise KeyError("boom")

    monkeypatch.setattr(validate_runner, "check_ompl", crash)
    good = panda("ros1")
    args = ["validate", str(good.path), "--no-plan", "--format", "json"]
    result = runner.invoke(app, [*args, "--package-path", str(good.package_paths[0])])
    assert result.exit_code == 2
    rules = [f["rule"] for f in json.loads(result.stdout)["findings"]]
    assert "internal.error" in rules and "pose.collision" in rules  # the other families ran


def test_json_survives_a_crash_outside_the_rules(tmp_path, monkeypatch):
    from marm_setup.validate import runner as validate_runner

    def crash(*_args, **_kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(validate_runner, "read_package", crash)
    result = runner.invoke(app, ["validate", str(tmp_path), "--format", "json"])
    assert result.exit_code == 2
    (finding,) = json.loads(result.stdout)["findings"]
    assert finding["rule"] == "internal.error" and "boom" in finding["message"]
    assert "Traceback" not in result.stdout


def test_a_self_pair_is_accepted_as_srdfdom_does(tmp_path):
    """`<disable_collisions link1="a" link2="a"/>` crashed the matrix rules (a traceback); srdfdom
    keeps it and it does nothing: a warning (issue 22, family 9)."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    pair = '<disable_collisions link1="panda_link1" link2="panda_link1" reason="Never"/>'
    replace_text(pkg, "config/panda.srdf", "</robot>", f"{pair}</robot>")
    args = [
        "validate",
        str(pkg),
        "--no-plan",
        "--format",
        "json",
        "--package-path",
        str(good.package_paths[0]),
    ]
    result = runner.invoke(app, args)
    assert result.exit_code == 1  # the panda's one real error (the transport pose)
    rules = {f["rule"] for f in json.loads(result.stdout)["findings"]}
    # controller.list-not-loaded: the panda's simple manager has no controller list loaded anywhere
    assert rules == {"pose.collision", "launch.missing-file", "srdf.self-pair", "controller.list-not-loaded"}


def test_the_summary_says_what_was_skipped_and_why(tmp_path):
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, "config/joint_limits.yaml", "joint_limits:", "joint_limits: [")
    args = ["validate", str(pkg), "--no-plan", "--package-path", str(good.package_paths[0])]
    summary = runner.invoke(app, args).stdout.splitlines()[-2]
    assert "; skipped the rules on config/joint_limits.yaml (malformed YAML" in summary

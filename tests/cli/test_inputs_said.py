"""Issue 23, "inputs never silently ignored, guesses said out loud": an SRDF xacro is expanded,
an SRDF that yields no group is refused, a `--xacro-arg` nothing reads is an error, and every
message names an option of the command that prints it."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import FIXTURES, MARM_URDF, realworld
from tests.helpers import ARM, build_file_tree, urdf

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
    assert "as MoveIt loads it" not in result.stdout  # nothing of the SRDF left out
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


# -- every message names an option of the command that prints it ----------------------------------


def _options(command: str) -> set[str]:
    """The options and argument metavars of `command`, from the app itself."""
    import typer.main

    params = typer.main.get_command(app).commands[command].params  # type: ignore[attr-defined]
    return {o for p in params for o in (*p.opts, *p.secondary_opts)} | {p.metavar or "" for p in params}


def _named_options(text: str) -> set[str]:
    import re

    return set(re.findall(r"(?<![\w-])--[a-z][a-z-]*", text))


def _bare_package(tmp_path):
    """A config package with an SRDF and nothing that names the robot description."""
    return build_file_tree(
        tmp_path / "bare_moveit_config",
        {
            "package.xml": "<package><name>bare_moveit_config</name></package>",
            "config/bare.srdf": "<robot name='bare'/>",
        },
    )


def test_init_from_package_without_a_description_names_its_own_way_to_give_one(tmp_path):
    pkg = _bare_package(tmp_path)
    result = runner.invoke(app, ["init", "--from-package", str(pkg), "--out", str(tmp_path / "out")])
    line = _one_error_line(result)
    assert "--urdf" not in line
    assert line.endswith("(give the robot's URDF as the URDF argument)")
    assert _named_options(line) <= _options("init")
    shown = runner.invoke(app, ["validate", str(pkg)])
    assert shown.stderr.strip().endswith("(pass --urdf URDF)")


def test_render_names_marm_setup_yaml_for_what_it_has_no_option_for(tmp_path):
    """The robot's package paths and xacro args are marm_setup.yaml's (render's --package-path and
    --xacro-arg only add to them for one run): the remedy names the setup file."""
    out = tmp_path / "pkg"
    assert runner.invoke(app, ["init", str(MARM_URDF), "--out", str(out), *TRIALS]).exit_code == 0
    setup = out / "marm_setup.yaml"
    text = setup.read_text()
    setup.write_text(text.replace("package://marm_description/", "package://nowhere_description/"))
    line = _one_error_line(runner.invoke(app, ["render", str(out)]))
    assert "unknown package 'nowhere_description'" in line
    assert line.endswith("(add its folder to robot.package_paths in marm_setup.yaml)")
    assert _named_options(line) <= _options("render")


def test_collisions_on_a_package_overwrites_a_hand_edited_srdf_with_the_force_it_asks_for(tmp_path):
    out = tmp_path / "pkg"
    assert runner.invoke(app, ["init", str(MARM_URDF), "--out", str(out), *TRIALS]).exit_code == 0
    srdf = out / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text().replace("</robot>", "<!-- mine --></robot>"))
    line = _one_error_line(runner.invoke(app, ["collisions", str(out), *TRIALS, "--seed", "1"]))
    assert "(use --force to overwrite)" in line and _named_options(line) <= _options("collisions")
    forced = runner.invoke(app, ["collisions", str(out), *TRIALS, "--seed", "1", "--force"])
    assert forced.exit_code == 0, forced.output
    assert "<!-- mine -->" in (out / "config" / "marm.srdf.orig").read_text()


@pytest.mark.parametrize("option", [["--xacro-arg", "with_gripper:=false"], ["--package-path", "."]])
def test_collisions_on_a_package_refuses_the_robot_options_it_would_ignore(tmp_path, option):
    out = tmp_path / "pkg"
    assert runner.invoke(app, ["init", str(MARM_URDF), "--out", str(out), *TRIALS]).exit_code == 0
    line = _one_error_line(runner.invoke(app, ["collisions", str(out), *TRIALS, *option]))
    assert line == (
        f"error: {option[0]}: not used with a package DIR (its marm_setup.yaml names the robot, "
        "its xacro args and package paths)"
    )


NEEDS_ARG = urdf(
    ARM.replace(
        '<link name="l1"><collision><geometry><box size="0.05',
        '<link name="l1"><collision><geometry><box size="$(arg size)',
        1,
    ),
    name="needy",
)


def test_every_command_says_how_it_takes_a_missing_xacro_arg(tmp_path):
    """The same failure (the description needs a xacro argument nobody gives) through every
    command: each says how it takes one, and names no option it does not have."""
    urdf = tmp_path / "needy.urdf.xacro"
    urdf.write_text(NEEDS_ARG)
    pkg = tmp_path / "pkg"
    made = runner.invoke(app, ["init", str(urdf), "--out", str(pkg), "--xacro-arg", "size:=0.1", *TRIALS])
    assert made.exit_code == 0, made.output
    setup = pkg / "marm_setup.yaml"
    setup.write_text(setup.read_text().replace("  xacro_args:\n    size: '0.1'\n", ""))
    runs = {
        "inspect": [str(urdf)],
        "collisions": [str(urdf), *TRIALS],
        "init": [str(urdf), "--out", str(tmp_path / "new"), *TRIALS],
        "render": [str(pkg)],
        "plan": [str(pkg), "--group", "arm", "--from", "home", "--to", "ready"],
    }
    remedies = {}
    for command, args in runs.items():
        line = _one_error_line(runner.invoke(app, [command, *args]))
        assert "undefined xacro arg 'size'" in line, line
        assert _named_options(line) <= _options(command), line
        remedies[command] = line.rsplit("'size'", 1)[1]
    assert remedies == {
        **{c: " (pass --xacro-arg NAME:=VALUE)" for c in ("inspect", "collisions", "init")},
        "render": " (set it in robot.xacro_args of marm_setup.yaml)",
        "plan": "",  # plan takes the package's own arguments only
    }
    report = runner.invoke(app, ["validate", str(pkg), "--no-plan", "--format", "json"])
    (load,) = [f for f in json.loads(report.stdout)["findings"] if f["rule"] == "urdf.load"]
    assert load["hint"] == "pass --xacro-arg NAME:=VALUE"


# -- one timing rule at init and validate ----------------------------------------------------------

TWO_LINK = FIXTURES / "two_link" / "urdf" / "two_link.urdf.xacro"


def _slow_two_link(tmp_path, velocity: str):
    urdf = tmp_path / "slow.urdf.xacro"
    urdf.write_text(TWO_LINK.read_text().replace('velocity="1.0"', f'velocity="{velocity}"'))
    return urdf


def _timing_errors(pkg) -> list[str]:
    report = json.loads(runner.invoke(app, ["validate", str(pkg), "--format", "json"]).stdout)
    return [f"{f['element']}: {f['message']}" for f in report["findings"] if f["rule"] == "runtime.limits"]


def test_init_refuses_a_velocity_limit_validate_would_find_untimeable(tmp_path):
    """init used to write max_velocity 1e-320 without a word; validate of that package reports
    it: the same rule now refuses it at init, with the same words, naming the URDF's element."""
    urdf = _slow_two_link(tmp_path, "1e-320")
    line = _one_error_line(runner.invoke(app, ["init", str(urdf), "--out", str(tmp_path / "pkg"), *TRIALS]))
    assert line == (
        f"error: {urdf}: joint[shoulder]/limit@velocity: max_velocity 9.99989e-321 of joint shoulder is below "
        "1e-06: no trajectory can be timed; override it with joint_limits[shoulder].max_velocity "
        "(in a SPEC: --setup SPEC)"
    )
    spec = tmp_path / "spec.yaml"
    spec.write_text(
        "joint_limits:\n- {joint: elbow, max_velocity: 1.0}\n- {joint: shoulder, max_velocity: 1.0}\n"
    )
    pkg = tmp_path / "pkg"
    made = runner.invoke(app, ["init", str(urdf), "--out", str(pkg), "--setup", str(spec), *TRIALS])
    assert made.exit_code == 0, made.output
    assert _timing_errors(pkg) == []
    limits = pkg / "config" / "moveit.yaml"
    limits.write_text(limits.read_text().replace("max_velocity: 1.0\n", "max_velocity: 1.0e-320\n", 1))
    (found,) = _timing_errors(pkg)
    assert found.endswith(
        "max_velocity 9.99989e-321 of joint elbow is below 1e-06: no trajectory can be timed"
    )


def test_init_refuses_a_scaled_velocity_validate_would_find_untimeable(tmp_path):
    urdf = _slow_two_link(tmp_path, "0.001")
    spec = tmp_path / "spec.yaml"
    spec.write_text("default_velocity_scaling: 0.0001\n")
    args = ["init", str(urdf), "--out", str(tmp_path / "pkg"), "--setup", str(spec), *TRIALS]
    line = _one_error_line(runner.invoke(app, args))
    assert line == (
        f"error: {spec}: default_velocity_scaling: max_velocity 0.001 of joint shoulder scaled by 0.0001 is "
        "below 1e-06: no trajectory can be timed"
    )


# -- a default package name that is already taken --------------------------------------------------


def test_a_default_package_name_another_package_has_is_said(tmp_path):
    """A workspace on the package paths already holds a marm_moveit_config: the default name
    <robot>_moveit_config would be a second package of that name in it."""
    ws = build_file_tree(
        tmp_path / "ws", {"old/package.xml": "<package><name>marm_moveit_config</name></package>"}
    )
    out = tmp_path / "pkg"
    result = runner.invoke(
        app, ["init", str(MARM_URDF), "--out", str(out), "--package-path", str(ws), *TRIALS]
    )
    assert result.exit_code == 0, result.output
    (line,) = [x.strip() for x in result.stdout.splitlines() if "package name" in x]
    assert line == (
        f"warning: package name 'marm_moveit_config' (the default) is also the package at "
        f"{(ws / 'old').resolve()}: two packages of one name break a workspace; pass --name"
    )
    args = [
        "init",
        str(MARM_URDF),
        "--out",
        str(tmp_path / "o2"),
        "--package-path",
        str(ws),
        "--name",
        "marm2_moveit_config",
    ]
    named = runner.invoke(app, [*args, *TRIALS])
    assert named.exit_code == 0 and "package name" not in named.stdout


def test_a_default_package_name_of_a_well_known_package_is_said(tmp_path):
    urdf = tmp_path / "panda.urdf"
    urdf.write_text(NEEDS_ARG.replace("$(arg size)", "0.1").replace('name="needy"', 'name="panda"', 1))
    result = runner.invoke(app, ["init", str(urdf), "--out", str(tmp_path / "pkg"), *TRIALS])
    assert result.exit_code == 0, result.output
    assert (
        "warning: package name 'panda_moveit_config' (the default) is the name of MoveIt's own "
        "panda_moveit_config; pass --name" in result.stdout
    )


@pytest.mark.parametrize("command", ["validate", "init"])
def test_a_misspelled_xacro_arg_for_a_package_is_an_error(tmp_path, command):
    """validate and init --from-package take --xacro-arg for the package's own description (and
    SRDF xacro): one neither takes is an error there too."""
    pkg = tmp_path / "pkg"
    assert runner.invoke(app, ["init", str(MARM_URDF), "--out", str(pkg), *TRIALS]).exit_code == 0
    args = {
        "validate": ["validate", str(pkg), "--no-plan"],
        "init": ["init", "--from-package", str(pkg), "--out", str(tmp_path / "new"), "--no-plan"],
    }[command]
    line = _one_error_line(runner.invoke(app, [*args, "--xacro-arg", "with_griper:=false"]))
    assert line.startswith("error: ") and line.endswith(
        ": --xacro-arg with_griper: not an argument of this xacro (did you mean 'with_gripper'?); "
        "it takes: with_gripper"
    )
    taken = runner.invoke(app, [*args, "--xacro-arg", "with_gripper:=true"])
    assert taken.exit_code in (0, 1), taken.output

"""Forms published MoveIt packages use that validate once called errors (issue 22, families 1-7),
and two defects it missed (8-9): one minimal vendor-style package each (tests/vendor_packages.py),
changed in the one way the published package is. An error claims MoveIt would fail; these load
and plan, so each is a warning or nothing, and the defects are reported."""

from __future__ import annotations

from pathlib import Path

import pytest

from marm_setup.findings import Finding
from marm_setup.package.builder import builder_files
from marm_setup.package.launch_python import BuilderCall
from marm_setup.package.read import read_package
from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

SRDF6 = "config/6dof/vx.srdf"
VJ = '<virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/>'


def findings(source: Path, paths: list[Path], **options) -> list[Finding]:
    return list(validate(source, package_paths=paths, plan=False, matrix_trials=0, **options).findings)


def errors(found: list[Finding]) -> list[tuple[str, str]]:
    return [(f.rule, f.element) for f in found if f.is_error]


def of_rule(found: list[Finding], rule: str) -> list[tuple[str, str]]:
    return [(str(f.severity), f.element) for f in found if f.rule == rule]


def edit(file: Path, old: str, new: str) -> None:
    text = file.read_text()
    assert old in text, f"{old!r} not in {file}"
    file.write_text(text.replace(old, new, 1))


# -- 1: an SRDF .xacro's args from the launch files' arg defaults, through includes ----------------

HAND_SRDF = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="vx">
  <xacro:arg name="hand" default="false"/>
  <group name="arm"><chain base_link="base_link" tip_link="link6"/></group>
  <xacro:if value="$(arg hand)"><group name="gripper"><joint name="gripper_finger_left_joint"/></group></xacro:if>
  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/>
</robot>
"""


def test_srdf_xacro_args_come_from_the_entry_launch_files_defaults(tmp_path):
    """start.launch (load_gripper default true) includes move_group.launch (default false), which
    passes it to planning_context.launch's `xacro vx.srdf.xacro hand:=$(arg load_gripper)`: what
    roslaunch start.launch loads has the gripper group, so its kinematics entry is no unknown
    group. move_group.launch sorts first but is included: it is not where the user starts."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    (source / "config/vx.srdf.xacro").write_text(HAND_SRDF)
    launch = source / "launch"
    edit(
        launch / "planning_context.launch",
        '<param name="robot_description_semantic" textfile="$(find vx_moveit_config)/config/$(arg dof)dof/vx.srdf"/>',
        '<arg name="load_gripper" default="false"/>'
        '<param name="robot_description_semantic" '
        "command=\"xacro '$(find vx_moveit_config)/config/vx.srdf.xacro' hand:=$(arg load_gripper)\"/>",
    )
    edit(
        launch / "move_group.launch",
        '<arg name="dof" default="6"/>',
        '<arg name="dof" default="6"/><arg name="load_gripper" default="false"/>',
    )
    edit(
        launch / "move_group.launch",
        '<arg name="dof" value="$(arg dof)"/></include>',
        '<arg name="dof" value="$(arg dof)"/><arg name="load_gripper" value="$(arg load_gripper)"/></include>',
    )
    (launch / "start.launch").write_text(
        '<launch><arg name="load_gripper" default="true"/><include file="$(dirname)/move_group.launch">'
        '<arg name="load_gripper" value="$(arg load_gripper)"/></include></launch>'
    )
    edit(source / "config/kinematics.yaml", "arm:", "gripper:\n  kinematics_solver: x/Y\narm:")
    pkg = read_package(source, package_paths=paths)
    assert (pkg.srdf_path, pkg.srdf_file.xacro_args) == ("config/vx.srdf.xacro", (("hand", "true"),))
    assert [g.name for g in pkg.srdf.groups] == ["arm", "gripper"]
    found = findings(source, paths)
    assert of_rule(found, "kinematics.unknown-group") == []
    assert errors(found) == []


def test_roslaunch_args_given_pick_the_variant_the_launch_files_load(tmp_path):
    """`--launch-arg dof:=7 --launch-arg load_robot_description:=true`, as `roslaunch
    vx_moveit_config move_group.launch dof:=7 load_robot_description:=true` takes them: the 7-dof
    SRDF, joint limits and controllers, and the 7-dof robot the launch files then load."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    six = read_package(source, package_paths=paths)
    assert (six.srdf_path, six.urdf.name) == ("config/6dof/vx.srdf", "vx6.urdf")
    given = {"dof": "7", "load_robot_description": "true"}
    seven = read_package(source, package_paths=paths, launch_args=given)
    assert (seven.srdf_path, seven.urdf.name) == ("config/7dof/vx.srdf", "vx7.urdf")
    assert (
        seven.joint_limits is not None
        and seven.joint_limits.where.file == "config/7dof/default_joint_limits.yaml"
    )
    assert errors(findings(source, paths, launch_args=given)) == []


# -- 2: groups in kinematics.yaml / ompl_planning.yaml the SRDF lacks --------------------------------


def test_groups_the_srdf_lacks_are_warnings(tmp_path):
    """MoveIt reads both files per group of the robot model; another key is never read."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    edit(source / "config/kinematics.yaml", "arm:", "old_arm:\n  kinematics_solver: x/Y\narm:")
    edit(source / "config/ompl_planning.yaml", "arm:", "old_arm:\n  planner_configs: [Nope]\narm:")
    found = findings(source, paths)
    assert of_rule(found, "kinematics.unknown-group") == [("warning", "old_arm")]
    assert of_rule(found, "ompl.unknown-group") == [("warning", "old_arm")]
    assert errors(found) == []


# -- 3: a driver controllers file without controllers ------------------------------------------------

SA_ROS_CONTROLLERS = """vx:
  generic_hw_control_loop:
    loop_hz: 300
  hardware_interface:
    joints: [joint_1, joint_2]
    sim_control_mode: 1
"""


def test_a_driver_file_without_controllers_is_nothing(tmp_path):
    """The Setup Assistant's ROS 1 ros_controllers.yaml with only hardware_interface: its
    spawner is given no controllers, nothing loads one from it; a list instead of a mapping
    still is malformed."""
    source, paths = PACKAGES["position_only"](tmp_path)
    (source / "config/ros_controllers.yaml").write_text(SA_ROS_CONTROLLERS)
    found = findings(source, paths)
    assert [f for f in found if f.file == "config/ros_controllers.yaml"] == []
    (source / "config/ros_controllers.yaml").write_text("[1, 2]\n")
    assert of_rule(findings(source, paths), "controller.driver-malformed") == [("error", "")]


# -- 4: a virtual joint whose parent frame is its own child link ------------------------------------


def test_a_virtual_joint_parented_to_its_own_child_is_no_tf_loop(tmp_path):
    source, paths = PACKAGES["arg_selected"](tmp_path)
    srdf = source / SRDF6
    edit(
        srdf,
        VJ,
        VJ.replace('parent_frame="world" child_link="base_link"', 'parent_frame="link1" child_link="link1"'),
    )
    found = findings(source, paths)
    assert of_rule(found, "srdf.virtual-joint-parent") == []
    assert errors(found) == []  # MoveIt skips it (child is not the root): a warning of its own
    edit(srdf, 'parent_frame="link1"', 'parent_frame="link2"')
    (
        source / "launch/demo.launch"
    ).write_text(  # publishes the virtual joint (tests/unit/test_validate_virtual_joint_tf.py)
        '<launch><node pkg="tf2_ros" type="static_transform_publisher" name="vj" args="0 0 0 0 0 0 link2 link1"/></launch>\n'
    )
    assert of_rule(findings(source, paths), "srdf.virtual-joint-parent") == [
        ("error", "virtual_joint[world_joint]")
    ]


# -- 5: .setup_assistant naming an SRDF that does not exist ------------------------------------------


def test_setup_assistant_naming_a_missing_srdf_is_a_warning(tmp_path):
    """Only the Setup Assistant reads .setup_assistant; move_group loads the SRDF the launch
    files name (config/6dof/vx.srdf)."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    edit(source / ".setup_assistant", "relative_path: config/6dof/vx.srdf", "relative_path: config/vx.srdf")
    found = findings(source, paths)
    assert of_rule(found, "srdf.missing") == [("warning", "SRDF.relative_path")]
    assert errors(found) == []


# -- 6: a virtual joint without a name ---------------------------------------------------------------


def test_a_virtual_joint_without_a_name_is_a_warning(tmp_path):
    """srdfdom skips it; MoveIt assumes a fixed root joint and plans. Another element without a
    name srdfdom skips stays an error."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    srdf = source / SRDF6
    edit(srdf, 'name="world_joint" ', "")
    found = findings(source, paths)
    assert of_rule(found, "srdf.parse") == [("warning", "virtual_joint")]
    assert errors(found) == []
    edit(srdf, '<group_state name="bent"', "<group_state")
    assert ("srdf.parse", "group_state") in errors(findings(source, paths))


# -- 7: ROS 2 packages whose launch files are Python ---------------------------------------------------


def test_ros2_control_manager_needs_no_controller_list(tmp_path):
    """Ros2ControlManager takes MoveIt's controllers from ros2_control at run time: no list is
    needed, and a group joint no trajectory or gripper controller drives is a warning."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / "config/bot_controllers.yaml").write_text(
        "moveit_controller_manager: moveit_ros_control_interface/Ros2ControlManager\n"
    )
    found = findings(source, paths)
    assert errors(found) == []
    assert of_rule(found, "controller.uncovered-joint") == []
    edit(
        source / "config/ros2_controllers.yaml",
        "type: position_controllers/GripperActionController",
        "type: x/Other",
    )
    found = findings(source, paths)
    assert errors(found) == []
    assert of_rule(found, "controller.uncovered-joint") == [("warning", "joint[gripper_finger_left_joint]")]


def test_a_package_building_several_robots_is_read_for_one():
    """One launch file per robot (open_manipulator_moveit_config): the calls of the robot the
    user's --srdf / --urdf names are read, not a mix of the first file naming each."""
    calls = tuple(
        BuilderCall(
            f"launch/{r}.launch.py", r, "om_moveit_config", files=(("joint_limits", f"config/{r}/l.yaml"),)
        )
        for r in ("omx", "omy")
    )
    first = builder_files(calls, "om_moveit_config")
    assert (first.robot_name, first.others, first.explicit("joint_limits").file) == (
        "omx",
        ("omy",),
        "config/omx/l.yaml",
    )
    chosen = builder_files(calls, "om_moveit_config", ("omy",))
    assert (chosen.robot_name, chosen.explicit("joint_limits").file) == ("omy", "config/omy/l.yaml")


def test_a_description_only_the_run_time_gives_is_a_warning_and_the_rest_runs(tmp_path):
    """No .setup_assistant, no config/<robot>.urdf.xacro, a builder naming no description (UR's
    ur_moveit_config): move_group takes it from /robot_description at run time. A warning says
    what was not read and what was skipped; the rules that need no robot still run (an unknown
    OMPL planner config is still an error); planning and porting still need --urdf (exit 2)."""
    import pytest

    from marm_setup.errors import InputError

    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    edit(source / "launch/move_group.launch.py", ".robot_description(mappings=mappings)\n", "")
    result = validate(source, package_paths=paths, plan=False, matrix_trials=0)
    found = list(result.findings)
    assert errors(found) == []
    [runtime] = [f for f in found if f.rule == "urdf.runtime-only"]
    assert (str(runtime.severity), runtime.file) == ("warning", "launch/move_group.launch.py")
    assert "/robot_description" in runtime.message and "collisions" in runtime.message
    assert result.robot is None and any("comes only at run time" in s for s in result.skipped)
    edit(
        source / "config/ompl_planning.yaml",
        "default_planner_config: RRTConnectkConfigDefault",
        "default_planner_config: Nope",
    )
    edit(
        source / "config/kinematics.yaml", "kinematics_solver_timeout: 0.05", "kinematics_solver_timeout: -1"
    )
    found = findings(source, paths)
    assert errors(found) == [("kinematics.non-positive", "arm.kinematics_solver_timeout")]
    # MoveIt plans with RRTConnect instead of an unknown default config: a warning
    assert of_rule(found, "ompl.unknown-default-planner") == [("warning", "arm.default_planner_config")]
    with pytest.raises(InputError, match="no description file validate can read"):
        _ = read_package(source, package_paths=paths).description_file
    (source / "config/bot.srdf").unlink()  # not a config package's robot any more: still bad input
    (source / "package.xml").unlink()
    with pytest.raises(InputError, match="not a MoveIt config package"):
        read_package(source, package_paths=paths)


# -- 8: a joint_limits.yaml override above the URDF's limit, in rosparam's degrees ------------------


def test_a_limit_in_degrees_above_the_urdf_is_reported(tmp_path):
    """rosparam's `!degrees 90` is 1.571 rad/s, above the URDF's 1.0: MoveIt uses the override.
    The forms once missed: MoveIt applies min/max_position without has_position_limits (it never
    reads that key), and MoveIt 1 a max_velocity without has_velocity_limits."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    limits = source / "config/6dof/default_joint_limits.yaml"
    edit(limits, "max_velocity: 0.41", "max_velocity: !degrees 90")
    edit(limits, "joint_2:\n    has_velocity_limits: true\n", "joint_2:\n    max_position: !degrees 180\n")
    found = findings(source, paths)
    assert of_rule(found, "limits.above-urdf") == [
        ("warning", "joint_limits.joint_1.max_velocity"),
        ("warning", "joint_limits.joint_2.max_position"),
    ]
    messages = [f.message for f in found if f.rule == "limits.above-urdf"]
    assert messages == [
        "max_velocity 1.5708 is above the URDF's 1",
        "max_position 3.14159 is above the URDF's 2",
    ]
    edit(limits, "has_velocity_limits: true\n    max_velocity: !degrees 90", "max_velocity: !degrees 90")
    assert len(of_rule(findings(source, paths), "limits.above-urdf")) == 2  # MoveIt 1 still applies it


# -- 9: <disable_collisions> of a link with itself ---------------------------------------------------


def test_a_link_disabled_against_itself_is_a_warning(tmp_path):
    source, paths = PACKAGES["arg_selected"](tmp_path)
    edit(
        source / SRDF6,
        "</robot>",
        '<disable_collisions link1="link2" link2="link2" reason="Adjacent"/></robot>',
    )
    found = findings(source, paths)
    assert of_rule(found, "srdf.self-pair") == [("warning", "disable_collisions[link2 link2]")]
    assert errors(found) == []


COMMAND_LAUNCH = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    hw_name = "hw"
    description = Command(
        [FindExecutable(name="xacro"), " ",
         PathJoinSubstitution([FindPackageShare("bot_description"), "urdf", "bot.urdf.xacro"]),
         " hw:=", LaunchConfiguration(hw_name), " robot_ip:=", LaunchConfiguration("robot_ip")]
    )
    return LaunchDescription([
        DeclareLaunchArgument(hw_name, default_value="mock"),
        DeclareLaunchArgument("robot_ip"),
        Node(package="moveit_ros_move_group", executable="move_group",
             parameters=[{"robot_description": description}]),
    ])
"""


def test_a_description_a_python_launch_file_builds_with_xacro_is_read(tmp_path):
    """franka_ros2's form: `{"robot_description": Command([FindExecutable(name="xacro"), " ",
    PathJoinSubstitution([FindPackageShare(...), ...]), " hw:=", LaunchConfiguration(...)])}`.
    Read statically: the file, the args whose value is known (launch argument defaults); an arg
    only the run time gives that the xacro needs, or a file in a package no path holds, is a
    warning (the rules needing no robot still run); a file its package lacks is bad input (exit 2)."""
    import pytest

    from marm_setup.errors import InputError

    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    (source / "launch/move_group.launch.py").write_text(COMMAND_LAUNCH)
    xacro = tmp_path / "bot_description/urdf/bot.urdf.xacro"
    edit(
        xacro,
        '<xacro:arg name="use_sim"',
        "<xacro:if value=\"${'$(arg hw)' == 'mock'}\"/>\n  <xacro:arg name=\"use_sim\"",
    )
    result = validate(source, package_paths=paths, plan=False, matrix_trials=0)
    assert (result.robot, result.urdf_origin) == ("bot", "xacro command in launch/move_group.launch.py")
    assert errors(list(result.findings)) == []
    edit(source / "launch/move_group.launch.py", 'hw_name, default_value="mock"', "hw_name")
    found = findings(source, paths)
    assert errors(found) == []
    assert of_rule(found, "urdf.runtime-arg") == [("warning", "xacro")]
    edit(
        source / "config/kinematics.yaml", "kinematics_solver_timeout: 0.05", "kinematics_solver_timeout: -1"
    )
    assert errors(findings(source, paths)) == [("kinematics.non-positive", "arm.kinematics_solver_timeout")]
    edit(
        source / "launch/move_group.launch.py",
        'FindPackageShare("bot_description")',
        'FindPackageShare("elsewhere")',
    )
    found = findings(source, paths)
    [missing] = [f for f in found if f.rule == "urdf.package-missing"]  # the package it names
    assert "'elsewhere'" in missing.message and str(missing.severity) == "warning"
    assert not [f for f in found if f.rule == "urdf.runtime-only"]
    edit(
        source / "launch/move_group.launch.py",
        'FindPackageShare("elsewhere")',
        'FindPackageShare("bot_description")',
    )
    edit(source / "launch/move_group.launch.py", '"bot.urdf.xacro"', '"gone.urdf.xacro"')
    with pytest.raises(InputError, match="gone.urdf.xacro does not exist"):
        read_package(source, package_paths=paths)
    outside = tmp_path.parent / f"{tmp_path.name}_outside.urdf.xacro"  # no package path holds it
    outside.write_text(xacro.read_text())
    launch = source / "launch/move_group.launch.py"
    launch.write_text(
        launch.read_text().replace(
            'PathJoinSubstitution([FindPackageShare("bot_description"), "urdf", "gone.urdf.xacro"])',
            repr(str(outside)),
        )
    )
    [runtime] = [f for f in findings(source, paths) if f.rule == "urdf.runtime-only"]
    assert "outside the package and the folders named" in runtime.message
    outside.unlink()


def _srdf_named_by_a_launch_arg(tmp_path: Path) -> tuple[Path, list[Path]]:
    """UR's form: the builder's SRDF xacro takes name:= from a launch argument without default
    (here robot_ip), and no .setup_assistant names a description."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    srdf = (source / "config/bot.srdf").read_text().replace('name="bot"', 'name="$(arg name)"', 1)
    (source / "config/bot.srdf.xacro").write_text(
        srdf.replace("<robot ", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" ', 1)
    )
    (source / "config/bot.srdf").unlink()
    edit(
        source / "launch/move_group.launch.py",
        ".robot_description(mappings=mappings)",
        '.robot_description_semantic("config/bot.srdf.xacro", {"name": LaunchConfiguration("robot_ip")})',
    )
    return source, paths


def test_an_srdf_xacro_arg_only_the_run_time_gives_is_a_warning(tmp_path):
    """UR's ur_moveit_config: `.robot_description_semantic(Path("srdf") / "ur.srdf.xacro",
    {"name": ur_type})`, `ur_type` a launch argument without default, the xacro's robot name
    `$(arg name)`. MoveIt has the value at run time; validate says what it could not read, and
    the controller rules (which need neither robot nor SRDF) still run."""
    source, paths = _srdf_named_by_a_launch_arg(tmp_path)
    found = findings(source, paths)
    assert errors(found) == []
    assert {f.rule for f in found if str(f.severity) == "warning"} >= {
        "urdf.runtime-only",
        "srdf.runtime-arg",
    }
    edit(source / "config/bot_controllers.yaml", "    action_ns: gripper_cmd\n", "")
    assert errors(findings(source, paths)) == [
        ("controller.missing-action-ns", "moveit_simple_controller_manager.bot_hand_controller")
    ]


def test_launch_args_given_as_ros2_launch_takes_them_fill_what_only_the_run_time_gave(tmp_path):
    """`--launch-arg NAME:=VALUE` (`ros2 launch pkg file ur_type:=ur5e`): a launch argument
    without default is known, so the SRDF xacro's name:= and the description's xacro arg are read
    instead of left to the run time; a given value beats a declared default."""
    source, paths = _srdf_named_by_a_launch_arg(tmp_path)
    given = validate(
        source, package_paths=paths, plan=False, matrix_trials=0, launch_args={"robot_ip": "bot"}
    )
    assert not [f for f in given.findings if f.rule == "srdf.runtime-arg"]
    assert given.as_dict()["launch_args"] == {"robot_ip": "bot"}
    assert "; launch args robot_ip:=bot" in given.describe()
    pkg = read_package(source, package_paths=paths, launch_args={"robot_ip": "bot"})
    assert (
        pkg.srdf_file is not None
        and pkg.srdf_file.srdf is not None
        and pkg.srdf_file.srdf.robot_name == "bot"
    )
    (source / "launch/move_group.launch.py").write_text(
        COMMAND_LAUNCH.replace('hw_name, default_value="mock"', "hw_name")
    )
    assert read_package(source, package_paths=paths).unread_xacro_args == ("hw", "robot_ip")
    pkg = read_package(source, package_paths=paths, launch_args={"hw": "mock", "robot_ip": "10.0.0.2"})
    assert dict(pkg.xacro_args) == {"hw": "mock", "robot_ip": "10.0.0.2"} and pkg.unread_xacro_args == ()


# -- a controller list a Python launch puts under the simple manager's namespace itself ----------

HAND_LAUNCH = "launch/moveit.launch.py"
HAND_LOAD = 'load_yaml("hl_moveit_config", "config/hlarm_controllers.yaml")'


def test_a_controller_list_the_launch_puts_under_the_manager_namespace(tmp_path):
    """`{"moveit_simple_controller_manager": load_yaml(...)}` lands a top-level controller_names
    where MoveIt 2 reads it (also through a name bound to the load): no controller.no-namespace.
    Handed over as it is, or namespaced twice, MoveIt 2 finds no controllers (an error)."""
    source, paths = PACKAGES["hand_loaded"](tmp_path / "a")
    assert of_rule(findings(source, paths), "controller.no-namespace") == []
    loaded = read_package(source, package_paths=paths).source("moveit_controllers")
    assert loaded is not None and "under moveit_simple_controller_manager" in loaded.how
    bound, paths = PACKAGES["hand_loaded"](tmp_path / "b")
    edit(bound / HAND_LAUNCH, "    controllers = {", f"    listed = {HAND_LOAD}\n    controllers = {{")
    edit(
        bound / HAND_LAUNCH,
        f'"moveit_simple_controller_manager": {HAND_LOAD}',
        '"moveit_simple_controller_manager": listed',
    )
    assert of_rule(findings(bound, paths), "controller.no-namespace") == []
    plain, paths = PACKAGES["hand_loaded"](tmp_path / "c")
    edit(plain / HAND_LAUNCH, f'"moveit_simple_controller_manager": {HAND_LOAD},', "")
    edit(plain / HAND_LAUNCH, "parameters=[controllers,", f"parameters=[controllers, {HAND_LOAD},")
    assert of_rule(findings(plain, paths), "controller.no-namespace") == [("error", "controller_names")]
    twice, paths = PACKAGES["hand_loaded"](tmp_path / "d")
    text = (twice / "config/hlarm_controllers.yaml").read_text()
    nested = "moveit_simple_controller_manager:\n" + "".join(f"  {line}\n" for line in text.splitlines())
    (twice / "config/hlarm_controllers.yaml").write_text(nested)
    found = [f for f in findings(twice, paths) if f.rule == "controller.no-namespace"]
    assert [f.severity for f in found] == ["error"]
    assert (
        "moveit_simple_controller_manager.moveit_simple_controller_manager.controller_names"
        in found[0].message
    )


# -- a Python launch without MoveItConfigsBuilder: what it loads by hand, not the builder's guess ----

DRIVER_NODE_PARAMS = """hl_trajectory_driver:
  ros__parameters:
    joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6]
"""


def test_a_hand_loaded_controller_list_wins_over_the_builders_guess(tmp_path):
    """A launch that calls no MoveItConfigsBuilder and loads `config/controllers.yaml` by hand
    into moveit_simple_controller_manager: that is move_group's list, even where the only
    `config/*_controllers.yaml` (the one the builder would guess) is `fake_controllers.yaml`,
    another node's parameter file."""
    source, paths = PACKAGES["hand_loaded"](tmp_path)
    (source / "config/hlarm_controllers.yaml").rename(source / "config/controllers.yaml")
    (source / "config/hlarm_ros_controllers.yaml").unlink()
    (source / "config/fake_controllers.yaml").write_text(DRIVER_NODE_PARAMS)
    edit(source / HAND_LAUNCH, "config/hlarm_controllers.yaml", "config/controllers.yaml")
    loaded = read_package(source, package_paths=paths).source("moveit_controllers")
    assert loaded is not None and loaded.file == "config/controllers.yaml"
    found = findings(source, paths)
    assert [f for f in errors(found) if f[0].startswith("controller.")] == []


FAKE_LIST = """controller_list:
  - name: fake_arm_controller
    type: $(arg fake_execution_type)
    joints: [joint_1]
initial:
  - group: nope
    pose: home
"""


def test_a_ros2_package_has_no_fake_controllers(tmp_path):
    """MoveIt 2 has no fake controller manager (moveit/moveit2#471): a MoveIt 1
    `fake_controllers.yaml` left in a ROS 2 package is read by nothing, so its joints, list and
    initial poses are no findings."""
    source, paths = PACKAGES["hand_loaded"](tmp_path)
    (source / "config/fake_controllers.yaml").write_text(FAKE_LIST)
    assert read_package(source, package_paths=paths).fake_controllers is None
    found = findings(source, paths)
    assert [f for f in found if "fake" in f.rule] == []
    assert errors(found) == []


OMPL_BY_HAND = """planner_configs:
  RRTConnectkConfigDefault:
    type: geometric::RRTConnect
arm:
  planner_configs: [RRTConnectkConfigDefault]
"""
PIPELINE_DICT = """    pipeline = {"move_group": {
        "planning_plugin": "ompl_interface/OMPLPlanner",
        "request_adapters": "default_planner_request_adapters/AddTimeOptimalParameterization "
                            "default_planner_request_adapters/FixStartStateBounds",
    }}
    pipeline["move_group"].update(load_yaml("hl_moveit_config", "config/ompl_planning.yaml"))
    controllers = {"""


@pytest.mark.parametrize(
    "named", ['"config/ompl_planning.yaml"', 'os.path.join("config", "ompl_planning.yaml")']
)
def test_a_pipeline_file_the_launch_gives_its_planning_plugin(tmp_path, named):
    """A Humble launch without MoveItConfigsBuilder that sets `move_group.planning_plugin` in a
    dict and updates it with ompl_planning.yaml: move_group gets the plugin (humble
    move_group.cpp plans with the `move_group` namespace when no planning_pipelines is set), so
    the file's lacking it is no error; a Jazzy-only adapter there still is one."""
    source, paths = PACKAGES["hand_loaded"](tmp_path)
    (source / "config/ompl_planning.yaml").write_text(OMPL_BY_HAND)
    edit(
        source / HAND_LAUNCH,
        "    controllers = {",
        PIPELINE_DICT.replace('"config/ompl_planning.yaml"', named),
    )
    edit(source / HAND_LAUNCH, "parameters=[controllers,", "parameters=[controllers, pipeline,")
    assert of_rule(findings(source, paths, ros_distro="humble"), "distro.pipeline-format") == []
    edit(
        source / HAND_LAUNCH,
        "default_planner_request_adapters/FixStartStateBounds",
        "default_planning_request_adapters/X",
    )
    assert errors(findings(source, paths, ros_distro="humble")) == [("distro.adapter", "request_adapters")]


def test_a_controller_list_the_launch_computes_at_run_time(tmp_path):
    """`.trajectory_execution("config/controllers/controllers" + suffix + ".yaml")`: the builder
    loads a file only the run time names, so there is a controller configuration (no
    controller.none, 'MoveIt can plan but not execute') and no guess among *_controllers.yaml;
    one controller.runtime-only warning says the controller rules were skipped."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / "config/controllers").mkdir()
    (source / "config/bot_controllers.yaml").rename(source / "config/controllers/controllers_a.yaml")
    edit(
        source / "launch/move_group.launch.py",
        '        .planning_pipelines(pipelines=["ompl"])',
        '        .trajectory_execution("config/controllers/controllers_" + use_sim.perform(None) + ".yaml")\n'
        '        .planning_pipelines(pipelines=["ompl"])',
    )
    found = findings(source, paths)
    assert of_rule(found, "controller.none") == []
    assert of_rule(found, "controller.runtime-only") == [("warning", "trajectory_execution")]
    assert errors(found) == []


OMPL_WITHOUT_CONFIGS = """planning_plugin: ompl_interface/OMPLPlanner
arm:
  default_planner_config: RRTConnect
  planner_configs: [RRTConnect, BiTRRT, LazyPRMstar]
"""


def test_the_builder_adds_moveits_planner_configs_to_an_ompl_file_without_them(tmp_path):
    """MoveItConfigsBuilder.planning_pipelines adds moveit_configs_utils' ompl_defaults.yaml to an
    ompl file without `planner_configs` (humble moveit_configs_builder.py l.475-479): a group
    naming those configurations names defined ones; one neither the file nor the defaults define
    still is an error."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / "config/ompl_planning.yaml").write_text(OMPL_WITHOUT_CONFIGS.replace("LazyPRMstar", "Nope"))
    found = findings(source, paths, ros_distro="humble")
    assert errors(found) == [("ompl.unknown-planner-config", "arm.planner_configs")]
    (source / "config/ompl_planning.yaml").write_text(OMPL_WITHOUT_CONFIGS)
    assert errors(findings(source, paths, ros_distro="humble")) == []

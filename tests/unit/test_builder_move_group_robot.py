"""A package whose launch files build several robot names is validated for the one move_group
gets: the builder of a launch file that starts move_group (generate_move_group_launch, or a
move_group node of its own; moveit2 moveit_configs_utils launches.py l.190-255), not the first
launch file by name. A controller_manager.launch.py building `<robot>_description` for
ros2_control_node alone sorted before demo.launch.py and move_group.launch.py, and validate
read that robot's files and named it as the one MoveIt loads."""

from __future__ import annotations

from marm_setup.package.builder import builder_files, builds_same_robot
from marm_setup.package.launch_python import BuilderCall, read_python_launch
from marm_setup.validate.runner import validate
from tests.vendor_packages import LAUNCH_PY, PACKAGES

CONTROL_ONLY = """from launch import LaunchDescription
from launch_ros.actions import Node
from moveit_configs_utils import MoveItConfigsBuilder


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder("bot_description", package_name="bot_moveit_config").to_moveit_configs()
    node = Node(package="controller_manager", executable="ros2_control_node",
                parameters=[moveit_config.robot_description])
    return LaunchDescription([node])
"""
GENERATED = """from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_move_group_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder("bot", package_name="bot_moveit_config").to_moveit_configs()
    return generate_move_group_launch(moveit_config)
"""


def test_the_robot_of_the_launch_starting_move_group_is_chosen():
    def calls(mover: bool) -> tuple[BuilderCall, ...]:
        return (
            BuilderCall("launch/controller_manager.launch.py", "bot_description", "p"),
            BuilderCall("launch/move_group.launch.py", "bot", "p", starts_move_group=mover),
        )

    assert builder_files(calls(False), "p").robot_name == "bot_description"  # no mover: the first
    chosen = builder_files(calls(True), "p")
    assert (chosen.robot_name, chosen.others) == ("bot", ("bot_description",))
    assert builder_files(calls(True), "p", ("bot_description",)).robot_name == "bot_description"


def test_which_launch_files_start_move_group(tmp_path):
    (tmp_path / "launch").mkdir()
    (tmp_path / "launch/a.launch.py").write_text(CONTROL_ONLY)
    (tmp_path / "launch/b.launch.py").write_text(GENERATED)
    (tmp_path / "launch/c.launch.py").write_text(PACKAGES_LAUNCH)
    names = ("launch/a.launch.py", "launch/b.launch.py", "launch/c.launch.py")
    found = read_python_launch(tmp_path, names, lambda _n: None)
    assert [(b.launch, b.starts_move_group) for b in found.builders] == [
        ("launch/a.launch.py", False),
        ("launch/b.launch.py", True),
        ("launch/c.launch.py", True),
    ]


def test_a_control_only_launch_sorting_first_does_not_choose_the_robot(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / "launch/controller_manager.launch.py").write_text(CONTROL_ONLY)
    found = validate(source, package_paths=paths, plan=False, matrix_trials=0).findings
    [several] = [f for f in found if f.rule == "launch.several-robots"]
    assert several.file == "launch/move_group.launch.py"
    assert "validated bot (" in several.message and "also build bot_description" in several.message


PACKAGES_LAUNCH = """from launch_ros.actions import Node
from moveit_configs_utils import MoveItConfigsBuilder


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder("bot").to_moveit_configs()
    return Node(package="moveit_ros_move_group", executable="move_group", parameters=[moveit_config.to_dict()])
"""


def test_another_robot_name_loading_the_same_files_is_the_same_robot(tmp_path):
    """comau_racer5_080_description_moveit_config: MoveItConfigsBuilder("<robot>_description")
    given config/<robot>.urdf.xacro and config/<robot>.srdf by file_path, beside the Setup
    Assistant's MoveItConfigsBuilder("<robot>"), which takes those same files by default: one
    robot, no launch.several-robots warning. Another file, or other xacro mappings, is another
    robot and keeps it."""
    (tmp_path / "config").mkdir()
    (tmp_path / "config/bot.urdf.xacro").write_text("<robot/>")
    urdf, srdf = (
        ("robot_description", "config/bot.urdf.xacro"),
        ("robot_description_semantic", "config/bot.srdf"),
    )
    mover = BuilderCall("launch/move_group.launch.py", "bot", "p", starts_move_group=True)

    def chosen(*files: tuple[str, str], mappings=()) -> object:
        control = BuilderCall(
            "launch/controller_manager.launch.py", "bot_d", "p", files=files, mappings=mappings
        )
        return builder_files((control, mover), "p")

    assert builds_same_robot(chosen(urdf, srdf), "bot_d", tmp_path, None)
    assert not builds_same_robot(chosen(urdf), "bot_d", tmp_path, None)  # config/bot_d.srdf
    assert not builds_same_robot(
        chosen(("robot_description", "config/x.urdf"), srdf), "bot_d", tmp_path, None
    )
    mapped = chosen(urdf, srdf, mappings=(("robot_description", (("arm", "left"),)),))
    assert not builds_same_robot(mapped, "bot_d", tmp_path, None)


def test_no_several_robots_warning_for_the_same_files(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path)
    same = LAUNCH_PY.replace('Builder("bot"', 'Builder("bot_description"').replace(
        'executable="move_group"', 'executable="ros2_control_node"'
    )
    (source / "launch/controller_manager.launch.py").write_text(same)
    found = validate(source, package_paths=paths, plan=False, matrix_trials=0).findings
    assert [f for f in found if f.rule == "launch.several-robots"] == []

"""turtlebot3_manipulation_moveit_config's move_group.launch.py: the controller list is loaded by
hand inline (`path = os.path.join(get_package_share_directory(pkg), "config", "x.yaml")`,
`with open(path) as file: listed = yaml.safe_load(file)`) and handed to move_group under
`{"moveit_simple_controller_manager": listed}`, where MoveIt 2 reads it (moveit2
moveit_simple_controller_manager.cpp initialize l.105-108). Its only MoveItConfigsBuilder is in
setup_assistant.launch.py, whose config goes to generate_setup_assistant_launch alone (moveit2
moveit_configs_utils launches.py: the Setup Assistant node with --config_pkg, no parameters):
that builder's trajectory_execution reaches no move_group."""

from __future__ import annotations

from marm_setup.package.read import read_package
from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

INLINE = """import os

import yaml
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    controllers_path = os.path.join(
        get_package_share_directory("hl_moveit_config"), "config", "moveit_controllers.yaml"
    )
    with open(controllers_path, "r") as file:
        controllers_yaml = yaml.safe_load(file)
    controllers = {
        "moveit_simple_controller_manager": controllers_yaml,
        "moveit_controller_manager": "moveit_simple_controller_manager/MoveItSimpleControllerManager",
    }
    move_group = Node(package="moveit_ros_move_group", executable="move_group", parameters=[controllers])
    return LaunchDescription([move_group])
"""
SETUP_ASSISTANT = """from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_setup_assistant_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder("hl", package_name="hl_moveit_config").to_moveit_configs()
    return generate_setup_assistant_launch(moveit_config)
"""


def inline_loaded(tmp_path):
    source, paths = PACKAGES["hand_loaded"](tmp_path)
    (source / "config/hlarm_controllers.yaml").rename(source / "config/moveit_controllers.yaml")
    (source / "launch/moveit.launch.py").write_text(INLINE)
    return source, paths


def how_loaded(source, paths) -> str:
    loaded = read_package(source, package_paths=paths).source("moveit_controllers")
    return "" if loaded is None else loaded.how


def namespace_findings(source, paths) -> list[str]:
    found = validate(source, package_paths=paths, plan=False, matrix_trials=0).findings
    return [str(f.severity) for f in found if f.rule == "controller.no-namespace"]


def test_an_inline_hand_load_under_the_manager_namespace(tmp_path):
    source, paths = inline_loaded(tmp_path)
    assert "under moveit_simple_controller_manager" in how_loaded(source, paths)
    assert namespace_findings(source, paths) == []


def test_a_builder_only_the_setup_assistant_gets_gives_move_group_nothing(tmp_path):
    source, paths = inline_loaded(tmp_path)
    (source / "launch/setup_assistant.launch.py").write_text(SETUP_ASSISTANT)
    assert "under moveit_simple_controller_manager" in how_loaded(source, paths)
    assert namespace_findings(source, paths) == []

"""A MoveItConfigsBuilder imported from another module than moveit_configs_utils (xarm_ros2's
`from uf_ros_lib.moveit_configs_builder import MoveItConfigsBuilder`, which wraps the controller
list under moveit_simple_controller_manager itself and merges its own defaults) is not MoveIt's:
validate follows the description and SRDF files it is given, reads nothing else through it, and
says so in the summary instead of applying MoveIt's builder conventions (a file handed over as
it is: controller.no-namespace)."""

from __future__ import annotations

from pathlib import Path

import pytest

from marm_setup.package.launch_python import builder_origins, is_moveit_builder
from marm_setup.validate import validate

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3"><name>tri_moveit_config</name><version>0.0.0</version>
<description>t</description><maintainer email="a@example.com">a</maintainer><license>BSD</license>
<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake</build_type></export>
</package>
"""
URDF = """<robot name="tri"><link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>
"""
SRDF = '<robot name="tri"><group name="arm"><joint name="j1"/></group></robot>\n'
CONTROLLERS = """controller_names: [arm_controller]
arm_controller: {action_ns: follow_joint_trajectory, type: FollowJointTrajectory, default: true, joints: [j1]}
"""
OMPL = "arm:\n  default_planner_config: RRTConnect\n  planner_configs: [RRTConnect]\n"
LAUNCH = """IMPORT


def generate_launch_description():
    moveit_config = (
        MoveItConfigsBuilder(context=None, dof=1)
        .robot_description(file_path="urdf/tri.urdf")
        .robot_description_semantic(file_path="config/tri.srdf")
        .trajectory_execution(file_path="config/controllers.yaml")
        .planning_pipelines(config_folder="config")
        .to_moveit_configs()
    )
    return moveit_config
"""
MOVEIT = "from moveit_configs_utils import MoveItConfigsBuilder"
VENDOR = "from uf_ros_lib.moveit_configs_builder import MoveItConfigsBuilder"


def _validated(root: Path, imports: str):
    pkg = root / "tri_moveit_config"
    for rel, text in {
        "package.xml": PACKAGE_XML,
        "urdf/tri.urdf": URDF,
        "config/tri.srdf": SRDF,
        "config/controllers.yaml": CONTROLLERS,
        "config/ompl_planning.yaml": OMPL,
        "launch/demo.launch.py": LAUNCH.replace("IMPORT", imports),
    }.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text(text, encoding="utf-8")
    return validate(pkg, plan=False, matrix_trials=0)


def test_moveits_builder_hands_the_list_over_as_it_is(tmp_path):
    done = _validated(tmp_path, MOVEIT)
    assert "controller.no-namespace" in [f.rule for f in done.findings if f.is_error]
    assert done.robot == "tri"


def test_a_vendor_builder_is_followed_for_the_description_only_and_said(tmp_path):
    done = _validated(tmp_path, VENDOR)
    assert [f.rule for f in done.findings if f.is_error] == []
    assert "controller.none" not in [f.rule for f in done.findings]
    assert done.robot == "tri"
    assert "uf_ros_lib.moveit_configs_builder" in done.urdf_origin
    said = [s for s in done.skipped if "uf_ros_lib.moveit_configs_builder" in s]
    assert said and "MoveIt's controller list" in said[0] and "planning pipelines" in said[0]


@pytest.mark.parametrize(
    ("source", "call", "moveit"),
    [
        ("from moveit_configs_utils import MoveItConfigsBuilder", "MoveItConfigsBuilder", True),
        ("from moveit_configs_utils.moveit_configs_builder import MoveItConfigsBuilder as B", "B", True),
        ("import moveit_configs_utils as mcu", "mcu", True),
        ("from moveit_configs_utils import *", "MoveItConfigsBuilder", True),
        ("from uf_ros_lib.moveit_configs_builder import MoveItConfigsBuilder", "MoveItConfigsBuilder", False),
        ("class MoveItConfigsBuilder:\n    pass", "MoveItConfigsBuilder", False),
    ],
)
def test_where_the_builder_name_comes_from(source, call, moveit):
    import ast

    origins = builder_origins(ast.parse(source))
    origin = origins.get(call) or origins.get(f"import {call}", "")
    assert is_moveit_builder(origin) is moveit

"""Packages whose Python launch computes the SRDF and hands move_group its parameter files
itself (no MoveItConfigsBuilder): the SRDF validate picks by name is a robot's, not a xacro
macro library's, and is the user's robot's when --urdf names it; a kinematics parameter file
(`/**: ros__parameters:`) is read as move_group reads it."""

from __future__ import annotations

from pathlib import Path

from marm_setup.package.read import read_package
from marm_setup.validate.runner import validate
from tests.helpers import build_file_tree
from tests.vendor_packages import AMENT, _arm_urdf, _srdf

CONFIG = "ux_moveit_config"
LAUNCH_PY = """from launch import LaunchDescription
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    dof = LaunchConfiguration("dof")
    return LaunchDescription([Node(package="moveit_ros_move_group", executable="move_group",
                                   parameters=[{"robot_description_semantic": dof}])])
"""
MACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://ros.org/wiki/xacro" name="{name}">{include}
  <xacro:macro name="{name}_macro">{body}</xacro:macro>
</robot>
"""
INCLUDE = '<xacro:include filename="_ux5_macro.srdf.xacro"/>'  # beside it
TOP = """<?xml version="1.0"?>
<robot xmlns:xacro="http://wiki.ros.org/xacro" name="{name}">
  <xacro:include filename="$(find ux_moveit_config)/srdf/ux_macro.srdf.xacro"/>
  <xacro:ux_srdf_macro/>
</robot>
"""


def _body(robot: str) -> str:
    text = _srdf(robot, 6, gripper=False)
    return text[text.index(">", text.index("<robot")) + 1 : text.rindex("</robot>")]


def _package(root: Path, srdf_folder: str = "srdf") -> Path:
    files = {
        "ux_description/package.xml": AMENT.format(name="ux_description"),
        "ux_description/urdf/ux.urdf.xacro": _arm_urdf("UX", 6, gripper=False),
        f"{CONFIG}/package.xml": AMENT.format(name=CONFIG),
        f"{CONFIG}/launch/move_group.launch.py": LAUNCH_PY,
        # a macro library for another model, sorting first; the library the tops include
        f"{CONFIG}/{srdf_folder}/_ux5_macro.srdf.xacro": MACRO.format(
            name="ux5_srdf", include="", body=_body("x")
        ),
        f"{CONFIG}/{srdf_folder}/ux_macro.srdf.xacro": MACRO.format(
            name="ux_srdf", include=INCLUDE, body=_body("x")
        ),
        f"{CONFIG}/{srdf_folder}/dual_ux.srdf.xacro": TOP.format(name="DUAL_UX"),
        f"{CONFIG}/{srdf_folder}/ux.srdf.xacro": TOP.format(name="UX"),
    }
    files = {
        k: v.replace("ux_moveit_config)/srdf/", f"ux_moveit_config)/{srdf_folder}/") for k, v in files.items()
    }
    build_file_tree(root, files)
    return root / CONFIG


def test_an_srdf_chosen_by_name_is_no_macro_library_and_the_urdfs_robot_comes_first(tmp_path):
    """srdfdom wants the SRDF's `<robot name>` to be the URDF's (srdfdom src/model.cpp initXml);
    a `.srdf.xacro` another one includes is loaded only through it (xacro:include)."""
    source = _package(tmp_path)
    assert read_package(source, package_paths=[tmp_path]).srdf_path == "srdf/dual_ux.srdf.xacro"
    urdf = tmp_path / "ux_description/urdf/ux.urdf.xacro"
    pkg = read_package(source, urdf=urdf, package_paths=[tmp_path])
    assert (pkg.srdf_path, pkg.srdf.robot_name) == ("srdf/ux.srdf.xacro", "UX")
    found = validate(source, urdf=urdf, package_paths=[tmp_path], plan=False, matrix_trials=0).findings
    assert [f.rule for f in found if f.is_error] == []


def test_an_srdf_in_a_config_sub_folder_is_found(tmp_path):
    """A launch computing `config/srdf/<model>.srdf.xacro` from its args at run time: the package
    has an SRDF, so no srdf.missing error."""
    source = _package(tmp_path, "config/srdf")
    urdf = tmp_path / "ux_description/urdf/ux.urdf.xacro"
    assert read_package(source, urdf=urdf, package_paths=[tmp_path]).srdf_path == "config/srdf/ux.srdf.xacro"
    found = validate(source, urdf=urdf, package_paths=[tmp_path], plan=False, matrix_trials=0).findings
    assert [f.rule for f in found if f.is_error] == []


KINEMATICS = """/**:
  ros__parameters:
    arm:
      kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin
      kinematics_solver_timeout: 0.005
"""


def test_a_kinematics_parameter_file_a_launch_hands_to_move_group(tmp_path):
    """No MoveItConfigsBuilder wraps it: `/**: ros__parameters: arm: ...` gives move_group
    `arm.kinematics_solver`, which Humble reads (kinematics_plugin_loader.cpp l.308-319); the
    wrapper is no group."""
    source = _package(tmp_path)
    (source / "config").mkdir(exist_ok=True)
    (source / "config/kinematics.yaml").write_text(KINEMATICS)
    urdf = tmp_path / "ux_description/urdf/ux.urdf.xacro"
    pkg = read_package(source, urdf=urdf, package_paths=[tmp_path])
    assert [g.group for g in pkg.kinematics.groups] == ["arm"]
    found = validate(source, urdf=urdf, package_paths=[tmp_path], plan=False, matrix_trials=0).findings
    assert [f for f in found if f.rule.startswith("kinematics.")] == []


ADJACENT = "".join(
    f'<disable_collisions link1="{a}" link2="{b}" reason="Adjacent"/>'
    for a, b in [("base_link", "link1")] + [(f"link{i}", f"link{i + 1}") for i in range(1, 6)]
)


def test_an_srdf_chosen_by_name_is_the_one_made_for_the_robot_loaded(tmp_path):
    """One SRDF per model in config/srdf/, the launch picking one at run time: the robot with its
    arm is checked against the SRDF whose matrix names the arm's links, not the first by name (a
    base-only model's, which names none: every arm pair would be a missing disable)."""
    config = tmp_path / CONFIG
    base_only = '<?xml version="1.0"?>\n<robot name="UX"><virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/></robot>\n'
    build_file_tree(
        tmp_path,
        {
            "ux_description/package.xml": AMENT.format(name="ux_description"),
            "ux_description/urdf/ux.urdf": _arm_urdf("UX", 6, gripper=False),
            f"{CONFIG}/package.xml": AMENT.format(name=CONFIG),
            f"{CONFIG}/launch/move_group.launch.py": LAUNCH_PY,
            f"{CONFIG}/config/srdf/ux_a-base.srdf": base_only,
            f"{CONFIG}/config/srdf/ux_b-arm.srdf": _srdf("UX", 6, gripper=False).replace(
                "</robot>", f"{ADJACENT}</robot>"
            ),
        },
    )
    urdf = tmp_path / "ux_description/urdf/ux.urdf"
    done = validate(config, urdf=urdf, package_paths=[tmp_path], plan=False, matrix_trials=0)
    assert done.srdf == "config/srdf/ux_b-arm.srdf"
    assert "ux_a-base.srdf fits it worse" in done.srdf_origin
    assert [f for f in done.findings if f.file.endswith("ux_a-base.srdf")] == []

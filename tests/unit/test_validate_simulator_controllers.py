"""A robot description's ros2_control simulator plugin (`<gazebo><plugin
filename="libgazebo_ros2_control.so"><parameters>FILE</parameters>`, or gz_ros2_control's
`gz_ros2_control-system`, Humble's `ign_ros2_control-system`) hands its controller manager FILE
as a --params-file (ros-controls/gazebo_ros2_control gazebo_ros2_control_plugin.cpp l.269-277;
gz_ros2_control gz_ros2_control_plugin.cpp l.281-300): in simulation, FILE's controllers are the
ones that run. IFRA-Cranfield's panda keeps them there (panda_ros2_gazebo/config/
panda_controller.yaml) and validate called MoveIt's controllers missing from the package's
ros2_controllers.yaml (controller.driver-missing). The package's own file still comes first."""

from __future__ import annotations

import shutil

import pytest

from tests.validate_helpers import copy_package, panda, replace_text, run

R2C = "config/ros2_controllers.yaml"
PLUGIN = """<gazebo><plugin filename="{filename}" name="sim_control">
  <parameters>$(find panda_moveit_config)/config/sim_controllers.yaml</parameters>
</plugin></gazebo>
</robot>"""


def test_the_parameters_of_ros2_control_simulator_plugins_only():
    from marm_setup.robot import simulator_parameter_files

    xml = """<robot name="r">
      <gazebo><plugin filename="libgazebo_ros2_control.so"><parameters>/a.yaml</parameters>
        <parameters>/b.yaml</parameters></plugin></gazebo>
      <gazebo><plugin filename="gz_ros2_control-system"><parameters> /c.yaml </parameters></plugin></gazebo>
      <gazebo><plugin filename="libign_ros2_control-system.so"><parameters>/d.yaml</parameters></plugin></gazebo>
      <gazebo><plugin filename="libgazebo_ros_p3d.so"><parameters>/e.yaml</parameters></plugin></gazebo>
    </robot>"""
    assert simulator_parameter_files(xml) == ("/a.yaml", "/b.yaml", "/c.yaml", "/d.yaml")
    assert simulator_parameter_files("<robot") == ()


@pytest.mark.parametrize(
    ("filename", "missing"),
    [
        ("libgazebo_ros2_control.so", False),
        ("gz_ros2_control-system", False),
        ("libign_ros2_control-system.so", False),
        ("libgazebo_ros_p3d.so", True),  # not a ros2_control plugin: its parameters are not controllers
    ],
)
def test_controllers_the_simulators_file_runs_are_not_missing(tmp_path, filename, missing):
    good = panda("ros2")
    pkg = copy_package(good, tmp_path)
    shutil.copyfile(pkg / R2C, pkg / "config/sim_controllers.yaml")
    replace_text(pkg, R2C, "    panda_arm_controller:", "    arm_controller:")  # the real hardware's name
    replace_text(pkg, "config/panda.urdf.xacro", "</robot>", PLUGIN.format(filename=filename))
    found = [
        (f.rule, f.severity, f.element) for f in run(pkg, good) if f.rule.startswith("controller.driver")
    ]
    missed = ("controller.driver-missing", "error", "moveit_simple_controller_manager.panda_arm_controller")
    expected = [missed] if missing else []
    assert found == expected


def test_a_controller_neither_file_has_is_missing_and_the_message_names_both(tmp_path):
    good = panda("ros2")
    pkg = copy_package(good, tmp_path)
    shutil.copyfile(pkg / R2C, pkg / "config/sim_controllers.yaml")
    replace_text(pkg, R2C, "    panda_arm_controller:", "    arm_controller:")
    replace_text(pkg, "config/sim_controllers.yaml", "    panda_arm_controller:", "    sim_arm:")
    replace_text(
        pkg, "config/panda.urdf.xacro", "</robot>", PLUGIN.format(filename="libgazebo_ros2_control.so")
    )
    found = [f for f in run(pkg, good) if f.rule == "controller.driver-missing"]
    assert [(f.severity, f.element) for f in found] == [
        ("error", "moveit_simple_controller_manager.panda_arm_controller")
    ]
    assert "nor in config/sim_controllers.yaml, which the simulator plugin loads" in found[0].message

"""YAML read as roslaunch reads it: rosparam's angle tags and `subst_value` substitutions.

Ground truth: the real `roslaunch --dump-params` (Debian's python3-roslaunch) when installed;
package cases edit a copy of the real MoveIt 1 panda package in tmp_path.
"""

from __future__ import annotations

import math
import shutil
import subprocess

import pytest

from marm_setup.package.files import located_text
from marm_setup.package.substitution import Scope, SubstitutionError, substitute
from tests.validate_helpers import copy_package, panda, replace_text, run

TAGGED = """joint_limits:
  j1:
    max_velocity: !degrees 180
    max_position: deg(90)
    min_position: rad(-pi/2)
    max_acceleration: !radians 2*pi
    scale: $(arg scale)
    path: $(find pkg_a)/x
"""


def load_ros_yaml(text: str):
    return located_text(text, "config/x.yaml").data


def test_angle_tags_and_scalars_become_radians():
    data = load_ros_yaml(TAGGED)["joint_limits"]["j1"]
    assert data["max_velocity"] == pytest.approx(math.pi)
    assert data["max_position"] == pytest.approx(math.pi / 2)
    assert data["min_position"] == pytest.approx(-math.pi / 2)
    assert data["max_acceleration"] == pytest.approx(2 * math.pi)
    assert data["scale"] == "$(arg scale)"  # without subst_value it stays text


def test_substitutions_use_the_launch_args():
    text = substitute(TAGGED, Scope({"scale": "3"}, lambda name: "/p/pkg_a" if name == "pkg_a" else None))
    data = load_ros_yaml(text)["joint_limits"]["j1"]
    assert (data["scale"], data["path"]) == (3, "/p/pkg_a/x")
    assert substitute("$(eval 2 * arg('scale'))", Scope({"scale": "3"})) == "6"
    with pytest.raises(SubstitutionError, match="whole attribute"):  # as roslaunch refuses it
        substitute("v: $(eval 2 * arg('scale'))", Scope({"scale": "3"}))
    with pytest.raises(SubstitutionError, match="nope"):
        substitute("v: $(arg nope)", Scope())


def test_the_same_values_as_the_real_roslaunch(tmp_path):
    if shutil.which("roslaunch") is None:
        pytest.skip("roslaunch (python3-roslaunch) not installed")
    pkg = tmp_path / "pkg_a"
    (pkg / "config").mkdir(parents=True)
    (pkg / "launch").mkdir()
    (pkg / "package.xml").write_text(
        '<package format="2"><name>pkg_a</name><version>0.0.0</version><description>x</description>'
        '<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>'
    )
    (pkg / "config" / "lim.yaml").write_text(TAGGED)
    (pkg / "launch" / "a.launch").write_text(
        '<launch><arg name="scale" default="3"/><rosparam subst_value="true" '
        'file="$(find pkg_a)/config/lim.yaml" ns="p"/></launch>'
    )
    dump = subprocess.run(
        ["roslaunch", "--dump-params", str(pkg / "launch" / "a.launch")],
        capture_output=True,
        text=True,
        env={"ROS_PACKAGE_PATH": str(tmp_path), "PATH": "/usr/bin:/bin", "HOME": str(tmp_path)},
        check=True,
    ).stdout
    theirs = dict(line.split(": ", 1) for line in dump.splitlines() if line.startswith("/p/"))
    ours = load_ros_yaml(substitute(TAGGED, Scope({"scale": "3"}, lambda _: str(pkg))))["joint_limits"]["j1"]
    for key, value in ours.items():
        assert str(value) == theirs[f"/p/joint_limits/j1/{key}"], key


LIMITS = "config/joint_limits.yaml"
CONTEXT = "launch/planning_context.launch"


def test_degrees_in_joint_limits_are_read_and_checked(tmp_path):
    """A tagged limit was 'malformed YAML' and every limits rule skipped; now it is read, and a
    limit above the URDF's (deg(200) = 3.49 > 2.3925) is found."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, LIMITS, "max_velocity: 2.1750", "max_velocity: !degrees 124.6")
    replace_text(pkg, LIMITS, "max_velocity: 2.1750", "max_velocity: deg(200)")
    found = [(f.rule, f.element) for f in run(pkg, good, matrix_trials=0) if f.file == LIMITS]
    assert found == [("limits.above-urdf", "joint_limits.panda_joint2.max_velocity")]


def test_subst_value_yaml_takes_the_launch_args(tmp_path):
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, LIMITS, "max_velocity: 2.1750", "max_velocity: $(arg joint1_velocity)")
    replace_text(
        pkg,
        CONTEXT,
        '<rosparam command="load" file="$(find moveit_resources_panda_moveit_config)/config/joint_limits.yaml"/>',
        '<rosparam command="load" subst_value="true" file="$(find moveit_resources_panda_moveit_config)/config/joint_limits.yaml"/>',
    )
    replace_text(
        pkg,
        CONTEXT,
        '<arg name="robot_description" default="robot_description"/>',
        '<arg name="robot_description" default="robot_description"/>\n  <arg name="joint1_velocity" default="2.1750"/>',
    )
    assert [f for f in run(pkg, good, matrix_trials=0) if f.file == LIMITS] == []
    replace_text(pkg, CONTEXT, 'default="2.1750"', 'default="9.0"')
    found = [(f.rule, f.element) for f in run(pkg, good, matrix_trials=0) if f.file == LIMITS]
    assert found == [("limits.above-urdf", "joint_limits.panda_joint1.max_velocity")]


def test_args_passed_with_pass_all_args_are_defined(tmp_path):
    """trajectory_execution.launch.xml includes `$(dirname)/$(arg moveit_controller_manager)_...`
    with pass_all_args: the included file may use the includer's args without declaring them
    (roslaunch xmlloader.py `_include_tag`)."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    fake = "launch/fake_moveit_controller_manager.launch.xml"
    replace_text(
        pkg,
        fake,
        '<arg name="fake_execution_type" default="interpolate" />',
        '<param name="execution_type" value="$(arg fake_execution_type)"/>',
    )
    assert [f for f in run(pkg, good, matrix_trials=0) if f.rule == "launch.undefined-arg"] == []
    # the same use in a file nobody includes that way is still undefined
    replace_text(
        pkg, "launch/demo.launch", "</launch>", '<param name="x" value="$(arg fake_type)"/></launch>'
    )
    found = [f.file for f in run(pkg, good, matrix_trials=0) if f.rule == "launch.undefined-arg"]
    assert found == ["launch/demo.launch"]


def test_subst_value_args_passed_by_the_including_launch_files(tmp_path):
    """fake_controllers.yaml's $(arg fake_execution_type) comes from whoever includes the file
    that loads it (here through pass_all_args) when that file declares the arg without a default."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    fake = "launch/fake_moveit_controller_manager.launch.xml"
    replace_text(
        pkg,
        fake,
        '<arg name="fake_execution_type" default="interpolate" />',
        '<arg name="fake_execution_type"/>',
    )
    found = [(f.rule, f.file) for f in run(pkg, good, matrix_trials=0) if f.rule.startswith("yaml.")]
    assert found == []

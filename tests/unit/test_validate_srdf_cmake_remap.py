"""A `.srdf.xacro` no launch file of the package names, which its CMakeLists.txt expands at
build time with `xacro_add_files(<file> REMAP name:=value ... INSTALL DESTINATION dir)`: the
build runs `xacro -o <output> <input> ${_XACRO_REMAP}` (ros/xacro ros2 cmake/xacro-extras.cmake
`xacro_add_xacro_file`) and installs the output, the SRDF a launch then loads. So an arg the
xacro declares no default for is given: validate expands it with a literal REMAP value, and a
value only CMake knows (`robot_name:=${model}` in a foreach, KUKA's kuka_kr_moveit_config) makes
it a srdf.runtime-arg warning, not a srdf.parse error. Without such a call the error stays."""

from __future__ import annotations

import pytest

from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

CMAKE = """cmake_minimum_required(VERSION 3.5)
project(bot_moveit_config)
find_package(xacro REQUIRED)
# xacro_add_files(srdf/bot.srdf.xacro REMAP robot_name:=commented_out)
xacro_add_files(TARGET bot srdf/bot.srdf.xacro
  REMAP robot_name:=VALUE OUTPUT bot.srdf INSTALL DESTINATION urdf)
ament_package()
"""


def srdf_rules(tmp_path, cmake: str | None) -> list[tuple[str, str]]:
    source, paths = PACKAGES["python_launch"](tmp_path)
    srdf = (source / "config/bot.srdf").read_text()
    (source / "config/bot.srdf").unlink()
    (source / "launch/move_group.launch.py").unlink()
    (source / "srdf").mkdir()
    head, rest = srdf.split("<robot", 1)
    rest = rest.split(">", 1)[1]
    xacro = f'{head}<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="$(arg robot_name)">{rest}'
    (source / "srdf/bot.srdf.xacro").write_text(xacro)
    if cmake is not None:
        (source / "CMakeLists.txt").write_text(cmake)
    found = validate(source, package_paths=paths, plan=False, matrix_trials=0).findings
    return sorted(
        {(f.rule, str(f.severity)) for f in found if f.rule.startswith(("srdf.parse", "srdf.runtime"))}
    )


def test_a_literal_remap_of_the_build_expands_the_srdf(tmp_path):
    assert srdf_rules(tmp_path, CMAKE.replace("VALUE", "bot")) == []


def test_a_remap_only_cmake_knows_is_a_runtime_arg(tmp_path):
    assert srdf_rules(tmp_path, CMAKE.replace("VALUE", "${model}")) == [("srdf.runtime-arg", "warning")]


@pytest.mark.parametrize("cmake", [None, CMAKE.replace("srdf/bot.srdf.xacro\n", "srdf/other.srdf.xacro\n")])
def test_without_the_build_giving_it_the_undefined_arg_is_an_error(tmp_path, cmake):
    assert srdf_rules(tmp_path, cmake) == [("srdf.parse", "error")]

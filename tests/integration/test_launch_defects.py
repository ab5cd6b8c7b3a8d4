"""`validate` reports each defect of issue 21 on a package that has it, statically (no ROS) and
through the real ROS 2 frontend (the harness's environment as the user's ROS 2: validate's
MARM_SETUP_ROS2_PYTHON). Each defective package is a generated package with the defect put back:
1. `$(command 'xacro ...')` without `warn` around a description xacro warns about;
2. an empty map in a parameter file (`robot_description_kinematics: {}`);
3. a URDF in no ROS package reached through `$(find pkg)/../..`;
4. a demo whose robot description keeps the vendor's real hardware (no replacing, no switch).
The ROS 1 side: real `roslaunch --dump-params` through MARM_SETUP_ROSLAUNCH.
"""

from __future__ import annotations

import os
import re
import shutil

import pytest

from marm_setup.validate.runner import validate
from tests.helpers import write_xacro_shim
from tests.ros2_harness import harness_python


def launch_files(pkg) -> set[str]:
    """Every XML launch file of a package (each runs the robot description)."""
    return {f"launch/{p.name}" for p in (pkg / "launch").glob("*.launch.xml")}


def _rules(validation, rule: str) -> dict[str, list[str]]:
    """{file: [element, ...]} of the errors of one rule."""
    out: dict[str, list[str]] = {}
    for f in validation.findings:
        if f.rule == rule and f.is_error:
            out.setdefault(f.file, []).append(f.element)
    return out


@pytest.fixture
def no_ros():
    """No ROS (tests/conftest.py's no_sourced_ros already unsets it): the static rules only."""


@pytest.fixture
def real_ros2(monkeypatch):
    """validate's ROS 2 consumer is the harness's Humble environment (launch 1.0, rcl)."""
    monkeypatch.setenv("MARM_SETUP_ROS2_PYTHON", str(harness_python("humble")))


def _replace(path, old: str, new: str, count: int = 0) -> None:
    text = path.read_text()
    assert old in text, (old, path)
    path.write_text(text.replace(old, new, count or -1))


def stderr_defect(ros2_packages):
    pkg = ros2_packages.copy("marm", "humble", "stderr")
    for launch in (pkg / "launch").glob("*.launch.xml"):  # demo, move_group, servo
        _replace(launch, "' warn)", "')")
    return pkg


def empty_map_defect(ros2_packages):
    pkg = ros2_packages.copy("marm", "humble", "empty_map")
    moveit = pkg / "config" / "moveit.yaml"
    text = re.sub(
        r"    robot_description_kinematics:\n(      .*\n|        .*\n)+",
        "    robot_description_kinematics: {}\n",
        moveit.read_text(),
    )
    moveit.write_text(text)
    return pkg


def outside_defect(ros2_packages):
    """The synthetic dual-arm table (a URDF in no ROS package) next to the package, as a
    workspace has it, and included as it was before: `$(find pkg)/../dual_arm_table.urdf`."""
    from tests.conftest import FIXTURES

    pkg = ros2_packages.copy("synthetic:dual_arm_table", "humble", "outside")
    shutil.copy(FIXTURES / "synthetic" / "dual_arm_table.urdf", pkg.parent)
    _replace(
        pkg / "config" / "dual_arm_table.urdf.xacro",
        "/description/dual_arm_table.urdf",
        "/../dual_arm_table.urdf",
    )
    shutil.rmtree(pkg / "description")
    return pkg


def real_hardware_defect(ros2_packages, style: str):
    """A vendor-style package with its mock handling taken out: the launch files run plain
    xacro (replace mode), or neither the launch files (their switch arg, which follows
    use_mock_hardware) nor the wrapper set the vendor's switch (switch mode)."""
    pkg = ros2_packages.copy(f"vendor:{style}", "humble", f"real_{style}")
    script = r"python3 \$\(find-pkg-share \w+\)/scripts/with_mock_hardware\.py "
    for launch in (pkg / "launch").glob("*.xml"):
        text = re.sub(script, "xacro ", launch.read_text())
        for switch in re.findall(r'<arg name="(\w+)" default="\$\(var use_mock_hardware\)"', text):
            text = text.replace(f" {switch}:=$(var {switch})", "")
        launch.write_text(text)
    for wrapper in (pkg / "config").glob("*.urdf.xacro"):
        wrapper.write_text(
            re.sub(
                r'  <xacro:arg name="\w+" default="\$\(arg use_mock_hardware\)"/>\n', "", wrapper.read_text()
            )
        )
    return pkg


# -- 1. stderr ----------------------------------------------------------------------------------


def test_stderr_static(ros2_packages, no_ros):
    pkg = stderr_defect(ros2_packages)
    found = _rules(validate(pkg, plan=False), "launch.command-stderr")
    assert set(found) == launch_files(pkg) >= {"launch/demo.launch.xml", "launch/move_group.launch.xml"}
    assert found["launch/demo.launch.xml"][0].endswith("let[robot_description]")


def test_stderr_real(ros2_packages, real_ros2):
    pkg = stderr_defect(ros2_packages)
    result = validate(pkg, plan=False)
    found = _rules(result, "ros2.launch")
    assert set(found) == launch_files(pkg)
    assert "ROS 2 launch 1.0" in result.launched_by
    messages = [f.message for f in result.findings if f.rule == "ros2.launch"]
    assert all("executed command showed stderr output" in m for m in messages)


# -- 2. empty map ---------------------------------------------------------------------------------


def test_empty_map_static(ros2_packages, no_ros):
    found = _rules(validate(empty_map_defect(ros2_packages), plan=False), "params.empty-value")
    assert found == {"config/moveit.yaml": ["/**.ros__parameters.robot_description_kinematics"]}


def test_empty_map_real(ros2_packages, real_ros2):
    result = validate(empty_map_defect(ros2_packages), plan=False)
    found = _rules(result, "ros2.params")
    assert "config/moveit.yaml" in found  # the parameter file itself
    assert "node[move_group]" in found["launch/move_group.launch.xml"]
    assert {"node[move_group]", "node[rviz2]"} <= set(found["launch/demo.launch.xml"])


# -- 3. outside the package --------------------------------------------------------------------


def test_outside_static(ros2_packages, no_ros):
    found = _rules(validate(outside_defect(ros2_packages), plan=False), "launch.leaves-package")
    assert list(found) == ["config/dual_arm_table.urdf.xacro"]


def test_outside_real(ros2_packages, real_ros2):
    pkg = outside_defect(ros2_packages)
    found = _rules(validate(pkg, plan=False), "ros2.launch")
    assert set(found) == launch_files(pkg)


# -- 4. real hardware in the demo ----------------------------------------------------------------


@pytest.mark.parametrize("style", ["plain_urdf_style", "kinova_style"])
def test_real_hardware_static(ros2_packages, no_ros, style):
    result = validate(real_hardware_defect(ros2_packages, style), plan=False)
    found = _rules(result, "demo.real-hardware")
    assert list(found) == ["launch/demo.launch.xml"]
    vendor = ros2_packages.vendor(style)
    messages = " ".join(f.message for f in result.findings if f.rule == "demo.real-hardware")
    assert all(plugin in messages for plugin in vendor.real_plugins)


@pytest.mark.parametrize("style", ["plain_urdf_style", "kinova_style"])
def test_real_hardware_real(ros2_packages, real_ros2, style):
    result = validate(real_hardware_defect(ros2_packages, style), plan=False)
    messages = [
        f.message for f in result.findings if f.rule == "demo.real-hardware" and "real launcher" in f.message
    ]
    vendor = ros2_packages.vendor(style)
    assert messages and all(any(p in m for p in vendor.real_plugins) for m in messages)


# -- the packages marm-setup writes: clean both ways ------------------------------------------------


@pytest.mark.parametrize(
    "key", ["marm", "synthetic:dual_arm_table", "vendor:plain_urdf_style", "vendor:ur_style"]
)
def test_generated_packages_are_clean_static_and_real(ros2_packages, monkeypatch, key):
    generated = ros2_packages.get(key, "humble")
    rules = ("launch.", "params.", "demo.", "ros2.")
    static = validate(generated.out, plan=False, package_paths=generated.roots)
    assert [f for f in static.findings if f.rule.startswith(rules)] == []
    assert static.launched_by.startswith("static rules only")
    monkeypatch.setenv("MARM_SETUP_ROS2_PYTHON", str(harness_python("jazzy")))
    real = validate(generated.out, plan=False, package_paths=generated.roots)
    assert [f for f in real.findings if f.rule.startswith(rules)] == []
    assert real.launched_by.startswith("ROS 2 launch 3.")


# -- ROS 1: real roslaunch -------------------------------------------------------------------------


@pytest.fixture
def real_ros1(monkeypatch, tmp_path):
    """validate's ROS 1 consumer: Debian's roslaunch, with our real-xacro expansion as `xacro`."""
    roslaunch = shutil.which("roslaunch")
    if roslaunch is None:
        pytest.skip("roslaunch not on PATH")
    shims = write_xacro_shim(tmp_path / "bin")
    monkeypatch.setenv("PATH", f"{shims}{os.pathsep}{os.environ['PATH']}")
    monkeypatch.setenv("MARM_SETUP_ROSLAUNCH", roslaunch)


def test_ros1_package_through_real_roslaunch(tmp_path, monkeypatch, real_ros1):
    from typer.testing import CliRunner

    from marm_setup.cli.app import app
    from tests.conftest import FIXTURES

    out = tmp_path / "marm_moveit_config"
    urdf = FIXTURES / "marm" / "urdf" / "marm.urdf.xacro"
    spec = FIXTURES / "marm" / "marm_setup.yaml"
    made = CliRunner().invoke(
        app, ["init", str(urdf), "--out", str(out), "--setup", str(spec), "--trials", "200"]
    )
    assert made.exit_code == 0, made.output
    clean = validate(out, plan=False)
    assert "roslaunch --dump-params" in clean.launched_by
    assert [f for f in clean.findings if f.rule == "ros1.launch"] == []
    _replace(
        out / "launch" / "demo.launch",
        "</launch>",
        '  <include file="$(find no_such_package)/launch/x.launch"/>\n</launch>',
    )
    (tmp_path / "ros").mkdir()  # a ROS sourced: the package it lacks is the launch's fault
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ros"))
    broken = validate(out, plan=False)
    found = _rules(broken, "ros1.launch")
    assert list(found) == ["launch/demo.launch"]
    assert "no_such_package" in next(f.message for f in broken.findings if f.rule == "ros1.launch")


def test_ros1_consumer_finds_the_xacro_marm_setup_runs(tmp_path, monkeypatch):
    """Debian's roslaunch has no xacro of its own: the launch files' `command="xacro ..."` runs
    marm-setup's own xacro command (robot/xacro_command.py, last on the child's PATH)."""
    from typer.testing import CliRunner

    from marm_setup.cli.app import app
    from tests.conftest import FIXTURES

    roslaunch = shutil.which("roslaunch")
    if roslaunch is None:
        pytest.skip("roslaunch not on PATH")
    out = tmp_path / "marm_moveit_config"
    urdf = FIXTURES / "marm" / "urdf" / "marm.urdf.xacro"
    made = CliRunner().invoke(
        app, ["init", str(urdf), "--out", str(out), "--target", "ros1", "--trials", "200"]
    )
    assert made.exit_code == 0, made.output
    monkeypatch.setenv("PATH", os.pathsep.join(("/usr/bin", "/bin")))
    monkeypatch.setenv("MARM_SETUP_ROSLAUNCH", roslaunch)
    checked = validate(out, plan=False)
    assert "roslaunch --dump-params" in checked.launched_by
    assert [f.message for f in checked.findings if f.rule == "ros1.launch"] == []


@pytest.mark.parametrize(
    ("package", "paths"),
    [
        ("fanuc/moveit_cfgs/fanuc_cr7ia_moveit_config", ["fanuc"]),  # command="$(find xacro)/xacro ..."
        ("universal_robot/ur5e_moveit_config", ["universal_robot"]),  # xacro with $(find ur_description)
    ],
)
def test_vendor_ros1_packages_through_real_roslaunch_without_a_ros_xacro(monkeypatch, package, paths):
    """Published packages call xacro as `$(find xacro)/xacro` or `xacro` and include files with
    `$(find pkg)`: marm-setup's fallback xacro package answers both (a ROS xacro would win)."""
    from tests.conftest import realworld2

    roslaunch = shutil.which("roslaunch")
    if roslaunch is None:
        pytest.skip("roslaunch not on PATH")
    monkeypatch.setenv("PATH", os.pathsep.join(("/usr/bin", "/bin")))
    monkeypatch.setenv("MARM_SETUP_ROSLAUNCH", roslaunch)
    checked = validate(realworld2(package), package_paths=[realworld2(p) for p in paths], plan=False)
    assert "roslaunch --dump-params" in checked.launched_by
    assert [f.message for f in checked.findings if f.rule == "ros1.launch"] == []

"""A package's files are read only inside it and the folders the user named (issue 23): a
symlink leaving the package, a `..` or an absolute path taken from marm_setup.yaml or
`.setup_assistant` is a `package.outside` warning naming the path, never read and never quoted;
a package whose folder holds `$(eval ...)` runs nothing through `$(dirname)`."""

from __future__ import annotations

import shutil

import pytest

from marm_setup.errors import InputError
from tests.conftest import FIXTURES
from tests.unit.test_eval_escapes import ESCAPE, LOOKALIKE
from tests.validate_helpers import generate_marm, replace_text, validate_package

SECRET = "AWS_SECRET=hunter2-do-not-leak"


@pytest.fixture(scope="module")
def marm_ros1(tmp_path_factory):
    return generate_marm(tmp_path_factory.mktemp("marm"), "ros1")


@pytest.fixture
def pkg(marm_ros1, tmp_path):
    """A copy of the marm ROS 1 package, and a secret folder beside it."""
    secret = tmp_path / "secret"
    secret.mkdir()
    (secret / "creds").write_text(f"{SECRET}\nline: 2\n", encoding="utf-8")
    (secret / "x.srdf").write_text('<robot name="x"><group name="SECRETGROUP"/></robot>\n', encoding="utf-8")
    out = tmp_path / "marm_ros1"  # the depth of the original: its relative URDF path holds
    shutil.copytree(marm_ros1, out)
    return out


def _outside(findings):
    return [(f.file, f.element) for f in findings if f.rule == "package.outside"]


def _assert_never_read(findings):
    text = "\n".join(f"{f.file} {f.element} {f.message} {f.hint}" for f in findings)
    assert "hunter2" not in text and "SECRETGROUP" not in text


def test_a_symlinked_kinematics_yaml_is_not_read(pkg):
    kinematics = pkg / "config" / "kinematics.yaml"
    kinematics.unlink()
    kinematics.symlink_to(pkg.parent / "secret" / "creds")
    findings = validate_package(pkg, plan=False)
    assert _outside(findings) == [("config/kinematics.yaml", "")]
    _assert_never_read(findings)
    assert not [f for f in findings if f.file == "config/kinematics.yaml" and f.rule != "package.outside"]


def test_a_symlink_into_a_folder_the_user_named_is_read(pkg):
    kinematics = pkg / "config" / "kinematics.yaml"
    outside = pkg.parent / "secret" / "kinematics.yaml"
    shutil.move(kinematics, outside)
    kinematics.symlink_to(outside)
    findings = validate_package(pkg, plan=False, package_paths=[outside.parent])
    assert _outside(findings) == []


def test_robot_name_with_dotdot_reads_no_srdf_outside(pkg):
    replace_text(pkg, "marm_setup.yaml", "robot_name: marm", "robot_name: ../../secret/x")
    findings = validate_package(pkg, plan=False)
    assert ("marm_setup.yaml", "robot_name") in _outside(findings)
    _assert_never_read(findings)


def test_an_absolute_setup_assistant_srdf_is_refused(pkg):
    (pkg / "marm_setup.yaml").unlink()
    replace_text(
        pkg,
        ".setup_assistant",
        "relative_path: config/marm.srdf",
        f"relative_path: {pkg.parent}/secret/x.srdf",
    )
    findings = validate_package(pkg, plan=False, package_paths=[FIXTURES])
    assert (".setup_assistant", "SRDF.relative_path") in _outside(findings)
    _assert_never_read(findings)


def test_a_symlinked_launch_file_is_not_parsed(pkg):
    (pkg / "launch" / "extra.launch").symlink_to(pkg.parent / "secret" / "creds")
    findings = validate_package(pkg, plan=False)
    assert ("launch/extra.launch", "") in _outside(findings)
    _assert_never_read(findings)


def test_a_folder_named_eval_runs_nothing_through_dirname(marm_ros1, tmp_path, monkeypatch):
    """The audit's: a package in a folder whose path holds `$(eval ...)` ran it via `$(dirname)`."""
    monkeypatch.chdir(tmp_path)
    folder = tmp_path / ("$(eval " + ESCAPE.format(u=LOOKALIKE, marker="ran") + ")")
    pkg = folder / "marm_moveit_config"
    shutil.copytree(marm_ros1, pkg)
    replace_text(
        pkg, "launch/move_group.launch", "<launch>", '<launch>\n  <arg name="here" value="$(dirname)"/>'
    )
    validate_package(pkg, plan=False)
    assert not (tmp_path / "ran").exists()


def test_names_from_a_package_reach_findings_printable_and_bounded(pkg):
    """A group name in kinematics.yaml holding a terminal escape, and a 5,000-character solver."""
    name = "evil\\e[2J" + "x" * 1000
    solver = "evil_solver/" + "y" * 5000
    with open(pkg / "config" / "kinematics.yaml", "a", encoding="utf-8") as out:
        out.write(f'"{name}":\n  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n')
        out.write(f"arm_{solver[:4]}:\n  kinematics_solver: {solver}\n")
    findings = validate_package(pkg, plan=False)
    assert [f for f in findings if "evil" in f.element + f.message]
    for f in findings:
        for text in (f.file, f.element, f.message, f.hint):
            assert text.isprintable() and len(text) <= 2000


@pytest.fixture(scope="module")
def marm_ros2(tmp_path_factory):
    return generate_marm(tmp_path_factory.mktemp("marm2"), "ros2")


def test_a_symlinked_description_wrapper_is_not_run(marm_ros2, tmp_path):
    """MoveItConfigsBuilder's `config/<robot>.urdf.xacro` leading outside is not taken."""
    pkg = tmp_path / "marm_ros2"
    shutil.copytree(marm_ros2, pkg)
    (pkg / "marm_setup.yaml").unlink()
    outside = tmp_path / "outside.urdf.xacro"
    outside.write_text(
        '<robot name="marm" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:include filename="$(find no_such_package_ran)/x.xacro"/></robot>\n'
    )
    wrapper = pkg / "config" / "marm.urdf.xacro"
    wrapper.unlink()
    wrapper.symlink_to(outside)
    findings = validate_package(pkg, plan=False, package_paths=[FIXTURES])
    assert ("config/marm.urdf.xacro", "") in _outside(findings)
    assert not [f for f in findings if "no_such_package_ran" in f.message]


def test_a_setup_assistant_urdf_path_leaving_its_package_is_one_line(pkg):
    """(.setup_assistant is read only where no launch file names the robot description.)"""
    (pkg / "marm_setup.yaml").unlink()
    replace_text(pkg, "launch/planning_context.launch", "command=\"xacro '$(find marm_description)", 'x="')
    replace_text(
        pkg, ".setup_assistant", "relative_path: urdf/marm.urdf.xacro", "relative_path: ../../x.urdf"
    )
    with pytest.raises(InputError, match=r"URDF.relative_path: path '../../x.urdf' leaves the package"):
        validate_package(pkg, plan=False, package_paths=[FIXTURES])


def test_an_error_line_is_bounded():
    from marm_setup.cli.common import one_line

    assert len(one_line("name " + "\x1b" * 10**6)) <= 4000

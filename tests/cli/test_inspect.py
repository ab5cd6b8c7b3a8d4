"""`marm-setup inspect`, and the bad-input contract shared by every robot-loading command."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import FIXTURES, MARM_URDF, realworld
from tests.helpers import TWO_BOXES, build_file_tree, urdf

runner = CliRunner()


def test_inspect_prints_the_marm_tree():
    result = runner.invoke(app, ["inspect", str(MARM_URDF)])
    assert result.exit_code == 0, result.output
    assert "finger_joint2 (prismatic [-0.06, 0] vel 1 mimics finger_joint1 x-1)" in result.stdout
    assert "grasping_frame [no collision geometry]" in result.stdout
    assert "11 links (10 with collision geometry), 10 joints (7 active, 1 mimic)" in result.stdout


def test_inspect_json():
    result = runner.invoke(app, ["inspect", str(MARM_URDF), "--format", "json"])
    data = json.loads(result.stdout)
    assert data["root"] == "base_link"
    assert data["active_joints"][-1] == "finger_joint1"


def test_inspect_realworld_panda():
    root = realworld("ros1")
    xacro = root / "panda_description/urdf/panda_arm_hand.urdf.xacro"
    result = runner.invoke(app, ["inspect", str(xacro), "--package-path", str(root)])
    assert result.exit_code == 0, result.output
    assert "panda_finger_joint2" in result.stdout
    result = runner.invoke(app, ["inspect", str(realworld("ros2", "panda_description/urdf/panda.urdf"))])
    assert result.exit_code == 0, result.output


MESH_LINK = '<link name="m"><collision><geometry><mesh filename="{uri}"/></geometry></collision></link>'
FIXED_TO_A = '<joint name="jm" type="fixed"><parent link="a"/><child link="m"/></joint>'
BAD_INPUTS = {
    "missing file": ({}, "nothere.urdf", "nothere.urdf: file not found"),
    "malformed xml": (
        {"r.urdf": "<robot name='x'>\n<link name='a'>\n</robot>\n"},
        "r.urdf",
        ": line 3: malformed XML",
    ),
    "unknown link": (
        {"r.urdf": TWO_BOXES.replace('<child link="b"/>', '<child link="bb"/>')},
        "r.urdf",
        "joint[j]/child: unknown link 'bb'",
    ),
    "two roots": (
        {"r.urdf": TWO_BOXES.replace("</robot>", '<link name="c"/></robot>')},
        "r.urdf",
        "several root links: a, c",
    ),
    "cycle": (
        {
            "r.urdf": TWO_BOXES.replace(
                "</robot>", '<joint name="k" type="fixed"><parent link="b"/><child link="a"/></joint></robot>'
            )
        },
        "r.urdf",
        "no root link (the joints form a cycle)",
    ),
    "lower above upper": (
        {"r.urdf": TWO_BOXES.replace('lower="-1" upper="1"', 'lower="1" upper="-1"')},
        "r.urdf",
        "joint[j]/limit: lower 1.0 > upper -1.0",
    ),
    "missing mesh": (
        {
            "r.urdf": TWO_BOXES.replace(
                "</robot>", MESH_LINK.format(uri="meshes/gone.stl") + FIXED_TO_A + "</robot>"
            )
        },
        "r.urdf",
        "link[m]/collision[0]/mesh: mesh 'meshes/gone.stl' not found (looked at ",
    ),
    "unknown package uri": (
        {
            "r.urdf": TWO_BOXES.replace(
                "</robot>", MESH_LINK.format(uri="package://nopkg/x.stl") + FIXED_TO_A + "</robot>"
            )
        },
        "r.urdf",
        "unknown package 'nopkg'",
    ),
    "unknown package in find": (
        {
            "r.urdf.xacro": '<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            '<xacro:include filename="$(find nopkg)/a.xacro"/><link name="a"/></robot>'
        },
        "r.urdf.xacro",
        "$(find nopkg): unknown package 'nopkg'",
    ),
    "zero joint axis": (
        {"r.urdf": TWO_BOXES.replace('axis xyz="0 0 1"', 'axis xyz="0 0 0"')},
        "r.urdf",
        "joint[j]/axis: axis must not be zero",
    ),
    "nan in a limit": (
        {"r.urdf": TWO_BOXES.replace('lower="-1"', 'lower="nan"')},
        "r.urdf",
        "joint[j]/limit@lower: expected finite numbers, got 'nan'",
    ),
    "negative box size": (
        {"r.urdf": TWO_BOXES.replace('size="', 'size="-', 1)},
        "r.urdf",
        "link[a]/collision[0]/box@size: must not be negative",
    ),
    "cylinder without length": (
        {"r.urdf": TWO_BOXES.replace('<box size="0.1 0.1 0.1"/>', '<cylinder radius="0.1"/>', 1)},
        "r.urdf",
        "link[a]/collision[0]/cylinder@length: missing value",
    ),
    "mimic of a fixed joint": (
        {
            "r.urdf": TWO_BOXES.replace(
                "</robot>",
                '<link name="c"/><joint name="k" type="revolute"><parent link="b"/><child link="c"/>'
                '<mimic joint="f"/><limit lower="-1" upper="1"/></joint>'
                '<link name="d"/><joint name="f" type="fixed"><parent link="a"/><child link="d"/></joint></robot>',
            )
        },
        "r.urdf",
        "joint[k]/mimic: follows 'f', a fixed joint; a mimic must follow a moving joint",
    ),
    "soft limits outside the limits": (
        {
            "r.urdf": TWO_BOXES.replace(
                "</joint>", '<safety_controller soft_lower_limit="1.5" soft_upper_limit="2"/></joint>'
            )
        },
        "r.urdf",
        "joint[j]/safety_controller: soft limits leave no range inside [-1.0, 1.0]",
    ),
    "undefined xacro arg": (
        {
            "r.urdf.xacro": '<robot name="x" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="$(arg nm)"/></robot>'
        },
        "r.urdf.xacro",
        "xacro: undefined xacro arg 'nm'",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD_INPUTS))
def test_bad_input_is_one_line_exit_2(case, tmp_path, monkeypatch):
    files, target, expected = BAD_INPUTS[case]
    build_file_tree(tmp_path, files)
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["inspect", target])
    assert result.exit_code == 2, result.output
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert lines[0].startswith(f"error: {target}"), lines[0]
    assert expected in lines[0]
    assert "Traceback" not in result.output


def test_second_fixture_takes_xacro_args():
    path = FIXTURES / "two_link" / "urdf" / "two_link.urdf.xacro"
    result = runner.invoke(app, ["inspect", str(path), "--xacro-arg", "with_tool:=false"])
    assert result.exit_code == 0 and "tool [" not in result.stdout
    result = runner.invoke(app, ["inspect", str(path), "--xacro-arg", "with_tool"])
    assert result.exit_code == 2 and "expected NAME:=VALUE" in result.stderr


def test_missing_package_path_is_named(tmp_path):
    result = runner.invoke(app, ["inspect", str(MARM_URDF), "--package-path", str(tmp_path / "nope")])
    assert result.exit_code == 2
    assert result.stderr.strip() == f"error: {tmp_path / 'nope'}: --package-path: not a directory"


def test_inline_urdf_helper_is_valid(tmp_path):
    build_file_tree(tmp_path, {"a.urdf": urdf('<link name="only"/>')})
    assert runner.invoke(app, ["inspect", str(tmp_path / "a.urdf")]).exit_code == 0


def test_a_folder_or_non_utf8_file_is_one_line_exit_2(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "latin1.urdf").write_bytes('<robot name="r\xe9"><link name="a"/></robot>'.encode("latin-1"))
    (tmp_path / "latin1.urdf.xacro").write_bytes((tmp_path / "latin1.urdf").read_bytes())
    (tmp_path / "robot").mkdir()
    for target, expected in (
        ("latin1.urdf", "error: latin1.urdf: not UTF-8 text (byte 14)"),
        ("latin1.urdf.xacro", "error: latin1.urdf.xacro: not UTF-8 text (byte 14)"),
        ("robot", "error: robot: is a folder; expected a .urdf or .xacro file"),
    ):
        result = runner.invoke(app, ["inspect", target])
        assert result.exit_code == 2 and result.stderr == expected + "\n", result.output


def test_inspect_says_how_each_package_was_found(tmp_path):
    from tests.unit.test_robot import _folder_named_package

    root = _folder_named_package(tmp_path)
    args = ["inspect", str(root / "work/r.urdf.xacro"), "--package-path", str(root / "share")]
    result = runner.invoke(app, args)
    assert result.exit_code == 0, result.output
    folder = (root / "share/my_robot_description").resolve()
    assert f"package my_robot_description: {folder} (found by folder name)" in result.stdout
    data = json.loads(runner.invoke(app, [*args, "--format", "json"]).stdout)
    assert data["packages"] == [
        {"name": "my_robot_description", "path": str(folder), "found_by": "folder name"}
    ]

"""Inputs that raised tracebacks or never returned: each is now one `error:` line (exit 2), a
finding, or a success; anything unforeseen is one `internal error` line (traceback with --debug)."""

from __future__ import annotations

import math
import os
import stat

import pytest
import typer
import yaml
from lxml import etree

from marm_setup.cli import app as app_module
from tests.conftest import FIXTURES, MARM_URDF
from tests.helpers import TWO_BOXES, urdf
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run
from tests.reliability.inputs import alias_bomb, chain_urdf, subgroup_chain, subgroup_diamonds

SPEC = FIXTURES / "marm" / "marm_setup.yaml"
TRIALS = ("--trials", "10")


def _write(path, text: str | bytes):
    path.write_bytes(text if isinstance(text, bytes) else text.encode())
    return path


def test_an_unexpected_exception_is_one_internal_error_line(capsys):
    def broken():
        raise RuntimeError("boom\nsecond line")

    with pytest.raises(typer.Exit) as exit_info:
        app_module.handle_errors(broken)()
    assert exit_info.value.exit_code == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("error: internal error: RuntimeError: boom\\nsecond line")
    assert "please report" in err


def test_debug_shows_the_traceback(monkeypatch):
    import marm_setup.robot as robot_api

    def broken(*_args, **_kwargs):
        raise RuntimeError("boom")

    monkeypatch.setattr(robot_api, "format_tree", broken)  # a bug inside a real command
    with_debug = run("--debug", "inspect", MARM_URDF)
    assert isinstance(with_debug.exception, RuntimeError)  # raised on to the caller: its traceback
    without = run("inspect", MARM_URDF)
    assert_one_line_error(without)
    assert without.exit_code == 2 and "internal error: RuntimeError: boom" in without.stderr


def test_a_thousand_link_chain(tmp_path):
    path = _write(tmp_path / "chain.urdf", chain_urdf(1000, geometry_every=250))
    assert_clean_exit(run("inspect", path), codes=(0,))
    assert_clean_exit(run("collisions", path, *TRIALS), codes=(0,))
    assert_clean_exit(run("init", path, "--out", tmp_path / "pkg", *TRIALS), codes=(0,))
    assert_clean_exit(run("validate", tmp_path / "pkg", "--no-plan"), codes=(0,))


@pytest.mark.parametrize(
    "spec", [subgroup_chain(3000), subgroup_diamonds(40)], ids=["chain-3000", "diamonds-40"]
)
def test_deep_and_diamond_subgroups(tmp_path, spec):
    path = _write(tmp_path / "spec.yaml", yaml.safe_dump(spec))
    assert_clean_exit(run("init", MARM_URDF, "--out", tmp_path / "pkg", "--setup", path, *TRIALS), codes=(0,))


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("groups: " + "[" * 50_000 + "]" * 50_000 + "\n", "nested deeper than"),
        (alias_bomb(), "expands to more than"),
        ("groups: &a [*a]\n", "refers to a node that contains it"),
        (b"package_name: \xff\xfe\n", "not UTF-8 text (byte 14)"),
    ],
    ids=["deep", "alias-bomb", "self-alias", "not-utf8"],
)
def test_yaml_that_would_not_load_is_one_line(tmp_path, text, message):
    path = _write(tmp_path / "spec.yaml", text)
    result = run("init", MARM_URDF, "--out", tmp_path / "pkg", "--setup", path, *TRIALS)
    assert_one_line_error(result, str(path), message)


def test_yaml_bounds_in_a_package_validate_reads(tmp_path):
    assert_clean_exit(run("init", MARM_URDF, "--out", tmp_path / "pkg", "--setup", SPEC, *TRIALS), codes=(0,))
    _write(tmp_path / "pkg" / "config" / "kinematics.yaml", alias_bomb())
    result = run("validate", tmp_path / "pkg", "--no-plan")
    assert_clean_exit(result, codes=(1,))
    assert "expands to more than" in result.stdout


def test_a_nul_byte_in_a_urdf_is_one_line(tmp_path):
    path = _write(tmp_path / "nul.urdf", b'<robot name="a">\x00<link name="a"/></robot>')
    result = run("inspect", path)
    assert_one_line_error(result, "malformed XML: Invalid character: Char 0x0 out of allowed range")
    assert "\\n" not in result.stderr and "column" not in result.stderr


def test_a_nul_byte_in_an_srdf_is_one_line(tmp_path):
    srdf = _write(tmp_path / "nul.srdf", b'<robot name="marm">\x00</robot>')
    result = run("init", MARM_URDF, "--out", tmp_path / "pkg", "--from-srdf", srdf, *TRIALS)
    assert_one_line_error(result, f"{srdf}: line 1: not well-formed XML: Invalid character")
    assert "\\n" not in result.stderr and "column" not in result.stderr


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_a_non_finite_srdf_pose_on_a_continuous_joint(tmp_path, value):
    body = TWO_BOXES.replace('type="revolute"', 'type="continuous"')
    path = _write(tmp_path / "robot.urdf", body)
    srdf = _write(
        tmp_path / "robot.srdf",
        '<robot name="test_robot"><group name="arm"><chain base_link="a" tip_link="b"/></group>'
        f'<group_state name="home" group="arm"><joint name="j" value="{value}"/></group_state></robot>',
    )
    result = run("init", path, "--out", tmp_path / "pkg", "--from-srdf", srdf, *TRIALS)
    assert_clean_exit(result, codes=(0,))  # the value is left out with a warning, as srdfdom skips
    assert f"group_state[home].joint[j]: expected a finite number, got '{value}'" in result.stdout
    written = etree.parse(str(tmp_path / "pkg" / "config" / "test_robot.srdf"))
    values = [float(j.get("value")) for j in written.iterfind("group_state/joint")]
    assert all(math.isfinite(v) for v in values)  # the emptied pose is dropped; home is inferred


@pytest.mark.parametrize(
    "attrs",
    ['xyz="1e308 0 0"', 'xyz="0 0 1e10"', 'rpy="0 0 -1e300"'],
)
def test_huge_numbers_in_a_urdf_are_one_line(tmp_path, attrs):
    body = TWO_BOXES.replace('<origin xyz="0 0 0.2"/>', f"<origin {attrs}/>")
    assert_one_line_error(run("collisions", _write(tmp_path / "r.urdf", body), *TRIALS), "out of range")


TRIANGLE_DAE = """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="{meter}" name="unit"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries><geometry id="g"><mesh>
    <source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
      <technique_common><accessor source="#pa" count="3" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
    <triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s"><node><instance_geometry url="#g"/></node></visual_scene>
  </library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
"""


@pytest.mark.parametrize("meter", ["nan", "0", "-1", "inf"])
def test_dae_units_must_be_a_positive_length(tmp_path, meter):
    _write(tmp_path / "m.dae", TRIANGLE_DAE.format(meter=meter))
    body = urdf('<link name="a"><collision><geometry><mesh filename="m.dae"/></geometry></collision></link>')
    assert_one_line_error(run("collisions", _write(tmp_path / "r.urdf", body), *TRIALS), "unit meter")


def test_a_dae_in_millimetres_still_loads(tmp_path):
    _write(tmp_path / "m.dae", TRIANGLE_DAE.format(meter="0.001"))
    body = urdf('<link name="a"><collision><geometry><mesh filename="m.dae"/></geometry></collision></link>')
    assert_clean_exit(run("collisions", _write(tmp_path / "r.urdf", body), *TRIALS), codes=(0,))


def test_nan_mesh_vertices_are_one_line(tmp_path):
    _write(tmp_path / "m.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n")
    body = urdf('<link name="a"><collision><geometry><mesh filename="m.obj"/></geometry></collision></link>')
    assert_one_line_error(run("collisions", _write(tmp_path / "r.urdf", body), *TRIALS), "finite")


def test_xacro_that_never_ends_is_stopped(tmp_path, monkeypatch):
    monkeypatch.setenv("MARM_SETUP_XACRO_TIMEOUT", "2")
    path = _write(
        tmp_path / "hang.urdf.xacro",
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="h">'
        '<xacro:if value="${10**10**8 > 0}"><link name="a"/></xacro:if></robot>',
    )
    assert_one_line_error(run("inspect", path), "did not finish within 2 s")


@pytest.mark.parametrize(
    ("key", "value"),
    [("max_velocity", 1.0e-300), ("max_acceleration", 5e-324), ("default_velocity_scaling_factor", 5e-324)],
)
def test_near_zero_limits_in_plan(tmp_path, key, value):
    """A package's joint_limits.yaml (ours or not) with a subnormal rate: one line, no numpy
    warnings (render refuses such a value in marm_setup.yaml before it gets there)."""
    pkg = tmp_path / "pkg"
    assert_clean_exit(run("init", MARM_URDF, "--out", pkg, "--setup", SPEC, *TRIALS), codes=(0,))
    limits = pkg / "config" / "joint_limits.yaml"
    data = yaml.safe_load(limits.read_text())
    if key == "default_velocity_scaling_factor":
        data[key] = value
    else:
        data["joint_limits"]["joint2"].update({key: value, "has_acceleration_limits": True})
    limits.write_text(yaml.safe_dump(data))
    result = run("plan", pkg, "--group", "arm", "--from", "home", "--to", "forward")
    assert_one_line_error(result, "below 1e-06")


def test_fake_controllers_initial_with_a_list_as_group(tmp_path):
    pkg = tmp_path / "pkg"
    assert_clean_exit(run("init", MARM_URDF, "--out", pkg, "--setup", SPEC, *TRIALS), codes=(0,))
    fake = pkg / "config" / "fake_controllers.yaml"
    data = yaml.safe_load(fake.read_text())
    data["initial"] = [{"group": [1]}]
    fake.write_text(yaml.safe_dump(data))
    result = run("validate", pkg, "--no-plan")
    assert_clean_exit(result, codes=(1,))
    assert "controller.fake-initial-pose" in result.stdout


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads every folder")
def test_an_unreadable_folder_on_a_package_path(tmp_path):
    locked = tmp_path / "ws" / "locked"
    locked.mkdir(parents=True)
    locked.chmod(0)
    try:
        result = run("inspect", MARM_URDF, "--package-path", tmp_path / "ws")
        assert_clean_exit(result, codes=(0,))
    finally:
        locked.chmod(stat.S_IRWXU)


def test_typed_errors_survive_the_xacro_child_process():
    import pickle

    from marm_setup.errors import PackageNotFound

    error = pickle.loads(
        pickle.dumps(PackageNotFound("unknown package 'p'", package="p", element="$(find p)"))
    )
    assert isinstance(error, PackageNotFound) and (error.package, error.element) == ("p", "$(find p)")
    assert str(error) == "$(find p): unknown package 'p'"


@pytest.mark.parametrize("value", [[1, 2], "x", {"ros__parameters": [1]}])
def test_a_ros2_moveit_yaml_whose_node_entry_is_not_ros_parameters(tmp_path, value):
    pkg = tmp_path / "pkg"
    assert_clean_exit(run("init", MARM_URDF, "--out", pkg, *TRIALS), codes=(0,))
    moveit = pkg / "config" / "moveit.yaml"
    moveit.write_text(yaml.safe_dump({"/**": value}))
    result = run("validate", pkg, "--no-plan")
    assert_clean_exit(result, codes=(1,))
    assert "yaml.ros2-params" in result.stdout


def test_from_srdf_refuses_a_virtual_joint_type_moveit_does_not_know(tmp_path):
    urdf_path = _write(tmp_path / "robot.urdf", TWO_BOXES)
    srdf = _write(
        tmp_path / "robot.srdf",
        '<robot name="test_robot"><group name="arm"><chain base_link="a" tip_link="b"/></group>'
        '<virtual_joint name="vj" type="hinge" parent_frame="world" child_link="a"/></robot>',
    )
    result = run("init", urdf_path, "--out", tmp_path / "pkg", "--from-srdf", srdf, *TRIALS)
    assert_one_line_error(result, "hinge")
    assert not (tmp_path / "pkg").exists()


def _denied(*_args, **_kwargs):
    raise PermissionError(13, "Permission denied", "/pkg/config")


def test_a_folder_we_may_not_read_is_one_line(tmp_path, monkeypatch):
    """An unreadable folder or file (root reads everything, so the error is injected where the
    package is read): one line naming it, exit 2; with --format json a JSON document."""
    import json

    pkg = tmp_path / "pkg"
    assert_clean_exit(run("init", MARM_URDF, "--out", pkg, "--setup", SPEC, *TRIALS), codes=(0,))
    monkeypatch.setattr("marm_setup.validate.runner.validate", _denied)
    assert_one_line_error(run("validate", pkg), "error: /pkg/config: permission denied")
    found = run("validate", pkg, "--format", "json")
    assert found.exit_code == 2 and json.loads(found.stdout)["findings"][0]["rule"] == "input.unreadable"
    monkeypatch.setattr("marm_setup.render.writer.plan_writes", _denied)
    assert_one_line_error(run("render", pkg), "error: /pkg/config: permission denied")


def test_memory_does_not_grow_with_the_trials():
    """--trials 1e8: the states come in chunks drawn where they are checked, so memory stays
    what a few chunks need (the run is stopped after three chunks)."""
    import tracemalloc

    from marm_setup.collision.matrix import CHUNK, compute_collision_matrix
    from marm_setup.robot.load import load_robot

    marm = load_robot(MARM_URDF)

    class Enough(Exception):
        pass

    def stop_after_three_chunks(done: int, total: int) -> None:
        if done >= 3 * CHUNK:
            raise Enough

    tracemalloc.start()
    with pytest.raises(Enough):
        compute_collision_matrix(marm, trials=100_000_000, jobs=1, progress=stop_after_three_chunks)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert peak < 64 * 2**20  # all 1e8 states at once would be 0.6 GB for the marm's 7 joints

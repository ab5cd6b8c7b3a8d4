"""Messages that say what is wrong and where (issue 36): a mesh trimesh refuses gives its reason,
not a file name; a port's setup check names the source file and field the value came from (a
`.setup_assistant` author, a joint limit), not the SRDF; a rate too small to time a trajectory
names the smallest one accepted."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
import yaml

from marm_setup.errors import InputError
from marm_setup.robot.meshes import load_mesh
from tests.conftest import MARM_URDF
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run

GLTF_VIEWS = (
    '{"asset":{"version":"2.0"},"buffers":[{"uri":"%s","byteLength":36}],'
    '"bufferViews":[{"buffer":0,"byteLength":36}],'
    '"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],'
    '"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]}'
)
GARBAGE = {
    "text.gltf": (b"garbage", "not a glTF file: not JSON ("),
    "utf16.gltf": (b"\xff\xfe garbage", "not a glTF file: not JSON ("),
    "list.gltf": (b"[1, 2, 3]", "not a glTF file: its JSON is list, not an object"),
    "number.gltf": (b"7", "not a glTF file: its JSON is int, not an object"),
    "short_buffer.gltf": (
        (GLTF_VIEWS % "data:application/octet-stream;base64,AAAA").encode(),
        "not a valid .gltf file (trimesh: AssertionError)",
    ),
    "bad_accessor.gltf": (
        b'{"asset":{"version":"2.0"},"meshes":[{"primitives":[{"attributes":{"POSITION":7}}]}]}',
        "not a valid .gltf file (trimesh: UnboundLocalError: ",
    ),
    "missing_buffer.gltf": ((GLTF_VIEWS % "gone.bin").encode(), "a file it refers to is missing: gone.bin"),
    "text.glb": (b"garbage", "not a binary glTF (.glb): it does not start with the bytes 'glTF'"),
}


@pytest.mark.parametrize("name", sorted(GARBAGE))
def test_a_garbage_gltf_says_what_is_wrong_in_one_line(tmp_path, name):
    data, reason = GARBAGE[name]
    (tmp_path / name).write_bytes(data)
    (tmp_path / "model.gltf").write_bytes(b"{}")  # trimesh's fallback for a .gltf it cannot parse
    with pytest.raises(InputError) as caught:
        load_mesh(str(tmp_path / name), shown="robot.urdf", element="link[a]/collision[0]/mesh")
    message = caught.value.message
    assert message.startswith(f"cannot read mesh '{tmp_path / name}': {reason}"), message
    assert "\n" not in message and not message.endswith("model.gltf")


@pytest.fixture(scope="module")
def marm(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("port") / "marm"
    assert_clean_exit(run("init", MARM_URDF, "--out", out, "--target", "ros2", "--trials", "20"), codes=(0,))
    return out


def _copy(marm: Path, tmp_path: Path) -> Path:
    source = tmp_path / "source"
    shutil.copytree(marm, source)
    return source


@pytest.mark.parametrize(
    "old, new, field",
    [
        ("author_email: user@example.com", 'author_email: "not an email"', "author_email"),
        ("author_name: marm-setup user", 'author_name: "a\\u200bb"', "author_name"),
    ],
)
def test_a_ported_setup_assistant_author_is_blamed_on_setup_assistant(marm, tmp_path, old, new, field):
    source = _copy(marm, tmp_path)
    sa = source / ".setup_assistant"
    assert old in sa.read_text()
    sa.write_text(sa.read_text().replace(old, new))
    result = run("init", "--from-package", source, "--out", tmp_path / "out")
    assert_one_line_error(
        result, f"error: {source}/.setup_assistant: moveit_setup_assistant_config.CONFIG.{field}: "
    )
    assert ".srdf" not in result.stderr and not (tmp_path / "out").exists()


@pytest.mark.parametrize("rate", [1e-300, 5e-324, 9.99e-7])
def test_a_ported_rate_too_small_to_time_names_its_file_and_the_smallest_accepted(marm, tmp_path, rate):
    source = _copy(marm, tmp_path)
    moveit = source / "config" / "moveit.yaml"
    data = yaml.safe_load(moveit.read_text())
    limits = data["/**"]["ros__parameters"]["robot_description_planning"]["joint_limits"]
    joint = sorted(limits)[0]
    limits[joint].update(has_velocity_limits=True, max_velocity=rate)
    moveit.write_text(yaml.safe_dump(data))
    result = run("init", "--from-package", source, "--out", tmp_path / "out")
    assert_one_line_error(
        result,
        f"error: {source}/config/moveit.yaml: /**.ros__parameters.robot_description_planning.joint_limits.{joint}: ",
        f"must be at least 1e-06 (no trajectory could be timed), got {rate:g}",
        f"joint_limits[{joint}].max_velocity",
    )
    assert "must be positive" not in result.stderr

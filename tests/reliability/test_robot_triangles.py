"""The collision meshes of a whole robot are bounded, not only each mesh (issue 36): one large
file used by many links at different scales is read once, and their total (the file once per
scale, each its own BVH) over MAX_ROBOT_TRIANGLES is one error line naming the bound and the
largest meshes, before any BVH is built."""

from __future__ import annotations

import time
import tracemalloc
from pathlib import Path

import numpy as np
import pytest

from marm_setup.robot import meshes
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run


def _write_stl(path: Path, triangles: int) -> Path:
    """A binary STL of `triangles` small triangles along x (numpy: fast for a million)."""
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
    rows = np.zeros(triangles, dtype=record)
    x = np.arange(triangles, dtype=np.float32) * 1e-6
    rows["corners"][:, 0, 0] = x
    rows["corners"][:, 1, 0] = x + 1e-3
    rows["corners"][:, 2, 1] = 1e-3
    with open(path, "wb") as out:
        out.write(b"\0" * 80 + np.uint32(triangles).tobytes())
        out.write(rows.tobytes())
    return path


def _urdf(folder: Path, mesh: str, scales: list[float]) -> Path:
    """A chain of one link per scale, each colliding with `mesh` at that scale."""
    links = ['<link name="base"/>']
    joints = []
    for i, scale in enumerate(scales):
        links.append(
            f'<link name="l{i}"><collision><geometry><mesh filename="{mesh}" '
            f'scale="{scale} {scale} {scale}"/></geometry></collision></link>'
        )
        parent = "base" if i == 0 else f"l{i - 1}"
        joints.append(
            f'<joint name="j{i}" type="revolute"><parent link="{parent}"/><child link="l{i}"/>'
            '<origin xyz="0 0 0.5"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        )
    path = folder / "robot.urdf"
    path.write_text(f'<robot name="r">{"".join(links)}{"".join(joints)}</robot>')
    return path


@pytest.mark.parametrize("scales, fits", [([1.0] * 20, True), ([1.0 + i / 10 for i in range(20)], False)])
def test_the_robots_total_is_bounded_and_each_file_read_once(tmp_path, monkeypatch, scales, fits):
    from marm_setup.robot import load_robot

    _write_stl(tmp_path / "part.stl", 40)
    robot = load_robot(_urdf(tmp_path, "part.stl", scales), {}, [])
    reads = []
    read = meshes._read
    monkeypatch.setattr(meshes, "_read", lambda path: reads.append(path) or read(path))
    monkeypatch.setattr(meshes, "MAX_ROBOT_TRIANGLES", 100)  # 40 at 20 scales: 800; at one scale: 40
    meshes._read_cached.cache_clear()
    if fits:
        meshes.check_robot_triangles(robot)
    else:
        with pytest.raises(meshes.InputError) as caught:
            meshes.check_robot_triangles(robot)
        message = caught.value.message
        assert message.startswith("the collision meshes hold 800 triangles in all")
        assert "more than the 100 a robot may have" in message
        assert f"largest: '{tmp_path / 'part.stl'}' 40 x 20 scales" in message
        assert caught.value.element == "link[l0]/collision[0]/mesh"
    for scale in sorted(set(scales)):
        meshes.load_mesh(str(tmp_path / "part.stl"), (scale, scale, scale))
    assert len(reads) == 1  # one parse for every scale and every load


@pytest.mark.slow
def test_a_million_triangle_file_at_twenty_scales_is_one_line_in_bounded_memory(tmp_path):
    """The audit's case: 999k triangles at 20 scales took 3.4 GB; now one line, within ~200 MB."""
    _write_stl(tmp_path / "big.stl", 999_000)
    urdf = _urdf(tmp_path, "big.stl", [1.0 + i / 10 for i in range(20)])
    meshes._read_cached.cache_clear()
    tracemalloc.start()
    start = time.monotonic()
    result = run("init", urdf, "--out", tmp_path / "pkg", "--trials", "10")
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    assert_one_line_error(
        result,
        f"error: {urdf}: link[l0]/collision[0]/mesh: the collision meshes hold 19,980,000 triangles in all",
        f"more than the {meshes.MAX_ROBOT_TRIANGLES:,} a robot may have; largest: '{tmp_path / 'big.stl'}' "
        "999,000 x 20 scales",
    )
    assert peak < 300e6, peak
    assert time.monotonic() - start < 60
    assert not (tmp_path / "pkg").exists()


def test_a_robot_within_the_bound_still_writes(tmp_path):
    _write_stl(tmp_path / "part.stl", 12)
    result = run("init", _urdf(tmp_path, "part.stl", [1.0, 2.0]), "--out", tmp_path / "pkg", "--trials", "10")
    assert_clean_exit(result, codes=(0,))

"""`report` on a package whose robot has a collision mesh that cannot be read (garbage bytes of
any format, a truncated file, no read permission): the page is still written, the robot drawn
without that shape, and the page and stderr say so (issue 36)."""

from __future__ import annotations

import errno
import json
import re
import struct
from pathlib import Path
from types import SimpleNamespace

import pytest

from marm_setup import bounded_read
from tests.reliability.checks import assert_clean_exit, run


def _stl(*triangles) -> bytes:
    body = b"".join(struct.pack("<12fH", 0, 0, 0, *(c for corner in t for c in corner), 0) for t in triangles)
    return b"\0" * 80 + struct.pack("<I", len(triangles)) + body


GOOD = _stl(((0, 0, 0), (0.1, 0, 0), (0, 0.1, 0)), ((0, 0, 0), (0, 0.1, 0), (0, 0, 0.1)))
URDF = """<robot name="r">
<link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
<link name="l1"><collision><geometry><mesh filename="good.stl"/></geometry></collision></link>
<link name="l2"><collision><origin xyz="0 0 0.3"/><geometry><mesh filename="{mesh}"/></geometry></collision></link>
<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.2"/>
 <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.2"/>
 <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""
UNREADABLE = {
    "garbage.stl": b"garbage garbage garbage",
    "truncated.stl": GOOD[:-30],
    "garbage.dae": b"<COLLADA><library_geometries><geometry><mesh>",
    "garbage.gltf": b'{"asset": {"version": "2.0"}, "meshes": [{"primitives": [{"attributes": {"POSITION": 7}}]}]}',
    "garbage.obj": b"\x00\x01\x02 not an obj",
    "denied.stl": GOOD,  # readable bytes, read refused (root reads every file: the refusal is injected)
}


@pytest.fixture(scope="module")
def package(tmp_path_factory) -> Path:
    """A package whose l2 mesh is `good.stl` when written (init reads it)."""
    root = tmp_path_factory.mktemp("unreadable")
    (root / "good.stl").write_bytes(GOOD)
    (root / "r.urdf").write_text(URDF.format(mesh="good.stl"))
    assert_clean_exit(run("init", root / "r.urdf", "--out", root / "pkg", "--trials", "50"), codes=(0,))
    return root / "pkg"


@pytest.mark.parametrize("name", sorted(UNREADABLE))
def test_report_draws_the_robot_without_an_unreadable_mesh(package, tmp_path, monkeypatch, name):
    root = package.parent
    (root / name).write_bytes(UNREADABLE[name])
    (root / "r.urdf").write_text(URDF.format(mesh=name))
    if name == "denied.stl":  # only the mesh reader is refused (other modules keep bounded_read)
        from marm_setup.robot import meshes

        def denied(path, limit, **options):
            if Path(path).name == name:
                raise PermissionError(errno.EACCES, "Permission denied", str(path))
            return bounded_read.read_bytes(path, limit, **options)

        monkeypatch.setattr(
            meshes, "bounded_read", SimpleNamespace(read_bytes=denied, MESH_BYTES=bounded_read.MESH_BYTES)
        )
    page = tmp_path / "report.html"
    result = run("report", package, "--output", page, "--no-plan", "--trials", "50")
    assert_clean_exit(result, codes=(1,))  # the mesh is a validate error: urdf.collision-geometry
    assert page.is_file()
    content = json.loads(
        re.search(r'<script type="application/json" id="report-data">(.*?)</script>', page.read_text(), re.S)[
            1
        ]
    )
    note = content["summary"]["not_drawn"]
    assert (
        note.startswith("drawn without 1 collision mesh")
        and "link[l2]/collision[0]/mesh: cannot read mesh '" in note
    )
    assert str(root) not in note  # the page names no machine path
    assert [link["name"] for link in content["geometry"]["links"]] == ["base", "l1"]
    assert len(content["geometry"]["meshes"]) == 1
    warning = [line for line in result.stderr.splitlines() if line.startswith("warning: ")]
    assert (
        len(warning) == 1 and f"link[l2]/collision[0]/mesh: cannot read mesh '{root / name}': " in warning[0]
    )
    assert "1 meshes" in result.stdout

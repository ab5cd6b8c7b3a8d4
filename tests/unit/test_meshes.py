"""Mesh loading: numpy STL reads give exactly trimesh's arrays; bad STL is one InputError."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from marm_setup.errors import InputError
from marm_setup.robot.meshes import load_mesh
from tests.conftest import FIXTURES, REALWORLD


def _trimesh_arrays(path) -> tuple[np.ndarray, np.ndarray]:
    mesh = trimesh.load(str(path), force="mesh", process=False)
    return np.asarray(mesh.vertices, dtype=float), np.asarray(mesh.faces, dtype=np.int64)


def _stl_files() -> list:
    found = sorted(FIXTURES.rglob("*.stl"))
    if REALWORLD.exists():
        found += sorted(p for p in REALWORLD.rglob("*") if p.suffix.lower() == ".stl")
    return found


def test_binary_stl_matches_trimesh_on_every_fixture_and_real_world_mesh():
    files = _stl_files()
    assert files
    for path in files:
        mesh = load_mesh(str(path))
        vertices, faces = _trimesh_arrays(path)
        assert np.array_equal(mesh.vertices, vertices), path
        assert np.array_equal(mesh.faces, faces), path


def test_ascii_stl_matches_trimesh(tmp_path):
    source = trimesh.creation.icosphere(subdivisions=1, radius=0.1)
    path = tmp_path / "ball.stl"
    path.write_text(trimesh.exchange.stl.export_stl_ascii(source), encoding="utf-8")
    mesh = load_mesh(str(path), (2.0, 1.0, 1.0))
    vertices, faces = _trimesh_arrays(path)
    assert len(mesh.faces) == len(source.faces)
    assert np.array_equal(mesh.vertices, vertices * [2.0, 1.0, 1.0])
    assert np.array_equal(mesh.faces, faces)


def test_ascii_stl_with_two_solids_keeps_both_in_order(tmp_path):
    tri = "facet normal 0 0 1\n outer loop\n  vertex {0} 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n"
    path = tmp_path / "two.stl"
    path.write_text(
        f"solid a\n{tri.format(0)}endsolid a\nSOLID b\n{tri.format(5)}ENDSOLID b\n", encoding="utf-8"
    )
    mesh = load_mesh(str(path))
    assert mesh.vertices[:, 0].tolist() == [0, 1, 0, 5, 1, 0]
    assert mesh.faces.tolist() == [[0, 1, 2], [3, 4, 5]]


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("solid x\nendsolid x\n", "no triangles"),
        ("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\nendloop\nendfacet\n", "bad ASCII"),
        ("solid x\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n", "incorrect number"),
    ],
)
def test_bad_ascii_stl_is_an_input_error(tmp_path, text, message):
    path = tmp_path / "bad.stl"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(InputError, match=message):
        load_mesh(str(path), shown="robot.urdf", element="link[a]/collision[0]/mesh")

"""Mesh files -> vertex/face arrays in [m] (trimesh), cached per file and scale.

Collada files carry a `<unit meter="...">` that trimesh records but does not apply; we apply
it, as MoveIt's assimp loader does. Every unreadable mesh is an InputError naming the URDF
element that uses it.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from marm_setup.errors import InputError
from marm_setup.robot.model import Vec3


@dataclass(frozen=True, eq=False)
class MeshData:
    """A triangle mesh: `vertices` (V, 3) in [m] with scale and units applied, `faces` (F, 3)."""

    vertices: np.ndarray
    faces: np.ndarray


def load_mesh(path: str, scale: Vec3 = (1.0, 1.0, 1.0), *, shown: str = "", element: str = "") -> MeshData:
    """The mesh at `path` scaled by `scale`; `shown`/`element` name the user's file in errors."""
    try:
        return _load_cached(str(path), tuple(float(s) for s in scale))
    except _MeshReadError as exc:
        raise InputError(f"cannot read mesh '{path}': {exc}", path=shown or path, element=element) from None


class _MeshReadError(Exception):
    pass


@lru_cache(maxsize=256)
def _load_cached(path: str, scale: tuple[float, float, float]) -> MeshData:
    vertices, faces = _read(Path(path))
    vertices = vertices * _unit_meters(Path(path)) * np.asarray(scale)
    vertices.setflags(write=False)
    faces.setflags(write=False)
    return MeshData(vertices, faces)


def _read(path: Path) -> tuple[np.ndarray, np.ndarray]:
    import trimesh

    if not path.is_file():
        raise _MeshReadError("file not found")
    try:
        mesh = trimesh.load(str(path), force="mesh", process=False)
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise _MeshReadError(" ".join(str(exc).split()) or type(exc).__name__) from None
    vertices = np.asarray(getattr(mesh, "vertices", ()), dtype=float).reshape(-1, 3)
    faces = np.asarray(getattr(mesh, "faces", ()), dtype=np.int64).reshape(-1, 3)
    if len(vertices) == 0 or len(faces) == 0:
        raise _MeshReadError("no triangles")
    return vertices.copy(), faces.copy()


def _unit_meters(path: Path) -> float:
    """The Collada `<asset><unit meter>` factor; 1 for other formats or when absent."""
    if path.suffix.lower() != ".dae":
        return 1.0
    from lxml import etree

    try:
        root = etree.parse(str(path), etree.XMLParser(huge_tree=True)).getroot()
    except etree.XMLSyntaxError as exc:
        raise _MeshReadError(f"malformed Collada XML: {exc.msg}") from None
    unit = root.find("{*}asset/{*}unit")
    try:
        return float(unit.get("meter")) if unit is not None and unit.get("meter") else 1.0
    except ValueError:
        raise _MeshReadError(f"bad <unit meter='{unit.get('meter')}'>") from None

"""Mesh files -> vertex/face arrays in [m], cached per file and scale.

STL (binary and ASCII) is read with numpy: triangle soup, one vertex per corner, as trimesh
gives with `process=False`; other formats (DAE, OBJ, ...) go through trimesh, imported only
then (it costs most of a second of start-up). Collada files carry a `<unit meter="...">` that
trimesh records (`mesh.units`) but does not apply; we convert to meters with trimesh, as
MoveIt's assimp loader applies the unit. Every unreadable mesh is an InputError naming the
URDF element that uses it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from marm_setup.errors import InputError, MeshNotFound
from marm_setup.robot.model import Vec3


@dataclass(frozen=True, eq=False)
class MeshData:
    """A triangle mesh: `vertices` (V, 3) in [m] with scale and units applied, `faces` (F, 3)."""

    vertices: np.ndarray
    faces: np.ndarray


def load_mesh(path: str, scale: Vec3 = (1.0, 1.0, 1.0), *, shown: str = "", element: str = "") -> MeshData:
    """The mesh at `path` scaled by `scale`; `shown`/`element` name the user's file in errors."""
    if not Path(path).is_file():
        message = f"cannot read mesh '{path}': file not found"
        raise MeshNotFound(message, uri=str(path), path=shown or path, element=element)
    try:
        return _load_cached(str(path), tuple(float(s) for s in scale))
    except _MeshReadError as exc:
        raise InputError(f"cannot read mesh '{path}': {exc}", path=shown or path, element=element) from None


MAX_VERTEX_M = 1e6  # [m] after units and scale: no robot part is larger


class _MeshReadError(Exception):
    pass


@lru_cache(maxsize=256)
def _load_cached(path: str, scale: tuple[float, float, float]) -> MeshData:
    vertices, faces = _read(Path(path))
    vertices = vertices * np.asarray(scale)
    if not np.all(np.isfinite(vertices)) or np.abs(vertices).max() > MAX_VERTEX_M:
        raise _MeshReadError(f"vertex coordinates must be finite and within {MAX_VERTEX_M:g} m")
    vertices.setflags(write=False)
    faces.setflags(write=False)
    return MeshData(vertices, faces)


def _check_units(units: str) -> None:
    """A declared unit must be a positive, finite length (Collada `<unit meter="0">` is not)."""
    from trimesh.units import unit_conversion

    try:
        meters = unit_conversion(units, "meters")
    except Exception:  # trimesh: ValueError / KeyError for names it does not know
        meters = math.nan
    if not (math.isfinite(meters) and 0 < meters <= MAX_VERTEX_M):
        raise _MeshReadError(f"bad unit meter='{units}': must be a positive length in metres")


def _read(path: Path) -> tuple[np.ndarray, np.ndarray]:
    if path.suffix.lower() == ".stl":
        return _read_stl(path.read_bytes())
    import trimesh

    try:
        mesh = trimesh.load(str(path), force="mesh", process=False)
        if isinstance(mesh, trimesh.Trimesh) and mesh.units is not None:  # Collada <unit>; never guessed
            _check_units(mesh.units)
            mesh.convert_units("meters")
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise _MeshReadError(" ".join(str(exc).split()) or type(exc).__name__) from None
    if not isinstance(mesh, trimesh.Trimesh):
        raise _MeshReadError("no triangles")
    vertices = np.asarray(mesh.vertices, dtype=float).reshape(-1, 3)
    faces = np.asarray(mesh.faces, dtype=np.int64).reshape(-1, 3)
    if len(vertices) == 0 or len(faces) == 0:
        raise _MeshReadError("no triangles")
    return vertices.copy(), faces.copy()


def _read_stl(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Binary STL when its size matches the triangle count in its header, else ASCII."""
    if len(data) >= 84:
        count = int(np.frombuffer(data, dtype="<u4", count=1, offset=80)[0])
        if count and len(data) == 84 + 50 * count:
            rows = np.frombuffer(data, dtype=_STL_RECORD, count=count, offset=84)
            return _soup(rows["corners"].reshape(-1, 3).astype(float))
    try:
        text = data.decode("utf-8", errors="replace").lower()
        numbers = [m.split() for m in _STL_VERTEX.findall(text)]
        corners = np.array(numbers, dtype=float).reshape(-1, 3)
    except ValueError as exc:
        raise _MeshReadError(f"bad ASCII STL vertex: {exc}") from None
    if len(corners) == 0 or len(corners) % 3:
        raise _MeshReadError("no triangles" if len(corners) == 0 else "incorrect number of vertices")
    return _soup(corners)


_STL_RECORD = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
_STL_VERTEX = re.compile(r"\bvertex\s+(\S+\s+\S+\s+\S+)")


def _soup(corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and faces of a triangle soup: face i is corners 3i, 3i+1, 3i+2."""
    if not len(corners):
        raise _MeshReadError("no triangles")
    return corners, np.arange(len(corners), dtype=np.int64).reshape(-1, 3)

"""Mesh files -> vertex/face arrays in [m]: each file read once (cached by path and its stat),
its scale applied after, so one file used by many links at several scales is parsed once.

STL (binary and ASCII) is read with numpy: triangle soup, one vertex per corner, as trimesh
gives with `process=False`; other formats (DAE, OBJ, ...) go through trimesh, imported only
then (it costs most of a second of start-up). Collada files carry a `<unit meter="...">` that
trimesh records (`mesh.units`) but does not apply; we convert to meters with trimesh, as
MoveIt's assimp loader applies the unit. Every unreadable mesh is an InputError naming the
URDF element that uses it. A robot's collision meshes are bounded in all
(`check_robot_triangles`, MAX_ROBOT_TRIANGLES), not only one by one.
"""

from __future__ import annotations

import io
import json
import math
import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.errors import InputError, MeshNotFound
from marm_setup.robot.model import Mesh, RobotModel, Vec3


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
        return _scaled(_file_mesh(str(path)), tuple(float(s) for s in scale))
    except _MeshReadError as exc:
        raise InputError(f"cannot read mesh '{path}': {exc}", path=shown or path, element=element) from None


MAX_VERTEX_M = 1e6  # [m] after units and scale: no robot part is larger
# collision mesh triangles of a whole robot, each file counted once per scale it is used at
# (each is a BVH of its own): 2M cost about 350 MB and 20 s to build and check
MAX_ROBOT_TRIANGLES = 2_000_000


class _MeshReadError(Exception):
    pass


def _file_mesh(path: str) -> MeshData:
    """The file's mesh unscaled, read once while the file stays the same (path and stat)."""
    try:
        info = Path(path).stat()
    except OSError as exc:
        raise _MeshReadError(exc.strerror or str(exc)) from None
    return _read_cached(path, (info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns))


@lru_cache(maxsize=64)
def _read_cached(path: str, _identity: tuple[int, ...]) -> MeshData:
    vertices, faces = _read(Path(path))
    vertices = np.asarray(vertices, dtype=float)
    vertices.setflags(write=False)
    faces.setflags(write=False)
    return MeshData(vertices, faces)


def _scaled(mesh: MeshData, scale: tuple[float, ...]) -> MeshData:
    """`mesh` scaled (`mesh` itself at scale 1; the faces always shared), its coordinates
    finite and within MAX_VERTEX_M."""
    unscaled = scale == (1.0, 1.0, 1.0)
    vertices = mesh.vertices if unscaled else mesh.vertices * np.asarray(scale)
    if not np.all(np.isfinite(vertices)) or np.abs(vertices).max() > MAX_VERTEX_M:
        raise _MeshReadError(f"vertex coordinates must be finite and within {MAX_VERTEX_M:g} m")
    if unscaled:
        return mesh
    vertices.setflags(write=False)
    return MeshData(vertices, mesh.faces)


def check_robot_triangles(robot: RobotModel) -> None:
    """Raise one InputError when the robot's collision meshes hold more than MAX_ROBOT_TRIANGLES
    triangles in all (a file counted once per scale it is used at), naming the largest; reads
    each file once (an unreadable one is its own InputError)."""
    uses: dict[tuple[str, tuple[float, ...]], str] = {}  # (file, scale) -> the first element using it
    triangles: dict[str, int] = {}
    for link in robot.links:
        for k, shape in enumerate(link.collisions):
            mesh = shape.geometry
            if not isinstance(mesh, Mesh) or (mesh.path, tuple(mesh.scale)) in uses:
                continue
            element = f"link[{link.name}]/collision[{k}]/mesh"
            uses[(mesh.path, tuple(mesh.scale))] = element
            if mesh.path not in triangles:
                found = load_mesh(mesh.path, shown=robot.source, element=element)
                triangles[mesh.path] = len(found.faces)
    total = sum(triangles[path] for path, _ in uses)
    if total <= MAX_ROBOT_TRIANGLES:
        return
    scales = {path: sum(1 for p, _ in uses if p == path) for path in triangles}
    largest = sorted(triangles, key=lambda p: (-triangles[p] * scales[p], p))
    said = ", ".join(
        f"'{p}' {triangles[p]:,}" + (f" x {scales[p]} scales" if scales[p] > 1 else "") for p in largest[:3]
    )
    element = next(e for (p, _), e in uses.items() if p == largest[0])
    raise InputError(
        f"the collision meshes hold {total:,} triangles in all (a file once per scale it is used at), "
        f"more than the {MAX_ROBOT_TRIANGLES:,} a robot may have; largest: {said} "
        "(simplify them, e.g. to their convex hulls)",
        path=robot.source or None,
        element=element,
    )


def _check_units(units: str) -> None:
    """A declared unit must be a positive, finite length (Collada `<unit meter="0">` is not)."""
    from trimesh.units import unit_conversion

    try:
        meters = unit_conversion(units, "meters")
    except Exception:  # trimesh: ValueError / KeyError for names it does not know
        meters = math.nan
    if not (math.isfinite(meters) and 0 < meters <= MAX_VERTEX_M):
        raise _MeshReadError(f"bad unit meter='{units}': must be a positive length in metres")


MAX_TRIANGLES = 1_000_000  # a collision mesh of more costs over 1 GB and 10 s to build; simplify it


def _read(path: Path) -> tuple[np.ndarray, np.ndarray]:
    try:
        data = bounded_read.read_bytes(path, bounded_read.MESH_BYTES)
    except FileTooLarge as exc:
        raise _MeshReadError(exc.message) from None
    except OSError as exc:
        raise _MeshReadError(exc.strerror or str(exc)) from None
    if path.suffix.lower() == ".stl":
        return _read_stl(data)
    vertices, faces = _read_with_trimesh(data, path)
    _check_triangles(len(faces))
    return vertices, faces


def _read_with_trimesh(data: bytes, path: Path) -> tuple[np.ndarray, np.ndarray]:
    """DAE, OBJ, PLY, ... through trimesh, from the bytes already read (files the mesh names,
    such as an OBJ's materials, are looked up next to it)."""
    import trimesh

    kind = path.suffix.lower().lstrip(".")
    _check_gltf(data, kind)
    try:
        resolver = trimesh.resolvers.FilePathResolver(str(path))
        mesh = trimesh.load(io.BytesIO(data), file_type=kind, force="mesh", process=False, resolver=resolver)
        if isinstance(mesh, trimesh.Trimesh) and mesh.units is not None:  # Collada <unit>; never guessed
            _check_units(mesh.units)
            mesh.convert_units("meters")
    except _MeshReadError:
        raise
    except Exception as exc:  # trimesh raises many types for unreadable files
        raise _MeshReadError(_trimesh_reason(exc, kind)) from None
    if not isinstance(mesh, trimesh.Trimesh):
        raise _MeshReadError("no triangles")
    vertices = np.asarray(mesh.vertices, dtype=float).reshape(-1, 3)
    faces = np.asarray(mesh.faces, dtype=np.int64).reshape(-1, 3)
    if len(vertices) == 0 or len(faces) == 0:
        raise _MeshReadError("no triangles")
    return vertices.copy(), faces.copy()


def _check_gltf(data: bytes, kind: str) -> None:
    """A .gltf must be a JSON object and a .glb start with the `glTF` magic (glTF 2.0 spec,
    sections 3 and 4.4): trimesh reads any other .gltf as a folder's `model.gltf` and reports
    only that name."""
    if kind == "glb" and data[:4] != b"glTF":
        raise _MeshReadError("not a binary glTF (.glb): it does not start with the bytes 'glTF'")
    if kind != "gltf":
        return
    try:
        tree = json.loads(data)
    except ValueError as exc:  # UnicodeDecodeError and JSONDecodeError alike
        raise _MeshReadError(f"not a glTF file: not JSON ({' '.join(str(exc).split())})") from None
    if not isinstance(tree, dict):
        raise _MeshReadError(f"not a glTF file: its JSON is {type(tree).__name__}, not an object")


def _trimesh_reason(exc: Exception, kind: str) -> str:
    """trimesh's reason for refusing a file, one line: a file it names that is missing, else the
    exception's type and words (an internal one, such as KeyError or AssertionError, says the
    file is not what its format requires)."""
    text = " ".join(str(exc).split())
    if isinstance(exc, FileNotFoundError):
        return f"a file it refers to is missing: {text or '?'}"
    name = type(exc).__name__
    said = text if text.startswith(name) else f"{name}: {text}" if text else name
    if isinstance(exc, (AttributeError, AssertionError, IndexError, KeyError, NameError, TypeError)):
        return f"not a valid .{kind} file (trimesh: {said})"
    return text or name


def _check_triangles(count: int) -> None:
    if count > MAX_TRIANGLES:
        raise _MeshReadError(
            f"{count:,} triangles, more than the {MAX_TRIANGLES:,} a collision mesh may have "
            "(simplify it, e.g. to its convex hull)"
        )


def _read_stl(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Binary STL when its size is the one its header's triangle count gives, else ASCII when it
    starts with `solid` and its first 500 bytes are ASCII, else neither: assimp's rule, which
    MoveIt loads meshes with (code/AssetLib/STL/STLLoader.cpp, IsBinarySTL and IsAsciiSTL)."""
    count = int(np.frombuffer(data, dtype="<u4", count=1, offset=80)[0]) if len(data) >= 84 else None
    if count is not None and len(data) == 84 + 50 * count:
        _check_triangles(count)
        if not count:
            raise _MeshReadError("no triangles")
        rows = np.frombuffer(data, dtype=_STL_RECORD, count=count, offset=84)
        return _soup(rows["corners"].reshape(-1, 3).astype(float))
    head = data.lstrip()[:500]
    if head[:5].lower() != b"solid" or max(head, default=0) > 127:
        said = "" if count is None else f" (its header counts {count:,} triangles: {84 + 50 * count:,} bytes)"
        raise _MeshReadError(
            f"neither ASCII STL (no 'solid' at the start) nor binary STL{said}: the file has {len(data):,} bytes"
        )
    return _read_ascii_stl(data)


def _read_ascii_stl(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    text = data.lower()
    _check_triangles(text.count(b"vertex") // 3)
    try:
        corners = np.array(_STL_VERTEX.findall(text), dtype=bytes).astype(float).reshape(-1, 3)
    except ValueError as exc:
        raise _MeshReadError(f"bad ASCII STL vertex: {exc}") from None
    if len(corners) == 0 or len(corners) % 3:
        raise _MeshReadError("no triangles" if len(corners) == 0 else "incorrect number of vertices")
    return _soup(corners)


_STL_RECORD = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attr", "<u2")])
_STL_VERTEX = re.compile(rb"\bvertex\s+(\S+)\s+(\S+)\s+(\S+)")


def _soup(corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and faces of a triangle soup: face i is corners 3i, 3i+1, 3i+2."""
    if not len(corners):
        raise _MeshReadError("no triangles")
    return corners, np.arange(len(corners), dtype=np.int64).reshape(-1, 3)

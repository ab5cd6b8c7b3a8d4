"""The robot's collision geometry as the page draws it: primitives as they are, meshes merged,
decimated and shared.

MoveIt checks collisions on this geometry (and the matrix and findings are about it), so the
report draws it rather than the visual meshes. A mesh above MAX_FACES triangles is decimated
with trimesh's quadric decimation (fast-simplification) towards MAX_FACES, at the most
aggressive setting that keeps its surface (AREA_KEPT of its area): at fast-simplification's
default aggressiveness (7) the Kinova Gen3 bicep lost 80 % of its area, a hole in the arm. A
mesh file used by several links (left and right arms) is sent once.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from marm_setup.robot import Box, CollisionShape, Cylinder, Mesh, RobotModel, Sphere, origin_matrix

MAX_FACES = 4000  # triangles per mesh: a collision view stays readable, a page stays small
AREA_KEPT = 0.95  # a decimated mesh keeps at least this share of its surface area, else less is cut
AGGRESSION = (5, 3, 1)  # fast-simplification's aggressiveness, tried in this order


@dataclass(frozen=True, eq=False)
class MeshArrays:
    """An indexed triangle mesh in [m]: `positions` (V, 3) float32, `indices` (F, 3) uint32;
    `faces_before` the triangles of the file."""

    positions: np.ndarray
    indices: np.ndarray
    faces_before: int


@dataclass(frozen=True)
class Shape:
    """One collision shape of a link: `kind` box | cylinder | sphere | mesh, `size` (box: x y z;
    cylinder: radius length; sphere: radius), `mesh` an index into the meshes, `origin` 3x4 in
    the link frame (row-major)."""

    kind: str
    size: tuple[float, ...]
    mesh: int | None
    origin: tuple[float, ...]


@dataclass(frozen=True)
class RobotGeometry:
    """Each geometry link's shapes (tree order) and the meshes they share."""

    links: tuple[tuple[str, tuple[Shape, ...]], ...]
    meshes: tuple[MeshArrays, ...]


def robot_geometry(
    robot: RobotModel, max_faces: int = MAX_FACES, progress: Callable[[int, int], None] | None = None
) -> RobotGeometry:
    """The collision shapes of every link that has any, meshes decimated to `max_faces`;
    `progress(done, total)` after each mesh file."""
    from marm_setup.robot import check_robot_triangles

    check_robot_triangles(robot)
    mesh_ids: dict[tuple[str, tuple[float, ...]], int] = {}
    meshes: list[MeshArrays] = []
    links = []
    total = len(
        {
            (s.geometry.path, tuple(s.geometry.scale))
            for name in robot.links_in_tree_order
            for s in robot.link(name).collisions
            if isinstance(s.geometry, Mesh)
        }
    )
    count = len(meshes)
    for name in robot.links_in_tree_order:
        link = robot.link(name)
        if not link.has_geometry:
            continue
        shapes = []
        for k, shape in enumerate(link.collisions):
            element = f"link[{name}]/collision[{k}]"
            shapes.append(_shape(shape, robot, element, mesh_ids, meshes, max_faces))
            if progress is not None and len(meshes) > count:
                count = len(meshes)
                progress(count, total)
        links.append((name, tuple(shapes)))
    return RobotGeometry(tuple(links), tuple(meshes))


def _shape(
    shape: CollisionShape,
    robot: RobotModel,
    element: str,
    mesh_ids: dict[tuple[str, tuple[float, ...]], int],
    meshes: list[MeshArrays],
    max_faces: int,
) -> Shape:
    origin = tuple(float(x) for x in origin_matrix(shape.origin)[:3].ravel())
    geometry = shape.geometry
    if isinstance(geometry, Box):
        return Shape("box", tuple(geometry.size), None, origin)
    if isinstance(geometry, Cylinder):
        return Shape("cylinder", (geometry.radius, geometry.length), None, origin)
    if isinstance(geometry, Sphere):
        return Shape("sphere", (geometry.radius,), None, origin)
    assert isinstance(geometry, Mesh)
    key = (geometry.path, tuple(geometry.scale))
    if key not in mesh_ids:
        mesh_ids[key] = len(meshes)
        meshes.append(_mesh_arrays(geometry, robot.source, element, max_faces))
    return Shape("mesh", (), mesh_ids[key], origin)


def _mesh_arrays(mesh: Mesh, shown: str, element: str, max_faces: int) -> MeshArrays:
    """The mesh file as an indexed mesh (corners merged), decimated above `max_faces`."""
    import trimesh

    from marm_setup.robot import load_mesh

    data = load_mesh(mesh.path, mesh.scale, shown=shown, element=element)
    solid = trimesh.Trimesh(np.asarray(data.vertices), np.asarray(data.faces), process=True)
    if len(solid.faces) > max_faces:
        solid = _decimated(solid, max_faces)
    return MeshArrays(
        np.ascontiguousarray(solid.vertices, dtype=np.float32),
        np.ascontiguousarray(solid.faces, dtype=np.uint32),
        len(data.faces),
    )


def _decimated(solid: Any, max_faces: int) -> Any:
    """`solid` (a trimesh.Trimesh) cut towards `max_faces` triangles at the most aggressive
    setting that keeps AREA_KEPT of its area; `solid` itself when none does."""
    for aggression in AGGRESSION:
        reduced = solid.simplify_quadric_decimation(face_count=max_faces, aggression=aggression)
        if reduced.area >= AREA_KEPT * solid.area:
            return reduced
    return solid

"""The robot the page can draw: its collision meshes that cannot be read (garbage bytes, no read
permission, over a bound) left out, each said once, so an unreadable mesh costs the page that
shape, not the page (issue 36). validate reports the same mesh as `urdf.collision-geometry`."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

from marm_setup.errors import InputError
from marm_setup.robot import Mesh, RobotModel


@dataclass(frozen=True)
class NotDrawn:
    """A collision shape left out: the file and element that use it, and why."""

    path: str
    element: str
    message: str

    def line(self) -> str:
        return f"{self.path}: {self.element}: {self.message}"


def drawable_robot(robot: RobotModel) -> tuple[RobotModel, tuple[NotDrawn, ...]]:
    """`robot` without the collision shapes whose mesh `load_mesh` refuses, and those shapes."""
    from marm_setup.robot import load_mesh

    left_out: list[NotDrawn] = []
    links = []
    for link in robot.links:
        kept = []
        for k, shape in enumerate(link.collisions):
            geometry = shape.geometry
            if isinstance(geometry, Mesh):
                element = f"link[{link.name}]/collision[{k}]/mesh"
                try:
                    load_mesh(geometry.path, geometry.scale, shown=robot.source, element=element)
                except InputError as exc:
                    left_out.append(NotDrawn(exc.path or robot.source, exc.element or element, exc.message))
                    continue
            kept.append(shape)
        links.append(
            link if len(kept) == len(link.collisions) else dataclasses.replace(link, collisions=tuple(kept))
        )
    if not left_out:
        return robot, ()
    return dataclasses.replace(robot, links=tuple(links)), tuple(left_out)


def not_drawn_note(left_out: tuple[NotDrawn, ...]) -> str:
    """The page's one line on the shapes left out ('' when none)."""
    if not left_out:
        return ""
    shapes = "; ".join(f"{n.element}: {n.message}" for n in left_out)
    return (
        f"drawn without {len(left_out)} collision mesh{'es' if len(left_out) > 1 else ''} that cannot be "
        f"read (their shapes are not in the view nor in the matrix below): {shapes}"
    )

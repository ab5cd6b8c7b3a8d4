"""pair_keys: what one pair's proof depends on, as a hash (the proof cache's key).

A pair's proof (collision/proof.py) reads only the two links' collision geometry and the
joints between them: the chains from their lowest common ancestor down to each link (type,
origin, axis, mimic) and the bounds of the variables that drive those joints (a mimic joint's
leader's), under the scene's padding. The key hashes exactly that, with the geometry as the
scene loaded it (vertex and triangle arrays after scale and units, so every byte a mesh
depends on counts, a glTF's `.bin` buffer as much as the file the URDF names), and nothing
else: the same arm with another tool, or another robot built round the same links, gets the
same key for its unchanged pairs. KEY_VERSION changes whenever what a proof means does.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING

from marm_setup.collision.meter import EXACT_UNITS, PAYS, PROBES, TRIANGLES_PER_UNIT
from marm_setup.collision.proof import SCREEN, SETTLE
from marm_setup.robot import Joint, Mesh, RobotModel, load_mesh

if TYPE_CHECKING:
    from marm_setup.collision.scene import CollisionScene

Pair = tuple[str, str]
KEY_VERSION = "marm-setup proof 1"


def pair_keys(scene: CollisionScene, pairs: Iterable[Pair]) -> dict[Pair, str]:
    """Pair -> the 32 hex digits of its proof's key (see the module doc)."""
    robot = scene.robot
    geometry: dict[str, str] = {}
    ancestors: dict[str, list[str]] = {}
    out = {}
    for a, b in pairs:
        for link in (a, b):
            if link not in geometry:
                geometry[link] = link_geometry_digest(robot, link)
                ancestors[link] = [link, *(j.parent for j in robot.path_to_root(link))]
        common = next(x for x in ancestors[a] if x in set(ancestors[b]))
        text = repr(
            (
                KEY_VERSION,
                scene.padding,
                common,
                [(link, geometry[link], _chain(robot, common, link)) for link in (a, b)],
            )
        )
        out[(a, b)] = hashlib.sha256(text.encode()).hexdigest()[:32]
    return out


def link_geometry_digest(robot: RobotModel, link: str) -> str:
    """A hash of a link's collision shapes as loaded: primitives by their sizes, meshes by
    their vertex and triangle arrays; each with its origin."""
    digest = hashlib.sha256()
    for shape in robot.link(link).collisions:
        geometry = shape.geometry
        if isinstance(geometry, Mesh):
            mesh = load_mesh(geometry.path, geometry.scale)
            digest.update(b"mesh")
            for array in (mesh.vertices, mesh.faces):
                digest.update(repr((array.dtype.str, array.shape)).encode())
                digest.update(array.tobytes())
        else:
            digest.update(repr(geometry).encode())
        digest.update(repr(shape.origin).encode())
    return digest.hexdigest()


def _chain(robot: RobotModel, common: str, link: str) -> list[tuple]:
    """The joints from `common` down to `link`, each with the bounds of what drives it."""
    return [_joint(robot, joint) for joint in robot.chain(common, link) or ()]


def _joint(robot: RobotModel, joint: Joint) -> tuple:
    mimic = (joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset) if joint.mimic else None
    leader = robot.joint(joint.mimic.joint) if joint.mimic else joint
    return (joint.name, joint.type, joint.origin, joint.axis, mimic, leader.name, leader.bounds)


def run_context(scene: CollisionScene, settings: Mapping[str, object]) -> str:
    """32 hex digits of what a whole matrix computation depends on: every candidate pair's key,
    the sampled joints (names, types, bounds, mimic) and the `settings` (seed, trials, ...). An
    unproved proof is the outcome of its budget, which the whole run decides: it is kept under
    its pair's key and this context, and reused only by the very same run: the proof budgets
    (proof.SCREEN, proof.SETTLE) and what the meter charges (collision/meter.py) count too, so a
    cache an older plan filled serves its facts (proved, in contact) but not its unproved
    outcomes."""
    robot = scene.robot
    keys = sorted(pair_keys(scene, scene.candidate_pairs).values())
    joints = [_joint(robot, joint) for joint in robot.joints if joint.is_actuated]
    values = sorted((name, repr(v.tolist() if hasattr(v, "tolist") else v)) for name, v in settings.items())
    charges = (EXACT_UNITS, TRIANGLES_PER_UNIT, PROBES, PAYS)
    text = repr((KEY_VERSION, keys, joints, values, SCREEN, SETTLE, charges))
    return hashlib.sha256(text.encode()).hexdigest()[:32]

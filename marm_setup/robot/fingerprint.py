"""robot_fingerprint: a short hash of what a robot's self-collisions depend on.

Joints (type, links, origin, axis, bounds, mimic) and collision shapes (geometry, origin; a
mesh by the bytes of its file and its scale, not by where it lies), in name order. Comments,
formatting, visual geometry, velocity and effort limits and where the files sit do not change
it, so the same robot gives the same fingerprint on any machine.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from marm_setup.robot.model import Mesh, RobotModel


def robot_fingerprint(robot: RobotModel) -> str:
    """16 hex digits of a SHA-256 over the robot's kinematics and collision geometry."""
    digest = hashlib.sha256()
    for joint in sorted(robot.joints, key=lambda j: j.name):
        bounds = joint.bounds if joint.is_actuated else None
        mimic = (joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset) if joint.mimic else None
        fields = (joint.name, joint.type, joint.parent, joint.child, joint.origin, joint.axis, bounds, mimic)
        digest.update(repr(fields).encode())
    meshes: dict[str, str] = {}
    for link in sorted(robot.links, key=lambda x: x.name):
        for shape in link.collisions:
            geometry = shape.geometry
            if isinstance(geometry, Mesh):
                if geometry.path not in meshes:
                    meshes[geometry.path] = hashlib.sha256(Path(geometry.path).read_bytes()).hexdigest()
                described = repr(("mesh", meshes[geometry.path], geometry.scale))
            else:
                described = repr(geometry)
            digest.update(repr((link.name, described, shape.origin)).encode())
    return digest.hexdigest()[:16]

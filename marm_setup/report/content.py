"""Everything the page shows, as one JSON-ready mapping (the page's script reads it).

Number arrays travel as base64 of little-endian float32 / uint32 bytes (a tenth of JSON text's
size for meshes and frames). Order is fixed (SRDF order, tree order, sorted pairs), so the same
package gives the same page.
"""

from __future__ import annotations

import base64
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from marm_setup.findings import Finding, count, finding_dict
from marm_setup.report.frames import link_frames
from marm_setup.report.geometry import RobotGeometry, Shape
from marm_setup.report.motions import Motion
from marm_setup.report.states import RobotState
from marm_setup.robot import RobotModel
from marm_setup.setup import EndEffector, Srdf, VirtualJoint, group_links, groups_by_name


@dataclass(frozen=True)
class MatrixSection:
    """The collision matrix: the SVG picture and `describe_matrix`'s mapping (pairs with reason,
    hits and closest distance)."""

    svg: str
    described: dict


@dataclass(frozen=True)
class Drawing:
    """What the 3D view draws, for a package whose robot and SRDF loaded."""

    robot: RobotModel
    srdf: Srdf
    geometry: RobotGeometry
    states: tuple[RobotState, ...]
    motions: tuple[Motion, ...]
    matrix: MatrixSection | None


def drawn_links(robot: RobotModel, geometry: RobotGeometry, srdf: Srdf) -> tuple[str, ...]:
    """Links the page places: those with geometry, the root, and the end effectors' parents."""
    wanted = {name for name, _ in geometry.links} | {robot.root}
    wanted |= {e.parent_link for e in srdf.end_effectors if e.parent_link in robot.link_map}
    return tuple(name for name in robot.links_in_tree_order if name in wanted)


def page_content(name: str, drawing: Drawing | None, findings: Sequence[Finding], summary: dict) -> dict:
    """The page's data (see the module docstring): `name` the robot's (or the package's, when no
    robot loaded), `summary` what was validated; without a drawing, the findings alone."""
    errors, warnings = count(findings)
    out: dict = {
        "robot": name,
        "summary": {**summary, "errors": errors, "warnings": warnings},
        "links": [],
        "geometry": {"links": [], "meshes": []},
        "groups": [],
        "end_effectors": [],
        "virtual_joints": [],
        "states": [],
        "motions": [],
        "findings": [_finding(k, f) for k, f in enumerate(findings)],
        "matrix": None,
    }
    if drawing is not None:
        out.update(_drawing(drawing))
    return out


def _drawing(d: Drawing) -> dict:
    links = drawn_links(d.robot, d.geometry, d.srdf)
    matrix = d.matrix
    return {
        "links": list(links),
        "geometry": _geometry(d.geometry),
        "groups": _groups(d.srdf, d.robot),
        "end_effectors": [_end_effector(e) for e in d.srdf.end_effectors],
        "virtual_joints": [_virtual_joint(v) for v in d.srdf.virtual_joints],
        "states": [_state(s, d.robot, links) for s in d.states],
        "motions": [_motion(m) for m in d.motions],
        "matrix": None if matrix is None else {"svg": matrix.svg, **_matrix(matrix.described)},
    }


def b64(array: np.ndarray, dtype: str) -> str:
    """`array` as base64 of little-endian `dtype` ('<f4' or '<u4') bytes."""
    return base64.b64encode(np.ascontiguousarray(array, dtype=dtype).tobytes()).decode("ascii")


def _geometry(geometry: RobotGeometry) -> dict:
    return {
        "links": [{"name": name, "shapes": [_shape(s) for s in shapes]} for name, shapes in geometry.links],
        "meshes": [
            {
                "positions": b64(m.positions, "<f4"),
                "indices": b64(m.indices, "<u4"),
                "faces": int(len(m.indices)),
                "faces_before": m.faces_before,
            }
            for m in geometry.meshes
        ],
    }


def _shape(shape: Shape) -> dict:
    out: dict = {"kind": shape.kind, "origin": [round(x, 9) for x in shape.origin]}
    if shape.mesh is None:
        out["size"] = list(shape.size)
    else:
        out["mesh"] = shape.mesh
    return out


def _groups(srdf: Srdf, robot: RobotModel) -> list[dict]:
    """Each group (SRDF order) with its links; a group whose members the URDF lacks gets the
    links it could find (validate reports the rest)."""
    by_name = groups_by_name(srdf.groups)
    out = []
    for group in srdf.groups:
        try:
            links = [name for name in group_links(group, by_name, robot) if name in robot.link_map]
        except (KeyError, ValueError):
            links = [name for name in group.links if name in robot.link_map]
        out.append({"name": group.name, "links": links, "subgroups": list(group.subgroups)})
    return out


def _end_effector(e: EndEffector) -> dict:
    return {"name": e.name, "group": e.group, "parent_link": e.parent_link, "parent_group": e.parent_group}


def _virtual_joint(v: VirtualJoint) -> dict:
    return {"name": v.name, "type": v.type, "parent_frame": v.parent_frame, "child_link": v.child_link}


def _state(state: RobotState, robot: RobotModel, links: tuple[str, ...]) -> dict:
    return {
        "key": state.key,
        "title": state.title,
        "group": state.group,
        "frames": b64(link_frames(robot, state.q, links), "<f4"),
        "contacts": [list(pair) for pair in state.contacts],
        "note": state.note,
        "joints": {
            name: round(float(v), 6) for name, v in zip(robot.active_joint_names, state.q, strict=True)
        },
    }


def _motion(motion: Motion) -> dict:
    return {
        "group": motion.group,
        "start": motion.start,
        "goal": motion.goal,
        "problem": motion.problem,
        "duration": round(motion.duration, 6),
        "times": b64(motion.times, "<f4"),
        "still": b64(motion.still, "<f4"),
        "moving": list(motion.moving),
        "frames": b64(motion.frames, "<f4"),
    }


def _finding(index: int, finding: Finding) -> dict:
    out = finding_dict(finding)
    out["state"] = f"finding:{index}" if finding.evidence is not None else None
    return out


def _matrix(described: dict) -> dict:
    keys = ("trials", "seed", "never_bound_95", "hit_counts", "counts", "prove", "proofs", "pairs")
    return {key: described[key] for key in keys}

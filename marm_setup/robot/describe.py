"""Human and machine descriptions of a RobotModel (for `marm-setup inspect`)."""

from __future__ import annotations

from marm_setup.robot.model import Box, Cylinder, Geometry, Joint, Mesh, RobotModel, Sphere


def describe_geometry(geometry: Geometry) -> str:
    if isinstance(geometry, Box):
        return "box " + " x ".join(f"{v:g}" for v in geometry.size)
    if isinstance(geometry, Cylinder):
        return f"cylinder r={geometry.radius:g} l={geometry.length:g}"
    if isinstance(geometry, Sphere):
        return f"sphere r={geometry.radius:g}"
    assert isinstance(geometry, Mesh)
    scale = (
        "" if geometry.scale == (1.0, 1.0, 1.0) else f" scale={' '.join(f'{s:g}' for s in geometry.scale)}"
    )
    return f"mesh {geometry.uri}{scale}"


def describe_joint(joint: Joint) -> str:
    """One line: `name (type [lower, upper] vel v, mimics leader)`."""
    parts = [joint.type]
    if joint.lower is not None and joint.upper is not None and joint.type != "continuous":
        parts.append(f"[{joint.lower:g}, {joint.upper:g}]")
    if joint.velocity is not None and joint.is_actuated:
        parts.append(f"vel {joint.velocity:g}")
    if joint.mimic is not None:
        m = joint.mimic
        parts.append(f"mimics {m.joint} x{m.multiplier:g}{f' {m.offset:+g}' if m.offset else ''}")
    return f"{joint.name} ({' '.join(parts)})"


def _link_label(robot: RobotModel, name: str) -> str:
    link = robot.link(name)
    if not link.has_geometry:
        return f"{name} [no collision geometry]"
    return f"{name} [{', '.join(describe_geometry(c.geometry) for c in link.collisions)}]"


MAX_INDENT = 30  # levels drawn as indentation; deeper joints say their depth instead


def format_tree(robot: RobotModel) -> str:
    """The kinematic tree as indented text, plus a summary line. Indentation stops growing at
    MAX_INDENT levels (a 20,000-link chain would otherwise print 600 MB of spaces): deeper
    lines carry their depth, `[depth 31]`."""
    lines = [f"robot {robot.name}", _link_label(robot, robot.root)]

    stack = [(joint, 0) for joint in reversed(robot.child_joints_of[robot.root])]
    while stack:  # depth first, iterative: a 1,000-link chain is fine
        joint, depth = stack.pop()
        mark = f"[depth {depth + 1}] " if depth >= MAX_INDENT else ""
        indent = "   " * min(depth, MAX_INDENT)
        lines.append(f"{indent}{mark}└─ {describe_joint(joint)} -> {_link_label(robot, joint.child)}")
        stack.extend((j, depth + 1) for j in reversed(robot.child_joints_of[joint.child]))
    lines += [f"package {name}: {path} (found by {how})" for name, path, how in robot.packages]
    n_mimic = sum(1 for j in robot.joints if j.mimic is not None)
    lines.append(
        f"{len(robot.links)} links ({len(robot.geometry_links)} with collision geometry), "
        f"{len(robot.joints)} joints ({len(robot.active_joints)} active, {n_mimic} mimic)"
    )
    return "\n".join(lines)


def describe_robot(robot: RobotModel) -> dict:
    """A JSON-ready dict of the tree."""
    return {
        "name": robot.name,
        "root": robot.root,
        "active_joints": list(robot.active_joint_names),
        "packages": [{"name": n, "path": p, "found_by": how} for n, p, how in robot.packages],
        "links": [
            {
                "name": link.name,
                "collision": [describe_geometry(c.geometry) for c in link.collisions],
            }
            for link in robot.links
        ],
        "joints": [
            {
                "name": j.name,
                "type": j.type,
                "parent": j.parent,
                "child": j.child,
                "lower": j.lower,
                "upper": j.upper,
                "velocity": j.velocity,
                "mimic": None
                if j.mimic is None
                else {
                    "joint": j.mimic.joint,
                    "multiplier": j.mimic.multiplier,
                    "offset": j.mimic.offset,
                },
            }
            for j in robot.joints
        ],
    }

"""SRDF vs URDF: the shared rule set of `setup.rules` (names, chains, subgroup cycles, poses,
end effectors, virtual and passive joints, disabled pairs), plus what only a file shows."""

from __future__ import annotations

from marm_setup.findings import Finding, error, warning
from marm_setup.package import SrdfFile
from marm_setup.robot import RobotModel
from marm_setup.setup import check_semantics, check_semantics_without_robot, srdf_element


def check_srdf(srdf_file: SrdfFile, robot: RobotModel) -> list[Finding]:
    """Every SRDF-vs-URDF rule, named pose values included (the SRDF must have been read)."""
    assert srdf_file.srdf is not None
    file = srdf_file.path
    out = check_semantics(srdf_file.srdf, robot, file, srdf_element)
    out += _duplicate_pairs(srdf_file)
    out += _nested_passive_joints(srdf_file, robot)
    return out


def check_srdf_without_robot(srdf_file: SrdfFile) -> list[Finding]:
    """The SRDF rules that need no robot (for a description only the run time gives)."""
    assert srdf_file.srdf is not None
    return check_semantics_without_robot(srdf_file.srdf, srdf_file.path, srdf_element) + _duplicate_pairs(
        srdf_file
    )


def _nested_passive_joints(srdf_file: SrdfFile, robot: RobotModel) -> list[Finding]:
    """A `<passive_joint>` inside a `<group>`: srdfdom model.cpp reads passive joints only as
    children of `<robot>` (`loadPassiveJoints`) and `loadGroups` skips unknown children, so the
    joint silently stays active: MoveIt plans for it and expects a controller and joint states
    (an error). For a mimic or fixed joint, which MoveIt never plans for, it is only a warning."""
    out = []
    for nested in srdf_file.nested_passive_joints:
        where = f"group[{nested.group}].passive_joint"
        active = nested.joint in robot.joint_map and robot.joint(nested.joint).is_active
        make = error if active else warning
        what = "the joint stays active" if active else "harmless here (not an active joint)"
        msg = f"passive_joint '{nested.joint}' inside a group is ignored by srdfdom: {what}"
        out.append(make("srdf.nested-passive-joint", srdf_file.path, where, msg, "move it under <robot>"))
    return out


def _duplicate_pairs(srdf_file: SrdfFile) -> list[Finding]:
    """`disable_collisions` pairs written more than once (in either order)."""
    return [
        warning(
            "srdf.duplicate-pair",
            srdf_file.path,
            f"disable_collisions[{a} {b}]",
            f"pair listed {n} times",
            hint="keep one entry (MoveIt uses the last reason)",
        )
        for a, b, n in srdf_file.duplicate_pairs
    ]

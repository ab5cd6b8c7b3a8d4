"""SRDF vs URDF: the shared rule set of `setup.rules` (names, chains, subgroup cycles, poses,
end effectors, virtual and passive joints, disabled pairs), plus what only a file shows."""

from __future__ import annotations

from marm_setup.bounded_read import XML_BYTES, FileTooLarge, read_text
from marm_setup.findings import Finding, error, warning
from marm_setup.package import MoveItPackage, SrdfFile
from marm_setup.robot import RobotModel
from marm_setup.setup import check_semantics, check_semantics_without_robot, srdf_element


def check_srdf(srdf_file: SrdfFile, robot: RobotModel, virtual_tfs: bool = True) -> list[Finding]:
    """Every SRDF-vs-URDF rule, named pose values included (the SRDF must have been read);
    `virtual_tfs`: a launch file publishes the virtual joints' transforms."""
    assert srdf_file.srdf is not None
    file = srdf_file.path
    out = check_semantics(srdf_file.srdf, robot, file, srdf_element, virtual_tfs)
    out += _duplicate_pairs(srdf_file)
    out += _nested_passive_joints(srdf_file, robot)
    return out


STATIC_TF_WORDS = ("static_transform_publisher", "static_virtual_joint_tfs")


def publishes_static_tfs(pkg: MoveItPackage) -> bool:
    """A launch file of the package starts a static_transform_publisher (the Setup Assistant's
    MoveIt 1 demo.launch `virtual_joint_broadcaster_N`) or runs or includes MoveIt 2's
    static_virtual_joint_tfs launch (moveit_configs_utils launches.py: one publisher per virtual
    joint, parent_frame to child_link; generate_demo_launch includes it when the file exists).
    A launch file that could not be read counts as one that does."""
    for launch in pkg.launch:
        if launch.root is None:
            return True
        for element in launch.root.iter():
            if any(word in str(value) for value in element.attrib.values() for word in STATIC_TF_WORDS):
                return True
    for rel in pkg.python_launch_files:
        try:
            text = read_text(pkg.path(rel), XML_BYTES)
        except (OSError, UnicodeDecodeError, FileTooLarge):
            return True
        if any(word in text for word in STATIC_TF_WORDS):
            return True
    return False


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

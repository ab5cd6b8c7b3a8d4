"""Small synthetic robots with primitive geometry for inference tests (fixtures/synthetic/*.urdf).

`python -m tests.synthetic_robots` rewrites the fixture files; a test checks they are current.
Each robot is built from the same parts: a box body, arms of cylinders with a two-finger gripper,
legs, a head, wheels; joint and link names follow common conventions (left_/right_, L/R, LF_).
"""

from __future__ import annotations

from pathlib import Path

FOLDER = Path(__file__).resolve().parent.parent / "fixtures" / "synthetic"
LIMIT = '<limit lower="{lo}" upper="{hi}" velocity="1.0" effort="10"/>'


def _link(name: str, geometry: str = "", xyz: str = "0 0 0") -> str:
    if not geometry:
        return f'<link name="{name}"/>'
    return (
        f'<link name="{name}"><collision><origin xyz="{xyz}"/><geometry>{geometry}</geometry>'
        f"</collision></link>"
    )


def _joint(name, kind, parent, child, xyz="0 0 0", axis="0 0 1", lo=-2.0, hi=2.0, mimic=None) -> str:
    limit = LIMIT.format(lo=lo, hi=hi) if kind in ("revolute", "prismatic") else ""
    limit = '<limit velocity="1.0" effort="10"/>' if kind == "continuous" else limit
    mimic_xml = f'<mimic joint="{mimic}"/>' if mimic else ""
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}"/><axis xyz="{axis}"/>{limit}{mimic_xml}</joint>'
    )


def _cyl(length: float, radius: float = 0.03) -> tuple[str, str]:
    return f'<cylinder radius="{radius}" length="{length}"/>', f"0 0 {length / 2}"


def arm(joint_names: list[str], link_prefix: str, parent: str, xyz: str, gripper: str | None) -> list[str]:
    """A serial arm of cylinders (axes alternate z / y), a tool frame, and a two-finger gripper."""
    out, prev = [], parent
    for i, name in enumerate(joint_names):
        link = f"{link_prefix}link{i + 1}"
        geometry, center = _cyl(0.15)
        out.append(_link(link, geometry, center))
        axis = "0 0 1" if i % 2 == 0 else "0 1 0"
        out.append(_joint(name, "revolute", prev, link, xyz if i == 0 else "0 0 0.17", axis))
        prev = link
    out.append(_link(f"{link_prefix}tool0"))
    out.append(_joint(f"{link_prefix}tool0_joint", "fixed", prev, f"{link_prefix}tool0", "0 0 0.17"))
    if gripper:
        out += _gripper(gripper, f"{link_prefix}tool0")
    return out


def _gripper(prefix: str, parent: str) -> list[str]:
    box = '<box size="0.04 0.1 0.02"/>'
    finger = '<box size="0.01 0.01 0.04"/>'
    out = [_link(f"{prefix}base", box, "0 0 0.01")]
    out.append(_joint(f"{prefix}base_joint", "fixed", parent, f"{prefix}base", "0 0 0.0"))
    for side, y, mimic in (("left", 0.03, None), ("right", -0.03, f"{prefix}finger_left_joint")):
        link = f"{prefix}finger_{side}"
        out.append(_link(link, finger, "0 0 0.03"))
        axis = "0 1 0" if side == "left" else "0 -1 0"
        out.append(
            _joint(
                f"{prefix}finger_{side}_joint",
                "prismatic",
                f"{prefix}base",
                link,
                f"0 {y} 0.02",
                axis,
                0.0,
                0.02,
                mimic,
            )
        )
    return out


def leg(joint_names: list[str], link_prefix: str, parent: str, xyz: str) -> list[str]:
    """A leg hanging down: cylinders along -z."""
    out, prev = [], parent
    for i, name in enumerate(joint_names):
        link = f"{link_prefix}{['hip', 'thigh', 'shank', 'ankle', 'foot', 'toe'][i]}"
        geometry = '<cylinder radius="0.03" length="0.12"/>'
        out.append(_link(link, geometry, "0 0 -0.06"))
        axis = ("0 0 1", "1 0 0", "0 1 0", "0 1 0", "1 0 0", "0 1 0")[i]
        out.append(_joint(name, "revolute", prev, link, xyz if i == 0 else "0 0 -0.14", axis, -1.0, 1.0))
        prev = link
    return out


def _robot(name: str, parts: list[str]) -> str:
    body = "\n  ".join(parts)
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n  {body}\n</robot>\n'


def dual_arm_table() -> str:
    parts = [_link("table", '<box size="1.0 1.2 0.05"/>', "0 0 -0.025")]
    for side, y in (("left", 0.35), ("right", -0.35)):
        parts += arm(
            [f"{side}_arm_joint{i}" for i in range(1, 7)],
            f"{side}_arm_",
            "table",
            f"0 {y} 0.0",
            f"{side}_gripper_",
        )
    return _robot("dual_arm_table", parts)


def humanoid() -> str:
    parts = [_link("pelvis", '<box size="0.2 0.3 0.1"/>')]
    parts += [_link("waist_link", '<cylinder radius="0.05" length="0.05"/>', "0 0 0.05")]
    parts.append(_joint("waist_yaw", "revolute", "pelvis", "waist_link", "0 0 0.08", "0 0 1", -1.0, 1.0))
    parts += [_link("chest", '<box size="0.18 0.3 0.25"/>', "0 0 0.15")]
    parts.append(_joint("waist_pitch", "revolute", "waist_link", "chest", "0 0 0.1", "0 1 0", -0.5, 0.5))
    parts += [_link("neck", '<cylinder radius="0.03" length="0.05"/>', "0 0 0.025")]
    parts.append(_joint("HeadYaw", "revolute", "chest", "neck", "0 0 0.32", "0 0 1", -1.5, 1.5))
    parts += [_link("head", '<sphere radius="0.08"/>', "0 0 0.1")]
    parts.append(_joint("HeadPitch", "revolute", "neck", "head", "0 0 0.05", "0 1 0", -0.5, 0.5))
    for side, y in (("L", 0.22), ("R", -0.22)):
        names = [
            f"{side}ShoulderPitch",
            f"{side}ShoulderRoll",
            f"{side}ElbowYaw",
            f"{side}ElbowRoll",
            f"{side}WristYaw",
        ]
        parts += _side_arm(names, f"{side}Arm", f"0 {y} 0.25", f"{side}Hand")
    for side, y in (("L", 0.1), ("R", -0.1)):
        names = [
            f"{side}HipYaw",
            f"{side}HipRoll",
            f"{side}HipPitch",
            f"{side}KneePitch",
            f"{side}AnklePitch",
            f"{side}AnkleRoll",
        ]
        parts += leg(names, f"{side}Leg_", "pelvis", f"0 {y} -0.06")
    return _robot("humanoid", parts)


def _side_arm(names: list[str], prefix: str, xyz: str, hand: str) -> list[str]:
    """A humanoid arm hanging sideways from the chest: cylinders along y."""
    out = arm(names, f"{prefix}_", "chest", xyz, f"{hand}_")
    return out


def legged_arm() -> str:
    parts = [_link("base", '<box size="0.6 0.3 0.15"/>')]
    for code, x, y in (("LF", 0.25, 0.12), ("RF", 0.25, -0.12), ("LH", -0.25, 0.12), ("RH", -0.25, -0.12)):
        parts += leg([f"{code}_HAA", f"{code}_HFE", f"{code}_KFE"], f"{code}_", "base", f"{x} {y} -0.08")
    parts += arm([f"arm_joint{i}" for i in range(1, 7)], "arm_", "base", "0.1 0 0.08", "gripper_")
    return _robot("legged_arm", parts)


def wheeled_manipulator() -> str:
    parts = [_link("base_footprint"), _link("base_link", '<box size="0.5 0.4 0.2"/>', "0 0 0.1")]
    parts.append(_joint("base_joint", "fixed", "base_footprint", "base_link", "0 0 0.08"))
    for side, y in (("left", 0.23), ("right", -0.23)):
        parts.append(_link(f"{side}_wheel", '<cylinder radius="0.08" length="0.04"/>'))
        parts.append(
            _joint(f"{side}_wheel_joint", "continuous", "base_link", f"{side}_wheel", f"0 {y} 0", "0 1 0")
        )
    parts += [_link("torso_link", '<box size="0.1 0.1 0.1"/>', "0 0 0.05")]
    parts.append(
        _joint("torso_lift_joint", "prismatic", "base_link", "torso_link", "0 0 0.2", "0 0 1", 0.0, 0.3)
    )
    parts += arm([f"arm_joint{i}" for i in range(1, 7)], "arm_", "torso_link", "0 0 0.12", "gripper_")
    parts += [_link("camera_link", '<box size="0.03 0.1 0.03"/>')]
    parts.append(
        _joint("camera_tilt_joint", "revolute", "base_link", "camera_link", "0.2 0 0.25", "0 1 0", -0.5, 0.5)
    )
    return _robot("wheeled_manipulator", parts)


ROBOTS = {
    "dual_arm_table": dual_arm_table,
    "humanoid": humanoid,
    "legged_arm": legged_arm,
    "wheeled_manipulator": wheeled_manipulator,
}


def write_all() -> None:
    FOLDER.mkdir(parents=True, exist_ok=True)
    for name, build in ROBOTS.items():
        (FOLDER / f"{name}.urdf").write_text(build(), encoding="utf-8")


if __name__ == "__main__":
    write_all()

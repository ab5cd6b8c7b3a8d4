"""Small synthetic robots with primitive geometry for inference tests (fixtures/synthetic/*.urdf).

`python -m tests.synthetic_robots` rewrites the fixture files; a test checks they are current.
Each robot is built from the same parts: a box body, arms of cylinders with a two-finger gripper,
legs, a head, wheels; joint and link names follow common conventions (left_/right_, L/R, LF_,
FR/RR, RLEG_). Some robots carry a case that inference once got wrong: limbs without collision
geometry, a wrist whose link is called `gripper`, suspensions, a bare hand, rotors, feet on
fixed joints.
"""

from __future__ import annotations

from pathlib import Path

FOLDER = Path(__file__).resolve().parent.parent / "fixtures" / "synthetic"
LIMIT = '<limit lower="{lo}" upper="{hi}" velocity="1.0" effort="10"/>'


def _link(name: str, geometry: str = "", xyz: str = "0 0 0", tag: str = "collision") -> str:
    """A link with one `tag` (collision or visual) shape, or none without `geometry`."""
    if not geometry:
        return f'<link name="{name}"/>'
    return f'<link name="{name}"><{tag}><origin xyz="{xyz}"/><geometry>{geometry}</geometry></{tag}></link>'


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


def unitree_quadruped() -> str:
    """Legs named FR/FL/RR/RL (front/rear first, then the side), each ending in a foot link with
    a sphere on a fixed joint."""
    parts = [_link("base"), _link("trunk", '<box size="0.4 0.2 0.1"/>')]
    parts.append(_joint("floating_base", "fixed", "base", "trunk"))
    parts += [_link("imu_link"), _joint("imu_joint", "fixed", "trunk", "imu_link")]
    for code, x, y in (("FR", 0.18, -0.05), ("FL", 0.18, 0.05), ("RR", -0.18, -0.05), ("RL", -0.18, 0.05)):
        parts += leg(
            [f"{code}_hip_joint", f"{code}_thigh_joint", f"{code}_calf_joint"],
            f"{code}_",
            "trunk",
            f"{x} {y} 0",
        )
        parts.append(_link(f"{code}_foot", '<sphere radius="0.02"/>'))
        parts.append(_joint(f"{code}_foot_fixed", "fixed", f"{code}_shank", f"{code}_foot", "0 0 -0.14"))
    return _robot("unitree_quadruped", parts)


def bare_humanoid() -> str:
    """A humanoid whose limbs have no collision geometry (arms and head only visual shapes, legs
    none), soles among sensor frames, and a pan-tilt camera mount that is no limb."""
    parts = [_link("base_link"), _link("BODY", '<box size="0.2 0.3 0.2"/>')]
    parts.append(_joint("waist", "fixed", "base_link", "BODY"))
    for side, y in (("R", -0.1), ("L", 0.1)):
        names = ["HIP_R", "HIP_P", "HIP_Y", "KNEE", "ANKLE_P", "ANKLE_R"]
        parts += _bare_chain([f"{side}LEG_{n}" for n in names], f"{side}LEG_LINK", "BODY", f"0 {y} -0.1", "")
        ankle, low = f"{side}LEG_LINK6", side.lower()
        for frame in (f"{low}_sole", f"{side}Fsr_frame", f"{side}FootBumper_frame"):
            parts += [_link(frame), _joint(f"{frame}_joint", "fixed", ankle, frame, "0 0 -0.05")]
    parts += _bare_chain(["WAIST_P", "WAIST_R", "CHEST"], "WAIST_LINK", "BODY", "0 0 0.1", "", "chest")
    parts += _bare_chain(["NECK_Y", "NECK_P"], "NECK_LINK", "chest", "0 0 0.3", '<sphere radius="0.08"/>')
    for side, y in (("R", -0.2), ("L", 0.2)):
        names = ["SHOULDER_P", "SHOULDER_R", "SHOULDER_Y", "ELBOW", "WRIST_Y", "WRIST_P"]
        geometry = '<cylinder radius="0.03" length="0.1"/>'
        parts += _bare_chain(
            [f"{side}ARM_{n}" for n in names], f"{side}ARM_LINK", "chest", f"0 {y} 0.25", geometry
        )
    parts += _bare_chain(["pan_joint", "tilt_joint"], "ptu_link", "chest", "0.1 0 0.3", "")
    return _robot("bare_humanoid", parts)


def _bare_chain(joint_names, link_prefix, parent, xyz, visual, last=""):
    """A chain of revolute joints along -z whose links have at most a visual shape."""
    out, prev = [], parent
    for i, name in enumerate(joint_names):
        link = last if last and i == len(joint_names) - 1 else f"{link_prefix}{i + 1}"
        out.append(_link(link, visual, tag="visual"))
        axis = ("0 0 1", "1 0 0", "0 1 0")[i % 3]
        out.append(_joint(name, "revolute", prev, link, xyz if i == 0 else "0 0 -0.1", axis, -1.0, 1.0))
        prev = link
    return out


def wrist_gripper_arm() -> str:
    """A five-joint arm whose wrist_roll joint moves a link called `gripper`; the one-joint jaw
    after it is the gripper."""
    parts = [_link("base", '<box size="0.1 0.1 0.05"/>')]
    names = ["shoulder_pan", "shoulder_lift", "elbow_flex", "wrist_flex", "wrist_roll"]
    links = ["shoulder", "upper_arm", "lower_arm", "wrist", "gripper"]
    prev = "base"
    for i, (name, link) in enumerate(zip(names, links, strict=True)):
        geometry, center = _cyl(0.1)
        parts.append(_link(link, geometry, center))
        parts.append(
            _joint(
                name,
                "revolute",
                prev,
                link,
                "0 0 0.05" if i == 0 else "0 0 0.12",
                "0 1 0" if i % 2 else "0 0 1",
            )
        )
        prev = link
    parts += [
        _link("gripper_frame"),
        _joint("gripper_frame_joint", "fixed", "gripper", "gripper_frame", "0 0 0.15"),
    ]
    parts.append(_link("jaw", '<box size="0.01 0.02 0.06"/>', "0 0 0.03"))
    parts.append(_joint("gripper", "revolute", "gripper", "jaw", "0.02 0 0.1", "0 1 0", 0.0, 1.0))
    return _robot("wrist_gripper_arm", parts)


def suspended_base() -> str:
    """A wheeled base whose drive wheels sit on prismatic suspensions, casters of two joints, and a
    lifting torso with an arm."""
    parts = [_link("base_footprint"), _link("base_link", '<box size="0.5 0.4 0.2"/>', "0 0 0.1")]
    parts.append(_joint("base_footprint_joint", "fixed", "base_footprint", "base_link", "0 0 0.08"))
    for side, y in (("right", -0.23), ("left", 0.23)):
        parts += [_link(f"suspension_{side}_link")]
        parts.append(
            _joint(
                f"suspension_{side}_joint",
                "prismatic",
                "base_link",
                f"suspension_{side}_link",
                f"0 {y} 0",
                "0 0 1",
                -0.02,
                0.02,
            )
        )
        parts.append(_link(f"wheel_{side}_link", '<cylinder radius="0.08" length="0.04"/>'))
        parts.append(
            _joint(
                f"wheel_{side}_joint",
                "continuous",
                f"suspension_{side}_link",
                f"wheel_{side}_link",
                axis="0 1 0",
            )
        )
    parts += [_link("caster_1_link"), _link("caster_2_link", '<sphere radius="0.03"/>')]
    parts.append(_joint("caster_1_joint", "continuous", "base_link", "caster_1_link", "-0.2 0 -0.03"))
    parts.append(
        _joint("caster_2_joint", "continuous", "caster_1_link", "caster_2_link", "-0.02 0 -0.02", "0 1 0")
    )
    parts += [_link("torso_lift_link", '<box size="0.1 0.1 0.1"/>', "0 0 0.05")]
    parts.append(
        _joint("torso_lift_joint", "prismatic", "base_link", "torso_lift_link", "0 0 0.2", "0 0 1", 0.0, 0.3)
    )
    parts += arm([f"arm_{i}_joint" for i in range(1, 7)], "arm_", "torso_lift_link", "0 0 0.12", "gripper_")
    return _robot("suspended_base", parts)


def finger_hand() -> str:
    """A bare four-finger hand: unnamed four-joint fingers on a palm."""
    parts = [_link("palm", '<box size="0.1 0.1 0.02"/>')]
    for f, y in enumerate((-0.045, -0.015, 0.015, 0.045)):
        parts += _finger(f, "palm", f"0 {y} 0.01")
    return _robot("finger_hand", parts)


def _finger(number: int, parent: str, xyz: str) -> list[str]:
    out, prev = [], parent
    for i in range(4):
        index = 4 * number + i
        geometry, center = _cyl(0.03, 0.008)
        out.append(_link(f"link_{index}", geometry, center))
        axis = "0 0 1" if i == 0 else "0 1 0"
        out.append(
            _joint(
                f"joint_{index}",
                "revolute",
                prev,
                f"link_{index}",
                xyz if i == 0 else "0 0 0.035",
                axis,
                -0.5,
                1.5,
            )
        )
        prev = f"link_{index}"
    out += [
        _link(f"link_{4 * number + 3}_tip"),
        _joint(f"joint_{4 * number + 3}_tip", "fixed", prev, f"link_{4 * number + 3}_tip", "0 0 0.03"),
    ]
    return out


def rotor_arm() -> str:
    """A quadrotor body (four continuous rotor joints) carrying a two-joint arm."""
    parts = [_link("body", '<box size="0.3 0.3 0.08"/>')]
    for i, (x, y) in enumerate(((0.2, 0.2), (-0.2, 0.2), (-0.2, -0.2), (0.2, -0.2))):
        parts.append(_link(f"rotor_{i}", '<cylinder radius="0.1" length="0.01"/>'))
        parts.append(_joint(f"rotor_{i}_joint", "continuous", "body", f"rotor_{i}", f"{x} {y} 0.06"))
    for i, parent in ((1, "body"), (2, "link1")):
        geometry, center = _cyl(0.12, 0.015)
        parts.append(_link(f"link{i}", geometry, f"0 0 -{center.split()[-1]}"))
        parts.append(
            _joint(
                f"arm_joint{i}",
                "revolute",
                parent,
                f"link{i}",
                "0 0 -0.06" if i == 1 else "0 0 -0.13",
                "0 1 0",
                -1.5,
                1.5,
            )
        )
    parts += [_link("ee"), _joint("ee_joint", "fixed", "link2", "ee", "0 0 -0.13")]
    return _robot("rotor_arm", parts)


ROBOTS = {
    "dual_arm_table": dual_arm_table,
    "humanoid": humanoid,
    "legged_arm": legged_arm,
    "wheeled_manipulator": wheeled_manipulator,
    "unitree_quadruped": unitree_quadruped,
    "bare_humanoid": bare_humanoid,
    "wrist_gripper_arm": wrist_gripper_arm,
    "suspended_base": suspended_base,
    "finger_hand": finger_hand,
    "rotor_arm": rotor_arm,
}


def write_all() -> None:
    FOLDER.mkdir(parents=True, exist_ok=True)
    for name, build in ROBOTS.items():
        (FOLDER / f"{name}.urdf").write_text(build(), encoding="utf-8")


if __name__ == "__main__":
    write_all()

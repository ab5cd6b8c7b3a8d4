"""joint_limits rules read values as MoveIt does (keep-one-thing / break-one-thing on a small
copy of the real panda joint_limits.yaml, for the real panda robot)."""

from __future__ import annotations

from marm_setup.package.files import located_text
from marm_setup.package.joint_limits_file import read_joint_limits
from marm_setup.validate.rules.limits_rules import check_joint_limits

# config/joint_limits.yaml of the shared MoveIt 1 panda package (two joints of it)
PANDA_LIMITS = """
default_velocity_scaling_factor: 0.1
default_acceleration_scaling_factor: 0.1
joint_limits:
  panda_joint1:
    has_velocity_limits: true
    max_velocity: 2.1750
    has_acceleration_limits: true
    max_acceleration: 3.75
  panda_joint2:
    has_velocity_limits: true
    max_velocity: 2.1750
    has_acceleration_limits: true
    max_acceleration: 1.875
"""


def found(text: str, panda1, target: str = "ros1", pilz: bool = False):
    srdf, robot = panda1
    limits = read_joint_limits(located_text(text, "config/joint_limits.yaml"))
    return [
        (f.rule, f.severity, f.element)
        for f in check_joint_limits(limits, srdf, robot, target, pilz=pilz)
        if f.rule != "limits.missing-joint"  # the copy holds two joints only
    ]


def test_the_copy_is_clean(panda1):
    assert found(PANDA_LIMITS, panda1) == []


def test_a_rounded_value_is_not_above_the_urdf(panda1):
    """2.3926 for the URDF's 2.3925 (as 2.0944 for 2.0943951): rounding, not a higher limit."""
    assert found(PANDA_LIMITS.replace("2.1750", "2.3926", 1), panda1) == []
    assert found(PANDA_LIMITS.replace("2.1750", "2.4", 1), panda1) == [
        ("limits.above-urdf", "warning", "joint_limits.panda_joint1.max_velocity")
    ]


SA_DEFAULT = "has_acceleration_limits: false\n    max_acceleration: 0"


def test_zero_acceleration_without_acceleration_limits_is_the_setup_assistant_default(panda1):
    text = PANDA_LIMITS.replace("has_acceleration_limits: true\n    max_acceleration: 3.75", SA_DEFAULT)
    assert found(text, panda1) == []
    # in ROS 2 MoveIt never reads max_acceleration while has_acceleration_limits is false
    # (robot_model_loader.cpp jazzy l.211): the integer 0 is no finding
    assert found(text, panda1, "ros2") == []
    broken = PANDA_LIMITS.replace("max_acceleration: 3.75", "max_acceleration: 0")
    assert found(broken, panda1) == [
        ("limits.non-positive", "error", "joint_limits.panda_joint1.max_acceleration")
    ]
    assert ("limits.not-float", "error", "joint_limits.panda_joint1.max_acceleration") in found(
        broken, panda1, "ros2"
    )


def test_a_rate_no_trajectory_can_be_timed_with_is_an_error_without_planning(panda1):
    """1.0e-320 rad/s is positive, but times the 0.1 scaling it is below the planner's MIN_RATE:
    `validate --no-plan` reports it as init and the planner would (setup/limits.py)."""
    assert found(PANDA_LIMITS.replace("2.1750", "1.0e-320", 1), panda1) == [
        ("limits.untimeable", "error", "joint_limits.panda_joint1.max_velocity")
    ]
    # 5e-6 rad/s alone can be timed, not at the file's 0.1 scaling
    assert found(PANDA_LIMITS.replace("max_acceleration: 1.875", "max_acceleration: 5.0e-6"), panda1) == [
        ("limits.untimeable", "error", "joint_limits.panda_joint2.max_acceleration")
    ]
    unscaled = PANDA_LIMITS.replace("default_acceleration_scaling_factor: 0.1\n", "")
    assert found(unscaled.replace("max_acceleration: 1.875", "max_acceleration: 5.0e-6"), panda1) == []


def test_an_integer_counts_in_ros2_only_where_moveit_reads_a_double(panda1):
    """robot_model_loader.cpp (humble l.133-239, jazzy l.138-244) reads max/min_position always,
    each max_velocity / max_acceleration / max_jerk only under its true has_* flag, never
    max_effort; Pilz's copy of joint_limits_rosparam.hpp reads max_effort under its flag too."""
    joint = "joint_limits.panda_joint1"
    unread = PANDA_LIMITS.replace(
        "has_velocity_limits: true\n    max_velocity: 2.1750",
        "has_velocity_limits: false\n    max_velocity: 2\n    max_jerk: 300\n    max_effort: 87",
        1,
    )
    assert found(unread, panda1, "ros2") == []
    assert found(unread, panda1, "ros2", pilz=True) == []
    flagged = unread.replace("max_jerk: 300", "has_jerk_limits: true\n    max_jerk: 300").replace(
        "max_effort: 87", "has_effort_limits: true\n    max_effort: 87"
    )
    assert found(flagged, panda1, "ros2") == [("limits.not-float", "error", f"{joint}.max_jerk")]
    assert found(flagged, panda1, "ros2", pilz=True) == [
        ("limits.not-float", "error", f"{joint}.max_jerk"),
        ("limits.not-float", "error", f"{joint}.max_effort"),
    ]
    position = PANDA_LIMITS.replace(
        "has_velocity_limits: true", "max_position: 2\n    has_velocity_limits: true", 1
    )
    assert found(position, panda1, "ros2") == [("limits.not-float", "error", f"{joint}.max_position")]
    velocity = PANDA_LIMITS.replace("max_velocity: 2.1750", "max_velocity: 2", 1)
    assert found(velocity, panda1, "ros2") == [("limits.not-float", "error", f"{joint}.max_velocity")]
    # Pilz reads the positions only under has_position_limits: true, and then stops move_group
    srdf, robot = panda1

    def said(text: str) -> str:
        limits = read_joint_limits(located_text(text, "config/joint_limits.yaml"))
        (one,) = [
            f
            for f in check_joint_limits(limits, srdf, robot, "ros2", pilz=True)
            if f.rule == "limits.not-float"
        ]
        return one.message

    pilz_reads = position.replace("max_position: 2", "has_position_limits: true\n    max_position: 2")
    assert "Pilz" in said(pilz_reads) and "ParameterTypeException" in said(pilz_reads)
    assert "Pilz" not in said(position)
    # roscpp converts an integer to the double MoveIt 1 asks for (param.cpp getImpl(double&))
    assert found(flagged, panda1) == []
    unknown = PANDA_LIMITS + "  no_such_joint:\n    has_velocity_limits: true\n    max_velocity: 2\n"
    assert ("limits.not-float", "error", "joint_limits.no_such_joint.max_velocity") not in found(
        unknown, panda1, "ros2"
    )

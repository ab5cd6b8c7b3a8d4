"""Good packages validate clean: marm from `init` (both targets) and the real panda packages."""

from __future__ import annotations

import pytest

from marm_setup.validate import validate_package
from tests.validate_helpers import generate_marm, panda


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_marm_packages_validate_clean(tmp_path, target):
    assert validate_package(generate_marm(tmp_path, target), plan=False) == []


def _summary(findings):
    return sorted((f.severity, f.rule, f.file, f.element) for f in findings)


def test_panda_ros1_findings_are_the_known_real_ones():
    good = panda("ros1")
    found = validate_package(good.path, package_paths=good.package_paths, plan=False)
    assert _summary(found) == [
        # the collision meshes of link5 and link7 overlap with joint6 at 0 (about 0.07 rad to clear)
        ("error", "pose.collision", "config/panda.srdf", "group_state[transport]"),
        # the snapshot left out non-XML launch assets that the Setup Assistant writes
        ("warning", "launch.missing-file", "launch/demo.launch", "line 60: arg[rviz_config]"),
        ("warning", "launch.missing-file", "launch/move_group.launch", "line 7: arg[launch_prefix]"),
    ]


def test_panda_ros2_findings_are_the_known_real_ones():
    good = panda("ros2")
    found = validate_package(good.path, package_paths=good.package_paths, plan=False)
    assert _summary(found) == [
        ("error", "pose.collision", "config/panda_arm_hand.srdf.xacro", "group_state[transport]"),
        # moveit_controllers.yaml drives the arm only; the hand needs gripper_moveit_controllers.yaml
        (
            "warning",
            "controller.uncovered-joint",
            "config/moveit_controllers.yaml",
            "moveit_simple_controller_manager.joint[panda_finger_joint1]",
        ),
    ]


def test_validate_is_deterministic():
    good = panda("ros2")
    runs = [validate_package(good.path, package_paths=good.package_paths, plan=False) for _ in range(2)]
    assert runs[0] == runs[1]

"""A hand-built SetupModel for the marm fixture (what `init` infers), for render tests."""

from __future__ import annotations

import functools
from pathlib import Path

from marm_setup.robot import load_robot
from marm_setup.robot_model import RobotModel
from marm_setup.setup_model import (
    Chain,
    Controller,
    EndEffector,
    Group,
    GroupState,
    Kinematics,
    PlannerDefaults,
    RobotSource,
    SetupModel,
    VirtualJoint,
)

ROOT = Path(__file__).resolve().parent.parent
MARM_URDF = ROOT / "fixtures" / "marm" / "urdf" / "marm.urdf.xacro"
MARM_SPEC = ROOT / "fixtures" / "marm" / "marm_setup.yaml"
ARM_JOINTS = ("joint1", "joint2", "joint3", "joint4", "joint5", "joint6")


def marm_model(target: str = "ros1", urdf: str = "../marm/urdf/marm.urdf.xacro") -> SetupModel:
    gripper_ns = "gripper_action" if target == "ros1" else "gripper_cmd"
    return SetupModel(
        package_name="marm_moveit_config",
        robot_name="marm",
        robot=RobotSource(urdf=urdf),
        target=target,
        virtual_joints=(VirtualJoint("virtual_joint", "fixed", "world", "base_link"),),
        groups=(
            Group("arm", chain=Chain("base_link", "grasping_frame")),
            Group(
                "gripper",
                joints=("finger_joint1", "finger_joint2"),
                links=("gripper_finger_link1", "gripper_finger_link2"),
            ),
        ),
        group_states=(
            GroupState(
                "forward",
                "arm",
                tuple(zip(ARM_JOINTS, (0.0, 0.4285, 0.7672, 0.0, -0.4487, 0.0), strict=True)),
            ),
            GroupState("home", "arm", tuple((j, 0.0) for j in ARM_JOINTS)),
        ),
        end_effectors=(EndEffector("robot_gripper", "gripper", "grasping_frame", "arm"),),
        kinematics=(Kinematics("arm"),),
        planners=(PlannerDefaults("arm"), PlannerDefaults("gripper")),
        controllers=(
            Controller(
                "arm_controller", "FollowJointTrajectory", "follow_joint_trajectory", ARM_JOINTS, "arm"
            ),
            Controller("gripper_controller", "GripperCommand", gripper_ns, ("finger_joint1",), "gripper"),
        ),
    )


def inferred_marm(target: str, out: Path) -> tuple[SetupModel, RobotModel]:
    """The marm setup as `init --setup fixtures/marm/marm_setup.yaml --out out` builds it.

    The collision matrix is left empty: render tests check templates, not sampling.
    """
    return _inferred(target, str(out))


@functools.lru_cache(maxsize=8)
def _inferred(target: str, out: str) -> tuple[SetupModel, RobotModel]:
    from marm_setup.init_flow import InitRequest, build_setup

    robot = marm_robot()
    request = InitRequest(urdf=MARM_URDF, out=Path(out), target=target, spec=MARM_SPEC)
    return build_setup(request, robot), robot


@functools.lru_cache(maxsize=1)
def marm_robot() -> RobotModel:
    return load_robot(MARM_URDF)

"""MoveIt Servo in the setup: default servos per arm group, what each resolves to, the checks of
the `servo` key (each error names its key path), and the files it renders."""

from __future__ import annotations

import dataclasses

import pytest
import yaml
from lxml import etree

from marm_setup.errors import InputError
from marm_setup.flows import InitRequest, RobotInput, build_setup
from marm_setup.robot.load import load_robot
from marm_setup.setup.checks import check_setup
from marm_setup.setup.model import Controller, Kinematics, Ros2ControlHardware, Servo, ServoScale
from marm_setup.setup.servo import default_servos, plan_servos
from marm_setup.setup.yaml_io import dump_setup, setup_from_dict, setup_to_dict
from tests.conftest import FIXTURES
from tests.render_helpers import assert_check_error, assert_yaml_errors, marm_robot, marm_with, rendered_files


def test_the_marm_arm_gets_a_servo_by_default():
    model, robot = marm_with()
    assert default_servos(model, robot) == (Servo("arm"),)
    (plan,) = plan_servos(model, robot)
    # the planning frame is the link the arm's Jacobian is in (not the virtual joint's `world`,
    # no link of MoveIt's robot model), the end-effector frame the chain's tip
    assert (plan.planning_frame, plan.ee_frame, plan.command_frame) == (
        "base_link",
        "grasping_frame",
        "base_link",
    )
    assert plan.output_controller == "arm_controller" and plan.is_trajectory
    assert plan.joints == tuple(f"joint{i}" for i in range(1, 7))


@pytest.mark.parametrize(
    "urdf, expected",
    [
        ("humanoid.urdf", ["left_arm", "right_arm"]),  # no legs, head, torso or hands
        ("unitree_quadruped.urdf", []),
        ("dual_arm_table.urdf", ["left_arm", "right_arm"]),
        ("suspended_base.urdf", ["arm"]),
    ],
)
def test_default_servos_are_the_arms(urdf, expected, tmp_path):
    path = FIXTURES / "synthetic" / urdf
    robot = load_robot(path)
    model = build_setup(InitRequest(RobotInput.parse(path), out=tmp_path / "pkg"), robot)
    assert [s.group for s in default_servos(model, robot)] == expected


def test_no_servo_key_is_the_default_and_an_empty_list_is_none():
    model, robot = marm_with("ros1", servo=())
    files = rendered_files(model, robot)
    assert not [p for p in files if "servo" in p]
    assert "moveit_servo" not in files["package.xml"]
    assert yaml.safe_load(files["marm_setup.yaml"])["servo"] == []
    default, _ = marm_with("ros1")
    assert "servo" not in yaml.safe_load(rendered_files(default, robot)["marm_setup.yaml"])


def test_servo_settings_round_trip_and_reach_the_file():
    servo = Servo(
        "arm",
        planning_frame="link1",
        ee_frame="link6",
        command_frame="grasping_frame",
        command_in_type="speed_units",
        scale=ServoScale(linear=0.2, rotational=0.3, joint=0.4),
        publish_period=0.02,
        check_collisions=False,
    )
    model, robot = marm_with("ros2", "humble", servo=(servo,))
    assert setup_from_dict(setup_to_dict(model)) == model
    check_setup(model, robot)
    params = yaml.safe_load(rendered_files(model, robot)["config/arm_servo.yaml"])["/**"]["ros__parameters"]
    servo_params = params["moveit_servo"]
    assert servo_params["planning_frame"] == "link1" and servo_params["ee_frame_name"] == "link6"
    assert servo_params["robot_link_command_frame"] == "grasping_frame"
    assert servo_params["scale"] == {"linear": 0.2, "rotational": 0.3, "joint": 0.4}
    assert servo_params["publish_period"] == 0.02 and servo_params["check_collisions"] is False
    assert servo_params["command_in_type"] == "speed_units"


def test_position_output_adds_an_inactive_forward_controller():
    model, robot = marm_with("ros2", "jazzy", servo=(Servo("arm", command_out="position"),))
    check_setup(model, robot)
    files = rendered_files(model, robot)
    for path, text in files.items():
        if path.endswith(".yaml"):
            yaml.safe_load(text)
        elif path.endswith((".xml", ".launch", ".xacro", ".srdf")):
            etree.fromstring(text.encode())
    controllers = yaml.safe_load(files["config/ros2_controllers.yaml"])
    manager = controllers["controller_manager"]["ros__parameters"]
    assert manager["arm_position_controller"]["type"] == "position_controllers/JointGroupPositionController"
    assert controllers["arm_position_controller"]["ros__parameters"]["joints"] == [
        f"joint{i}" for i in range(1, 7)
    ]
    demo = etree.fromstring(files["launch/demo.launch.xml"].encode())
    spawned = {
        n.get("args").split()[0]: n.get("args") for n in demo.iter("node") if n.get("exec") == "spawner"
    }
    assert "--inactive" in spawned["arm_position_controller"]
    assert "--inactive" not in spawned["arm_controller"]
    moveit = yaml.safe_load(files["config/moveit.yaml"])["/**"]["ros__parameters"]
    assert "arm_position_controller" not in moveit["moveit_simple_controller_manager"]["controller_names"]
    out = yaml.safe_load(files["config/arm_servo.yaml"])["/**"]["ros__parameters"]["moveit_servo"]
    assert out["command_out_type"] == "std_msgs/Float64MultiArray"
    assert out["command_out_topic"] == "/arm_position_controller/commands"
    assert (out["publish_joint_positions"], out["publish_joint_velocities"]) == (True, False)
    assert "<exec_depend>position_controllers</exec_depend>" in files["package.xml"]


GRIPPER_ONLY = (
    Controller("gripper_controller", "GripperCommand", "gripper_cmd", ("finger_joint1",), "gripper"),
)
SHORT_ARM = (
    Controller("arm_controller", "FollowJointTrajectory", "follow_joint_trajectory", ("joint1", "joint2")),
)
BAD = {
    "unknown group": (
        {"servo": (Servo("amr"),)},
        "servo[amr].group",
        "unknown group 'amr' (did you mean 'arm'?)",
    ),
    "not a chain": ({"servo": (Servo("gripper"),)}, "servo[gripper].group", "is not a chain"),
    "duplicate": ({"servo": (Servo("arm"), Servo("arm"))}, "servo[arm]", "duplicate servo for group 'arm'"),
    "world is no link": (
        {"servo": (Servo("arm", planning_frame="world"),)},
        "servo[arm].planning_frame",
        "'world' is not a link of the robot",
    ),
    "ee frame typo": (
        {"servo": (Servo("arm", ee_frame="grasping_fram"),)},
        "servo[arm].ee_frame",
        "did you mean 'grasping_frame'?",
    ),
    "unknown controller": (
        {"servo": (Servo("arm", controller="arm_ctrl"),)},
        "servo[arm].controller",
        "unknown controller 'arm_ctrl'",
    ),
    "gripper controller": (
        {"servo": (Servo("arm", controller="gripper_controller"),)},
        "servo[arm].controller",
        "is a GripperCommand controller",
    ),
    "no controller behind the output": (
        {"controllers": GRIPPER_ONLY, "servo": (Servo("arm"),)},
        "servo[arm].controller",
        "servo's output would reach no controller",
    ),
    "controller of other joints": (
        {"controllers": SHORT_ARM + GRIPPER_ONLY, "servo": (Servo("arm", controller="arm_controller"),)},
        "servo[arm].controller",
        "would reject servo's commands",
    ),
    "no position interface": (
        {
            "ros2_control": Ros2ControlHardware(command_interfaces=("velocity",)),
            "servo": (Servo("arm", command_out="position"),),
        },
        "servo[arm].command_out",
        "no 'position' command interface",
    ),
    "forward name taken": (
        {"servo": (Servo("arm", command_out="position", controller="gripper_controller"),)},
        "servo[arm].controller",
        "already names another controller",
    ),
    "zero scale": (
        {"servo": (Servo("arm", scale=ServoScale(linear=0.0)),)},
        "servo[arm].scale.linear",
        "must be > 0",
    ),
    "bad controller name": (
        {"servo": (Servo("arm", command_out="position", controller="arm position"),)},
        "servo[arm].controller",
        "not a valid controller name",
    ),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_servos_name_the_key(case):
    changes, element, message = BAD[case]
    assert_check_error(*marm_with("ros2", "humble", **changes), element, message)


def test_position_output_needs_ros2_control():
    model, robot = marm_with("ros1", servo=(Servo("arm", command_out="position"),))
    with pytest.raises(InputError, match="a ros1 package has none") as err:
        check_setup(model, robot)
    assert err.value.element == "servo[arm].command_out"


def test_jazzy_servo_needs_the_groups_ik_solver():
    model, robot = marm_with("ros2", "jazzy", servo=(Servo("arm"),), kinematics=())
    with pytest.raises(InputError, match="Jazzy's servo takes its planning and end-effector frames"):
        check_setup(model, robot)
    humble, _ = marm_with("ros2", "humble", servo=(Servo("arm"),), kinematics=())
    check_setup(humble, robot)  # humble's servo reads its frames from its parameters
    assert default_servos(dataclasses.replace(humble, servo=None), robot) == ()  # no solver: no arm


def test_yaml_errors_in_the_servo_key_name_the_path():
    model, _ = marm_with("ros2", "humble")
    cases = [
        (
            {"servo": [{"group": "arm", "scale": {"lineer": 1.0}}]},
            "servo[arm].scale.lineer",
            "did you mean 'linear'?",
        ),
        (
            {"servo": [{"group": "arm", "command_out": "positon"}]},
            "servo[arm].command_out",
            "did you mean 'position'?",
        ),
        (
            {"servo": [{"group": "arm", "command_in_type": "speed"}]},
            "servo[arm].command_in_type",
            "speed_units",
        ),
        ({"servo": [{"group": "arm", "planing_frame": "x"}]}, "servo[arm].planing_frame", "'planning_frame'"),
    ]
    assert_yaml_errors(model, cases)


def test_dump_of_default_servo_leaves_the_key_out():
    model, robot = marm_with()
    assert "servo" not in yaml.safe_load(dump_setup(model))
    explicit = dataclasses.replace(model, servo=(Servo("arm"),))
    assert yaml.safe_load(dump_setup(explicit))["servo"] == [{"group": "arm", "command_out": "trajectory"}]
    assert plan_servos(explicit, robot) == plan_servos(model, robot)


def test_a_servo_for_a_second_chain_with_its_own_controller():
    """A chain sub-arm (joint1..joint3) servoed through a controller of exactly its joints."""
    from marm_setup.setup.model import Chain, Group

    model, robot = marm_with("ros2", "humble")
    short = Group("shoulder", chain=Chain("base_link", "link3"))
    ctl = Controller(
        "shoulder_controller",
        "FollowJointTrajectory",
        "follow_joint_trajectory",
        ("joint1", "joint2", "joint3"),
    )
    model = dataclasses.replace(
        model,
        groups=(*model.groups, short),
        kinematics=(*model.kinematics, Kinematics("shoulder")),
        servo=(Servo("shoulder"),),
        controllers=(*model.controllers, ctl),
    )
    check_setup(model, robot)
    (plan,) = plan_servos(model, robot)
    assert (plan.output_controller, plan.ee_frame) == ("shoulder_controller", "link3")
    assert robot is marm_robot()

"""Small vendor-style MoveIt config packages written into a test's tmp_path (synthetic, in the
layouts published vendor packages use, none of them copied):

- `arg_selected`: MoveIt 1; the launch files pick the SRDF, joint limits and controllers with
  an arg (`config/$(arg dof)dof/default_joint_limits.yaml`, `config/$(arg dof)dof/controllers.yaml`),
  default scaling factors 1.0 and vendor controller names; a 6- and a 7-DOF variant.
- `python_launch`: MoveIt 2; a Python launch builds the config with MoveItConfigsBuilder
  (`.robot_description(mappings=...)`, `.joint_limits(file_path=...)`,
  `.planning_pipelines(pipelines=[...])`), MoveIt's controllers in `<robot>_controllers.yaml`
  next to `ros2_controllers.yaml`, TRAC-IK with its `solve_type`.
- `position_only`: MoveIt 1; a 4-DOF arm that can only reach positions (`position_only_ik: True`),
  one joint's velocity within rounding of the URDF's (0.99995 next to 1.0, as a vendor writes
  9.6 rad/s next to a URDF's radians(550) = 9.599311).
- `ros2_control_manager`: MoveIt 2; `moveit_controller_manager:
  moveit_ros_control_interface/Ros2ControlManager` and no controller list: MoveIt's controllers
  are the ros2_control ones (vendor names, a JointTrajectoryController and a
  GripperActionController); joint_6 has an acceleration limit only (the URDF's velocity stays).
- `hand_loaded`: MoveIt 2 without MoveItConfigsBuilder; its Python launch loads MoveIt's
  controller list by hand (`load_yaml(pkg, "config/hlarm_controllers.yaml")`) next to
  `config/hlarm_ros_controllers.yaml` (two `*_controllers.yaml`, neither named after the package's
  robot `hl`: no builder convention picks one).
- `own_wrapper`: MoveIt 2; the launch names the package's own ros2_control wrapper
  (`.robot_description(file_path="config/wr.urdf.xacro")`, as moveit_resources' fanuc does) and
  `.setup_assistant` the description it wraps.
- `footprint_parented`: MoveIt 1; the URDF's root is `base_footprint` (fixed to `base_link`), the
  SRDF's virtual joint `world -> base_link` names a link that already has a URDF parent: MoveIt
  skips it (its source demo.launch gave base_link two TF parents).

Each returns (package folder, package paths to pass).
"""

from __future__ import annotations

from pathlib import Path

from tests.helpers import build_file_tree
from tests.synthetic_robots import _robot, arm

CATKIN = """<?xml version="1.0"?>
<package format="2"><name>{name}</name><version>1.2.3</version><description>{name}</description>
<maintainer email="dev@vendor.example">Vendor Dev</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend></package>
"""
AMENT = """<?xml version="1.0"?>
<package format="3"><name>{name}</name><version>2.0.0</version><description>{name}</description>
<maintainer email="dev@vendor.example">Vendor Dev</maintainer><license>BSD-3-Clause</license>
<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake</build_type></export></package>
"""


def _joints(n: int) -> list[str]:
    return [f"joint_{i}" for i in range(1, n + 1)]


def _arm_urdf(name: str, dof: int, gripper: bool) -> str:
    parts = [
        '<link name="base_link"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>'
    ]
    parts += arm(_joints(dof), "", "base_link", "0 0 0.06", "gripper_" if gripper else None)
    return _robot(name, parts)


def _srdf(robot: str, dof: int, gripper: bool) -> str:
    joints = "".join(f'<joint name="{j}"/>' for j in _joints(dof))
    hand = '<group name="gripper"><joint name="gripper_finger_left_joint"/></group>' if gripper else ""
    zero = "".join(f'<joint name="{j}" value="0"/>' for j in _joints(dof))
    bent = "".join(
        f'<joint name="{j}" value="{0.3 if i % 2 else -0.2}"/>' for i, j in enumerate(_joints(dof))
    )
    return (
        f'<?xml version="1.0"?>\n<robot name="{robot}">\n  <group name="arm">{joints}</group>\n  {hand}\n'
        f'  <group_state name="home" group="arm">{zero}</group_state>\n'
        f'  <group_state name="bent" group="arm">{bent}</group_state>\n'
        '  <virtual_joint name="world_joint" type="fixed" parent_frame="world" child_link="base_link"/>\n'
        "</robot>\n"
    )


def _limits(dof: int, velocity: float, acceleration: float, scaling: float) -> str:
    rows = "".join(
        f"  {j}:\n    has_velocity_limits: true\n    max_velocity: {velocity}\n"
        f"    has_acceleration_limits: true\n    max_acceleration: {acceleration}\n"
        for j in _joints(dof)
    )
    return (
        f"default_velocity_scaling_factor: {scaling}\ndefault_acceleration_scaling_factor: {scaling}\n"
        f"joint_limits:\n{rows}"
    )


# -- MoveIt 1, files picked with an arg ---------------------------------------------------------------

CONTEXT = """<launch>
  <arg name="dof" default="6"/>
  <arg name="load_robot_description" default="false"/>
  <param if="$(arg load_robot_description)" name="robot_description"
         textfile="$(find vx_description)/urdf/vx$(arg dof).urdf"/>
  <param name="robot_description_semantic" textfile="$(find vx_moveit_config)/config/$(arg dof)dof/vx.srdf"/>
  <group ns="robot_description_planning">
    <rosparam command="load" file="$(find vx_moveit_config)/config/$(arg dof)dof/default_joint_limits.yaml"/>
  </group>
  <group ns="robot_description_kinematics">
    <rosparam command="load" file="$(find vx_moveit_config)/config/kinematics.yaml"/>
  </group>
</launch>
"""
MOVE_GROUP = """<launch>
  <arg name="dof" default="6"/>
  <include file="$(dirname)/planning_context.launch"><arg name="dof" value="$(arg dof)"/></include>
  <node name="move_group" pkg="moveit_ros_move_group" type="move_group">
    <include file="$(dirname)/trajectory_execution.launch.xml" pass_all_args="true"/>
  </node>
</launch>
"""
EXECUTION = """<launch>
  <arg name="dof"/>
  <param name="moveit_controller_manager" value="moveit_simple_controller_manager/MoveItSimpleControllerManager"/>
  <rosparam file="$(find vx_moveit_config)/config/$(arg dof)dof/controllers.yaml"/>
</launch>
"""
CONTROLLERS = """controller_list:
  - name: vx{dof}/arm_trajectory
    action_ns: follow_joint_trajectory
    type: FollowJointTrajectory
    default: true
    joints: [{joints}]
  - name: vx{dof}/gripper_command
    action_ns: gripper_cmd
    type: GripperCommand
    default: true
    joints: [gripper_finger_left_joint]
"""


def arg_selected(root: Path) -> tuple[Path, list[Path]]:
    """`vx_moveit_config` (MoveIt 1): SRDF, joint limits (0.41 rad/s, scaling 1.0) and
    controllers in `config/$(arg dof)dof/`, the dof arg 6 by default."""
    files = {"vx_description/package.xml": CATKIN.format(name="vx_description")}
    config = "vx_moveit_config"
    for dof in (6, 7):
        files[f"vx_description/urdf/vx{dof}.urdf"] = _arm_urdf("vx", dof, gripper=True)
        files[f"{config}/config/{dof}dof/vx.srdf"] = _srdf("vx", dof, gripper=True)
        files[f"{config}/config/{dof}dof/default_joint_limits.yaml"] = _limits(dof, 0.41, 1.2, 1.0)
        joints = ", ".join(_joints(dof))
        files[f"{config}/config/{dof}dof/controllers.yaml"] = CONTROLLERS.format(dof=dof, joints=joints)
    files.update(
        {
            f"{config}/package.xml": CATKIN.format(name=config),
            f"{config}/.setup_assistant": (
                "moveit_setup_assistant_config:\n  URDF:\n    package: vx_description\n"
                "    relative_path: urdf/vx6.urdf\n  SRDF:\n    relative_path: config/6dof/vx.srdf\n"
            ),
            f"{config}/config/kinematics.yaml": (
                "arm:\n  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n"
                "  kinematics_solver_search_resolution: 0.005\n  kinematics_solver_timeout: 0.05\n"
            ),
            f"{config}/launch/planning_context.launch": CONTEXT,
            f"{config}/launch/move_group.launch": MOVE_GROUP,
            f"{config}/launch/trajectory_execution.launch.xml": EXECUTION,
        }
    )
    build_file_tree(root, files)
    return root / config, [root]


# -- MoveIt 2, a Python launch and <robot>_controllers.yaml ------------------------------------------

LAUNCH_PY = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
from moveit_configs_utils import MoveItConfigsBuilder


def generate_launch_description():
    use_sim = LaunchConfiguration("use_sim")
    mappings = {"gripper": "true", "use_sim": use_sim, "robot_ip": LaunchConfiguration("robot_ip")}
    moveit_config = (
        MoveItConfigsBuilder("bot", package_name="bot_moveit_config")
        .robot_description(mappings=mappings)
        .joint_limits(file_path="config/limits/bot_joint_limits.yaml")
        .planning_pipelines(pipelines=["ompl"])
        .to_moveit_configs()
    )
    move_group = Node(package="moveit_ros_move_group", executable="move_group",
                      parameters=[moveit_config.to_dict()])
    return LaunchDescription([
        DeclareLaunchArgument("use_sim", default_value="false"),
        DeclareLaunchArgument("robot_ip"),
        move_group,
    ])
"""
BOT_CONTROLLERS = """moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager
moveit_simple_controller_manager:
  controller_names: [bot_arm_controller, bot_hand_controller]
  bot_arm_controller:
    type: FollowJointTrajectory
    action_ns: follow_joint_trajectory
    default: true
    joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6]
  bot_hand_controller:
    type: GripperCommand
    action_ns: gripper_cmd
    default: true
    joints: [gripper_finger_left_joint]
"""
ROS2_CONTROLLERS = """controller_manager:
  ros__parameters:
    update_rate: 100
    bot_arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
    bot_hand_controller:
      type: position_controllers/GripperActionController
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
bot_arm_controller:
  ros__parameters:
    joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6]
    command_interfaces: [position]
    state_interfaces: [position, velocity]
bot_hand_controller:
  ros__parameters:
    joint: gripper_finger_left_joint
"""
BOT_XACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="bot">
  <xacro:arg name="gripper" default="false"/>
  <xacro:arg name="use_sim" default="true"/>
  {body}
</robot>
"""


def python_launch(root: Path) -> tuple[Path, list[Path]]:
    """`bot_moveit_config` (MoveIt 2): MoveItConfigsBuilder in launch/move_group.launch.py,
    controllers in config/bot_controllers.yaml, limits in config/limits/, TRAC-IK."""
    body = _arm_urdf("bot", 6, gripper=True).split("\n", 2)[2].rsplit("</robot>", 1)[0]
    config = "bot_moveit_config"
    build_file_tree(
        root,
        {
            "bot_description/package.xml": AMENT.format(name="bot_description"),
            "bot_description/urdf/bot.urdf.xacro": BOT_XACRO.format(body=body),
            f"{config}/package.xml": AMENT.format(name=config),
            f"{config}/.setup_assistant": (
                "moveit_setup_assistant_config:\n  urdf:\n    package: bot_description\n"
                "    relative_path: urdf/bot.urdf.xacro\n  srdf:\n    relative_path: config/bot.srdf\n"
                "  package_settings:\n    author_name: Bot Maker\n    author_email: maker@bot.example\n"
            ),
            f"{config}/config/bot.srdf": _srdf("bot", 6, gripper=True),
            f"{config}/config/bot_controllers.yaml": BOT_CONTROLLERS,
            f"{config}/config/ros2_controllers.yaml": ROS2_CONTROLLERS,
            f"{config}/config/limits/bot_joint_limits.yaml": _limits(6, 0.8, 2.5, 0.5),
            f"{config}/config/kinematics.yaml": (
                "arm:\n  kinematics_solver: trac_ik_kinematics_plugin/TRAC_IKKinematicsPlugin\n"
                "  kinematics_solver_search_resolution: 0.005\n  kinematics_solver_timeout: 0.05\n"
                "  solve_type: Distance\n  epsilon: 1.0e-05\n"
            ),
            f"{config}/config/ompl_planning.yaml": (
                "planner_configs:\n  RRTConnectkConfigDefault:\n    type: geometric::RRTConnect\n"
                "arm:\n  planner_configs: [RRTConnectkConfigDefault]\n  default_planner_config: RRTConnectkConfigDefault\n"
            ),
            f"{config}/launch/move_group.launch.py": LAUNCH_PY,
        },
    )
    return root / config, [root]


# -- MoveIt 1, a 4-DOF arm with position-only IK -------------------------------------------------------


def position_only(root: Path) -> tuple[Path, list[Path]]:
    """`scara_moveit_config` (MoveIt 1 Setup Assistant layout, no launch files): a 4-DOF arm
    whose IK must ignore orientation (`position_only_ik: True`); joint_4's 0.99995 rad/s is
    within rounding of the URDF's 1.0 and must stay 0.99995."""
    config = "scara_moveit_config"
    build_file_tree(
        root,
        {
            "scara_description/package.xml": CATKIN.format(name="scara_description"),
            "scara_description/urdf/scara.urdf": _arm_urdf("scara", 4, gripper=False),
            f"{config}/package.xml": CATKIN.format(name=config),
            f"{config}/.setup_assistant": (
                "moveit_setup_assistant_config:\n  URDF:\n    package: scara_description\n"
                "    relative_path: urdf/scara.urdf\n  SRDF:\n    relative_path: config/scara.srdf\n"
                "  CONFIG:\n    author_name: Scara Dev\n    author_email: dev@scara.example\n"
            ),
            f"{config}/config/scara.srdf": _srdf("scara", 4, gripper=False),
            f"{config}/config/kinematics.yaml": (
                "arm:\n  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n"
                "  kinematics_solver_search_resolution: 0.005\n  kinematics_solver_timeout: 0.005\n"
                "  position_only_ik: True\n"
            ),
            f"{config}/config/joint_limits.yaml": _limits(4, 0.9, 3.0, 0.25).replace(
                "joint_4:\n    has_velocity_limits: true\n    max_velocity: 0.9",
                "joint_4:\n    has_velocity_limits: true\n    max_velocity: 0.99995",
            ),
            f"{config}/config/simple_moveit_controllers.yaml": (
                "controller_list:\n  - name: scara_controller\n    action_ns: follow_joint_trajectory\n"
                "    type: FollowJointTrajectory\n    default: true\n    joints: [joint_1, joint_2, joint_3, joint_4]\n"
            ),
        },
    )
    return root / config, [root]


KDL = (
    "arm:\n  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n"
    "  kinematics_solver_search_resolution: 0.005\n  kinematics_solver_timeout: 0.05\n"
)


def _moveit2_skeleton(robot: str, gripper: bool, limits: str) -> dict[str, str]:
    """A MoveIt 2 `<robot>_moveit_config` and `<robot>_description` (URDF, .setup_assistant
    naming it, SRDF, KDL, joint limits): each package adds its launch and controllers."""
    config = f"{robot}_moveit_config"
    return {
        f"{robot}_description/package.xml": AMENT.format(name=f"{robot}_description"),
        f"{robot}_description/urdf/{robot}.urdf": _arm_urdf(robot, 6, gripper=gripper),
        f"{config}/package.xml": AMENT.format(name=config),
        f"{config}/.setup_assistant": (
            f"moveit_setup_assistant_config:\n  urdf:\n    package: {robot}_description\n"
            f"    relative_path: urdf/{robot}.urdf\n  srdf:\n    relative_path: config/{robot}.srdf\n"
        ),
        f"{config}/config/{robot}.srdf": _srdf(robot, 6, gripper=gripper),
        f"{config}/config/joint_limits.yaml": limits,
        f"{config}/config/kinematics.yaml": KDL,
    }


# -- MoveIt 2, controllers found through ros2_control -----------------------------------------------

MANAGER_LAUNCH_PY = """from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_move_group_launch


def generate_launch_description():
    moveit_config = (
        MoveItConfigsBuilder("rc", package_name="rc_moveit_config")
        .trajectory_execution(file_path="config/moveit_controllers.yaml")
        .to_moveit_configs()
    )
    return generate_move_group_launch(moveit_config)
"""
RC_CONTROLLERS = """controller_manager:
  ros__parameters:
    update_rate: 100
    rc_arm_jtc:
      type: joint_trajectory_controller/JointTrajectoryController
    rc_hand:
      type: position_controllers/GripperActionController
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
rc_arm_jtc:
  ros__parameters:
    joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6]
    command_interfaces: [position]
    state_interfaces: [position, velocity]
rc_hand:
  ros__parameters:
    joint: gripper_finger_left_joint
"""


def ros2_control_manager(root: Path) -> tuple[Path, list[Path]]:
    """`rc_moveit_config` (MoveIt 2): Ros2ControlManager, controllers only in ros2_controllers.yaml."""
    config = "rc_moveit_config"
    limits = _limits(6, 0.7, 2.0, 0.3).replace(
        "joint_6:\n    has_velocity_limits: true\n    max_velocity: 0.7\n", "joint_6:\n"
    )
    files = _moveit2_skeleton("rc", gripper=True, limits=limits)
    files[f"{config}/config/moveit_controllers.yaml"] = (
        "trajectory_execution:\n  allowed_execution_duration_scaling: 1.2\n"
        "moveit_controller_manager: moveit_ros_control_interface/Ros2ControlManager\n"
    )
    files[f"{config}/config/ros2_controllers.yaml"] = RC_CONTROLLERS
    files[f"{config}/launch/move_group.launch.py"] = MANAGER_LAUNCH_PY
    build_file_tree(root, files)
    return root / config, [root]


HAND_LAUNCH_PY = """import os

import yaml
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def load_yaml(package_name, file_path):
    with open(os.path.join(get_package_share_directory(package_name), file_path)) as file:
        return yaml.safe_load(file)


def generate_launch_description():
    controllers = {
        "moveit_simple_controller_manager": load_yaml("hl_moveit_config", "config/hlarm_controllers.yaml"),
        "moveit_controller_manager": "moveit_simple_controller_manager/MoveItSimpleControllerManager",
    }
    kinematics = load_yaml("hl_moveit_config", "config/kinematics.yaml")
    move_group = Node(package="moveit_ros_move_group", executable="move_group",
                      parameters=[controllers, {"robot_description_kinematics": kinematics}])
    return LaunchDescription([move_group])
"""
HL_CONTROLLERS = """controller_names: [hl_arm_controller, hl_gripper]
hl_arm_controller:
  action_ns: follow_joint_trajectory
  type: FollowJointTrajectory
  default: true
  joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6]
hl_gripper:
  action_ns: gripper_action
  type: GripperCommand
  default: true
  joints: [gripper_finger_left_joint]
"""


def hand_loaded(root: Path) -> tuple[Path, list[Path]]:
    """`hl_moveit_config` (MoveIt 2): controllers loaded by hand in launch/moveit.launch.py."""
    config = "hl_moveit_config"
    driver = RC_CONTROLLERS.replace("rc_arm_jtc", "hl_arm_controller").replace("rc_hand", "hl_gripper")
    files = _moveit2_skeleton("hl", gripper=True, limits=_limits(6, 0.6, 1.5, 0.2))
    files[f"{config}/config/hlarm_controllers.yaml"] = HL_CONTROLLERS
    files[f"{config}/config/hlarm_ros_controllers.yaml"] = driver
    files[f"{config}/launch/moveit.launch.py"] = HAND_LAUNCH_PY
    build_file_tree(root, files)
    return root / config, [root]


WRAPPER_LAUNCH_PY = """from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_demo_launch


def generate_launch_description():
    moveit_config = (
        MoveItConfigsBuilder("wrapped_arm", package_name="wr_moveit_config")
        .robot_description(file_path="config/wr.urdf.xacro")
        .robot_description_semantic(file_path="config/wr.srdf")
        .to_moveit_configs()
    )
    return generate_demo_launch(moveit_config)
"""
WRAPPER_XACRO = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="wr">
  <xacro:include filename="$(find wr_description)/urdf/wr.urdf"/>
</robot>
"""


def own_wrapper(root: Path) -> tuple[Path, list[Path]]:
    """`wr_moveit_config` (MoveIt 2): the builder loads config/wr.urdf.xacro, a wrapper of
    wr_description's URDF that .setup_assistant names."""
    config = "wr_moveit_config"
    files = _moveit2_skeleton("wr", gripper=False, limits=_limits(6, 0.5, 1.0, 0.1))
    files[f"{config}/config/wr.urdf.xacro"] = WRAPPER_XACRO
    files[f"{config}/config/moveit_controllers.yaml"] = (
        "moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager\n"
        "moveit_simple_controller_manager:\n  controller_names: [wr_arm]\n  wr_arm:\n"
        "    type: FollowJointTrajectory\n    action_ns: follow_joint_trajectory\n    default: true\n"
        "    joints: [joint_1, joint_2, joint_3, joint_4, joint_5, joint_6]\n"
    )
    files[f"{config}/launch/demo.launch.py"] = WRAPPER_LAUNCH_PY
    build_file_tree(root, files)
    return root / config, [root]


def footprint_parented(root: Path) -> tuple[Path, list[Path]]:
    """`fp_moveit_config` (MoveIt 1 Setup Assistant layout): SRDF virtual joint world -> base_link
    onto a URDF rooted at base_footprint (a mobile base's description); demo.launch publishes
    its static TF, as the Setup Assistant writes it."""
    config = "fp_moveit_config"
    urdf = _arm_urdf("fp", 6, gripper=False).replace(
        '<robot name="fp">\n',
        '<robot name="fp">\n  <link name="base_footprint"/>\n  <joint name="base_footprint_joint" '
        'type="fixed"><parent link="base_footprint"/><child link="base_link"/>'
        '<origin xyz="0 0 0.1"/></joint>\n',
    )
    demo = (
        '<launch>\n  <node pkg="tf2_ros" type="static_transform_publisher" name="virtual_joint_broadcaster_0"'
        ' args="0 0 0 0 0 0 world base_link"/>\n</launch>\n'
    )
    build_file_tree(
        root,
        {
            "fp_description/package.xml": CATKIN.format(name="fp_description"),
            "fp_description/urdf/fp.urdf": urdf,
            f"{config}/package.xml": CATKIN.format(name=config),
            f"{config}/.setup_assistant": (
                "moveit_setup_assistant_config:\n  URDF:\n    package: fp_description\n"
                "    relative_path: urdf/fp.urdf\n  SRDF:\n    relative_path: config/fp.srdf\n"
            ),
            f"{config}/config/fp.srdf": _srdf("fp", 6, gripper=False),
            f"{config}/config/kinematics.yaml": KDL,
            f"{config}/launch/demo.launch": demo,
        },
    )
    return root / config, [root]


PACKAGES = {
    "own_wrapper": own_wrapper,
    "hand_loaded": hand_loaded,
    "arg_selected": arg_selected,
    "python_launch": python_launch,
    "position_only": position_only,
    "ros2_control_manager": ros2_control_manager,
}

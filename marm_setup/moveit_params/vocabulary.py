"""MoveIt's tables, in one place: controller types and the actions their drivers serve, kinematics
solver plugins, OMPL planner configurations, virtual joint types.

Setup (model, inference, checks), render and validate all read these; nothing else spells them.
"""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.ros import Target

# srdfdom's virtual joint types (srdfdom model.cpp loadVirtualJoints accepts these three).
VIRTUAL_JOINT_TYPES = ("fixed", "floating", "planar")

# -- controllers ---------------------------------------------------------------------------------

FOLLOW_JOINT_TRAJECTORY = "FollowJointTrajectory"
GRIPPER_COMMAND = "GripperCommand"
# The controller kinds a setup names (a FollowJointTrajectory or a gripper controller).
MOVEIT_CONTROLLER_TYPES = (FOLLOW_JOINT_TRAJECTORY, GRIPPER_COMMAND)
# The handle types MoveIt's simple controller manager knows (moveit2 humble to main,
# moveit_simple_controller_manager.cpp l.148-213: FollowJointTrajectory, GripperCommand and, from
# Jazzy on, ParallelGripperCommand, what a parallel_gripper_action_controller serves).
PARALLEL_GRIPPER_COMMAND = "ParallelGripperCommand"
MOVEIT_HANDLE_TYPES = (*MOVEIT_CONTROLLER_TYPES, PARALLEL_GRIPPER_COMMAND)

# Action namespaces the drivers serve: ros2_control's JointTrajectoryController
# `<name>/follow_joint_trajectory`, its GripperActionController `<name>/gripper_cmd`, the ArbotiX
# gripper_controller node `<node>/gripper_action`. (The ArbotiX follow_controller serves the
# action_name that arbotix.yaml gives it, so a ros1 FollowJointTrajectory controller may use any.)
FOLLOW_JOINT_TRAJECTORY_NS = "follow_joint_trajectory"
GRIPPER_CMD_NS = "gripper_cmd"
ARBOTIX_GRIPPER_ACTION_NS = "gripper_action"

# ros2_control / ros_control controller class (the type's last part) -> (MoveIt controller type,
# the action namespace it serves).
DRIVER_CONTROLLERS = {
    "JointTrajectoryController": (FOLLOW_JOINT_TRAJECTORY, FOLLOW_JOINT_TRAJECTORY_NS),
    "GripperActionController": (GRIPPER_COMMAND, GRIPPER_CMD_NS),
    "ParallelGripperCommandController": (GRIPPER_COMMAND, GRIPPER_CMD_NS),
}
# Full controller types whose class name alone says too little: ros2_controllers'
# parallel_gripper_action_controller serves control_msgs ParallelGripperCommand
# (parallel_gripper_action_controller.hpp l.97), not GripperCommand.
DRIVER_CONTROLLER_TYPES = {
    "parallel_gripper_action_controller/GripperActionController": (PARALLEL_GRIPPER_COMMAND, GRIPPER_CMD_NS),
}
# Driver controller classes whose `joints` / `joint` parameters name URDF joints.
JOINT_DRIVER_CONTROLLERS = frozenset(
    {
        *DRIVER_CONTROLLERS,
        "JointGroupPositionController",
        "JointGroupVelocityController",
        "JointGroupEffortController",
        "ForwardCommandController",
        "JointPositionController",
        "JointVelocityController",
        "JointEffortController",
    }
)
# The ros2_control controller we generate for each MoveIt controller type.
ROS2_CONTROLLER_TYPES = {
    FOLLOW_JOINT_TRAJECTORY: "joint_trajectory_controller/JointTrajectoryController",
    GRIPPER_COMMAND: "position_controllers/GripperActionController",
}
# (driver, MoveIt controller type) -> the action namespace that driver serves, where the driver
# fixes it; the driver is ros2_control (`ros2`) for ros2, the setup's `driver` for ros1. A ros1
# package with no driver named may use any action namespace.
DRIVER_ACTION_NS = {
    **{
        ("ros2", kind): DRIVER_CONTROLLERS[plugin.rsplit("/", 1)[-1]][1]
        for kind, plugin in ROS2_CONTROLLER_TYPES.items()
    },
    ("arbotix", GRIPPER_COMMAND): ARBOTIX_GRIPPER_ACTION_NS,
}
# What an inferred controller uses where no driver fixes it.
DEFAULT_ACTION_NS = {FOLLOW_JOINT_TRAJECTORY: FOLLOW_JOINT_TRAJECTORY_NS, GRIPPER_COMMAND: GRIPPER_CMD_NS}
# Hardware drivers whose files a ros1 package can carry (`driver:` in the setup).
DRIVERS = ("arbotix",)
ROS2_ACTION_NS = {kind: ns for (target, kind), ns in DRIVER_ACTION_NS.items() if target == Target.ROS2}

# -- kinematics solvers --------------------------------------------------------------------------

KDL_PLUGIN = "kdl_kinematics_plugin/KDLKinematicsPlugin"
KINEMATICS_PLUGINS = (
    KDL_PLUGIN,
    "trac_ik_kinematics_plugin/TRAC_IKKinematicsPlugin",
    "pick_ik/PickIkPlugin",
    "bio_ik/BioIKKinematicsPlugin",
    "lma_kinematics_plugin/LMAKinematicsPlugin",
    "cached_ik_kinematics_plugin/CachedKDLKinematicsPlugin",
    "cached_ik_kinematics_plugin/CachedSrvKinematicsPlugin",
    "cached_ik_kinematics_plugin/CachedTRACKinematicsPlugin",
    "srv_kinematics_plugin/SrvKinematicsPlugin",
)
# The solvers moveit_kinematics itself ships (moveit/moveit2 moveit_kinematics: kdl, lma,
# cached_ik, srv): a package depending on it needs no other for them.
MOVEIT_KINEMATICS_PLUGINS = (
    KDL_PLUGIN,
    "lma_kinematics_plugin/LMAKinematicsPlugin",
    "cached_ik_kinematics_plugin/CachedKDLKinematicsPlugin",
    "cached_ik_kinematics_plugin/CachedSrvKinematicsPlugin",
    "srv_kinematics_plugin/SrvKinematicsPlugin",
)
# kinematics.yaml's keys for a group's solver, search resolution [rad], timeout [s] and attempts;
# every other key of a group's entry is an option of its solver plugin.
KINEMATICS_KEYS = (
    "kinematics_solver",
    "kinematics_solver_search_resolution",
    "kinematics_solver_timeout",
    "kinematics_solver_attempts",
)
IKFAST_PLUGIN_SUFFIX = "/IKFastKinematicsPlugin"  # generated per robot: `<robot>_<group>_ikfast_plugin/...`
# Solvers that need the group to be a chain.
CHAIN_ONLY_PLUGINS = (
    KDL_PLUGIN,
    "cached_ik_kinematics_plugin/CachedKDLKinematicsPlugin",
    "lma_kinematics_plugin/LMAKinematicsPlugin",
)

# -- ros2_control --------------------------------------------------------------------------------

# ros2_control's mock hardware (package mock_components): mirrors commands to states.
MOCK_HARDWARE = "mock_components/GenericSystem"

# -- planning pipelines --------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class Pipeline:
    """A MoveIt planning pipeline: its parameter namespace (the name move_group's
    planning_pipelines lists), planner plugin per MoveIt generation and the package exporting it.
    Which distros ship it: their rows (marm_setup.ros DISTROS, `planners`, `planners_from_source`)."""

    namespace: str
    plugin_ros1: str
    plugin_ros2: str
    package: str

    def plugin(self, target: Target) -> str:
        return self.plugin_ros1 if target == Target.ROS1 else self.plugin_ros2


# The setup's `planning_pipelines` names. STOMP is not in Humble's binaries: moveit2's humble
# branch has no moveit_planners/stomp (it is there from Iron on); Humble users build that package
# (stomp_moveit, moveit_planners_stomp) from source, with Humble's pipeline format
# (moveit/moveit2#2550, #2742; Kinovarobotics/ros2_kortex#153 took it out of their Humble
# binaries' config for that reason). MoveIt 1's STOMP is a separate stomp_moveit package.
# MoveIt 1's Pilz plugin class is `pilz_industrial_motion_planner::CommandPlanner` (what the Setup
# Assistant writes), MoveIt 2's `pilz_industrial_motion_planner/CommandPlanner`.
PIPELINES = {
    "ompl": Pipeline(
        "ompl",
        "ompl_interface/OMPLPlanner",
        "ompl_interface/OMPLPlanner",
        "moveit_planners_ompl",
    ),
    "chomp": Pipeline(
        "chomp",
        "chomp_interface/CHOMPPlanner",
        "chomp_interface/CHOMPPlanner",
        "moveit_planners_chomp",
    ),
    "pilz": Pipeline(
        "pilz_industrial_motion_planner",
        "pilz_industrial_motion_planner::CommandPlanner",
        "pilz_industrial_motion_planner/CommandPlanner",
        "pilz_industrial_motion_planner",
    ),
    "stomp": Pipeline("stomp", "", "stomp_moveit/StompPlanner", "moveit_planners_stomp"),
}
# OMPL for any query, Pilz for deterministic PTP/LIN/CIRC motions (needs only the cartesian
# limits); CHOMP and STOMP optimise trajectories and want tuning per robot, so they are opt-in.
DEFAULT_PIPELINES = ("ompl", "pilz")

# -- OMPL ----------------------------------------------------------------------------------------

DEFAULT_PLANNER = "RRTConnect"
# The OMPL planner configurations the package defines (name, type): a group's default_planner is one.
OMPL_PLANNERS = (
    ("AnytimePathShortening", "geometric::AnytimePathShortening"),
    ("BKPIECE", "geometric::BKPIECE"),
    ("EST", "geometric::EST"),
    ("KPIECE", "geometric::KPIECE"),
    ("LBKPIECE", "geometric::LBKPIECE"),
    ("PRM", "geometric::PRM"),
    ("PRMstar", "geometric::PRMstar"),
    ("RRT", "geometric::RRT"),
    (DEFAULT_PLANNER, "geometric::RRTConnect"),
    ("RRTstar", "geometric::RRTstar"),
    ("SBL", "geometric::SBL"),
    ("TRRT", "geometric::TRRT"),
)
OMPL_PLANNER_NAMES = tuple(name for name, _ in OMPL_PLANNERS)

# -- MoveIt Servo --------------------------------------------------------------------------------

# What servo publishes (`servo[].command_out`): a trajectory to a FollowJointTrajectory
# controller, or positions to a forward position controller (ros2_control, added for it).
SERVO_TRAJECTORY = "trajectory"
SERVO_POSITION = "position"
SERVO_OUTPUTS = (SERVO_TRAJECTORY, SERVO_POSITION)
# moveit_servo's command_in_type values (noetic servo.cpp readParameters, humble
# servo_parameters.cpp validate, jazzy servo_parameters.yaml `one_of`).
SERVO_COMMAND_IN_TYPES = ("unitless", "speed_units")
# The kind of the forward controller servo's `position` output drives (subscribes to
# `<name>/commands`, std_msgs/Float64MultiArray); its type is the distro's (marm_setup.ros DISTROS
# `controllers`: position_controllers/JointGroupPositionController, on Rolling
# forward_command_controller/ForwardCommandController).
FORWARD_POSITION = "forward_position"

# -- 3D perception -------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class SensorType:
    """An occupancy map updater plugin: its pluginlib name, the parameter its topic goes in, and
    the other parameters it reads with the value MoveIt's Setup Assistant writes for them (its
    `templates/config/sensors_3d.yaml`, noetic and jazzy alike; the skip_*_pixels the
    Setup Assistant does not write: the updater's constructor defaults), in the order MoveIt 2's
    `setParams` reads them."""

    plugin: str
    topic_key: str
    defaults: tuple[tuple[str, float | int | str], ...]


# moveit_ros_perception's updaters. MoveIt 2's setParams (humble and jazzy,
# pointcloud_octomap_updater.cpp l.75-86, depth_image_octomap_updater.cpp l.92-108) fails the
# sensor when one of these is missing (the depth image updater stops reading at the first one
# missing); `ns` alone is optional (get_parameter_or), so it is written only when given.
SENSOR_TYPES = {
    "pointcloud": SensorType(
        "occupancy_map_monitor/PointCloudOctomapUpdater",
        "point_cloud_topic",
        (
            ("max_range", 5.0),
            ("padding_offset", 0.1),
            ("padding_scale", 1.0),
            ("point_subsample", 1),
            ("max_update_rate", 1.0),
            ("filtered_cloud_topic", "filtered_cloud"),
        ),
    ),
    "depth_image": SensorType(
        "occupancy_map_monitor/DepthImageOctomapUpdater",
        "image_topic",
        (
            ("queue_size", 5),
            ("near_clipping_plane_distance", 0.3),
            ("far_clipping_plane_distance", 5.0),
            ("shadow_threshold", 0.2),
            ("padding_scale", 4.0),
            ("padding_offset", 0.03),
            ("max_update_rate", 1.0),
            ("skip_vertical_pixels", 4),
            ("skip_horizontal_pixels", 6),
            ("filtered_cloud_topic", "filtered_cloud"),
        ),
    ),
}
# The Setup Assistant's noetic sensor_manager.launch.xml value (MoveIt's occupancy map monitor
# assumes 0.1 and warns when none is given).
DEFAULT_OCTOMAP_RESOLUTION = 0.025

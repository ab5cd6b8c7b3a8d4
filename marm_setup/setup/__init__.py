"""The setup model (`marm_setup.yaml`): dataclasses, YAML I/O, inference from a robot, group
queries, SRDF reading, MoveIt's tables (`domain`), the one rule set and the setup checks.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "model": (
        "ArbotixJoint Author CollisionSettings Controller EndEffector Group GroupState JointLimitOverride "
        "Kinematics PipelineParameterValue PlannerDefaults RobotSource Ros2ControlHardware Sensor Servo "
        "ServoScale SetupModel VirtualJoint"
    ),
    "yaml_io": (
        "dump_setup load_setup Partial patch_from_dict read_yaml_mapping setup_from_dict setup_to_dict"
    ),
    "assemble": "apply_patch checked COMMAND_LINE_KEYS with_spec",
    "infer": (
        "derive_group_settings describe_setup fill_group_settings fit_to_spec home_poses infer_setup "
        "Inference REFERENCE"
    ),
    "checks": "as_input_error check_setup distro_problem package_name_problem setup_warnings",
    "rules": "check_semantics check_semantics_without_robot setup_element srdf_element",
    "start_state": "demo_start_values model_start_values pose_configuration start_configuration start_pose",
    "domain": (
        "ARBOTIX_GRIPPER_ACTION_NS CHAIN_ONLY_PLUGINS DEFAULT_PLANNER DRIVER_ACTION_NS DRIVER_CONTROLLERS "
        "FOLLOW_JOINT_TRAJECTORY FOLLOW_JOINT_TRAJECTORY_NS GRIPPER_CMD_NS GRIPPER_COMMAND "
        "IKFAST_PLUGIN_SUFFIX JOINT_DRIVER_CONTROLLERS KINEMATICS_KEYS KINEMATICS_PLUGINS MOCK_HARDWARE "
        "DRIVER_CONTROLLER_TYPES MOVEIT_CONTROLLER_TYPES MOVEIT_HANDLE_TYPES MOVEIT_KINEMATICS_PLUGINS OMPL_PLANNER_NAMES OMPL_PLANNERS PIPELINES "
        "ROS2_CONTROLLER_TYPES SENSOR_TYPES SERVO_POSITION SERVO_TRAJECTORY VIRTUAL_JOINT_TYPES"
    ),
    "srdf": (
        "allowed_pairs expand_srdf_xacro load_srdf parse_srdf_document parse_srdf_string read_srdf "
        "setup_to_srdf Srdf srdf_to_setup"
    ),
    "groups": "active_group_joints group_joints group_links groups_by_name is_chain planning_joints",
    "srdf_load": "as_moveit_loads root_virtual_joint",
    "poses": "choose_start_poses infer_poses",
    "limits": "joint_limits timing_problem",
    "sensors": "check_sensors plan_perception",
    "servo": "check_servos default_servos forward_controllers plan_servos",
    "spec_overlay": "patch_items spec_items without_replaced",
    "move_group_params": (
        "BY_ROS1_NAME MOVE_GROUP_PARAMS MoveGroupParam move_group_problem move_group_values written_values"
    ),
    "pipeline_params": (
        "ADAPTER_FAMILIES effective_parameters flatten known_parameters other_distros_reading parameter "
        "STRUCTURE_KEYS infinite_problem unknown_name_hint value_problem"
    ),
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.setup.assemble import COMMAND_LINE_KEYS as COMMAND_LINE_KEYS
    from marm_setup.setup.assemble import apply_patch as apply_patch
    from marm_setup.setup.assemble import checked as checked
    from marm_setup.setup.assemble import with_spec as with_spec
    from marm_setup.setup.checks import as_input_error as as_input_error
    from marm_setup.setup.checks import check_setup as check_setup
    from marm_setup.setup.checks import distro_problem as distro_problem
    from marm_setup.setup.checks import package_name_problem as package_name_problem
    from marm_setup.setup.checks import setup_warnings as setup_warnings
    from marm_setup.setup.domain import ARBOTIX_GRIPPER_ACTION_NS as ARBOTIX_GRIPPER_ACTION_NS
    from marm_setup.setup.domain import CHAIN_ONLY_PLUGINS as CHAIN_ONLY_PLUGINS
    from marm_setup.setup.domain import DEFAULT_PLANNER as DEFAULT_PLANNER
    from marm_setup.setup.domain import DRIVER_ACTION_NS as DRIVER_ACTION_NS
    from marm_setup.setup.domain import DRIVER_CONTROLLER_TYPES as DRIVER_CONTROLLER_TYPES
    from marm_setup.setup.domain import DRIVER_CONTROLLERS as DRIVER_CONTROLLERS
    from marm_setup.setup.domain import FOLLOW_JOINT_TRAJECTORY as FOLLOW_JOINT_TRAJECTORY
    from marm_setup.setup.domain import FOLLOW_JOINT_TRAJECTORY_NS as FOLLOW_JOINT_TRAJECTORY_NS
    from marm_setup.setup.domain import GRIPPER_CMD_NS as GRIPPER_CMD_NS
    from marm_setup.setup.domain import GRIPPER_COMMAND as GRIPPER_COMMAND
    from marm_setup.setup.domain import IKFAST_PLUGIN_SUFFIX as IKFAST_PLUGIN_SUFFIX
    from marm_setup.setup.domain import JOINT_DRIVER_CONTROLLERS as JOINT_DRIVER_CONTROLLERS
    from marm_setup.setup.domain import KINEMATICS_KEYS as KINEMATICS_KEYS
    from marm_setup.setup.domain import KINEMATICS_PLUGINS as KINEMATICS_PLUGINS
    from marm_setup.setup.domain import MOCK_HARDWARE as MOCK_HARDWARE
    from marm_setup.setup.domain import MOVEIT_CONTROLLER_TYPES as MOVEIT_CONTROLLER_TYPES
    from marm_setup.setup.domain import MOVEIT_HANDLE_TYPES as MOVEIT_HANDLE_TYPES
    from marm_setup.setup.domain import MOVEIT_KINEMATICS_PLUGINS as MOVEIT_KINEMATICS_PLUGINS
    from marm_setup.setup.domain import OMPL_PLANNER_NAMES as OMPL_PLANNER_NAMES
    from marm_setup.setup.domain import OMPL_PLANNERS as OMPL_PLANNERS
    from marm_setup.setup.domain import PIPELINES as PIPELINES
    from marm_setup.setup.domain import ROS2_CONTROLLER_TYPES as ROS2_CONTROLLER_TYPES
    from marm_setup.setup.domain import SENSOR_TYPES as SENSOR_TYPES
    from marm_setup.setup.domain import SERVO_POSITION as SERVO_POSITION
    from marm_setup.setup.domain import SERVO_TRAJECTORY as SERVO_TRAJECTORY
    from marm_setup.setup.domain import VIRTUAL_JOINT_TYPES as VIRTUAL_JOINT_TYPES
    from marm_setup.setup.groups import active_group_joints as active_group_joints
    from marm_setup.setup.groups import group_joints as group_joints
    from marm_setup.setup.groups import group_links as group_links
    from marm_setup.setup.groups import groups_by_name as groups_by_name
    from marm_setup.setup.groups import is_chain as is_chain
    from marm_setup.setup.groups import planning_joints as planning_joints
    from marm_setup.setup.infer import REFERENCE as REFERENCE
    from marm_setup.setup.infer import Inference as Inference
    from marm_setup.setup.infer import derive_group_settings as derive_group_settings
    from marm_setup.setup.infer import describe_setup as describe_setup
    from marm_setup.setup.infer import fill_group_settings as fill_group_settings
    from marm_setup.setup.infer import fit_to_spec as fit_to_spec
    from marm_setup.setup.infer import home_poses as home_poses
    from marm_setup.setup.infer import infer_setup as infer_setup
    from marm_setup.setup.limits import joint_limits as joint_limits
    from marm_setup.setup.limits import timing_problem as timing_problem
    from marm_setup.setup.model import ArbotixJoint as ArbotixJoint
    from marm_setup.setup.model import Author as Author
    from marm_setup.setup.model import CollisionSettings as CollisionSettings
    from marm_setup.setup.model import Controller as Controller
    from marm_setup.setup.model import EndEffector as EndEffector
    from marm_setup.setup.model import Group as Group
    from marm_setup.setup.model import GroupState as GroupState
    from marm_setup.setup.model import JointLimitOverride as JointLimitOverride
    from marm_setup.setup.model import Kinematics as Kinematics
    from marm_setup.setup.model import PipelineParameterValue as PipelineParameterValue
    from marm_setup.setup.model import PlannerDefaults as PlannerDefaults
    from marm_setup.setup.model import RobotSource as RobotSource
    from marm_setup.setup.model import Ros2ControlHardware as Ros2ControlHardware
    from marm_setup.setup.model import Sensor as Sensor
    from marm_setup.setup.model import Servo as Servo
    from marm_setup.setup.model import ServoScale as ServoScale
    from marm_setup.setup.model import SetupModel as SetupModel
    from marm_setup.setup.model import VirtualJoint as VirtualJoint
    from marm_setup.setup.move_group_params import BY_ROS1_NAME as BY_ROS1_NAME
    from marm_setup.setup.move_group_params import MOVE_GROUP_PARAMS as MOVE_GROUP_PARAMS
    from marm_setup.setup.move_group_params import MoveGroupParam as MoveGroupParam
    from marm_setup.setup.move_group_params import move_group_problem as move_group_problem
    from marm_setup.setup.move_group_params import move_group_values as move_group_values
    from marm_setup.setup.move_group_params import written_values as written_values
    from marm_setup.setup.pipeline_params import ADAPTER_FAMILIES as ADAPTER_FAMILIES
    from marm_setup.setup.pipeline_params import STRUCTURE_KEYS as STRUCTURE_KEYS
    from marm_setup.setup.pipeline_params import effective_parameters as effective_parameters
    from marm_setup.setup.pipeline_params import flatten as flatten
    from marm_setup.setup.pipeline_params import infinite_problem as infinite_problem
    from marm_setup.setup.pipeline_params import known_parameters as known_parameters
    from marm_setup.setup.pipeline_params import other_distros_reading as other_distros_reading
    from marm_setup.setup.pipeline_params import parameter as parameter
    from marm_setup.setup.pipeline_params import unknown_name_hint as unknown_name_hint
    from marm_setup.setup.pipeline_params import value_problem as value_problem
    from marm_setup.setup.poses import choose_start_poses as choose_start_poses
    from marm_setup.setup.poses import infer_poses as infer_poses
    from marm_setup.setup.rules import check_semantics as check_semantics
    from marm_setup.setup.rules import check_semantics_without_robot as check_semantics_without_robot
    from marm_setup.setup.rules import setup_element as setup_element
    from marm_setup.setup.rules import srdf_element as srdf_element
    from marm_setup.setup.sensors import check_sensors as check_sensors
    from marm_setup.setup.sensors import plan_perception as plan_perception
    from marm_setup.setup.servo import check_servos as check_servos
    from marm_setup.setup.servo import default_servos as default_servos
    from marm_setup.setup.servo import forward_controllers as forward_controllers
    from marm_setup.setup.servo import plan_servos as plan_servos
    from marm_setup.setup.spec_overlay import patch_items as patch_items
    from marm_setup.setup.spec_overlay import spec_items as spec_items
    from marm_setup.setup.spec_overlay import without_replaced as without_replaced
    from marm_setup.setup.srdf import Srdf as Srdf
    from marm_setup.setup.srdf import allowed_pairs as allowed_pairs
    from marm_setup.setup.srdf import expand_srdf_xacro as expand_srdf_xacro
    from marm_setup.setup.srdf import load_srdf as load_srdf
    from marm_setup.setup.srdf import parse_srdf_document as parse_srdf_document
    from marm_setup.setup.srdf import parse_srdf_string as parse_srdf_string
    from marm_setup.setup.srdf import read_srdf as read_srdf
    from marm_setup.setup.srdf import setup_to_srdf as setup_to_srdf
    from marm_setup.setup.srdf import srdf_to_setup as srdf_to_setup
    from marm_setup.setup.srdf_load import as_moveit_loads as as_moveit_loads
    from marm_setup.setup.srdf_load import root_virtual_joint as root_virtual_joint
    from marm_setup.setup.start_state import demo_start_values as demo_start_values
    from marm_setup.setup.start_state import model_start_values as model_start_values
    from marm_setup.setup.start_state import pose_configuration as pose_configuration
    from marm_setup.setup.start_state import start_configuration as start_configuration
    from marm_setup.setup.start_state import start_pose as start_pose
    from marm_setup.setup.yaml_io import Partial as Partial
    from marm_setup.setup.yaml_io import dump_setup as dump_setup
    from marm_setup.setup.yaml_io import load_setup as load_setup
    from marm_setup.setup.yaml_io import patch_from_dict as patch_from_dict
    from marm_setup.setup.yaml_io import read_yaml_mapping as read_yaml_mapping
    from marm_setup.setup.yaml_io import setup_from_dict as setup_from_dict
    from marm_setup.setup.yaml_io import setup_to_dict as setup_to_dict

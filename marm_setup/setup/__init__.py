"""The setup model (`marm_setup.yaml`): its dataclasses and YAML I/O, group queries, SRDF
reading and writing, the state a package's demo starts in, the one rule set and the setup
checks (names, limits, sensors, servos).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "model": (
        "ArbotixJoint Author Chain CollisionSettings Controller EndEffector Group GroupState "
        "JointLimitOverride Kinematics PlannerDefaults RobotSource Ros2ControlHardware Sensor Servo "
        "ServoScale SetupModel StartPose VirtualJoint"
    ),
    "yaml_io": (
        "dump_setup load_setup Partial patch_from_dict read_yaml_mapping setup_from_dict setup_to_dict "
        "ITEM_KEYS"
    ),
    "checks": "as_input_error check_setup distro_problem package_name_problem setup_warnings",
    "rules": "check_semantics check_semantics_without_robot setup_element srdf_element Style",
    "start_state": "demo_start_values model_start_values pose_configuration start_configuration start_pose",
    "srdf": (
        "allowed_pairs expand_srdf_xacro load_srdf parse_srdf_document parse_srdf_string read_srdf "
        "setup_to_srdf Srdf srdf_to_setup"
    ),
    "groups": "active_group_joints group_joints group_links groups_by_name is_chain planning_joints",
    "srdf_load": "as_moveit_loads root_virtual_joint",
    "limits": "joint_limits timing_problem",
    "sensors": "check_sensors plan_perception",
    "servo": "check_servos default_servos forward_controllers plan_servos",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.setup.checks import as_input_error as as_input_error
    from marm_setup.setup.checks import check_setup as check_setup
    from marm_setup.setup.checks import distro_problem as distro_problem
    from marm_setup.setup.checks import package_name_problem as package_name_problem
    from marm_setup.setup.checks import setup_warnings as setup_warnings
    from marm_setup.setup.groups import active_group_joints as active_group_joints
    from marm_setup.setup.groups import group_joints as group_joints
    from marm_setup.setup.groups import group_links as group_links
    from marm_setup.setup.groups import groups_by_name as groups_by_name
    from marm_setup.setup.groups import is_chain as is_chain
    from marm_setup.setup.groups import planning_joints as planning_joints
    from marm_setup.setup.limits import joint_limits as joint_limits
    from marm_setup.setup.limits import timing_problem as timing_problem
    from marm_setup.setup.model import ArbotixJoint as ArbotixJoint
    from marm_setup.setup.model import Author as Author
    from marm_setup.setup.model import Chain as Chain
    from marm_setup.setup.model import CollisionSettings as CollisionSettings
    from marm_setup.setup.model import Controller as Controller
    from marm_setup.setup.model import EndEffector as EndEffector
    from marm_setup.setup.model import Group as Group
    from marm_setup.setup.model import GroupState as GroupState
    from marm_setup.setup.model import JointLimitOverride as JointLimitOverride
    from marm_setup.setup.model import Kinematics as Kinematics
    from marm_setup.setup.model import PlannerDefaults as PlannerDefaults
    from marm_setup.setup.model import RobotSource as RobotSource
    from marm_setup.setup.model import Ros2ControlHardware as Ros2ControlHardware
    from marm_setup.setup.model import Sensor as Sensor
    from marm_setup.setup.model import Servo as Servo
    from marm_setup.setup.model import ServoScale as ServoScale
    from marm_setup.setup.model import SetupModel as SetupModel
    from marm_setup.setup.model import StartPose as StartPose
    from marm_setup.setup.model import VirtualJoint as VirtualJoint
    from marm_setup.setup.rules import Style as Style
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
    from marm_setup.setup.yaml_io import ITEM_KEYS as ITEM_KEYS
    from marm_setup.setup.yaml_io import Partial as Partial
    from marm_setup.setup.yaml_io import dump_setup as dump_setup
    from marm_setup.setup.yaml_io import load_setup as load_setup
    from marm_setup.setup.yaml_io import patch_from_dict as patch_from_dict
    from marm_setup.setup.yaml_io import read_yaml_mapping as read_yaml_mapping
    from marm_setup.setup.yaml_io import setup_from_dict as setup_from_dict
    from marm_setup.setup.yaml_io import setup_to_dict as setup_to_dict

"""The robot: URDF/xacro loading, ROS package lookup, meshes, the frozen RobotModel,
batched forward kinematics, its text description, and the words its joint and link names
say (arm, leg, hand, side: `limb_words`).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "load": "load_robot parse_xacro_args xml_syntax_message",
    "tinyxml": "tinyxml_comments",
    "xacro_expand": "check_xacro_args expand_xacro run_xacro XacroOutput",
    "model": (
        "Box CollisionShape Cylinder described_joints described_systems Joint limit_slack LIMIT_TOLERANCE Link "
        "Mesh MIN_RATE RobotModel Sphere"
    ),
    "kinematics": (
        "bounds default_configuration forward_kinematics link_index onto_bounds origin_matrix "
        "sample_configurations wrap_continuous"
    ),
    "meshes": "check_robot_triangles load_mesh MAX_ROBOT_TRIANGLES",
    "ros_packages": (
        "description_file exported_plugin_classes find_package find_packages misspelt_package package_name PackageIndex "
        "PackageMap resolve_uri"
    ),
    "describe": "describe_robot format_tree",
    "fingerprint": "robot_fingerprint",
    "ros2_control": (
        "ANY_MOCK HardwareArg JointInterfaces joint_interfaces MOCK_PLUGIN MOCK_PLUGINS on_mock_hardware "
        "Ros2ControlSystem simulator_parameter_files SIMULATOR_CONTROL_PLUGINS systems_in_urdf"
    ),
    "urdf": "strict_float",
    "sandbox": "ChildDied kill limit_memory picklable run_limited TimeLimitExceeded",
    "xacro_cli": "parse_xacro_argv parse_xacro_command split_command XacroCall",
    "limb_words": (
        "BASE_KINDS common_prefix FINGER_WORDS FOOT_WORDS is_kind joint_kinds KIND_WORDS MOUNT_WORDS name_kinds "
        "name_words side_of tokens TOOL_RANKS TOOL_WORDS VISION_WORDS votes_for"
    ),
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.robot.describe import describe_robot as describe_robot
    from marm_setup.robot.describe import format_tree as format_tree
    from marm_setup.robot.fingerprint import robot_fingerprint as robot_fingerprint
    from marm_setup.robot.kinematics import bounds as bounds
    from marm_setup.robot.kinematics import default_configuration as default_configuration
    from marm_setup.robot.kinematics import forward_kinematics as forward_kinematics
    from marm_setup.robot.kinematics import link_index as link_index
    from marm_setup.robot.kinematics import onto_bounds as onto_bounds
    from marm_setup.robot.kinematics import origin_matrix as origin_matrix
    from marm_setup.robot.kinematics import sample_configurations as sample_configurations
    from marm_setup.robot.kinematics import wrap_continuous as wrap_continuous
    from marm_setup.robot.limb_words import BASE_KINDS as BASE_KINDS
    from marm_setup.robot.limb_words import FINGER_WORDS as FINGER_WORDS
    from marm_setup.robot.limb_words import FOOT_WORDS as FOOT_WORDS
    from marm_setup.robot.limb_words import KIND_WORDS as KIND_WORDS
    from marm_setup.robot.limb_words import MOUNT_WORDS as MOUNT_WORDS
    from marm_setup.robot.limb_words import TOOL_RANKS as TOOL_RANKS
    from marm_setup.robot.limb_words import TOOL_WORDS as TOOL_WORDS
    from marm_setup.robot.limb_words import VISION_WORDS as VISION_WORDS
    from marm_setup.robot.limb_words import common_prefix as common_prefix
    from marm_setup.robot.limb_words import is_kind as is_kind
    from marm_setup.robot.limb_words import joint_kinds as joint_kinds
    from marm_setup.robot.limb_words import name_kinds as name_kinds
    from marm_setup.robot.limb_words import name_words as name_words
    from marm_setup.robot.limb_words import side_of as side_of
    from marm_setup.robot.limb_words import tokens as tokens
    from marm_setup.robot.limb_words import votes_for as votes_for
    from marm_setup.robot.load import load_robot as load_robot
    from marm_setup.robot.load import parse_xacro_args as parse_xacro_args
    from marm_setup.robot.load import xml_syntax_message as xml_syntax_message
    from marm_setup.robot.meshes import MAX_ROBOT_TRIANGLES as MAX_ROBOT_TRIANGLES
    from marm_setup.robot.meshes import check_robot_triangles as check_robot_triangles
    from marm_setup.robot.meshes import load_mesh as load_mesh
    from marm_setup.robot.model import LIMIT_TOLERANCE as LIMIT_TOLERANCE
    from marm_setup.robot.model import MIN_RATE as MIN_RATE
    from marm_setup.robot.model import Box as Box
    from marm_setup.robot.model import CollisionShape as CollisionShape
    from marm_setup.robot.model import Cylinder as Cylinder
    from marm_setup.robot.model import Joint as Joint
    from marm_setup.robot.model import Link as Link
    from marm_setup.robot.model import Mesh as Mesh
    from marm_setup.robot.model import RobotModel as RobotModel
    from marm_setup.robot.model import Sphere as Sphere
    from marm_setup.robot.model import described_joints as described_joints
    from marm_setup.robot.model import described_systems as described_systems
    from marm_setup.robot.model import limit_slack as limit_slack
    from marm_setup.robot.ros2_control import ANY_MOCK as ANY_MOCK
    from marm_setup.robot.ros2_control import MOCK_PLUGIN as MOCK_PLUGIN
    from marm_setup.robot.ros2_control import MOCK_PLUGINS as MOCK_PLUGINS
    from marm_setup.robot.ros2_control import SIMULATOR_CONTROL_PLUGINS as SIMULATOR_CONTROL_PLUGINS
    from marm_setup.robot.ros2_control import HardwareArg as HardwareArg
    from marm_setup.robot.ros2_control import JointInterfaces as JointInterfaces
    from marm_setup.robot.ros2_control import Ros2ControlSystem as Ros2ControlSystem
    from marm_setup.robot.ros2_control import joint_interfaces as joint_interfaces
    from marm_setup.robot.ros2_control import on_mock_hardware as on_mock_hardware
    from marm_setup.robot.ros2_control import simulator_parameter_files as simulator_parameter_files
    from marm_setup.robot.ros2_control import systems_in_urdf as systems_in_urdf
    from marm_setup.robot.ros_packages import PackageIndex as PackageIndex
    from marm_setup.robot.ros_packages import PackageMap as PackageMap
    from marm_setup.robot.ros_packages import description_file as description_file
    from marm_setup.robot.ros_packages import exported_plugin_classes as exported_plugin_classes
    from marm_setup.robot.ros_packages import find_package as find_package
    from marm_setup.robot.ros_packages import find_packages as find_packages
    from marm_setup.robot.ros_packages import misspelt_package as misspelt_package
    from marm_setup.robot.ros_packages import package_name as package_name
    from marm_setup.robot.ros_packages import resolve_uri as resolve_uri
    from marm_setup.robot.sandbox import ChildDied as ChildDied
    from marm_setup.robot.sandbox import TimeLimitExceeded as TimeLimitExceeded
    from marm_setup.robot.sandbox import kill as kill
    from marm_setup.robot.sandbox import limit_memory as limit_memory
    from marm_setup.robot.sandbox import picklable as picklable
    from marm_setup.robot.sandbox import run_limited as run_limited
    from marm_setup.robot.tinyxml import tinyxml_comments as tinyxml_comments
    from marm_setup.robot.urdf import strict_float as strict_float
    from marm_setup.robot.xacro_cli import XacroCall as XacroCall
    from marm_setup.robot.xacro_cli import parse_xacro_argv as parse_xacro_argv
    from marm_setup.robot.xacro_cli import parse_xacro_command as parse_xacro_command
    from marm_setup.robot.xacro_cli import split_command as split_command
    from marm_setup.robot.xacro_expand import XacroOutput as XacroOutput
    from marm_setup.robot.xacro_expand import check_xacro_args as check_xacro_args
    from marm_setup.robot.xacro_expand import expand_xacro as expand_xacro
    from marm_setup.robot.xacro_expand import run_xacro as run_xacro

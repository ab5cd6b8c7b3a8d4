"""MoveIt's tables: its declared parameters per distro family, as data (tables.py,
data/<family>.yaml), how a value fits them (values.py) and how they are rebuilt from MoveIt's
sources (regenerate.py); the controller types, plugins, planners and other names MoveIt reads
(vocabulary.py); the parameters of a planning pipeline (pipeline_params.py) and of move_group
(move_group_params.py) a setup may give; ros2_control's and its controllers' declared parameters
(driver_params.py, data/drivers_<family>.yaml).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "tables": "FAMILIES LOGS ParamRow Table family_of load_table",
    "values": "type_problem validator_problem",
    "vocabulary": (
        "ARBOTIX_GRIPPER_ACTION_NS CHAIN_ONLY_PLUGINS DEFAULT_PLANNER DRIVER_ACTION_NS DRIVER_CONTROLLERS "
        "FOLLOW_JOINT_TRAJECTORY FOLLOW_JOINT_TRAJECTORY_NS GRIPPER_CMD_NS GRIPPER_COMMAND "
        "IKFAST_PLUGIN_SUFFIX JOINT_DRIVER_CONTROLLERS KINEMATICS_KEYS KINEMATICS_PLUGINS MOCK_HARDWARE "
        "DRIVER_CONTROLLER_TYPES MOVEIT_CONTROLLER_TYPES MOVEIT_HANDLE_TYPES MOVEIT_KINEMATICS_PLUGINS "
        "OMPL_PLANNER_NAMES OMPL_PLANNERS PIPELINES ROS2_CONTROLLER_TYPES SENSOR_TYPES SERVO_POSITION "
        "SERVO_TRAJECTORY VIRTUAL_JOINT_TYPES DEFAULT_ACTION_NS DEFAULT_OCTOMAP_RESOLUTION DEFAULT_PIPELINES "
        "DRIVERS FORWARD_POSITION KDL_PLUGIN SERVO_COMMAND_IN_TYPES SERVO_OUTPUTS"
    ),
    "pipeline_params": (
        "ADAPTER_FAMILIES bounds_problem effective_parameters flatten kind_problem known_parameters "
        "other_distros_reading parameter planner_of STRUCTURE_KEYS infinite_problem unknown_name_hint value_problem "
        "PipelineParameter PipelineParameterValue parameter_problem"
    ),
    "driver_params": "CONTROLLER_MANAGER driver_rows",
    "move_group_params": (
        "BY_ROS1_NAME MOVE_GROUP_PARAMS MoveGroupParam move_group_problem move_group_values written_values "
        "MoveGroupValue"
    ),
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.moveit_params.driver_params import CONTROLLER_MANAGER as CONTROLLER_MANAGER
    from marm_setup.moveit_params.driver_params import driver_rows as driver_rows
    from marm_setup.moveit_params.move_group_params import BY_ROS1_NAME as BY_ROS1_NAME
    from marm_setup.moveit_params.move_group_params import MOVE_GROUP_PARAMS as MOVE_GROUP_PARAMS
    from marm_setup.moveit_params.move_group_params import MoveGroupParam as MoveGroupParam
    from marm_setup.moveit_params.move_group_params import MoveGroupValue as MoveGroupValue
    from marm_setup.moveit_params.move_group_params import move_group_problem as move_group_problem
    from marm_setup.moveit_params.move_group_params import move_group_values as move_group_values
    from marm_setup.moveit_params.move_group_params import written_values as written_values
    from marm_setup.moveit_params.pipeline_params import ADAPTER_FAMILIES as ADAPTER_FAMILIES
    from marm_setup.moveit_params.pipeline_params import STRUCTURE_KEYS as STRUCTURE_KEYS
    from marm_setup.moveit_params.pipeline_params import PipelineParameter as PipelineParameter
    from marm_setup.moveit_params.pipeline_params import PipelineParameterValue as PipelineParameterValue
    from marm_setup.moveit_params.pipeline_params import bounds_problem as bounds_problem
    from marm_setup.moveit_params.pipeline_params import effective_parameters as effective_parameters
    from marm_setup.moveit_params.pipeline_params import flatten as flatten
    from marm_setup.moveit_params.pipeline_params import infinite_problem as infinite_problem
    from marm_setup.moveit_params.pipeline_params import kind_problem as kind_problem
    from marm_setup.moveit_params.pipeline_params import known_parameters as known_parameters
    from marm_setup.moveit_params.pipeline_params import other_distros_reading as other_distros_reading
    from marm_setup.moveit_params.pipeline_params import parameter as parameter
    from marm_setup.moveit_params.pipeline_params import parameter_problem as parameter_problem
    from marm_setup.moveit_params.pipeline_params import planner_of as planner_of
    from marm_setup.moveit_params.pipeline_params import unknown_name_hint as unknown_name_hint
    from marm_setup.moveit_params.pipeline_params import value_problem as value_problem
    from marm_setup.moveit_params.tables import FAMILIES as FAMILIES
    from marm_setup.moveit_params.tables import LOGS as LOGS
    from marm_setup.moveit_params.tables import ParamRow as ParamRow
    from marm_setup.moveit_params.tables import Table as Table
    from marm_setup.moveit_params.tables import family_of as family_of
    from marm_setup.moveit_params.tables import load_table as load_table
    from marm_setup.moveit_params.values import type_problem as type_problem
    from marm_setup.moveit_params.values import validator_problem as validator_problem
    from marm_setup.moveit_params.vocabulary import ARBOTIX_GRIPPER_ACTION_NS as ARBOTIX_GRIPPER_ACTION_NS
    from marm_setup.moveit_params.vocabulary import CHAIN_ONLY_PLUGINS as CHAIN_ONLY_PLUGINS
    from marm_setup.moveit_params.vocabulary import DEFAULT_ACTION_NS as DEFAULT_ACTION_NS
    from marm_setup.moveit_params.vocabulary import DEFAULT_OCTOMAP_RESOLUTION as DEFAULT_OCTOMAP_RESOLUTION
    from marm_setup.moveit_params.vocabulary import DEFAULT_PIPELINES as DEFAULT_PIPELINES
    from marm_setup.moveit_params.vocabulary import DEFAULT_PLANNER as DEFAULT_PLANNER
    from marm_setup.moveit_params.vocabulary import DRIVER_ACTION_NS as DRIVER_ACTION_NS
    from marm_setup.moveit_params.vocabulary import DRIVER_CONTROLLER_TYPES as DRIVER_CONTROLLER_TYPES
    from marm_setup.moveit_params.vocabulary import DRIVER_CONTROLLERS as DRIVER_CONTROLLERS
    from marm_setup.moveit_params.vocabulary import DRIVERS as DRIVERS
    from marm_setup.moveit_params.vocabulary import FOLLOW_JOINT_TRAJECTORY as FOLLOW_JOINT_TRAJECTORY
    from marm_setup.moveit_params.vocabulary import FOLLOW_JOINT_TRAJECTORY_NS as FOLLOW_JOINT_TRAJECTORY_NS
    from marm_setup.moveit_params.vocabulary import FORWARD_POSITION as FORWARD_POSITION
    from marm_setup.moveit_params.vocabulary import GRIPPER_CMD_NS as GRIPPER_CMD_NS
    from marm_setup.moveit_params.vocabulary import GRIPPER_COMMAND as GRIPPER_COMMAND
    from marm_setup.moveit_params.vocabulary import IKFAST_PLUGIN_SUFFIX as IKFAST_PLUGIN_SUFFIX
    from marm_setup.moveit_params.vocabulary import JOINT_DRIVER_CONTROLLERS as JOINT_DRIVER_CONTROLLERS
    from marm_setup.moveit_params.vocabulary import KDL_PLUGIN as KDL_PLUGIN
    from marm_setup.moveit_params.vocabulary import KINEMATICS_KEYS as KINEMATICS_KEYS
    from marm_setup.moveit_params.vocabulary import KINEMATICS_PLUGINS as KINEMATICS_PLUGINS
    from marm_setup.moveit_params.vocabulary import MOCK_HARDWARE as MOCK_HARDWARE
    from marm_setup.moveit_params.vocabulary import MOVEIT_CONTROLLER_TYPES as MOVEIT_CONTROLLER_TYPES
    from marm_setup.moveit_params.vocabulary import MOVEIT_HANDLE_TYPES as MOVEIT_HANDLE_TYPES
    from marm_setup.moveit_params.vocabulary import MOVEIT_KINEMATICS_PLUGINS as MOVEIT_KINEMATICS_PLUGINS
    from marm_setup.moveit_params.vocabulary import OMPL_PLANNER_NAMES as OMPL_PLANNER_NAMES
    from marm_setup.moveit_params.vocabulary import OMPL_PLANNERS as OMPL_PLANNERS
    from marm_setup.moveit_params.vocabulary import PIPELINES as PIPELINES
    from marm_setup.moveit_params.vocabulary import ROS2_CONTROLLER_TYPES as ROS2_CONTROLLER_TYPES
    from marm_setup.moveit_params.vocabulary import SENSOR_TYPES as SENSOR_TYPES
    from marm_setup.moveit_params.vocabulary import SERVO_COMMAND_IN_TYPES as SERVO_COMMAND_IN_TYPES
    from marm_setup.moveit_params.vocabulary import SERVO_OUTPUTS as SERVO_OUTPUTS
    from marm_setup.moveit_params.vocabulary import SERVO_POSITION as SERVO_POSITION
    from marm_setup.moveit_params.vocabulary import SERVO_TRAJECTORY as SERVO_TRAJECTORY
    from marm_setup.moveit_params.vocabulary import VIRTUAL_JOINT_TYPES as VIRTUAL_JOINT_TYPES

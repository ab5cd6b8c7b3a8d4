"""A MoveIt config package, read once: which file feeds each MoveIt file kind (following the
launch files: ROS 1 XML, ROS 2 XML, MoveIt 2 Python read statically), each kind parsed once
into a typed value that keeps its file and key path. validate, port and plan read only this.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "read": "read_package",
    "model": "MoveItPackage Source",
    "limits": "effective_limits LoadedLimit",
    "start": "package_start_values",
    "where": "FrozenMapping Param Value Where",
    "description": "marm_package_paths setup_assistant_description srdfs_by_name SRDF_GUESSED",
    "controllers_file": "ControllersFile MoveItController SIMPLE_MANAGER SIMPLE_MANAGER_CLASS SkippedController",
    "control_manager": "ROS2_CONTROL_HANDLES",
    "driver_file": "ArbotixFile ArbotixServo DriverController DriverFile InitialPositions read_simulator_drivers Ros2ControlFile Settings",
    "kinematics_file": "GroupKinematics KinematicsFile",
    "joint_limits_file": "JointLimitEntry JointLimitsFile",
    "perception_files": "Sensor ServoConfig",
    "planning_file": "GroupPlanning PlanningPipeline",
    "launch_xml": "condition LaunchXml",
    "substitution": "Scope SubstitutionError SubstitutionTooLarge substitute",
    "srdf_file": "SrdfFile read_srdf_file",
    "setup_files": "read_package_xml RecordedProofs",
    "launch_ros1": "LaunchParam launch_nodes",
    "launch_python": "undefined_unread_arg",
    "rosparam": "RosparamLoader",
    "received": "Received received_parameters",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.package.control_manager import ROS2_CONTROL_HANDLES as ROS2_CONTROL_HANDLES
    from marm_setup.package.controllers_file import SIMPLE_MANAGER as SIMPLE_MANAGER
    from marm_setup.package.controllers_file import SIMPLE_MANAGER_CLASS as SIMPLE_MANAGER_CLASS
    from marm_setup.package.controllers_file import ControllersFile as ControllersFile
    from marm_setup.package.controllers_file import MoveItController as MoveItController
    from marm_setup.package.controllers_file import SkippedController as SkippedController
    from marm_setup.package.description import SRDF_GUESSED as SRDF_GUESSED
    from marm_setup.package.description import marm_package_paths as marm_package_paths
    from marm_setup.package.description import setup_assistant_description as setup_assistant_description
    from marm_setup.package.description import srdfs_by_name as srdfs_by_name
    from marm_setup.package.driver_file import ArbotixFile as ArbotixFile
    from marm_setup.package.driver_file import ArbotixServo as ArbotixServo
    from marm_setup.package.driver_file import DriverController as DriverController
    from marm_setup.package.driver_file import DriverFile as DriverFile
    from marm_setup.package.driver_file import InitialPositions as InitialPositions
    from marm_setup.package.driver_file import Ros2ControlFile as Ros2ControlFile
    from marm_setup.package.driver_file import Settings as Settings
    from marm_setup.package.driver_file import read_simulator_drivers as read_simulator_drivers
    from marm_setup.package.joint_limits_file import JointLimitEntry as JointLimitEntry
    from marm_setup.package.joint_limits_file import JointLimitsFile as JointLimitsFile
    from marm_setup.package.kinematics_file import GroupKinematics as GroupKinematics
    from marm_setup.package.kinematics_file import KinematicsFile as KinematicsFile
    from marm_setup.package.launch_python import undefined_unread_arg as undefined_unread_arg
    from marm_setup.package.launch_ros1 import LaunchParam as LaunchParam
    from marm_setup.package.launch_ros1 import launch_nodes as launch_nodes
    from marm_setup.package.launch_xml import LaunchXml as LaunchXml
    from marm_setup.package.launch_xml import condition as condition
    from marm_setup.package.limits import LoadedLimit as LoadedLimit
    from marm_setup.package.limits import effective_limits as effective_limits
    from marm_setup.package.model import MoveItPackage as MoveItPackage
    from marm_setup.package.model import Source as Source
    from marm_setup.package.perception_files import Sensor as Sensor
    from marm_setup.package.perception_files import ServoConfig as ServoConfig
    from marm_setup.package.planning_file import GroupPlanning as GroupPlanning
    from marm_setup.package.planning_file import PlanningPipeline as PlanningPipeline
    from marm_setup.package.read import read_package as read_package
    from marm_setup.package.received import Received as Received
    from marm_setup.package.received import received_parameters as received_parameters
    from marm_setup.package.rosparam import RosparamLoader as RosparamLoader
    from marm_setup.package.setup_files import RecordedProofs as RecordedProofs
    from marm_setup.package.setup_files import read_package_xml as read_package_xml
    from marm_setup.package.srdf_file import SrdfFile as SrdfFile
    from marm_setup.package.srdf_file import read_srdf_file as read_srdf_file
    from marm_setup.package.start import package_start_values as package_start_values
    from marm_setup.package.substitution import Scope as Scope
    from marm_setup.package.substitution import SubstitutionError as SubstitutionError
    from marm_setup.package.substitution import SubstitutionTooLarge as SubstitutionTooLarge
    from marm_setup.package.substitution import substitute as substitute
    from marm_setup.package.where import FrozenMapping as FrozenMapping
    from marm_setup.package.where import Param as Param
    from marm_setup.package.where import Value as Value
    from marm_setup.package.where import Where as Where

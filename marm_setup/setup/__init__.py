"""The setup model (`marm_setup.yaml`): dataclasses, YAML I/O, inference from a robot, group
queries, SRDF reading, MoveIt's tables (`domain`), the one rule set and the setup checks.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "model": "SetupModel Group GroupState EndEffector VirtualJoint Controller",
        "yaml_io": "load_setup dump_setup setup_from_dict",
        "infer": "infer Inference",
        "checks": "check_setup",
        "rules": "check_semantics",
        "start_state": "demo_start_values model_start_values",
        "domain": "VIRTUAL_JOINT_TYPES MOVEIT_CONTROLLER_TYPES DRIVER_ACTION_NS KINEMATICS_PLUGINS OMPL_PLANNER_NAMES",
        "srdf": "read_srdf parse_srdf_string srdf_to_setup",
        "groups": "group_joints active_group_joints planning_joints",
    },
)

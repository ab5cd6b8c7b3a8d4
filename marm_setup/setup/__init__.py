"""The setup model (`marm_setup.yaml`): dataclasses, YAML I/O, inference from a robot, group
queries, SRDF reading and the setup checks.

Public API below (name -> module); names load on first use (see `marm_setup.exports`).
"""

from __future__ import annotations

from typing import Any

from marm_setup.exports import load_export

_API = {
    "SetupModel": "model",
    "Group": "model",
    "GroupState": "model",
    "EndEffector": "model",
    "VirtualJoint": "model",
    "Controller": "model",
    "load_setup": "yaml_io",
    "dump_setup": "yaml_io",
    "setup_from_dict": "yaml_io",
    "infer_setup": "infer",
    "check_setup": "checks",
    "read_srdf": "srdf",
    "parse_srdf_string": "srdf",
    "srdf_to_setup": "srdf",
    "group_joints": "groups",
    "active_group_joints": "groups",
    "planning_joints": "groups",
}
__all__ = sorted(_API)


def __getattr__(name: str) -> Any:
    return load_export(__name__, _API, name)


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})

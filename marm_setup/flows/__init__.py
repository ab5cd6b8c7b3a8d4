"""The flows behind the commands, one function per command: the CLI parses options, calls one of
these and prints what it returns (`cli/` holds no flow of its own, and no command calls
another's).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "build": "build_setup InitRequest target_of",
    "init": "InitResult run_init",
    "port": "PortInitRequest PortResult run_port",
    "write": "describe reused_ros2_control with_collision_matrix write_package",
    "render": "load_package_setup RenderResult run_render",
    "collisions": "CollisionsRequest CollisionsResult run_collisions run_package_collisions",
    "plan": "PlanRequest PlanResult run_plan",
    "report": "ReportRequest run_report",
    "settings": "DEFAULT_TRIALS MatrixSettings RobotInput",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.flows.build import InitRequest as InitRequest
    from marm_setup.flows.build import build_setup as build_setup
    from marm_setup.flows.build import target_of as target_of
    from marm_setup.flows.collisions import CollisionsRequest as CollisionsRequest
    from marm_setup.flows.collisions import CollisionsResult as CollisionsResult
    from marm_setup.flows.collisions import run_collisions as run_collisions
    from marm_setup.flows.collisions import run_package_collisions as run_package_collisions
    from marm_setup.flows.init import InitResult as InitResult
    from marm_setup.flows.init import run_init as run_init
    from marm_setup.flows.plan import PlanRequest as PlanRequest
    from marm_setup.flows.plan import PlanResult as PlanResult
    from marm_setup.flows.plan import run_plan as run_plan
    from marm_setup.flows.port import PortInitRequest as PortInitRequest
    from marm_setup.flows.port import PortResult as PortResult
    from marm_setup.flows.port import run_port as run_port
    from marm_setup.flows.render import RenderResult as RenderResult
    from marm_setup.flows.render import load_package_setup as load_package_setup
    from marm_setup.flows.render import run_render as run_render
    from marm_setup.flows.report import ReportRequest as ReportRequest
    from marm_setup.flows.report import run_report as run_report
    from marm_setup.flows.settings import DEFAULT_TRIALS as DEFAULT_TRIALS
    from marm_setup.flows.settings import MatrixSettings as MatrixSettings
    from marm_setup.flows.settings import RobotInput as RobotInput
    from marm_setup.flows.write import describe as describe
    from marm_setup.flows.write import reused_ros2_control as reused_ros2_control
    from marm_setup.flows.write import with_collision_matrix as with_collision_matrix
    from marm_setup.flows.write import write_package as write_package

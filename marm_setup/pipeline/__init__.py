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
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.pipeline.build import InitRequest as InitRequest
    from marm_setup.pipeline.build import build_setup as build_setup
    from marm_setup.pipeline.build import target_of as target_of
    from marm_setup.pipeline.collisions import CollisionsRequest as CollisionsRequest
    from marm_setup.pipeline.collisions import CollisionsResult as CollisionsResult
    from marm_setup.pipeline.collisions import run_collisions as run_collisions
    from marm_setup.pipeline.collisions import run_package_collisions as run_package_collisions
    from marm_setup.pipeline.init import InitResult as InitResult
    from marm_setup.pipeline.init import run_init as run_init
    from marm_setup.pipeline.plan import PlanRequest as PlanRequest
    from marm_setup.pipeline.plan import PlanResult as PlanResult
    from marm_setup.pipeline.plan import run_plan as run_plan
    from marm_setup.pipeline.port import PortInitRequest as PortInitRequest
    from marm_setup.pipeline.port import PortResult as PortResult
    from marm_setup.pipeline.port import run_port as run_port
    from marm_setup.pipeline.render import RenderResult as RenderResult
    from marm_setup.pipeline.render import load_package_setup as load_package_setup
    from marm_setup.pipeline.render import run_render as run_render
    from marm_setup.pipeline.report import ReportRequest as ReportRequest
    from marm_setup.pipeline.report import run_report as run_report
    from marm_setup.pipeline.write import describe as describe
    from marm_setup.pipeline.write import reused_ros2_control as reused_ros2_control
    from marm_setup.pipeline.write import with_collision_matrix as with_collision_matrix
    from marm_setup.pipeline.write import write_package as write_package

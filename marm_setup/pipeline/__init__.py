"""The flows behind the commands, one function per command: the CLI parses options, calls one of
these and prints what it returns (`cli/` holds no flow of its own, and no command calls
another's).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "build": "InitRequest build_setup target_of",
        "init": "InitResult run_init",
        "port": "PortInitRequest PortResult run_port",
        "write": "with_collision_matrix describe reused_ros2_control write_package",
        "render": "RenderResult run_render load_package_setup",
        "collisions": "CollisionsRequest CollisionsResult run_collisions run_package_collisions",
        "plan": "PlanRequest PlanResult run_plan",
        "report": "ReportRequest run_report",
    },
)

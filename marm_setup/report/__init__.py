"""The report: one offline HTML page with the robot drawn at every pose, its groups, the
findings, the collision matrix and the planned trajectories (`marm-setup report`).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "build": "build_report Report",
        "page": "render_page",
    },
)

"""The report: one offline HTML page with the robot drawn at every pose, its groups, the
findings, the collision matrix and the planned trajectories (`marm-setup report`).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "build": "build_report Report",
    "page": "render_page",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.report.build import Report as Report
    from marm_setup.report.build import build_report as build_report
    from marm_setup.report.page import render_page as render_page

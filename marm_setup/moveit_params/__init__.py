"""MoveIt's declared parameters per distro family, as data (tables.py, data/<family>.yaml),
how a value fits them (values.py), what a ROS 2 package hands each node (received.py), and how
the tables are rebuilt from MoveIt's sources (regenerate.py).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "tables": "FAMILIES LOGS ParamRow Table family_of load_table",
    "values": "type_problem validator_problem",
    "received": "Received received_parameters",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.moveit_params.received import Received as Received
    from marm_setup.moveit_params.received import received_parameters as received_parameters
    from marm_setup.moveit_params.tables import FAMILIES as FAMILIES
    from marm_setup.moveit_params.tables import LOGS as LOGS
    from marm_setup.moveit_params.tables import ParamRow as ParamRow
    from marm_setup.moveit_params.tables import Table as Table
    from marm_setup.moveit_params.tables import family_of as family_of
    from marm_setup.moveit_params.tables import load_table as load_table
    from marm_setup.moveit_params.values import type_problem as type_problem
    from marm_setup.moveit_params.values import validator_problem as validator_problem

"""A MoveIt config package, read once: which file feeds each MoveIt file kind (following the
launch files: ROS 1 XML, ROS 2 XML, MoveIt 2 Python read statically), each kind parsed once
into a typed value that keeps its file and key path. validate, port and plan read only this.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "read": "read_package",
        "model": "MoveItPackage Source",
        "limits": "LoadedLimit effective_limits",
        "start": "package_start_values",
        "where": "Where Param",
    },
)

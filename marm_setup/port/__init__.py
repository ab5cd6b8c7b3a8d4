"""Porting an existing MoveIt config package (MoveIt 1 or 2, any layout) into a setup, with a
report of every setting carried over, changed or dropped.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "importer": "PortRequest Ported port_package",
        "report": "PortItem counts",
    },
)

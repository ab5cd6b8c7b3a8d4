"""Porting an existing MoveIt config package (MoveIt 1 or 2, any layout) into a setup, with a
report of every setting carried over, changed or dropped.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "blame": "blamed_on_source",
    "importer": "port_package Ported PortRequest",
    "port_log": "counts PortItem STATUSES summary",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.port.blame import blamed_on_source as blamed_on_source
    from marm_setup.port.importer import Ported as Ported
    from marm_setup.port.importer import PortRequest as PortRequest
    from marm_setup.port.importer import port_package as port_package
    from marm_setup.port.port_log import STATUSES as STATUSES
    from marm_setup.port.port_log import PortItem as PortItem
    from marm_setup.port.port_log import counts as counts
    from marm_setup.port.port_log import summary as summary

"""Printing a port: the report (text grouped by status, or one JSON document) plus the new
package's validation summary."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

from marm_setup.cli.common import one_line

if TYPE_CHECKING:
    from marm_setup.flows import PortResult
    from marm_setup.port import PortItem

HEADINGS = {
    "carried": "carried over",
    "changed": "changed on the way (and why)",
    "dropped": "dropped (and why)",
    "todo": "still to do by hand",
}


def format_port_text(result: PortResult) -> str:
    """The port report as text: a summary line; first what changes how the robot moves (what
    was not carried as it was, one line each, and how many settings were), then the other
    items under one heading per status."""
    from marm_setup.port import STATUSES, counts

    ported = result.ported
    n = counts(ported.items)
    lines = [
        f"ported {ported.source} ({ported.source_target}, {ported.source_layout} layout) to "
        f"{result.model.target} ({result.model.distro}): " + ", ".join(f"{n[s]} {s}" for s in STATUSES)
    ]
    motion = [i for i in ported.items if i.moves_robot]
    moved = counts(tuple(motion))
    lines.append(
        "how the robot moves (limits, scaling, controllers, IK, planners, execution): "
        + ", ".join(f"{moved[s]} {s}" for s in STATUSES)
    )
    lines += [one_line(f"  {i.status} {_item(i)}") for i in motion if i.status != "carried"]
    for status in STATUSES:
        items = [
            i for i in ported.items if i.status == status and not (i.moves_robot and status != "carried")
        ]
        if items:
            lines.append(f"{HEADINGS[status]}:")
            lines += [one_line(f"  {_item(i)}") for i in items]
    return "\n".join(lines) + "\n"


def closing_line(result: PortResult) -> str:
    """The last line: the new package's validation summary and what was not carried."""
    from marm_setup.findings import summary as validation_summary
    from marm_setup.port import summary

    return f"{validation_summary(result.validation.findings)}; {summary(result.ported.items)}"


def _item(item: PortItem) -> str:
    source = f" [{item.source}]" if item.source else ""
    detail = f": {item.detail}" if item.detail else ""
    return f"{item.setting}{detail}{source}"


def format_port_json(result: PortResult) -> str:
    """One JSON document: the port (source, target, counts, items), the files written and the
    new package's validation (its summary and findings)."""
    from marm_setup.findings import format_json
    from marm_setup.port import counts, summary

    ported, validation = result.ported, result.validation
    doc = {
        "port": {
            "source": ported.source,
            "source_target": ported.source_target,
            "source_layout": ported.source_layout,
            "target": result.model.target,
            "ros_distro": result.model.distro,
            "counts": counts(ported.items),
            "motion_counts": counts(ported.items, motion_only=True),
            "summary": summary(ported.items),
            "items": [i.as_dict() for i in ported.items],
        },
        "files": list(result.status_lines),
        "validation": json.loads(format_json(validation.findings, checked=validation.as_dict())),
    }
    return json.dumps(doc, indent=2) + "\n"

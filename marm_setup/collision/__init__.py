"""Self-collision: link pairs and their reasons, the coal collision scene, MoveIt's collision
matrix, SRDF updates and the matrix report.

Public API below (name -> module); names load on first use (see `marm_setup.exports`).
"""

from __future__ import annotations

from typing import Any

from marm_setup.exports import load_export

_API = {
    "DisabledPair": "pairs",
    "DisabledReason": "pairs",
    "link_pair": "pairs",
    "CollisionScene": "scene",
    "CollisionMatrix": "matrix",
    "compute_collision_matrix": "matrix",
    "update_srdf": "srdf_update",
    "render_minimal_srdf": "srdf_update",
    "read_srdf_entries": "srdf_update",
    "describe_matrix": "report",
    "render_matrix_svg": "report",
    "render_matrix_html": "report",
}
__all__ = sorted(_API)


def __getattr__(name: str) -> Any:
    return load_export(__name__, _API, name)


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})

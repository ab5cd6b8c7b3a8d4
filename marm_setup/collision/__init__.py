"""Self-collision: link pairs and their reasons, the coal collision scene, MoveIt's collision
matrix, SRDF updates and the matrix report.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "pairs": "DisabledPair DisabledReason link_pair",
        "scene": "CollisionScene",
        "matrix": "CollisionMatrix compute_collision_matrix",
        "srdf_update": "update_srdf render_minimal_srdf read_srdf_entries",
        "report": "describe_matrix render_matrix_svg render_matrix_html",
    },
)

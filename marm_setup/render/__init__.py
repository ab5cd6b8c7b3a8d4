"""Rendering a config package: the per-template context, the whole package in memory, and the
atomic writer with its edit-guarding manifest.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "context": "build_context",
        "package": "render_package",
        "writer": "plan_writes apply_writes check_output_dir write_text_atomic",
    },
)

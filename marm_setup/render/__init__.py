"""Rendering a config package: the per-template context, the whole package in memory, and the
atomic writer with its edit-guarding manifest.

Public API below (name -> module); names load on first use (see `marm_setup.exports`).
"""

from __future__ import annotations

from typing import Any

from marm_setup.exports import load_export

_API = {
    "build_context": "context",
    "render_package": "package",
    "plan_writes": "writer",
    "apply_writes": "writer",
    "check_output_dir": "writer",
    "write_text_atomic": "writer",
}
__all__ = sorted(_API)


def __getattr__(name: str) -> Any:
    return load_export(__name__, _API, name)


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})

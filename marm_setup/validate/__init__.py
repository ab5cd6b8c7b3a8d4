"""Validating a config package: discovery of its files, the rule families (`rules/`), the runner
and the runtime (planning) checks.

Public API below (name -> module); names load on first use (see `marm_setup.exports`).
"""

from __future__ import annotations

from typing import Any

from marm_setup.exports import load_export

_API = {
    "discover_package": "discovery",
    "validate": "runner",
    "check_runtime": "runtime",
}
__all__ = sorted(_API)


def __getattr__(name: str) -> Any:
    return load_export(__name__, _API, name)


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})

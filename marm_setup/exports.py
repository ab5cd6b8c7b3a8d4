"""Lazy public APIs for the subpackages.

Each subpackage's `__init__.py` names its public API in a table (name -> module) and loads a
name from its module on first use, so importing one light module of a package (for example
`marm_setup.collision.pairs`) never pulls in coal or trimesh through the package's `__init__`.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from typing import Any


def load_export(package: str, api: Mapping[str, str], name: str) -> Any:
    """`package.<api[name]>.name`, or AttributeError as for any missing attribute."""
    module = api.get(name)
    if module is None:
        raise AttributeError(f"module {package!r} has no attribute {name!r}")
    return getattr(importlib.import_module(f"{package}.{module}"), name)

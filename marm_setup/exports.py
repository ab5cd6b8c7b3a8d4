"""Lazy public APIs for the subpackages.

Each subpackage's `__init__.py` names its public API as `{module: "name name ..."}` and gets
its module-level `__getattr__` and `__dir__` from `lazy_api`: a name loads from its module on
first use, so importing one light module of a package (e.g. `marm_setup.collision.pairs`)
never pulls in coal or trimesh through the package's `__init__`.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any


def lazy_api(
    package: str, api: Mapping[str, str]
) -> tuple[list[str], Callable[[str], Any], Callable[[], list[str]]]:
    """(`__all__`, `__getattr__`, `__dir__`) for `package`, whose public names are
    `api[module].split()` for each of its modules."""
    home = {name: module for module, names in api.items() for name in names.split()}

    def getattr_(name: str) -> Any:
        module = home.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(f"{package}.{module}"), name)

    def dir_() -> list[str]:
        return sorted({*vars(importlib.import_module(package)), *home})

    return sorted(home), getattr_, dir_

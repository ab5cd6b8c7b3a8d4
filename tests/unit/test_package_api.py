"""Each subpackage's public API: every listed name resolves, and the lazy table keeps a light
module's import from loading the heavy libraries through the package's `__init__`."""

from __future__ import annotations

import importlib
import subprocess
import sys

import pytest

PACKAGES = (
    "robot",
    "collision",
    "setup",
    "inference",
    "moveit_params",
    "render",
    "package",
    "plan",
    "validate",
    "port",
    "report",
    "flows",
)


@pytest.mark.parametrize("package", PACKAGES)
def test_every_public_name_resolves(package):
    module = importlib.import_module(f"marm_setup.{package}")
    assert module.__all__, f"marm_setup.{package} names no public API"
    for name in module.__all__:
        assert getattr(module, name) is not None, name
    assert set(module.__all__) <= set(dir(module))


def test_unknown_name_is_an_attribute_error():
    import marm_setup.collision

    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        marm_setup.collision.nope  # noqa: B018


def test_light_module_does_not_load_coal_through_its_package():
    code = "import sys, marm_setup.collision.pairs; print('coal' in sys.modules, 'trimesh' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]


@pytest.mark.parametrize("package", PACKAGES)
def test_type_checkers_see_the_same_names(package):
    """The TYPE_CHECKING imports of each `__init__` name exactly its API table, each from its
    module (other packages import these names from the package; the import-linter contracts
    refuse a reach into its modules)."""
    import ast
    from pathlib import Path

    module = importlib.import_module(f"marm_setup.{package}")
    tree = ast.parse(Path(module.__file__).read_text(encoding="utf-8"))
    typed = {
        (node.module.removeprefix(f"marm_setup.{package}."), alias.name)
        for block in tree.body
        if isinstance(block, ast.If)
        for node in block.body
        if isinstance(node, ast.ImportFrom)
        for alias in node.names
    }
    assert typed == {(m, name) for m, names in module.API.items() for name in names.split()}

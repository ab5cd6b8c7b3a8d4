"""Test helpers: inline file trees and tiny URDFs (copier's build_file_tree, yourdfpy's inline XML)."""

from __future__ import annotations

import textwrap
from pathlib import Path


def build_file_tree(root: Path, files: dict[str, str]) -> Path:
    """Write {relative path: dedented text} below `root`; returns root."""
    for rel, text in files.items():
        path = root / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    return root


def urdf(body: str, name: str = "test_robot") -> str:
    """A URDF document around `body` (links and joints)."""
    return f'<?xml version="1.0"?>\n<robot name="{name}">\n{textwrap.dedent(body)}\n</robot>\n'


TWO_BOXES = urdf(
    """
    <link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
    <link name="b"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
    <joint name="j" type="revolute">
      <parent link="a"/><child link="b"/><origin xyz="0 0 0.2"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" velocity="1" effort="1"/>
    </joint>
    """
)

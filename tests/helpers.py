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


# A three-joint arm base -> l1 -> l2 -> l3 (j1 with zero outside its limits, j2 with zero near one),
# and a gripper's two fingers on a link `hand`.
BOX = '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>'
ARM = f"""
    <link name="base">{BOX}</link><link name="l1">{BOX}</link><link name="l2">{BOX}</link>
    <link name="l3">{BOX}</link>
    <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.1"/>
      <axis xyz="0 0 1"/><limit lower="0.5" upper="1.0" velocity="1" effort="1"/></joint>
    <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.1"/>
      <axis xyz="0 1 0"/><limit lower="-3.1416" upper="0.0873" velocity="1" effort="1"/></joint>
    <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/><origin xyz="0 0 0.1"/>
      <axis xyz="0 1 0"/><limit lower="-2" upper="2" velocity="1" effort="1"/></joint>
"""


def fixed_link(parent: str, child: str, geometry: bool = False) -> str:
    """A link fixed to `parent` (with a small box when `geometry`)."""
    link = f'<link name="{child}">{BOX if geometry else ""}</link>'
    return f'{link}<joint name="{child}_joint" type="fixed"><parent link="{parent}"/><child link="{child}"/></joint>'


FINGERS = f"""
    <link name="finger_l">{BOX}</link><link name="finger_r">{BOX}</link>
    <joint name="finger_joint_l" type="prismatic"><parent link="hand"/><child link="finger_l"/>
      <origin xyz="0 0.02 0.05"/><axis xyz="0 1 0"/><limit lower="0" upper="0.04" velocity="0.1" effort="1"/></joint>
    <joint name="finger_joint_r" type="prismatic"><parent link="hand"/><child link="finger_r"/>
      <origin xyz="0 -0.02 0.05"/><axis xyz="0 -1 0"/><limit lower="0" upper="0.04" velocity="0.1" effort="1"/>
      <mimic joint="finger_joint_l"/></joint>
"""


# A `xacro` command for launchers (roslaunch's command=, the generated mock-hardware script) that
# runs marm-setup's real-xacro expansion: `$(find pkg)` through ROS_PACKAGE_PATH and the folders
# around the file (pip's xacro has no ament index).
XACRO_SHIM = """#!{python}
import sys
from pathlib import Path
from marm_setup.robot.ros_packages import find_packages
from marm_setup.robot.load import expand_xacro, parse_xacro_args
args = [a for a in sys.argv[1:] if not a.startswith("-")]
file = Path(args[0])
sys.stdout.write(expand_xacro(file, parse_xacro_args(args[1:]), find_packages([], near=file), shown=str(file)))
"""


def write_xacro_shim(folder: Path) -> Path:
    """`folder/xacro` (XACRO_SHIM for this interpreter), executable; returns the folder."""
    import sys

    folder.mkdir(parents=True, exist_ok=True)
    shim = folder / "xacro"
    shim.write_text(XACRO_SHIM.format(python=sys.executable))
    shim.chmod(0o755)
    return folder

"""A fixed virtual joint whose parent frame is one of the robot's own links. MoveIt keeps the
root link as its model frame for a fixed virtual joint (moveit_core robot_model.cpp "for fixed
frames we still use the robot root link", moveit l.963, moveit2 l.1027): the parent frame only
matters to TF, and makes a loop only where a launch file publishes the virtual joint's transform
(the Setup Assistant's demo.launch virtual_joint_broadcaster, MoveIt 2's
static_virtual_joint_tfs.launch.py). Without one it is a likely mistake, not a failure (MoveIt's
own prbt_moveit_config has such a joint and no broadcaster)."""

from __future__ import annotations

from pathlib import Path

from marm_setup.findings import Finding
from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

SRDF6 = "config/6dof/vx.srdf"
VJ = 'parent_frame="world" child_link="base_link"'
BROADCASTER = (
    '<launch>\n  <node pkg="tf2_ros" type="static_transform_publisher" name="virtual_joint_broadcaster_0"'
    ' args="0 0 0 0 0 0 link2 base_link"/>\n</launch>\n'
)


def findings(source: Path, paths: list[Path]) -> list[Finding]:
    return list(validate(source, package_paths=paths, plan=False, matrix_trials=0).findings)


def of_rule(found: list[Finding], rule: str) -> list[tuple[str, str]]:
    return [(str(f.severity), f.element) for f in found if f.rule == rule]


def parent_link2(source: Path, joint_type: str = "fixed") -> None:
    srdf = source / SRDF6
    text = srdf.read_text()
    assert VJ in text
    text = text.replace(VJ, 'parent_frame="link2" child_link="base_link"')
    srdf.write_text(
        text.replace('type="fixed" parent_frame="link2"', f'type="{joint_type}" parent_frame="link2"')
    )


def test_no_launch_publishes_the_fixed_virtual_joint_a_warning(tmp_path):
    source, paths = PACKAGES["arg_selected"](tmp_path)
    parent_link2(source)
    found = findings(source, paths)
    assert of_rule(found, "srdf.virtual-joint-parent") == [("warning", "virtual_joint[world_joint]")]


def test_a_launch_publishing_the_virtual_joint_keeps_the_error(tmp_path):
    source, paths = PACKAGES["arg_selected"](tmp_path)
    parent_link2(source)
    (source / "launch/demo.launch").write_text(BROADCASTER)
    found = findings(source, paths)
    assert of_rule(found, "srdf.virtual-joint-parent") == [("error", "virtual_joint[world_joint]")]


def test_a_ros2_static_virtual_joint_tfs_launch_keeps_the_error(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path)
    srdf = next(p for p in source.rglob("*.srdf"))
    text = srdf.read_text()
    assert VJ in text
    srdf.write_text(text.replace(VJ, 'parent_frame="link2" child_link="base_link"'))
    assert of_rule(findings(source, paths), "srdf.virtual-joint-parent") == [
        ("warning", "virtual_joint[world_joint]")
    ]
    (source / "launch/static_virtual_joint_tfs.launch.py").write_text(
        "from moveit_configs_utils import MoveItConfigsBuilder\n"
        "from moveit_configs_utils.launches import generate_static_virtual_joint_tfs_launch\n\n\n"
        "def generate_launch_description():\n"
        '    moveit_config = MoveItConfigsBuilder("bot", package_name="bot_moveit_config").to_moveit_configs()\n'
        "    return generate_static_virtual_joint_tfs_launch(moveit_config)\n"
    )
    assert of_rule(findings(source, paths), "srdf.virtual-joint-parent") == [
        ("error", "virtual_joint[world_joint]")
    ]


def test_a_planar_virtual_joint_on_an_own_link_stays_an_error(tmp_path):
    """For planar and floating joints the parent frame is MoveIt's model frame (robot_model.cpp)."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    parent_link2(source, "planar")
    found = findings(source, paths)
    assert of_rule(found, "srdf.virtual-joint-parent") == [("error", "virtual_joint[world_joint]")]

"""A virtual joint whose child is not the URDF's root. MoveIt's RobotModel (robot_model.cpp,
the URDF root: moveit l.931-945, moveit2 l.989-1003) skips it with "Skipping virtual joint ...
does not match the URDF frame", except for a fixed virtual joint onto a URDF whose root is a
`world` link without collision or visual geometry (Gazebo's dummy world link): then it builds
the fixed joint, silently, whatever the parent frame (kinova-ros's j2n6s300_moveit_config:
parent `world_frame`, child `root`, URDF root `world`). The parent frame's name is not the test."""

from __future__ import annotations

from pathlib import Path

from marm_setup.findings import Finding
from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

URDF = "vx_description/urdf/vx6.urdf"
SRDF6 = "config/6dof/vx.srdf"
VJ = 'type="fixed" parent_frame="world" child_link="base_link"'
WORLD = (
    '<link name="world"/><joint name="world_fixed" type="fixed"><parent link="world"/>'
    '<child link="base_link"/></joint>'
)


def virtual_findings(source: Path, paths: list[Path]) -> list[tuple[str, str]]:
    found: list[Finding] = list(validate(source, package_paths=paths, plan=False, matrix_trials=0).findings)
    return [(str(f.severity), f.rule) for f in found if f.rule.startswith("srdf.virtual")]


def world_rooted(tmp_path: Path, world: str = WORLD, vj: str = 'type="fixed" parent_frame="world_frame"'):
    source, paths = PACKAGES["arg_selected"](tmp_path)
    urdf = tmp_path / URDF
    text = urdf.read_text()
    urdf.write_text(text.replace('<link name="base_link">', world + '<link name="base_link">', 1))
    srdf = source / SRDF6
    srdf.write_text(srdf.read_text().replace(VJ, f'{vj} child_link="base_link"'))
    return source, paths


def test_a_fixed_virtual_joint_onto_an_empty_world_root_is_built_silently(tmp_path):
    assert virtual_findings(*world_rooted(tmp_path)) == []


def test_a_world_root_with_geometry_is_skipped_with_a_warning(tmp_path):
    world = WORLD.replace(
        '<link name="world"/>',
        '<link name="world"><visual><geometry><box size="1 1 1"/></geometry></visual></link>',
    )
    assert virtual_findings(*world_rooted(tmp_path, world)) == [("warning", "srdf.virtual-joint-child")]


def test_a_planar_virtual_joint_onto_a_world_root_is_skipped(tmp_path):
    found = virtual_findings(*world_rooted(tmp_path, vj='type="planar" parent_frame="odom"'))
    assert found == [("error", "srdf.virtual-joint-child")]


def test_a_parent_frame_named_like_a_root_other_than_world_is_skipped_with_a_warning(tmp_path):
    """Root `base_link`, virtual joint base_link -> link1: MoveIt warns and skips it."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    srdf = source / SRDF6
    srdf.write_text(srdf.read_text().replace(VJ, 'type="fixed" parent_frame="base_link" child_link="link1"'))
    assert virtual_findings(source, paths) == [("warning", "srdf.virtual-joint-child")]

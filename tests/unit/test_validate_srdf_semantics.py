"""SRDF forms MoveIt / srdfdom accept, read as they read them (keep-one-thing / break-one-thing
on a copy of the real MoveIt 1 panda package in tmp_path)."""

from __future__ import annotations

from tests.validate_helpers import copy_package, panda, replace_text, run

SRDF = "config/panda.srdf"
VJ = '<virtual_joint name="virtual_joint" type="fixed" parent_frame="world" child_link="panda_link0"/>'


def found(pkg, good, rule_prefix=""):
    return sorted(
        (f.rule, f.severity, f.element)
        for f in run(pkg, good, matrix_trials=0)
        if f.rule.startswith(rule_prefix)
    )


def test_disable_default_collisions_and_enable_collisions_shape_the_matrix(tmp_path):
    """The transport pose's one real collision (panda_link5 - panda_link7) is not checked once
    panda_link7's collisions are off by default, and is again once the pair is re-enabled."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    assert found(pkg, good, "pose.collision") == [("pose.collision", "error", "group_state[transport]")]
    replace_text(pkg, SRDF, "</robot>", '<disable_default_collisions link="panda_link7"/></robot>')
    assert found(pkg, good, "pose.collision") == []
    replace_text(
        pkg, SRDF, "</robot>", '<enable_collisions link1="panda_link7" link2="panda_link5"/></robot>'
    )
    assert found(pkg, good, "pose.collision") == [("pose.collision", "error", "group_state[transport]")]


def test_a_group_may_name_the_virtual_joint(tmp_path):
    """srdfdom's isValidJoint accepts the SRDF's own virtual joints in groups."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(
        pkg, SRDF, '<group name="hand">', '<group name="hand">\n        <joint name="virtual_joint"/>'
    )
    assert found(pkg, good, "srdf.") == []


def test_a_virtual_joint_below_a_urdf_root_named_like_its_parent_frame(tmp_path):
    """A URDF that already has the `world` root (Gazebo's fixed joint): MoveIt 2 does not warn."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(
        pkg,
        SRDF,
        VJ,
        VJ.replace('child_link="panda_link0"', 'child_link="panda_link1"').replace(
            'parent_frame="world"', 'parent_frame="panda_link0"'
        ),
    )
    assert found(pkg, good, "srdf.virtual") == []
    replace_text(pkg, SRDF, 'parent_frame="panda_link0"', 'parent_frame="world"')
    assert found(pkg, good, "srdf.virtual") == [
        ("srdf.virtual-joint-child", "warning", "virtual_joint[virtual_joint]")
    ]


def test_a_passive_joint_nested_in_a_group_is_ignored_by_srdfdom(tmp_path):
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(
        pkg, SRDF, '<group name="hand">', '<group name="hand">\n        <passive_joint name="panda_joint7"/>'
    )
    assert found(pkg, good, "srdf.nested") == [
        ("srdf.nested-passive-joint", "error", "group[hand].passive_joint")
    ]

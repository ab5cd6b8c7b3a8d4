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
    """The panda's root is panda_link0, not an empty `world` link: MoveIt skips a virtual joint
    onto panda_link1 with a warning whatever its parent frame (robot_model.cpp, moveit2
    l.989-1003; the Gazebo `world` root is tests/unit/test_validate_virtual_joint_world_root.py)."""
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
    assert found(pkg, good, "srdf.virtual") == [
        ("srdf.virtual-joint-child", "warning", "virtual_joint[virtual_joint]")
    ]
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


def test_one_malformed_srdf_element_leaves_the_rest_checked(tmp_path):
    """A pose value without its attribute (srdfdom skips that <joint>): that value is reported,
    every other element is still read and checked (the transport collision is still found)."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, SRDF, '<joint name="panda_joint1" value="0"/>', '<joint name="panda_joint1"/>')
    errors = sorted((f.rule, f.element) for f in run(pkg, good, matrix_trials=0) if f.is_error)
    assert errors == [
        ("pose.collision", "group_state[transport]"),
        ("srdf.parse", "group_state[ready].joint[panda_joint1]"),
    ]


def test_a_group_this_validator_cannot_model_is_skipped_without_a_cascade(tmp_path):
    """Two <chain>s in one group (srdfdom reads them): a warning that it is not checked, and no
    'unknown group' from kinematics, OMPL or poses that name it."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    chain = '<chain base_link="panda_link0" tip_link="panda_link8"/>'
    replace_text(pkg, SRDF, chain, chain + "\n" + chain)
    found = [
        (f.rule, f.severity, f.element)
        for f in run(pkg, good, matrix_trials=0)
        if f.file != "launch/demo.launch"
    ]
    assert ("srdf.unsupported", "warning", "group[panda_arm]") in found
    # poses may collide now that the arm's `ready` start pose is gone: the rest is no cascade
    assert not [f for f in found if f[1] == "error" and f[0] != "pose.collision"], found


def test_double_hyphens_in_an_srdf_comment_are_read_as_srdfdom_reads_them(tmp_path):
    """srdfdom's tinyxml2 takes `--` inside a comment (libxml2 does not): no srdf.parse, and the
    SRDF rules run (the transport pose's real collision is still found)."""
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, SRDF, "<robot", "<!-- edited -- by hand --->\n<robot")
    assert found(pkg, good, "srdf.") == []
    assert found(pkg, good, "pose.collision") == [("pose.collision", "error", "group_state[transport]")]

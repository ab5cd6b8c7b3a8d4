"""matrix.stale: a Never pair that collides in nearly every resampled state is what the Setup
Assistant labels Always and disables all the same (franka_ros2's panda_link1 - panda_link3 on
its capsule geometry): MoveIt reads no reason label, so nothing is stale. A Never pair that
collides in some states only is still flagged."""

from __future__ import annotations

from marm_setup.collision import CollisionScene
from marm_setup.robot.load import load_robot
from marm_setup.setup.srdf import parse_srdf_string
from marm_setup.validate.rules.matrix_rules import check_matrix_fresh

URDF = """<robot name="tri">
  <link name="base"><collision><geometry><sphere radius="0.3"/></geometry></collision></link>
  <link name="hub"><collision><geometry><sphere radius="0.3"/></geometry></collision></link>
  <link name="arm"><collision><origin xyz="1 0 0"/><geometry><sphere radius="0.1"/></geometry></collision></link>
  <link name="post"><collision><origin xyz="1 0 0"/><geometry><sphere radius="0.1"/></geometry></collision></link>
  <joint name="j_hub" type="revolute"><parent link="base"/><child link="hub"/>
    <axis xyz="0 0 1"/><limit lower="-3.14" upper="3.14" effort="1" velocity="1"/></joint>
  <joint name="j_arm" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-3.14" upper="3.14" effort="1" velocity="1"/></joint>
  <joint name="j_post" type="fixed"><parent link="base"/><child link="post"/></joint>
</robot>
"""
SRDF = """<robot name="tri">
  <group name="all"><joint name="j_hub"/><joint name="j_arm"/></group>
  <disable_collisions link1="base" link2="hub" reason="Adjacent"/>
  <disable_collisions link1="base" link2="arm" reason="Adjacent"/>
  <disable_collisions link1="base" link2="post" reason="Adjacent"/>
  <disable_collisions link1="arm" link2="hub" reason="Never"/>
  <disable_collisions link1="hub" link2="post" reason="Never"/>
  <disable_collisions link1="arm" link2="post" reason="Never"/>
</robot>
"""


def test_a_never_pair_colliding_always_is_not_stale_one_colliding_sometimes_is(tmp_path):
    """hub-post and arm-hub: hub's sphere is the base's, the others 1 m out, never touching it;
    arm-post: the arm's sphere meets the post's only near j_arm = 0 (about 6 % of states)."""
    urdf = tmp_path / "tri.urdf"
    urdf.write_text(URDF, encoding="utf-8")
    robot = load_robot(urdf)
    found = check_matrix_fresh(parse_srdf_string(SRDF), robot, CollisionScene(robot), "tri.srdf")
    assert [(f.rule, f.element) for f in found] == [("matrix.stale", "disable_collisions[arm post]")]
    always = SRDF.replace(
        '<disable_collisions link1="hub" link2="post" reason="Never"/>',
        '<disable_collisions link1="hub" link2="post" reason="Never"/>'
        '<disable_collisions link1="base" link2="hub" reason="Never"/>',
    ).replace('<disable_collisions link1="base" link2="hub" reason="Adjacent"/>', "")
    found = check_matrix_fresh(parse_srdf_string(always), robot, CollisionScene(robot), "tri.srdf")
    assert [f.element for f in found] == ["disable_collisions[arm post]"]  # base-hub: Always, not stale

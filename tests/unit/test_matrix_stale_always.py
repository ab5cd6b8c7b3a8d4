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


def _with_proxy(tmp_path, radius: float, proxy_pair: str):
    """The robot with `arm_sc`, a sphere of `radius` fixed on the arm where its own sphere is
    (franka_description's `*_sc` self-collision links), and the SRDF with `proxy_pair` for the
    pair arm_sc - post."""
    urdf = tmp_path / "tri_sc.urdf"
    urdf.write_text(
        URDF.replace(
            "</robot>",
            f'  <link name="arm_sc"><collision><origin xyz="1 0 0"/><geometry><sphere radius="{radius}"/>'
            "</geometry></collision></link>\n"
            '  <joint name="j_sc" type="fixed"><parent link="arm"/><child link="arm_sc"/></joint>\n</robot>',
        ),
        encoding="utf-8",
    )
    srdf = SRDF.replace(
        "</robot>",
        '  <disable_collisions link1="arm" link2="arm_sc" reason="Adjacent"/>\n'
        '  <disable_collisions link1="arm_sc" link2="base" reason="Adjacent"/>\n'
        '  <disable_collisions link1="arm_sc" link2="hub" reason="Never"/>\n'
        f"  {proxy_pair}\n</robot>",
    )
    robot = load_robot(urdf)
    return check_matrix_fresh(parse_srdf_string(srdf), robot, CollisionScene(robot), "tri.srdf")


def test_a_never_pair_whose_rigid_bodies_collide_through_an_enabled_proxy_pair_is_not_stale(tmp_path):
    """arm - post disabled, arm_sc (enclosing the arm's sphere, fixed to it) - post enabled:
    MoveIt finds every state where arm meets post in collision through arm_sc."""
    assert _with_proxy(tmp_path, 0.15, "") == []
    disabled = _with_proxy(tmp_path, 0.15, '<disable_collisions link1="arm_sc" link2="post" reason="User"/>')
    assert [f.element for f in disabled] == ["disable_collisions[arm post]"]
    assert "where none" not in disabled[0].message


def test_a_proxy_that_misses_some_contacts_leaves_those_states_counted(tmp_path):
    smaller = _with_proxy(tmp_path, 0.05, "")
    assert [f.element for f in smaller] == ["disable_collisions[arm post]"]
    assert "where none of the enabled pairs of the same rigid bodies (arm_sc/post) is" in smaller[0].message
    full = _with_proxy(tmp_path, 0.15, '<disable_collisions link1="arm_sc" link2="post" reason="User"/>')[0]
    assert int(smaller[0].message.split(" of ")[0].split()[-1]) < int(
        full.message.split(" of ")[0].split()[-1]
    )

"""setup.srdf_load: an SRDF as srdfdom and MoveIt load it (what they skip is left out, said)."""

from __future__ import annotations

from marm_setup.setup.srdf import parse_srdf_string
from marm_setup.setup.srdf_load import START_BOUNDS_TOLERANCE, as_moveit_loads

ARM = "<group name='arm'><chain base_link='base_link' tip_link='grasping_frame'/></group>"


def load(marm, body: str):
    return as_moveit_loads(parse_srdf_string(f"<robot name='marm'>{body}</robot>"), marm)


def test_a_clean_srdf_loads_as_it_is(marm):
    srdf, notes = load(
        marm, ARM + "<group_state name='home' group='arm'><joint name='joint1' value='0'/></group_state>"
    )
    assert notes == () and [g.name for g in srdf.groups] == ["arm"] and len(srdf.group_states) == 1


def test_groups_whose_subgroups_do_not_all_load_are_dropped_in_chains(marm):
    body = ARM + (
        "<group name='a'><group name='arm'/><group name='b'/></group>"  # b never loads: a goes too
        "<group name='b'><group name='c'/></group><group name='c'><group name='b'/></group>"  # a cycle
        "<group name='ok'><group name='arm'/></group><group name='arm'><joint name='joint1'/></group>"
    )
    srdf, notes = load(marm, body)
    assert [g.name for g in srdf.groups] == ["arm", "ok"]
    assert srdf.groups[0].joints == ()  # the first group of a name is kept, as MoveIt does
    assert notes[0] == "group[arm]: a second group of that name (MoveIt keeps the first)"
    assert {n.split(":")[0] for n in notes[1:]} == {"group[a]", "group[b]", "group[c]"}


def test_pose_values_slightly_outside_the_limits_are_clamped_larger_ones_kept(marm):
    lo, hi = marm.joint("joint2").bounds
    near, far = hi + START_BOUNDS_TOLERANCE / 2, hi + 2 * START_BOUNDS_TOLERANCE
    body = ARM + "".join(
        f"<group_state name='{n}' group='arm'><joint name='joint2' value='{v}'/></group_state>"
        for n, v in (("near", near), ("far", far))
    )
    srdf, notes = load(marm, body)
    assert [dict(s.values)["joint2"] for s in srdf.group_states] == [hi, far]
    assert len(notes) == 1 and "clamped" in notes[0] and "group_state[near]" in notes[0]


def test_unknown_virtual_and_passive_joints_and_parent_groups(marm):
    body = ARM + (
        "<group name='hand'><joint name='finger_joint1'/></group>"
        "<virtual_joint name='v' type='fixed' parent_frame='world' child_link='base_lnk'/>"
        "<passive_joint name='jointQ'/>"
        "<end_effector name='e' group='hand' parent_link='grasping_frame' parent_group='arms'/>"
    )
    srdf, notes = load(marm, body)
    assert srdf.virtual_joints == () and srdf.passive_joints == ()
    assert srdf.end_effectors[0].parent_group is None
    assert notes == (
        "virtual_joint[v]: unknown child link 'base_lnk'",
        "end_effector[e]: parent group 'arms' is not loaded (ignored)",
        "passive_joint[jointQ]: unknown joint",
    )


def test_a_state_left_without_values_and_pairs_of_unknown_links_are_left_out(marm):
    body = ARM + (
        "<group_state name='ghost' group='arm'><joint name='jointX' value='0'/></group_state>"
        "<disable_collisions link1='base_link' link2='link9' reason='Never'/>"
        "<disable_collisions link1='base_link' link2='link1' reason='Adjacent'/>"
    )
    srdf, notes = load(marm, body)
    assert srdf.group_states == () and [p.pair for p in srdf.disabled] == [("base_link", "link1")]
    assert notes == (
        "group_state[ghost].joint[jointX]: unknown joint",
        "group_state[ghost]: no joint value left (MoveIt adds no such state)",
        "disable_collisions[base_link link9]: unknown link",
    )

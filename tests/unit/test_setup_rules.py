"""The one rule set (`setup.rules`): the same findings on a setup and on its SRDF, element names
per entry point, the subgroup cycle finder, "did you mean" and the limit tolerance."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from marm_setup.errors import InputError
from marm_setup.names import did_you_mean, with_hint
from marm_setup.render.package import render_package
from marm_setup.robot.model import LIMIT_TOLERANCE
from marm_setup.setup.checks import check_setup
from marm_setup.setup.model import EndEffector, Group, GroupState, VirtualJoint
from marm_setup.setup.rules import Where, check_semantics, setup_element, srdf_element, subgroup_cycle
from marm_setup.setup.srdf import parse_srdf_string, setup_to_srdf
from tests.render_helpers import inferred_marm


@pytest.fixture(scope="module")
def marm_setup():
    return inferred_marm("ros1", Path("/tmp/unused"))


BREAKS = {
    "unknown chain tip": lambda m: dataclasses.replace(
        m,
        groups=(dataclasses.replace(m.groups[0], chain=dataclasses.replace(m.groups[0].chain, tip="link9")),)
        + m.groups[1:],
    ),
    "subgroup cycle": lambda m: dataclasses.replace(
        m, groups=(*m.groups, Group("a", subgroups=("b",)), Group("b", subgroups=("a",)))
    ),
    "pose out of limits": lambda m: dataclasses.replace(
        m, group_states=(GroupState("up", "arm", tuple((f"joint{i}", 9.0) for i in range(1, 7))),)
    ),
    "end effector of unknown group": lambda m: dataclasses.replace(
        m, end_effectors=(EndEffector("ee", "grippr", "grasping_frame"),)
    ),
    "virtual joint not at the root": lambda m: dataclasses.replace(
        m, virtual_joints=(VirtualJoint("vj", "floating", "world", "link1"),)
    ),
    "unknown passive joint": lambda m: dataclasses.replace(m, passive_joints=("joint9",)),
}


@pytest.mark.parametrize("case", list(BREAKS))
def test_a_setup_and_its_rendered_srdf_break_the_same_rules(case, marm_setup):
    """init/render (setup key paths) and validate (SRDF elements) get the same rule and message."""
    model, robot = marm_setup
    broken = BREAKS[case](model)
    on_setup = check_semantics(setup_to_srdf(broken), robot, "marm_setup.yaml", setup_element)
    (text,) = (f.content for f in render_package(broken, robot) if f.path.endswith(".srdf"))
    on_srdf = check_semantics(parse_srdf_string(text), robot, "x.srdf", srdf_element)
    assert [f for f in on_setup if f.is_error], case
    assert sorted((f.rule, f.message, f.hint) for f in on_setup) == sorted(
        (f.rule, f.message, f.hint) for f in on_srdf
    )
    first = next(f for f in on_setup if f.is_error)
    with pytest.raises(InputError) as raised:
        check_setup(broken, robot, "marm_setup.yaml")
    assert (raised.value.element, raised.value.message) == (
        first.element,
        with_hint(first.message, first.hint),
    )


def test_the_good_setup_breaks_no_rule(marm_setup):
    model, robot = marm_setup
    assert check_semantics(setup_to_srdf(model), robot, "marm_setup.yaml", setup_element) == []


@pytest.mark.parametrize(
    "where, setup, srdf",
    [
        (Where("robot"), "robot_name", "robot"),
        (Where("group", "arm", ("chain", "tip")), "groups[arm].chain.tip", "group[arm].chain"),
        (Where("group", "arm", ("joints", 1)), "groups[arm].joints[1]", "group[arm].joint"),
        (Where("group", "both", ("subgroups", 0)), "groups[both].subgroups[0]", "group[both].group"),
        (Where("group", "both", ("subgroups",)), "groups[both].subgroups", "group[both]"),
        (Where("group_state", "home", ("values", "joint1")), "group_states[home].values.joint1",
         "group_state[home].joint[joint1]"),
        (Where("group_state", "home", ("values",)), "group_states[home].values", "group_state[home]"),
        (Where("end_effector", "ee", ("parent_link",)), "end_effectors[ee].parent_link", "end_effector[ee]"),
        (Where("passive_joint", "j9", index=2), "passive_joints[2]", "passive_joint[j9]"),
        (Where("disable_collisions", "a b", ("link2",), 4), "collision.disabled[4].link2",
         "disable_collisions[a b]"),
    ],
)  # fmt: skip
def test_element_names_per_entry_point(where, setup, srdf):
    assert (setup_element(where), srdf_element(where)) == (setup, srdf)


class _CountingEdges(dict):
    """Subgroup edges that count how often each group's subgroups are read."""

    def __init__(self, *args):
        super().__init__(*args)
        self.reads: dict[str, int] = {}

    def get(self, key, default=None):
        self.reads[key] = self.reads.get(key, 0) + 1
        return super().get(key, default)


def test_cycle_finder_reads_each_group_once_on_diamonds():
    """40 stacked diamonds (2^40 paths): each group's subgroups are read once, no cycle found."""
    edges = _CountingEdges()
    for i in range(40):
        edges[f"n{i}"] = (f"l{i}", f"r{i}")
        edges[f"l{i}"] = edges[f"r{i}"] = (f"n{i + 1}",)
    assert subgroup_cycle("n0", edges) is None
    assert max(edges.reads.values()) == 1 and len(edges.reads) == 3 * 40 + 1


def test_cycle_finder_gives_the_path_back_to_the_start():
    edges = {"a": ("x", "b"), "b": ("c",), "c": ("a",), "x": ()}
    assert subgroup_cycle("a", edges) == ("a", "b", "c", "a")
    assert subgroup_cycle("x", edges) is None
    assert subgroup_cycle("s", {"s": ("s",)}) == ("s", "s")


def test_did_you_mean_one_spelling():
    assert did_you_mean("finger_jiont2", ["finger_joint1", "finger_joint2", "joint1"]) == (
        "did you mean 'finger_joint2', 'finger_joint1'?"
    )
    assert did_you_mean("manipulator", ["gripper", "arm"]) == "known: arm, gripper"
    assert did_you_mean("manipulator", ["gripper", "arm"], few=0) == ""
    assert did_you_mean("zzz", [f"link{i}" for i in range(20)]) == ""
    assert with_hint("unknown group 'x'", "") == "unknown group 'x'"


def test_a_pose_on_its_limit_within_the_tolerance_is_inside(marm_setup):
    model, robot = marm_setup
    lo, hi = robot.joint("joint2").bounds
    assert robot.joint("joint2").within_limits(hi + LIMIT_TOLERANCE / 2)
    assert not robot.joint("joint2").within_limits(hi + 2 * LIMIT_TOLERANCE)
    assert robot.joint("joint2").within_limits(lo - LIMIT_TOLERANCE / 2)
    home = next(s for s in model.group_states if s.group == "arm")
    values = tuple((j, hi + LIMIT_TOLERANCE / 2 if j == "joint2" else v) for j, v in home.values)
    check_setup(dataclasses.replace(model, group_states=(GroupState(home.name, "arm", values),)), robot, "x")


class _CountingGroups(dict):
    """Groups by name that count how often each is looked up."""

    def __init__(self, *args):
        super().__init__(*args)
        self.reads: dict[str, int] = {}

    def __getitem__(self, key):
        self.reads[key] = self.reads.get(key, 0) + 1
        return super().__getitem__(key)


def test_group_links_expand_each_subgroup_once_on_diamonds(marm):
    """12 stacked diamonds of subgroups (4096 paths): each subgroup is looked up once."""
    from marm_setup.setup.groups import group_links

    groups = _CountingGroups({"n12": Group("n12", links=("link6",))})
    for i in range(12):
        groups[f"n{i}"] = Group(f"n{i}", subgroups=(f"l{i}", f"r{i}"))
        groups[f"l{i}"] = Group(f"l{i}", links=("link1",), subgroups=(f"n{i + 1}",))
        groups[f"r{i}"] = Group(f"r{i}", links=("link2",), subgroups=(f"n{i + 1}",))
    start = groups["n0"]
    groups.reads.clear()  # count the expansion's lookups only
    assert group_links(start, groups, marm) == ("link1", "link2", "link6")
    assert set(groups.reads.values()) == {1} and len(groups.reads) == 3 * 12 + 1


def test_a_limit_written_rounded_is_the_same_limit():
    """One slack for every file-vs-URDF limit comparison (validate's limits rules, the port)."""
    from marm_setup.robot.model import limit_slack

    assert limit_slack(2.0943951) >= 2.0944 - 2.0943951  # 5 significant digits
    assert limit_slack(2.0943951) < 2.1 - 2.0943951
    assert limit_slack(0.0) == LIMIT_TOLERANCE


def test_findings_carry_their_element_and_what_they_name_as_data(marm_setup):
    """Callers (validate's cascade filter, the port) read Finding.location, never the text: the
    element's kind and name, and the unknown element it refers to."""
    from marm_setup.findings import Location

    model, marm = marm_setup
    arm = model.groups[0]
    broken = dataclasses.replace(
        model,
        groups=(*model.groups, Group("both", subgroups=(arm.name, "gone"))),
        end_effectors=(EndEffector("ee", "nothere", "link1"),),
    )
    found = {f.rule: f.location for f in check_semantics(setup_to_srdf(broken), marm, "x.srdf", srdf_element)}
    assert found["srdf.unknown-subgroup"] == Location("group", "both", ("group", "gone"))
    assert found["srdf.ee-unknown-group"] == Location("end_effector", "ee", ("group", "nothere"))


def test_an_unknown_link_in_many_disabled_pairs_is_one_warning(marm_setup):
    """An SRDF for another variant names a few links in many pairs: one warning per link, at its
    first pair, saying how many pairs srdfdom drops."""
    _model, robot = marm_setup
    pairs = [
        ("link1", "ghost"),
        ("ghost", "link3"),
        ("link2", "spook"),
        ("link4", "ghost"),
        ("link1", "link3"),
    ]
    body = "".join(f'<disable_collisions link1="{a}" link2="{b}" reason="Never"/>' for a, b in pairs)
    found = check_semantics(
        parse_srdf_string(f'<robot name="marm">{body}</robot>'), robot, "x.srdf", srdf_element
    )
    assert [(f.rule, f.severity, f.element, f.message) for f in found] == [
        (
            "srdf.unknown-link",
            "warning",
            "disable_collisions[ghost link1]",
            "unknown link 'ghost' (srdfdom ignores the 3 pairs naming it)",
        ),
        (
            "srdf.unknown-link",
            "warning",
            "disable_collisions[link2 spook]",
            "unknown link 'spook' (srdfdom ignores the pair)",
        ),
    ]


def test_a_pose_past_its_bound_within_moveits_goal_tolerance_is_reached(marm_setup):
    """A named pose written rounded (0.1745 for a lower limit of 0.174533, braccio_moveit_config):
    MoveIt's joint goal has a tolerance (goal_joint_tolerance, 1e-4 by default: moveit
    move_group_interface.h l.78), so the state on the bound meets it and the plan goes there; no
    pose.out-of-limits. Past the tolerance MoveIt moves the goal onto the bound with a warning
    (kinematic_constraint.cpp JointConstraint::configure): still an error. The runtime plans to
    the state on the bound."""
    import numpy as np

    from marm_setup.robot import onto_bounds
    from marm_setup.robot.model import GOAL_JOINT_TOLERANCE

    model, robot = marm_setup
    lo, hi = robot.joint("joint2").bounds
    home = next(s for s in model.group_states if s.group == "arm")

    def rules(value: float) -> list[str]:
        values = tuple((j, value if j == "joint2" else v) for j, v in home.values)
        srdf = setup_to_srdf(dataclasses.replace(model, group_states=(GroupState(home.name, "arm", values),)))
        return [f.rule for f in check_semantics(srdf, robot, "x.srdf", srdf_element)]

    assert "pose.out-of-limits" not in rules(lo - GOAL_JOINT_TOLERANCE / 3)
    assert "pose.out-of-limits" not in rules(hi + GOAL_JOINT_TOLERANCE / 3)
    assert "pose.out-of-limits" in rules(hi + 3 * GOAL_JOINT_TOLERANCE)
    i = robot.active_joint_names.index("joint2")
    q = np.zeros(len(robot.active_joint_names))
    q[i] = hi + GOAL_JOINT_TOLERANCE / 3
    assert onto_bounds(robot, q)[i] == hi
    q[i] = hi + 3 * GOAL_JOINT_TOLERANCE
    assert onto_bounds(robot, q)[i] == q[i]

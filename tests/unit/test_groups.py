"""setup.groups: what a group holds, resolved as MoveIt resolves it."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from marm_setup.robot.load import load_robot
from marm_setup.setup.groups import chain_joint_names, group_joints, groups_by_name
from marm_setup.setup.model import Chain, Group
from tests.helpers import urdf

# root -j1- torso -j2- chest -ja1- a1 -ja2- a2 ; torso -jl1- l1 -jl2- l2
TREE = "".join(f'<link name="{n}"/>' for n in ("root", "torso", "chest", "a1", "a2", "l1", "l2")) + "".join(
    f'<joint name="{j}" type="revolute"><parent link="{p}"/><child link="{c}"/><axis xyz="0 0 1"/>'
    f'<limit lower="-1" upper="1" velocity="1" effort="1"/></joint>'
    for j, p, c in (
        ("j1", "root", "torso"),
        ("j2", "torso", "chest"),
        ("ja1", "chest", "a1"),
        ("ja2", "a1", "a2"),
        ("jl1", "torso", "l1"),
        ("jl2", "l1", "l2"),
    )
)


@pytest.fixture(scope="module")
def tree(tmp_path_factory):
    path = tmp_path_factory.mktemp("tree") / "tree.urdf"
    path.write_text(urdf(TREE), encoding="utf-8")
    return load_robot(path)


@pytest.mark.parametrize(
    ("base", "tip", "joints"),
    [
        ("torso", "l2", ("jl1", "jl2")),  # the tip below the base: the joints between, in order
        ("root", "a2", ("j1", "j2", "ja1", "ja2")),
        ("l2", "l2", ()),
        # not below: up from the tip to where the base's path meets it (torso), the joint above
        # that link (j1) included as MoveIt's walk does, plus the base's path up to torso
        ("chest", "l2", {"jl2", "jl1", "j1", "j2"}),
        ("a2", "l2", {"jl2", "jl1", "j1", "ja2", "ja1", "j2"}),
        ("l2", "root", {"jl2", "jl1", "j1"}),  # the root's own joint is the virtual joint: left out
        ("l2", "nowhere", ()),
    ],
)
def test_chain_joints_follow_moveits_walk(tree, base, tip, joints):
    found = chain_joint_names(tree, base, tip)
    assert (set(found) if isinstance(joints, set) else found) == joints
    assert len(set(found)) == len(found)


def test_a_chain_group_holds_its_walk_in_tree_order(tree):
    group = Group(name="legs_to_arm", chain=Chain(base="a2", tip="l2"))
    assert group_joints(group, groups_by_name((group,)), tree) == ("j1", "j2", "ja1", "ja2", "jl1", "jl2")


def _reference_joints(name: str, groups: dict, robot) -> set[str]:
    """Every joint reachable through subgroups, walked naively (breadth first, visited set)."""
    seen, queue, joints = {name}, [name], set()
    while queue:
        group = groups[queue.pop(0)]
        joints |= set(group.joints)
        for sub in group.subgroups:
            if sub in groups and sub not in seen:
                seen.add(sub)
                queue.append(sub)
    return joints


@settings(max_examples=60)
@given(st.lists(st.lists(st.integers(0, 9), max_size=3), min_size=1, max_size=10), st.data())
def test_memoised_expansion_matches_a_naive_walk(tree, edges, data):
    """Random subgroup graphs (cycles, self-loops, diamonds, names that are no group)."""
    names = [f"g{i}" for i in range(len(edges))]
    joints = ("j1", "j2", "ja1", "ja2", "jl1", "jl2")
    groups = {
        name: Group(
            name=name,
            joints=(data.draw(st.sampled_from(joints)),),
            subgroups=tuple(f"g{k}" for k in subs),  # g9 may be no group
        )
        for name, subs in zip(names, edges, strict=True)
    }
    for name, group in groups.items():
        assert set(group_joints(group, groups, tree)) == _reference_joints(name, groups, tree)


def test_groups_by_name_is_read_only_and_an_edited_copy_replaces_its_group(tree):
    """Expansions are cached per mapping, so the mappings are read-only; a group that is not the
    mapping's own (an edited copy) is expanded with it in its original's place."""
    groups = groups_by_name(
        (Group("c", joints=("j1",), subgroups=("d",)), Group("d", joints=("j2",), subgroups=("c",)))
    )
    with pytest.raises(TypeError):
        groups["c"] = Group("c")  # type: ignore[index]
    edited = Group("c", joints=("ja1",), subgroups=("d",))
    assert set(group_joints(edited, groups, tree)) == {"ja1", "j2"}  # not the original c's j1
    assert set(group_joints(groups["c"], groups, tree)) == {"j1", "j2"}

"""SRDF output for the collision matrix: minimal SRDF, in-place update, pinocchio as a consumer."""

from __future__ import annotations

import re

import pytest
from lxml import etree

from marm_setup.collision.matrix import compute_collision_matrix
from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.srdf_update import read_srdf_entries, render_minimal_srdf, update_srdf
from marm_setup.errors import InputError
from marm_setup.render.writer import write_text_atomic
from marm_setup.robot.load import load_robot
from tests.conftest import FIXTURES, MARM_URDF, realworld

N, U, A = DisabledReason.NEVER, DisabledReason.USER, DisabledReason.ADJACENT
COMPUTED = [
    DisabledPair.of("b", "a", A),
    DisabledPair.of("c", "a", N),
    DisabledPair.of("d", "c", N),
]
EXISTING = """<?xml version="1.0" encoding="UTF-8"?>
<!-- hand-written header, kept -->
<robot name="toy">
    <group name="arm">
        <chain base_link="a" tip_link="d"/>
    </group>
    <!-- <disable_collisions link1="x" link2="y" reason="Never"/> in a comment: untouched -->
    <disable_collisions link1="a" link2="b" reason="Adjacent" />
    <disable_collisions link1="d"   link2="b" reason="User"/>
    <disable_collisions link1="a" link2="old" reason="Never"/>
    <end_effector name="hand" parent_link="d" group="arm"/>
    <disable_collisions link1="c" link2="a" reason="my own words"/>
</robot>
"""


def _without_entries(text: str) -> str:
    """The text minus every line holding a disable_collisions element (comment lines stay)."""
    return "".join(
        line for line in text.splitlines(True) if "<disable_collisions" not in line or "<!--" in line
    )


def test_minimal_srdf_is_sorted_and_parses():
    text = render_minimal_srdf("toy", COMPUTED)
    root = etree.fromstring(text.encode())
    assert root.tag == "robot" and root.get("name") == "toy"
    pairs = [(e.get("link1"), e.get("link2"), e.get("reason")) for e in root.iter("disable_collisions")]
    assert pairs == [("a", "b", "Adjacent"), ("a", "c", "Never"), ("c", "d", "Never")]
    assert text.endswith("</robot>\n")


def test_update_replaces_computed_entries_and_keeps_everything_else():
    text, final = update_srdf(EXISTING, COMPUTED, shown="in.srdf")
    assert _without_entries(text) == _without_entries(EXISTING)  # every other byte
    assert '    <disable_collisions link1="d"   link2="b" reason="User"/>\n' in text
    assert '<disable_collisions link1="c" link2="a" reason="my own words"/>' in text
    assert 'link2="old"' not in text
    entries = [(e.link1, e.link2, e.reason) for e in read_srdf_entries(text, shown="out.srdf")]
    assert entries == [
        ("a", "b", "Adjacent"),  # the new block, sorted, where the first removed entry was
        ("c", "d", "Never"),
        ("d", "b", "User"),
        ("c", "a", "my own words"),  # a reason we do not compute is the user's: kept, and wins
    ]
    assert text.count('    <disable_collisions link1="a" link2="b" reason="Adjacent"/>\n') == 1
    assert {d.pair: d.reason for d in final} == {("a", "b"): A, ("c", "d"): N, ("b", "d"): U, ("a", "c"): U}


def test_update_with_keep_keeps_every_existing_entry():
    text, final = update_srdf(EXISTING, COMPUTED, keep=True, shown="in.srdf")
    for line in EXISTING.splitlines(True):
        assert line in text
    assert text.count("<disable_collisions") == EXISTING.count("<disable_collisions") + 1  # + c/d
    assert ("a", "old") in {d.pair for d in final}


def test_update_is_idempotent_and_keeps_crlf():
    once, _ = update_srdf(EXISTING.replace("\n", "\r\n"), COMPUTED, shown="in.srdf")
    twice, _ = update_srdf(once, COMPUTED, shown="in.srdf")
    assert once == twice
    assert "\n" not in once.replace("\r\n", "")


def test_update_without_entries_inserts_before_robot_end():
    text, _ = update_srdf('<robot name="toy">\n  <group name="g"/>\n</robot>\n', COMPUTED, shown="in.srdf")
    assert text.startswith('<robot name="toy">\n  <group name="g"/>\n  <disable_collisions link1="a"')
    assert text.endswith('reason="Never"/>\n</robot>\n')
    with pytest.raises(InputError, match="no end tag"):
        update_srdf('<robot name="toy"/>', COMPUTED, shown="in.srdf")


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("<robot name='x'>\n<group>\n</robot>\n", "in.srdf: line 3: malformed XML"),
        ("<notrobot/>", "in.srdf: root element is <notrobot>, expected <robot>"),
        ("<robot>\n<disable_collisions link1='a'/>\n</robot>", "in.srdf: line 2: disable_collisions needs"),
    ],
)
def test_bad_srdf_is_an_input_error(text, expected):
    with pytest.raises(InputError) as info:
        read_srdf_entries(text, shown="in.srdf")
    assert str(info.value).startswith(expected)


def test_write_text_atomic_keeps_bytes(tmp_path):
    target = tmp_path / "sub" / "out.srdf"
    write_text_atomic(target, "a\r\nb\n", shown="out.srdf")
    assert target.read_bytes() == b"a\r\nb\n"
    assert [p.name for p in target.parent.iterdir()] == ["out.srdf"]


def _pin_removed(urdf_xml: str, srdf_path, package_dir) -> tuple[int, int]:
    """(pairs pinocchio removed, pairs it could remove: links on different joints)."""
    import pinocchio as pin

    model = pin.buildModelFromXML(urdf_xml)
    geom = pin.buildGeomFromUrdfString(
        model, urdf_xml, pin.GeometryType.COLLISION, package_dirs=[str(package_dir)]
    )
    geom.addAllCollisionPairs()
    before = len(geom.collisionPairs)
    pin.removeCollisionPairs(model, geom, str(srdf_path))
    joint_of = {o.name.rsplit("_", 1)[0]: o.parentJoint for o in geom.geometryObjects}
    root = etree.parse(str(srdf_path)).getroot()
    removable = sum(
        1 for e in root.iter("disable_collisions") if joint_of[e.get("link1")] != joint_of[e.get("link2")]
    )
    return before - len(geom.collisionPairs), removable


def test_pinocchio_removes_exactly_the_pairs_we_wrote(tmp_path):
    robot = load_robot(MARM_URDF)
    matrix = compute_collision_matrix(robot, trials=500, seed=0)
    srdf = tmp_path / "marm.srdf"
    srdf.write_text(render_minimal_srdf(robot.name, matrix.disabled), encoding="utf-8")
    (tmp_path / "pkgs").mkdir()
    (tmp_path / "pkgs" / "marm_description").symlink_to(FIXTURES / "marm")
    removed, removable = _pin_removed(robot.urdf_xml, srdf, tmp_path / "pkgs")
    assert removed == removable
    assert removable == len(matrix.disabled) - 1  # base_link/bottom_link share pinocchio's joint 0


def test_update_of_the_shared_panda_srdf(tmp_path):
    root = realworld("ros1")
    robot = load_robot(root / "panda_description/urdf/panda_arm_hand.urdf.xacro", package_paths=[root])
    original = (root / "panda_moveit_config/config/panda.srdf").read_text(encoding="utf-8")
    matrix = compute_collision_matrix(robot, trials=1000, seed=0)
    text, final = update_srdf(original, matrix.disabled, shown="panda.srdf")
    assert _without_entries(text) == _without_entries(original)
    written = re.findall(r'<disable_collisions link1="([^"]+)" link2="([^"]+)"', text)
    assert len(written) == len(final) == len(matrix.disabled)
    srdf = tmp_path / "panda.srdf"
    srdf.write_text(text, encoding="utf-8")
    pkgs = tmp_path / "pkgs"
    pkgs.mkdir()
    (pkgs / "moveit_resources_panda_description").symlink_to(root / "panda_description")
    removed, removable = _pin_removed(robot.urdf_xml, srdf, pkgs)
    assert removed == removable == len(final) - 1  # panda_hand/panda_link7: both on joint 7


def test_update_escapes_link_names():
    text, _ = update_srdf('<robot name="r">\n</robot>\n', [DisabledPair.of('a&"b', "c<d", N)], shown="r.srdf")
    entry = etree.fromstring(text.encode()).find("disable_collisions")
    assert (entry.get("link1"), entry.get("link2")) == ('a&"b', "c<d")


NOTE = "unproved Never: proved collision-free over 93.1 % of its joint range; the rest only sampled (300 states, no contact)"


def test_notes_go_on_the_line_before_their_pair_and_leave_with_it():
    notes = {("c", "d"): NOTE}
    minimal = render_minimal_srdf("toy", COMPUTED, notes)
    lines = minimal.splitlines()
    assert (
        lines[lines.index(f"  <!-- {NOTE} -->") + 1]
        == '  <disable_collisions link1="c" link2="d" reason="Never"/>'
    )
    etree.fromstring(minimal.encode())
    updated, _ = update_srdf(EXISTING, COMPUTED, shown="toy.srdf", notes=notes)
    assert (
        updated.count(NOTE) == 1
        and f'    <!-- {NOTE} -->\n    <disable_collisions link1="c" link2="d"' in updated
    )
    again, _ = update_srdf(updated, COMPUTED, shown="toy.srdf", notes=notes)
    assert again == updated  # the old note is replaced, not kept beside the new one
    without, _ = update_srdf(updated, COMPUTED, shown="toy.srdf")
    assert NOTE not in without and without == update_srdf(EXISTING, COMPUTED, shown="toy.srdf")[0]
    kept, _ = update_srdf(updated, COMPUTED, keep=True, shown="toy.srdf")
    assert kept == updated  # --keep leaves every entry, and so its note, as it was


def test_notes_keep_crlf_and_other_comments():
    crlf = EXISTING.replace("\n", "\r\n")
    updated, _ = update_srdf(crlf, COMPUTED, shown="toy.srdf", notes={("c", "d"): NOTE})
    assert f"<!-- {NOTE} -->\r\n" in updated and "\n" not in updated.replace("\r\n", "")
    assert "<!-- hand-written header, kept -->" in updated and "in a comment: untouched" in updated

"""Every user-facing error branch of the URDF parser and loader: one line naming the file, the
element and what is wrong (the CLI prints it as `error: <line>`; tests/cli/test_inspect.py
covers the CLI contract and the branches listed there)."""

from __future__ import annotations

import pytest

from marm_setup.errors import InputError
from marm_setup.robot.load import load_robot
from tests.helpers import TWO_BOXES, build_file_tree, urdf

BOX = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
J_LIMIT = '<limit lower="-1" upper="1" velocity="1" effort="1"/>'


def _joint(name: str, parent: str, child: str, extra: str = "", kind: str = "fixed") -> str:
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>{extra}</joint>'
    )


def _with(*extra: str) -> str:
    """TWO_BOXES (links a, b; revolute j from a to b) plus `extra` elements."""
    return TWO_BOXES.replace("</robot>", "".join(extra) + "</robot>")


# case: (URDF text, element, message)
CASES = {
    "root is not robot": (
        '<?xml version="1.0"?>\n<model name="x"/>\n',
        "<model>",
        "root element must be <robot>",
    ),
    "no links": (urdf(""), "robot", "no <link> elements"),
    "link without name": (
        urdf("<link/>"),
        "line 3: <link>",
        "missing name",
    ),
    "collision without geometry": (
        urdf('<link name="a"><collision><origin xyz="0 0 0"/></collision></link>'),
        "link[a]/collision[0]",
        "missing <geometry>",
    ),
    "unknown geometry": (
        urdf('<link name="a"><collision><geometry><capsule radius="1"/></geometry></collision></link>'),
        "link[a]/collision[0]/capsule",
        "unknown geometry; expected box, cylinder, sphere or mesh",
    ),
    "mesh without filename": (
        urdf('<link name="a"><collision><geometry><mesh/></geometry></collision></link>'),
        "link[a]/collision[0]/mesh",
        "missing filename",
    ),
    "origin not numbers": (
        TWO_BOXES.replace('<origin xyz="0 0 0.2"/>', '<origin xyz="0 zero 0.2"/>'),
        "joint[j]/origin@xyz",
        "expected 3 numbers, got '0 zero 0.2'",
    ),
    "a number Python reads but urdfdom does not": (
        TWO_BOXES.replace('upper="1"', 'upper="1_0"'),
        "joint[j]/limit@upper",
        "expected 1 numbers, got '1_0'",
    ),
    "digits of another script": (
        TWO_BOXES.replace('upper="1"', 'upper="\u0661"'),
        "joint[j]/limit@upper",
        "expected 1 numbers, got '\u0661'",
    ),
    "a limit beyond sdformat's unbounded 1e16": (
        TWO_BOXES.replace('upper="1"', 'upper="1e17"'),
        "joint[j]/limit@upper",
        "'1e17' is out of range (|value| <= 1e+16: metres, radians, N, m/s)",
    ),
    "a subnormal axis": (
        TWO_BOXES.replace('<axis xyz="0 0 1"/>', '<axis xyz="1e-320 1e-320 0"/>'),
        "joint[j]/axis",
        "axis must not be zero",
    ),
    "origin with two numbers": (
        TWO_BOXES.replace('<origin xyz="0 0 0.2"/>', '<origin xyz="0 0.2"/>'),
        "joint[j]/origin@xyz",
        "expected 3 numbers, got '0 0.2'",
    ),
    "joint without name": (
        _with('<link name="c"/>', '<joint type="fixed"><parent link="b"/><child link="c"/></joint>'),
        "line 11: <joint>",
        "missing name",
    ),
    "unknown joint type": (
        _with('<link name="c"/>', _joint("k", "b", "c", kind="hinge")),
        "joint[k]",
        "unknown type 'hinge'; expected one of revolute, continuous, prismatic, fixed, floating, planar",
    ),
    "joint without parent": (
        _with('<link name="c"/>', '<joint name="k" type="fixed"><child link="c"/></joint>'),
        "joint[k]",
        "needs <parent link=...> and <child link=...>",
    ),
    "revolute without limit": (
        TWO_BOXES.replace(J_LIMIT, ""),
        "joint[j]/limit",
        "a revolute joint needs <limit>",
    ),
    "negative velocity": (
        TWO_BOXES.replace('velocity="1"', 'velocity="-2"'),
        "joint[j]/limit",
        "negative velocity -2.0",
    ),
    "mimic without joint": (
        _with('<link name="c"/>', _joint("k", "b", "c", '<mimic multiplier="2"/>' + J_LIMIT, "revolute")),
        "joint[k]/mimic",
        "missing joint",
    ),
    "mimic of an unknown joint": (
        _with('<link name="c"/>', _joint("k", "b", "c", '<mimic joint="jj"/>' + J_LIMIT, "revolute")),
        "joint[k]/mimic",
        "unknown joint 'jj'",
    ),
    "mimic of a mimic": (
        _with(
            '<link name="c"/>',
            _joint("k", "b", "c", '<mimic joint="j"/>' + J_LIMIT, "revolute"),
            '<link name="d"/>',
            _joint("m", "c", "d", '<mimic joint="k"/>' + J_LIMIT, "revolute"),
        ),
        "joint[m]/mimic",
        "'k' is itself a mimic joint",
    ),
    "duplicate link": (
        _with(f'<link name="b">{BOX}</link>'),
        "link[b]",
        "duplicate link name",
    ),
    "duplicate joint": (
        _with('<link name="c"/>', _joint("j", "b", "c")),
        "joint[j]",
        "duplicate joint name",
    ),
    "unknown parent link": (
        _with('<link name="c"/>', _joint("k", "bee", "c")),
        "joint[k]/parent",
        "unknown link 'bee'",
    ),
    "two parents": (
        _with(_joint("k", "a", "b")),
        "joint[k]/child",
        "link 'b' already has a parent joint",
    ),
    "cycle below the root": (
        _with('<link name="c"/>', '<link name="d"/>', _joint("k", "c", "d"), _joint("m", "d", "c")),
        "link[c]",
        "the joints form a cycle through this link",
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_urdf_error_names_file_and_element(case, tmp_path):
    text, element, message = CASES[case]
    build_file_tree(tmp_path, {"r.urdf": text})
    path = tmp_path / "r.urdf"
    with pytest.raises(InputError) as err:
        load_robot(path)
    assert (err.value.path, err.value.element, err.value.message) == (str(path), element, message)
    assert str(err.value) == f"{path}: {element}: {message}"
    assert "\n" not in str(err.value)


def test_malformed_xacro_names_the_line(tmp_path):
    build_file_tree(tmp_path, {"r.urdf.xacro": '<robot name="x">\n<link name="a">\n</robot>\n'})
    path = tmp_path / "r.urdf.xacro"
    with pytest.raises(InputError) as err:
        load_robot(path)
    assert err.value.path == str(path) and err.value.element == "line 3"
    assert err.value.message.startswith("malformed XML: mismatched tag")


def test_gazebo_style_unbounded_limits_load(tmp_path):
    """SDF -> URDF writes +-1e16 for a joint without limits (sdformat's default): it loads."""
    path = tmp_path / "r.urdf"
    path.write_text(TWO_BOXES.replace('lower="-1" upper="1"', 'lower="-1e+16" upper="1e16"'))
    assert load_robot(path).joint("j").bounds == (-1e16, 1e16)

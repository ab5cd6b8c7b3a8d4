"""XML read as MoveIt's tinyxml2-based parsers (srdfdom, urdfdom) read it: `--` inside a comment
is taken, anything else malformed is still refused (robot/tinyxml.py)."""

from __future__ import annotations

import pytest

from marm_setup.errors import InputError
from marm_setup.robot.load import load_robot
from marm_setup.robot.tinyxml import tinyxml_comments
from marm_setup.setup import parse_srdf_string
from tests.helpers import ARM, urdf

SRDF = """<?xml version="1.0"?>
<!-- generated -- by hand --->
<robot name="bot">
  <!-- arm
       -- the whole chain - -->
  <group name="arm"><chain base_link="base" tip_link="l3"/></group>
</robot>
"""


def test_comments_keep_their_length_and_lines():
    text = "<a><!-- x -- y\n -- z ---></a>\n"
    out = tinyxml_comments(text)
    assert len(out) == len(text) and out.count("\n") == text.count("\n")
    assert out.startswith("<a><!--") and out.endswith("--></a>\n") and "--" not in out[7:-8]
    assert tinyxml_comments(text.encode()) == out.encode()


def test_an_srdf_with_double_hyphens_in_comments_reads():
    assert [g.name for g in parse_srdf_string(SRDF).groups] == ["arm"]


@pytest.mark.parametrize(
    ("broken", "line"),
    [
        (SRDF.replace("</group>", ""), "line 7"),  # an unclosed element, after the comments
        (SRDF.replace("<!-- arm", "<!- arm"), "line 4"),  # no comment at all
        (SRDF.replace("- -->", "- ->"), "line 5"),  # a comment never closed (tinyxml2 refuses it too)
    ],
)
def test_real_malformation_is_still_refused_at_its_line(broken, line):
    with pytest.raises(InputError) as caught:
        parse_srdf_string(broken, "bot.srdf")
    assert caught.value.element == line


def test_a_urdf_with_double_hyphens_in_a_comment_loads(tmp_path):
    file = tmp_path / "bot.urdf"
    file.write_text(urdf(ARM, "bot").replace("<robot", "<!-- v2 -- fixed -->\n<robot", 1), encoding="utf-8")
    assert load_robot(file).name == "bot"


def test_ros2_control_systems_are_seen_past_such_a_comment():
    from marm_setup.robot.ros2_control import systems_in_urdf

    xml = '<robot name="b"><!-- mock -- hardware --><ros2_control name="s"><hardware><plugin>p</plugin></hardware></ros2_control></robot>'
    assert [s.name for s in systems_in_urdf(xml)] == ["s"]

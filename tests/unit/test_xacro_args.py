"""Which arguments a xacro takes (robot/xacro_expand.py): real xacro ignores a mapping no
`<xacro:arg>`, `$(arg)`, `arg()` or `$(eval)` name reads, so a misspelled `--xacro-arg` would
silently change nothing; the expansion reports every name the xacro declares or reads, in the
included files too, and `check_xacro_args` refuses the others, naming the declared ones."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from marm_setup.errors import InputError
from marm_setup.robot.load import load_robot
from marm_setup.robot.ros_packages import find_packages
from marm_setup.robot.xacro_expand import check_xacro_args, run_xacro
from tests.helpers import build_file_tree

LINK = '<link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>'
TREE = {
    "main.urdf.xacro": f"""
        <robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:arg name="hand" default="false"/>
          <xacro:include filename="$(find pkg)/inc.xacro"/>
          <xacro:if value="$(arg hand)"><xacro:include filename="$(find pkg)/hand.xacro"/></xacro:if>
          <xacro:if value="false"><xacro:arg name="skipped_branch" default="1"/></xacro:if>
          <xacro:property name="undeclared" value="$(arg used_without_declaration)"/>
          <xacro:property name="evaluated" value="$(eval bare_name == 'x')"/>
          <xacro:property name="through_arg" value="${{xacro.arg('read_by_python')}}"/>
          {LINK}<link name="${{undeclared}}_${{evaluated}}_${{through_arg}}"/>
        </robot>""",
    "inc.xacro": """
        <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:arg name="tool" default="none"/>
        </robot>""",
    "hand.xacro": """
        <robot xmlns:xacro="http://www.ros.org/wiki/xacro">
          <xacro:arg name="finger_count" default="2"/>
        </robot>""",
    "package.xml": "<package><name>pkg</name></package>",
}
GIVEN = {"used_without_declaration": "1", "bare_name": "x", "read_by_python": "y"}


@pytest.fixture
def tree(tmp_path: Path) -> Path:
    return build_file_tree(tmp_path, TREE)


def _declared(tree: Path, **args: str) -> frozenset[str]:
    file = tree / "main.urdf.xacro"
    return run_xacro(
        file, {**GIVEN, **args}, find_packages([tree], near=file), shown="main.urdf.xacro"
    ).declared


def test_every_way_a_xacro_takes_an_argument_counts(tree):
    """Declared in the file and in an included one, read without a declaration by `$(arg)`, by
    a bare name in `$(eval)` and by `xacro.arg()`, declared in a branch that was not taken (an
    argument of the file all the same) and in a file included only with hand:=true."""
    assert _declared(tree) == {
        "hand", "tool", "skipped_branch", *GIVEN,
    }  # fmt: skip
    assert "finger_count" in _declared(tree, hand="true")


def test_an_undeclared_argument_is_an_error_naming_the_declared_ones(tree):
    declared = _declared(tree)
    check_xacro_args({"hand": "true", "tool": "x"}, declared, path="main.urdf.xacro")
    with pytest.raises(InputError) as caught:
        check_xacro_args({"hnad": "true"}, declared, path="main.urdf.xacro")
    assert str(caught.value) == (
        "main.urdf.xacro: --xacro-arg hnad: not an argument of this xacro (did you mean 'hand'?); "
        "it takes: bare_name, hand, read_by_python, skipped_branch, tool, used_without_declaration"
    )


def test_a_plain_urdf_takes_no_xacro_argument(tmp_path):
    file = tmp_path / "r.urdf"
    file.write_text(f'<robot name="r">{LINK}</robot>')
    robot = load_robot(file)
    assert robot.xacro_args is None
    with pytest.raises(InputError, match=r"r.urdf: --xacro-arg hand: .*not a xacro file"):
        check_xacro_args({"hand": "true"}, robot.xacro_args, path="r.urdf")


def test_real_xacro_ignores_an_undeclared_mapping_without_a_word(tree):
    """Why the check exists: the xacro command itself accepts `hnad:=true` silently."""
    xacro = Path(sys.executable).with_name("xacro")
    if not xacro.exists():
        pytest.skip("no xacro command")
    env = {"ROS_PACKAGE_PATH": str(tree), "PATH": "/usr/bin:/bin"}
    files = build_file_tree(
        tree / "plain", {"t.xacro": TREE["hand.xacro"].replace("<robot ", '<robot name="t" ')}
    )
    done = subprocess.run(
        [str(xacro), str(files / "t.xacro"), "hnad:=true"], capture_output=True, text=True, env=env
    )
    assert (done.returncode, done.stderr) == (0, "")

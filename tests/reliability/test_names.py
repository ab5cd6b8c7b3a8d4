"""Hostile names: refused with one line where ROS constrains them, escaped per language where it
does not, never turned into code (Python, launch substitutions, command-line options)."""

from __future__ import annotations

import ast
import shutil

import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st
from lxml import etree

from marm_setup.names import KINDS, name_problem
from marm_setup.templating import py_repr, xml_comment, yaml_str
from tests.conftest import FIXTURES, MARM_URDF
from tests.helpers import TWO_BOXES
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, assert_package_parses, run

SPEC = FIXTURES / "marm" / "marm_setup.yaml"
TRIALS = ("--trials", "50")
INJECTION = 'x"""; __import__("os").system("touch pwned") #'


def _spec(tmp_path, edit) -> str:
    data = yaml.safe_load(SPEC.read_text())
    edit(data)
    path = tmp_path / "spec.yaml"
    path.write_text(yaml.safe_dump(data))
    return str(path)


def _init(tmp_path, spec: str, *args: str):
    return run("init", MARM_URDF, "--out", tmp_path / "pkg", "--setup", spec, *TRIALS, *args)


@pytest.mark.parametrize(
    ("kind", "name", "valid"),
    [
        ("package", "marm_moveit_config", True),
        ("package", "Marm", False),
        ("robot", "L31K-GRIPPER_URDF_SIMPLIFIED_V2", True),
        ("robot", "my robot", False),
        ("robot", "2dof_planar", True),
        ("robot", ".hidden", False),
        ("joint", "j,1", False),
        ("joint", "j}1", False),
        ("joint", "arm.joint_1", True),
        ("plugin", "mock_components/GenericSystem", True),
        ("plugin", "$(env X)/Y", False),
        ("interface", "position", True),
        ("parameter", "calculate_dynamics", True),
        ("group", "panda_arm", True),
        ("group", "a: b", False),
        ("group", "$(env HOME)", False),
        ("controller", "arm/follow", True),
        ("controller", "x --controller-manager /evil", False),
        ("pose", "all-zeros", True),
        ("pose", INJECTION, True),
        ("pose", "a\nb", False),
        ("pose", "$(env HOME)", False),
        ("link", "base-link.1", True),
        ("link", "--help", False),
        ("joint", "j'1", False),
        ("frame", "a b", False),
        ("end effector", "x\x00", False),
    ],
)
def test_one_rule_per_kind(kind, name, valid):
    assert (name_problem(kind, name) is None) is valid


@given(st.sampled_from(KINDS), st.text(max_size=30))
def test_a_problem_is_one_printable_line(kind, name):
    problem = name_problem(kind, name)
    assert problem is None or "\n" not in problem


@given(st.text(max_size=40))
def test_yaml_str_round_trips_as_value_and_key(text):
    out = yaml_str(text)
    assert "\n" not in out
    assert yaml.safe_load(f"- {out}") == [text]
    assert yaml.safe_load(f"{out}: 1") == {text: 1}


@pytest.mark.parametrize("text", ["wait...", "...", "a: b", "1e3", "0x1F", "on", "- x", "#c", "a\nb"])
def test_yaml_str_keeps_every_character(text):
    assert yaml.safe_load(yaml_str(text)) == text


@given(st.text(max_size=40))
def test_py_repr_is_one_literal(text):
    tree = ast.parse(f"X = {py_repr(text)}")
    assert ast.literal_eval(tree.body[0].value) == text


@given(st.text(st.characters(codec="utf-8", exclude_categories=("Cc", "Cs")), max_size=40))
def test_xml_comment_never_ends_a_comment(text):
    etree.fromstring(f"<r><!-- {xml_comment(text)} --></r>".encode())


def test_pose_name_cannot_inject_python(tmp_path):
    spec = _spec(tmp_path, lambda d: d["group_states"][1].update(name=INJECTION))
    result = _init(tmp_path, spec)
    assert_clean_exit(result, codes=(0,))
    pkg = tmp_path / "pkg"
    assert_package_parses(pkg)
    tree = ast.parse((pkg / "scripts" / "trajectory_demo.py").read_text())
    consts = {t.id: n.value for n in tree.body if isinstance(n, ast.Assign) for t in n.targets}
    assert ast.literal_eval(consts["GOAL_NAME"]) == INJECTION
    imports = [a.name for n in tree.body if isinstance(n, ast.Import | ast.ImportFrom) for a in n.names]
    assert "os" not in imports and not (tmp_path / "pwned").exists()
    srdf = etree.parse(str(pkg / "config" / "marm.srdf"))
    assert srdf.find("group_state[2]").get("name") == INJECTION


@pytest.mark.parametrize(
    ("edit", "fragments"),
    [
        (
            lambda d: d.update(controllers=[_ctl("x --controller-manager /evil")]),
            ["controllers[x --controller-manager /evil]", "not a valid controller name"],
        ),
        (lambda d: d["groups"][0].update(name="$(env HOME)"), ["groups[$(env HOME)]", "group name"]),
        (lambda d: d["groups"][0].update(name="arm: x"), ["not a valid group name"]),
        (lambda d: d["groups"][0].update(name="arm\nx"), ["groups[arm\\nx]"]),
        (lambda d: d["group_states"][0].update(name="$(env HOME)"), ["roslaunch substitution"]),
        (lambda d: d["group_states"][0].update(name="home\x07"), ["control or invisible character"]),
        (lambda d: d["end_effectors"][0].update(name="ee\u2028x"), ["end_effectors[ee\\u2028x]"]),
        (lambda d: d.update(virtual_joints=[_vj("--help")]), ["starts with '-'"]),
    ],
)
def test_unsafe_setup_names_are_one_line_errors(tmp_path, edit, fragments):
    result = _init(tmp_path, _spec(tmp_path, edit))
    assert_one_line_error(result, *fragments)
    assert not (tmp_path / "pkg").exists()


def _ctl(name: str) -> dict:
    return {"name": name, "type": "FollowJointTrajectory", "action_ns": "follow", "joints": ["joint1"]}


def _vj(frame: str) -> dict:
    return {"name": "vj", "type": "fixed", "parent_frame": frame, "child_link": "base_link"}


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_names_that_need_escaping_make_parseable_packages(tmp_path, target):
    def edit(d):
        d["group_states"][1]["name"] = "wait... <&> 'x' -- \"y\": #z"
        d["end_effectors"][0]["name"] = "ee -- -"
        d["virtual_joints"] = [
            {"name": "v--j-", "type": "fixed", "parent_frame": "w&o<r>l--d", "child_link": "base_link"}
        ]

    result = _init(tmp_path, _spec(tmp_path, edit), "--target", target)
    assert_clean_exit(result, codes=(0,))
    assert_package_parses(tmp_path / "pkg")
    validated = run("validate", tmp_path / "pkg", "--no-plan")
    assert_clean_exit(validated, codes=(0,))
    if target == "ros1":
        fake = yaml.safe_load((tmp_path / "pkg" / "config" / "fake_controllers.yaml").read_text())
        assert {"group": "arm", "pose": "home"} in fake["initial"]


@pytest.mark.parametrize("robot_name", ["my robot", ".hidden", "a:b", ""])
def test_robot_names_that_cannot_name_files_or_macros(tmp_path, robot_name):
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(TWO_BOXES.replace('name="test_robot"', f'name="{robot_name}"'))
    result = run("init", urdf, "--out", tmp_path / "pkg", *TRIALS)
    assert_one_line_error(result, "robot name")
    assert not (tmp_path / "pkg").exists()


def test_validate_reports_unsafe_names_in_foreign_packages(tmp_path):
    result = _init(tmp_path, str(SPEC))
    assert_clean_exit(result, codes=(0,))
    pkg = tmp_path / "pkg"
    foreign = tmp_path / "foreign"
    shutil.copytree(pkg, foreign)
    (foreign / ".marm_setup").exists() and shutil.rmtree(foreign / ".marm_setup")
    controllers = foreign / "config" / "controllers.yaml"
    controllers.write_text(
        controllers.read_text().replace("name: arm_controller", "name: x --controller-manager /evil")
    )
    srdf = foreign / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text().replace('group_state name="forward"', 'group_state name="$(env HOME)"'))
    found = run("validate", foreign, "--no-plan", "--format", "json")
    assert_clean_exit(found)
    import json

    rules = {(f["rule"], f["element"]) for f in json.loads(found.stdout)["findings"]}
    assert ("names.invalid", "group_state[$(env HOME)]") in rules
    assert any(rule == "names.invalid" and "controller_list" in where for rule, where in rules), rules


def test_a_robot_named_with_a_leading_digit_gets_a_package_that_expands(tmp_path):
    """urdfdom and srdfdom take `2dof_planar`; the ros2_control macro is the Setup Assistant's
    `<robot>_ros2_control` behind an '_' (no XML name starts with a digit)."""
    from marm_setup.robot.load import expand_xacro
    from marm_setup.robot.ros_packages import find_packages

    urdf = tmp_path / "robot.urdf"
    urdf.write_text(TWO_BOXES.replace('name="test_robot"', 'name="2dof_planar"'))
    pkg = tmp_path / "pkg"
    assert_clean_exit(run("init", urdf, "--out", pkg, *TRIALS), codes=(0,))
    wrapper = pkg / "config" / "2dof_planar.urdf.xacro"
    text = expand_xacro(wrapper, {}, find_packages([tmp_path], near=wrapper), shown=str(wrapper))
    assert len(etree.fromstring(text.encode()).findall("ros2_control")) == 1
    assert_clean_exit(run("validate", pkg, "--no-plan"), codes=(0,))


@pytest.mark.parametrize("joint", ["j,1", "j}1", "j)2"])
def test_joint_names_that_break_moveit_lists_or_xacro_are_one_line(tmp_path, joint):
    urdf = tmp_path / "robot.urdf"
    urdf.write_text(TWO_BOXES.replace('joint name="j"', f'joint name="{joint}"'))
    assert_one_line_error(run("init", urdf, "--out", tmp_path / "pkg", *TRIALS), f"joint[{joint!r}]")


def test_hardware_parameters_reach_xacro_as_text(tmp_path):
    """`$(env HOME)` and `${...}` in a hardware parameter stay text through real xacro; names of
    the plugin and interfaces are refused when they are not ROS names."""
    from marm_setup.robot.load import expand_xacro
    from marm_setup.robot.ros_packages import find_packages

    def hardware(plugin: str):
        def edit(data):
            data.update(target="ros2", ros_distro="jazzy")
            del data["driver"]
            data["ros2_control"] = {"plugin": plugin, "parameters": {"port": "$(env HOME) ${10**10**8}"}}

        return edit

    result = _init(tmp_path, _spec(tmp_path, hardware("my_driver/ArmSystem")))
    assert_clean_exit(result, codes=(0,))
    wrapper = tmp_path / "pkg" / "config" / "marm.urdf.xacro"
    packages = find_packages([tmp_path, FIXTURES / "marm"], near=wrapper)
    text = expand_xacro(wrapper, {"use_mock_hardware": "false"}, packages, shown=str(wrapper))
    (param,) = etree.fromstring(text.encode()).xpath("//hardware/param[@name='port']")
    assert param.text == "$(env HOME) ${10**10**8}"
    shutil.rmtree(tmp_path / "pkg")
    bad = _init(tmp_path, _spec(tmp_path, hardware("$(env X)/Y")))
    assert_one_line_error(bad, "ros2_control.plugin")


def _twin_servo_groups(first: str, second: str):
    """Two copies of the arm group named `first` and `second`, each with IK and a servo."""

    def edit(data: dict) -> None:
        data.update(target="ros2", ros_distro="jazzy")
        data.pop("driver", None)
        arm = next(g for g in data["groups"] if g["name"] == "arm")
        data["groups"] = [g for g in data["groups"] if g["name"] != "arm"]
        data["groups"] += [{**arm, "name": first}, {**arm, "name": second}]
        for key in ("group_states", "end_effectors"):
            data[key] = [i for i in data.get(key, []) if i.get("group") != "arm"]
        solver = "kdl_kinematics_plugin/KDLKinematicsPlugin"
        data["kinematics"] = [{"group": g, "solver": solver} for g in (first, second)]
        data["servo"] = [{"group": first}, {"group": second}]

    return edit


@pytest.mark.parametrize(("first", "second"), [("arm", "Arm"), ("left_arm", "LEFT_ARM"), ("arm", "arm_2")])
def test_groups_whose_servo_files_differ_only_in_case_are_refused(tmp_path, first, second):
    """config/<group>_servo.yaml of `arm` and `Arm` are one file on macOS and Windows."""
    result = _init(tmp_path, _spec(tmp_path, _twin_servo_groups(first, second)))
    if first.casefold() != second.casefold():
        assert_clean_exit(result, codes=(0,))
        assert (tmp_path / "pkg" / f"config/{second}_servo.yaml").is_file()
        return
    assert_one_line_error(result, f"servo[{second}]", "differs from", "only in case")
    assert not (tmp_path / "pkg").exists()


@pytest.mark.parametrize("size", [400, 10_000, 100_000])
@pytest.mark.parametrize(
    ("where", "reason"),
    [("group", "is longer than 200 characters"), ("controller", "missing key 'action_ns'")],
)
def test_a_huge_name_is_excerpted_and_the_reason_kept(tmp_path, size, where, reason):
    """The name is cut in its middle, not the error line at its end (cli/common.py one_line)."""
    from marm_setup.cli.common import MAX_LINE

    huge = "g" * (size - 1) + "Z"

    def edit(data: dict) -> None:
        if where == "group":
            data["groups"].append({"name": huge, "joints": ["joint1"]})
        else:
            data["controllers"] = [{"name": huge, "type": "FollowJointTrajectory", "joints": ["nojoint"]}]

    result = _init(tmp_path, _spec(tmp_path, edit))
    assert_one_line_error(result)
    line = result.stderr.strip()
    assert len(line) <= MAX_LINE and line.endswith(reason) and "...g" in line and "gZ]" in line

"""render_package: golden trees, every file parsed back, controller wiring agrees across files."""

from __future__ import annotations

import dataclasses
import functools
import math
from pathlib import Path

import pytest
import yaml
from lxml import etree

from marm_setup.errors import InputError
from marm_setup.moveit_params.vocabulary import ROS2_ACTION_NS, ROS2_CONTROLLER_TYPES
from marm_setup.render.package import description_package, render_package
from marm_setup.setup.model import ArbotixJoint, JointLimitOverride, RobotSource
from tests.conftest import GOLDENS
from tests.render_helpers import inferred_marm, marm_robot

TARGETS = ("ros1", "ros2")
# (target, distro) of each golden tree, tests/goldens/<target>-<distro>/
DISTROS = (("ros1", "noetic"), ("ros2", "humble"), ("ros2", "jazzy"))
DEFAULT_DISTRO = {"ros1": "noetic", "ros2": "humble"}
XML_SUFFIXES = (".xml", ".launch", ".srdf", ".xacro")


def golden_dir(target: str, distro: str | None = None) -> Path:
    return GOLDENS / f"{target}-{distro or DEFAULT_DISTRO[target]}"


def marm_model(target: str, distro: str | None = None):
    """The marm setup `init --setup fixtures/marm/marm_setup.yaml --target <target>` builds."""
    return inferred_marm(target, golden_dir(target, distro), distro)[0]


@functools.lru_cache(maxsize=4)
def rendered(target: str, distro: str | None = None) -> dict[str, str]:
    model, robot = inferred_marm(target, golden_dir(target, distro), distro)
    return {f.path: f.content for f in render_package(model, robot)}


def load_yaml(files: dict[str, str], path: str):
    return yaml.safe_load(files[path])


# THE LIST OF GENERATED FILES: every file the marm package must have, per golden tree, written
# out here rather than taken from marm_setup's own tables, so a file that stops being generated
# (or a new one nobody reviewed) fails test_file_list. A new generated file goes here, and its
# golden under tests/goldens/<tree>/ (`pytest --update-goldens` writes it once, failing).
ROS1_PACKAGE = (
    ".setup_assistant",
    "CMakeLists.txt",
    "config/arbotix.yaml",
    "config/arm_servo.yaml",
    "config/controllers.yaml",
    "config/fake_controllers.yaml",
    "config/joint_limits.yaml",
    "config/cartesian_limits.yaml",
    "config/kinematics.yaml",
    "config/marm.srdf",
    "config/ompl_planning.yaml",
    "launch/arbotix.launch",
    "launch/arbotix_moveit.launch",
    "launch/default_warehouse_db.launch",
    "launch/demo.launch",
    "launch/fake_moveit_controller_manager.launch.xml",
    "launch/move_group.launch",
    "launch/moveit.rviz",
    "launch/moveit_rviz.launch",
    "launch/ompl_planning_pipeline.launch.xml",
    "launch/pilz_industrial_motion_planner_planning_pipeline.launch.xml",
    "launch/planning_context.launch",
    "launch/planning_pipeline.launch.xml",
    "launch/ros_control_moveit_controller_manager.launch.xml",
    "launch/servo.launch",
    "launch/simple_moveit_controller_manager.launch.xml",
    "launch/trajectory_execution.launch.xml",
    "launch/warehouse.launch",
    "launch/warehouse_settings.launch.xml",
    "marm_setup.yaml",
    "package.xml",
    "scripts/gripper_controller.py",
    "scripts/trajectory_demo.py",
)
ROS2_PACKAGE = (
    ".setup_assistant",
    "CMakeLists.txt",
    "config/arm_servo.yaml",
    "config/initial_positions.yaml",
    "config/marm.ros2_control.xacro",
    "config/marm.srdf",
    "config/marm.urdf.xacro",
    "config/moveit.rviz",
    "config/moveit.yaml",
    "config/ros2_controllers.yaml",
    "launch/demo.launch.xml",
    "launch/move_group.launch.xml",
    "launch/servo.launch.xml",
    "marm_setup.yaml",
    "package.xml",
)
EXPECTED_FILES = {"ros1-noetic": ROS1_PACKAGE, "ros2-humble": ROS2_PACKAGE, "ros2-jazzy": ROS2_PACKAGE}


def expected_paths(target: str, distro: str | None = None) -> list[str]:
    return sorted(EXPECTED_FILES[f"{target}-{distro or DEFAULT_DISTRO[target]}"])


GOLDEN_CASES = [(t, d, p) for t, d in DISTROS for p in expected_paths(t, d)]


@pytest.mark.parametrize(("target", "distro"), DISTROS)
def test_file_list(target, distro):
    assert sorted(EXPECTED_FILES) == sorted(f"{t}-{d}" for t, d in DISTROS)
    assert sorted(rendered(target, distro)) == expected_paths(target, distro)
    tree = golden_dir(target, distro)
    on_disk = sorted(p.relative_to(tree).as_posix() for p in tree.rglob("*") if p.is_file())
    assert [p for p in on_disk if not p.endswith(".obtained")] == expected_paths(target, distro)


@pytest.mark.parametrize(
    ("target", "distro", "path"), GOLDEN_CASES, ids=[f"{t}-{d}/{p}" for t, d, p in GOLDEN_CASES]
)
def test_golden_file(target, distro, path, assert_golden):
    assert_golden(f"{target}-{distro}/{path}", rendered(target, distro)[path])


@pytest.mark.parametrize(("target", "distro"), DISTROS)
def test_render_is_pure_sorted_and_newline_terminated(target, distro):
    model, robot = inferred_marm(target, golden_dir(target, distro), distro)
    first, second = render_package(model, robot), render_package(model, robot)
    assert first == second
    assert [f.path for f in first] == sorted(f.path for f in first)
    for f in first:
        assert f.content.endswith("\n") and not f.content.endswith("\n\n"), f.path
        assert "\r" not in f.content and "/work/" not in f.content, f.path


@pytest.mark.parametrize(("target", "distro"), DISTROS)
def test_every_yaml_and_xml_parses(target, distro):
    files = rendered(target, distro)
    for path, content in files.items():
        if path.endswith(".yaml"):
            assert isinstance(yaml.safe_load(content), dict), path
        elif path.endswith(XML_SUFFIXES):
            etree.fromstring(content.encode())
    for script in ("scripts/trajectory_demo.py", "scripts/gripper_controller.py"):
        compile(files.get(script, ""), script, "exec")


@pytest.mark.parametrize("target", TARGETS)
def test_catkin_pkg_accepts_package_xml(target, tmp_path):
    from catkin_pkg.package import parse_package

    (tmp_path / "package.xml").write_text(rendered(target)["package.xml"])
    package = parse_package(str(tmp_path / "package.xml"))
    assert package.name == "marm_moveit_config"
    assert package.package_format == (2 if target == "ros1" else 3)
    buildtool = {d.name for d in package.buildtool_depends}
    assert buildtool == ({"catkin"} if target == "ros1" else {"ament_cmake"})
    assert "marm_description" in {d.name for d in package.exec_depends}


def test_ros1_yaml_structure():
    files = rendered("ros1")
    robot = marm_robot()
    kin = load_yaml(files, "config/kinematics.yaml")
    assert set(kin) == {"arm"}
    assert kin["arm"]["kinematics_solver"] == "kdl_kinematics_plugin/KDLKinematicsPlugin"
    assert isinstance(kin["arm"]["kinematics_solver_timeout"], float)
    assert "kinematics_solver_attempts" not in kin["arm"]  # MoveIt 1 warns: it only has a timeout

    limits = load_yaml(files, "config/joint_limits.yaml")
    assert set(limits["joint_limits"]) == {f"joint{i}" for i in range(1, 7)} | {"finger_joint1"}
    for name, entry in limits["joint_limits"].items():
        assert entry["has_velocity_limits"] is True
        assert entry["max_velocity"] == robot.joint(name).velocity
        assert entry["has_acceleration_limits"] is True and entry["max_acceleration"] > 0

    ompl = load_yaml(files, "config/ompl_planning.yaml")
    for group in ("arm", "gripper"):
        assert ompl[group]["default_planner_config"] in ompl["planner_configs"]
        assert set(ompl[group]["planner_configs"]) <= set(ompl["planner_configs"])

    fake = load_yaml(files, "config/fake_controllers.yaml")
    assert [c["name"] for c in fake["controller_list"]] == ["fake_arm_controller", "fake_gripper_controller"]
    assert fake["controller_list"][1]["joints"] == ["finger_joint1"]
    assert fake["initial"] == [{"group": "arm", "pose": "home"}]


def test_ros1_arbotix_angles_come_from_urdf_limits():
    files = rendered("ros1")
    robot = marm_robot()
    arbotix = load_yaml(files, "config/arbotix.yaml")
    ids = [j["id"] for j in arbotix["joints"].values()]
    assert len(set(ids)) == len(ids)
    for name, servo in arbotix["joints"].items():
        joint = robot.joint(name)
        if joint.type == "revolute":
            assert servo["min_angle"] == pytest.approx(math.degrees(joint.lower), abs=1e-3)
            assert servo["max_angle"] == pytest.approx(math.degrees(joint.upper), abs=1e-3)
    assert arbotix["controllers"]["arm_controller"]["type"] == "follow_controller"


def test_ros1_servo_ids_not_in_the_setup_avoid_the_given_ones():
    model = dataclasses.replace(marm_model("ros1"), arbotix_joints=(ArbotixJoint("finger_joint1", 1),))
    files = {f.path: f.content for f in render_package(model, marm_robot())}
    ids = {name: j["id"] for name, j in load_yaml(files, "config/arbotix.yaml")["joints"].items()}
    assert ids["finger_joint1"] == 1
    assert sorted(ids.values()) == list(range(1, 8))


def test_ros1_controller_wiring_agrees():
    files = rendered("ros1")
    moveit = load_yaml(files, "config/controllers.yaml")["controller_list"]
    arbotix = load_yaml(files, "config/arbotix.yaml")
    launch = etree.fromstring(files["launch/arbotix.launch"].encode())
    grippers = {n.get("name"): n for n in launch.iter("node") if n.get("type") == "gripper_controller.py"}
    served = {f"{n}/gripper_action" for n in grippers}
    served |= {c["action_name"] for c in arbotix["controllers"].values()}
    assert {f"{c['name']}/{c['action_ns']}" for c in moveit} == served
    for c in moveit:
        if c["type"] == "FollowJointTrajectory":
            assert arbotix["controllers"][c["name"]]["joints"] == c["joints"]
        else:
            params = {p.get("name"): p.get("value") for p in grippers[c["name"]].iter("param")}
            assert params["joint"] == c["joints"][0]
        assert set(c["joints"]) <= set(arbotix["joints"])


def test_ros1_trajectory_demo_drives_the_arbotix_arm_controller():
    import ast

    files = rendered("ros1")
    tree = ast.parse(files["scripts/trajectory_demo.py"])
    consts = {
        node.targets[0].id: ast.literal_eval(node.value)
        for node in tree.body
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name)
    }
    arm = load_yaml(files, "config/arbotix.yaml")["controllers"]["arm_controller"]
    assert consts["ACTION"] == arm["action_name"] and consts["JOINTS"] == arm["joints"]
    poses = {s.name: dict(s.values) for s in marm_model("ros1").group_states}
    assert consts["HOME"] == [poses["home"][j] for j in arm["joints"]]
    assert consts["GOAL"] == [poses["forward"][j] for j in arm["joints"]]
    # ArbotiX's follow_controller times a point by time_from_start and warns when velocities come too
    assigned = {
        t.attr
        for n in ast.walk(tree)
        if isinstance(n, ast.Assign)
        for t in n.targets
        if isinstance(t, ast.Attribute)
    }
    assert "time_from_start" in assigned and "velocities" not in assigned


def test_ros1_launch_references_exist():
    """Every config and launch file is loaded by a launch file, directly or as the
    `$(arg moveit_controller_manager)` / `$(arg pipeline)` choice the Setup Assistant's layout uses
    (and servo.launch's `$(arg group)`)."""
    files = rendered("ros1")
    text = "\n".join(v for k, v in files.items() if k.startswith("launch/"))
    chosen = ("_moveit_controller_manager.launch.xml", "_planning_pipeline.launch.xml", "_servo.yaml")
    top = ("demo.launch", "arbotix_moveit.launch", "servo.launch")
    for path in files:
        if path.startswith(("config/", "launch/")) and not path.endswith(chosen):
            assert path in text or path.endswith(top), path
    assert "$(find marm_moveit_config)/config/$(arg group)_servo.yaml" in text
    launch = "$(find marm_moveit_config)/launch/"
    assert f"{launch}$(arg moveit_controller_manager)_moveit_controller_manager.launch.xml" in text
    assert f"{launch}$(arg pipeline)_planning_pipeline.launch.xml" in text
    for manager in ("simple", "fake", "ros_control"):
        assert f"launch/{manager}_moveit_controller_manager.launch.xml" in files
    move_group = etree.fromstring(files["launch/move_group.launch"].encode())
    for include in move_group.iter("include"):
        for arg in include.iter("arg"):
            if arg.get("name") == "pipeline" and "$(" not in arg.get("value"):
                assert f"launch/{arg.get('value')}_planning_pipeline.launch.xml" in files


def _floats_only(tree, where=""):
    """Every number in a mapping tree, except ints listed as such by MoveIt/ros2_control."""
    if isinstance(tree, dict):
        for key, value in tree.items():
            yield from _floats_only(value, f"{where}/{key}")
    elif isinstance(tree, list):
        for i, value in enumerate(tree):
            yield from _floats_only(value, f"{where}[{i}]")
    elif isinstance(tree, int | float) and not isinstance(tree, bool):
        yield where, tree


def test_ros2_numeric_params_are_floats():
    files = rendered("ros2")
    moveit = load_yaml(files, "config/moveit.yaml")["/**"]["ros__parameters"]
    for section in ("robot_description_planning", "robot_description_kinematics", "trajectory_execution"):
        for where, value in _floats_only(moveit[section], section):
            assert isinstance(value, float), where
    ompl = moveit["ompl"]
    assert isinstance(ompl["start_state_max_bounds_error"], float)
    assert isinstance(ompl["arm"]["longest_valid_segment_fraction"], float)
    for where, value in _floats_only(load_yaml(files, "config/initial_positions.yaml")):
        assert isinstance(value, float), where
    controllers = load_yaml(files, "config/ros2_controllers.yaml")
    assert isinstance(controllers["controller_manager"]["ros__parameters"]["update_rate"], int)


def test_ros2_moveit_yaml_structure():
    files = rendered("ros2")
    params = load_yaml(files, "config/moveit.yaml")["/**"]["ros__parameters"]
    assert params["planning_pipelines"] == ["ompl", "pilz_industrial_motion_planner"]
    assert set(params["robot_description_kinematics"]) == {"arm"}
    planning = params["robot_description_planning"]
    assert set(planning["cartesian_limits"]) == {
        "max_trans_vel",
        "max_trans_acc",
        "max_trans_dec",
        "max_rot_vel",
    }
    assert "joint1" in planning["joint_limits"]
    assert (
        params["moveit_controller_manager"]
        == "moveit_simple_controller_manager/MoveItSimpleControllerManager"
    )


def test_ros2_controller_wiring_agrees():
    files = rendered("ros2")
    moveit = load_yaml(files, "config/moveit.yaml")["/**"]["ros__parameters"][
        "moveit_simple_controller_manager"
    ]
    ros2 = load_yaml(files, "config/ros2_controllers.yaml")
    manager = ros2["controller_manager"]["ros__parameters"]
    assert manager["joint_state_broadcaster"]["type"] == "joint_state_broadcaster/JointStateBroadcaster"
    assert set(moveit["controller_names"]) == set(manager) - {"update_rate", "joint_state_broadcaster"}
    for name in moveit["controller_names"]:
        entry = moveit[name]
        assert manager[name]["type"] == ROS2_CONTROLLER_TYPES[entry["type"]]
        assert entry["action_ns"] == ROS2_ACTION_NS[entry["type"]]
        params = ros2[name]["ros__parameters"]
        assert params.get("joints", [params.get("joint")]) == entry["joints"]
    demo = etree.fromstring(files["launch/demo.launch.xml"].encode())
    spawned = {n.get("args").split()[0] for n in demo.iter("node") if n.get("exec") == "spawner"}
    assert spawned == set(moveit["controller_names"]) | {"joint_state_broadcaster"}
    param_file = "--param-file $(find-pkg-share marm_moveit_config)/config/ros2_controllers.yaml"
    for node in demo.iter("node"):  # a controller with a parameter section gets it from its spawner
        args = node.get("args") or ""
        if node.get("exec") == "spawner" and args.split()[0] in ros2:
            assert param_file in args, args


# ros2_controllers: the package that exports each controller plugin type.
PLUGIN_PACKAGES = {
    "joint_state_broadcaster/JointStateBroadcaster": "joint_state_broadcaster",
    "joint_trajectory_controller/JointTrajectoryController": "joint_trajectory_controller",
    "position_controllers/GripperActionController": "gripper_controllers",
}


def test_ros2_package_xml_depends_on_every_controller_plugin_package(tmp_path):
    from catkin_pkg.package import parse_package

    files = rendered("ros2")
    (tmp_path / "package.xml").write_text(files["package.xml"])
    depends = {d.name for d in parse_package(str(tmp_path / "package.xml")).exec_depends}
    manager = load_yaml(files, "config/ros2_controllers.yaml")["controller_manager"]["ros__parameters"]
    types = {entry["type"] for entry in manager.values() if isinstance(entry, dict)}
    assert types == set(PLUGIN_PACKAGES)
    assert {PLUGIN_PACKAGES[t] for t in types} <= depends


def test_ros2_initial_positions_within_limits_and_cover_ros2_control():
    files = rendered("ros2")
    robot = marm_robot()
    initial = load_yaml(files, "config/initial_positions.yaml")["initial_positions"]
    for name, value in initial.items():
        lo, hi = robot.joint(name).bounds
        assert lo <= value <= hi
    xacro = etree.fromstring(files["config/marm.ros2_control.xacro"].encode())
    joints = {j.get("name"): j for j in xacro.iter("joint")}
    assert set(joints) == set(initial)
    mimic = {p.get("name"): p.text for p in joints["finger_joint2"].iter("param")}
    assert mimic["mimic"] == "finger_joint1" and float(mimic["multiplier"]) == -1.0
    assert joints["finger_joint2"].find("command_interface") is None
    assert xacro.find(".//plugin").text == "mock_components/GenericSystem"


def test_ros2_launch_description_params_are_typed_str():
    files = rendered("ros2")
    count = 0
    for path in ("launch/demo.launch.xml", "launch/move_group.launch.xml"):
        for param in etree.fromstring(files[path].encode()).iter("param"):
            if (param.get("name") or "").startswith("robot_description"):
                assert param.get("type") == "str", (path, param.get("name"))
                count += 1
    assert count == 6


def test_joint_limit_overrides_and_missing_velocity():
    model, robot = inferred_marm("ros1", golden_dir("ros1"))
    model = dataclasses.replace(
        model,
        joint_limits=(JointLimitOverride("joint2", max_velocity=0.5, max_acceleration=2.0, max_jerk=9.0),),
    )
    files = {f.path: f.content for f in render_package(model, robot)}
    entry = yaml.safe_load(files["config/joint_limits.yaml"])["joint_limits"]["joint2"]
    assert entry == {
        "has_velocity_limits": True,
        "max_velocity": 0.5,
        "has_acceleration_limits": True,
        "max_acceleration": 2.0,
        "has_jerk_limits": True,
        "max_jerk": 9.0,
    }


def test_both_targets_render_the_srdf_with_the_virtual_joint():
    for target in TARGETS:
        files = {f.path: f.content for f in render_package(marm_model(target), marm_robot())}
        assert "config/marm.srdf" in files
        assert "virtual_joint" in files["config/marm.srdf"]


def test_description_package_and_fallback(tmp_path):
    urdf = Path(marm_robot().source)
    assert description_package(urdf) == ("marm_description", "urdf/marm.urdf.xacro")
    loose = tmp_path / "robot.urdf"
    loose.write_text("<robot name='x'/>")
    assert description_package(loose) is None
    robot = dataclasses.replace(marm_robot(), source=str(loose))
    files = {}
    for target in TARGETS:
        model = dataclasses.replace(marm_model(target), robot=RobotSource(urdf="../robot.urdf"))
        files[target] = {f.path: f.content for f in render_package(model, robot)}
        # a URDF in no ROS package is copied in: only share/<pkg> is installed, '../' is not
        copy = files[target]["description/robot.urdf"]
        assert copy.rstrip("\n") == robot.urdf_xml.rstrip("\n")
        assert "install(DIRECTORY launch config description " in files[target]["CMakeLists.txt"]
        assert not any(
            "/.." in text for path, text in files[target].items() if path.startswith(("launch/", "config/"))
        )
    planning_context = files["ros1"]["launch/planning_context.launch"]
    assert 'textfile="$(find marm_moveit_config)/description/robot.urdf"' in planning_context
    wrapper = files["ros2"]["config/marm.urdf.xacro"]
    assert 'filename="$(find marm_moveit_config)/description/robot.urdf"' in wrapper


def test_unknown_target_is_input_error():
    model = dataclasses.replace(marm_model("ros1"), target="ros3")
    with pytest.raises(InputError, match="ros3"):
        render_package(model, marm_robot())


def test_xacro_args_reach_both_targets():
    for target in TARGETS:
        model = marm_model(target)
        source = dataclasses.replace(model.robot, xacro_args=(("with_gripper", "true"),))
        model = dataclasses.replace(model, robot=source)
        files = {f.path: f.content for f in render_package(model, marm_robot())}
        if target == "ros1":
            context = files["launch/planning_context.launch"]
            assert (
                "command=\"xacro '$(find marm_description)/urdf/marm.urdf.xacro' with_gripper:=true\""
                in context
            )
        else:
            wrapper = etree.fromstring(files["config/marm.urdf.xacro"].encode())
            xacro_ns = "{http://www.ros.org/wiki/xacro}"
            args = {a.get("name"): a.get("default") for a in wrapper.iter(f"{xacro_ns}arg")}
            assert args["with_gripper"] == "true"


def _with_home(target: str, values: dict[str, float]):
    from marm_setup.setup.model import GroupState

    model = marm_model(target)
    states = tuple(
        GroupState(s.name, s.group, tuple((j, values.get(j, v)) for j, v in s.values))
        if s.name == "home"
        else s
        for s in model.group_states
    )
    gripper = GroupState("open", "gripper", (("finger_joint1", values["finger_joint1"]),))
    return dataclasses.replace(model, group_states=(*states, gripper))


def test_ros2_starts_at_the_pose_ros1_starts_at():
    home = {"joint2": 0.3, "joint3": -0.5, "finger_joint1": 0.01}
    ros1 = {f.path: f.content for f in render_package(_with_home("ros1", home), marm_robot())}
    ros2 = {f.path: f.content for f in render_package(_with_home("ros2", home), marm_robot())}
    poses = {(s.group, s.name): dict(s.values) for s in _with_home("ros1", home).group_states}
    start = {}
    for entry in load_yaml(ros1, "config/fake_controllers.yaml")["initial"]:
        start.update(poses[entry["group"], entry["pose"]])
    initial = load_yaml(ros2, "config/initial_positions.yaml")["initial_positions"]
    assert {j: initial[j] for j in start} == start
    assert initial["joint2"] == 0.3 and initial["finger_joint2"] == -0.01  # the mimic follows its leader


def test_every_virtual_joint_type_gets_a_static_tf():
    from marm_setup.setup.model import VirtualJoint

    for target, launch in (("ros1", "launch/demo.launch"), ("ros2", "launch/demo.launch.xml")):
        model = dataclasses.replace(
            marm_model(target), virtual_joints=(VirtualJoint("base_joint", "floating", "odom", "base_link"),)
        )
        files = {f.path: f.content for f in render_package(model, marm_robot())}
        nodes = etree.fromstring(files[launch].encode()).iter("node")
        args = [n.get("args") for n in nodes if n.get("pkg") == "tf2_ros"]
        assert len(args) == 1 and "odom" in args[0] and "base_link" in args[0], args


@pytest.mark.parametrize(("target", "distro"), DISTROS)
def test_ompl_projection_evaluator_for_groups_of_two_or_more_joints(target, distro):
    files = rendered(target, distro)
    if target == "ros1":
        ompl = load_yaml(files, "config/ompl_planning.yaml")
    else:
        ompl = load_yaml(files, "config/moveit.yaml")["/**"]["ros__parameters"]["ompl"]
    assert ompl["arm"]["projection_evaluator"] == "joints(joint1,joint2)"
    assert "projection_evaluator" not in ompl["gripper"]  # one active joint (finger_joint2 mimics it)


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_ros2_publishes_the_planning_scene_for_rviz(distro):
    params = load_yaml(rendered("ros2", distro), "config/moveit.yaml")["/**"]["ros__parameters"]
    for flag in ("planning_scene", "geometry_updates", "state_updates", "transforms_updates"):
        assert params[f"publish_{flag}"] is True


@pytest.mark.parametrize(("target", "distro"), DISTROS)
def test_rviz_config_shows_motion_planning_for_the_arm_and_the_demo_loads_it(target, distro):
    files = rendered(target, distro)
    path = "launch/moveit.rviz" if target == "ros1" else "config/moveit.rviz"
    config = load_yaml(files, path)["Visualization Manager"]
    displays = {d["Class"].rsplit("/", 1)[-1]: d for d in config["Displays"]}
    assert {"Grid", "RobotModel", "TF", "MotionPlanning"} <= set(displays)
    assert displays["MotionPlanning"]["Planning Request"]["Planning Group"] == "arm"
    assert config["Global Options"]["Fixed Frame"] == "world"  # the virtual joint's parent
    prefix = "rviz" if target == "ros1" else "rviz_default_plugins"
    assert displays["Grid"]["Class"] == f"{prefix}/Grid"
    if target == "ros1":
        rviz = etree.fromstring(files["launch/moveit_rviz.launch"].encode())
        assert rviz.find("node").get("args") == "$(arg command_args)"
        assert "-d $(arg rviz_config)" in files["launch/moveit_rviz.launch"]
        demo = etree.fromstring(files["launch/demo.launch"].encode())
        include = next(i for i in demo.iter("include") if "moveit_rviz.launch" in i.get("file"))
        assert include.find("arg[@name='rviz_config']").get("value").endswith("/launch/moveit.rviz")
    else:
        demo = etree.fromstring(files["launch/demo.launch.xml"].encode())
        node = next(n for n in demo.iter("node") if n.get("exec") == "rviz2")
        assert node.get("args") == "-d $(find-pkg-share marm_moveit_config)/config/moveit.rviz"

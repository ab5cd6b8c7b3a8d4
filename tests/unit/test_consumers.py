"""Which real consumer validate uses (validate/consumers.py), and how the check script's report
becomes findings naming the launch file. The real runs are in tests/integration/test_launch_defects.py."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from marm_setup.package.launch_xml import parse_launch
from marm_setup.validate.consumers import (
    _dump_problem,
    _needs_args,
    _run,
    find_ros2_python,
    find_roslaunch,
    ros2_findings,
    ros2_python,
    ros2_ran,
)
from tests.helpers import build_file_tree

REPORT = {
    "launch": {
        "launch/demo.launch.xml": {
            "code": 0,
            "errors": [],
            "nodes": [
                {
                    "package": "robot_state_publisher",
                    "executable": "robot_state_publisher",
                    "name": "robot_state_publisher",
                    "error": None,
                    "ros2_control": {"arm": "acme/Arm", "hand": "mock_components/GenericSystem"},
                },
                {
                    "package": "rviz2",
                    "executable": "rviz2",
                    "name": "rviz2",
                    "error": "ValueError: Cannot declare a statically typed parameter with default value of type PARAMETER_NOT_SET",
                },
            ],
        },
        "launch/move_group.launch.xml": {
            "code": 1,
            "errors": ["Caught exception in launch: executed command showed stderr output"],
            "nodes": [],
        },
    },
    "params": {
        "config/moveit.yaml": ["move_group: ValueError: PARAMETER_NOT_SET"],
        "config/ros2_controllers.yaml": [],
    },
}


def test_the_report_becomes_findings_naming_the_launch_file():
    found = {(f.rule, f.file, f.element) for f in ros2_findings(REPORT, "jazzy")}
    assert found == {
        ("demo.real-hardware", "launch/demo.launch.xml", "ros2_control[arm]"),
        ("ros2.params", "launch/demo.launch.xml", "node[rviz2]"),
        ("ros2.launch", "launch/move_group.launch.xml", "launch"),
        ("ros2.params", "config/moveit.yaml", "move_group"),
    }
    assert all(f.is_error for f in ros2_findings(REPORT, "jazzy"))


def test_humbles_fake_components_count_as_mock_on_humble_only():
    report = {
        "launch": {
            "launch/demo.launch.xml": {
                "code": 0,
                "errors": [],
                "nodes": [
                    {
                        "package": "p",
                        "executable": "ros2_control_node",
                        "name": "controller_manager",
                        "error": None,
                        "ros2_control": {"arm": "fake_components/GenericSystem"},
                    }
                ],
            }
        }
    }
    assert ros2_findings(report, "humble") == []
    assert [f.rule for f in ros2_findings(report, "jazzy")] == ["demo.real-hardware"]


def test_no_ros_no_consumer(monkeypatch, tmp_path):
    monkeypatch.setenv("MARM_SETUP_ROS2_PYTHON", "")
    monkeypatch.setenv("ROS_DISTRO", "jazzy")
    assert find_ros2_python() == (None, "MARM_SETUP_ROS2_PYTHON is empty")  # empty: never
    monkeypatch.setenv("MARM_SETUP_ROS2_PYTHON", sys.executable)  # a Python without launch_ros
    assert ros2_python() is None
    monkeypatch.delenv("MARM_SETUP_ROS2_PYTHON")
    monkeypatch.setenv("PATH", str(tmp_path))  # nothing on PATH
    assert find_ros2_python() == (None, "no ros2 or python3 on PATH: source ROS 2")


def _script(folder, name: str, body: str) -> str:
    path = folder / name
    path.write_text(body, encoding="utf-8")
    path.chmod(0o755)
    return str(path)


def test_the_python_of_ros2_on_path_wins_over_a_venv_first_on_path(monkeypatch, tmp_path):
    """marm-setup's own venv first on PATH: its python3 lacks launch_ros; the `ros2` command's
    `#!` line names the Python ROS 2 runs on."""
    venv, ros = tmp_path / "venv", tmp_path / "ros"
    venv.mkdir(), ros.mkdir()
    os.symlink(sys.executable, venv / "python3")
    ros_python = _script(ros, "python3.12", "#!/bin/sh\necho 3.4.5\n")  # imports launch: prints its version
    _script(ros, "ros2", f"#!{ros_python}\nimport ros2cli\n")
    monkeypatch.delenv("MARM_SETUP_ROS2_PYTHON")
    monkeypatch.setenv("PATH", os.pathsep.join([str(venv), str(ros)]))
    assert find_ros2_python() == ((ros_python, "3.4.5"), "")
    (ros / "ros2").unlink()
    found, why = find_ros2_python()
    assert found is None
    assert why.startswith("no Python with ROS 2's launch_ros and rclpy (set MARM_SETUP_ROS2_PYTHON")
    assert f"tried {venv / 'python3'}: ModuleNotFoundError: No module named 'launch'" in why


def test_roslaunch_on_path_is_used_when_it_runs_without_a_sourced_ros(monkeypatch, tmp_path):
    monkeypatch.delenv("MARM_SETUP_ROSLAUNCH")
    monkeypatch.setenv("PATH", str(tmp_path))
    assert find_roslaunch() == (
        None,
        "no roslaunch on PATH: install ROS 1 (or Debian's python3-roslaunch), or set MARM_SETUP_ROSLAUNCH",
    )
    roslaunch = _script(tmp_path, "roslaunch", "#!/bin/sh\nexit 0\n")
    assert find_roslaunch() == (roslaunch, "")
    _script(tmp_path, "roslaunch", "#!/bin/sh\necho 'ImportError: no rospkg' >&2\nexit 1\n")
    assert find_roslaunch() == (None, f"{roslaunch} does not run (ImportError: no rospkg)")
    monkeypatch.setenv("MARM_SETUP_ROSLAUNCH", "")
    assert find_roslaunch() == (None, "MARM_SETUP_ROSLAUNCH is empty")


def test_the_summary_never_says_the_ros2_launcher_ran_when_it_evaluated_nothing():
    missing = {"code": 1, "errors": ["Caught exception: No module named 'moveit_configs_utils'"], "nodes": []}
    unrun = {"launch": {"launch/demo.launch.py": missing, "launch/move_group.launch.py": missing}}
    assert ros2_ran(unrun, "ROS 2 launch 3.4.5 and rcl (py)") == (
        "static rules only (ROS 2 launch 3.4.5 and rcl (py) evaluated no launch or parameter file: "
        "2 import modules this ROS lacks)"
    )
    assert ros2_ran({"launch": {}, "params": {}}, "L").startswith("static rules only (L evaluated no launch")
    some = {"launch": {**unrun["launch"], "launch/x.launch.xml": REPORT["launch"]["launch/demo.launch.xml"]}}
    assert ros2_ran({**some, "params": {"config/a.yaml": []}}, "L") == (
        "L: 1 launch file evaluated, 1 parameter file parsed, 2 launch files not runnable here; "
        "and the static rules"
    )


def test_a_launch_file_with_an_arg_without_value_is_an_include(tmp_path):
    root = build_file_tree(
        tmp_path,
        {
            "a.launch": '<launch><arg name="x"/></launch>',
            "b.launch": '<launch><arg name="x" default="1"/></launch>',
        },
    )
    a, b = (parse_launch(root / rel, rel).root for rel in ("a.launch", "b.launch"))
    assert _needs_args(a) and not _needs_args(b)
    assert not _needs_args(a, frozenset({"x"}))  # --launch-arg x:=...: roslaunch runs it alone


@pytest.mark.parametrize(
    ("code", "stdout", "stderr", "problem"),
    [
        (0, "/a: 1\n", "", ""),
        (0, "Unable to load file x.launch: boom", "", "Unable to load file x.launch: boom"),
        (
            1,
            "",
            "RLException: [x.launch] is neither a launch file\n",
            "RLException: [x.launch] is neither a launch file",
        ),
    ],
)
def test_a_dump_that_prints_no_parameter_tree_failed(code, stdout, stderr, problem):
    assert _dump_problem(subprocess.CompletedProcess([], code, stdout, stderr)) == problem


def test_a_python_launch_file_needing_a_module_this_ros_lacks_is_a_warning():
    """MoveIt Setup Assistant launch files import moveit_configs_utils: without MoveIt installed
    the launcher cannot run them, which says nothing about the package."""
    message = "Caught exception in launch: ModuleNotFoundError: No module named 'moveit_configs_utils'"
    report = {"launch": {"launch/demo.launch.py": {"code": 1, "errors": [message], "nodes": []}}}
    (finding,) = ros2_findings(report, "humble")
    assert (finding.rule, finding.severity) == ("ros2.launch-unrun", "warning")


def test_a_launcher_that_does_not_finish_is_killed_with_its_children(tmp_path):
    """The consumer's child runs in its own process group: on timeout every process of it goes
    (a launcher's $(command) children included)."""
    pid_file = tmp_path / "child.pid"
    script = f"sleep 60 & echo $! > {pid_file}; wait"
    assert _run(["sh", "-c", script], dict(os.environ), 1.0) is None
    child = int(pid_file.read_text())
    with pytest.raises(ProcessLookupError):
        for _ in range(50):  # reaped by init shortly after the kill
            os.kill(child, 0)
            time.sleep(0.1)


def test_roslaunch_never_runs_marm_setups_own_pip_xacro(monkeypatch, tmp_path):
    """An activated venv puts PyPI's (ROS 2) xacro first on PATH: a ROS 1 launch's `xacro` must not
    be it (`$(find pkg)` needs ament there), the fallback comes last instead."""
    import sysconfig

    from marm_setup.validate.consumers import _ros1_path

    own = sysconfig.get_path("scripts")
    monkeypatch.setenv("PATH", os.pathsep.join([own, "/usr/bin", "/bin"]))
    assert _ros1_path(str(tmp_path)).split(os.pathsep) == ["/usr/bin", "/bin", str(tmp_path)]


def test_a_roslaunch_failure_for_want_of_the_description_package_is_a_warning():
    from marm_setup.validate.consumers import _launch_failure

    problem = "Unable to load file /ws/x_moveit_config/launch/demo.launch: x_description"
    unheld = lambda name: "" if name == "x_description" else None  # noqa: E731 - the description's package, not passed
    lacking = _launch_failure("launch/demo.launch", problem, unheld)
    assert (lacking.rule, lacking.severity) == ("ros1.launch", "warning")
    assert "--package-path DIR (the folder holding x_description)" in lacking.hint
    typo = problem.replace("x_description", "no_such_package")  # a package nobody has: the launch's fault
    assert _launch_failure("launch/demo.launch", typo, unheld).severity == "error"
    other = _launch_failure("launch/demo.launch", "unused args [controller_manager]", unheld)
    assert other.severity == "error"


GAZEBO_LAUNCH = """<launch>
  <arg name="paused" default="false"/>
  <include file="$(find gazebo_ros)/launch/empty_world.launch" pass_all_args="true"/>
  <node name="spawn_gazebo_model" pkg="gazebo_ros" type="spawn_model" args="-urdf -param robot_description"/>
</launch>
"""


def test_a_ros_package_roslaunch_lacks_is_a_warning_while_no_ros_is_sourced(tmp_path, monkeypatch):
    """The Setup Assistant's gazebo.launch $(find)s gazebo_ros, which its package.xml leaves out:
    with no ROS sourced, roslaunch here cannot tell a package this machine lacks from a wrong name;
    with a ROS sourced that has no such package, the launch fails for the user too."""
    import shutil

    from marm_setup.validate.runner import validate
    from tests.validate_helpers import generate_marm

    roslaunch = shutil.which("roslaunch")
    if roslaunch is None:
        pytest.skip("roslaunch not on PATH")
    pkg = generate_marm(tmp_path, "ros1")
    (pkg / "launch" / "gazebo.launch").write_text(GAZEBO_LAUNCH, encoding="utf-8")
    monkeypatch.setenv("MARM_SETUP_ROSLAUNCH", roslaunch)
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)

    def found() -> list[tuple[str, str, str]]:
        checked = validate(pkg, plan=False)
        return [(f.file, str(f.severity), f.hint) for f in checked.findings if f.rule == "ros1.launch"]

    [(file, severity, hint)] = found()
    assert (file, severity) == ("launch/gazebo.launch", "warning")
    assert "the folder holding gazebo_ros), or source the ROS installation that has it" in hint
    (tmp_path / "ros").mkdir()
    monkeypatch.setenv("ROS_PACKAGE_PATH", str(tmp_path / "ros"))
    assert [(file, severity) for file, severity, _ in found()] == [("launch/gazebo.launch", "error")]


def test_a_misspelt_package_roslaunch_lacks_is_an_error_even_with_no_ros_sourced(tmp_path, monkeypatch):
    """A name a letter away from the package's own (or one its package paths hold) is a typo,
    not a ROS package this machine may lack."""
    import shutil

    from marm_setup.validate.runner import validate
    from tests.validate_helpers import generate_marm

    roslaunch = shutil.which("roslaunch")
    if roslaunch is None:
        pytest.skip("roslaunch not on PATH")
    pkg = generate_marm(tmp_path, "ros1")
    launch = pkg / "launch" / "planning_context.launch"
    launch.write_text(
        launch.read_text().replace("$(find marm_moveit_config)", "$(find marm_moveit_confg)", 1)
    )
    monkeypatch.setenv("MARM_SETUP_ROSLAUNCH", roslaunch)
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    checked = validate(pkg, plan=False)
    found = {(f.file, str(f.severity)) for f in checked.findings if f.rule == "ros1.launch"}
    assert ("launch/planning_context.launch", "error") in found
    assert all(severity == "error" for _, severity in found)


@pytest.mark.parametrize(
    ("problem", "missing"),
    [
        # roslaunch runs the description's xacro command; its `$(find pkg): unknown package` is
        # the same want of a package as roslaunch's own ResourceNotFound
        (
            "xacro: /ws/x_support/urdf/x.xacro: $(find x_resources): unknown package 'x_resources' "
            "(no package.xml or folder of that name; known packages: x_support)",
            "x_resources",
        ),
        # roslaunch words a missing package in an <arg> tag's default its own way (xmlloader.py
        # _arg_tag: 'The following package was not found in <arg .../>: pkg'); the tag's text
        # holds ':' and '/', so the package name is only the last word
        (
            "Unable to load file /ws/x_moveit_config/launch/gazebo.launch: The following package was not "
            'found in <arg name="urdf_path" default="$(find x_description)/urdf/x.urdf.xacro"/>: x_description',
            "x_description",
        ),
    ],
)
def test_a_roslaunch_failure_for_want_of_a_package_no_path_holds_is_that_package_missing(problem, missing):
    from marm_setup.validate.consumers import _launch_failure

    unheld = lambda name: "" if name == missing else None  # noqa: E731
    found = _launch_failure("launch/demo.launch", problem, unheld)
    assert (found.severity, f"the folder holding {missing}" in found.hint) == ("warning", True)
    assert _launch_failure("launch/demo.launch", problem, lambda name: None).severity == "error"


def test_a_misspelling_is_one_or_two_letters_from_a_name_the_package_declares():
    from marm_setup.robot import misspelt_package

    own = ["marm_moveit_config", "marm_description"]
    assert misspelt_package("marm_moveit_confg", own) == "marm_moveit_config"
    assert misspelt_package("marm_descriptoin", own) == "marm_description"
    assert misspelt_package("marm_description", own) is None  # declared: no typo
    assert misspelt_package("gazebo_ros", own) is None  # another package, installed elsewhere
    # a long shared prefix is not a typo (difflib's ratio would say 0.8)
    assert (
        misspelt_package("moveit_resources_panda_description", ["moveit_resources_panda_moveit_config"])
        is None
    )


@pytest.mark.parametrize(
    ("body", "included"),
    [
        ('<node pkg="a" type="b" name="c" args="$(arg transmission)_controller"/>', True),
        (
            '<arg name="transmission" default="e"/><node pkg="a" type="b" name="c" args="$(arg transmission)"/>',
            False,
        ),
        ('<group><arg name="t" default="e"/><param name="p" value="$(arg t)"/></group>', False),
        ('<include file="x.launch"><arg name="t" value="$(arg other)"/></include>', True),
        ('<param name="p" value="$(eval arg(\'speed\') * 2)"/>', True),
        ('<rosparam subst_value="true">a: $(arg gain)</rosparam>', True),
        ("<!-- $(arg commented) --><param name='p' value='1'/>", False),
        ('<arg name="fake" default="$(arg fake)"/>', True),  # its own default: only an includer sets it
        ('<param name="p" value="$(arg t)"/><arg name="t" default="e"/>', True),  # used before declared
        ('<arg name="d" default="false"/><arg name="i" default="$(arg d)"/>', False),
    ],
)
def test_a_launch_file_using_an_arg_it_never_declares_is_an_include(tmp_path, body, included):
    """franka's panda_moveit_config ros_controllers.launch uses $(arg transmission) that only
    franka_control.launch (pass_all_args) sets: run alone, roslaunch stops on it."""
    root = build_file_tree(tmp_path, {"a.launch": f"<launch>{body}</launch>"})
    assert _needs_args(parse_launch(root / "a.launch", "a.launch").root) is included


def test_a_xacro_py_command_names_noetic_and_no_temporary_folder():
    """`$(find xacro)/xacro.py` (fanuc_lrmate200i_moveit_config): Noetic's xacro installs no
    xacro.py (ros/xacro noetic-devel CMakeLists.txt installs scripts/xacro only; melodic-devel
    also installed xacro.py), so roslaunch fails there; the message shows the command as the
    package wrote it, not the path of validate's stand-in xacro (a temporary folder, new each run)."""
    from marm_setup.validate.consumers import _launch_failure, _shown

    fallback = "/tmp/marm_ros1_abc123/fallback/xacro"
    problem = (
        "Invalid <param> tag: Cannot load command parameter [robot_description]: no such command "
        f"[['{fallback}/xacro.py', '--inorder', '/ws/x_support/urdf/x.xacro']]"
    )
    shown = _shown(problem, fallback)
    assert fallback not in shown and "'$(find xacro)/xacro.py'" in shown
    found = _launch_failure("launch/demo.launch", shown, lambda name: None)
    assert found.severity == "error" and "Noetic's xacro installs no xacro.py" in found.hint

"""The user's own ROS in the loop: a package's launch files run by the real launcher, starting
nothing, in a child process bounded in time (DESIGN §7).

- ROS 2 (a `ros2` package): a Python that imports launch_ros, launch_xml and rclpy (ROS 2
  sourced) runs `ros2_launch_check.py`: every launch file in that installation's launch
  frontend, every node's command line and parameter file through rcl. Failures are errors
  naming the launch file (`ros2.launch`, `ros2.params`, `demo.real-hardware`).
- ROS 1 (a `ros1` package): `roslaunch --dump-params` on each top-level `launch/*.launch`
  (`ros1.launch`); a file with an arg that has no value is meant to be included and is left out.
Which launcher: $MARM_SETUP_ROS2_PYTHON (ROS 2) and $MARM_SETUP_ROSLAUNCH (ROS 1) when set
(empty: never); else for ROS 2 the interpreter of the `ros2` command on PATH (its `#!` line: the
Python ROS 2 was installed for, whatever venv comes first on PATH), then `python3` on PATH; for
ROS 1 `roslaunch` on PATH (a sourced ROS, or Debian's python3-roslaunch, which needs no
sourcing). Each is used only when it runs (a probe). The summary says what ran on how many files,
and "static rules only (why)" whenever no launch or parameter file was evaluated.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import signal
import subprocess
import sys
import sysconfig
import tempfile
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error, warning
from marm_setup.package import SIMPLE_MANAGER_CLASS
from marm_setup.ros import Target
from marm_setup.safe_yaml import YamlLimitError, load_yaml

if TYPE_CHECKING:
    from lxml import etree

    from marm_setup.package import MoveItPackage
    from marm_setup.robot import RobotModel

ROS2_PYTHON_ENV = "MARM_SETUP_ROS2_PYTHON"
ROSLAUNCH_ENV = "MARM_SETUP_ROSLAUNCH"
TIMEOUT_ENV = "MARM_SETUP_CONSUMER_TIMEOUT"
TIMEOUT = 300.0  # [s] for all the launch files of one package
PROBE = "import launch, launch_ros, launch_xml, rclpy; from importlib.metadata import version; print(version('launch'))"
MESSAGE_CHARS = 600  # of one launcher message in a finding
MISSING_MODULE = "No module named"


@dataclass(frozen=True)
class ConsumerRun:
    """What the real consumer found, and the summary's words for what ran."""

    findings: tuple[Finding, ...]
    ran: str


def _shebang_python(script: str) -> str | None:
    """The interpreter a Python script's `#!` line names (`#!/usr/bin/env python3` looked up on PATH)."""
    try:
        with open(script, "rb") as f:
            first = f.readline(512).decode("utf-8", "replace")
    except OSError:
        return None
    words = first[2:].split() if first.startswith("#!") else []
    if words and os.path.basename(words[0]) == "env":
        words = words[1:]
    return shutil.which(words[0]) if words and "python" in os.path.basename(words[0]) else None


def _probe(argv: list[str]) -> tuple[bool, str]:
    """(whether `argv` exits 0, its stdout or why not)."""
    try:
        done = subprocess.run(argv, capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return False, type(exc).__name__
    if done.returncode == 0:
        return True, done.stdout.strip()
    lines = done.stderr.strip().splitlines()
    return False, lines[-1][:200] if lines else f"exit {done.returncode}"


def _environment(home: str) -> dict[str, str]:
    """The child's environment: the user's, with ROS logs and discovery kept local."""
    return {
        **os.environ,
        "ROS_HOME": home,
        "ROS_LOG_DIR": os.path.join(home, "log"),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "OFF",
        "ROS_LOCALHOST_ONLY": "1",
    }


XACRO_PACKAGE = (
    '<?xml version="1.0"?>\n<package format="2"><name>xacro</name><version>0.0.0</version></package>\n'
)
XACRO_SCRIPT = "#!{python}\nimport sys\nfrom marm_setup.robot.xacro_command import main\nsys.exit(main())\n"


def _xacro_fallback(home: str) -> str:
    """A package folder `xacro` holding an executable `xacro` of marm-setup's own
    (robot/xacro_command.py), for ROS 1 launch files' `command="xacro ..."` and
    `command="$(find xacro)/xacro ..."` when the user's ROS has no xacro (Debian's roslaunch).
    It goes last on PATH and ROS_PACKAGE_PATH: a real xacro wins. Not for ROS 2: its launch
    check puts its own interpreter's (ament-aware) xacro last."""
    folder = os.path.join(home, "fallback", "xacro")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "package.xml"), "w", encoding="utf-8") as out:
        out.write(XACRO_PACKAGE)
    script = os.path.join(folder, "xacro")
    with open(script, "w", encoding="utf-8") as out:
        out.write(XACRO_SCRIPT.format(python=sys.executable))
    os.chmod(script, 0o755)
    return folder


def _ros1_path(fallback: str) -> str:
    """PATH for roslaunch: the user's without marm-setup's own scripts folder, whose `xacro` is
    PyPI's (ROS 2's, needing ament_index: `$(find pkg)` fails in a ROS 1 launch when an activated
    venv puts it first), then the fallback xacro (robot/xacro_command.py) last."""
    own = os.path.realpath(sysconfig.get_path("scripts"))
    kept = [p for p in os.environ.get("PATH", "").split(os.pathsep) if p and os.path.realpath(p) != own]
    return os.pathsep.join([*kept, fallback])


def _run(argv: list[str], env: dict[str, str], seconds: float) -> subprocess.CompletedProcess | None:
    """`argv` in its own process group, killed with every child on timeout (None then)."""
    with subprocess.Popen(
        argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env, start_new_session=True
    ) as proc:
        try:
            out, err = proc.communicate(timeout=seconds)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)  # the launcher and every command it runs
            proc.communicate()
            return None
    return subprocess.CompletedProcess(argv, proc.returncode, out, err)


def ros2_python() -> tuple[str, str] | None:
    """(interpreter, launch version) of a ROS 2 installation, or None."""
    return find_ros2_python()[0]


def find_ros2_python() -> tuple[tuple[str, str] | None, str]:
    """((interpreter, launch version), "") of the first Python that imports launch_ros, launch_xml
    and rclpy (module doc), else (None, why none ran)."""
    given = os.environ.get(ROS2_PYTHON_ENV)
    if given is not None:
        candidates = [given] if given else []
        if not given:
            return None, f"{ROS2_PYTHON_ENV} is empty"
    else:
        ros2 = shutil.which("ros2")
        found = [_shebang_python(ros2) if ros2 else None, shutil.which("python3")]
        candidates = list(dict.fromkeys(c for c in found if c))
    tried = []
    for python in candidates:
        ok, said = _probe([python, "-c", PROBE])
        if ok:
            return (python, said), ""
        tried.append(f"{python}: {said}")
    if not tried:
        return None, "no ros2 or python3 on PATH: source ROS 2"
    why = "no Python with ROS 2's launch_ros and rclpy" + (
        f" (set {ROS2_PYTHON_ENV}, or source ROS 2)" if given is None else ""
    )
    return None, f"{why}; tried {'; '.join(tried)}"


def find_roslaunch() -> tuple[str | None, str]:
    """(roslaunch, "") when $MARM_SETUP_ROSLAUNCH or `roslaunch` on PATH runs, else (None, why not)."""
    given = os.environ.get(ROSLAUNCH_ENV)
    if given == "":
        return None, f"{ROSLAUNCH_ENV} is empty"
    command = given or shutil.which("roslaunch")
    if command is None:
        return (
            None,
            f"no roslaunch on PATH: install ROS 1 (or Debian's python3-roslaunch), or set {ROSLAUNCH_ENV}",
        )
    ok, said = _probe([command, "-h"])
    return (command, "") if ok else (None, f"{command} does not run ({said})")


def run_consumer(pkg: MoveItPackage, robot: RobotModel | None, distro: str | None) -> ConsumerRun:
    """The real consumer for the package's target, when the user has it."""
    seconds = float(os.environ.get(TIMEOUT_ENV, TIMEOUT))
    if pkg.target == Target.ROS2:
        found, why = find_ros2_python()
        if found is None:
            return ConsumerRun((), f"static rules only ({why})")
        return run_ros2(pkg, robot, distro, found, seconds)
    roslaunch, why = find_roslaunch()
    if roslaunch is None:
        return ConsumerRun((), f"static rules only ({why})")
    return run_ros1(pkg, roslaunch, seconds)


def _packages(pkg: MoveItPackage, robot: RobotModel | None) -> dict[str, str]:
    """Packages the launch files may name: every package.xml package on the package paths and
    every package the robot description used."""
    from marm_setup.robot import find_packages

    found = find_packages(pkg.package_paths)
    out = {name: str(found[name]) for name in found}
    for name, path, _ in robot.packages if robot is not None else ():
        out.setdefault(name, path)
    out.pop(pkg.name, None)
    return out


def run_ros2(
    pkg: MoveItPackage, robot: RobotModel | None, distro: str | None, found: tuple[str, str], seconds: float
) -> ConsumerRun:
    python, version = found
    launch_files = ros2_launch_files(pkg)
    script = Path(__file__).with_name("ros2_launch_check.py")
    with tempfile.TemporaryDirectory(prefix="marm_ros2_") as home:
        out = os.path.join(home, "report.json")
        argv = [python, str(script), str(pkg.root), "--out", out]
        argv += [f"--package={n}={p}" for n, p in sorted(_packages(pkg, robot).items())]
        argv += [f"--launch={rel}" for rel in launch_files]
        argv += [f"--arg={name}:={value}" for name, value in pkg.launch_args]
        done = _run(argv, _environment(home), seconds)
        launcher = f"ROS 2 launch {version} and rcl ({python})"
        if done is None:
            return ConsumerRun((_stopped(pkg, seconds),), f"static rules only ({launcher} did not finish)")
        if done.returncode != 0 or not os.path.isfile(out):
            tail = " ".join(done.stderr.strip().splitlines()[-1:]) or f"exit {done.returncode}"
            msg = f"the ROS 2 check could not run ({tail}): the static rules ran"
            ran = f"static rules only ({launcher} could not run the check)"
            return ConsumerRun((error("ros2.consumer", "launch", "", msg[:MESSAGE_CHARS]),), ran)
        with open(out, encoding="utf-8") as f:
            report = json.load(f)
    return ConsumerRun(tuple(ros2_findings(report, distro)), ros2_ran(report, launcher))


def ros2_ran(report: dict, launcher: str) -> str:
    """The summary's words for what the ROS 2 check evaluated: launch files the launcher ran (not
    those importing a module this ROS lacks) and parameter files rcl parsed; "static rules only"
    when that is none."""
    launch = report.get("launch", {})
    unrun = sum(1 for e in launch.values() if any(MISSING_MODULE in m for m in e.get("errors", [])))
    evaluated, params = len(launch) - unrun, len(report.get("params", {}))
    if not evaluated and not params:
        why = f"{unrun} import modules this ROS lacks" if unrun else "the package has none"
        return f"static rules only ({launcher} evaluated no launch or parameter file: {why})"
    said = [f"{_count(evaluated, 'launch file')} evaluated", f"{_count(params, 'parameter file')} parsed"]
    if unrun:
        said.append(f"{_count(unrun, 'launch file')} not runnable here")
    return f"{launcher}: {', '.join(said)}; and the static rules"


def _count(n: int, noun: str) -> str:
    return f"{n} {noun}" if n == 1 else f"{n} {noun}s"


def ros2_launch_files(pkg: MoveItPackage) -> list[str]:
    """The package's ROS 2 launch files: XML (as the package model lists them), Python and YAML."""
    xml = [rel for rel in pkg.launch_files if rel.endswith(".launch.xml")]
    others = [p.relative_to(pkg.root).as_posix() for p in sorted((pkg.root / "launch").glob("*.launch.*"))]
    return sorted({*xml, *(rel for rel in others if rel.endswith((".launch.py", ".launch.yaml")))})


def _stopped(pkg: MoveItPackage, seconds: float) -> Finding:
    msg = f"the launch files did not finish within {seconds:g} s in the real launcher (set {TIMEOUT_ENV})"
    return error("consumer.timeout", "launch", "", msg)


def ros2_findings(report: dict, distro: str | None) -> list[Finding]:
    """Findings from ros2_launch_check.py's report."""
    from marm_setup.robot import ANY_MOCK, MOCK_PLUGINS

    out = []
    mocks = MOCK_PLUGINS.get(distro or "", ANY_MOCK)
    for rel, entry in sorted(report.get("launch", {}).items()):
        for message in entry.get("errors", []) if entry.get("code") else []:
            text = " ".join(message.split())[:MESSAGE_CHARS]
            if MISSING_MODULE in text:  # a Python launch file importing what this ROS lacks
                msg = f"could not be run here (this ROS installation lacks a module it imports): {text}"
                hint = "install it, or source the ROS that has it"
                out.append(warning("ros2.launch-unrun", rel, "launch", msg, hint))
            else:
                out.append(error("ros2.launch", rel, "launch", f"the ROS 2 launcher fails: {text}"))
        hardware: set[tuple[str, str]] = set()
        for node in entry.get("nodes", []):
            if node.get("error"):
                msg = f"rcl refuses the parameters of {node['package']}/{node['executable']}: {node['error']}"
                out.append(error("ros2.params", rel, f"node[{node['name']}]", msg[:MESSAGE_CHARS]))
            if Path(rel).name.startswith("demo") and node.get("executable") in (
                "robot_state_publisher",
                "ros2_control_node",
            ):
                hardware |= {(s, p) for s, p in node.get("ros2_control", {}).items() if p not in mocks}
        for system, plugin in sorted(hardware):
            msg = f"run by the real launcher, the demo starts ros2_control system '{system}' on '{plugin}', not mock hardware"
            out.append(error("demo.real-hardware", rel, f"ros2_control[{system}]", msg))
    for rel, errors in sorted(report.get("params", {}).items()):
        for message in errors:
            key, _, text = message.partition(": ")
            out.append(
                error("ros2.params", rel, key, f"rcl refuses this parameter file: {text}"[:MESSAGE_CHARS])
            )
    return out


def run_ros1(pkg: MoveItPackage, roslaunch: str, seconds: float) -> ConsumerRun:
    """`roslaunch --dump-params` on each top-level launch file that needs no arg (as many at once
    as there are CPUs: each is a Python start-up and xacro, about 1.5 s)."""
    out = []
    evaluated = 0
    with tempfile.TemporaryDirectory(prefix="marm_ros1_") as home:
        xacro = _xacro_fallback(home)
        roots = [
            str(pkg.root),
            *(str(p) for p in pkg.package_paths),
            os.environ.get("ROS_PACKAGE_PATH", ""),
            os.path.dirname(xacro),
        ]
        env = {
            **_environment(home),
            "ROS_PACKAGE_PATH": os.pathsep.join(r for r in roots if r),
            "PATH": _ros1_path(xacro),
        }
        given = frozenset(name for name, _ in pkg.launch_args)
        files = [
            launch.file
            for launch in pkg.launch
            if launch.file.endswith(".launch")
            and launch.root is not None
            and not _needs_args(launch.root, given)
        ]
        args = [f"{name}:={value}" for name, value in pkg.launch_args]
        argvs = [[roslaunch, "--dump-params", str(pkg.path(rel)), *args] for rel in files]
        unheld = _unheld_packages(pkg, os.environ.get("ROS_PACKAGE_PATH", ""))
        with ThreadPoolExecutor(max_workers=max(1, min(len(files), os.cpu_count() or 1))) as pool:
            runs = list(pool.map(lambda argv: _run(argv, env, seconds), argvs))  # each a process
        for rel, done in zip(files, runs, strict=True):
            evaluated += done is not None
            if done is None:
                out.append(_stopped(pkg, seconds))
                continue
            problem = _shown(_dump_problem(done), xacro)
            if problem:
                out.append(_launch_failure(rel, problem, unheld))
            elif not _static_list_namespace(pkg):
                out += dump_list_namespace(rel, done.stdout)
    if not evaluated:
        why = "did not finish" if out else "no top-level launch file runs without args"
        return ConsumerRun(tuple(out), f"static rules only (roslaunch {roslaunch}: {why})")
    ran = f"roslaunch --dump-params ({roslaunch}) on {_count(evaluated, 'top-level launch file')}, and the static rules"
    return ConsumerRun(tuple(out), ran)


MANAGER_KEY = "/moveit_controller_manager"
LIST_KEY = "/controller_list"


def _static_list_namespace(pkg: MoveItPackage) -> bool:
    """The static rule already found the list outside move_group's namespace (one finding)."""
    return pkg.moveit_controllers is not None and bool(pkg.moveit_controllers.elsewhere)


def dump_list_namespace(rel: str, dumped: str) -> list[Finding]:
    """The parameter tree roslaunch printed for `rel`: where it sets the simple controller
    manager (`<ns>/moveit_controller_manager`, move_group's private namespace) but no
    `<ns>/controller_list`, while a `controller_list` lands elsewhere: the same defect as the
    static controller.list-namespace (validate/rules/controller_rules.py check_ros1_namespace),
    which reports it with the line when it can; this one covers what the launch tree holds and the
    static reader does not follow."""
    import yaml

    try:
        tree = load_yaml(dumped)
    except (YamlLimitError, yaml.YAMLError):  # a tree _dump_problem accepted as too large to read back
        return []
    if not isinstance(tree, dict):
        return []
    keys = [str(k) for k in tree]
    lists = [k[: -len(LIST_KEY)] for k in keys if k.endswith(LIST_KEY)]
    out = []
    for key in keys:
        ns = key[: -len(MANAGER_KEY)]
        if not key.endswith(MANAGER_KEY) or SIMPLE_MANAGER_CLASS not in str(tree[key]) or ns in lists:
            continue
        away = [other for other in lists if other != ns]
        if away:
            msg = (
                f"run by roslaunch, this launch sets the simple controller manager in '{ns or '/'}' but "
                f"loads controller_list only at '{away[0]}{LIST_KEY}', not '{ns}{LIST_KEY}': MoveIt logs "
                "'No controller_list specified.' and has no controllers to execute with"
            )
            hint = f"load the controller list file in move_group's namespace ('{ns or '/'}')"
            out.append(error("controller.list-namespace", rel, "roslaunch --dump-params", msg, hint))
    return out


USED_ARG = re.compile(
    r"\$\(arg\s+([^\s()]+)\s*\)|\barg\(\s*['\"]([^'\"]+)['\"]\s*\)"
)  # $(arg x), $(eval arg('x'))


def _needs_args(root: etree._Element, given: frozenset[str] = frozenset()) -> bool:
    """The file is meant to be included, or needs args the user did not give (`given`, the
    --launch-arg names): it declares an arg with neither default nor value, or uses an arg it
    never declares (`$(arg x)`, `arg('x')` in `$(eval)`), which only an includer passing its own
    (`pass_all_args`) sets. roslaunch run on it alone stops at either (xmlloader.py:
    ArgException, "requires the 'x' arg to be set"; with --dump-params its handler fails first on
    a loader attribute --dump-params never sets, ignore_unset_args). roslaunch reads the tags in
    order (xmlloader.py `_recurse_load`) and resolves an arg's attributes before declaring it
    (`_arg_tag`: opt_attrs, then context.add_arg), so an arg used before its declaration, or in
    its own default (`<arg name="x" default="$(arg x)"/>`), is one only an includer sets too."""
    required = {
        a.get("name") for a in root.findall("arg") if a.get("default") is None and a.get("value") is None
    }
    if required - given:
        return True
    declared: set[str | None] = set(given)
    for element in (e for e in root.iter() if isinstance(e.tag, str)):
        texts = (*element.attrib.values(), element.text or "")
        if {m.group(1) or m.group(2) for text in texts for m in USED_ARG.finditer(text)} - declared:
            return True
        if element.tag == "arg" and _parent_tag(element) != "include":
            declared.add(element.get("name"))
    return False


def _parent_tag(element: etree._Element) -> str | None:
    parent = element.getparent()
    return None if parent is None else str(parent.tag)


MISSING_RESOURCE = re.compile(
    r"(?:ResourceNotFound|[Rr]esource not found|Unable to load file [^:]+): ([A-Za-z][\w]*)$"
    r"|\$\(find ([A-Za-z]\w*)\): unknown package '\2'"  # a robot_description command's xacro
    r"|The following package was not found in [\s\S]*: ([A-Za-z]\w*)$"  # an <arg> default (xmlloader.py _arg_tag)
)


def _shown(problem: str, fallback: str) -> str:
    """roslaunch's failure as the user reads it: the stand-in xacro package's folder (a temporary
    folder, new each run: _xacro_fallback) shown as `$(find xacro)`."""
    return problem.replace(fallback, "$(find xacro)")


XACRO_PY_HINT = (
    "Noetic's xacro installs no xacro.py (ros/xacro noetic-devel CMakeLists.txt installs scripts/xacro "
    "only; melodic-devel also installed xacro.py): call $(find xacro)/xacro"
)


def _launch_failure(rel: str, problem: str, unheld: Callable[[str], str | None]) -> Finding:
    """A roslaunch failure: an error, but a warning when it only lacks a package validate cannot
    tell is missing from the user's machine (`unheld` says why; the user's environment, not the
    package)."""
    msg = f"roslaunch fails: {problem}"[:MESSAGE_CHARS]
    missing = MISSING_RESOURCE.search(problem)
    name = None if missing is None else missing.group(1) or missing.group(2) or missing.group(3)
    why = None if name is None else unheld(name)
    if name is None or why is None:
        hint = XACRO_PY_HINT if "no such command" in problem and "xacro.py" in problem else ""
        return error("ros1.launch", rel, "launch", msg, hint)
    hint = f"pass --package-path DIR (the folder holding {name}){why}"
    return warning("ros1.launch", rel, "launch", msg, hint)


def _unheld_packages(pkg: MoveItPackage, ros_package_path: str) -> Callable[[str], str | None]:
    """Why a package roslaunch lacks is no fault of the package ('' or the words to add to the
    hint), else None: the package the robot description lives in, which no package path holds
    (package.read's urdf/srdf.package-missing names it); or any package while no ROS is sourced
    (ROS_PACKAGE_PATH unset), when roslaunch here sees only the package paths given and cannot
    tell a ROS package this machine lacks from a wrong name: roslaunch's $(find) looks only on
    ROS_PACKAGE_PATH (ros/ros_comm tools/roslaunch/src/roslaunch/substitution_args.py _find
    l.141 at 845f746, through rospkg.RosPack), and MoveIt's own Setup Assistant gazebo.launch
    includes $(find gazebo_ros) while its package.xml leaves the Gazebo packages out on purpose
    (moveit/moveit moveit_setup_assistant/templates/moveit_config_pkg_template/launch/gazebo.launch
    l.11 and package.xml.template l.32-35 at noetic-devel 5555c3d)."""
    from marm_setup.robot import misspelt_package

    names = {f.location.name for f in pkg.problems if f.rule.endswith(".package-missing")}
    sourced = any(ros_package_path.split(os.pathsep))
    at_hand = _packages_at_hand(pkg)

    def why(name: str) -> str | None:
        if misspelt_package(name, at_hand) is not None:
            return None
        if name in names:
            return ""
        if not sourced:
            return (
                ", or source the ROS installation that has it: no ROS is sourced (ROS_PACKAGE_PATH is "
                "unset), so roslaunch here finds only the package paths given"
            )
        return None

    return why


def _packages_at_hand(pkg: MoveItPackage) -> list[str]:
    """The package's own name and the packages its package.xml depends on: a name roslaunch
    lacks that nearly spells one of them is a misspelling (an error), whatever ROS is sourced.
    (Not every package the paths hold: a vendor repository's ur5_description would make its
    ur5e_description, installed elsewhere, look like a typo.)"""
    return sorted(pkg.package_xml.names) if pkg.package_xml is not None else []


def _dump_problem(done: subprocess.CompletedProcess) -> str:
    """Why a --dump-params run failed ('' when it printed a parameter tree)."""
    import yaml

    if done.returncode == 0:  # a parameter tree: every key a global name (roslaunch prints
        try:  # some failures to stdout and exits 0, e.g. "Unable to load file ...")
            tree = load_yaml(done.stdout)
            if isinstance(tree, dict) and all(str(key).startswith("/") for key in tree):
                return ""
        except YamlLimitError:
            return ""  # a tree too large to read back: roslaunch printed parameters, not a failure
        except yaml.YAMLError:
            pass
    noise = ("ROS path [", "The traceback for the exception", "... logging to", "Checking log directory")
    lines = [line.strip() for line in (done.stderr + "\n" + done.stdout).splitlines() if line.strip()]
    return " ".join([line for line in lines if not line.startswith(noise)][:3]) or f"exit {done.returncode}"

"""Run a ROS 2 package's launch files in the installed ROS 2 launch frontend, starting nothing.

This file is a script for the ROS 2 Python interpreter (ROS sourced: launch, launch_ros and
rclpy import); marm-setup's validate runs it in a bounded child process (validate/consumers.py)
and never imports it. Standard library plus what ROS 2 itself ships.

usage: python3 ros2_launch_check.py PKG_DIR --out REPORT.json [--package NAME=DIR ...] [--launch REL ...]

1. A temporary install prefix holds the package as ament_cmake installs it (what CMakeLists.txt's
   install(... DESTINATION share/${PROJECT_NAME}) rules name, else the whole folder) and the
   description packages, first on AMENT_PREFIX_PATH; a ROS package the environment lacks
   (move_group, rviz2, ...) gets an executable that is never run, so its node is still checked.
2. Each launch file runs in a LaunchService whose processes are never started: every node's
   command line is resolved ($(command ...) runs, as ROS runs it) and recorded.
3. Each node's command line goes to rcl (rclpy.init + a node that declares every override):
   the parameters exactly as that node would get them, or rcl's error.
4. Every YAML file holding ros__parameters is parsed by rcl for each node name it holds.
The report (JSON) names, per launch file, its failure and each node's error and ros2_control plugins.
"""

from __future__ import annotations

import argparse
import glob
import json
import logging
import os
import re
import shutil
import sys
import tempfile
import xml.etree.ElementTree as ET
from typing import Any

# Executables of ROS packages a MoveIt package starts, for packages the environment lacks.
ROS_EXECUTABLES = {
    "moveit_ros_move_group": ("move_group",),
    "robot_state_publisher": ("robot_state_publisher",),
    "tf2_ros": ("static_transform_publisher",),
    "controller_manager": ("ros2_control_node", "spawner", "unspawner"),
    "rviz2": ("rviz2",),
    "joint_state_publisher": ("joint_state_publisher",),
    "joint_state_publisher_gui": ("joint_state_publisher_gui",),
    "moveit_ros_warehouse": ("moveit_warehouse_services",),
    "moveit_servo": ("servo_node", "servo_node_main"),
}
# The node name an executable takes when the launch file gives none (its parameter file key).
DEFAULT_NODE_NAMES = {"ros2_control_node": "controller_manager", "rviz2": "rviz"}
INSTALL_RULE = re.compile(
    r"install\s*\(\s*(?:DIRECTORY|FILES)\s+([^)]*?)\s+DESTINATION\s+share/\$\{PROJECT_NAME\}\s*\)"
)


def installed_entries(pkg_dir: str) -> list[str] | None:
    """Top-level entries ament_cmake installs into share/<pkg>, or None (no CMakeLists: all)."""
    try:
        with open(os.path.join(pkg_dir, "CMakeLists.txt"), encoding="utf-8") as f:
            text = f.read()
    except OSError:
        return None
    entries = {"package.xml"}
    for body in INSTALL_RULE.findall(text):
        entries.update(word.rstrip("/") for word in body.split())
    return sorted(entries)


def package_name(pkg_dir: str) -> str:
    return (ET.parse(os.path.join(pkg_dir, "package.xml")).getroot().findtext("name") or "").strip()


def make_prefix(pkg_dir: str, name: str, packages: dict[str, str]) -> tuple[str, list[str]]:
    """A temporary install prefix with the package, the description packages and stubs."""
    prefix = os.path.join(tempfile.mkdtemp(prefix="marm_ros2_check_"), "install")
    index = os.path.join(prefix, "share", "ament_index", "resource_index", "packages")
    os.makedirs(index)
    share = os.path.join(prefix, "share")
    entries = installed_entries(pkg_dir)
    if entries is None:
        os.symlink(pkg_dir, os.path.join(share, name))
    else:
        os.makedirs(os.path.join(share, name))
        for entry in entries:
            if os.path.exists(os.path.join(pkg_dir, entry)):
                os.symlink(os.path.join(pkg_dir, entry), os.path.join(share, name, entry))
    open(os.path.join(index, name), "w").close()
    for other, folder in packages.items():
        if other != name and not os.path.exists(os.path.join(share, other)):
            os.symlink(folder, os.path.join(share, other))
            open(os.path.join(index, other), "w").close()
    return prefix, add_stubs(prefix, index, set(packages) | {name})


def add_stubs(prefix: str, index: str, given: set[str]) -> list[str]:
    """Executables (never run) for the ROS packages the environment lacks; their names."""
    from ament_index_python.packages import PackageNotFoundError, get_package_prefix

    stubbed = []
    for package, executables in sorted(ROS_EXECUTABLES.items()):
        if package in given:
            continue
        try:
            get_package_prefix(package)
            continue
        except (PackageNotFoundError, ValueError, OSError):  # OSError: AMENT_PREFIX_PATH unset
            stubbed.append(package)
        open(os.path.join(index, package), "w").close()
        os.makedirs(os.path.join(prefix, "share", package), exist_ok=True)
        os.makedirs(os.path.join(prefix, "lib", package), exist_ok=True)
        for exe in executables:
            path = os.path.join(prefix, "lib", package, exe)
            with open(path, "w") as f:
                f.write("#!/bin/sh\nexit 1\n")
            os.chmod(path, 0o755)
    return stubbed


def rcl_parameters(argv: list[str], node_name: str) -> tuple[tuple[dict, dict] | None, str | None]:
    """(parameter names -> type names, None) a node named node_name started with argv gets from
    rcl, or (None, rcl's error)."""
    import rclpy

    context = rclpy.Context()
    try:
        rclpy.init(args=argv, context=context)
    except Exception as exc:  # rcl's parse errors
        return None, f"{type(exc).__name__}: {exc}"
    try:
        node = rclpy.create_node(
            node_name,
            context=context,
            start_parameter_services=False,
            enable_rosout=False,
            automatically_declare_parameters_from_overrides=True,
        )
        params = {n: p.type_.name for n, p in node._parameters.items()}
        values = {n: p.value for n, p in node._parameters.items() if n == "robot_description"}
        node.destroy_node()
        return (params, values), None
    except Exception as exc:  # a value rcl could not give (an empty map or list), a bad type
        return None, f"{type(exc).__name__}: {exc}"
    finally:
        rclpy.shutdown(context=context)


def ros2_control_plugins(urdf: str) -> dict[str, str]:
    """{system name: hardware plugin} of a URDF string (ros2_control elements under <robot>)."""
    try:
        root = ET.fromstring(urdf)
    except ET.ParseError as exc:
        return {"<URDF does not parse>": str(exc)}
    return {
        s.get("name", ""): (s.findtext("hardware/plugin") or "").strip() for s in root.findall("ros2_control")
    }


def run_launch(path: str, arguments: list[tuple[str, str]] | None = None) -> tuple[int, list[str], list]:
    """(return code, error messages, node actions) of one launch file given `arguments` (as
    `ros2 launch` includes it with them), nothing started."""
    import launch
    import launch.actions
    from launch.launch_description_sources import AnyLaunchDescriptionSource

    started, messages = [], []

    def record(self: Any, context: Any) -> None:
        self.prepare(context)
        started.append(self)

    def keep(entry: logging.LogRecord) -> bool:
        """A filter on launch's screen handler: every record passes, errors are kept."""
        if entry.levelno >= logging.ERROR:
            messages.append(entry.getMessage())
        return True

    launch.actions.ExecuteLocal.execute = record
    screen = launch.logging.launch_config.get_screen_handler()
    screen.addFilter(keep)
    service = launch.LaunchService(argv=[])
    service.include_launch_description(
        launch.LaunchDescription(
            [
                launch.actions.IncludeLaunchDescription(
                    AnyLaunchDescriptionSource(path), launch_arguments=list(arguments or [])
                )
            ]
        )
    )
    try:
        code = service.run()
    except Exception as exc:
        code, messages = 1, [*messages, f"{type(exc).__name__}: {exc}"]
    screen.removeFilter(keep)
    return code, sorted(set(messages), key=messages.index), started


def describe_node(action: Any) -> dict[str, Any]:
    """The node's package, executable, name, rcl's verdict on its parameters, ros2_control plugins."""
    cmd = list(action.process_details["cmd"])
    exe = os.path.basename(cmd[0])
    node = {"package": os.path.basename(os.path.dirname(cmd[0])), "executable": exe}
    named = [c[len("__node:=") :] for c in cmd if c.startswith("__node:=")]
    name = named[-1] if named else DEFAULT_NODE_NAMES.get(exe, exe)
    node["name"] = name
    result, problem = rcl_parameters(cmd, name)
    node["error"] = problem
    if result is not None:
        params, values = result
        node["parameters"] = len(params)
        if isinstance(values.get("robot_description"), str):
            node["ros2_control"] = ros2_control_plugins(values["robot_description"])
    temporary = [cmd[i + 1] for i, c in enumerate(cmd[:-1]) if c == "--params-file"]
    for path in temporary:
        if os.path.basename(path).startswith("launch_params_"):
            os.remove(path)
    return node


def params_file_nodes(data: Any, prefix: str = "") -> list[str]:
    """Node names a parameter file gives (`/**` and wildcards as one node 'node')."""
    names = []
    for key, value in (data or {}).items() if isinstance(data, dict) else ():
        if isinstance(value, dict) and "ros__parameters" not in value:
            names += params_file_nodes(value, f"{prefix}{key}/")
        elif isinstance(value, dict):
            names.append(f"{prefix}{key}".strip("/"))
    return names


def check_params_file(path: str) -> list[str]:
    """rcl's errors for each node a parameter file names."""
    import yaml

    try:
        with open(path, encoding="utf-8") as f:
            data = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as exc:
        return [f"YAML: {exc}"]
    errors = []
    for key in params_file_nodes(data):
        namespace, _, base = key.rpartition("/")
        base = "node" if "*" in base else base
        argv = ["check", "--ros-args", "--params-file", path]
        if namespace and "*" not in namespace:
            argv += ["-r", f"__ns:=/{namespace}"]
        _, problem = rcl_parameters(argv, base)
        if problem:
            errors.append(f"{key}: {problem}")
    return errors


def versions() -> dict[str, str]:
    from importlib.metadata import PackageNotFoundError, version

    out = {}
    for name in ("launch", "launch_ros", "rclpy"):
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = "?"
    return out


def check(
    pkg_dir: str,
    packages: dict[str, str],
    launch_files: list[str],
    arguments: list[tuple[str, str]] | None = None,
) -> dict[str, Any]:
    name = package_name(pkg_dir)
    prefix, stubbed = make_prefix(pkg_dir, name, packages)
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    if os.path.isdir(os.path.join(sys.prefix, "share", "ament_index")) and sys.prefix not in prefixes:
        prefixes.append(sys.prefix)  # ROS 2 Python packages installed into this interpreter's prefix
    os.environ["AMENT_PREFIX_PATH"] = os.pathsep.join([prefix, *prefixes])
    # ROS 2 executables (xacro) next to this interpreter, after whatever PATH holds
    os.environ["PATH"] = os.pathsep.join([os.environ.get("PATH", ""), os.path.dirname(sys.executable)])
    launched: dict[str, Any] = {}
    params: dict[str, list[str]] = {}
    try:
        for rel in launch_files:
            code, messages, started = run_launch(os.path.join(pkg_dir, rel), arguments)
            launched[rel] = {
                "code": code,
                "errors": [m.replace(prefix, "<install>") for m in messages],
                "nodes": [describe_node(a) for a in started if hasattr(a, "node_package")],
            }
        for path in sorted(glob.glob(os.path.join(pkg_dir, "**", "*.yaml"), recursive=True)):
            with open(path, encoding="utf-8", errors="replace") as f:
                if "ros__parameters" in f.read():
                    params[os.path.relpath(path, pkg_dir)] = check_params_file(path)
    finally:
        shutil.rmtree(os.path.dirname(prefix), ignore_errors=True)
    return {"versions": versions(), "stubbed": stubbed, "launch": launched, "params": params}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("pkg_dir")
    parser.add_argument("--out", required=True)
    parser.add_argument(
        "--package", action="append", default=[], help="NAME=DIR of a package the launch files use"
    )
    parser.add_argument("--launch", action="append", default=[], help="launch file, relative to PKG_DIR")
    parser.add_argument("--arg", action="append", default=[], help="NAME:=VALUE launch argument")
    args = parser.parse_args(argv)
    os.dup2(2, 1)  # launch, rcl and xacro print to stdout: keep it for nothing
    packages = dict(p.split("=", 1) for p in args.package)
    arguments = [(name, value) for name, _, value in (a.partition(":=") for a in args.arg)]
    report = check(os.path.abspath(args.pkg_dir), packages, args.launch, arguments)
    with open(args.out, "w", encoding="utf-8") as f:
        json.dump(report, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())

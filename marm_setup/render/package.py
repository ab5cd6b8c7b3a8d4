"""render_package: a SetupModel and its robot -> every file of the MoveIt config package, in memory.

Each output file has one template at a mirrored path (`templates/<target>/<path>.j2`, or
`templates/common/...` for files both targets share); `robot` in a template's file name stands for
the robot's name in the output path.
"""

from __future__ import annotations

import os
from pathlib import Path

from marm_setup.errors import InputError
from marm_setup.names import did_you_mean, with_hint
from marm_setup.render.context import build_context
from marm_setup.robot import RobotModel, package_name
from marm_setup.ros import TARGETS, Target
from marm_setup.setup import SetupModel, dump_setup
from marm_setup.templating import RenderedFile, render_template

COMMON_FILES = ("config/robot.srdf", ".setup_assistant")
ROS1_FILES = (
    "CMakeLists.txt",
    "package.xml",
    "config/arbotix.yaml",
    "config/controllers.yaml",
    "config/fake_controllers.yaml",
    "config/joint_limits.yaml",
    "config/kinematics.yaml",
    "launch/arbotix.launch",
    "launch/arbotix_moveit.launch",
    "launch/default_warehouse_db.launch",
    "launch/demo.launch",
    "launch/fake_moveit_controller_manager.launch.xml",
    "launch/move_group.launch",
    "launch/moveit.rviz",
    "launch/moveit_rviz.launch",
    "launch/planning_context.launch",
    "launch/planning_pipeline.launch.xml",
    "launch/ros_control_moveit_controller_manager.launch.xml",
    "launch/simple_moveit_controller_manager.launch.xml",
    "launch/trajectory_execution.launch.xml",
    "launch/warehouse.launch",
    "launch/warehouse_settings.launch.xml",
    "scripts/gripper_controller.py",
    "scripts/trajectory_demo.py",
)
ROS2_FILES = (
    "CMakeLists.txt",
    "package.xml",
    "config/initial_positions.yaml",
    "config/moveit.rviz",
    "config/moveit.yaml",
    "config/robot.ros2_control.xacro",
    "config/robot.urdf.xacro",
    "config/ros2_controllers.yaml",
    "launch/demo.launch.xml",
    "launch/move_group.launch.xml",
)
TARGET_FILES = {"ros1": ROS1_FILES, "ros2": ROS2_FILES}
# Files only a package whose setup names the driver gets (ros1).
DRIVER_FILES = {
    "arbotix": (
        "config/arbotix.yaml",
        "launch/arbotix.launch",
        "launch/arbotix_moveit.launch",
        "scripts/gripper_controller.py",
    )
}
SETUP_FILE = "marm_setup.yaml"


def output_path(template_path: str, robot_name: str) -> str:
    """`config/robot.srdf` -> `config/marm.srdf` (only the file name's `robot` part is replaced)."""
    folder, _, name = template_path.rpartition("/")
    if name.startswith("robot.") or name.startswith("robot_"):
        name = robot_name + name[len("robot") :]
    return f"{folder}/{name}" if folder else name


def target_templates(target: Target, driver: str | None = None) -> list[tuple[str, str]]:
    """(template name, template path in the package) for one target; common files first.
    Driver files (`arbotix.yaml`, ...) only for the driver named, and only for ros1."""
    if target not in TARGET_FILES:
        raise InputError(
            with_hint(f"unknown target '{target}'", did_you_mean(target, TARGETS)), element="target"
        )
    other_drivers = {
        p for d, files in DRIVER_FILES.items() if d != driver or target != Target.ROS1 for p in files
    }
    common = [(f"common/{p}.j2", p) for p in COMMON_FILES]
    return common + [(f"{target}/{p}.j2", p) for p in TARGET_FILES[target] if p not in other_drivers]


def pipeline_templates(model: SetupModel) -> list[tuple[str, str, dict]]:
    """(template, path, extra context) of the files the setup's planning pipelines add (ros1: one
    launch file per pipeline, ompl_planning.yaml, chomp_planning.yaml, Pilz's cartesian_limits.yaml;
    ros2 writes every pipeline into moveit.yaml)."""
    from marm_setup.moveit_params import PIPELINES

    if model.target != Target.ROS1:
        return []
    out = []
    configs = {"ompl": "ompl_planning.yaml", "chomp": "chomp_planning.yaml", "pilz": "cartesian_limits.yaml"}
    for name in model.planning_pipelines:
        pipeline = PIPELINES[name]
        launch = f"launch/{pipeline.namespace}_planning_pipeline.launch.xml"
        out.append((f"ros1/launch/{name}_planning_pipeline.launch.xml.j2", launch, {"pipeline": pipeline}))
        if name in configs:
            out.append((f"ros1/config/{configs[name]}.j2", f"config/{configs[name]}", {}))
    return out


def servo_and_sensor_templates(target: Target, context: dict) -> list[tuple[str, str, dict]]:
    """(template, path, extra context) of the servo files (a config per servo group and one launch
    file) and the perception files (ros1: the Setup Assistant's sensors_3d.yaml and sensor
    manager launch files; ros2: sensors_3d.yaml, loaded by move_group)."""
    out = [
        (f"{target}/config/servo.yaml.j2", f"config/{plan.group}_servo.yaml", {"servo": plan})
        for plan in context["servos"]
    ]
    if context["servos"]:
        launch = "launch/servo.launch" if target == Target.ROS1 else "launch/servo.launch.xml"
        out.append((f"{target}/{launch}.j2", launch, {}))
    if context["perception"] is not None:
        out.append((f"{target}/config/sensors_3d.yaml.j2", "config/sensors_3d.yaml", {}))
        if target == Target.ROS1:
            for launch in (
                "launch/sensor_manager.launch.xml",
                "launch/robot_moveit_sensor_manager.launch.xml",
            ):
                out.append((f"ros1/{launch}.j2", launch, {}))
    return out


def description_package(urdf: Path) -> tuple[str, str] | None:
    """(package, path inside it) of the ROS package holding the URDF file, if any."""
    urdf = urdf.resolve()
    for folder in list(urdf.parents)[:6]:
        name = package_name(folder)
        if name:
            return name, urdf.relative_to(folder).as_posix()
    return None


def robot_reference(urdf: Path, out: Path, package_paths: list[str]) -> tuple[str, list[str]]:
    """(robot.urdf, robot.package_paths) for a package at `out`, so it can move: `package://pkg/path`
    when the URDF lives in a ROS package (found again by name next to the package, in the
    environment or in the package paths, which then also hold the folder around that package),
    else the URDF's path relative to `out`."""
    described = description_package(urdf)
    if described is None:
        return _relative(urdf, out), package_paths
    home = urdf.resolve()
    for _ in Path(described[1]).parts:
        home = home.parent
    around = _relative(home.parent, out)
    return f"package://{described[0]}/{described[1]}", [
        *package_paths,
        *([around] if around not in package_paths else []),
    ]


def _relative(path: Path, base: Path) -> str:
    return Path(os.path.relpath(path.resolve(), base.resolve())).as_posix()


def render_package(
    model: SetupModel, robot: RobotModel, *, description: tuple[str, str] | None = None
) -> list[RenderedFile]:
    """Every file of the package for `model.target`, sorted by path.

    `description` is (package, path inside it) of the URDF for launch files; by default it is
    looked up from the folder of `robot.source` (a package.xml above it), else the URDF is
    referenced relative to our own package as `model.robot.urdf` gives it.
    """
    if description is None and robot.source:
        description = description_package(Path(robot.source))
    context = build_context(model, robot, description)
    files = [RenderedFile(SETUP_FILE, dump_setup(model))]
    templates: list[tuple[str, str, dict]] = [
        (t, p, {}) for t, p in target_templates(model.target, model.driver)
    ]
    templates += pipeline_templates(model) + servo_and_sensor_templates(model.target, context)
    templates += hardware_templates(model, context)
    for template, path, extra in templates:
        content = render_template(template, target=model.target, **context, **extra)
        files.append(RenderedFile(output_path(path, model.robot_name), content))
    return sorted(files + description_copy(context, robot), key=lambda f: f.path)


def hardware_templates(model: SetupModel, context: dict) -> list[tuple[str, str, dict]]:
    """The script that puts the description's own ros2_control systems on mock hardware, for
    a ros2 package whose description has no proven switch (render/hardware.py)."""
    from marm_setup.render.hardware import MOCK_SCRIPT

    if model.target != Target.ROS2 or context["description_hardware"].mode != "replace":
        return []
    return [(f"ros2/{MOCK_SCRIPT}.j2", MOCK_SCRIPT, {})]


def description_copy(context: dict, robot: RobotModel) -> list[RenderedFile]:
    """The URDF (a xacro expanded with the setup's args) copied into the package when it lives
    in no ROS package: launch files can reach nothing outside share/<pkg> once it is installed."""
    ref = context["description"]
    if ref.package is not None:
        return []
    text = robot.urdf_xml if robot.urdf_xml.endswith("\n") else robot.urdf_xml + "\n"
    return [RenderedFile(ref.path, text)]

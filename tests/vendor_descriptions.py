"""Small robot description packages that carry their own `<ros2_control>`, each switched to mock
hardware the way one vendor's real description does it (read from their repositories: Franka
franka_description, ROBOTIS open_manipulator_description, ABB abb_ros2 (PickNik), Universal
Robots' ROS 2 description/driver, Kinova ros2_kortex with a Robotiq gripper), plus two with no
usable switch. The robot is a synthetic 6-joint arm with a two-finger gripper (tests/synthetic_robots.py).

`write_vendor_descriptions(root)` writes one package per style under `root` and returns them.
`modes` is what the generated package does with `use_mock_hardware:=true`, per distro:
`switch` (the vendor's own arg, proven), `replace` (the launch files replace the hardware).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from tests.synthetic_robots import arm

ARM_JOINTS = [f"joint{i}" for i in range(1, 7)]
FINGERS = ["hand_finger_left_joint", "hand_finger_right_joint"]


@dataclass(frozen=True)
class VendorDescription:
    name: str
    urdf: Path
    root: Path  # the folder holding the package (a --package-path)
    xacro_args: tuple[str, ...]  # NAME:=VALUE init takes
    modes: dict[str, str]  # distro -> switch | replace
    real_plugins: frozenset[str]  # the hardware use_mock_hardware:=false gives
    switch: str | None = None


def _described(
    name: str,
    urdf: Path,
    root: Path,
    real: frozenset[str],
    switch: str | None = None,
    args: tuple[str, ...] = (),
    modes: dict[str, str] | None = None,
) -> VendorDescription:
    """A style's description: the same mode on both distros unless `modes` says otherwise."""
    mode = "switch" if switch else "replace"
    return VendorDescription(name, urdf, root, args, modes or {"humble": mode, "jazzy": mode}, real, switch)


def _joints_xml(joints: list[str], fake_mimic: bool = False) -> str:
    out = []
    for joint in joints:
        state = '<state_interface name="position"><param name="initial_value">0.0</param></state_interface>'
        out.append(
            f'<joint name="{joint}"><command_interface name="position"/>{state}<state_interface name="velocity"/></joint>'
        )
    if fake_mimic:  # Robotiq's mock system also lists the mimic finger (Kinova's use_fake_hardware)
        out.append(f'<joint name="{FINGERS[1]}"><state_interface name="position"/></joint>')
    return "\n      ".join(out)


def _robot_body() -> str:
    parts = [
        '<link name="base_link"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>'
    ]
    parts += arm(ARM_JOINTS, "", "base_link", "0 0 0.05", "hand_")
    return "\n  ".join(parts)


def _package(root: Path, name: str, files: dict[str, str]) -> Path:
    folder = root / f"{name}_description"
    for rel, text in files.items():
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        (folder / rel).write_text(text)
    (folder / "package.xml").write_text(
        f"<package format='3'><name>{name}_description</name><version>0.1.0</version>"
        "<description>test</description><maintainer email='a@b.c'>t</maintainer><license>BSD</license></package>"
    )
    return folder


def _top(name: str, args: dict[str, str], system: str, instance: str) -> str:
    """The robot's top-level xacro: its args, the arm, its ros2_control macro and its call."""
    declared = "\n  ".join(f'<xacro:arg name="{k}" default="{v}"/>' for k, v in args.items())
    return (
        f'<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="{name}">\n  {declared}\n'
        f"  {_robot_body()}\n  {system}\n  {instance}\n</robot>\n"
    )


def franka_style(root: Path) -> VendorDescription:
    """franka_description: ros2_control only with ros2_control:=true; use_fake_hardware gives
    fake_components/GenericSystem (Humble's, gone in Jazzy); gazebo an Ignition system."""
    system = f"""<xacro:macro name="franka_arm_ros2_control" params="use_fake_hardware:=^|false gazebo:=^|false">
    <ros2_control name="FrankaHardwareInterface" type="system">
      <hardware>
        <param name="arm_id">fr3</param>
        <xacro:if value="${{use_fake_hardware}}">
          <plugin>fake_components/GenericSystem</plugin>
          <param name="fake_sensor_commands">$(arg fake_sensor_commands)</param>
        </xacro:if>
        <xacro:if value="${{gazebo}}"><plugin>franka_ign_ros2_control/IgnitionSystem</plugin></xacro:if>
        <xacro:if value="${{use_fake_hardware == 0 and gazebo == 0}}">
          <plugin>franka_hardware/FrankaHardwareInterface</plugin>
          <param name="robot_ip">$(arg robot_ip)</param>
        </xacro:if>
      </hardware>
      {_joints_xml(ARM_JOINTS)}
    </ros2_control>
  </xacro:macro>"""
    instance = """<xacro:if value="$(arg ros2_control)">
    <xacro:franka_arm_ros2_control use_fake_hardware="$(arg use_fake_hardware)" gazebo="$(arg gazebo)"/>
  </xacro:if>"""
    args = {
        "ros2_control": "false",
        "robot_ip": "",
        "use_fake_hardware": "false",
        "fake_sensor_commands": "false",
        "gazebo": "false",
    }
    folder = _package(root, "franka_style", {"robots/fr3.urdf.xacro": _top("fr3", args, system, instance)})
    return _described(
        "franka_style",
        folder / "robots" / "fr3.urdf.xacro",
        root,
        frozenset({"franka_hardware/FrankaHardwareInterface"}),
        args=("ros2_control:=true",),
        switch="use_fake_hardware",
        modes={"humble": "switch", "jazzy": "replace"},
    )


def robotis_style(root: Path) -> VendorDescription:
    """open_manipulator_description: use_sim (Gazebo) outside, use_mock_hardware inside, the
    DYNAMIXEL driver otherwise; the macro lives in its own ros2_control file."""
    macro = f"""<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="omx_system" params="name port_name:=^|/dev/ttyUSB0 use_sim:=^|false use_mock_hardware:=^|false">
    <ros2_control name="${{name}}" type="system">
      <xacro:if value="${{use_sim}}"><hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware></xacro:if>
      <xacro:unless value="${{use_sim}}">
        <hardware>
          <xacro:if value="${{use_mock_hardware}}">
            <plugin>mock_components/GenericSystem</plugin>
            <param name="mock_sensor_commands">$(arg mock_sensor_commands)</param>
          </xacro:if>
          <xacro:unless value="${{use_mock_hardware}}">
            <plugin>dynamixel_hardware_interface/DynamixelHardware</plugin>
            <param name="port_name">${{port_name}}</param>
          </xacro:unless>
        </hardware>
      </xacro:unless>
      {_joints_xml(ARM_JOINTS + FINGERS[:1])}
    </ros2_control>
  </xacro:macro>
</robot>
"""
    include = (
        '<xacro:include filename="$(find robotis_style_description)/ros2_control/omx.ros2_control.xacro"/>'
    )
    instance = '<xacro:omx_system name="OpenManipulatorXSystem" use_sim="$(arg use_sim)" use_mock_hardware="$(arg use_mock_hardware)" port_name="$(arg port_name)"/>'
    args = {
        "use_sim": "false",
        "use_mock_hardware": "false",
        "mock_sensor_commands": "false",
        "port_name": "/dev/ttyUSB0",
    }
    files = {
        "urdf/omx.urdf.xacro": _top("omx", args, include, instance),
        "ros2_control/omx.ros2_control.xacro": macro,
    }
    folder = _package(root, "robotis_style", files)
    return _described(
        "robotis_style",
        folder / "urdf" / "omx.urdf.xacro",
        root,
        frozenset({"dynamixel_hardware_interface/DynamixelHardware"}),
        switch="use_mock_hardware",
    )


def abb_style(root: Path) -> VendorDescription:
    """abb_ros2: use_fake_hardware defaults to TRUE (mock out of the box), a property copies
    the arg, and the plugin is chosen by xacro:if / xacro:unless with the RWS parameters."""
    system = f"""<xacro:macro name="abb_ros2_control" params="name use_fake_hardware:=true rws_ip">
    <ros2_control name="${{name}}" type="system">
      <hardware>
        <xacro:if value="${{use_fake_hardware}}">
          <plugin>mock_components/GenericSystem</plugin>
          <param name="fake_sensor_commands">false</param>
        </xacro:if>
        <xacro:unless value="${{use_fake_hardware}}">
          <plugin>abb_hardware_interface/ABBSystemHardware</plugin>
          <param name="rws_ip">${{rws_ip}}</param>
        </xacro:unless>
      </hardware>
      {_joints_xml(ARM_JOINTS + FINGERS[:1])}
    </ros2_control>
  </xacro:macro>
  <xacro:property name="use_fake_hardware" value="$(arg use_fake_hardware)"/>"""
    instance = '<xacro:abb_ros2_control name="ABBMultiInterfaceHardware" use_fake_hardware="${use_fake_hardware}" rws_ip="$(arg rws_ip)"/>'
    args = {"use_fake_hardware": "true", "rws_ip": "None"}
    folder = _package(root, "abb_style", {"urdf/irb.xacro": _top("irb", args, system, instance)})
    return _described(
        "abb_style",
        folder / "urdf" / "irb.xacro",
        root,
        frozenset({"abb_hardware_interface/ABBSystemHardware"}),
        switch="use_fake_hardware",
    )


def ur_style(root: Path) -> VendorDescription:
    """Universal Robots (Jazzy driver's ur.urdf.xacro): use_mock_hardware with
    mock_sensor_commands, sim_gazebo and sim_ignition choose simulators, else the UR driver."""
    system = f"""<ros2_control name="$(arg name)" type="system">
    <hardware>
      <xacro:if value="$(arg sim_gazebo)"><plugin>gazebo_ros2_control/GazeboSystem</plugin></xacro:if>
      <xacro:if value="$(arg sim_ignition)"><plugin>ign_ros2_control/IgnitionSystem</plugin></xacro:if>
      <xacro:if value="$(arg use_mock_hardware)">
        <plugin>mock_components/GenericSystem</plugin>
        <param name="mock_sensor_commands">$(arg mock_sensor_commands)</param>
      </xacro:if>
      <xacro:unless value="${{use_mock_hardware or sim_gazebo or sim_ignition}}">
        <plugin>ur_robot_driver/URPositionHardwareInterface</plugin>
        <param name="robot_ip">$(arg robot_ip)</param>
      </xacro:unless>
    </hardware>
    {_joints_xml(ARM_JOINTS + FINGERS[:1])}
  </ros2_control>"""
    system = (
        "".join(
            f'<xacro:property name="{k}" value="$(arg {k})"/>'
            for k in ("use_mock_hardware", "sim_gazebo", "sim_ignition")
        )
        + system
    )
    args = {
        "name": "ur",
        "robot_ip": "0.0.0.0",
        "mock_sensor_commands": "false",
        "sim_gazebo": "false",
        "sim_ignition": "false",
        "use_mock_hardware": "false",
    }
    folder = _package(root, "ur_style", {"urdf/ur.urdf.xacro": _top("ur", args, system, "")})
    return _described(
        "ur_style",
        folder / "urdf" / "ur.urdf.xacro",
        root,
        frozenset({"ur_robot_driver/URPositionHardwareInterface"}),
        switch="use_mock_hardware",
    )


def kinova_style(root: Path) -> VendorDescription:
    """ros2_kortex + Robotiq: two systems (arm, gripper) on one use_fake_hardware; in mock mode
    the gripper's system also lists its mimic finger; sim_gazebo picks Gazebo for both."""

    def system(name: str, real: str, joints: list[str], mimic: bool) -> str:
        fake = '<xacro:if value="$(arg use_fake_hardware)"><plugin>mock_components/GenericSystem</plugin></xacro:if>'
        gz = '<xacro:if value="$(arg sim_gazebo)"><plugin>gz_ros2_control/GazeboSimSystem</plugin></xacro:if>'
        hw = f'<xacro:unless value="${{use_fake_hardware or sim_gazebo}}"><plugin>{real}</plugin></xacro:unless>'
        extra = (
            f'<xacro:if value="$(arg use_fake_hardware)">{_joints_xml([], fake_mimic=True)}</xacro:if>'
            if mimic
            else ""
        )
        return f'<ros2_control name="{name}" type="system"><hardware>{gz}{fake}{hw}</hardware>{_joints_xml(joints)}{extra}</ros2_control>'

    systems = "".join(
        f'<xacro:property name="{k}" value="$(arg {k})"/>' for k in ("use_fake_hardware", "sim_gazebo")
    )
    systems += system(
        "KortexMultiInterfaceHardware", "kortex_driver/KortexMultiInterfaceHardware", ARM_JOINTS, False
    )
    systems += "\n  " + system(
        "RobotiqGripperHardwareInterface", "robotiq_driver/RobotiqGripperHardwareInterface", FINGERS[:1], True
    )
    args = {"use_fake_hardware": "false", "fake_sensor_commands": "false", "sim_gazebo": "false"}
    folder = _package(root, "kinova_style", {"robots/gen3.xacro": _top("gen3", args, systems, "")})
    return _described(
        "kinova_style",
        folder / "robots" / "gen3.xacro",
        root,
        frozenset(
            {"kortex_driver/KortexMultiInterfaceHardware", "robotiq_driver/RobotiqGripperHardwareInterface"}
        ),
        switch="use_fake_hardware",
    )


def sim_only_style(root: Path) -> VendorDescription:
    """A description whose only switch picks a simulator (use_sim: Gazebo), never mock hardware,
    with an `actuator` element: no arg proves mock, so the launch files replace the hardware."""
    system = f"""<ros2_control name="arm_hw" type="actuator">
    <hardware>
      <xacro:if value="$(arg use_sim)"><plugin>gz_ros2_control/GazeboSimSystem</plugin></xacro:if>
      <xacro:unless value="$(arg use_sim)"><plugin>acme_driver/ArmActuator</plugin></xacro:unless>
    </hardware>
    {_joints_xml(ARM_JOINTS + FINGERS[:1])}
  </ros2_control>"""
    folder = _package(
        root, "sim_only_style", {"urdf/arm.urdf.xacro": _top("arm", {"use_sim": "false"}, system, "")}
    )
    return _described(
        "sim_only_style", folder / "urdf" / "arm.urdf.xacro", root, frozenset({"acme_driver/ArmActuator"})
    )


def plain_urdf_style(root: Path) -> VendorDescription:
    """A plain URDF (no xacro, no args) with a real system for the arm: only replacing works."""
    system = f'<ros2_control name="acme_arm" type="system"><hardware><plugin>acme_driver/ArmSystem</plugin></hardware>{_joints_xml(ARM_JOINTS)}</ros2_control>'
    text = f'<?xml version="1.0"?>\n<robot name="acme">\n  {_robot_body()}\n  {system}\n</robot>\n'
    folder = _package(root, "plain_urdf_style", {"urdf/acme.urdf": text})
    return _described(
        "plain_urdf_style", folder / "urdf" / "acme.urdf", root, frozenset({"acme_driver/ArmSystem"})
    )


STYLES = (franka_style, robotis_style, abb_style, ur_style, kinova_style, sim_only_style, plain_urdf_style)
NAMES = tuple(style.__name__ for style in STYLES)


def write_vendor_descriptions(root: Path) -> dict[str, VendorDescription]:
    """Every style's package under `root`, by name."""
    return {d.name: d for d in (style(root) for style in STYLES)}

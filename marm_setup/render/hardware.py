"""What the launch files' `use_mock_hardware` does to every ros2_control system of a package.

A demo never drives real hardware (DESIGN §7). The generated system (config/<robot>.ros2_control.xacro)
switches itself; the description's own `<ros2_control>` systems are handled in one of four modes:
- `none`: the description has no system of its own;
- `switch`: a xacro arg of the description proved to put every one of its systems on mock
  hardware (robot/mock_switch.py); the wrapper xacro sets it from use_mock_hardware;
- `mock`: its systems are mock hardware whatever the args;
- `replace`: no arg is proven: the launch files run xacro through scripts/with_mock_hardware.py,
  which puts every system on mock_components/GenericSystem when use_mock_hardware is true.
`use_mock_hardware:=false` gives the real hardware; where there is none the texts say so.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from marm_setup.robot import MOCK_PLUGIN, HardwareArg, RobotModel, Ros2ControlSystem, described_systems
from marm_setup.setup import Ros2ControlHardware

MOCK_SCRIPT = "scripts/with_mock_hardware.py"


@dataclass(frozen=True, slots=True)
class DescriptionHardware:
    """The description's own systems on the real side (use_mock_hardware:=false) and the mode."""

    mode: str  # none | switch | mock | replace
    systems: tuple[Ros2ControlSystem, ...] = ()
    switch: str | None = None
    why_not_switch: str = ""  # replace mode with a switch that gives a mock the distro lacks

    @property
    def plugins(self) -> str:
        return ", ".join(sorted({s.plugin or "(no plugin)" for s in self.systems}))

    @property
    def names(self) -> str:
        return ", ".join(s.name for s in self.systems)


def description_hardware(robot: RobotModel, distro: str | None) -> DescriptionHardware:
    """The mode for `robot` in a package for `distro` (a switch to a mock the distro lacks,
    such as Humble's fake_components on Jazzy, does not count)."""
    systems = described_systems(robot)
    switch = robot.mock_switch
    if switch is not None and switch.works_on(distro):
        return DescriptionHardware("switch", switch.real, switch.arg)
    if not systems:
        return DescriptionHardware("none")
    if all(s.is_mock(distro) for s in systems):
        return DescriptionHardware("mock", systems)
    why = ""
    if switch is not None:
        plugins = ", ".join(sorted({s.plugin for s in switch.mock}))
        why = f"its {switch.arg}:=true gives {plugins}, which {distro or 'this distro'} does not have"
    return DescriptionHardware("replace", systems, None, why)


@dataclass(frozen=True, slots=True)
class LaunchArg:
    """A launch arg the launch files pass on to the description's xacro (`NAME:=$(var NAME)`)."""

    name: str
    default: str
    description: str


# the launch files' own args: a description arg of one of these names is not offered again
OWN_LAUNCH_ARGS = frozenset({"use_mock_hardware", "use_sim_time", "use_rviz", "group"})


def description_launch_args(
    hw: DescriptionHardware, given: tuple[tuple[str, str], ...], hardware_args: tuple[HardwareArg, ...]
) -> list[LaunchArg]:
    """The description's args the launch files offer: the xacro args of the setup (init's
    `--xacro-arg`), the description's own hardware switch (following use_mock_hardware) and the
    args of its real hardware (robot/hardware_args.py), each with its default."""
    out = [
        LaunchArg(n, v, "xacro arg of the robot description (marm_setup.yaml robot.xacro_args)")
        for n, v in given
    ]
    if hw.mode == "switch" and hw.switch is not None:
        text = f"the description's own hardware switch: true mock hardware, false {hw.plugins}; as use_mock_hardware unless given"
        out = [a for a in out if a.name != hw.switch] + [
            LaunchArg(hw.switch, "$(var use_mock_hardware)", text)
        ]
    taken = {a.name for a in out}
    out += [
        LaunchArg(
            a.name, a.default, f"{a.param} of the real hardware of {a.system} (use_mock_hardware:=false)"
        )
        for a in hardware_args
        if a.name not in taken and launch_safe(a.default)
    ]
    return [a for a in out if a.name not in OWN_LAUNCH_ARGS]


def launch_safe(value: str) -> bool:
    """Text a `$(command '...')` can pass as one word (launch splits it like a shell, unquoted)."""
    return value.isprintable() and not set(value) & set(" \t$'\"`\\")


def description_command(
    hw: DescriptionHardware, pkg: str, robot_name: str, args: Sequence[LaunchArg] = ()
) -> str:
    """The command the launch files run for the robot description (inside `$(command '...')`)."""
    passed = "".join(f" {a.name}:=$(var {a.name})" for a in args)
    wrapper = f"$(find-pkg-share {pkg})/config/{robot_name}.urdf.xacro use_mock_hardware:=$(var use_mock_hardware){passed}"
    if hw.mode == "replace":
        return f"python3 $(find-pkg-share {pkg})/{MOCK_SCRIPT} {wrapper}"
    return f"xacro {wrapper}"


def command_comment(hw: DescriptionHardware) -> str:
    """Why the description command is what it is (a comment above it in the launch files)."""
    text = (
        "the URDF with its ros2_control systems; warn: the warnings of xacro are shown, not fatal "
        "(by default $(command) fails the launch on any stderr output)"
    )
    if hw.mode == "replace":
        text += f"; {MOCK_SCRIPT} puts the own systems of the description on mock hardware when use_mock_hardware is true"
    return text


def use_mock_hardware_help(hw: DescriptionHardware, own: Ros2ControlHardware, has_own_system: bool) -> str:
    """The use_mock_hardware arg's description: what true and false give, per system."""
    parts = []
    if has_own_system:
        if own.plugin == MOCK_PLUGIN:
            parts.append(
                "the marm-setup system: mock hardware either way, marm_setup.yaml ros2_control names no real plugin"
            )
        else:
            parts.append(f"the marm-setup system: true {MOCK_PLUGIN}, false {own.plugin}")
    if hw.mode == "switch":
        parts.append(
            f"the description systems {hw.names}: true sets its xacro arg {hw.switch}:=true (mock hardware), "
            f"false {hw.switch}:=false ({hw.plugins})"
        )
    elif hw.mode == "replace":
        parts.append(
            f"the description systems {hw.names}: true replaces their hardware with {MOCK_PLUGIN}, false keeps it ({hw.plugins})"
        )
    elif hw.mode == "mock":
        parts.append(f"the description systems {hw.names}: mock hardware either way")
    return f"true: mock ros2_control hardware, false: the real hardware ({'; '.join(parts)})"


def hardware_lines(hw: DescriptionHardware, own: Ros2ControlHardware, own_joints: int) -> list[str]:
    """What init prints about the ros2_control hardware of the package."""
    lines = []
    if own_joints:
        real = "nothing real: marm_setup.yaml names no hardware plugin (ros2_control.plugin)"
        lines.append(
            f"ros2_control: marm-setup's system for {own_joints} joint(s): use_mock_hardware:=true {MOCK_PLUGIN}, "
            f"false {real if own.plugin == MOCK_PLUGIN else own.plugin}"
        )
    for system in hw.systems:
        joints = ", ".join(system.joints)
        lines.append(
            f"ros2_control: reusing the description's system {system.name} ({system.plugin}) for {joints}"
        )
    how = {
        "switch": f"its xacro arg {hw.switch}:=true, proven by expansion to make every system mock",
        "replace": f"{hw.why_not_switch or 'no xacro arg of it makes every system mock'}, so the launch files "
        f"replace the hardware ({MOCK_SCRIPT})",
        "mock": "its systems are mock hardware either way",
    }
    if hw.mode in how:
        lines.append(
            f"ros2_control: use_mock_hardware:=true puts the description's systems on mock hardware: {how[hw.mode]}"
        )
    return lines

"""The xacro args of a description that configure its real ros2_control hardware (the robot's
address, credentials, ports: `robot_ip`, `username`, ...), found by expansion: an arg is one when
its value reaches a `<param>` of a system's `<hardware>` on the real side and nothing else of
the URDF. The launch files offer them as launch args, so that `use_mock_hardware:=false
robot_ip:=...` reaches the robot at hand.

Candidates are the args whose value (not a boolean, not empty) is a hardware parameter's value;
one expansion with each candidate set to a marker of its own proves which reach only hardware
parameters (a marker that also names a joint, say, or a failed expansion proves nothing).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

from marm_setup.errors import InputError
from marm_setup.robot.ros2_control import HardwareArg, Ros2ControlSystem, systems_in_urdf

BOOLEANS = frozenset({"true", "false", "True", "False", "1", "0"})


def marker(name: str) -> str:
    return f"marm_setup_arg_{name}_value"


def hardware_arg_candidates(
    known: Mapping[str, str],
    given: Mapping[str, str],
    skip: frozenset[str],
    systems: tuple[Ros2ControlSystem, ...],
) -> list[str]:
    """Args (not given, not in `skip`) whose value is the value of a hardware parameter."""
    values = {v for s in systems for _, v in s.params}
    return sorted(
        n
        for n, v in known.items()
        if n not in given and n not in skip and v.strip() and v not in BOOLEANS and v in values
    )


def find_hardware_args(
    expand: Callable[[Mapping[str, str]], str],
    real_args: Mapping[str, str],
    known: Mapping[str, str],
    systems: tuple[Ros2ControlSystem, ...],
    skip: frozenset[str] = frozenset(),
) -> tuple[HardwareArg, ...]:
    """Each arg proven to configure only the real hardware; `real_args` expand the
    description's real side, whose systems are `systems`."""
    candidates = hardware_arg_candidates(known, real_args, skip, systems)
    if not candidates:
        return ()
    try:
        xml = expand({**real_args, **{n: marker(n) for n in candidates}})
    except InputError:
        return ()
    params = [(s.name, p, v) for s in systems_in_urdf(xml) for p, v in s.params]
    out = []
    for name in candidates:
        reached = [(system, param) for system, param, value in params if marker(name) in value]
        in_params = sum(value.count(marker(name)) for _, _, value in params)
        if reached and xml.count(marker(name)) == in_params:
            out.append(HardwareArg(name, known[name], *reached[0]))
    return tuple(out)

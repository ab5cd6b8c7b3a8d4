"""Find the xacro arg that switches a description's own `<ros2_control>` systems to mock hardware.

Vendor descriptions carry their own switch, each in its own words: Franka, ABB and Kinova
`use_fake_hardware`, Universal Robots `use_mock_hardware` (Humble: `use_fake_hardware`),
ROBOTIS `use_sim` or `use_fake_hardware`, and gazebo switches (`sim_gazebo`, `sim_ignition`)
that choose a simulator, not mock hardware. A name proves nothing: an arg is the switch only
when expanding the description with it `true` gives mock hardware in every system and with it
`false` gives some real hardware (the setup's other args as they are). Where no arg passes,
the generated launch files replace the systems' hardware instead (render/hardware.py).
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping

from marm_setup.errors import InputError
from marm_setup.robot.ros2_control import MockSwitch, systems_in_urdf

# Words of a switch's name; mock/fake names are tried before simulator names.
SWITCH_WORDS = re.compile(r"mock|fake|sim", re.IGNORECASE)
FIRST_WORDS = re.compile(r"mock|fake", re.IGNORECASE)
BOOLEANS = frozenset({"true", "false", "True", "False", "1", "0"})


def switch_candidates(known: Mapping[str, str]) -> list[str]:
    """xacro args (as xacro knew them after an expansion) that may be a hardware switch: a
    boolean value and a name with mock, fake or sim in it; mock/fake names first."""
    names = [n for n, v in known.items() if SWITCH_WORDS.search(n) and v.strip() in BOOLEANS]
    return sorted(names, key=lambda n: (FIRST_WORDS.search(n) is None, n))


def find_mock_switch(
    expand: Callable[[Mapping[str, str]], str], args: Mapping[str, str], known: Mapping[str, str]
) -> MockSwitch | None:
    """The first candidate arg proven to be the switch, by expanding (`expand(args) -> URDF XML`)
    with it true and false; None when none is (an expansion that fails proves nothing)."""
    for name in switch_candidates(known):
        try:
            mock = systems_in_urdf(expand({**args, name: "true"}))
            if not mock or not all(s.is_mock() for s in mock):
                continue
            real = systems_in_urdf(expand({**args, name: "false"}))
        except InputError:
            continue
        if real and not all(s.is_mock() for s in real):
            return MockSwitch(name, mock, real)
    return None

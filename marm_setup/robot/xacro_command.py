"""`xacro [options] FILE [name:=value ...]` as a command, for ROS 1 launch files run by the user's roslaunch
when their ROS has no xacro of its own (Debian's roslaunch): the same expansion marm-setup uses,
with `$(find pkg)` resolved through ROS_PACKAGE_PATH and the packages around FILE.

validate's ROS 1 consumer (validate/consumers.py) puts a `xacro` script calling `main` last on
the launcher's PATH; a real ROS xacro earlier on PATH wins.
"""

from __future__ import annotations

import sys
from pathlib import Path


def main(argv: list[str] | None = None) -> int:
    from marm_setup.errors import MarmError
    from marm_setup.robot.load import expand_xacro
    from marm_setup.robot.ros_packages import find_packages
    from marm_setup.robot.xacro_cli import parse_xacro_argv

    call = parse_xacro_argv(sys.argv[1:] if argv is None else argv)
    if call.file is None:
        print("usage: xacro [options] FILE [name:=value ...]", file=sys.stderr)
        return 2
    file = Path(call.file)
    try:
        packages = find_packages([], near=file)
        sys.stdout.write(expand_xacro(file, dict(call.args), packages, shown=str(file)))
    except MarmError as exc:
        print(f"xacro: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Where a config package's robot description and SRDF come from, and which ROS it targets.

`marm_setup.yaml` first, then the MoveIt 2 `config/<robot>.urdf.xacro`, then `.setup_assistant`
(MoveIt 1 `URDF`/`SRDF` keys and MoveIt 2 lower-case ones); `--urdf` overrides them all.
`marm` arguments are the parsed marm_setup.yaml (or None).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.errors import InputError, MarmError, remedy
from marm_setup.findings import Finding, error, warning
from marm_setup.robot.ros_packages import package_name

MARM_MOVEIT_YAML = "config/moveit.yaml"


def detect_target(root: Path, marm: Any) -> str:
    """ros2 for ament packages, ros1 for catkin; falls back on marm_setup.yaml and file names."""
    xml = root / "package.xml"
    if xml.is_file():
        try:
            text = bounded_read.read_bytes(xml, bounded_read.XML_BYTES).decode("utf-8", errors="replace")
        except (OSError, FileTooLarge):
            text = ""
        if "ament_cmake" in text or "ament_python" in text:
            return "ros2"
        if "catkin" in text:
            return "ros1"
    if isinstance(marm, dict) and marm.get("target") in ("ros1", "ros2"):
        return marm["target"]
    ros2_files = ("config/moveit_controllers.yaml", "config/ros2_controllers.yaml", MARM_MOVEIT_YAML)
    return "ros2" if any((root / f).is_file() for f in ros2_files) else "ros1"


def _setup_assistant_config(raw: Any) -> dict:
    if isinstance(raw, dict) and isinstance(raw.get("moveit_setup_assistant_config"), dict):
        return raw["moveit_setup_assistant_config"]
    return {}


def _sa_entry(raw: Any, key: str) -> dict:
    config = _setup_assistant_config(raw)
    entry = config.get(key.upper(), config.get(key.lower()))
    return entry if isinstance(entry, dict) else {}


SRDF_GLOBS = ("config/*.srdf", "srdf/*.srdf", "config/*.srdf.xacro", "srdf/*.srdf.xacro")


def find_srdf(root: Path, marm: Any, setup_assistant: Any, launch=None, problems=None):
    """(relative SRDF path or None, its xacro args): marm_setup.yaml's, `.setup_assistant`'s,
    the one a launch file sets as `*_semantic` (with the xacro args it passes), then the first of
    `config/*.srdf`, `srdf/*.srdf` and their `.srdf.xacro` forms. A `.setup_assistant` naming a
    missing SRDF is an error in `problems`: the Setup Assistant cannot load the package."""
    candidates: list[tuple[str, tuple]] = []
    if isinstance(marm, dict) and marm.get("robot_name"):
        candidates.append((f"config/{marm['robot_name']}.srdf", ()))
    rel = _sa_entry(setup_assistant, "srdf").get("relative_path")
    if isinstance(rel, str):
        if (root / rel).is_file():
            candidates.append((rel, ()))
        elif problems is not None:
            problems.append(_missing_sa_srdf(setup_assistant, rel))
    if launch is not None:
        candidates.append(launch)
    for pattern in SRDF_GLOBS:
        candidates += [(p.relative_to(root).as_posix(), ()) for p in sorted(root.glob(pattern))]
    return next(((c, a) for c, a in candidates if (root / c).is_file()), (None, ()))


def _missing_sa_srdf(setup_assistant: Any, rel: str) -> Finding:
    key = "SRDF" if "SRDF" in _setup_assistant_config(setup_assistant) else "srdf"
    msg = f"names the SRDF '{rel}', which does not exist: the Setup Assistant cannot load this package"
    return error("srdf.missing", ".setup_assistant", f"{key}.relative_path", msg, "fix the path")


def srdf_robot_name(root: Path, rel: str | None) -> str | None:
    """The `<robot name>` of the SRDF (what MoveItConfigsBuilder and launch files pair a URDF by)."""
    if rel is None:
        return None
    from lxml import etree

    try:
        with open(root / rel, "rb") as stream:  # closed also when the first element returns
            if os.fstat(stream.fileno()).st_size > bounded_read.XML_BYTES:
                return None  # read_srdf_source reports it
            for _event, elem in etree.iterparse(stream, events=("start",)):
                return elem.get("name") or None
    except (etree.XMLSyntaxError, OSError):
        return None
    return None


def read_srdf_source(
    root: Path, rel: str, paths: tuple[Path, ...], problems: list[Finding], args: dict | None = None
) -> tuple[Any, str | None]:
    """(parsed SRDF, its text); a `.srdf.xacro` is expanded by xacro (with `args`) first;
    failures -> problems."""
    from marm_setup.setup.srdf import parse_srdf_string

    file = root / rel
    skipped: list[InputError] = []
    try:
        text = _srdf_text(file, rel, paths, args or {})
        srdf = parse_srdf_string(text, rel, skipped)
    except MarmError as exc:
        problems.append(error("srdf.parse", rel, exc.element or "", exc.message, remedy(exc.needs)))
        return None, None
    problems += [_skipped_element(rel, exc) for exc in skipped]
    return _without_skipped_groups(srdf, skipped), text


def _skipped_element(rel: str, exc: InputError) -> Finding:
    """An SRDF element left out: srdfdom also skips one missing an attribute (logging an error);
    a form srdfdom reads but this validator does not model is only not checked."""
    if "not supported" in exc.message:
        return warning("srdf.unsupported", rel, exc.element or "", f"not checked: {exc.message}")
    return error("srdf.parse", rel, exc.element or "", f"{exc.message} (srdfdom skips this element)")


def skipped_groups(skipped) -> set[str]:
    """Names of the groups left out (errors or findings whose element is `group[NAME]`)."""
    return {
        e.element[len("group[") : -1]
        for e in skipped
        if (e.element or "").startswith("group[") and e.element.endswith("]")
    }


def _without_skipped_groups(srdf, skipped: list[InputError]):
    """Poses and end effectors of a group left out are left out too (no cascade of 'unknown group')."""
    import dataclasses

    gone = skipped_groups(skipped)
    if not gone:
        return srdf
    return dataclasses.replace(
        srdf,
        group_states=tuple(s for s in srdf.group_states if s.group not in gone),
        end_effectors=tuple(
            e for e in srdf.end_effectors if e.group not in gone and e.parent_group not in gone
        ),
    )


def _srdf_text(file: Path, rel: str, paths: tuple[Path, ...], args: dict) -> str:
    if not rel.endswith(".xacro"):
        try:
            return bounded_read.read_text(file, bounded_read.XML_BYTES, shown=rel)
        except (OSError, UnicodeDecodeError) as exc:
            raise InputError(f"cannot read: {exc}", path=rel) from None
    from marm_setup.setup.srdf import expand_srdf_xacro

    return expand_srdf_xacro(file, args, paths, shown=rel).xml


def find_urdf(root, shown, urdf, xacro_args, marm, setup_assistant, paths, robot_name=None):
    """(path, origin, xacro args) of the robot description; InputError when none can be found.

    The MoveIt 2 `config/<robot>.urdf.xacro` is picked by the SRDF's robot name, as
    MoveItConfigsBuilder(robot_name) pairs `config/<robot_name>.urdf.xacro` with its SRDF."""
    args = tuple(sorted((xacro_args or {}).items()))
    if urdf is not None:
        if not Path(urdf).is_file():
            raise InputError("file not found", path=str(urdf), element="--urdf")
        return Path(urdf), "--urdf", args
    if isinstance(marm, dict) and isinstance(marm.get("robot"), dict):
        robot = marm["robot"]
        if isinstance(robot.get("urdf"), str):
            from marm_setup.robot.ros_packages import description_file

            try:
                file = description_file(robot["urdf"], root, (*paths, *marm_package_paths(root, marm)))
            except InputError:  # a package:// the package cannot find: reported as the missing URDF
                file = root / robot["urdf"]
            return file, "marm_setup.yaml", args or _marm_xacro_args(robot.get("xacro_args"))
    name = package_name(root) or root.name
    xacros = sorted((root / "config").glob("*.urdf.xacro"))
    named = [c for c in xacros if c.name == f"{robot_name}.urdf.xacro"]
    if named or (len(xacros) == 1 and robot_name is None):
        return (named or xacros)[0], "config/<robot>.urdf.xacro", args
    entry = _sa_entry(setup_assistant, "urdf")
    if entry.get("package") and entry.get("relative_path"):
        return _setup_assistant_urdf(entry, paths, shown, args)
    raise InputError(
        f"cannot find the robot description of package '{name}' ({_why_no_urdf(root, marm, setup_assistant)})",
        path=shown,
        element="robot description",
        needs="--urdf",
    )


def _why_no_urdf(root: Path, marm: Any, setup_assistant: Any) -> str:
    """Why none of the robot description sources gave a URDF, naming the files that exist."""
    for rel, data in (("marm_setup.yaml", marm), (".setup_assistant", setup_assistant)):
        if (root / rel).is_file() and data is None:
            return f"{rel} is not readable YAML"
    if (root / ".setup_assistant").is_file():
        return ".setup_assistant gives no URDF package and relative_path"
    if (root / "marm_setup.yaml").is_file():
        return "marm_setup.yaml gives no robot.urdf"
    return "no marm_setup.yaml, .setup_assistant or config/<robot>.urdf.xacro"


def setup_assistant_urdf(root: Path, shown: str, paths: tuple[Path, ...]):
    """(path, origin, xacro args) of the description `.setup_assistant` names (its URDF package
    and relative_path), or None when it names none; InputError when the package is not found."""
    import yaml

    from marm_setup.safe_yaml import load_yaml

    try:
        raw = load_yaml(bounded_read.read_text(root / ".setup_assistant", bounded_read.YAML_BYTES))
    except (OSError, UnicodeDecodeError, yaml.YAMLError, FileTooLarge):
        return None
    entry = _sa_entry(raw, "urdf")
    if not (entry.get("package") and entry.get("relative_path")):
        return None
    return _setup_assistant_urdf(entry, paths, shown, ())


def _setup_assistant_urdf(entry: dict, paths: tuple[Path, ...], shown: str, args):
    from marm_setup.robot.ros_packages import find_package, find_packages

    packages = find_packages(paths)
    where = str(Path(shown) / ".setup_assistant")
    pkg_dir = find_package(str(entry["package"]), packages, path=where, element="URDF.package")
    sa_args = _marm_xacro_args(str(entry.get("xacro_args") or "").split())
    return pkg_dir / str(entry["relative_path"]), ".setup_assistant", args or sa_args


def marm_package_paths(root: Path, marm: Any) -> tuple[Path, ...]:
    """`robot.package_paths` of marm_setup.yaml (relative to the package) that exist: a package
    copied into a workspace finds its description next to it instead."""
    robot = marm.get("robot") if isinstance(marm, dict) else None
    items = robot.get("package_paths") if isinstance(robot, dict) else None
    if not isinstance(items, list):
        return ()
    paths = ((root / str(p)).resolve() for p in items if isinstance(p, str))
    return tuple(p for p in paths if p.is_dir())


def _marm_xacro_args(value: Any) -> tuple[tuple[str, str], ...]:
    """xacro args given as a mapping, a list of `NAME:=VALUE` or a list of pairs."""
    if isinstance(value, dict):
        return tuple(sorted((str(k), str(v)) for k, v in value.items()))
    out = []
    for item in value or ():
        if isinstance(item, str) and ":=" in item:
            name, _, val = item.partition(":=")
            out.append((name, val))
        elif isinstance(item, (list, tuple)) and len(item) == 2:
            out.append((str(item[0]), str(item[1])))
    return tuple(sorted(out))

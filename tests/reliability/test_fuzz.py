"""A fuzzer over URDF, setup file and SRDF: every run exits 0, 1 or 2 without a traceback, and
every package written with exit 0 parses (XML, YAML, Python) and passes our own `validate`.
Also file sizes at and around each kind's bound (sparse, up to 6 GiB) and binary STLs whose
triangle count agrees with their size or not: refused in one line, never read whole.

`make test` runs a few examples per input kind; `make fuzz` runs FUZZ_EXAMPLES of each with a
random seed and prints the counts."""

from __future__ import annotations

import atexit
import math
import os
import shutil
import tempfile
from collections import Counter
from pathlib import Path

import pytest
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from lxml import etree

from tests.reliability.checks import assert_clean_exit, assert_package_parses, run
from tests.unit.test_eval_escapes import ESCAPE, LOOKALIKE

EXAMPLES = int(os.environ.get("FUZZ_EXAMPLES", "5"))
FUZZ = settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=list(HealthCheck))
STATS: Counter = Counter()

HOSTILE = ["a b", "x$(env HOME)", "--help", "q'\"", "n\nl", "a: b", "wait...", "<&>", "-", "1e3", "é", "a--b"]
_valid = st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,7}", fullmatch=True)
_any = st.text(st.characters(exclude_categories=("Cs",)), min_size=0, max_size=8)
names = st.one_of(_valid, _valid, _valid, st.sampled_from(HOSTILE), _any)  # mostly names that pass
_sane = st.floats(-0.9, 0.9)
numbers = st.one_of(
    _sane,
    _sane,
    _sane,
    st.sampled_from([0.0, 1e308, -1e300, 1e-300, math.nan, math.inf, 1e9, 2e9]),
    st.floats(allow_nan=True, allow_infinity=True),
)


@pytest.fixture(scope="module", autouse=True)
def _report():
    yield
    print(f"\nfuzz: {dict(sorted(STATS.items()))}")


def _xml(root: etree._Element) -> bytes:
    return etree.tostring(root, xml_declaration=True, encoding="utf-8")


def _el(parent, tag: str, **attrs) -> etree._Element:
    try:
        return etree.SubElement(parent, tag, {k: str(v) for k, v in attrs.items()})
    except ValueError:  # a name XML cannot hold (control characters): lxml refuses it
        return etree.SubElement(parent, tag, {k: "x" for k in attrs})


def robot_xml(robot: str, links: list[str], values: list[float]) -> bytes:
    """A 3-link arm: base -> l1 -> l2 (revolute), l2 -> tool (fixed); boxes on the first three."""
    root = etree.Element("robot")
    try:
        root.set("name", robot)
    except ValueError:
        root.set("name", "r")
    for i, name in enumerate(links):
        link = _el(root, "link", name=name)
        if i < 3:
            geometry = etree.SubElement(etree.SubElement(link, "collision"), "geometry")
            _el(geometry, "box", size=f"{values[0] if i == 0 else 0.05} 0.05 0.05")
    for i in range(3):
        joint = _el(root, "joint", name=f"j{i + 1}", type="revolute" if i < 2 else "fixed")
        _el(joint, "parent", link=links[i])
        _el(joint, "child", link=links[i + 1])
        _el(joint, "origin", xyz=f"0 0 {values[1] if i == 1 else 0.1}")
        _el(joint, "axis", xyz="0 0 1")
        if i < 2:
            _el(joint, "limit", lower=-1, upper=values[2] if i == 0 else 1, velocity=1, effort=1)
    return _xml(root)


def _check_run(args: list, out: Path) -> None:
    result = run(*args)
    assert_clean_exit(result)
    STATS[f"exit {result.exit_code}"] += 1
    if os.environ.get("FUZZ_VERBOSE") and result.exit_code == 2:
        print(result.stderr.strip()[:160])
    if result.exit_code == 0:
        assert_package_parses(out)
        validated = run("validate", out, "--no-plan")
        assert_clean_exit(validated, codes=(0,))
        STATS["packages validated"] += 1


def _workdir() -> Path:
    return Path(tempfile.mkdtemp(prefix="marm-fuzz-"))


@FUZZ
@given(
    robot=names,
    links=st.lists(names, min_size=4, max_size=4),
    values=st.lists(numbers, min_size=3, max_size=3),
    cut=st.one_of(st.none(), st.none(), st.none(), st.integers(0, 2000)),
    target=st.sampled_from(["ros1", "ros2"]),
)
def test_fuzz_urdf(robot, links, values, cut, target):
    work = _workdir()
    try:
        text = robot_xml(robot, links, values)
        (work / "r.urdf").write_bytes(text if cut is None else text[:cut])
        STATS["urdf examples"] += 1
        _check_run(
            ["init", work / "r.urdf", "--out", work / "pkg", "--trials", "10", "--target", target],
            work / "pkg",
        )
    finally:
        shutil.rmtree(work, ignore_errors=True)


SAFE_ROBOT = robot_xml("fuzzbot", ["base", "l1", "l2", "tool"], [0.05, 0.1, 1.0])


def _spec(group, pose, ee, ctl, ns, q, scale, target) -> dict:
    return {
        "target": target,
        "groups": [
            {"name": group, "chain": {"base": "base", "tip": "tool"}},
            {"name": "hand", "links": ["tool"]},
        ],
        "group_states": [{"name": pose, "group": group, "values": {"j1": q, "j2": 0.0}}],
        "end_effectors": [{"name": ee, "group": "hand", "parent_link": "l2"}],
        "controllers": [
            {"name": ctl, "type": "FollowJointTrajectory", "action_ns": ns, "joints": ["j1", "j2"]}
        ],
        "default_velocity_scaling": scale,
    }


@FUZZ
@given(
    group=names,
    pose=names,
    ee=names,
    ctl=names,
    ns=names,
    q=numbers,
    scale=numbers,
    target=st.sampled_from(["ros1", "ros2"]),
    cut=st.one_of(st.none(), st.none(), st.none(), st.integers(0, 600)),
)
def test_fuzz_setup_file(group, pose, ee, ctl, ns, q, scale, target, cut):
    work = _workdir()
    try:
        (work / "r.urdf").write_bytes(SAFE_ROBOT)
        text = yaml.safe_dump(_spec(group, pose, ee, ctl, ns, q, scale, target), allow_unicode=True)
        (work / "spec.yaml").write_text(text if cut is None else text[:cut], encoding="utf-8")
        STATS["setup examples"] += 1
        args = [
            "init",
            work / "r.urdf",
            "--out",
            work / "pkg",
            "--trials",
            "10",
            "--setup",
            work / "spec.yaml",
        ]
        _check_run(args, work / "pkg")
    finally:
        shutil.rmtree(work, ignore_errors=True)


def srdf_xml(group: str, pose: str, joint: str, value: float, vj_type: str) -> bytes:
    root = etree.Element("robot", name="fuzzbot")
    g = _el(root, "group", name=group)
    _el(g, "chain", base_link="base", tip_link="tool")
    state = _el(root, "group_state", name=pose, group=group)
    _el(state, "joint", name=joint, value=value)
    _el(state, "joint", name="j2", value=0)
    _el(root, "virtual_joint", name="vj", type=vj_type, parent_frame="world", child_link="base")
    return _xml(root)


@FUZZ
@given(
    group=names,
    pose=names,
    joint=st.one_of(st.just("j1"), names),
    value=numbers,
    vj_type=st.sampled_from(["fixed", "planar", "floating", "hinge", ""]),
    target=st.sampled_from(["ros1", "ros2"]),
)
def test_fuzz_srdf(group, pose, joint, value, vj_type, target):
    work = _workdir()
    try:
        (work / "r.urdf").write_bytes(SAFE_ROBOT)
        (work / "r.srdf").write_bytes(srdf_xml(group, pose, joint, value, vj_type))
        STATS["srdf examples"] += 1
        args = [
            "init",
            work / "r.urdf",
            "--out",
            work / "pkg",
            "--trials",
            "10",
            "--from-srdf",
            work / "r.srdf",
            "--target",
            target,
        ]
        _check_run(args, work / "pkg")
    finally:
        shutil.rmtree(work, ignore_errors=True)


# -- size bounds ---------------------------------------------------------------------------------
# Files at, just under and just over the bound of their kind (bounded_read), sparse up to 6 GiB,
# and binary STLs whose triangle count agrees with their size or not: every run is a clean exit,
# and a file over its bound is a 'too large' refusal (a line, or a finding in validate).

GiB = 1 << 30


def _bound(kind: str) -> int:
    from marm_setup import bounded_read

    return {
        "mesh": bounded_read.MESH_BYTES,
        "setup": bounded_read.YAML_BYTES,
        "package yaml": bounded_read.YAML_BYTES,
    }.get(kind, bounded_read.XML_BYTES)


def _sized(path: Path, size: int, head: bytes) -> Path:
    with open(path, "wb") as out:
        out.write(head[:size])
        out.truncate(size)
    return path


_HEADS = {
    "urdf": b'<robot name="r"><link name="a"/></robot>',
    "xacro": b'<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r"><link name="a"/></robot>',
    "setup": b"groups: []\n",
    "srdf": b'<robot name="fuzzbot"></robot>',
    "package yaml": b"{}\n",
}
_PACKAGE: dict[str, Path] = {}


def _package(work: Path) -> Path:
    """One generated package per session, copied for each example."""
    if "pkg" not in _PACKAGE:
        base = Path(tempfile.mkdtemp(prefix="marm-fuzz-pkg-"))
        atexit.register(shutil.rmtree, base, True)
        (base / "r.urdf").write_bytes(SAFE_ROBOT)
        assert_clean_exit(run("init", base / "r.urdf", "--out", base / "pkg", "--trials", "10"), codes=(0,))
        _PACKAGE["pkg"] = base / "pkg"
    shutil.copytree(_PACKAGE["pkg"], work / "pkg")
    (work / "r.urdf").write_bytes(SAFE_ROBOT)
    return work / "pkg"


def _size_args(kind: str, work: Path, file: Path) -> list:
    (work / "r.urdf").write_bytes(SAFE_ROBOT)
    return {
        "urdf": ["inspect", file],
        "xacro": ["inspect", file],
        "setup": ["init", work / "r.urdf", "--out", work / "out", "--trials", "10", "--setup", file],
        "srdf": ["init", work / "r.urdf", "--out", work / "out", "--trials", "10", "--from-srdf", file],
    }[kind]


@FUZZ
@given(
    kind=st.sampled_from(["urdf", "xacro", "setup", "srdf", "package yaml"]),
    offset=st.sampled_from([-1, 0, 1]),
    huge=st.booleans(),
    keep_head=st.booleans(),
)
def test_fuzz_file_sizes(kind, offset, huge, keep_head):
    work = _workdir()
    try:
        size = 6 * GiB if huge else _bound(kind) + offset
        name = {"xacro": "r2.urdf.xacro", "setup": "s.yaml", "srdf": "r.srdf", "urdf": "r2.urdf"}.get(
            kind, "k.yaml"
        )
        head = _HEADS[kind] if keep_head else b""
        if kind == "package yaml":
            pkg = _package(work)
            _sized(pkg / "config" / "kinematics.yaml", size, head)
            result = run("validate", pkg, "--no-plan")
        else:
            result = run(*_size_args(kind, work, _sized(work / name, size, head)))
        assert_clean_exit(result)
        STATS[f"size {kind}: exit {result.exit_code}"] += 1
        if size > _bound(kind):
            assert "too large" in result.stdout + result.stderr
    finally:
        shutil.rmtree(work, ignore_errors=True)


@FUZZ
@given(
    count=st.sampled_from([0, 1, 12, 999_999, 1_000_000, 1_000_001, 5_000_000]),
    delta=st.sampled_from([0, 0, -1, 1, 7, 4096]),
    solid=st.booleans(),
)
def test_fuzz_binary_stl_counts(count, delta, solid):
    """A binary STL whose header's triangle count agrees with its size (or is off by `delta`):
    read, refused for its triangles, or refused as neither binary nor ASCII; never decoded whole."""
    from marm_setup.robot.meshes import MAX_TRIANGLES

    work = _workdir()
    try:
        size = max(84 + 50 * count + delta, 0)
        header = (b"solid fuzz" if solid else b"").ljust(80, b"\0") + count.to_bytes(4, "little")
        _sized(work / "m.stl", size, header)
        body = SAFE_ROBOT.replace(b'<box size="0.05 0.05 0.05"/>', b'<mesh filename="m.stl"/>', 1)
        (work / "r.urdf").write_bytes(body)
        result = run("collisions", work / "r.urdf", "--trials", "10")
        assert_clean_exit(result)
        STATS[f"stl: exit {result.exit_code}"] += 1
        if delta == 0 and count > MAX_TRIANGLES:
            assert f"{count:,} triangles, more than" in result.stderr
        elif delta:
            assert result.exit_code == 2
    finally:
        shutil.rmtree(work, ignore_errors=True)


# -- escapes -------------------------------------------------------------------------------------
# A package that tries to run code or read outside itself (issue 23): a symlink out of it, a
# `..` or absolute path in marm_setup.yaml / .setup_assistant, `$(eval ...)` in a launch file
# (the NFKC look-alike escape, unbounded work, constructs outside the allow-list, random text)
# and a package folder whose path holds a substitution. validate (and --untrusted) exits cleanly,
# never runs the code (no marker file) and never shows the outside file's content.

SECRET = "FUZZ-SECRET-hunter2"
EXPRESSIONS = [
    ESCAPE.format(u=LOOKALIKE, marker="ran"),
    "9**9**9",
    "'a' * 10**10",
    "(lambda: 0)()",
    "open('ran', 'w')",
    "arg('x').upper()",
    "1 if true else 0",
    "$(arg nope)",
]
SYMLINKED = [
    "config/moveit.yaml",
    "config/initial_positions.yaml",
    "config/ros2_controllers.yaml",
    "config/fuzzbot.srdf",
    "package.xml",
    "marm_setup.yaml",
]
PATHS = [("robot_name", "../../secret/x"), ("robot_name", "{secret}/x"), ("srdf", "{secret}/x.srdf")]


def _secret(work: Path) -> Path:
    secret = work / "secret"
    secret.mkdir()
    (secret / "creds").write_text(f"{SECRET}: 1\n", encoding="utf-8")
    (secret / "x.srdf").write_text(
        f'<robot name="{SECRET}"><group name="{SECRET}"/></robot>\n', encoding="utf-8"
    )
    return secret


def _with_arg(pkg: Path, value: str) -> None:
    """`<arg name="fuzz_z" default="value"/>` first in each launch file."""
    for launch in (pkg / "launch").iterdir():
        if launch.name.endswith((".launch", ".launch.xml")):
            text = launch.read_text(encoding="utf-8")
            arg = f'<arg name="fuzz_z" default="{escape(value)}"/>'
            launch.write_text(text.replace("<launch>", f"<launch>\n  {arg}", 1), encoding="utf-8")


def escape(text: str) -> str:
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")


def _with_path(pkg: Path, key: str, value: str) -> None:
    if key == "robot_name":
        text = (pkg / "marm_setup.yaml").read_text(encoding="utf-8")
        start = text.index("robot_name: ")
        end = text.index("\n", start)
        (pkg / "marm_setup.yaml").write_text(
            f"{text[:start]}robot_name: {value}{text[end:]}", encoding="utf-8"
        )
    elif (pkg / ".setup_assistant").is_file():
        data = yaml.safe_load((pkg / ".setup_assistant").read_text(encoding="utf-8"))
        config = data["moveit_setup_assistant_config"]
        config.setdefault("SRDF", {})["relative_path"] = value
        (pkg / ".setup_assistant").write_text(yaml.safe_dump(data), encoding="utf-8")


@FUZZ
@given(
    kind=st.sampled_from(["symlink", "eval", "folder", "path"]),
    symlinked=st.sampled_from(SYMLINKED),
    expression=st.one_of(st.sampled_from(EXPRESSIONS), st.text(max_size=30)),
    path=st.sampled_from(PATHS),
    untrusted=st.booleans(),
)
def test_fuzz_escapes(kind, symlinked, expression, path, untrusted):
    work = _workdir()
    here = os.getcwd()
    try:
        os.chdir(work)  # where a `touch ran` that got through would leave its marker
        secret = _secret(work)
        pkg = _package(work)
        if kind == "symlink":
            (pkg / symlinked).unlink()
            (pkg / symlinked).symlink_to(secret / "creds")
        elif kind == "eval":
            _with_arg(pkg, f"$(eval {expression})")
        elif kind == "folder":
            folder = work / f"$(eval {expression})".replace("/", "_").replace("\x00", "_")[:200]
            folder.mkdir()
            pkg = Path(shutil.move(pkg, folder / "pkg"))
            (folder / "r.urdf").write_bytes(SAFE_ROBOT)  # marm_setup.yaml's '../r.urdf'
            _with_arg(pkg, "$(dirname)/x")
        else:
            _with_path(pkg, path[0], path[1].format(secret=secret))
        result = run("validate", pkg, "--no-plan", *(["--untrusted"] if untrusted else []))
        assert_clean_exit(result)
        STATS[f"escape {kind}: exit {result.exit_code}"] += 1
        assert SECRET not in result.output
        assert not (work / "ran").exists()
        if kind == "symlink" and result.exit_code != 2:
            assert "package.outside" in result.stdout
    finally:
        os.chdir(here)
        shutil.rmtree(work, ignore_errors=True)


# -- round 4 (issue 36) --------------------------------------------------------------------------
# Launch files that grow (args doubling, files including themselves, Python launch files past
# their bounds), the user's environment under --untrusted, and writers aimed at a symlink: every
# run is a clean exit, the secret never shows, the link's target is never written.

ENV_SECRET = "FUZZ-ENV-SECRET-hunter3"


def _hostile_launch(pkg: Path, family: str, ros2: bool, n: int, copies: int) -> None:
    from tests.reliability.hostile_launch import growing_args, python_launch, self_including, with_args

    if family == "args":
        with_args(pkg, ros2, growing_args(ros2, n, copies))
    elif family == "include":
        self_including(pkg, ros2, copies, new_args=n % 2 == 1)
    elif family == "env":
        use = "optenv" if n % 2 else "env"
        with_args(pkg, ros2, f'<arg name="fuzz_env" default="$({use} MARM_FUZZ_ENV)"/>')
    else:
        kind = ["sum", "unary", "negations", "string", "list", "nested list", "fstring"][n % 7]
        size = {"sum": 20_000, "unary": 3_000, "negations": 3_000}.get(kind, 10 + 5 * copies)
        (pkg / "launch" / "x.launch.py").write_text(python_launch(kind, size), encoding="utf-8")


@FUZZ
@given(
    family=st.sampled_from(["args", "include", "env", "python"]),
    n=st.integers(1, 40),
    copies=st.integers(2, 6),
    untrusted=st.booleans(),
)
def test_fuzz_growth_and_environment(family, n, copies, untrusted):
    from tests.validate_helpers import generate_marm

    work = _workdir()
    os.environ["MARM_FUZZ_ENV"] = ENV_SECRET
    try:
        ros2 = family == "python" or n % 3 == 0
        pkg = generate_marm(work, "ros2" if ros2 else "ros1")
        _hostile_launch(pkg, family, ros2, n, copies)
        result = run("validate", pkg, "--no-plan", *(["--untrusted"] if untrusted else []))
        assert_clean_exit(result)
        assert "internal error" not in result.output
        STATS[f"growth {family}: exit {result.exit_code}"] += 1
        if untrusted:
            assert ENV_SECRET not in result.output
    finally:
        os.environ.pop("MARM_FUZZ_ENV", None)
        shutil.rmtree(work, ignore_errors=True)


@FUZZ
@given(writer=st.sampled_from(["collisions --output", "collisions --report"]), dangling=st.booleans())
def test_fuzz_writers_refuse_symlinks(writer, dangling):
    work = _workdir()
    try:
        (work / "r.urdf").write_bytes(SAFE_ROBOT)
        victim = work / "victim.txt"
        if not dangling:
            victim.write_text("keep\n", encoding="utf-8")
        link = work / ("m.svg" if writer.endswith("report") else "m.srdf")
        link.symlink_to(victim)
        flag = writer.split()[1]
        result = run("collisions", work / "r.urdf", "--trials", "10", flag, link)
        assert_clean_exit(result, codes=(2,))
        STATS[f"symlink {writer}: refused"] += 1
        assert link.is_symlink() and (
            victim.read_text(encoding="utf-8") == "keep\n" if not dangling else not victim.exists()
        )
    finally:
        shutil.rmtree(work, ignore_errors=True)


# Values MoveIt rejects or uses wrongly (issue 36, wrong results with exit 0): Pilz's Cartesian
# rates, servo's scale namespace, move_group's lists. Oracle: a rate that is not a positive
# finite double, or a list that is not a list, exits 1; a scale that is not a mapping is named.
WRONG_TARGETS = {
    "rate": ("config/moveit.yaml", ("robot_description_planning", "cartesian_limits", "max_trans_vel")),
    "rot": ("config/moveit.yaml", ("robot_description_planning", "cartesian_limits", "max_rot_vel")),
    "scale": ("config/arm_servo.yaml", ("moveit_servo", "scale")),
    "pipelines": ("config/moveit.yaml", ("planning_pipelines",)),
    "sensors": ("config/moveit.yaml", ("sensors",)),
}
wrong_values = st.one_of(
    numbers,
    st.integers(-5, 5),
    st.sampled_from(["fast", "", "1.0", True, None, [], [1.0], {"x": 1.0}, ["ompl"]]),
)


def _jazzy_package(work: Path) -> Path:
    if "jazzy" not in _PACKAGE:
        base = Path(tempfile.mkdtemp(prefix="marm-fuzz-jazzy-"))
        atexit.register(shutil.rmtree, base, True)
        from tests.conftest import MARM_URDF

        args = ("--target", "ros2", "--ros-distro", "jazzy", "--trials", "10")
        assert_clean_exit(run("init", MARM_URDF, "--out", base / "pkg", *args), codes=(0,))
        _PACKAGE["jazzy"] = base / "pkg"
    return Path(shutil.copytree(_PACKAGE["jazzy"], work / "pkg"))


def _rejected(kind: str, value) -> bool | None:
    """Whether validate must exit 1 for `value` at `kind` (None: no exit claimed)."""
    if kind in ("rate", "rot"):
        return value is not None and not (isinstance(value, float) and 0 < value < math.inf)
    if kind in ("pipelines", "sensors") and isinstance(value, list):
        return None if all(isinstance(v, str) for v in value) else True  # names: other rules'
    if kind in ("pipelines", "sensors"):
        return value is not None and not isinstance(value, dict)
    return None


@FUZZ
@given(kind=st.sampled_from(sorted(WRONG_TARGETS)), value=wrong_values)
def test_fuzz_values_moveit_rejects(kind, value):
    work = _workdir()
    try:
        pkg = _jazzy_package(work)
        rel, keys = WRONG_TARGETS[kind]
        file = pkg / rel
        data = yaml.safe_load(file.read_text(encoding="utf-8"))
        parent = data["/**"]["ros__parameters"]
        for key in keys[:-1]:
            parent = parent[key]
        parent[keys[-1]] = value
        file.write_text(yaml.safe_dump(data), encoding="utf-8")
        result = run("validate", pkg, "--no-plan")
        assert_clean_exit(result, codes=(0, 1))
        assert "internal" not in result.output
        expected = _rejected(kind, value)
        if expected is not None and value not in ([], {}):
            assert (result.exit_code == 1) == expected, (kind, value, result.output)
        if kind == "scale" and value is not None and not isinstance(value, dict | list):
            assert "moveit_servo.scale" in result.output, (value, result.output)
        STATS[f"wrong value {kind}: exit {result.exit_code}"] += 1
    finally:
        shutil.rmtree(work, ignore_errors=True)

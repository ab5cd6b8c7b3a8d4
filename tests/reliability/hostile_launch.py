"""Hostile launch files built on the fly (issue 36): args and Python values that double
themselves, files that include themselves, Python launch files too large or nested too deeply."""

from __future__ import annotations

from pathlib import Path

ROS1_LAUNCH = "launch/demo.launch"
ROS2_LAUNCH = "launch/demo.launch.xml"


def growing_args(ros2: bool, steps: int, copies: int = 2) -> str:
    """`<arg>`s each `copies` times the one before: `copies ** steps` characters at the end."""
    use = "var" if ros2 else "arg"
    lines = ['<arg name="g0" default="ab"/>']
    for i in range(1, steps + 1):
        lines.append(f'<arg name="g{i}" default="{f"$({use} g{i - 1})" * copies}"/>')
    return "\n".join(lines)


def with_args(pkg: Path, ros2: bool, text: str) -> None:
    launch = pkg / (ROS2_LAUNCH if ros2 else ROS1_LAUNCH)
    body = launch.read_text(encoding="utf-8")
    launch.write_text(body.replace("<launch>", f"<launch>\n{text}", 1), encoding="utf-8")


def self_including(pkg: Path, ros2: bool, copies: int, new_args: bool) -> str:
    """launch/self.launch[.xml] including itself `copies` times (each with its own longer arg)."""
    rel = "launch/self.launch.xml" if ros2 else "launch/self.launch"
    find = "find-pkg-share" if ros2 else "find"
    use = "var" if ros2 else "arg"
    name = pkg.name if not (pkg / "package.xml").is_file() else _package_name(pkg)
    inner = (f'<arg name="a" value="$({use} a){k}"/>' if new_args else "" for k in range(copies))
    includes = "".join(f'<include file="$({find} {name})/{rel}">{arg}</include>\n' for arg in inner)
    (pkg / rel).write_text(f'<launch>\n<arg name="a" default="x"/>\n{includes}</launch>\n', encoding="utf-8")
    return rel


def _package_name(pkg: Path) -> str:
    text = (pkg / "package.xml").read_text(encoding="utf-8")
    return text.split("<name>", 1)[1].split("</name>", 1)[0]


def python_launch(kind: str, n: int) -> str:
    """A Python launch file of `kind`: a sum of `n` terms, `n` nested `not`/`-`, a string, list or
    f-string doubled `n` times, a list nested `n` deep by reference, or `n` bytes of comment."""
    if kind == "sum":
        return "x = " + " + ".join(['"a"'] * n) + "\n"
    if kind == "unary":
        return "x = " + "not " * n + "y\n"
    if kind == "negations":
        return "a0 = 1\n" + "".join(f"a{i} = -(-a{i - 1})\n" for i in range(1, n)) + "x = " + "-" * n + "a0\n"
    if kind == "string":
        return 'a = "ab"\n' + "a = a + a\n" * n + 'p = a + ".yaml"\n'
    if kind == "list":
        return 'a = ["ab"]\n' + "a = a + a\n" * n
    if kind == "nested list":  # 2**n items when printed, n + 1 lists in memory
        return 'a = ["ab"]\n' + "a = [a, a]\n" * n + "b = str(a)\nc = f'{a}'\nd = PathJoinSubstitution(a)\n"
    if kind == "fstring":
        return 'a = "ab"\n' + 'a = f"{a}{a}"\n' * n + "b = PathJoinSubstitution([a, a])\n"
    if kind == "size":
        return "# " + "x" * n + "\n"
    raise ValueError(kind)

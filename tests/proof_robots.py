"""Robots for the proof tests: a toy whose contacts are rarer than sampling sees, and random
URDFs (hypothesis) of boxes, cylinders, spheres and meshes on revolute, continuous, prismatic,
fixed and mimic joints.

`RARE` (root `base`), written to tmp_path by tests:
- `pointer` turns about z (continuous) at the origin: a 1 mm thin rod reaching 0.525 m; `nub`,
  a 2 mm ball fixed 0.5255 m out at angle 1 rad, touches it only within about +-0.005 rad of
  that angle, in about 0.2 % of the turn: a few dozen trials miss it, a proof finds it;
- `slider` slides along x over [0, 1] at y = 1 with `follower` mimicking it at twice its travel
  (a 2 mm ball); `stop`, a 2 mm ball at x = 1.0, y = 1.3, is touched by `follower` only
  near slider = 0.5 (about 0.4 % of the range);
- `far`, a box 10 m away: Never and proved with everything;
- `shell` (a 1 m mesh cube, a surface) holds `inside`, a ball sliding over [0, 0.3] from its
  centre: never touching the surface, it is Never and proved (the convex hulls overlap all the
  time: only the surface distance proves it).
"""

from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

from tests.helpers import urdf

AXES = ("1 0 0", "0 1 0", "0 0 1", "0.6 0.8 0", "0 0.6 -0.8")


def _fixed(name: str, parent: str, child: str, xyz: str) -> str:
    return (
        f'<joint name="{name}" type="fixed"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}"/></joint>'
    )


def _link(name: str, geometry: str, xyz: str = "0 0 0", rpy: str = "0 0 0") -> str:
    return (
        f'<link name="{name}"><collision><origin xyz="{xyz}" rpy="{rpy}"/>'
        f"<geometry>{geometry}</geometry></collision></link>"
    )


def rare_urdf(mesh_path: str) -> str:
    """The RARE toy (see the module doc); `mesh_path`: a 1 m cube mesh (shell)."""
    ball = '<sphere radius="0.002"/>'
    body = [
        _link("base", '<box size="0.05 0.05 0.05"/>', "0 0 -0.2"),
        _link("pointer", '<cylinder radius="0.001" length="0.45"/>', "0.3 0 0", "0 1.5707963 0"),
        '<joint name="turn" type="continuous"><parent link="base"/><child link="pointer"/>'
        '<axis xyz="0 0 1"/></joint>',
        _link("nub", ball),
        _fixed("jnub", "base", "nub", f"{0.5255 * np.cos(1.0):.6f} {0.5255 * np.sin(1.0):.6f} 0"),
        _link("slider", '<box size="0.01 0.01 0.01"/>'),
        '<joint name="slide" type="prismatic"><parent link="base"/><child link="slider"/>'
        '<origin xyz="0 1 0"/><axis xyz="1 0 0"/><limit lower="0" upper="1" velocity="1" effort="1"/></joint>',
        _link("follower", ball),
        '<joint name="follow" type="prismatic"><parent link="base"/><child link="follower"/>'
        '<origin xyz="0 1.3 0"/><axis xyz="1 0 0"/><limit lower="0" upper="2" velocity="1" effort="1"/>'
        '<mimic joint="slide" multiplier="2" offset="0"/></joint>',
        _link("stop", ball),
        _fixed("jstop", "base", "stop", "1.0 1.3 0"),
        _link("far", '<box size="0.1 0.1 0.1"/>'),
        _fixed("jfar", "base", "far", "10 0 0"),
        _link("shell", f'<mesh filename="file://{mesh_path}"/>'),
        _fixed("jshell", "base", "shell", "0 0 5"),
        _link("inside", '<sphere radius="0.05"/>'),
        '<joint name="jin" type="prismatic"><parent link="base"/><child link="inside"/>'
        '<origin xyz="0 0 5"/><axis xyz="1 0 0"/><limit lower="0" upper="0.3" velocity="1" effort="1"/></joint>',
    ]
    return urdf("\n".join(body), name="rare")


def write_meshes(folder) -> dict[str, str]:
    """Meshes for random robots: a cube, a ball, an L of two boxes, an open box (a surface with
    a hole); returns name -> path."""
    import trimesh

    cube = trimesh.creation.box((0.1, 0.1, 0.1))
    ball = trimesh.creation.icosphere(subdivisions=2, radius=0.05)
    ell = trimesh.util.concatenate(
        [
            trimesh.creation.box((0.15, 0.04, 0.04)),
            trimesh.creation.box((0.04, 0.04, 0.15)).apply_translation((0.055, 0, 0.055)),
        ]
    )
    open_box = trimesh.creation.box((0.12, 0.12, 0.12))
    open_box = trimesh.Trimesh(open_box.vertices, open_box.faces[open_box.face_normals[:, 2] < 0.5])
    paths = {}
    for name, mesh in (("cube", cube), ("ball", ball), ("ell", ell), ("open_box", open_box)):
        path = folder / f"{name}.stl"
        mesh.export(path)
        paths[name] = str(path)
    paths["big_cube"] = str(folder / "big_cube.stl")
    trimesh.creation.box((1.0, 1.0, 1.0)).export(paths["big_cube"])
    return paths


def _numbers(low: float, high: float, count: int) -> st.SearchStrategy:
    return st.lists(st.floats(low, high, allow_nan=False), min_size=count, max_size=count)


@st.composite
def geometries(draw, meshes: dict[str, str]) -> str:
    kind = draw(st.sampled_from(("box", "cylinder", "sphere", "mesh")))
    if kind == "box":
        return '<box size="{:.4f} {:.4f} {:.4f}"/>'.format(*draw(_numbers(0.02, 0.2, 3)))
    if kind == "cylinder":
        radius, length = draw(_numbers(0.01, 0.08, 1))[0], draw(_numbers(0.02, 0.25, 1))[0]
        return f'<cylinder radius="{radius:.4f}" length="{length:.4f}"/>'
    if kind == "sphere":
        return f'<sphere radius="{draw(_numbers(0.01, 0.1, 1))[0]:.4f}"/>'
    name = draw(st.sampled_from(sorted(k for k in meshes if k != "big_cube")))
    scale = draw(st.floats(0.5, 1.8))
    return f'<mesh filename="file://{meshes[name]}" scale="{scale:.3f} {scale:.3f} {scale:.3f}"/>'


@st.composite
def random_robots(draw, meshes: dict[str, str]) -> str:
    """A random tree of 3 to 6 links (see the module doc); joints' origins keep links close.
    Half of them are planar: every turning axis parallel to z, sliding axes across it (the
    separating-direction bound proves their pairs in few boxes)."""
    count = draw(st.integers(3, 6))
    planar = draw(st.booleans())
    parts = [_link("l0", draw(geometries(meshes)))]
    movers: list[tuple[str, str]] = []  # (joint, type) of joints a mimic may follow
    for i in range(1, count):
        parts.append(_shaped_link(draw, f"l{i}", meshes))
        parts.append(_random_joint(draw, i, movers, planar))
    return urdf("\n".join(parts), name="random")


def _shaped_link(draw, name: str, meshes: dict[str, str]) -> str:
    xyz = "{:.3f} {:.3f} {:.3f}".format(*draw(_numbers(-0.05, 0.05, 3)))
    rpy = "{:.3f} {:.3f} {:.3f}".format(*draw(_numbers(-np.pi, np.pi, 3)))
    return _link(name, draw(geometries(meshes)), xyz, rpy)


def _random_joint(draw, i: int, movers: list[tuple[str, str]], planar: bool = False) -> str:
    parent = f"l{draw(st.integers(0, i - 1))}"
    kind = draw(st.sampled_from(("revolute", "revolute", "continuous", "prismatic", "fixed")))
    xyz = "{:.3f} {:.3f} {:.3f}".format(*draw(_numbers(-0.2, 0.2, 3)))
    rpy = "0 0 {:.3f}".format(*draw(_numbers(-np.pi, np.pi, 1)))
    if not planar:
        rpy = "{:.3f} {:.3f} {:.3f}".format(*draw(_numbers(-np.pi, np.pi, 3)))
    head = f'<joint name="j{i}" type="{kind}"><parent link="{parent}"/><child link="l{i}"/><origin xyz="{xyz}" rpy="{rpy}"/>'
    if kind == "fixed":
        return head + "</joint>"
    axes = AXES if not planar else ("1 0 0", "0.6 0.8 0") if kind == "prismatic" else ("0 0 1", "0 0 -1")
    head += f'<axis xyz="{draw(st.sampled_from(axes))}"/>'
    if kind == "revolute":
        low, high = draw(st.floats(-3.1, 0.0)), draw(st.floats(0.0, 3.1))
    else:
        low, high = draw(st.floats(-0.2, 0.0)), draw(st.floats(0.0, 0.2))
    limit = (
        f'<limit lower="{low:.3f}" upper="{high:.3f}" velocity="1" effort="1"/>'
        if kind != "continuous"
        else ""
    )
    same = [name for name, leader_kind in movers if (leader_kind == "prismatic") == (kind == "prismatic")]
    mimic = ""
    if same and draw(st.integers(0, 3)) == 0:
        multiplier = draw(st.sampled_from((1.0, -1.0, 0.5, 2.0)))
        offset = draw(st.floats(-0.2, 0.2))
        mimic = (
            f'<mimic joint="{draw(st.sampled_from(same))}" multiplier="{multiplier}" offset="{offset:.3f}"/>'
        )
    else:
        movers.append((f"j{i}", kind))
    return head + limit + mimic + "</joint>"


def tilting_bar_urdf() -> str:
    """A plate (root `plate`) under a bar that pans about z and tilts about y: the plate's
    normal is the pan axis, so the pair's separating-direction bound works along z, less what
    the tilt moves the bar along it (see test_proof)."""
    return urdf(
        "\n".join(
            [
                _link("plate", '<box size="1 1 0.01"/>'),
                _link("turret", '<sphere radius="0.01"/>', "0 0 0.5"),
                '<joint name="pan" type="revolute"><parent link="plate"/><child link="turret"/>'
                '<axis xyz="0 0 1"/><limit lower="-3" upper="3" velocity="1" effort="1"/></joint>',
                _link("bar", '<box size="0.4 0.05 0.02"/>', "0.2 0 0"),
                '<joint name="tilt" type="revolute"><parent link="turret"/><child link="bar"/>'
                '<origin xyz="0 0 0.2"/><axis xyz="0 1 0"/><limit lower="-0.4" upper="0.4" velocity="1" effort="1"/>'
                "</joint>",
            ]
        ),
        name="tilting_bar",
    )


def speck_urdf(mesh_path: str) -> str:
    """A 1 mm cube (`speck`, on `arm`, which turns about z and slides out along its x over
    [0, 2]) and a 1 m mesh cube (`shell`, a surface) centred 1.5 m out along x: the speck is in
    contact only while it straddles the surface, a shell 1 mm thick (the PR2's gripper
    accelerometer, a 1 mm box, against the other arm's wrist mesh)."""
    return urdf(
        "\n".join(
            [
                _link("base", '<sphere radius="0.01"/>', "0 0 -0.5"),
                _link("turner", '<sphere radius="0.001"/>', "0 0 -0.2"),
                '<joint name="turn" type="revolute"><parent link="base"/><child link="turner"/>'
                '<axis xyz="0 0 1"/><limit lower="-0.6" upper="0.6" velocity="1" effort="1"/></joint>',
                _link("speck", '<box size="0.001 0.001 0.001"/>'),
                '<joint name="out" type="prismatic"><parent link="turner"/><child link="speck"/>'
                '<axis xyz="1 0 0"/><limit lower="0" upper="2" velocity="1" effort="1"/></joint>',
                _link("shell", f'<mesh filename="file://{mesh_path}"/>'),
                _fixed("jshell", "base", "shell", "1.5 0 0"),
            ]
        ),
        name="speck",
    )

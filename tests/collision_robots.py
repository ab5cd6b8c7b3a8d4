"""Tiny URDFs with a collision matrix known by construction (written to tmp_path by tests).

`TOY` (root `base`, a 0.2 m cube at the origin), every sphere radius 0.05 m:
- `slider_a` slides along x over [0, 1] at y=1; `block` (fixed) spans x in [0.06, 1.0] there:
  they touch for q > 0.01, 99 % of the range, but not at the default q=0 -> Always.
- `slider_c` slides over [0, 1] at y=-1 past `post` (x in [0.4, 0.6]): touching for q in
  (0.35, 0.65), 30 % of the range -> stays enabled.
- `slider_d` slides over [-1, 1] at y=2 next to `stop` (x in [0.04, 0.2]): touching at the
  default q=0 and for q in (-0.01, 0.25), 13 % of the range -> Default.
- `tip` hangs below two geometry-less links (`hub`, `hub2`) at z=3 -> Adjacent to `base`.
- `far` sits at x=10 -> Never with everything it is not fixed to.
"""

from __future__ import annotations

from tests.helpers import urdf

SPHERE = '<collision><geometry><sphere radius="0.05"/></geometry></collision>'


def _box_link(name: str, size: str) -> str:
    return f'<link name="{name}"><collision><geometry><box size="{size}"/></geometry></collision></link>'


def _fixed(name: str, child: str, xyz: str, parent: str = "base") -> str:
    return (
        f'<joint name="{name}" type="fixed"><parent link="{parent}"/><child link="{child}"/>'
        f'<origin xyz="{xyz}"/></joint>'
    )


def _slider(name: str, child: str, xyz: str, lower: float, upper: float) -> str:
    return (
        f'<link name="{child}">{SPHERE}</link>'
        f'<joint name="{name}" type="prismatic"><parent link="base"/><child link="{child}"/>'
        f'<origin xyz="{xyz}"/><axis xyz="1 0 0"/>'
        f'<limit lower="{lower}" upper="{upper}" velocity="1" effort="1"/></joint>'
    )


TOY = urdf(
    "\n".join(
        [
            _box_link("base", "0.2 0.2 0.2"),
            _slider("ja", "slider_a", "0 1 0", 0.0, 1.0),
            _box_link("block", "0.94 0.2 0.2"),
            _fixed("jblock", "block", "0.53 1 0"),
            _slider("jc", "slider_c", "0 -1 0", 0.0, 1.0),
            _box_link("post", "0.2 0.2 0.2"),
            _fixed("jpost", "post", "0.5 -1 0"),
            _slider("jd", "slider_d", "0 2 0", -1.0, 1.0),
            _box_link("stop", "0.16 0.2 0.2"),
            _fixed("jstop", "stop", "0.12 2 0"),
            '<link name="hub"/><link name="hub2"/>',
            '<joint name="jh" type="revolute"><parent link="base"/><child link="hub"/>'
            '<origin xyz="0 0 3"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>',
            _fixed("jh2", "hub2", "0 0 0.1", parent="hub"),
            f'<link name="tip">{SPHERE}</link>',
            '<joint name="jt" type="continuous"><parent link="hub2"/><child link="tip"/>'
            '<origin xyz="0.2 0 0"/><axis xyz="0 0 1"/></joint>',
            _box_link("far", "0.1 0.1 0.1"),
            _fixed("jfar", "far", "10 0 0"),
        ]
    ),
    name="toy",
)


def mesh_shell_urdf(mesh_path: str) -> str:
    """A 1 m cube as a mesh (`shell`) and as a box (`solid`), each with a sphere sliding out of it.

    `inner_m` starts at the shell's centre and slides along x over [0, 1]: inside (not touching
    the surface) for q < 0.45, crossing it for q in (0.45, 0.55), outside beyond.
    """
    body = [
        _box_link("base", "0.1 0.1 0.1"),
        f'<link name="shell"><collision><geometry><mesh filename="file://{mesh_path}"/></geometry></collision></link>',
        _fixed("jshell", "shell", "0 0 5"),
        _box_link("solid", "1 1 1"),
        _fixed("jsolid", "solid", "0 5 5"),
    ]
    for suffix, y in (("m", 0), ("s", 5)):
        body.append(
            f'<link name="inner_{suffix}">{SPHERE}</link>'
            f'<joint name="j{suffix}" type="prismatic"><parent link="base"/><child link="inner_{suffix}"/>'
            f'<origin xyz="0 {y} 5"/><axis xyz="1 0 0"/><limit lower="0" upper="1" velocity="1" effort="1"/></joint>'
        )
    return urdf("\n".join(body), name="shells")

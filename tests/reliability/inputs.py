"""Hostile inputs built on the fly (kept small: each is the least that showed the problem)."""

from __future__ import annotations

from tests.helpers import urdf

BOX = '<collision><geometry><box size="0.01 0.01 0.01"/></geometry></collision>'


def chain_urdf(n: int, geometry_every: int = 1) -> str:
    """A serial chain of `n` revolute joints (n + 1 links); every `geometry_every`-th link has a box."""
    links = [f'<link name="l{i}">{BOX if i % geometry_every == 0 else ""}</link>' for i in range(n + 1)]
    joints = [
        f'<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
        f'<origin xyz="0 0 0.02"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>'
        for i in range(n)
    ]
    return urdf("\n".join(links + joints), name="chain")


def alias_bomb(levels: int = 9) -> str:
    """`groups:` a list that, aliases followed, holds 9**levels strings in a few hundred bytes."""
    lines = ['a0: &a0 ["x", "x", "x", "x", "x", "x", "x", "x", "x"]']
    for i in range(1, levels):
        refs = ", ".join([f"*a{i - 1}"] * 9)
        lines.append(f"a{i}: &a{i} [{refs}]")
    return "\n".join(lines) + f"\ngroups: *a{levels - 1}\n"


def subgroup_chain(n: int) -> dict:
    """A SPEC whose groups nest `n` deep: g0 > g1 > ... > arm."""
    groups = [{"name": "arm", "chain": {"base": "base_link", "tip": "grasping_frame"}}]
    groups += [{"name": f"g{i}", "subgroups": [f"g{i + 1}" if i + 1 < n else "arm"]} for i in range(n)]
    return {"groups": groups}


def subgroup_diamonds(n: int) -> dict:
    """`n` diamonds in a row: g_i has subgroups a_i and b_i, both of which have g_(i+1)."""
    groups = [{"name": "arm", "chain": {"base": "base_link", "tip": "grasping_frame"}}]
    for i in range(n):
        nxt = f"g{i + 1}" if i + 1 < n else "arm"
        groups += [
            {"name": f"g{i}", "subgroups": [f"a{i}", f"b{i}"]},
            {"name": f"a{i}", "subgroups": [nxt]},
            {"name": f"b{i}", "subgroups": [nxt]},
        ]
    return {"groups": groups}


def many_poses(n: int) -> str:
    """`n` SRDF group_states p000, p001, ... of the marm's arm, joint1 from -1 in steps of 0.01."""
    zeros = "".join(f'<joint name="joint{j}" value="0"/>' for j in range(2, 7))
    return "".join(
        f'<group_state name="p{i:03d}" group="arm"><joint name="joint1" value="{-1 + i / 100:.2f}"/>'
        f"{zeros}</group_state>\n"
        for i in range(n)
    )

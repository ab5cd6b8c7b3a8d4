"""Packages for the report's tests: the marm from `init`, and a copy with a pose in collision and
a stale Never pair."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np

from tests.conftest import MARM_URDF
from tests.validate_helpers import generate_marm


def marm_package(root: Path) -> Path:
    """The marm's MoveIt 1 package (`init` with the ArbotiX driver) under `root`."""
    return generate_marm(root, "ros1")


def broken_marm(root: Path) -> Path:
    """A copy of the marm package whose `ready` pose is in self-collision (pose.collision) and
    whose most often colliding enabled pair is marked Never (matrix.stale)."""
    from marm_setup.collision.matrix import trial_samples
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.robot.load import load_robot
    from marm_setup.setup.srdf import allowed_pairs, read_srdf

    good = marm_package(root)
    pkg = root / f"broken_{good.name}"  # same depth: marm_setup.yaml's relative package path holds
    if pkg.exists():
        return pkg
    shutil.copytree(good, pkg)
    srdf_file = pkg / "config" / "marm.srdf"
    srdf = read_srdf(srdf_file)
    robot = load_robot(MARM_URDF, {}, [])
    scene = CollisionScene(robot)
    checked = scene.enabled_pairs(allowed_pairs(srdf, scene.candidate_pairs))
    q = trial_samples(robot, 0, 1000)
    counts = scene.collision_counts(scene.link_poses(q), scene.pair_ids(checked))
    a, b = stale = checked[int(np.argmax(counts))]
    still = tuple(p for p in checked if p != stale)
    text = _colliding_ready(srdf_file.read_text(encoding="utf-8"), robot, scene, still)
    text = text.replace(
        "</robot>", f'  <disable_collisions link1="{a}" link2="{b}" reason="Never"/>\n</robot>'
    )
    srdf_file.write_text(text, encoding="utf-8")
    return pkg


def _colliding_ready(text: str, robot, scene, pairs) -> str:
    """The SRDF text with the arm's `ready` pose set to the first seeded random arm
    configuration in which two arm links collide."""
    block = re.search(r'<group_state name="ready" group="arm">.*?</group_state>', text, re.S)
    assert block is not None, "no ready pose"
    names = re.findall(r'<joint name="([^"]+)"', block.group(0))
    index = [robot.active_joint_names.index(n) for n in names]
    rng = np.random.default_rng(1)
    lower = np.array([robot.joint(n).bounds[0] for n in names])
    upper = np.array([robot.joint(n).bounds[1] for n in names])
    arm_links = {robot.joint(n).child for n in names}
    for _ in range(5000):
        q = np.array([j.default_position for j in robot.active_joints])
        q[index] = lower + rng.random(len(names)) * (upper - lower)
        hit = scene.first_collisions(q[None], pairs)[0]
        if hit is not None and (hit[0] in arm_links or hit[1] in arm_links):
            new = block.group(0)
            for name, value in zip(names, q[index], strict=True):
                new = re.sub(rf'(<joint name="{name}" value=")[^"]*(")', rf"\g<1>{value:.5f}\2", new)
            return text.replace(block.group(0), new)
    raise AssertionError("no colliding arm configuration found")

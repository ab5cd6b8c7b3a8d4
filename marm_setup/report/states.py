"""The robot states the page can show, each with the link pairs in contact there.

States: MoveIt's default state, the demo's start state, every named pose (over the start state,
as validate checks it), the state each finding's evidence names (a pose in collision, a
Never pair seen colliding), and each proof witness of a pair the SRDF disables. Contacts are the pairs MoveIt would check under the SRDF (a
disabled pair touching is no contact), except for a finding's state, whose contact is the pair
the finding is about (a stale Never pair is disabled, yet collides there).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.findings import Finding
from marm_setup.robot import RobotModel
from marm_setup.setup import Srdf, allowed_pairs, pose_configuration, start_configuration

if TYPE_CHECKING:
    from marm_setup.collision import CollisionMatrix, CollisionScene

Pair = tuple[str, str]


@dataclass(frozen=True, eq=False)
class RobotState:
    """A state to show: `key` unique on the page, `title` for people, `group` the group it
    poses (None: the whole robot), `q` the active configuration, `contacts` pairs in contact."""

    key: str
    title: str
    group: str | None
    q: np.ndarray
    contacts: tuple[Pair, ...]
    note: str = ""


def robot_states(
    srdf: Srdf,
    robot: RobotModel,
    scene: CollisionScene,
    start: Mapping[str, float],
    findings: Sequence[Finding],
) -> tuple[RobotState, ...]:
    """Default, start, the named poses (SRDF order), then each finding's evidence state."""
    checked = scene.enabled_pairs(allowed_pairs(srdf, scene.candidate_pairs))
    known = {s.group for s in srdf.group_states} & {g.name for g in srdf.groups}
    out = [
        RobotState("default", "default state", None, start_configuration(robot), ()),
        RobotState("start", "demo start state", None, start_configuration(robot, start), ()),
    ]
    out += [
        RobotState(f"pose:{s.group}:{s.name}", s.name, s.group, pose_configuration(s, robot, start), ())
        for s in srdf.group_states
        if s.group in known
    ]
    out = [_with_contacts(state, scene, checked) for state in out]
    out += [_evidence_state(k, f, robot) for k, f in enumerate(findings) if f.evidence is not None]
    return tuple(out)


def witness_states(matrix: CollisionMatrix, srdf: Srdf, robot: RobotModel) -> tuple[RobotState, ...]:
    """Per pair the SRDF disables that a proof of `matrix` found in contact, its witness state
    (other joints at their default), the pair as the contact."""
    disabled = {d.pair for d in srdf.disabled}
    out = []
    for stats in matrix.stats:
        proof = stats.proof
        if proof is None or proof.outcome != "collides" or stats.pair not in disabled:
            continue
        values = dict(proof.witness)
        q = np.array([values.get(j.name, j.default_position) for j in robot.active_joints])
        title = f"{stats.link1} – {stats.link2} in contact"
        note = "a proof found this pair, which the SRDF disables, in contact here"
        out.append(RobotState(f"witness:{stats.link1}:{stats.link2}", title, None, q, (stats.pair,), note))
    return tuple(out)


def _with_contacts(state: RobotState, scene: CollisionScene, pairs: tuple[Pair, ...]) -> RobotState:
    """`state` with the pairs of `pairs` in collision there."""
    if not pairs:
        return state
    counts = scene.collision_counts(scene.link_poses(state.q[None]), scene.pair_ids(pairs))
    contacts = tuple(pair for pair, n in zip(pairs, counts.tolist(), strict=True) if n)
    return RobotState(state.key, state.title, state.group, state.q, contacts, state.note)


def _evidence_state(index: int, finding: Finding, robot: RobotModel) -> RobotState:
    """The state a finding's evidence names, its links as the contact."""
    assert finding.evidence is not None
    values = dict(finding.evidence.state)
    q = np.array([values.get(j.name, j.default_position) for j in robot.active_joints])
    links = sorted(finding.evidence.links)
    contacts = ((links[0], links[1]),) if len(links) == 2 else ()
    title = f"{finding.rule}: {finding.element}"
    return RobotState(f"finding:{index}", title, None, q, contacts, finding.message)

"""`collisions`: the self-collision matrix of a robot, an SRDF updated with it (or a minimal one
written) and its heat map; `collisions DIR`: a generated package's matrix recomputed into its
marm_setup.yaml and SRDF together."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.flows.settings import MatrixSettings
from marm_setup.names import did_you_mean, with_hint

if TYPE_CHECKING:
    import numpy as np

    from marm_setup.collision import CollisionMatrix, DisabledPair, Progress
    from marm_setup.robot import RobotModel


@dataclass(frozen=True)
class CollisionsRequest:
    """What `collisions URDF` computes and writes (see its options)."""

    matrix: MatrixSettings = MatrixSettings()  # its keep_disabled: keep the SRDF's pairs
    check_default: bool = True
    check_always: bool = True
    default_pose: str | None = None  # a pose of `srdf` as the default state
    srdf: Path | None = None  # updated (in place unless `output`)
    output: Path | None = None
    force: bool = False  # update an SRDF of another robot anyway
    report: Path | None = None  # .svg or .html
    distances: bool = False  # the closest distance of each Never pair (json, report)
    verbose: bool = False  # list each pair the SRDF update adds and removes


@dataclass(frozen=True)
class CollisionsResult:
    matrix: CollisionMatrix
    disabled: tuple[DisabledPair, ...]  # what the written SRDF disables (the matrix's, or merged)
    messages: tuple[str, ...]  # for stderr, in order: files written, the SRDF's changes


def run_collisions(
    request: CollisionsRequest, robot: RobotModel, progress: Progress | None = None
) -> CollisionsResult:
    """Compute the matrix; update or write the SRDF and the report the request names."""
    from marm_setup.collision import compute_cached_matrix, load_srdf_text, read_srdf_entries

    srdf, srdf_text = request.srdf, None
    if srdf is not None:
        srdf_text = load_srdf_text(srdf, shown=str(srdf))
        read_srdf_entries(srdf_text, shown=str(srdf))  # fail on a bad SRDF before the long part
        if not request.force:
            _check_same_robot(robot, srdf_text, str(srdf))
    default_q = None
    if request.default_pose is not None and srdf_text is not None:
        default_q = pose_configuration(robot, srdf_text, request.default_pose, str(srdf))
    matrix = compute_cached_matrix(
        robot,
        padding=request.matrix.padding,
        **request.matrix.matrix_options(),
        check_default=request.check_default,
        check_always=request.check_always,
        default_q=default_q,
        progress=progress,
        distances=request.distances,
    )
    messages: list[str] = []
    disabled = _write_srdf(robot.name, matrix, request, srdf_text, messages)
    if srdf_text is not None and srdf is not None:
        messages += srdf_changes(srdf_text, disabled, str(srdf), verbose=request.verbose)
    if request.report is not None:
        _write_report(request.report, matrix, robot, disabled)
        messages.append(f"wrote {request.report}")
    return CollisionsResult(matrix, tuple(disabled), tuple(messages))


def pose_configuration(robot: RobotModel, srdf_text: str, name: str, shown: str) -> np.ndarray:
    """The default configuration with the SRDF pose `name` laid over it: a pose of any group,
    composite ones included; where several groups have a pose of that name (a `home` per
    group), all of them. Multi-DOF values (a virtual joint's) do not move the robot's links."""
    from marm_setup.robot import default_configuration
    from marm_setup.setup import parse_srdf_string

    states = parse_srdf_string(srdf_text, shown).group_states
    named = [s for s in states if s.name == name]
    if not named:
        names = sorted({s.name for s in states})
        message = with_hint(f"unknown pose '{name}'", did_you_mean(name, names))
        raise InputError(message, path=shown, element="--default-pose")
    q = default_configuration(robot)
    index = {joint: i for i, joint in enumerate(robot.active_joint_names)}
    for joint, value in (v for s in named for v in s.values):
        if joint in index:
            q[index[joint]] = value
    return q


def _write_srdf(
    robot_name: str,
    matrix: CollisionMatrix,
    request: CollisionsRequest,
    srdf_text: str | None,
    messages: list[str],
) -> tuple[DisabledPair, ...]:
    """Write the SRDF the request asks for; return the final disabled pairs."""
    srdf, output = request.srdf, request.output
    if srdf is None and output is None:
        return matrix.disabled  # nothing to write: no Jinja, no writer imported
    from marm_setup.collision import render_minimal_srdf, unproved_notes, update_srdf
    from marm_setup.render import write_text_atomic

    notes = unproved_notes(matrix)
    if srdf is None or srdf_text is None:  # the text is read whenever --srdf is given
        if output is not None:
            text = render_minimal_srdf(robot_name, matrix.disabled, notes)
            write_text_atomic(output, text, shown=str(output))
            messages.append(f"wrote {output}")
        return matrix.disabled
    text, disabled = update_srdf(
        srdf_text, matrix.disabled, keep=request.matrix.keep_disabled, shown=str(srdf), notes=notes
    )
    target = output or srdf
    write_text_atomic(target, text, shown=str(target), follow_symlink=output is None)  # --srdf in place
    messages.append(f"wrote {target}")
    return disabled


def _pair_changes(old_pairs: Sequence[DisabledPair], new: Sequence[DisabledPair]) -> str:
    old = {p.pair: p for p in old_pairs}
    now = {p.pair: p for p in new}
    added = [now[k] for k in sorted(now) if k not in old or old[k].reason != now[k].reason]
    removed = [old[k] for k in sorted(old) if k not in now or old[k].reason != now[k].reason]
    counts = [
        f"{sign}{sum(p.reason.value == r for p in pairs)} {r}"
        for sign, pairs in (("+", added), ("-", removed))
        for r in sorted({p.reason.value for p in pairs})
    ]
    return ", ".join(counts) if counts else "none"


def _check_same_robot(robot: RobotModel, srdf_text: str, shown: str) -> None:
    """An SRDF of another robot (its name, or links its pairs and groups name) is refused: updating
    it would rewrite a file the matrix does not belong to."""
    from marm_setup.setup import parse_srdf_string

    srdf = parse_srdf_string(srdf_text, shown)
    if srdf.robot_name and srdf.robot_name != robot.name:
        message = (
            f"the SRDF is robot '{srdf.robot_name}', the URDF is '{robot.name}' (--force updates it anyway)"
        )
        raise InputError(message, path=shown, element="robot")
    named = {x for p in srdf.disabled for x in p.pair}
    named |= {x for g in srdf.groups for x in (*g.links, *((g.chain.base, g.chain.tip) if g.chain else ()))}
    unknown = sorted(named - set(robot.link_map))
    if unknown:
        shown_links = ", ".join(unknown[:3]) + (f" and {len(unknown) - 3} more" if len(unknown) > 3 else "")
        message = f"links not in the URDF: {shown_links} (another robot's SRDF? --force updates it anyway)"
        raise InputError(message, path=shown, element="robot")


def srdf_changes(old_text: str, new: Sequence[DisabledPair], shown: str, *, verbose: bool) -> list[str]:
    """What the update changed: pairs added and removed per reason, and with `verbose` each pair."""
    from marm_setup.setup import parse_srdf_string

    old_pairs = parse_srdf_string(old_text, shown).disabled
    lines = [f"changes to {shown}: {_pair_changes(old_pairs, new)}"]
    if verbose:
        old = {p.pair: p for p in old_pairs}
        now = {p.pair: p for p in new}
        lines += [
            f"  + {p.link1} {p.link2} ({p.reason.value})" for k, p in sorted(now.items()) if old.get(k) != p
        ]
        lines += [
            f"  - {p.link1} {p.link2} ({p.reason.value})" for k, p in sorted(old.items()) if now.get(k) != p
        ]
    return lines


def _write_report(
    report: Path, matrix: CollisionMatrix, robot: RobotModel, disabled: Sequence[DisabledPair]
) -> None:
    from marm_setup.collision import render_matrix_html, render_matrix_svg
    from marm_setup.render import write_text_atomic

    links = [name for name in robot.links_in_tree_order if robot.link(name).has_geometry]
    svg = render_matrix_svg(matrix, robot.name, links, disabled)
    text = render_matrix_html(svg, robot.name) if report.suffix.lower() == ".html" else svg
    write_text_atomic(report, text, shown=str(report))


@dataclass(frozen=True)
class PackageCollisionsResult:
    """The files written (their status lines) and a summary of the pairs that changed."""

    status_lines: tuple[str, ...]
    summary: str


def run_package_collisions(
    pkg: Path, settings: MatrixSettings, *, force: bool, progress: Progress | None = None
) -> PackageCollisionsResult:
    """Recompute a generated package's matrix into its marm_setup.yaml and SRDF together (its
    User pairs kept), so the next `render` has nothing to disagree with; with `force` a
    hand-edited file is overwritten (kept as `.orig`, as render does)."""
    from marm_setup.collision import DisabledReason
    from marm_setup.flows.render import load_package_setup
    from marm_setup.flows.write import collision_settings, compute_matrix
    from marm_setup.render import apply_writes, format_change, plan_writes, render_package

    model, robot = load_package_setup(pkg)
    matrix = compute_matrix(robot, **settings.matrix_options(), progress=progress, distances=False)
    computed = {p.pair for p in matrix.disabled}
    user = [p for p in model.collision.disabled if p.reason is DisabledReason.USER and p.pair not in computed]
    disabled = tuple(sorted((*matrix.disabled, *user)))
    new = dataclasses.replace(model, collision=collision_settings(matrix, disabled, robot))
    changes = plan_writes(render_package(new, robot), pkg)
    apply_writes(changes, pkg, force=force)
    lines = tuple(
        line for line in (format_change(c, forced=force) for c in changes) if not line.startswith("unchanged")
    )
    summary = f"marm_setup.yaml and the SRDF: {len(disabled)} disabled pairs (changes: {_pair_changes(model.collision.disabled, disabled)})"
    return PackageCollisionsResult(lines, summary)

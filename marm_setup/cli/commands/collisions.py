"""`marm-setup collisions`: the self-collision matrix alone (a headless `collisions_updater`)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import (
    JobsOption,
    OutputFormat,
    PackagePaths,
    TrialsText,
    UrdfArg,
    XacroArgs,
    YesOption,
    default_jobs,
    echo_err,
    load_robot_from_cli,
    parse_count,
)
from marm_setup.errors import InputError
from marm_setup.names import did_you_mean, with_hint

if TYPE_CHECKING:
    import numpy as np

    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.collision.matrix import CollisionMatrix
    from marm_setup.collision.pairs import DisabledPair
    from marm_setup.robot.model import RobotModel

REPORT_SUFFIXES = (".svg", ".html")


def collisions(
    urdf: UrdfArg,
    xacro_arg: XacroArgs = None,
    package_path: PackagePaths = None,
    trials: TrialsText = "10000",
    min_collision_fraction: Annotated[
        float,
        typer.Option(
            "--min-collision-fraction", help="Always: in collision in at least this share of samples."
        ),
    ] = 0.95,
    seed: Annotated[int, typer.Option("--seed", help="Random seed (same seed, same output).")] = 0,
    jobs: JobsOption = None,
    padding: Annotated[
        float, typer.Option("--padding", help="Treat pairs closer than this [m] as colliding.")
    ] = 0.0,
    srdf: Annotated[
        Path | None,
        typer.Option("--srdf", help="Update this SRDF (in place unless --output).", metavar="IN.srdf"),
    ] = None,
    output: Annotated[
        Path | None, typer.Option("--output", help="Write the SRDF here (minimal SRDF without --srdf).")
    ] = None,
    keep: Annotated[
        bool,
        typer.Option("--keep", help="With --srdf: keep every pair it already disables (User always kept)."),
    ] = False,
    default: Annotated[
        bool, typer.Option("--default/--no-default", help="Disable pairs colliding at the default state.")
    ] = True,
    always: Annotated[
        bool, typer.Option("--always/--no-always", help="Disable pairs (almost) always colliding.")
    ] = True,
    default_pose: Annotated[
        str | None,
        typer.Option(
            "--default-pose",
            help="With --srdf: a named pose of that SRDF as the default state (else 0 / mid-range).",
            metavar="NAME",
        ),
    ] = None,
    report: Annotated[
        Path | None, typer.Option("--report", help="Write a heat map of the matrix (.svg or .html).")
    ] = None,
    format: Annotated[OutputFormat, typer.Option("--format", help="text or json.")] = OutputFormat.text,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="With --srdf: update it even if it names another robot or links; with a package DIR: "
            "overwrite hand-edited files (kept as .orig).",
        ),
    ] = False,
    verbose: Annotated[
        bool, typer.Option("--verbose", help="With --srdf: list the pairs added and removed.")
    ] = False,
    yes: YesOption = False,
) -> None:
    """Compute which link pairs MoveIt need not check (Adjacent, Default, Always, Never).

    Seeded and deterministic (same seed, same bytes, whatever --jobs). Never is statistical: with N trials and no hit, a pair collides with probability below 3/N (95 %). Meshes are surfaces, as in MoveIt: a shape entirely inside a mesh, not touching it, does not collide.
    """
    count = parse_count(trials, element="--trials")
    jobs = default_jobs(jobs)
    if urdf.is_dir():  # a package made by init: its marm_setup.yaml and SRDF, together
        _check_options(min_collision_fraction, seed, padding, None, False, None)
        _refuse_unused(xacro_arg=xacro_arg, package_path=package_path)
        _update_package(urdf, count, seed, min_collision_fraction, jobs, force=force, yes=yes)
        return
    _check_options(min_collision_fraction, seed, padding, srdf, keep, report)
    if default_pose is not None and srdf is None:
        raise InputError("needs --srdf (the SRDF holding the pose)", element="--default-pose")
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.collision.matrix import compute_collision_matrix
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.collision.srdf_update import load_srdf_text, read_srdf_entries

    robot = load_robot_from_cli(urdf, xacro_arg, package_path)
    srdf_text = None
    if srdf is not None:
        srdf_text = load_srdf_text(srdf, shown=str(srdf))
        read_srdf_entries(srdf_text, shown=str(srdf))  # fail on a bad SRDF before the long part
        if not force:
            _check_same_robot(robot, srdf_text, str(srdf))
    default_q = None
    if default_pose is not None and srdf_text is not None:  # --default-pose needs --srdf (checked above)
        default_q = _pose_configuration(robot, srdf_text, default_pose, str(srdf))
    scene = CollisionScene(robot, padding)
    with SamplingProgress(enabled=format is OutputFormat.text, confirmed=yes) as progress:
        matrix = compute_collision_matrix(
            robot,
            scene,
            trials=count,
            seed=seed,
            min_collision_fraction=min_collision_fraction,
            check_default=default,
            check_always=always,
            default_q=default_q,
            jobs=jobs,
            progress=progress,
            distances=format is OutputFormat.json or report is not None,
        )
    disabled = _write_srdf(robot.name, matrix, srdf, srdf_text, output, keep)
    if srdf_text is not None:
        for line in _changes(srdf_text, disabled, str(srdf), verbose=verbose):
            echo_err(line)
    if report is not None:
        _write_report(report, matrix, robot, disabled)
    _print_result(matrix, robot.name, disabled, progress, format)


def _pose_configuration(robot: RobotModel, srdf_text: str, name: str, shown: str) -> np.ndarray:
    """The default configuration with the SRDF pose `name` laid over it: a pose of any group,
    composite ones included; where several groups have a pose of that name (a `home` per
    group), all of them. Multi-DOF values (a virtual joint's) do not move the robot's links."""
    from marm_setup.robot.kinematics import default_configuration
    from marm_setup.setup.srdf import parse_srdf_string

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


def _check_options(
    fraction: float, seed: int, padding: float, srdf: Path | None, keep: bool, report: Path | None
) -> None:
    if seed < 0:
        raise InputError(f"must be >= 0, got {seed}", element="--seed")
    if not 0.0 < fraction <= 1.0:
        raise InputError(f"must be in (0, 1], got {fraction}", element="--min-collision-fraction")
    if not 0.0 <= padding < float("inf"):  # also refuses nan, which would disable every pair
        raise InputError(f"must be >= 0 and finite, got {padding}", element="--padding")
    if keep and srdf is None:
        raise InputError("--keep needs --srdf (the SRDF whose pairs to keep)", element="--keep")
    if report is not None and report.suffix.lower() not in REPORT_SUFFIXES:
        raise InputError(f"unknown report type '{report.suffix}'; expected .svg or .html", path=str(report))


def _write_srdf(
    robot_name: str,
    matrix: CollisionMatrix,
    srdf: Path | None,
    srdf_text: str | None,
    output: Path | None,
    keep: bool,
) -> tuple[DisabledPair, ...]:
    """Write the SRDF the options ask for; return the final disabled pairs."""
    if srdf is None and output is None:
        return matrix.disabled  # nothing to write: no Jinja, no writer imported
    from marm_setup.collision.srdf_update import render_minimal_srdf, update_srdf
    from marm_setup.render.writer import write_text_atomic

    if srdf is None or srdf_text is None:  # the text is read whenever --srdf is given
        if output is not None:
            write_text_atomic(output, render_minimal_srdf(robot_name, matrix.disabled), shown=str(output))
            echo_err(f"wrote {output}")
        return matrix.disabled
    text, disabled = update_srdf(srdf_text, matrix.disabled, keep=keep, shown=str(srdf))
    target = output or srdf
    write_text_atomic(target, text, shown=str(target))
    echo_err(f"wrote {target}")
    return disabled


def _refuse_unused(**given: object) -> None:
    """A package DIR's marm_setup.yaml names the robot: an option that would choose it is refused."""
    for name, value in given.items():
        if value:
            option = "--" + name.replace("_", "-")
            raise InputError(
                "not used with a package DIR (its marm_setup.yaml names the robot, its xacro args and "
                "package paths)",
                element=option,
            )


def _update_package(
    pkg: Path, trials: int, seed: int, fraction: float, jobs: int, *, force: bool, yes: bool = False
) -> None:
    """Recompute a generated package's matrix into its marm_setup.yaml and SRDF together (its
    User pairs kept), so the next `render` has nothing to disagree with; with `force` a
    hand-edited file is overwritten (kept as `.orig`, as render does)."""
    import dataclasses

    from marm_setup.cli.commands.render import load_package_setup
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.collision.matrix import compute_collision_matrix
    from marm_setup.collision.pairs import DisabledReason
    from marm_setup.render.package import render_package
    from marm_setup.render.writer import apply_writes, format_change, plan_writes
    from marm_setup.setup.model import CollisionSettings

    model, robot = load_package_setup(pkg)
    with SamplingProgress(confirmed=yes) as progress:
        matrix = compute_collision_matrix(
            robot,
            trials=trials,
            seed=seed,
            min_collision_fraction=fraction,
            jobs=jobs,
            progress=progress,
            distances=False,
        )
    computed = {p.pair for p in matrix.disabled}
    user = [p for p in model.collision.disabled if p.reason is DisabledReason.USER and p.pair not in computed]
    disabled = tuple(sorted((*matrix.disabled, *user)))
    settings = CollisionSettings(seed=seed, trials=trials, min_collision_fraction=fraction, disabled=disabled)
    new = dataclasses.replace(model, collision=settings)
    changes = plan_writes(render_package(new, robot), pkg)
    apply_writes(changes, pkg, force=force)
    for line in (format_change(c, forced=force) for c in changes):
        if not line.startswith("unchanged"):
            typer.echo(line)
    summary = _pair_changes(model.collision.disabled, disabled)
    typer.echo(f"marm_setup.yaml and the SRDF: {len(disabled)} disabled pairs (changes: {summary})")


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
    from marm_setup.setup.srdf import parse_srdf_string

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


def _changes(old_text: str, new: Sequence[DisabledPair], shown: str, *, verbose: bool) -> list[str]:
    """What the update changed: pairs added and removed per reason, and with `verbose` each pair."""
    from marm_setup.setup.srdf import parse_srdf_string

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
    from marm_setup.collision.report import render_matrix_html, render_matrix_svg
    from marm_setup.render.writer import write_text_atomic

    links = [name for name in robot.links_in_tree_order if robot.link(name).has_geometry]
    svg = render_matrix_svg(matrix, robot.name, links, disabled)
    text = render_matrix_html(svg, robot.name) if report.suffix.lower() == ".html" else svg
    write_text_atomic(report, text, shown=str(report))
    echo_err(f"wrote {report}")


def _print_result(
    matrix: CollisionMatrix,
    robot_name: str,
    disabled: Sequence[DisabledPair],
    progress: SamplingProgress,
    format: OutputFormat,
) -> None:
    from marm_setup.collision.report import describe_matrix, format_summary

    if format is OutputFormat.json:
        typer.echo(json.dumps(describe_matrix(matrix, robot_name, disabled), indent=2))
    else:
        seconds = progress.finished - progress.started
        typer.echo(format_summary(matrix, robot_name, disabled, seconds, progress.denser_seconds()))

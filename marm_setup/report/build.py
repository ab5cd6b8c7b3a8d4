"""`build_report`: validate a package, then gather what the page draws and render it.

validate (through its public API) gives the findings, the package's SRDF and robot and the
trajectories its runtime checks planned; the collision scene gives the contacts of each state;
the collision matrix is recomputed (seed 0, `--trials` or DEFAULT_TRIALS: never the package's
own `collision` settings, a claim that may ask for 1e12 trials) for each pair's hits and
closest distance, the reasons staying the SRDF's. Each pair's proof status is the report's own:
the matrix is proved as `collisions` proves it (--prove on, reusing the user's proof cache),
never taken from what the package's marm_setup.yaml says of itself; a pair the SRDF disables
that a proof finds in contact is drawn at its witness state, as a stale pair's finding is.
A collision mesh that cannot be read is left out of the view and the matrix, and the page says
so (report/readable.py): the page is written whatever the package holds.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.report.content import Drawing, MatrixSection, drawn_links, page_content
from marm_setup.report.geometry import MAX_FACES, MeshArrays, RobotGeometry, robot_geometry
from marm_setup.report.readable import NotDrawn, drawable_robot, not_drawn_note

if TYPE_CHECKING:
    from marm_setup.collision import CollisionMatrix, CollisionScene
    from marm_setup.robot import RobotModel
    from marm_setup.setup import Srdf
    from marm_setup.validate import ValidatedPackage

Progress = Callable[[str, int, int], None]  # (stage, done, total)
DEFAULT_TRIALS = 10000  # the Setup Assistant's default sampling density


@dataclass(frozen=True)
class Report:
    """The page, and what went into it (`drawing` None when the robot or SRDF did not load;
    `not_drawn` the collision meshes left out, unreadable)."""

    html: str
    validated: ValidatedPackage
    drawing: Drawing | None
    not_drawn: tuple[NotDrawn, ...] = ()

    @property
    def meshes(self) -> tuple[MeshArrays, ...]:
        """The mesh files drawn (decimated)."""
        return self.drawing.geometry.meshes if self.drawing is not None else ()


def build_report(
    path: str | Path,
    *,
    urdf: str | Path | None = None,
    srdf: str | Path | None = None,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    plan: bool = True,
    trials: int | None = None,
    jobs: int = 1,
    max_faces: int = MAX_FACES,
    progress: Progress | None = None,
) -> Report:
    """The report of the package at `path`; `trials` for the matrix (default: DEFAULT_TRIALS). Raises InputError (exit 2) when `path` is no config package at all."""
    from marm_setup.report.page import render_page
    from marm_setup.validate import validate_package

    step = _stages(progress)
    checking = step("checking")
    checking(0, 0)  # no count to show: an open bar while the static rules run
    validated = validate_package(
        path,
        urdf=urdf,
        srdf=srdf,
        xacro_args=xacro_args,
        package_paths=package_paths,
        plan=plan,
        progress=step("planning") if progress else None,
    )
    checking(1, 1)
    robot, srdf_model = validated.robot, validated.package.srdf
    drawing, left_out = None, tuple[NotDrawn, ...]()
    if robot is not None and srdf_model is not None:
        robot, left_out = drawable_robot(robot)
        geometry = robot_geometry(robot, max_faces, step("meshes") if progress else None)
        drawing = _drawing(validated, robot, srdf_model, geometry, trials, jobs, step)
    name = robot.name if robot is not None else validated.validation.package
    writing = step("writing the page")
    writing(0, 0)
    summary = {**_summary(validated), "not_drawn": not_drawn_note(left_out)}
    content = page_content(name, drawing, validated.validation.findings, summary)
    html = render_page(_relative(content, validated))
    writing(1, 1)
    return Report(html, validated, drawing, left_out)


def _stages(progress: Progress | None) -> Callable[[str], Callable[[int, int], None]]:
    """`step(stage)`: a `(done, total)` callback reporting `stage` to `progress` (or nothing)."""

    def step(stage: str) -> Callable[[int, int], None]:
        def report(done: int, total: int) -> None:
            if progress is not None:
                progress(stage, done, total)

        return report

    return step


def _drawing(
    validated: ValidatedPackage,
    robot: RobotModel,
    srdf: Srdf,
    geometry: RobotGeometry,
    trials: int | None,
    jobs: int,
    step: Callable[[str], Callable[[int, int], None]],
) -> Drawing:
    """What the 3D view draws for a package whose robot and SRDF loaded."""
    from marm_setup.collision import CollisionScene
    from marm_setup.package import package_start_values
    from marm_setup.report.motions import motions
    from marm_setup.report.states import robot_states, witness_states

    posing = step("robot states")
    posing(0, 0)
    scene = CollisionScene(robot)
    start = package_start_values(validated.package, robot)
    states = robot_states(srdf, robot, scene, start, validated.validation.findings)
    posing(1, 1)
    section = _matrix_section(validated, robot, srdf, scene, trials, jobs, step("collision matrix"))
    if section is not None:
        states += witness_states(section[1], srdf, robot)
    moving = step("trajectories")
    moving(0, 0)
    moves = motions(robot, validated.plans, drawn_links(robot, geometry, srdf))
    moving(1, 1)
    return Drawing(robot, srdf, geometry, states, moves, section[0] if section else None)


def _matrix_section(
    validated: ValidatedPackage,
    robot: RobotModel,
    srdf: Srdf,
    scene: CollisionScene,
    trials: int | None,
    jobs: int,
    progress: Callable[[int, int], None],
) -> tuple[MatrixSection, CollisionMatrix] | None:
    """The matrix picture and pairs (reasons from the SRDF, counts and proofs from a fresh
    computation; see the module doc), and the matrix."""
    from marm_setup.collision import compute_cached_matrix, describe_matrix, render_matrix_svg

    if not scene.candidate_pairs:
        return None
    count = trials or DEFAULT_TRIALS  # the command's own, whatever the package says
    matrix = compute_cached_matrix(robot, scene, trials=count, jobs=jobs, progress=progress, prove="on")
    links = [name for name in robot.links_in_tree_order if robot.link(name).has_geometry]
    svg = render_matrix_svg(matrix, robot.name, links, srdf.disabled)
    return MatrixSection(svg, describe_matrix(matrix, robot.name, srdf.disabled)), matrix


def _relative(content: dict, validated: ValidatedPackage) -> dict:
    """`content` with paths relative to the package, none of the machine's (report/paths.py)."""
    from marm_setup.report.paths import relative_content

    return relative_content(content, validated.package.root, _package_of)


def _package_of(folder: Path) -> str | None:
    from marm_setup.robot import package_name

    return package_name(folder)


def _summary(validated: ValidatedPackage) -> dict:
    from marm_setup.report.paths import with_page_urdf

    pkg = validated.package
    v = with_page_urdf(validated.validation, pkg.root, _package_of, pkg.urdf)
    return {"package": v.package, "target": v.target, "layout": v.layout, "validated": v.describe()}

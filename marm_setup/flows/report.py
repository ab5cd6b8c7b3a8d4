"""`report`: one offline HTML page of a config package (report.build_report), written atomically."""

from __future__ import annotations

from collections.abc import Callable
from contextlib import nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.flows.settings import MatrixSettings, RobotInput
from marm_setup.untrusted import no_package_code

if TYPE_CHECKING:
    from marm_setup.report import Report


@dataclass(frozen=True)
class ReportRequest:
    package: Path
    output: Path  # .html or .htm
    robot: RobotInput = RobotInput()  # --urdf, --srdf, --xacro-arg over the package's; --untrusted
    matrix: MatrixSettings = MatrixSettings()  # its trials and jobs (never the package's trials)
    plan: bool = True


def run_report(request: ReportRequest, progress: Callable[[str, int, int], None] | None = None) -> Report:
    """Build the page and write it (the page is written whatever the package's findings)."""
    from marm_setup.render import write_text_atomic

    output = request.output
    if output.suffix.lower() not in (".html", ".htm"):
        raise InputError(f"expected an .html file, got '{output.name}'", path=str(output), element="--output")
    with no_package_code() if request.robot.untrusted else nullcontext():
        result = _build(request, progress)
    write_text_atomic(output, result.html, shown=str(output))
    return result


def _build(request: ReportRequest, progress: Callable[[str, int, int], None] | None) -> Report:
    from marm_setup.report import build_report

    return build_report(
        request.package,
        urdf=request.robot.urdf,
        srdf=request.robot.srdf,
        xacro_args=request.robot.xacro_mapping,
        package_paths=request.robot.package_paths,
        plan=request.plan,
        trials=request.matrix.trials,
        jobs=request.matrix.jobs,
        progress=progress,
    )

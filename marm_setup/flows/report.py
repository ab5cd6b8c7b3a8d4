"""`report`: one offline HTML page of a config package (report.build_report), written atomically."""

from __future__ import annotations

from collections.abc import Callable
from contextlib import nullcontext
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.untrusted import no_package_code

if TYPE_CHECKING:
    from marm_setup.report import Report


@dataclass(frozen=True)
class ReportRequest:
    package: Path
    output: Path  # .html or .htm
    urdf: Path | None = None
    srdf: Path | None = None
    xacro_args: dict[str, str] = field(default_factory=dict)
    package_paths: tuple[Path, ...] = ()
    plan: bool = True
    trials: int | None = None  # the matrix's; None: report.build.DEFAULT_TRIALS (never the package's)
    jobs: int = 1
    untrusted: bool = False  # run none of the package's code (marm_setup.untrusted)


def run_report(request: ReportRequest, progress: Callable[[str, int, int], None] | None = None) -> Report:
    """Build the page and write it (the page is written whatever the package's findings)."""
    from marm_setup.render import write_text_atomic

    output = request.output
    if output.suffix.lower() not in (".html", ".htm"):
        raise InputError(f"expected an .html file, got '{output.name}'", path=str(output), element="--output")
    with no_package_code() if request.untrusted else nullcontext():
        result = _build(request, progress)
    write_text_atomic(output, result.html, shown=str(output))
    return result


def _build(request: ReportRequest, progress: Callable[[str, int, int], None] | None) -> Report:
    from marm_setup.report import build_report

    return build_report(
        request.package,
        urdf=request.urdf,
        srdf=request.srdf,
        xacro_args=request.xacro_args,
        package_paths=request.package_paths,
        plan=request.plan,
        trials=request.trials,
        jobs=request.jobs,
        progress=progress,
    )

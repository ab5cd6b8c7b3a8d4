"""The SRDF validate picks by name, refit to the robot once it is loaded.

Where no launch file names the SRDF statically (a Python launch computes
`config/srdf/<model><suffix>.srdf` from its args, or a vendor's own builder picks it), validate
falls back on the package's SRDFs by name (package/description.py `srdfs_by_name`); the launch
picks the one made for the robot it loads. So, once the robot is loaded, a candidate that does
not fit it gives way to the first that fits better: validating another robot's SRDF would report
errors move_group never sees. Fit is (the SRDF-vs-URDF errors, then the robot's links with
collision geometry the SRDF's matrix never names: an SRDF made for a robot without its arm names
none of the arm's links, and validate would call every arm pair a missing disable).
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

from marm_setup.findings import Finding
from marm_setup.package import MoveItPackage, Source

if TYPE_CHECKING:
    from marm_setup.package import SrdfFile
    from marm_setup.robot import RobotModel

FIT: tuple[float, int] = (0.0, 0)  # no error, every link with geometry named


def fitting_srdf(pkg: MoveItPackage, robot: RobotModel) -> MoveItPackage:
    """`pkg` with, when its SRDF was chosen by name and does not fit `robot`, the first other
    candidate with fewer SRDF-vs-URDF errors."""
    from marm_setup.package import SRDF_GUESSED, srdfs_by_name

    source, chosen = pkg.source("srdf"), pkg.srdf_file
    if source is None or source.how != SRDF_GUESSED or chosen is None:
        return pkg
    best, misfit, problems = chosen, _misfit(chosen, robot), list[Finding]()
    for rel in srdfs_by_name(pkg.root):
        if misfit <= FIT:
            break
        if rel == best.path:
            continue
        found: list[Finding] = []
        other = _read(pkg, rel, chosen, found)
        if (score := _misfit(other, robot)) < misfit:
            best, misfit, problems = other, score, found
    if best is chosen:
        return pkg
    return _with_srdf(pkg, chosen, best, problems)


def _read(pkg: MoveItPackage, rel: str, chosen: SrdfFile, problems: list[Finding]) -> SrdfFile:
    from marm_setup.package import read_srdf_file

    return read_srdf_file(pkg.root, rel, pkg.package_paths, problems, dict(chosen.xacro_args))


def _misfit(srdf_file: SrdfFile, robot: RobotModel) -> tuple[float, int]:
    """(the SRDF's SRDF-vs-URDF errors on `robot`, the robot's links with collision geometry
    its matrix never names); infinite when it could not be read."""
    from marm_setup.validate.rules.srdf_rules import check_srdf

    srdf = srdf_file.srdf
    if srdf is None:
        return float("inf"), 0
    named = {link for pair in srdf.disabled for link in (pair.link1, pair.link2)}
    unnamed = sum(1 for link in robot.links if link.has_geometry and link.name not in named)
    return sum(f.is_error for f in check_srdf(srdf_file, robot)), unnamed


def _with_srdf(pkg: MoveItPackage, old: SrdfFile, new: SrdfFile, problems: list[Finding]) -> MoveItPackage:
    how = (
        "chosen by its name among the package's SRDFs (no file or launch names one statically): "
        f"the one that fits the robot best ({old.path} fits it worse)"
    )
    sources = tuple(s for s in pkg.sources if s.kind != "srdf") + (Source("srdf", new.path, how),)
    kept = tuple(p for p in pkg.problems if p.file != old.path)
    return dataclasses.replace(pkg, srdf_file=new, sources=sources, problems=(*kept, *problems))

"""The option groups the commands share, as values the flows take whole: where the robot comes
from (`RobotInput`) and how the collision matrix is computed (`MatrixSettings`), each with its
defaults and its check in one place."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from marm_setup.errors import InputError

if TYPE_CHECKING:
    from marm_setup.setup import CollisionSettings

DEFAULT_TRIALS = 10000  # the Setup Assistant's sampling density
DEFAULT_PROVE = "on"  # README "Proved Never": on by default; off is MoveIt's sampling alone
MAX_TRIALS = 10**12  # a trillion states would take days on any robot


@dataclass(frozen=True)
class RobotInput:
    """The robot a command loads: its description (`urdf`: the URDF argument, or --urdf over the
    one a package names), --srdf over a package's, --xacro-arg as (name, value) pairs,
    --package-path, and --untrusted (run none of the package's code)."""

    urdf: Path | None = None
    srdf: Path | None = None
    xacro_args: tuple[tuple[str, str], ...] = ()
    package_paths: tuple[Path, ...] = ()
    untrusted: bool = False

    @classmethod
    def parse(
        cls,
        urdf: Path | None = None,
        srdf: Path | None = None,
        xacro_args: list[str] | tuple[str, ...] | None = None,
        package_paths: list[Path] | tuple[Path, ...] | None = None,
        untrusted: bool = False,
    ) -> RobotInput:
        """The group from its options; a --xacro-arg not written NAME:=VALUE is an InputError."""
        from marm_setup.robot import parse_xacro_args

        pairs = tuple(parse_xacro_args(xacro_args or ()).items())
        return cls(urdf, srdf, pairs, tuple(package_paths or ()), untrusted)

    @property
    def xacro_mapping(self) -> dict[str, str]:
        """The --xacro-args as a mapping (the last value of a name repeated)."""
        return dict(self.xacro_args)


@dataclass(frozen=True)
class MatrixSettings:
    """How the self-collision matrix is computed: random states for the Never phase, their seed,
    the Always share, padding [m], how hard Never pairs are proved (off, on, exhaustive), worker
    processes (the result does not depend on them), and whether a given matrix is kept as it is.
    `given` names the settings the command line gave (init takes the SPEC's for the others; None:
    all of them)."""

    trials: int = DEFAULT_TRIALS
    seed: int = 0
    min_collision_fraction: float = 0.95
    padding: float = 0.0
    prove: str = DEFAULT_PROVE
    jobs: int = 1
    keep_disabled: bool = False
    given: frozenset[str] | None = None

    def __post_init__(self) -> None:
        for problem, element in self.problems():
            raise InputError(problem, element=element)

    def problems(self) -> list[tuple[str, str]]:
        """(message, option) of each setting out of range."""
        from marm_setup.collision import PROVE_MODES

        checks = [
            (1 <= self.trials <= MAX_TRIALS, f"must be between 1 and {MAX_TRIALS:.0e}", "trials"),
            (self.seed >= 0, "must be >= 0", "seed"),
            (0.0 < self.min_collision_fraction <= 1.0, "must be in (0, 1]", "min_collision_fraction"),
            (0.0 <= self.padding < float("inf"), "must be >= 0 and finite", "padding"),  # nan too
            (self.prove in PROVE_MODES, f"must be one of {', '.join(PROVE_MODES)}", "prove"),
            (self.jobs >= 1, "must be >= 1", "jobs"),
        ]
        return [
            (f"{message}, got {getattr(self, name)}", "--" + name.replace("_", "-"))
            for ok, message, name in checks
            if not ok
        ]

    def over(self, recorded: CollisionSettings) -> MatrixSettings:
        """These settings with a setup's trials, seed and prove where the command line gave none."""
        taken = {
            name: getattr(recorded, name)
            for name in ("trials", "seed", "prove")
            if self.given is not None and name not in self.given and getattr(recorded, name) is not None
        }
        return dataclasses.replace(self, **taken)

    def matrix_options(self) -> dict[str, Any]:
        """The keyword arguments of compute_collision_matrix these settings give."""
        return {
            "trials": self.trials,
            "seed": self.seed,
            "min_collision_fraction": self.min_collision_fraction,
            "jobs": self.jobs,
            "prove": self.prove,
        }

"""Options and helpers shared by the CLI commands (kept free of heavy imports)."""

from __future__ import annotations

import enum
import inspect
import re
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, TypeVar

import typer

from marm_setup.cli.option_groups import OptionGroup
from marm_setup.flows import DEFAULT_TRIALS, MatrixSettings, RobotInput

if TYPE_CHECKING:
    from marm_setup.robot import RobotModel

T = TypeVar("T")

UrdfArg = Annotated[
    Path, typer.Argument(help="Robot description: .urdf, .xacro or .urdf.xacro.", metavar="URDF")
]
XacroArgs = Annotated[
    list[str] | None,
    typer.Option("--xacro-arg", help="xacro argument NAME:=VALUE (repeatable).", metavar="NAME:=VALUE"),
]
PackagePaths = Annotated[
    list[Path] | None,
    typer.Option(
        "--package-path",
        help="Folder holding ROS packages, or a package (repeatable); ROS_PACKAGE_PATH is also read.",
        metavar="DIR",
    ),
]

PackageUrdf = Annotated[
    Path | None,
    typer.Option("--urdf", help="Robot description to use instead of the one the package names."),
]
PackageSrdf = Annotated[
    Path | None,
    typer.Option("--srdf", help="SRDF (or .srdf.xacro) to use instead of the one the package names."),
]


def either(value: T | None, old: T | None, *, name: str, old_name: str) -> T | None:
    """An option's value given by its name or its old (hidden) one; an InputError when both are
    given and differ."""
    from marm_setup.errors import InputError

    if value is not None and old is not None and value != old:
        raise InputError(f"given twice ({old_name} is the old name of {name}): keep one", element=name)
    return value if value is not None else old


class OutputFormat(str, enum.Enum):
    text = "text"
    json = "json"


class ProveMode(str, enum.Enum):
    """How hard to prove the Never pairs (collision/proof.py): off is MoveIt's sampling alone."""

    off = "off"
    on = "on"
    exhaustive = "exhaustive"


ProveOption = Annotated[
    ProveMode,
    typer.Option(
        "--prove",
        help="Prove Never pairs collision-free over their whole joint range (off: MoveIt's sampling "
        "alone; exhaustive: a far larger budget). A pair a proof finds in contact stays enabled.",
    ),
]


def load_robot_from_cli(given: RobotInput, *, check_args: bool = True) -> RobotModel:
    """Load the robot a command's options name (the import stays out of --help); a `--xacro-arg`
    the description does not take is an InputError, unless `check_args` is false (the caller
    checks it against more files: init's SRDF xacro)."""
    from marm_setup.robot import check_xacro_args, load_robot

    assert given.urdf is not None  # the URDF argument of the commands that load it here
    robot = load_robot(given.urdf, given.xacro_mapping, given.package_paths)
    if check_args:
        check_xacro_args(given.xacro_mapping, robot.xacro_args, path=str(given.urdf))
    return robot


MAX_LINE = 4000  # characters of one error line (a name from a file can be any size)


LONG_WORD = 300  # characters of one name or path quoted whole; a longer one is excerpted


def one_line(text: str) -> str:
    """`text` with control characters (newlines too) escaped, so a message stays one line, of at
    most MAX_LINE characters: each word (a name, a path) longer than LONG_WORD is cut in its
    middle first, so the reason after a 10,000-character name still shows; a line still too
    long loses its middle, never its end."""
    line = "".join(c if c.isprintable() or c == " " else repr(c)[1:-1] for c in text)
    line = re.sub(rf"\S{{{LONG_WORD + 1},}}", lambda m: _cut(m[0], LONG_WORD), line)
    return _cut(line, MAX_LINE)


def _cut(text: str, limit: int) -> str:
    """`text` within `limit` characters, its middle replaced by `...` when longer."""
    if len(text) <= limit:
        return text
    head = (limit - 3) * 2 // 3
    return text[:head] + "..." + text[len(text) - (limit - 3 - head) :]


COUNT_SUFFIXES = {"k": 1_000, "m": 1_000_000}
TrialsText = Annotated[
    str,
    typer.Option("--trials", help="Random states for the Never phase (10000, 100k, 1M).", metavar="N"),
]
JobsOption = Annotated[
    int | None,
    typer.Option(
        "--jobs",
        help="Worker processes [default: CPU count] (the result does not depend on it).",
        metavar="N",
    ),
]


UntrustedOption = Annotated[
    bool,
    typer.Option(
        "--untrusted",
        help=(
            "Run none of the package's code (no xacro, $(eval), $(command) or launch file): "
            "check what can be read and say what was skipped."
        ),
    ),
]
YesOption = Annotated[
    bool,
    typer.Option(
        "--yes", help="Run the sampling even when it is estimated to take over 30 minutes (said up front)."
    ),
]


MAX_COUNT = 1e12  # trials: a trillion states would take days on any robot


def parse_count(text: str, *, element: str) -> int:
    """A positive count written `10000`, `10_000`, `100k`, `1M` or `1e5`; else an InputError."""
    from marm_setup.errors import InputError

    raw = text.strip().lower().replace("_", "")
    scale = COUNT_SUFFIXES.get(raw[-1:], 1)
    number = raw[:-1] if scale > 1 else raw
    try:
        value = float(number) * scale
    except ValueError:
        raise InputError(f"expected a count like 10000, 100k or 1M, got '{text}'", element=element) from None
    if not 1 <= value <= MAX_COUNT:  # also refuses nan and inf
        raise InputError(f"must be between 1 and {MAX_COUNT:.0e}, got {text}", element=element)
    if value != int(value):
        raise InputError(f"must be a whole number, got {text}", element=element)
    return int(value)


def default_jobs(jobs: int | None) -> int:
    """`jobs`, or the CPUs this process may run on; an InputError below 1."""
    import os

    from marm_setup.errors import InputError

    if jobs is None:
        return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    if jobs < 1:
        raise InputError(f"must be >= 1, got {jobs}", element="--jobs")
    return jobs


def _robot_input(
    urdf: Path | None = None,
    srdf: Path | None = None,
    xacro_arg: list[str] | None = None,
    package_path: list[Path] | None = None,
    untrusted: bool = False,
) -> RobotInput:
    return RobotInput.parse(urdf, srdf, xacro_arg, package_path, untrusted)


# Where the robot comes from: each command takes the options that apply to it (ROBOT.of(...)).
ROBOT = OptionGroup(
    {
        "urdf": (UrdfArg, inspect.Parameter.empty),
        "srdf": (PackageSrdf, None),
        "xacro_arg": (XacroArgs, None),
        "package_path": (PackagePaths, None),
        "untrusted": (UntrustedOption, False),
    },
    _robot_input,
)


def _matrix_settings(**options: object) -> MatrixSettings:
    """The matrix settings from the options given (None: not given, the default), --keep and
    --keep-matrix the old names of --keep-disabled."""
    given = {name: value for name, value in options.items() if value is not None}
    keep = bool(given.pop("keep", False)) | bool(given.pop("keep_matrix", False))
    if "trials" in given:
        given["trials"] = parse_count(str(given["trials"]), element="--trials")
    prove = given.get("prove")
    if isinstance(prove, ProveMode):
        given["prove"] = prove.value
    given["jobs"] = default_jobs(given.get("jobs"))  # type: ignore[arg-type]
    given["keep_disabled"] = bool(given.get("keep_disabled")) or keep
    return MatrixSettings(**given, given=frozenset(given))  # type: ignore[arg-type]


SeedOption = Annotated[int, typer.Option("--seed", help="Random seed (same seed, same output).")]
FractionOption = Annotated[
    float,
    typer.Option("--min-collision-fraction", help="Always: in collision in at least this share of samples."),
]
PaddingOption = Annotated[
    float, typer.Option("--padding", help="Treat pairs closer than this [m] as colliding.")
]
KeepDisabledOption = Annotated[
    bool,
    typer.Option(
        "--keep-disabled", help="With --srdf: keep every pair it already disables (User always kept)."
    ),
]

# How the collision matrix is computed: each command takes the options that apply to it (MATRIX.of(...)).
MATRIX = OptionGroup(
    {
        "trials": (TrialsText, str(DEFAULT_TRIALS)),
        "min_collision_fraction": (FractionOption, MatrixSettings.min_collision_fraction),
        "seed": (SeedOption, MatrixSettings.seed),
        "jobs": (JobsOption, None),
        "padding": (PaddingOption, MatrixSettings.padding),
        "keep_disabled": (KeepDisabledOption, False),
        "keep": (Annotated[bool, typer.Option("--keep", hidden=True)], False),  # --keep-disabled's old name
        "prove": (ProveOption, ProveMode(MatrixSettings.prove)),
    },
    _matrix_settings,
)


def echo_err(message: str) -> None:
    """Print one line to stderr."""
    typer.echo(one_line(message), err=True)

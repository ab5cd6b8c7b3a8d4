"""Usage errors of the real console script: one `error:` line with exit 2, like any bad input
(CliRunner calls the app without `main`, so these run `python -m marm_setup`)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from tests.conftest import MARM_URDF


def run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "marm_setup", *args], capture_output=True, text=True, timeout=60
    )


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (("init", str(MARM_URDF), "--target", "ros3", "--out", "x"), "'ros3' is not one of 'ros2', 'ros1'"),
        (("collisions", str(MARM_URDF), "--jobs", "abc"), "Invalid value for '--jobs'"),
        (("validate", "--nope", "x"), "No such option: --nope"),
        (("nocommand",), "No such command 'nocommand'"),
    ],
)
def test_a_usage_error_is_one_line_exit_2(args, fragment):
    result = run(*args)
    assert result.returncode == 2, result.stderr
    (line,) = result.stderr.strip().splitlines()
    assert line.startswith("error: ") and fragment in line and "--help')" in line
    assert result.stdout == ""


@pytest.mark.parametrize(
    ("args", "line"),
    [
        (
            ("init",),
            "error: URDF: missing: the robot's URDF (marm-setup init URDF -o DIR), or --from-package PKG",
        ),
        (("init", str(MARM_URDF)), "error: -o/--output: missing: the package folder to write (-o DIR)"),
    ],
)
def test_a_missing_argument_is_named_first(args, line):
    """init's URDF is optional for click (--from-package takes none): the URDF is asked for before
    the output folder, each as one line."""
    result = run(*args)
    assert result.returncode == 2
    assert result.stderr.splitlines() == [line]


def test_help_and_version_still_print():
    assert run("--version").stdout.startswith("marm-setup ")
    helped = run("plan", "--help")
    assert helped.returncode == 0 and "--group" in helped.stdout
    bare = run()
    assert bare.returncode == 2 and bare.stderr.startswith("Usage: marm-setup")  # click's no-args help

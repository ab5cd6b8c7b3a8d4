"""One name per idea across commands: `-o/--output` for what a command writes, `--keep-disabled`
for keeping the pairs an SRDF or SPEC already disables; the old names still work, unlisted."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import MARM_URDF

runner = CliRunner()
FAST = ["--trials", "200", "--prove", "off"]


@pytest.mark.parametrize(
    ("command", "listed", "hidden"),
    [
        ("init", ["-o, --output", "--keep-disabled"], ["--out ", "--keep-matrix"]),
        ("collisions", ["-o, --output", "--keep-disabled"], ["--keep "]),
        ("plan", ["-o, --output"], []),
        ("report", ["-o, --output"], []),
        ("render", ["--xacro-arg", "--package-path"], []),
    ],
)
def test_help_lists_the_one_name(command, listed, hidden):
    text = runner.invoke(app, [command, "--help"], terminal_width=200).stdout
    for name in listed:
        assert name in text, (command, name)
    for name in hidden:
        assert name not in text, (command, name)


def test_init_takes_output_and_its_old_name(tmp_path):
    for flag, name in (("-o", "a"), ("--output", "b"), ("--out", "c")):
        out = tmp_path / name
        result = runner.invoke(app, ["init", str(MARM_URDF), flag, str(out), "--target", "ros1", *FAST])
        assert result.exit_code == 0, result.output
        assert (out / "package.xml").is_file()
    both = runner.invoke(
        app, ["init", str(MARM_URDF), "-o", str(tmp_path / "d"), "--out", str(tmp_path / "e")]
    )
    assert both.exit_code == 2
    assert "error: -o/--output: given twice (--out is the old name of -o/--output): keep one" in both.stderr


def test_collisions_keep_disabled_and_its_old_name_keep_the_srdfs_pairs(tmp_path):
    srdf = tmp_path / "in.srdf"
    srdf.write_text(
        '<robot name="marm"><disable_collisions link1="base_link" link2="gripper_finger_link1" reason="Never"/></robot>'
    )
    for flag in ("--keep-disabled", "--keep"):
        out = tmp_path / f"{flag.strip('-')}.srdf"
        args = ["collisions", str(MARM_URDF), *FAST, "--srdf", str(srdf), flag, "-o", str(out)]
        result = runner.invoke(app, args)
        assert result.exit_code == 0, result.output
        assert 'link1="base_link" link2="gripper_finger_link1"' in out.read_text()
    alone = runner.invoke(app, ["collisions", str(MARM_URDF), *FAST, "--keep-disabled"])
    assert alone.exit_code == 2
    assert alone.stderr.startswith("error: --keep-disabled: needs --srdf")

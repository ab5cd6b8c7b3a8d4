"""What every reliability test asserts about a run: exit code, one-line errors, parseable output."""

from __future__ import annotations

import ast
import json
from pathlib import Path

import yaml
from lxml import etree
from typer.testing import CliRunner

from marm_setup.cli.app import app

runner = CliRunner()
XML_SUFFIXES = (".xml", ".srdf", ".launch", ".xacro", ".urdf")


def run(*args: str):
    """Invoke the CLI in-process (exceptions are the app's to handle: none may escape)."""
    return runner.invoke(app, [str(a) for a in args], catch_exceptions=True)


def assert_clean_exit(result, codes=(0, 1, 2)) -> None:
    """An expected exit code, no traceback, and an error is exactly one stderr line."""
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    assert result.exit_code in codes, (result.exit_code, result.output)
    assert "Traceback" not in result.output
    if result.exit_code == 2:
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error: "), result.stderr


def assert_one_line_error(result, *fragments: str) -> None:
    assert_clean_exit(result, codes=(2,))
    for fragment in fragments:
        assert fragment in result.stderr, result.stderr


def assert_package_parses(pkg: Path) -> None:
    """Every file parses as its language: XML (lxml), YAML (PyYAML), Python (ast), JSON."""
    files = [p for p in pkg.rglob("*") if p.is_file()]
    assert files
    for path in files:
        text = path.read_text(encoding="utf-8")
        if path.name.endswith(XML_SUFFIXES):
            etree.fromstring(text.encode("utf-8"))
        elif path.suffix == ".yaml":
            yaml.safe_load(text)
        elif path.suffix == ".py":
            ast.parse(text)
        elif path.suffix == ".json":
            json.loads(text)

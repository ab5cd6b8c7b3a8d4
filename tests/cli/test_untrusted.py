"""`--untrusted` (issue 23): validate, init --from-package and report run none of the package's
code (no xacro, `$(eval)`, `$(command)` or launch file), say what they skipped, and still report
what they can read."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.validate_helpers import generate_marm, replace_text

runner = CliRunner()

# A robot description whose xacro fails as soon as it runs: proof of whether it ran.
XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find no_such_package_ran)/x.xacro"/>
  <link name="base_link"/>
</robot>
"""


def _package(tmp_path):
    pkg = generate_marm(tmp_path, "ros1")
    (pkg / "urdf").mkdir()
    (pkg / "urdf" / "r.urdf.xacro").write_text(XACRO, encoding="utf-8")
    text = (pkg / "marm_setup.yaml").read_text(encoding="utf-8")
    start = text.index("  urdf: ")
    end = text.index("\n", start)
    (pkg / "marm_setup.yaml").write_text(
        text[:start] + "  urdf: urdf/r.urdf.xacro" + text[end:], encoding="utf-8"
    )
    return pkg


def test_validate_runs_the_package_xacro_by_default(tmp_path):
    pkg = _package(tmp_path)
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan"])
    assert "no_such_package_ran" in result.stdout  # a package no path holds: urdf.package-missing


def test_validate_untrusted_runs_no_package_code_and_says_what_it_skipped(tmp_path):
    pkg = _package(tmp_path)
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan", "--untrusted", "--format", "json"])
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    assert not [f for f in doc["findings"] if "no_such_package_ran" in f["message"]]
    skipped = " ".join(doc["validated"]["skipped"])
    assert "package code (--untrusted)" in skipped
    assert "xacro of" in skipped and "r.urdf.xacro" in skipped
    assert "$(eval arg('moveit_controller_manager') == 'fake')" in skipped  # demo.launch's
    assert "--untrusted" in doc["validated"]["launched_by"]


def test_validate_untrusted_still_reports_what_it_reads(tmp_path):
    pkg = _package(tmp_path)
    replace_text(pkg, "package.xml", "<name>marm_moveit_config</name>", "<name>marm_moveit_config</nam>")
    result = runner.invoke(app, ["validate", str(pkg), "--no-plan", "--untrusted"])
    assert result.exit_code == 1 and "package.invalid" in result.stdout


def test_init_from_package_untrusted_refuses_a_xacro_description_in_one_line(tmp_path):
    pkg = _package(tmp_path)
    out = tmp_path / "out"
    result = runner.invoke(app, ["init", "--from-package", str(pkg), "--out", str(out), "--untrusted"])
    assert result.exit_code == 2, result.output
    line = result.output.strip().splitlines()[-1]
    assert line.startswith("error: ") and "xacro of" in line and "--untrusted" in line
    assert "no_such_package_ran" not in result.output and not out.exists()


def test_init_untrusted_needs_from_package(tmp_path):
    result = runner.invoke(
        app, ["init", str(tmp_path / "r.urdf"), "--out", str(tmp_path / "o"), "--untrusted"]
    )
    assert result.exit_code == 2 and "--from-package" in result.output


def test_report_untrusted_writes_the_page_and_says_what_it_skipped(tmp_path):
    pkg = _package(tmp_path)
    page = tmp_path / "r.html"
    result = runner.invoke(app, ["report", str(pkg), "-o", str(page), "--no-plan", "--untrusted"])
    assert result.exit_code == 0, result.output
    html = page.read_text(encoding="utf-8")
    assert "package code (--untrusted)" in html and "no_such_package_ran" not in html

"""`--untrusted` reads nothing from the user's environment or outside the package, and no writer
follows a symlink it did not create (issue 36): `$(env)` / `$(optenv)` stay unresolved with a
finding saying so, a robot description or mesh outside the package is not read, and a report,
SRDF or matrix written onto a link is refused in one line, the link's target untouched."""

from __future__ import annotations

import pytest

from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run
from tests.validate_helpers import generate_marm, replace_text

SECRET = "hunter2-ENV-SECRET"
TRIANGLE = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\nendloop\nendfacet\nendsolid t\n"


def _point_urdf(pkg, urdf: str) -> None:
    text = (pkg / "marm_setup.yaml").read_text(encoding="utf-8")
    start = text.index("  urdf: ")
    end = text.index("\n", start)
    (pkg / "marm_setup.yaml").write_text(text[:start] + f"  urdf: {urdf}" + text[end:], encoding="utf-8")


@pytest.mark.parametrize("command", ["env", "optenv"])
@pytest.mark.parametrize("where", ["subst_value yaml", "launch arg"])
def test_environment_is_not_read_under_untrusted(tmp_path, monkeypatch, command, where):
    monkeypatch.setenv("MARM_FUZZ_SECRET", SECRET)
    pkg = generate_marm(tmp_path, "ros1")
    reference = f"$({command} MARM_FUZZ_SECRET)" + (" 0.05" if command == "optenv" else "")
    if where == "subst_value yaml":
        launch = "launch/planning_context.launch"
        old = 'command="load" file="$(find marm_moveit_config)/config/kinematics.yaml"'
        replace_text(pkg, launch, old, f'subst_value="true" {old}')
        replace_text(pkg, "config/kinematics.yaml", "kdl_kinematics_plugin/KDLKinematicsPlugin", reference)
    else:
        replace_text(
            pkg, "launch/demo.launch", "<launch>", f'<launch>\n  <arg name="z" default="{reference}"/>'
        )
    trusted = run("validate", pkg, "--no-plan", "--format", "json")
    assert_clean_exit(trusted)
    untrusted = run("validate", pkg, "--no-plan", "--untrusted", "--format", "json")
    assert_clean_exit(untrusted)
    assert SECRET not in untrusted.output
    if where == "subst_value yaml":
        assert SECRET in trusted.output  # the trusted run reads it (kinematics.unknown-solver)
        assert "reads nothing from your environment" in untrusted.output


def test_a_robot_description_outside_the_package_is_not_read_under_untrusted(tmp_path):
    pkg = generate_marm(tmp_path, "ros1")
    outside = tmp_path / "elsewhere" / "secret.urdf"
    outside.parent.mkdir()
    outside.write_text(f'<robot name="{SECRET}"><link name="{SECRET}"/></robot>', encoding="utf-8")
    for reference in (str(outside), "../elsewhere/secret.urdf"):
        _point_urdf(pkg, reference)
        result = run("validate", pkg, "--no-plan", "--untrusted")
        assert_clean_exit(result)
        assert SECRET not in result.output and "package.outside" in result.output
        assert "not read (--untrusted" in result.output
        given = run("validate", pkg, "--no-plan", "--untrusted", "--urdf", outside)  # the user names it
        assert_clean_exit(given)
        assert "lies outside the package" not in given.output


@pytest.mark.parametrize("uri", ["file://{outside}", "{outside}", "../../elsewhere/m.stl"])
def test_a_mesh_outside_the_package_is_not_read_under_untrusted(tmp_path, uri):
    pkg = generate_marm(tmp_path, "ros1")
    outside = tmp_path / "elsewhere" / "m.stl"
    outside.parent.mkdir()
    outside.write_text(TRIANGLE, encoding="utf-8")
    (pkg / "urdf").mkdir()
    mesh = uri.format(outside=outside)
    (pkg / "urdf" / "r.urdf").write_text(
        f'<robot name="marm"><link name="base_link"><collision><geometry><mesh filename="{mesh}"/>'
        "</geometry></collision></link></robot>",
        encoding="utf-8",
    )
    _point_urdf(pkg, "urdf/r.urdf")
    result = run("validate", pkg, "--no-plan", "--untrusted")
    assert_clean_exit(result)
    assert "lies outside the package: not read" in result.output
    trusted = run("validate", pkg, "--no-plan")
    assert "lies outside the package" not in trusted.output
    page = tmp_path / "r.html"
    report = run("report", pkg, "-o", page, "--no-plan", "--untrusted", "--trials", "10")
    assert_clean_exit(report)
    assert page.is_file() and "0 meshes" in report.output


@pytest.mark.parametrize("writer", ["report", "collisions --output", "collisions --report", "plan --output"])
def test_no_writer_follows_a_symlink_it_did_not_create(tmp_path, writer):
    pkg = generate_marm(tmp_path, "ros1")
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me\n", encoding="utf-8")
    name = {"report": "report.html", "collisions --report": "m.svg"}.get(writer, "out.yaml")
    link = pkg / name
    link.symlink_to(victim)
    urdf = tmp_path / "r.urdf"
    urdf.write_text(
        '<robot name="r"><link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry>'
        "</collision></link></robot>",
        encoding="utf-8",
    )
    args = {
        "report": ["report", pkg, "-o", link, "--no-plan", "--trials", "10"],
        "collisions --output": ["collisions", urdf, "--trials", "10", "--output", link],
        "collisions --report": ["collisions", urdf, "--trials", "10", "--report", link],
        "plan --output": ["plan", pkg, "--group", "arm", "--from", "home", "--to", "ready", "--output", link],
    }[writer]
    result = run(*args)
    assert_one_line_error(result, "is a symlink", "not written through")
    assert victim.read_text(encoding="utf-8") == "keep me\n" and link.is_symlink()

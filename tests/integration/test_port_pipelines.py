"""A port carries the planning pipelines move_group loads and each one's parameters (issue 27):
the package model of the source and of the port hold the same pipelines and, per pipeline, the
same parameters as the target distro reads them, or the port report names each difference; a
Humble package with OMPL + STOMP + Pilz (fixtures/kinova_gen3/setup.yaml) ported to Jazzy and
back is the package it was."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.package.read import read_package
from marm_setup.port.pipelines import RENAMED, pipeline_key
from tests.conftest import FIXTURES, MARM_URDF, realworld2

runner = CliRunner()
STRUCTURE = ("planning_plugin", "planning_plugins")


def port(
    source: Path, out: Path, distro: str, paths: tuple[Path, ...] = (), clean: bool = True
) -> list[dict]:
    argv = ["init", "--from-package", str(source), "--out", str(out), "--target", "ros2"]
    argv += ["--ros-distro", distro, "--no-plan", "--format", "json", "--jobs", "1"]
    made = runner.invoke(app, [*argv, *(a for p in paths for a in ("--package-path", str(p)))])
    assert made.exit_code in (0, 1), made.output
    doc = json.loads(made.stdout)
    assert not clean or doc["validation"]["errors"] == 0, doc["validation"]
    return doc["port"]["items"]


def pipelines(pkg: Path, paths: tuple[Path, ...] = ()) -> dict[str, dict[str, object]]:
    """Setup name -> the parameters of its namespace (sub-namespaces flattened, no plugin)."""
    out = {}
    for p in read_package(pkg, package_paths=paths).pipelines:
        params = {s.key: s.value for s in p.settings if s.key not in STRUCTURE and s.key != "totg"}
        params.update({f"totg.{k}": v for s in p.settings if s.key == "totg" for k, v in s.value})
        for entry in p.groups:
            params.update({n: q.value for q in entry.params if (n := f"{entry.group}.{q.key}") in RENAMED})
        out[pipeline_key(p)] = params
    return out


def unexplained(before: dict, after: dict, items: list[dict]) -> dict[str, object]:
    """Source parameters the port neither keeps (under their name or the target's) nor reports."""
    explained = {i["setting"] for i in items if i["status"] in ("changed", "dropped")}
    namespaces = {"pilz": "pilz_industrial_motion_planner"}
    missing = {}
    for key, params in before.items():
        for name, value in params.items():
            kept = after.get(key, {})
            if kept.get(name, kept.get(RENAMED.get(name, ""), object())) == value:
                continue
            if f"{namespaces.get(key, key)}.{name}" not in explained:
                missing[f"{key}.{name}"] = value
    return missing


def init_marm(out: Path, setup: str) -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    spec = out.parent / "spec.yaml"
    lines = (FIXTURES / "marm" / "marm_setup.yaml").read_text().splitlines(keepends=True)
    spec.write_text("".join(x for x in lines if not x.startswith(("target:", "driver:"))) + setup)
    argv = ["init", str(MARM_URDF), "--setup", str(spec), "--out", str(out), "--trials", "200", "--jobs", "1"]
    made = runner.invoke(app, [*argv, "--package-path", str(FIXTURES / "marm"), "--no-plan"])
    assert made.exit_code == 0, made.output


CHOMP_SETUP = """
target: ros2
ros_distro: humble
planning_pipelines: [chomp, ompl, pilz]
pipeline_parameters:
  chomp: {planning_time_limit: 4.5, max_iterations: 120, trajectory_initialization_method: linear}
  ompl: {jiggle_fraction: 0.2, path_tolerance: 0.05}
"""


def test_a_humble_ports_pipelines_and_parameters_reach_jazzy(tmp_path):
    """CHOMP first (move_group's default), its parameters, OMPL's path_tolerance as Jazzy's
    totg.path_tolerance; jiggle_fraction (Humble's FixStartStateCollision) reported dropped."""
    init_marm(tmp_path / "humble" / "pkg", CHOMP_SETUP)
    items = port(tmp_path / "humble" / "pkg", tmp_path / "jazzy" / "pkg", "jazzy", (FIXTURES / "marm",))
    text = (tmp_path / "jazzy" / "pkg" / "marm_setup.yaml").read_text()
    assert "planning_pipelines:\n- chomp\n- ompl\n- pilz\n" in text
    assert "planning_time_limit: 4.5" in text and "totg.path_tolerance: 0.05" in text
    before, after = pipelines(tmp_path / "humble" / "pkg"), pipelines(tmp_path / "jazzy" / "pkg")
    assert after["chomp"]["max_iterations"] == 120 and after["ompl"]["totg.path_tolerance"] == 0.05
    assert unexplained(before, after, items) == {}
    dropped = {i["setting"] for i in items if i["status"] == "dropped"}
    assert "ompl.jiggle_fraction" in dropped


def test_noetic_keeps_the_pipelines_and_reports_the_parameters(tmp_path):
    init_marm(tmp_path / "humble" / "pkg", CHOMP_SETUP)
    argv = ["init", "--from-package", str(tmp_path / "humble" / "pkg"), "--out", str(tmp_path / "n" / "pkg")]
    made = runner.invoke(app, [*argv, "--target", "ros1", "--no-plan", "--format", "json", "--jobs", "1"])
    assert made.exit_code in (0, 1), made.output
    items = json.loads(made.stdout)["port"]["items"]
    text = (tmp_path / "n" / "pkg" / "marm_setup.yaml").read_text()
    assert "planning_pipelines:\n- chomp\n- ompl\n- pilz\n" in text and "pipeline_parameters" not in text
    dropped = {i["setting"] for i in items if i["status"] == "dropped"}
    assert {"chomp.planning_time_limit", "chomp.max_iterations", "ompl.jiggle_fraction"} <= dropped


def gen3_humble(out: Path) -> tuple[Path, ...]:
    paths = (realworld2("ros2_kortex"), realworld2("ros2_robotiq_gripper"))
    gen3 = paths[0] / "kortex_description" / "robots" / "gen3.xacro"
    argv = ["init", str(gen3), "--xacro-arg", "dof:=7", "--xacro-arg", "gripper:=robotiq_2f_85"]
    argv += ["--setup", str(FIXTURES / "kinova_gen3" / "setup.yaml"), "--target", "ros2"]
    argv += ["--ros-distro", "humble", "--out", str(out), "--trials", "200", "--jobs", "1", "--no-plan"]
    made = runner.invoke(app, [*argv, *(a for p in paths for a in ("--package-path", str(p)))])
    assert made.exit_code == 0, made.output
    return paths


def test_gen3_ompl_stomp_pilz_to_jazzy_and_back(tmp_path):
    humble, jazzy, back = (tmp_path / d / "kinova_gen3_moveit_config" for d in ("h", "j", "b"))
    paths = gen3_humble(humble)
    items = port(humble, jazzy, "jazzy", paths)
    before, after = pipelines(humble, paths), pipelines(jazzy, paths)
    assert list(after) == ["ompl", "pilz", "stomp"]
    assert "planning_pipelines:\n- ompl\n- stomp\n- pilz\n" in (jazzy / "marm_setup.yaml").read_text()
    assert unexplained(before, after, items) == {}
    assert after["stomp"]["num_timesteps"] == 60 and after["pilz"]["default_planner_config"] == "PTP"
    port(jazzy, back, "humble", paths)
    assert pipelines(back, paths) == before


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_stomp_is_not_added_to_humble_from_a_vendor_package(tmp_path, distro):
    """A vendor's STOMP (MoveIt's panda, Jazzy format) reaches Jazzy; Humble's binaries lack it,
    so a port to Humble leaves it out and says what to build."""
    from tests.conftest import realworld

    source = realworld("ros2", "panda_moveit_config")
    items = port(
        source, tmp_path / "out", distro, (realworld("ros2"),), clean=False
    )  # panda's own pose collides
    line = next(i for i in items if i["setting"] == "planning_pipelines.stomp")
    assert line["status"] == ("dropped" if distro == "humble" else "carried")
    assert "chomp" in pipelines(tmp_path / "out")

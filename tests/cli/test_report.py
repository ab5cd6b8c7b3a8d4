"""`marm-setup report`: the page is written for any package validate reads, byte-identical for
the same inputs, with validate's exit codes (the drawing itself: tests/integration/test_report_browser.py)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import realworld
from tests.report_helpers import broken_marm, marm_package


def page_data(page: Path) -> dict:
    """The JSON the page's script reads."""
    text = page.read_text(encoding="utf-8")
    found = re.search(r'<script type="application/json" id="report-data">(.*?)</script>', text, re.S)
    assert found is not None
    return json.loads(found.group(1))


def report(*args: str | Path):
    return CliRunner().invoke(app, ["report", *map(str, args)])


@pytest.fixture(scope="module")
def root(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("report")


def test_a_good_package_gives_exit_0_and_every_part_of_the_page(root, tmp_path):
    page = tmp_path / "marm.html"
    result = report(marm_package(root), "-o", page)
    assert result.exit_code == 0, result.output
    assert result.stdout.startswith(f"wrote {page} (") and "0 errors, 0 warnings" in result.stdout
    data = page_data(page)
    assert data["robot"] == "marm" and data["summary"]["errors"] == 0
    keys = [s["key"] for s in data["states"]]
    assert keys == ["default", "start", "pose:arm:home", "pose:gripper:home", "pose:arm:ready"]
    assert {g["name"] for g in data["groups"]} >= {"arm", "gripper"}
    assert [e["name"] for e in data["end_effectors"]] and [v["type"] for v in data["virtual_joints"]] == [
        "fixed"
    ]
    assert data["motions"] and all(m["problem"] == "" and m["moving"] for m in data["motions"])
    pairs = data["matrix"]["pairs"]
    assert pairs and {p["reason"] for p in pairs} >= {"Adjacent", "Never", None}
    assert data["matrix"]["svg"].lstrip().startswith("<?xml") or "<svg" in data["matrix"]["svg"]


def test_the_same_package_gives_the_same_bytes(root, tmp_path):
    pkg = marm_package(root)
    first, second = tmp_path / "a.html", tmp_path / "b.html"
    assert report(pkg, "-o", first, "--jobs", "1").exit_code == 0
    assert report(pkg, "-o", second, "--jobs", "2").exit_code == 0
    assert first.read_bytes() == second.read_bytes()


def test_errors_give_exit_1_and_the_page_shows_them_with_their_states(root, tmp_path):
    page = tmp_path / "broken.html"
    result = report(broken_marm(root), "-o", page, "--no-plan")
    assert result.exit_code == 1, result.output
    data = page_data(page)
    by_rule = {f["rule"]: f for f in data["findings"]}
    assert {"pose.collision", "matrix.stale"} <= set(by_rule)
    states = {s["key"]: s for s in data["states"]}
    assert states["pose:arm:ready"]["contacts"], "the pose in collision names the links in contact"
    for rule in ("pose.collision", "matrix.stale"):
        finding = by_rule[rule]
        shown = states[finding["state"]]
        assert shown["contacts"] == [sorted(finding["evidence"]["links"])]
        assert shown["joints"] == {k: round(v, 6) for k, v in finding["evidence"]["state"].items()}
    assert data["motions"] == []  # --no-plan


def test_not_a_package_is_one_error_line_and_no_file(tmp_path):
    page = tmp_path / "out.html"
    result = report(tmp_path / "missing", "-o", page)
    assert result.exit_code == 2
    assert result.stderr.startswith("error: ") and len(result.stderr.splitlines()) == 1
    assert "Traceback" not in result.output and not page.exists()


def test_the_output_must_be_html(root, tmp_path):
    result = report(marm_package(root), "-o", tmp_path / "report.svg")
    assert result.exit_code == 2 and "--output" in result.stderr and "expected an .html file" in result.stderr


def test_a_setup_assistant_package_with_package_paths(tmp_path):
    pkg = realworld("ros1", "panda_moveit_config")
    page = tmp_path / "panda.html"
    result = report(pkg, "--package-path", realworld("ros1"), "-o", page, "--trials", "1000", "--no-plan")
    assert result.exit_code == 1, result.output  # its 'transport' pose is in collision
    data = page_data(page)
    transport = next(s for s in data["states"] if s["key"] == "pose:panda_arm:transport")
    assert transport["contacts"] and data["matrix"]["trials"] == 1000


def test_the_page_proves_the_matrix_itself_whatever_the_package_records(tmp_path):
    """A package whose marm_setup.yaml vouches for a colliding Never pair (listed as proved,
    its proof key recomputed, `trials: 0`) gets no proof from the page: the page proves the
    matrix itself, shows that pair in collision and every other Never pair proved or unproved."""
    from marm_setup.robot.load import load_robot
    from tests.conftest import MARM_URDF
    from tests.validate_helpers import vouching_package

    pkg, pair = vouching_package(tmp_path, load_robot(MARM_URDF, {}, []))
    page = tmp_path / "marm.html"
    assert report(pkg, "-o", page, "--no-plan", "--trials", "1000").exit_code == 0  # stale: a warning
    matrix = page_data(page)["matrix"]
    assert matrix["prove"] == "on" and matrix["trials"] == 1000
    pairs = {(p["link1"], p["link2"]): p for p in matrix["pairs"]}
    assert pairs[pair]["reason"] == "Never" and pairs[pair]["proof"] != "proved" and pairs[pair]["hits"] > 0
    never = [p for key, p in pairs.items() if p["reason"] == "Never" and key != pair]
    assert never and all(p["proof"] in ("proved", "unproved") for p in never)


def test_a_package_without_recorded_proofs_is_proved_and_its_disabled_contacts_drawn(tmp_path):
    """The Setup Assistant's panda package records no proofs: the page proves the matrix as
    `collisions` does; a pair its SRDF disables that a proof finds in contact (link 2 against
    link 6, which 10,000 of the Setup Assistant's samples missed) is drawn at the witness state,
    which really is in contact."""
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.robot.load import load_robot

    pkg = realworld("ros1", "panda_moveit_config")
    page = tmp_path / "panda.html"
    result = report(pkg, "--package-path", realworld("ros1"), "-o", page, "--trials", "1000", "--no-plan")
    assert result.exit_code == 1, result.output
    data = page_data(page)
    matrix = data["matrix"]
    assert matrix["prove"] == "on" and matrix["proofs"]["collides"] > 0
    found = [p for p in matrix["pairs"] if p["proof"] == "collides" and p["reason"] is not None]
    assert found, "no disabled pair found in contact"
    states = {s["key"]: s for s in data["states"]}
    robot = load_robot(
        realworld("ros1", "panda_description", "urdf", "panda_arm_hand.urdf.xacro"), {}, [realworld("ros1")]
    )
    scene = CollisionScene(robot)
    for p in found:
        state = states[f"witness:{p['link1']}:{p['link2']}"]
        assert state["contacts"] == [[p["link1"], p["link2"]]]
        assert all(abs(state["joints"][joint] - value) < 1e-6 for joint, value in p["witness"].items())
        q = np.array([state["joints"][name] for name in robot.active_joint_names])
        pair_id = scene.pair_ids([(p["link1"], p["link2"])])[0]
        assert scene.collide(scene.link_poses(q[None])[0], int(pair_id))


def test_a_report_after_init_proves_nothing_again(tmp_path, monkeypatch):
    """The page's matrix is init's run again (same trials, seed and robot): every proof, the
    unproved ones too, comes from the proof cache that init filled."""
    pkg = marm_package(tmp_path)  # init's package, and its proofs in this test's cache

    def proved_again(*args, **kwargs):
        raise AssertionError("a pair was proved again")

    monkeypatch.setattr("marm_setup.collision.proving.prove_pair", proved_again)
    result = report(pkg, "-o", tmp_path / "page.html")
    assert result.exit_code == 0, result.output

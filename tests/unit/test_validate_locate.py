"""validate/locate.py and sarif.py's regions: where review tools put a finding."""

from __future__ import annotations

import pytest

from marm_setup.findings import error
from marm_setup.validate.locate import finding_uri, location_base, repository_root
from marm_setup.validate.sarif import line_of


def test_line_of_reads_line_elements_only():
    assert line_of("line 12") == 12
    assert line_of("line 7: <arg>") == 7
    assert line_of("line 0") is None  # lxml's unknown line
    assert line_of("group[arm]/chain") is None
    assert line_of("line 12a") is None
    assert line_of("pipeline 3: x") is None


def test_uris_are_relative_to_the_repository_else_a_file_uri(tmp_path):
    repo = tmp_path / "repo"
    pkg = repo / "robots" / "pkg"
    (pkg / "config").mkdir(parents=True)
    (repo / ".git").mkdir()
    (pkg / "package.xml").write_text("<package/>", encoding="utf-8")
    outside = tmp_path / "robot.urdf"
    outside.write_text("<robot/>", encoding="utf-8")
    assert repository_root(pkg / "config") == repo.resolve()
    base = location_base(pkg)
    assert finding_uri(error("srdf.x", "config/a.srdf", "", "m"), pkg, base) == "robots/pkg/config/a.srdf"
    assert finding_uri(error("package.x", "", "", "m"), pkg, base) == "robots/pkg/package.xml"
    assert finding_uri(error("urdf.x", str(outside), "", "m"), pkg, base) == outside.resolve().as_uri()


def test_without_a_repository_uris_are_relative_to_the_current_folder(tmp_path, monkeypatch):
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    monkeypatch.chdir(tmp_path)
    if repository_root(tmp_path) is not None:
        pytest.skip("the temporary folder is inside a git checkout")
    assert location_base(pkg) == tmp_path.resolve()
    assert finding_uri(error("launch.x", "launch", "", "m"), pkg, location_base(pkg)) == "pkg/launch"

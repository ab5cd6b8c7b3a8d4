"""The report page survives any link name (issue 36): MeshCat's scene tree is a plain object, so
the page's viewer paths are keys it makes (`node(name)`), never a name such as `constructor`."""

from __future__ import annotations

import re

import pytest

from marm_setup.templating import templates_dir
from tests.reliability.checks import assert_clean_exit, run

VIEWER_PATH = re.compile(r"viewer\.set_(?:object|transform)\(\[\"robot\", ([^\]]+)\]")


def test_every_robot_path_of_the_viewer_is_a_made_key():
    script = (templates_dir() / "report" / "report.js").read_text(encoding="utf-8")
    paths = VIEWER_PATH.findall(script)
    assert paths and all(p.startswith("node(") for p in paths), paths


@pytest.mark.parametrize("name", ["constructor", "__proto__", "toString", "hasOwnProperty"])
def test_a_report_of_links_named_like_object_properties(tmp_path, name):
    urdf = tmp_path / "r.urdf"
    box = '<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>'
    urdf.write_text(
        f'<robot name="r"><link name="base">{box}</link><link name="{name}">{box}</link>'
        f'<joint name="j" type="revolute"><parent link="base"/><child link="{name}"/>'
        '<origin xyz="0 0 0.2"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/>'
        "</joint></robot>",
        encoding="utf-8",
    )
    pkg = tmp_path / "pkg"
    assert_clean_exit(run("init", urdf, "--out", pkg, "--trials", "10", "--target", "ros2"), codes=(0,))
    page = tmp_path / "r.html"
    result = run("report", pkg, "-o", page, "--no-plan", "--trials", "10")
    assert_clean_exit(result, codes=(0, 1))
    assert f'"{name}"' in page.read_text(encoding="utf-8")

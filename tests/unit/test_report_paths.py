"""report/paths.py: the page names files relative to the package, never by the machine's folders."""

from __future__ import annotations

from pathlib import Path

from marm_setup.report.paths import page_path, relative_content, relative_text

PACKAGES = {Path("/opt/ws/share/robot_description"): "robot_description"}


def package_of(folder: Path) -> str | None:
    return PACKAGES.get(folder)


def test_inside_the_workspace_a_path_is_relative_to_the_package(tmp_path):
    root = tmp_path / "src" / "robot_moveit_config"
    assert page_path(root / "config" / "robot.srdf", root, package_of) == "config/robot.srdf"
    sibling = tmp_path / "src" / "robot_description" / "urdf" / "robot.urdf"
    assert page_path(sibling, root, package_of) == "../robot_description/urdf/robot.urdf"


def test_elsewhere_a_ros_package_file_is_a_package_uri_and_anything_else_its_tail(tmp_path):
    root = tmp_path / "robot_moveit_config"
    urdf = "/opt/ws/share/robot_description/urdf/robot.urdf"
    assert page_path(urdf, root, package_of) == "package://robot_description/urdf/robot.urdf"
    assert page_path("/usr/local/bin/python3", root, package_of) == "…/bin/python3"


def test_free_text_loses_machine_paths_and_keeps_ros_names(tmp_path):
    root = tmp_path / "pkg"
    text = f"tried /usr/bin/python3: no launch; from {root}/urdf/r.urdf (marm_setup.yaml); /robot_description"
    shown = relative_text(text, root, package_of)
    assert shown == "tried …/bin/python3: no launch; from urdf/r.urdf (marm_setup.yaml); /robot_description"
    assert (
        relative_text("/move_group/planning_pipelines", root, package_of) == "/move_group/planning_pipelines"
    )


def test_the_content_text_is_rewritten_and_the_rest_kept(tmp_path):
    root = tmp_path / "pkg"
    content = {
        "robot": "r",
        "summary": {"validated": f"from {root}/r.urdf", "errors": 1},
        "findings": [
            {"file": f"{root}/a.yaml", "element": "e", "message": f"see {tmp_path}/x/y", "hint": None}
        ],
        "states": [{"key": "k", "title": "t", "note": f"{root}/n", "frames": "AAA/"}],
    }
    out = relative_content(content, root, package_of)
    assert out["summary"] == {"validated": "from r.urdf", "errors": 1}
    assert out["findings"][0] == {"file": "a.yaml", "element": "e", "message": "see ../x/y", "hint": None}
    assert out["states"][0] == {"key": "k", "title": "t", "note": "n", "frames": "AAA/"}
    assert str(tmp_path) not in repr(out)

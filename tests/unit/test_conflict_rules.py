"""Git merge-conflict markers in any file of a package (validate/rules/conflict_rules.py):
an error naming the file and line where ROS parses the file, a warning in a file no ROS tool
reads; binary files, hidden folders and an reStructuredText underline are not markers."""

from __future__ import annotations

import os

import pytest

from marm_setup.validate.rules.conflict_rules import check_merge_conflicts, first_marker
from tests.helpers import build_file_tree
from tests.validate_helpers import copy_package, panda, replace_text, run

CONFLICT = (
    '<<<<<<< HEAD\n  <arg name="a" default="1"/>\n=======\n  <arg name="a" default="2"/>\n>>>>>>> other\n'
)


def found(root) -> list[tuple[str, str, str]]:
    return [(f.file, f.element, str(f.severity)) for f in check_merge_conflicts(root)]


def test_markers_in_any_file_name_the_file_and_line(tmp_path):
    root = build_file_tree(
        tmp_path,
        {
            "launch/demo.launch": f"<launch>\n{CONFLICT}</launch>\n",
            "CMakeLists.txt": "cmake_minimum_required(VERSION 3.1)\n>>>>>>> theirs\n",
            "config/kinematics.yaml": "arm:\n<<<<<<< ours\n  kinematics_solver_timeout: 0.05\n",
            "README.md": f"# bot\n\n{CONFLICT}",
            "README.rst": "Title\n=======\n\ntext\n",  # an underline, no conflict
            "config/ok.srdf": "<robot name='b'>\n<!-- <<<<<<< in a comment, not at a line start -->\n</robot>\n",
        },
    )
    assert found(root) == [
        ("CMakeLists.txt", "line 2", "error"),
        ("README.md", "line 3", "warning"),
        ("config/kinematics.yaml", "line 2", "error"),
        ("launch/demo.launch", "line 2", "error"),
    ]


def test_binary_files_hidden_folders_and_special_files_are_not_read(tmp_path):
    root = build_file_tree(tmp_path, {".git/MERGE_MSG": CONFLICT, ".marm_setup/x.yaml": CONFLICT})
    (root / "meshes").mkdir()
    (root / "meshes/link.stl").write_bytes(b"solid\n" + CONFLICT.encode())
    (root / "blob.dat").write_bytes(b"\0\1" + CONFLICT.encode())
    (root / "outside.yaml").symlink_to(root / ".git/MERGE_MSG")
    os.mkfifo(root / "pipe.yaml")  # opening it would block
    assert found(root) == []


@pytest.mark.parametrize(
    ("text", "line"),
    [
        (b"a\n<<<<<<<\nb\n", 2),
        (b"a\r\n=======\r\n>>>>>>> x\r\n", 3),  # a lone separator is no marker; the end one is
        (b"<<<<<<<< eight\n", None),
        (b"a\n<<<<<<< HEAD\n", 2),
    ],
)
def test_what_a_marker_is(text, line):
    assert first_marker(text) == line


def test_validate_reports_a_conflicted_launch_file_of_a_real_package(tmp_path):
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(pkg, "launch/move_group.launch", "<launch>", "<launch>\n" + CONFLICT)
    conflicts = [
        (f.rule, f.file, f.element) for f in run(pkg, good) if f.is_error and f.rule.startswith("file.")
    ]
    assert conflicts == [("file.merge-conflict", "launch/move_group.launch", "line 2")]

"""Finding values: order, de-duplication, text and json output."""

from __future__ import annotations

import json

import pytest

from marm_setup.findings import Finding, error, format_json, format_text, sort_findings, summary, warning

F1 = error("srdf.unknown-link", "config/a.srdf", "group[arm].link", "unknown link 'x'", "did you mean y?")
F2 = warning("limits.above-urdf", "config/joint_limits.yaml", "joint_limits.j1.max_velocity", "too fast")
F3 = error("srdf.robot-name", "config/a.srdf", "robot", "wrong name")


def test_sorted_by_file_then_element_and_deduplicated():
    assert sort_findings([F3, F1, F2, F1]) == [F1, F3, F2]


def test_severity_is_checked():
    with pytest.raises(ValueError):
        Finding("x.y", "fatal", "f", "e", "m")


def test_text_groups_by_file_with_hint_and_summary():
    text = format_text([F3, F2, F1])
    assert text.splitlines() == [
        "config/a.srdf",
        "  error   group[arm].link: unknown link 'x' [srdf.unknown-link]",
        "          hint: did you mean y?",
        "  error   robot: wrong name [srdf.robot-name]",
        "config/joint_limits.yaml",
        "  warning joint_limits.j1.max_velocity: too fast [limits.above-urdf]",
        "2 errors, 1 warning",
    ]
    assert "\x1b[" not in text
    assert "\x1b[31merror" in format_text([F1], color=True)


def test_json_round_trips():
    doc = json.loads(format_json([F2, F1]))
    assert doc["errors"] == 1 and doc["warnings"] == 1
    assert [Finding(**f) for f in doc["findings"]] == [F1, F2]


def test_summary_when_clean():
    assert summary([]) == "no findings"
    assert format_text([]) == "no findings\n"

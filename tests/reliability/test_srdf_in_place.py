"""`collisions --srdf` edits the real root element in place: comments, entities, processing
instructions elsewhere stay byte for byte; a symlinked SRDF is followed; the mode is kept."""

from __future__ import annotations

import os
import stat

from lxml import etree

from tests.helpers import TWO_BOXES
from tests.reliability.checks import assert_clean_exit, run

HEAD = '<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY b "b">]>\n<?pi </robot> ?>\n'


def _collide(tmp_path, srdf_text: str, *extra: str):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(TWO_BOXES)
    srdf = tmp_path / "r.srdf"
    srdf.write_text(srdf_text)
    return srdf, run("collisions", urdf, "--trials", "20", "--srdf", srdf, *extra)


def _pairs(path) -> list[tuple[str, str, str]]:
    root = etree.parse(str(path)).getroot()
    return [(e.get("link1"), e.get("link2"), e.get("reason")) for e in root.iter("disable_collisions")]


def test_a_closing_tag_in_a_comment_after_the_root(tmp_path):
    text = '<robot name="test_robot">\n</robot>\n<!-- old copy: <robot name="x"></robot> -->\n'
    srdf, result = _collide(tmp_path, text)
    assert_clean_exit(result, codes=(0,))
    written = srdf.read_text()
    assert written.endswith('</robot>\n<!-- old copy: <robot name="x"></robot> -->\n')
    assert _pairs(srdf) == [("a", "b", "Adjacent")]


def test_entities_pis_and_a_raw_slash_gt_in_attributes(tmp_path):
    text = (
        HEAD + '<robot name="test_robot">\n'
        '  <disable_collisions link1="a" link2="&b;" reason="User"/>\n'
        '  <disable_collisions link1="a" link2="b" reason="x/>y"/>\n'
        "</robot>\n"
    )
    srdf, result = _collide(tmp_path, text)
    assert_clean_exit(result, codes=(0,))
    written = srdf.read_text()
    assert written.startswith(HEAD + '<robot name="test_robot">\n  <disable_collisions link1="a" link2="&b;"')
    assert ("a", "b", "User") in _pairs(srdf)


def test_a_symlinked_srdf_is_followed_and_keeps_its_mode(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    target = real / "robot.srdf"
    target.write_text('<robot name="test_robot">\n</robot>\n')
    target.chmod(0o640)
    link = tmp_path / "link.srdf"
    link.symlink_to(target)
    urdf = tmp_path / "r.urdf"
    urdf.write_text(TWO_BOXES)
    result = run("collisions", urdf, "--trials", "20", "--srdf", link)
    assert_clean_exit(result, codes=(0,))
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert _pairs(target) == [("a", "b", "Adjacent")]
    assert stat.S_IMODE(target.stat().st_mode) == 0o640


def test_a_new_output_file_gets_the_umask_mode(tmp_path):
    urdf = tmp_path / "r.urdf"
    urdf.write_text(TWO_BOXES)
    out = tmp_path / "out.srdf"
    old = os.umask(0o022)
    try:
        assert_clean_exit(run("collisions", urdf, "--trials", "20", "--output", out), codes=(0,))
    finally:
        os.umask(old)
    assert stat.S_IMODE(out.stat().st_mode) == 0o644


def test_an_srdf_of_70000_entries(tmp_path):
    """Line numbers were counted from the start of the file for every entry and the edits
    spliced into the whole text one by one (quadratic: 50,000 entries took minutes), and past
    line 65534 libxml2 reports some lines one too high (its 16-bit marker), which refused the
    file as 'an unexpected form'. Now both are linear and big line numbers are matched."""
    body = "".join(
        f'  <disable_collisions link1="u{i}" link2="v{i}" reason="{"User" if i % 2 else "Never"}"/>\n'
        for i in range(70_000)
    )
    srdf, result = _collide(tmp_path, f'<robot name="test_robot">\n{body}</robot>\n', "--force")
    assert_clean_exit(result, codes=(0,))
    pairs = _pairs(srdf)
    assert len(pairs) == 35_001 and pairs[0] == ("a", "b", "Adjacent")  # where the first Never was
    assert pairs[1] == ("u1", "v1", "User") and pairs[-1] == ("u69999", "v69999", "User")

"""`init --force` over a package of the other target (issue 36): the files the old package's
init wrote that the new one does not generate are removed when unchanged since written, listed
when edited by hand, and a file marm-setup did not write is never touched."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from marm_setup.render.commit_record import COMMIT
from tests.conftest import MARM_URDF
from tests.reliability.checks import assert_clean_exit, run

MANIFEST = ".marm_setup/manifest.json"


def _init(out: Path, target: str, *more: str):
    result = run("init", MARM_URDF, "--out", out, "--target", target, "--trials", "20", *more)
    assert_clean_exit(result, codes=(0,))
    return result


def _files(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*") if p.is_file() or p.is_symlink()}


def _folders(root: Path) -> set[str]:
    return {str(p.relative_to(root)) for p in root.rglob("*") if p.is_dir() and not p.is_symlink()}


@pytest.mark.parametrize("old, new", [("ros1", "ros2"), ("ros2", "ros1")])
@pytest.mark.parametrize("in_place", [False, True], ids=["swapped", "in-place"])
def test_a_target_switch_removes_the_old_targets_files_only(tmp_path, monkeypatch, old, new, in_place):
    fresh, pkg = tmp_path / "fresh", tmp_path / "pkg"
    _init(fresh, new)  # what the new target's package alone holds
    _init(pkg, old)
    generated = _files(pkg)
    leftovers = sorted(generated - _files(fresh))
    assert len(leftovers) >= 5
    edited, *unchanged = leftovers
    (pkg / edited).write_text((pkg / edited).read_text() + "\n# my edit\n")
    mine = [f"{Path(edited).parent}/notes.txt", "my_folder/mine.yaml"]
    for rel in mine:
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text("mine\n")
    if in_place:
        monkeypatch.chdir(pkg)  # a package holding the current folder is written in place
    out = _init(pkg, new, "--force").stdout

    assert _files(pkg) == _files(fresh) | {edited, *mine}
    assert _folders(pkg) == _folders(fresh) | {str(Path(r).parent) for r in mine}  # emptied: gone
    lines = out.splitlines()
    assert f"stale     {edited} (no longer generated; edited by hand since written: left in place)" in lines
    for rel in unchanged:
        assert f"remove    {rel} (no longer generated; unchanged since written: removed)" in lines
    assert not any(rel in out for rel in mine)
    recorded = set(json.loads((pkg / MANIFEST).read_text())["files"])
    assert recorded == set(json.loads((fresh / MANIFEST).read_text())["files"]) | {edited}
    assert not (pkg / COMMIT).exists()


def test_a_leftover_made_a_link_is_neither_removed_nor_followed(tmp_path):
    pkg, outside = tmp_path / "pkg", tmp_path / "outside.launch"
    _init(pkg, "ros1")
    rel = "launch/move_group.launch"
    outside.write_bytes((pkg / rel).read_bytes())  # the bytes marm-setup wrote, but not its file
    (pkg / rel).unlink()
    os.symlink(outside, pkg / rel)
    out = _init(pkg, "ros2", "--force").stdout
    assert f"stale     {rel}" in out
    assert (pkg / rel).is_symlink() and outside.read_bytes()


def test_without_force_nothing_is_removed_and_render_only_lists(tmp_path):
    pkg = tmp_path / "pkg"
    _init(pkg, "ros1")
    before = _files(pkg)
    setup = pkg / "marm_setup.yaml"
    setup.write_text(setup.read_text().replace("target: ros1", "target: ros2").replace("noetic", "humble"))
    result = run("render", pkg)
    assert_clean_exit(result, codes=(0,))
    assert "stale     launch/move_group.launch (no longer generated; left in place)" in result.stdout
    assert before <= _files(pkg)


def test_a_killed_in_place_switch_removes_its_files_on_the_next_write(tmp_path):
    from marm_setup.render.switch import finish_interrupted

    pkg = tmp_path / "pkg"
    (pkg / ".marm_setup/stage-abc").mkdir(parents=True)
    (pkg / ".marm_setup/stage-abc/new.yaml").write_text("new\n")
    for rel in ("old/a.launch", "kept.txt"):
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text("old\n")
    record = {"stage": ".marm_setup/stage-abc", "files": ["new.yaml"], "remove": ["old/a.launch"]}
    (pkg / COMMIT).write_text(json.dumps(record))
    finish_interrupted(pkg)
    assert _files(pkg) == {"new.yaml", "kept.txt"} and not (pkg / "old").exists()


@pytest.mark.parametrize("bad", ["../outside.txt", ".marm_setup/manifest2.json", "/etc/passwd"])
def test_a_commit_record_removing_outside_the_generated_files_is_refused(tmp_path, bad):
    from marm_setup.errors import InputError
    from marm_setup.render.switch import finish_interrupted

    pkg, outside = tmp_path / "pkg", tmp_path / "outside.txt"
    (pkg / ".marm_setup").mkdir(parents=True)
    outside.write_text("mine\n")
    (pkg / COMMIT).write_text(json.dumps({"stage": ".marm_setup/stage-abc", "files": [], "remove": [bad]}))
    with pytest.raises(InputError, match="remove"):
        finish_interrupted(pkg)
    assert outside.read_text() == "mine\n" and (pkg / COMMIT).exists()

"""writer: new / identical / update / conflict by content hash, staged atomic writes."""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest

from marm_setup.errors import ConflictError, InputError
from marm_setup.render.writer import (
    MANIFEST,
    apply_writes,
    check_output_dir,
    format_change,
    load_manifest,
    plan_writes,
    sha256,
    stale_files,
)
from marm_setup.templating import RenderedFile

FILES = [
    RenderedFile("package.xml", "<package/>\n"),
    RenderedFile("config/a.yaml", "a: 1\n"),
    RenderedFile("scripts/run.py", "print('hi')\n"),
]


def statuses(changes):
    return {c.path: c.status for c in changes}


def write_all(files, out: Path, force=False):
    return apply_writes(plan_writes(files, out), out, force=force)


def test_fresh_package_is_all_new_and_written_with_manifest(tmp_path):
    out = tmp_path / "pkg"
    changes = plan_writes(FILES, out)
    assert [c.path for c in changes] == sorted(f.path for f in FILES)
    assert set(statuses(changes).values()) == {"new"}
    apply_writes(changes, out)
    for f in FILES:
        assert (out / f.path).read_bytes() == f.content.encode()
    manifest = load_manifest(out)
    assert manifest == {f.path: sha256(f.content.encode()) for f in FILES}
    assert json.loads((out / MANIFEST).read_text())["files"] == manifest
    assert os.access(out / "scripts/run.py", os.X_OK)
    assert [p.name for p in tmp_path.iterdir()] == ["pkg"]  # no staging dir left behind


def test_rerender_is_identical_and_writes_nothing(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    before = {p: p.stat().st_mtime_ns for p in out.rglob("*") if p.is_file()}
    changes = plan_writes(FILES, out)
    assert set(statuses(changes).values()) == {"identical"}
    assert apply_writes(changes, out) == []
    # an mtime change alone is not an edit: hashes decide
    os.utime(out / "config/a.yaml", (1, 1))
    assert statuses(plan_writes(FILES, out))["config/a.yaml"] == "identical"
    assert before[out / "package.xml"] == (out / "package.xml").stat().st_mtime_ns
    assert before[out / MANIFEST] == (out / MANIFEST).stat().st_mtime_ns  # a true no-op


def test_changed_render_of_untouched_file_is_update(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    new = [FILES[0], RenderedFile("config/a.yaml", "a: 2\n"), FILES[2]]
    changes = plan_writes(new, out)
    assert statuses(changes)["config/a.yaml"] == "update"
    apply_writes(changes, out)
    assert (out / "config/a.yaml").read_text() == "a: 2\n"
    assert load_manifest(out)["config/a.yaml"] == sha256(b"a: 2\n")


def test_hand_edit_is_conflict_and_refused_without_force(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    (out / "config/a.yaml").write_text("a: 1  # mine\n")
    new = [FILES[0], RenderedFile("config/a.yaml", "a: 2\n"), RenderedFile("config/b.yaml", "b: 1\n")]
    changes = plan_writes(new, out)
    assert statuses(changes)["config/a.yaml"] == "conflict"
    with pytest.raises(ConflictError, match="config/a.yaml"):
        apply_writes(changes, out)
    assert (out / "config/a.yaml").read_text() == "a: 1  # mine\n"
    assert not (out / "config/b.yaml").exists()  # nothing half-written
    apply_writes(changes, out, force=True)
    assert (out / "config/a.yaml").read_text() == "a: 2\n"
    assert (out / "config/b.yaml").read_text() == "b: 1\n"


def test_untracked_file_on_disk_that_differs_is_conflict(tmp_path):
    out = tmp_path / "pkg"
    (out / "config").mkdir(parents=True)
    (out / "config/a.yaml").write_text("mine\n")
    assert statuses(plan_writes(FILES, out))["config/a.yaml"] == "conflict"


def test_hand_edit_matching_render_is_identical(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    (out / "config/a.yaml").write_text("a: 2\n")
    new = [RenderedFile("config/a.yaml", "a: 2\n")]
    assert statuses(plan_writes(new, out)) == {"config/a.yaml": "identical"}
    apply_writes(plan_writes(new, out), out)
    assert load_manifest(out)["config/a.yaml"] == sha256(b"a: 2\n")
    assert "package.xml" in load_manifest(out)  # other entries kept


def test_newlines_are_lf_and_utf8(tmp_path):
    out = tmp_path / "pkg"
    write_all([RenderedFile("x.txt", "é\nline\n")], out)
    assert (out / "x.txt").read_bytes() == "é\nline\n".encode()


def test_failure_while_staging_leaves_package_untouched(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    bad = [RenderedFile("config/a.yaml", "a: 3\n"), RenderedFile("package.xml", "\ud800")]
    with pytest.raises(UnicodeEncodeError):
        apply_writes(plan_writes(bad, out), out)
    assert (out / "config/a.yaml").read_text() == "a: 1\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pkg"]


def test_paths_escaping_the_package_are_rejected(tmp_path):
    with pytest.raises(InputError):
        plan_writes([RenderedFile("../evil", "x\n")], tmp_path / "pkg")


def test_check_output_dir(tmp_path):
    check_output_dir(tmp_path / "missing", force=False)
    (tmp_path / "empty").mkdir()
    check_output_dir(tmp_path / "empty", force=False)
    (tmp_path / "full").mkdir()
    (tmp_path / "full" / "x").write_text("x")
    with pytest.raises(InputError, match="not empty") as info:
        check_output_dir(tmp_path / "full", force=False, shown="full")
    assert info.value.path == "full"
    check_output_dir(tmp_path / "full", force=True)
    (tmp_path / "file").write_text("x")
    with pytest.raises(InputError, match="not a directory"):
        check_output_dir(tmp_path / "file", force=True)


def test_fresh_empty_dir_is_filled(tmp_path):
    out = tmp_path / "pkg"
    out.mkdir()
    write_all(FILES, out)
    assert (out / "package.xml").exists()


def test_format_change():
    changes = plan_writes([RenderedFile("a", "x\n")], Path("/nonexistent-marm"))
    assert format_change(changes[0]) == "create    a"


def test_stale_files_are_manifest_entries_no_longer_rendered(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    changes = plan_writes(FILES[:1], out)
    assert stale_files(changes, out) == ["config/a.yaml", "scripts/run.py"]
    assert stale_files(changes, out, keep=["scripts/run.py"]) == ["config/a.yaml"]
    (out / "config/a.yaml").unlink()
    assert stale_files(changes, out) == ["scripts/run.py"]


def test_os_errors_while_writing_are_input_errors_naming_the_file(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    (out / "config" / "a.yaml").unlink()
    (out / "config" / "a.yaml").mkdir()  # a folder where a generated file goes
    changes = plan_writes([RenderedFile("config/a.yaml", "a: 2\n")], out)
    with pytest.raises(InputError, match="cannot write") as info:
        apply_writes(changes, out)
    assert (info.value.path, info.value.element) == (str(out), "config/a.yaml")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pkg"]  # staging dir removed


def test_output_dir_below_a_file_is_refused(tmp_path):
    (tmp_path / "file").write_text("x")
    with pytest.raises(InputError, match="is not a directory"):
        check_output_dir(tmp_path / "file" / "pkg", force=False)
    with pytest.raises(InputError, match="cannot write"):
        write_all(FILES, tmp_path / "file" / "pkg")


def test_force_never_overwrites_an_earlier_orig(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    edits = []
    for n in (2, 3, 4):
        edit = f"a: 1  # mine {n}\n"
        (out / "config/a.yaml").write_text(edit)
        edits.append(edit)
        changes = plan_writes([RenderedFile("config/a.yaml", f"a: {n}\n")], out)
        assert changes[0].kept_as == "config/a.yaml.orig" + (f".{n - 2}" if n > 2 else "")
        write_all([RenderedFile("config/a.yaml", f"a: {n}\n")], out, force=True)
    kept = ["config/a.yaml.orig", "config/a.yaml.orig.1", "config/a.yaml.orig.2"]
    assert [(out / k).read_text() for k in kept] == edits
    assert (out / "config/a.yaml").read_text() == "a: 4\n"


def test_a_dangling_symlink_takes_an_orig_name(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    (out / "config/a.yaml.orig").symlink_to(tmp_path / "nowhere")
    (out / "config/a.yaml").write_text("mine\n")
    write_all([RenderedFile("config/a.yaml", "a: 2\n")], out, force=True)
    assert (out / "config/a.yaml.orig.1").read_text() == "mine\n"
    assert not (tmp_path / "nowhere").exists()


def test_format_change_names_the_file_kept_under_force(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    (out / "config/a.yaml").write_text("mine\n")
    (out / "config/a.yaml.orig").write_text("older\n")
    [change] = plan_writes([RenderedFile("config/a.yaml", "a: 2\n")], out)
    assert format_change(change) == "conflict  config/a.yaml"
    assert format_change(change, forced=True) == (
        "conflict  config/a.yaml (overwritten: --force; yours kept as config/a.yaml.orig.1)"
    )


def test_an_orig_name_taken_meanwhile_is_a_conflict(tmp_path):
    out = tmp_path / "pkg"
    write_all(FILES, out)
    (out / "config/a.yaml").write_text("mine\n")
    changes = plan_writes([RenderedFile("config/a.yaml", "a: 2\n")], out)
    (out / "config/a.yaml.orig").write_text("another run's\n")
    with pytest.raises(ConflictError, match="config/a.yaml.orig changed while"):
        apply_writes(changes, out, force=True)
    assert (out / "config/a.yaml.orig").read_text() == "another run's\n"
    assert (out / "config/a.yaml").read_text() == "mine\n"


def test_a_new_package_is_checked_again_under_the_lock(tmp_path):
    """init without --force: another run filled the folder after check_output_dir passed."""
    out = tmp_path / "pkg"
    check_output_dir(out, force=False)
    write_all(FILES, out)  # the other run, finished before this one plans
    other = [RenderedFile("package.xml", "<package>mine</package>\n"), RenderedFile("b.txt", "b\n")]
    changes = plan_writes(other, out)
    with pytest.raises(InputError, match="not empty") as info:
        apply_writes(changes, out, require_fresh=True)
    assert info.value.path == str(out)
    assert {p: (out / p).read_text() for p in load_manifest(out)} == {f.path: f.content for f in FILES}
    assert not (out / "b.txt").exists()
    fresh = tmp_path / "fresh"
    fresh.mkdir()
    apply_writes(plan_writes(other, fresh), fresh, require_fresh=True)
    assert (fresh / "b.txt").read_text() == "b\n"

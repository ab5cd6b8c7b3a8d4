"""Proofs in a setup: marm_setup.yaml keeps the prove mode, the unproved pairs and the proof key;
the package SRDF notes the unproved pairs; validate trusts no proof a package records about
itself, only the user's own proof cache."""

from __future__ import annotations

import dataclasses

import pytest
import yaml

from marm_setup.collision.pairs import DisabledPair, DisabledReason, UnprovedPair
from marm_setup.errors import InputError
from marm_setup.flows import with_collision_matrix
from marm_setup.inference.infer import infer_setup as infer
from marm_setup.render.package import render_package
from marm_setup.setup.model import RobotSource
from marm_setup.setup.yaml_io import dump_setup, setup_from_dict

N = DisabledReason.NEVER


@pytest.fixture(scope="module")
def proved_setup(marm):
    source = RobotSource("../urdf/marm.urdf.xacro", (), ("../..",))
    model = infer(marm, package_name="marm_moveit_config", source=source).model
    return with_collision_matrix(model, marm, trials=300, seed=0, prove="on")


def test_the_setup_file_keeps_the_proofs_and_loads_them_back(proved_setup):
    collision = proved_setup.collision
    assert collision.prove == "on" and collision.unproved and collision.proof_key
    assert all(u.pair in {p.pair for p in collision.disabled if p.reason is N} for u in collision.unproved)
    text = dump_setup(proved_setup)
    assert "  prove: 'on'\n" in text  # quoted: YAML 1.1 would read a bare on as true
    assert setup_from_dict(yaml.safe_load(text)) == proved_setup


@pytest.mark.parametrize(
    ("change", "element"),
    [
        ({"prove": "maybe"}, "collision.prove"),
        (
            {"unproved": [{"link1": "link1", "link2": "link4", "proved_fraction": 1.5}]},
            "collision.unproved[0].proved_fraction",
        ),
    ],
)
def test_bad_proof_settings_name_their_key(proved_setup, marm, change, element):
    from marm_setup.setup.checks import check_setup

    data = yaml.safe_load(dump_setup(proved_setup))
    data["collision"].update(change)
    with pytest.raises(InputError) as caught:
        check_setup(setup_from_dict(data, "marm_setup.yaml"), marm, "marm_setup.yaml")
    assert caught.value.element == element


def test_the_package_srdf_notes_each_unproved_pair(proved_setup, marm):
    files = {f.path: f.content for f in render_package(proved_setup, marm)}
    srdf = next(text for rel, text in files.items() if rel.endswith(".srdf"))
    lines = srdf.splitlines()
    for unproved in proved_setup.collision.unproved:
        entry = f'    <disable_collisions link1="{unproved.link1}" link2="{unproved.link2}" reason="Never"/>'
        assert lines[lines.index(entry) - 1] == f"    <!-- {unproved.note(proved_setup.collision.trials)} -->"
    assert srdf.count("unproved Never:") == len(proved_setup.collision.unproved)


def test_a_package_cannot_vouch_for_itself(tmp_path, marm, monkeypatch):
    """Neither a recorded proof with a matching key, nor `trials: 0`, nor the package's seed
    hides a Never pair that collides; with or without the user's proof cache."""
    from tests.validate_helpers import validate_package, vouching_package

    pkg, pair = vouching_package(tmp_path, marm)
    element = f"disable_collisions[{pair[0]} {pair[1]}]"
    for cache in ("warm", "cold"):
        if cache == "cold":
            monkeypatch.setenv("MARM_SETUP_CACHE", str(tmp_path / "empty-cache"))
        stale = [f for f in validate_package(pkg, plan=False) if f.rule == "matrix.stale"]
        assert [f.element for f in stale] == [element], cache


def test_validate_skips_only_the_pairs_the_users_cache_proves(tmp_path, marm, monkeypatch):
    """The pairs not resampled are exactly the SRDF's Never pairs the user's own cache holds as
    proved (init filled it); an empty cache or another robot's geometry trusts none."""
    from marm_setup.collision import CollisionScene
    from marm_setup.package import read_package
    from marm_setup.validate.rules.matrix_rules import cached_proved
    from tests.validate_helpers import generate_marm

    pkg = read_package(generate_marm(tmp_path, "ros1"))
    scene = CollisionScene(marm)
    setup = yaml.safe_load((pkg.root / "marm_setup.yaml").read_text(encoding="utf-8"))["collision"]
    never = {(d["link1"], d["link2"]) for d in setup["disabled"] if d["reason"] == "Never"}
    unproved = {(u["link1"], u["link2"]) for u in setup["unproved"]}
    assert cached_proved(pkg.srdf, scene) == never - unproved and never - unproved
    joint = next(j for j in marm.joints if j.type == "revolute")
    wider = dataclasses.replace(joint, upper=joint.upper + 0.5)
    changed = dataclasses.replace(marm, joints=tuple(wider if j is joint else j for j in marm.joints))
    moved = cached_proved(pkg.srdf, CollisionScene(changed))
    assert moved < never - unproved  # the pairs whose joint box grew are no longer trusted
    assert all(joint.child not in pair for pair in moved)
    monkeypatch.setenv("MARM_SETUP_CACHE", str(tmp_path / "empty-cache"))
    assert cached_proved(pkg.srdf, scene) == frozenset()
    monkeypatch.setenv("MARM_SETUP_CACHE", "off")
    assert cached_proved(pkg.srdf, scene) == frozenset()


def test_notes_round_down_so_a_nearly_proved_pair_never_reads_100():
    note = UnprovedPair("a", "b", 0.99996).note(10000)
    assert "99.9 %" in note and "10000 states" in note and "--" not in note
    assert DisabledPair.of("b", "a", N).pair == UnprovedPair("a", "b", 0.5).pair


def test_prove_off_records_no_proofs(marm):
    source = RobotSource("../urdf/marm.urdf.xacro", (), ("../..",))
    model = infer(marm, package_name="marm_moveit_config", source=source).model
    off = with_collision_matrix(model, marm, trials=300, seed=0, prove="off").collision
    assert off.prove == "off" and off.unproved == () and off.proof_key is None

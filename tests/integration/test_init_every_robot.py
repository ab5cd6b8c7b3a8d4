"""`init` without a SPEC on every robot description we have: the shared real-world robots
(../shared/realworld*, skipped when absent) and the synthetic fixtures. Each exits 0, and the
package it writes validates with 0 errors, planning included, with at least one pose pair
planned per arm, and per limb of two or more joints (DESIGN §2: a collision-free `home` and a
second pose per limb)."""

from __future__ import annotations

import json

import pytest
import yaml
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.generated_packages import SHARED, SYNTHETIC

runner = CliRunner()


def _validate(generated) -> tuple[dict, dict]:
    """The package `init` wrote (once per session: tests/generated_packages.py) and validate's report."""
    paths = [a for root in generated.roots for a in ("--package-path", str(root))]
    checked = runner.invoke(app, ["validate", str(generated.out), "--format", "json", *paths])
    return yaml.safe_load((generated.out / "marm_setup.yaml").read_text()), json.loads(checked.stdout)


def _check(setup: dict, report: dict) -> None:
    errors = [
        f"{f['rule']} {f['file']} {f['element']}: {f['message']}"
        for f in report["findings"]
        if f["severity"] == "error"
    ]
    assert errors == []
    # limbs of two or more joints get `home` and `ready` (a one-joint torso lift only `home`)
    limbs = [g["name"] for g in setup["groups"] if "chain" in g]
    poses = {limb: [s for s in setup.get("group_states", []) if s["group"] == limb] for limb in limbs}
    posed = [limb for limb in limbs if len(poses[limb]) >= 2]
    arms = [limb for limb in limbs if "arm" in limb]
    assert set(arms) <= set(posed), {arm: len(poses[arm]) for arm in arms}
    assert report["validated"]["planned_pairs"] >= len(posed)


@pytest.mark.parametrize("name", list(SHARED))
def test_init_on_a_real_robot_validates_and_plans(ros2_packages, name):
    _check(*_validate(ros2_packages.get(f"shared:{name}", "humble")))


@pytest.mark.parametrize("name", SYNTHETIC)
def test_init_on_a_synthetic_robot_validates_and_plans(ros2_packages, name):
    _check(*_validate(ros2_packages.get(f"synthetic:{name}", "humble")))

"""docs/setup-file.md: every key it documents is used by an example, and every example is a SPEC
that `init --setup` accepts on the robot its first line names."""

from __future__ import annotations

import re
from pathlib import Path

import pytest
import yaml

from marm_setup.flows import InitRequest, RobotInput, build_setup
from marm_setup.robot.load import load_robot
from tests.conftest import ROOT

DOC = ROOT / "docs" / "setup-file.md"
FREE_MAPPINGS = (
    "values",
    "multi_dof",
    "xacro_args",
    "options",
    "move_group_parameters",
)  # keys: joint / arg / option / parameter names


def _examples() -> list[tuple[str, str]]:
    blocks = re.findall(r"```yaml\n(.*?)```", DOC.read_text(encoding="utf-8"), re.S)
    return [(re.match(r"# robot: (\S+)", b).group(1), b) for b in blocks]


def _documented() -> set[str]:
    rows = re.findall(r"^\| `([a-z0-9_.\[\]]+)` \|", DOC.read_text(encoding="utf-8"), re.M)
    return set(rows)


def _paths(obj, prefix: str = ""):
    if isinstance(obj, dict):
        for key, value in obj.items():
            path = f"{prefix}.{key}" if prefix else str(key)
            yield path
            if key not in FREE_MAPPINGS:
                yield from _paths(value, path)
    elif isinstance(obj, list):
        for item in obj:
            yield from _paths(item, f"{prefix}[]")


def test_every_documented_key_is_in_an_example_and_every_key_is_documented():
    from marm_setup.setup.model import SetupModel

    used = {p for _, text in _examples() for p in _paths(yaml.safe_load(text))}
    documented = _documented()
    assert documented - used == set()
    assert {f.name for f in SetupModel.__dataclass_fields__.values()} <= documented


@pytest.mark.parametrize("robot, text", _examples(), ids=[Path(r).stem for r, _ in _examples()])
def test_each_example_is_a_spec_init_accepts(tmp_path, robot, text):
    spec = tmp_path / "spec.yaml"
    spec.write_text(text, encoding="utf-8")
    urdf = ROOT / robot
    request = InitRequest(RobotInput.parse(urdf), out=tmp_path / "pkg", spec=spec)
    model = build_setup(request, load_robot(urdf))
    data = yaml.safe_load(text)
    assert {g["name"] for g in data.get("groups", [])} <= {g.name for g in model.groups}
    assert len(model.group_states) >= len(data.get("group_states", []))

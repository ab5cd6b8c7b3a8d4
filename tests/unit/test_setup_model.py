"""marm_setup.yaml: typed load, stable dump, round trips, and errors naming the key path."""

from __future__ import annotations

import dataclasses

import pytest
import yaml

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.errors import InputError
from marm_setup.inference.infer import infer_setup as infer
from marm_setup.setup.model import (
    ArbotixJoint,
    CollisionPair,
    CollisionSettings,
    JointLimitOverride,
    JointProperty,
    LinkSpheres,
    RobotSource,
    SetupModel,
    SphereApprox,
    SrdfExtras,
)
from marm_setup.setup.yaml_io import dump_setup, load_setup, setup_from_dict
from tests.conftest import FIXTURES


@pytest.fixture(scope="module")
def marm_setup(marm):
    source = RobotSource("../urdf/marm.urdf.xacro", (("with_gripper", "true"),), ("../..",))
    model = infer(marm, package_name="marm_moveit_config", source=source, target="ros1").model
    pairs = (DisabledPair.of("link2", "link1", "Adjacent"), DisabledPair.of("base_link", "link3", "Never"))
    return dataclasses.replace(
        model,
        collision=CollisionSettings(seed=7, trials=1234, disabled=tuple(sorted(pairs))),
        joint_limits=(JointLimitOverride("joint1", max_velocity=0.5, max_acceleration=1.5),),
        arbotix_joints=(ArbotixJoint("joint1", 1, max_speed=90.0),),
    )


def test_load_of_dump_is_the_model_and_dump_of_load_is_the_text(marm_setup, tmp_path):
    text = dump_setup(marm_setup)
    path = tmp_path / "marm_setup.yaml"
    path.write_text(text)
    loaded = load_setup(path)
    assert loaded == marm_setup
    assert dump_setup(loaded) == text


def test_dump_is_plain_yaml_in_field_order(marm_setup):
    data = yaml.safe_load(dump_setup(marm_setup))
    assert list(data)[:4] == ["package_name", "robot_name", "robot", "target"]
    assert data["groups"][0] == {"name": "arm", "chain": {"base": "base_link", "tip": "grasping_frame"}}
    assert data["group_states"][0]["values"]["joint3"] == 0.0
    assert data["collision"]["disabled"][0] == {"link1": "base_link", "link2": "link3", "reason": "Never"}
    assert data["robot"]["xacro_args"] == {"with_gripper": "true"}
    assert "srdf_extras" not in data and "passive_joints" not in data


def test_srdf_extras_round_trip():
    extras = SrdfExtras(
        enable_collisions=(CollisionPair("a", "b", "Tool"),),
        disable_default_collisions=("a",),
        joint_properties=(JointProperty("j", "angular_distance_weight", "0.5"),),
        link_sphere_approximations=(LinkSpheres("a", (SphereApprox((0.0, 0.1, -0.2), 0.05),)),),
    )
    model = SetupModel("p", "r", RobotSource("r.urdf"), srdf_extras=extras, passive_joints=("j",))
    again = setup_from_dict(yaml.safe_load(dump_setup(model)))
    assert again == model


def test_course_spec_fixture_loads_with_defaults():
    from marm_setup.setup.yaml_io import read_yaml_mapping

    spec = read_yaml_mapping(FIXTURES / "marm" / "marm_setup.yaml")
    spec |= {"robot_name": "marm", "robot": {"urdf": "urdf/marm.urdf.xacro"}}
    model = setup_from_dict(spec, "marm_setup.yaml")
    forward = next(s for s in model.group_states if s.name == "forward")
    assert dict(forward.values) == {
        "joint1": 0.0,
        "joint2": 0.4285,
        "joint3": 0.7672,
        "joint4": 0.0,
        "joint5": -0.4487,
        "joint6": 0.0,
    }
    assert isinstance(forward.values[0][1], float)


BASE = {"package_name": "p", "robot_name": "r", "robot": {"urdf": "r.urdf"}}
BAD = {
    "unknown top key": ({"grups": []}, "grups", "unknown key 'grups' (did you mean 'groups'?)"),
    "unknown nested key": (
        {"groups": [{"name": "arm", "chian": {"base": "a", "tip": "b"}}]},
        "groups[arm].chian",
        "did you mean 'chain'?",
    ),
    "wrong item type": (
        {"groups": [{"name": "arm", "joints": ["j1", "j2", "j3", 4]}]},
        "groups[arm].joints[3]",
        "expected a string, got an integer (4)",
    ),
    "not a list": ({"passive_joints": "j1"}, "passive_joints", "expected a list, got a string"),
    "pose value": (
        {"group_states": [{"name": "home", "group": "arm", "values": {"j1": "zero"}}]},
        "group_states[home].values.j1",
        "expected a number",
    ),
    "values as list": (
        {"group_states": [{"name": "home", "group": "arm", "values": [0, 1]}]},
        "group_states[home].values",
        "expected a mapping of names to values",
    ),
    "bad target": ({"target": "ros3"}, "target", "'ros3' is not one of: ros2, ros1"),
    "bad reason": (
        {"collision": {"disabled": [{"link1": "a", "link2": "b", "reason": "Sometimes"}]}},
        "collision.disabled[0].reason",
        "not one of: Adjacent, Default, Always, Never, User",
    ),
    "bool is not an int": ({"collision": {"trials": True}}, "collision.trials", "expected an integer"),
    "missing key": ({"groups": [{"chain": {"base": "a"}}]}, "groups[0]", "missing key 'name'"),
    "bad controller type": (
        {"controllers": [{"name": "c", "type": "FollowJointTrajectry", "action_ns": "x", "joints": []}]},
        "controllers[c].type",
        "did you mean 'FollowJointTrajectory'?",
    ),
    "infinite pose value": (
        {"group_states": [{"name": "home", "group": "arm", "values": {"j1": float("inf")}}]},
        "group_states[home].values.j1",
        "expected a finite number, got inf",
    ),
    "unknown OMPL planner": (
        {"planners": [{"group": "arm", "default_planner": "RRTconnect"}]},
        "planners[arm].default_planner",
        "did you mean 'RRTConnect'?",
    ),
}


@pytest.mark.parametrize("case", list(BAD))
def test_bad_setups_name_the_key_path(case):
    extra, element, message = BAD[case]
    with pytest.raises(InputError) as err:
        setup_from_dict({**BASE, **extra}, "spec.yaml")
    assert err.value.path == "spec.yaml"
    assert err.value.element == element
    assert message in err.value.message


def test_missing_top_level_key():
    with pytest.raises(InputError, match="missing key 'robot_name'"):
        setup_from_dict({"package_name": "p", "robot": {"urdf": "r"}}, "s.yaml")


@pytest.mark.parametrize(
    "text, message",
    [
        ("groups: [\n", r"not valid YAML \(line 2\)"),
        ("- a\n- b\n", "expected a mapping at the top, got a list"),
        ("package_name: a\npackage_name: b\n", r"not valid YAML \(line 2\): key 'package_name' given twice"),
        ("default_acceleration: " + "1" * 5000 + "\n", "not valid YAML: a value no number can hold"),
        ("package_name: p\nrobot_name: r\nrobot: {urdf: r}\ndefault_acceleration: " + "1" * 400 + "\n",
         "default_acceleration: expected a finite number, got an integer of 400 digits"),
    ],
)  # fmt: skip
def test_unreadable_files(tmp_path, text, message):
    path = tmp_path / "s.yaml"
    path.write_text(text)
    with pytest.raises(InputError, match=message):
        load_setup(path)
    with pytest.raises(InputError, match="cannot read"):
        load_setup(tmp_path / "missing.yaml")


def test_disabled_pairs_are_canonical_after_load():
    data = {**BASE, "collision": {"disabled": [{"link1": "z", "link2": "a", "reason": "Never"}]}}
    (pair,) = setup_from_dict(data).collision.disabled
    assert pair == DisabledPair("a", "z", DisabledReason.NEVER)


def _models():
    from hypothesis import strategies as st

    from marm_setup.setup.model import Chain, EndEffector, Group, GroupState, Kinematics

    names = st.text(min_size=1, max_size=12)
    floats = st.floats(allow_nan=False, allow_infinity=False)
    group = st.builds(
        Group,
        name=names,
        chain=st.none() | st.builds(Chain, names, names),
        joints=st.tuples(names, names) | st.just(()),
        subgroups=st.lists(names, max_size=2).map(tuple),
    )
    state = st.builds(
        GroupState,
        name=names,
        group=names,
        values=st.dictionaries(names, floats, max_size=4).map(lambda d: tuple(d.items())),
    )
    pair = st.builds(DisabledPair.of, names, names, st.sampled_from(list(DisabledReason)))
    return st.builds(
        SetupModel,
        package_name=names,
        robot_name=names,
        robot=st.builds(RobotSource, names),
        target=st.sampled_from(["ros1", "ros2"]),
        groups=st.lists(group, max_size=3).map(tuple),
        group_states=st.lists(state, max_size=2).map(tuple),
        end_effectors=st.lists(
            st.builds(EndEffector, names, names, names, st.none() | names), max_size=2
        ).map(tuple),
        collision=st.builds(
            CollisionSettings, seed=st.integers(0, 2**31), disabled=st.lists(pair, max_size=3).map(tuple)
        ),
        kinematics=st.lists(st.builds(Kinematics, names, timeout=floats), max_size=2).map(tuple),
        default_velocity_scaling=floats,
    )


def test_round_trip_property():
    from hypothesis import given

    @given(_models())
    def check(model):
        text = dump_setup(model)
        loaded = setup_from_dict(yaml.safe_load(text), "x.yaml")
        assert loaded == model
        assert dump_setup(loaded) == text

    check()


def test_yaml_merge_keys_still_work_in_setup_files(tmp_path):
    """The duplicate-key check flattens `<<: *anchor` first, as PyYAML's SafeLoader does."""
    from marm_setup.setup.yaml_io import read_yaml_mapping

    path = tmp_path / "s.yaml"
    path.write_text("base: &who {name: Ann}\nauthor: {<<: *who, email: ann@example.com}\n", encoding="utf-8")
    assert read_yaml_mapping(path)["author"] == {"name": "Ann", "email": "ann@example.com"}

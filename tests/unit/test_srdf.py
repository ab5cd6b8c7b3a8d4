"""SRDF read/render round trips (ours and the shared panda SRDFs), extras kept, errors, and
pinocchio reading our SRDF (collision pairs and reference configurations)."""

from __future__ import annotations

import dataclasses

import pytest
from lxml import etree

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.errors import InputError
from marm_setup.inference.infer import infer_setup as infer
from marm_setup.render.package import render_package
from marm_setup.setup.model import CollisionPair, GroupState, RobotSource, SetupModel
from marm_setup.setup.srdf import parse_srdf_string, read_srdf, setup_to_srdf, srdf_to_setup
from marm_setup.templating import render_template
from tests.conftest import realworld

FORWARD = (
    ("joint1", 0.0),
    ("joint2", 0.4285),
    ("joint3", 0.7672),
    ("joint4", 0.0),
    ("joint5", -0.4487),
    ("joint6", 0.0),
)


@pytest.fixture(scope="module")
def marm_model(marm):
    from marm_setup.flows import with_collision_matrix

    model = infer(marm, package_name="p", source=RobotSource("x"), target="ros1").model
    model = dataclasses.replace(
        model, group_states=(*model.group_states, GroupState("forward", "arm", FORWARD))
    )
    return with_collision_matrix(model, marm, trials=1000, seed=0)


class _Named:
    def __init__(self, name: str):
        self.name = name


def render_srdf(model: SetupModel, robot) -> str:
    """The SRDF template alone: `robot` needs only a `name` (the panda has no RobotModel here)."""
    return render_template("common/config/robot.srdf.j2", model=model, robot=robot)


def test_our_srdf_reads_back_as_the_model(marm, marm_model):
    [text] = [f.content for f in render_package(marm_model, marm) if f.path == "config/marm.srdf"]
    assert parse_srdf_string(text) == dataclasses.replace(
        setup_to_srdf(marm_model), disabled=tuple(sorted(marm_model.collision.disabled))
    )
    root = etree.fromstring(text.encode())
    tags = [e.tag for e in root if isinstance(e.tag, str)]
    order = ["group", "group_state", "end_effector", "virtual_joint", "disable_collisions"]
    assert [t for i, t in enumerate(tags) if i == 0 or tags[i - 1] != t] == order
    pairs = [(e.get("link1"), e.get("link2")) for e in root.iter("disable_collisions")]
    assert pairs == sorted(pairs) and all(a < b for a, b in pairs)
    assert render_srdf(marm_model, marm) == text


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_shared_panda_srdf_round_trip(target):
    path = realworld(target, "panda_moveit_config/config/panda.srdf")
    srdf = read_srdf(path)
    assert [g.name for g in srdf.groups] == ["panda_arm", "hand", "panda_arm_hand"]
    assert len(srdf.group_states) == 5 and srdf.end_effectors[0].parent_group == "panda_arm"
    model = srdf_to_setup(srdf, SetupModel("p", "panda", RobotSource("x")))
    again = parse_srdf_string(render_srdf(model, _Named("panda")))
    assert again == srdf


EXTRAS = """<?xml version="1.0"?>
<robot name="r">
  <group name="g"><chain base_link="a" tip_link="c"/><joint name="j"/></group>
  <group_state name="s" group="g"><joint name="j" value="0.25"/></group_state>
  <virtual_joint name="v" type="planar" parent_frame="odom" child_link="a"/>
  <passive_joint name="p"/>
  <joint_property joint_name="v" property_name="motion_model" value="diff_drive"/>
  <link_sphere_approximation link="a"><sphere center="0 0.1 -0.2" radius="0.05"/></link_sphere_approximation>
  <link_sphere_approximation link="b"/>
  <disable_default_collisions link="c"/>
  <enable_collisions link1="c" link2="a" reason="Tool"/>
  <disable_collisions link1="c" link2="b"/>
  <disable_collisions link1="b" link2="a" reason="Adjacent"/>
</robot>
"""


def test_every_srdfdom_element_is_kept():
    srdf = parse_srdf_string(EXTRAS)
    assert srdf.disabled == (
        DisabledPair.of("a", "b", "Adjacent"),
        DisabledPair("b", "c", DisabledReason.USER),
    )
    assert srdf.extras.enable_collisions[0] == CollisionPair("a", "c", "Tool")
    assert srdf.extras.joint_properties[0].value == "diff_drive"
    assert srdf.extras.link_sphere_approximations[0].spheres[0].center == (0.0, 0.1, -0.2)
    assert srdf.extras.disable_default_collisions == ("c",)
    model = srdf_to_setup(srdf, SetupModel("p", "r", RobotSource("x")))
    text = render_srdf(model, _Named("r"))
    assert parse_srdf_string(text) == srdf
    assert '<link_sphere_approximation link="b">' in text


@pytest.mark.parametrize(
    "text, element, message",
    [
        ("<robot><group name='g'>", "line 1", "not well-formed XML"),
        ("<srdf/>", "robot", "root element is <srdf>"),
        ("<robot><group/></robot>", "group", "missing attribute 'name'"),
        (
            "<robot><group_state name='s' group='g'><joint name='j' value='x'/></group_state></robot>",
            "group_state[s].joint[j]",
            "not a number",
        ),
        (  # srdfdom's lexical_cast refuses it; Python's float reads 0_1 as 1
            "<robot><group_state name='s' group='g'><joint name='j' value='0_1'/></group_state></robot>",
            "group_state[s].joint[j]",
            "not a number",
        ),
        (
            "<robot><group_state name='s' group='g'><joint name='j' value='\u0661'/></group_state></robot>",
            "group_state[s].joint[j]",
            "not a number",
        ),
    ],
)
def test_bad_srdf_is_an_input_error(text, element, message):
    with pytest.raises(InputError) as err:
        parse_srdf_string(text, "in.srdf")
    assert err.value.path == "in.srdf" and err.value.element == element
    assert message in err.value.message


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="cannot read"):
        read_srdf(tmp_path / "nope.srdf")


def _pinocchio_models(robot):
    pin = pytest.importorskip("pinocchio")
    mesh = robot.link("link6").collisions[0].geometry
    xml = robot.urdf_xml.replace(mesh.uri, mesh.path)  # pinocchio does not know our package paths
    model = pin.buildModelFromXML(xml)
    geom = pin.buildGeomFromUrdfString(model, xml, pin.COLLISION)
    return pin, model, geom


def _pin_pairs(model, geom) -> set[tuple[str, str]]:
    frames = [model.frames[g.parentFrame].name for g in geom.geometryObjects]
    return {tuple(sorted((frames[p.first], frames[p.second]))) for p in geom.collisionPairs}


def test_pinocchio_removes_exactly_our_pairs(marm, marm_model, tmp_path):
    pin, model, geom = _pinocchio_models(marm)
    path = tmp_path / "marm.srdf"
    path.write_text(render_srdf(marm_model, marm))
    geom.addAllCollisionPairs()
    before = _pin_pairs(model, geom)
    pin.removeCollisionPairs(model, geom, str(path))
    removed = before - _pin_pairs(model, geom)
    ours = {d.pair for d in marm_model.collision.disabled}
    assert removed == ours & before
    assert ours - before == {("base_link", "bottom_link")}  # same pinocchio joint: never paired


def test_pinocchio_reference_configurations(marm, marm_model, tmp_path):
    pin, model, _ = _pinocchio_models(marm)
    path = tmp_path / "marm.srdf"
    path.write_text(render_srdf(marm_model, marm))
    pin.loadReferenceConfigurations(model, str(path))
    configs = {entry.key(): entry.data().copy() for entry in model.referenceConfigurations}
    assert set(configs) == {"home", "forward"}
    assert list(configs["home"]) == [0.0] * model.nq
    forward = configs["forward"]
    for joint, value in FORWARD:
        assert forward[model.joints[model.getJointId(joint)].idx_q] == pytest.approx(value)


def test_unknown_or_missing_reason_is_user_as_in_the_setup_assistant():
    text = (
        "<robot name='r'><disable_collisions link1='b' link2='a' reason='Sometimes'/>"
        "<disable_collisions link1='c' link2='a'/></robot>"
    )
    disabled = parse_srdf_string(text, "x.srdf").disabled
    assert disabled == (
        DisabledPair.of("a", "b", DisabledReason.USER),
        DisabledPair.of("a", "c", DisabledReason.USER),
    )

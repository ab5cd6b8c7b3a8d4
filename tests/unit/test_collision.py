"""CollisionScene and mesh loading: real coal, real trimesh, inline URDFs in tmp_path."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from marm_setup.collision.scene import CollisionScene
from marm_setup.errors import InputError
from marm_setup.robot.kinematics import sample_configurations
from marm_setup.robot.load import load_robot
from marm_setup.robot.meshes import load_mesh
from tests.collision_robots import TOY, mesh_shell_urdf
from tests.helpers import urdf


@pytest.fixture
def toy(tmp_path):
    path = tmp_path / "toy.urdf"
    path.write_text(TOY, encoding="utf-8")
    return load_robot(path)


def _cube_stl(tmp_path):
    import trimesh

    path = tmp_path / "cube.stl"
    trimesh.creation.box(extents=(1.0, 1.0, 1.0)).export(str(path))
    return path


def test_candidate_pairs_are_all_geometry_pairs_sorted(marm, marm_scene):
    geometry = marm.geometry_links
    assert marm_scene.links == geometry
    assert marm_scene.candidate_pairs == tuple(sorted(itertools.combinations(geometry, 2)))
    assert all(a < b for a, b in marm_scene.candidate_pairs)
    assert "grasping_frame" not in {link for pair in marm_scene.candidate_pairs for link in pair}
    assert len(marm_scene.candidate_pairs) == 45  # 10 links with geometry; adjacency not removed


def test_enabled_pairs_removes_disabled_in_any_order(marm_scene):
    disabled = [("link2", "link1"), ("base_link", "bottom_link"), ("not", "a_link")]
    enabled = marm_scene.enabled_pairs(disabled)
    assert ("link1", "link2") not in enabled and ("base_link", "bottom_link") not in enabled
    assert len(enabled) == len(marm_scene.candidate_pairs) - 2


def test_first_collisions_reports_the_first_pair_in_the_given_order(toy):
    scene = CollisionScene(toy)
    # slider_d at 0.1 touches stop; slider_c at 0.5 touches post; slider_a at 0.5 touches block.
    q = np.zeros((3, len(toy.active_joints)))
    names = toy.active_joint_names
    q[0, names.index("jd")] = 0.1
    q[1, names.index("jd")] = -0.9
    q[1, names.index("ja")] = 0.5
    q[1, names.index("jc")] = 0.5
    q[2, names.index("jd")] = -0.9
    pairs = [("slider_c", "post"), ("block", "slider_a"), ("slider_d", "stop")]
    assert scene.first_collisions(q, pairs) == [("slider_d", "stop"), ("post", "slider_c"), None]
    assert scene.first_collisions(q, list(reversed(pairs)))[1] == ("block", "slider_a")
    assert scene.first_collisions(q, []) == [None, None, None]


def test_filters_never_reject_a_colliding_pair(marm, marm_scene):
    """The bounding-sphere and box filters are conservative: compare with coal on every pair."""
    q = sample_configurations(marm, np.random.default_rng(7), 300)
    poses = marm_scene.link_poses(q)
    ids = np.arange(len(marm_scene.candidate_pairs))
    maybe = marm_scene.maybe_colliding(poses, ids)
    exact = np.array([[marm_scene.collide(poses[n], k) for k in ids] for n in range(len(q))])
    assert exact.any()
    assert not (exact & ~maybe).any()
    assert maybe.sum() < maybe.size / 2  # and they do filter
    np.testing.assert_array_equal(marm_scene.collision_counts(poses, ids), exact.sum(axis=0))


def test_a_mesh_is_a_surface_a_box_is_solid(tmp_path):
    """As in MoveIt's FCL: a sphere inside a mesh cube does not collide until it meets a triangle."""
    path = tmp_path / "shells.urdf"
    path.write_text(mesh_shell_urdf(str(_cube_stl(tmp_path))), encoding="utf-8")
    robot = load_robot(path)
    scene = CollisionScene(robot)
    mesh_pair, box_pair = ("inner_m", "shell"), ("inner_s", "solid")
    for value, mesh_hit, box_hit in [
        (0.0, False, True),
        (0.3, False, True),
        (0.5, True, True),
        (0.8, False, False),
    ]:
        q = np.full((1, 2), value)
        assert scene.first_collisions(q, [mesh_pair]) == [mesh_pair if mesh_hit else None], value
        assert scene.first_collisions(q, [box_pair]) == [box_pair if box_hit else None], value


def test_padding_turns_near_misses_into_collisions(toy):
    q = np.zeros((1, len(toy.active_joints)))
    q[0, toy.active_joint_names.index("jc")] = 0.33  # sphere 0.02 m short of the post
    pair = [("post", "slider_c")]
    assert CollisionScene(toy).first_collisions(q, pair) == [None]
    assert CollisionScene(toy, padding=0.03).first_collisions(q, pair) == [("post", "slider_c")]
    assert CollisionScene(toy, padding=0.01).first_collisions(q, pair) == [None]


def test_distance_of_separated_pair(toy):
    scene = CollisionScene(toy)
    poses = scene.link_poses(np.zeros((1, len(toy.active_joints))))
    pair_id = int(scene.pair_ids([("post", "slider_c")])[0])
    assert scene.distance(poses[0], pair_id) == pytest.approx(0.4 - 0.05, abs=1e-6)


def test_unknown_pair_is_rejected(marm_scene):
    with pytest.raises(ValueError, match="candidate"):
        marm_scene.pair_ids([("link1", "grasping_frame")])


def test_mesh_cache_and_scale(tmp_path):
    path = _cube_stl(tmp_path)
    first = load_mesh(str(path), (1.0, 1.0, 1.0))
    assert load_mesh(str(path), (1.0, 1.0, 1.0)) is first
    scaled = load_mesh(str(path), (2.0, 1.0, 0.5))
    np.testing.assert_allclose(np.ptp(scaled.vertices, axis=0), [2.0, 1.0, 0.5])
    assert scaled.faces is first.faces  # one file read for every scale


@pytest.mark.parametrize(
    ("unit", "size"),
    [(None, 100.0), ('<unit meter="0.001" name="millimeter"/>', 0.1), ('<unit meter="0.0254"/>', 2.54)],
)
def test_collada_unit_is_applied(tmp_path, unit, size):
    """A Collada `<unit meter>` scales the vertices to [m] (MoveIt's assimp loader applies it)."""
    import trimesh

    text = trimesh.exchange.dae.export_collada(trimesh.creation.box(extents=(100, 100, 100))).decode()
    assert "<unit" not in text and "<asset>" in text
    if unit:
        text = text.replace("<asset>", f"<asset>{unit}", 1)
    (tmp_path / "cube.dae").write_text(text, encoding="utf-8")
    mesh = load_mesh(str(tmp_path / "cube.dae"))
    np.testing.assert_allclose(np.ptp(mesh.vertices, axis=0), [size] * 3)
    scaled = load_mesh(str(tmp_path / "cube.dae"), (2.0, 1.0, 1.0))  # the URDF scale comes on top
    np.testing.assert_allclose(np.ptp(scaled.vertices, axis=0), [2 * size, size, size])


def test_unreadable_mesh_is_an_input_error(tmp_path):
    bad = tmp_path / "broken.stl"
    bad.write_text("this is not a mesh", encoding="utf-8")
    path = tmp_path / "r.urdf"
    body = """
    <link name="a"><collision><geometry><mesh filename="broken.stl"/></geometry></collision></link>
    <link name="b"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
    <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
    """
    path.write_text(urdf(body), encoding="utf-8")
    with pytest.raises(InputError) as info:
        CollisionScene(load_robot(path))
    assert str(info.value).startswith(f"{path}: link[a]/collision[0]/mesh: cannot read mesh")
    assert str(bad) in str(info.value)


def test_a_mesh_coal_cannot_hull_is_checked_as_it_is(tmp_path):
    """coal's convexHull throws 'Too many neighbors' on a vertex with hundreds of edges (a fine
    cone's apex; a 15k-vertex pelvis in a real robot): that link gets no hull test, same matrix."""
    import trimesh

    cone = tmp_path / "cone.stl"
    trimesh.creation.cone(radius=0.1, height=0.2, sections=300).export(str(cone))
    body = f"""
      <link name="base"><collision><geometry><mesh filename="{cone}"/></geometry></collision></link>
      <link name="arm"><collision><origin xyz="0.15 0 0.1"/><geometry><box size="0.05 0.05 0.2"/></geometry>
      </collision></link>
      <joint name="j" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.3"/>
        <axis xyz="0 1 0"/><limit lower="-2" upper="2" velocity="1" effort="1"/></joint>"""
    (tmp_path / "r.urdf").write_text(urdf(body), encoding="utf-8")
    robot = load_robot(tmp_path / "r.urdf")
    scene = CollisionScene(robot)
    poses = scene.link_poses(np.linspace(-2, 2, 41)[:, None])
    ids = scene.pair_ids([("arm", "base")])
    with_hulls = scene.collision_counts(poses, ids, hulls=True)
    assert 0 < with_hulls[0] < 41
    np.testing.assert_array_equal(with_hulls, scene.collision_counts(poses, ids))


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(*[st.sampled_from([-1.5, 0.0, 0.25, 2.0])] * 3), min_size=1, max_size=40))
def test_a_hull_is_built_from_each_distinct_vertex_once_in_first_seen_order(rows):
    from marm_setup.collision.scene import _distinct_rows

    once = list(dict.fromkeys(rows))
    assert _distinct_rows(np.array(rows, dtype=float)).tolist() == [list(r) for r in once]

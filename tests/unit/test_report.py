"""The report's parts: geometry and decimation, frames, states and their contacts, motions, the
page's JSON and HTML (the page in a real browser: tests/integration/test_report_browser.py)."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

from marm_setup.findings import Evidence, Finding
from marm_setup.report.content import b64
from marm_setup.report.frames import MAX_FRAMES, link_frames
from marm_setup.report.geometry import AREA_KEPT, _decimated, robot_geometry
from marm_setup.report.page import json_for_script
from marm_setup.report.viewer import inline_script, viewer_script
from marm_setup.robot.kinematics import forward_kinematics, link_index
from marm_setup.robot.load import load_robot
from tests.conftest import MARM_URDF, realworld2
from tests.helpers import urdf


@pytest.fixture(scope="module")
def marm():
    return load_robot(MARM_URDF, {}, [])


def _robot(tmp_path, body: str):
    path = tmp_path / "robot.urdf"
    path.write_text(urdf(body), encoding="utf-8")
    return load_robot(path, {}, [])


def _stl(path, mesh) -> str:
    path.write_bytes(mesh.export(file_type="stl"))
    return path.name


def test_primitives_keep_their_sizes_and_origins(tmp_path):
    robot = _robot(
        tmp_path,
        """
        <link name="a"><collision><origin xyz="0 0 0.5" rpy="0 0 1.5707963"/><geometry><box size="1 2 3"/></geometry></collision>
          <collision><geometry><cylinder radius="0.1" length="0.4"/></geometry></collision></link>
        <link name="b"><collision><geometry><sphere radius="0.2"/></geometry></collision></link>
        <link name="c"/>
        <joint name="j" type="revolute"><parent link="a"/><child link="b"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
        <joint name="k" type="fixed"><parent link="b"/><child link="c"/></joint>
        """,
    )
    geometry = robot_geometry(robot)
    assert [name for name, _ in geometry.links] == ["a", "b"]  # c has no geometry
    (box, cylinder), (sphere,) = (shapes for _, shapes in geometry.links)
    assert (box.kind, box.size, cylinder.kind, cylinder.size) == ("box", (1, 2, 3), "cylinder", (0.1, 0.4))
    assert (sphere.kind, sphere.size, geometry.meshes) == ("sphere", (0.2,), ())
    origin = np.array(box.origin).reshape(3, 4)
    assert np.allclose(origin[:, 3], [0, 0, 0.5]) and np.allclose(
        origin[:2, :2], [[0, -1], [1, 0]], atol=1e-6
    )


def test_a_mesh_used_by_two_links_is_sent_once_and_decimated_to_the_budget(tmp_path):
    import trimesh

    name = _stl(tmp_path / "ball.stl", trimesh.creation.icosphere(subdivisions=5))  # 20480 triangles
    robot = _robot(
        tmp_path,
        f"""
        <link name="a"><collision><geometry><mesh filename="{name}"/></geometry></collision></link>
        <link name="b"><collision><geometry><mesh filename="{name}"/></geometry></collision></link>
        <joint name="j" type="fixed"><parent link="a"/><child link="b"/></joint>
        """,
    )
    geometry = robot_geometry(robot, max_faces=2000)
    (mesh,) = geometry.meshes
    assert [shape.mesh for _, shapes in geometry.links for shape in shapes] == [0, 0]
    assert mesh.faces_before == 20480 and len(mesh.indices) <= 2000
    assert mesh.positions.dtype == np.float32 and mesh.indices.dtype == np.uint32
    assert np.allclose(np.linalg.norm(mesh.positions, axis=1), 1.0, atol=0.02)  # still the unit sphere
    assert mesh.indices.max() < len(mesh.positions)


def test_decimation_never_trades_a_links_surface_for_its_budget():
    """The Kinova Gen3's bicep (15,666 triangles) loses 80 % of its surface at fast-simplification's
    default aggressiveness, a hole in the arm: a gentler setting is taken instead."""
    import trimesh

    from marm_setup.robot.meshes import load_mesh

    stl = realworld2("ros2_kortex", "kortex_description", "arms", "gen3", "6dof", "meshes", "bicep_link.STL")
    data = load_mesh(str(stl))
    bicep = trimesh.Trimesh(np.asarray(data.vertices), np.asarray(data.faces), process=True)
    assert bicep.simplify_quadric_decimation(face_count=4000).area < 0.5 * bicep.area  # the trap
    reduced = _decimated(bicep, 4000)
    assert reduced.area >= AREA_KEPT * bicep.area and len(reduced.faces) < 0.4 * len(bicep.faces)


def test_link_frames_are_the_forward_kinematics(marm):
    links = ("base_link", "link3", "gripper_finger_link1")
    q = np.linspace(-0.5, 0.5, len(marm.active_joint_names))
    frames = link_frames(marm, q, links)
    poses = forward_kinematics(marm, q)[0]
    index = link_index(marm)
    assert frames.shape == (36,) and frames.dtype == np.float32
    for k, name in enumerate(links):
        assert np.allclose(frames[12 * k : 12 * k + 12].reshape(3, 4), poses[index[name]][:3], atol=1e-6)
    batch = link_frames(marm, np.stack([q, -q]), links)
    assert batch.shape == (2, 36) and np.allclose(batch[0], frames)


def test_states_carry_the_contacts_moveit_would_check(marm):
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.report.states import robot_states
    from marm_setup.setup.model import Group, GroupState
    from marm_setup.setup.srdf import Srdf

    scene = CollisionScene(marm)
    folded = (("joint2", 1.9), ("joint3", -2.5), ("joint4", -1.0), ("joint5", 2.6))
    srdf = Srdf(
        "marm", groups=(Group("arm", links=("link2",)),), group_states=(GroupState("folded", "arm", folded),)
    )
    q = np.array([dict(folded).get(n, 0.0) for n in marm.active_joint_names])
    touching = [p for p in scene.candidate_pairs if scene.first_collisions(q[None], [p])[0]]
    assert touching, "the folded arm touches itself"
    evidence = Evidence.of(touching[0], marm.active_joint_names, q)
    stale = Finding(
        "matrix.stale", "warning", "config/marm.srdf", "disable_collisions[x y]", "m", "", evidence
    )
    states = robot_states(srdf, marm, scene, {}, [Finding("a.b", "error", "f", "e", "m"), stale])
    assert [s.key for s in states] == ["default", "start", "pose:arm:folded", "finding:1"]
    pose = states[2]
    assert set(pose.contacts) == set(touching)  # nothing disabled: every touching pair counts
    assert states[3].contacts == (tuple(sorted(touching[0])),) and np.allclose(states[3].q, q)
    disabled = Srdf("marm", groups=srdf.groups, group_states=srdf.group_states, disabled=_disabled(touching))
    assert robot_states(disabled, marm, scene, {}, [])[2].contacts == ()


def _disabled(pairs):
    from marm_setup.collision.pairs import DisabledPair

    return tuple(sorted(DisabledPair.of(a, b, "User") for a, b in pairs))


def test_a_motion_sends_the_moving_links_only(marm):
    from marm_setup.plan.execution import ExecutionReport
    from marm_setup.plan.planner import PlanFound
    from marm_setup.plan.problem import Executed
    from marm_setup.plan.timing import JointLimits, time_parameterize
    from marm_setup.report.motions import motions
    from marm_setup.validate import PlannedPair

    names = ("joint5", "joint6")
    path = np.array([[0.0, 0.0], [1.0, -1.0]])
    limits = JointLimits(names, np.array([1.0, 1.0]), np.array([1.0, 1.0]))
    trajectory = time_parameterize(path, limits)
    outcome = Executed(PlanFound(names, path), trajectory, ExecutionReport((), 10, trajectory.duration))
    q_start = np.zeros(len(marm.active_joint_names))
    links = ("base_link", "link1", "link5", "link6")
    (motion,) = motions(marm, [PlannedPair("arm", "a", "b", q_start, outcome)], links)
    assert motion.moving == (2, 3) and motion.problem == ""  # link5 and link6 move
    frames = motion.frames.reshape(len(motion.times), 2, 12)
    assert len(motion.times) <= MAX_FRAMES and motion.times[-1] == pytest.approx(trajectory.duration)
    end = q_start.copy()
    end[[marm.active_joint_names.index(n) for n in names]] = path[-1]
    assert np.allclose(frames[-1].ravel(), link_frames(marm, end, links[2:]), atol=1e-5)
    assert np.allclose(motion.still, link_frames(marm, q_start, links), atol=1e-6)


def test_arrays_travel_as_little_endian_base64():
    import base64

    data = base64.b64decode(b64(np.array([1.5, -2.0]), "<f4"))
    assert np.frombuffer(data, "<f4").tolist() == [1.5, -2.0]


def test_the_pages_json_cannot_end_its_script_element():
    text = json_for_script({"name": "</script><script>alert(1)</script>", "x": "a & b"})
    assert "<" not in text and ">" not in text and "&" not in text
    assert json.loads(text) == {"name": "</script><script>alert(1)</script>", "x": "a & b"}


def test_the_viewer_script_is_meshcats_and_safe_to_inline():
    script = viewer_script()
    assert "MeshCat" in script and len(script) > 100_000 and "</script" not in script.lower()
    assert inline_script("a</SCRIPT>b</script") == "a<\\/SCRIPT>b<\\/script"


def test_the_page_names_no_url_to_fetch(tmp_path):
    """Everything is inline: no src/href/url() pointing anywhere (the browser test also blocks
    and counts every request that is not the file itself)."""
    from marm_setup.report.page import render_page

    html = render_page(
        {
            "robot": "r",
            "summary": {"package": "p", "validated": "v", "errors": 0, "warnings": 0},
            **{
                k: []
                for k in (
                    "links",
                    "groups",
                    "end_effectors",
                    "virtual_joints",
                    "states",
                    "motions",
                    "findings",
                )
            },
            "geometry": {"links": [], "meshes": []},
            "matrix": None,
        }
    )
    assert html.startswith("<!DOCTYPE html>") and html.count("<script") == 3
    assert not re.search(r"""(src|href)\s*=\s*["']?\s*(https?:|//)""", html, re.I)
    assert not re.search(r"""url\(\s*["']?\s*(https?:|//)""", html, re.I)
    assert not re.search(r"""@import""", html)

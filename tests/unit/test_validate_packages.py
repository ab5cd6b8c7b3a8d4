"""Good packages validate clean: marm from `init` (both targets) and the real panda packages."""

from __future__ import annotations

import pytest

from tests.validate_helpers import generate_marm, panda, validate_package


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_marm_packages_validate_clean(tmp_path, target):
    assert validate_package(generate_marm(tmp_path, target), plan=False) == []


def _summary(findings):
    return sorted((f.severity, f.rule, f.file, f.element) for f in findings)


def test_panda_ros1_findings_are_the_known_real_ones():
    good = panda("ros1")
    found = validate_package(good.path, package_paths=good.package_paths, plan=False)
    assert _summary(found) == [
        # the collision meshes of link5 and link7 overlap with joint6 at 0 (about 0.07 rad to clear)
        ("error", "pose.collision", "config/panda.srdf", "group_state[transport]"),
        # move_group.launch's default manager is the simple one, whose launch file loads
        # ros_controllers.yaml (no controller_list) and never simple_moveit_controllers.yaml:
        # roslaunch --dump-params has no /move_group/controller_list
        (
            "warning",
            "controller.list-not-loaded",
            "launch/simple_moveit_controller_manager.launch.xml",
            "moveit_controller_manager",
        ),
        # the snapshot left out non-XML launch assets that the Setup Assistant writes
        ("warning", "launch.missing-file", "launch/demo.launch", "line 60: arg[rviz_config]"),
        # not launch/move_group.launch's debug-only gdb_settings.gdb: the Setup Assistant never writes it,
        # and only `gdb -x` (not roslaunch) would read it, with debug:=true
    ]


def test_panda_ros2_findings_are_the_known_real_ones():
    good = panda("ros2")
    found = validate_package(good.path, package_paths=good.package_paths, plan=False)
    assert _summary(found) == [
        ("error", "pose.collision", "config/panda_arm_hand.srdf.xacro", "group_state[transport]"),
        # moveit_controllers.yaml drives the arm only; the hand needs gripper_moveit_controllers.yaml
        (
            "warning",
            "controller.uncovered-joint",
            "config/moveit_controllers.yaml",
            "moveit_simple_controller_manager.joint[panda_finger_joint1]",
        ),
        # the Setup Assistant's TrajOptDefault is of type geometric::TrajOpt, which MoveIt 2's OMPL
        # never registers: choosing it fails with "Unknown planner" (the default, RRTConnect, works)
        (
            "warning",
            "ompl.unknown-planner-type",
            "config/ompl_planning.yaml",
            "planner_configs.TrajOptDefault.type",
        ),
        # hand.xacro nests <passive_joint name="panda_finger_joint2"> in the hand group: srdfdom
        # ignores it there, harmless since that joint is a mimic joint MoveIt never plans for
        (
            "warning",
            "srdf.nested-passive-joint",
            "config/panda_arm_hand.srdf.xacro",
            "group[hand].passive_joint",
        ),
    ]


def test_validate_is_deterministic():
    good = panda("ros2")
    runs = [validate_package(good.path, package_paths=good.package_paths, plan=False) for _ in range(2)]
    assert runs[0] == runs[1]


def test_panda_transport_collision_is_confirmed_by_pinocchio():
    """The one panda error is real: pinocchio (own URDF parser, mesh loader and FK) agrees."""
    pin = pytest.importorskip("pinocchio")
    from marm_setup.package.read import read_package
    from marm_setup.validate.runner import load_package_robot

    good = panda("ros1")
    pkg = read_package(good.path, package_paths=good.package_paths)
    robot, _ = load_package_robot(pkg)
    xml = robot.urdf_xml.replace(
        "package://moveit_resources_panda_description/", f"{good.package_paths[0]}/panda_description/"
    )
    model = pin.buildModelFromXML(xml)
    geom = pin.buildGeomFromUrdfString(model, xml, pin.GeometryType.COLLISION)
    names = [g.name for g in geom.geometryObjects]
    geom.addCollisionPair(pin.CollisionPair(names.index("panda_link5_0"), names.index("panda_link7_0")))
    data, gdata = model.createData(), pin.GeometryData(geom)

    def collides(pose: str) -> bool:
        values = dict(next(s for s in pkg.srdf.group_states if s.name == pose).values)
        q = pin.neutral(model)
        for j in range(1, model.njoints):
            if model.names[j] in values:
                q[model.idx_qs[j]] = values[model.names[j]]
        return pin.computeCollisions(model, data, geom, gdata, q, True)

    assert collides("transport")
    assert not collides("ready")


def test_runtime_checks_run_unless_no_plan():
    """The planner's runtime rules come in through the seam; plan=False (--no-plan) skips them."""
    good = panda("ros1")
    with_plan = validate_package(good.path, package_paths=good.package_paths, plan=True)
    without = validate_package(good.path, package_paths=good.package_paths, plan=False)
    runtime = [f for f in with_plan if f.rule.startswith("runtime.")]
    assert [(f.rule, f.element) for f in runtime] == [("runtime.pose-skipped", "group_state[transport]")]
    assert set(with_plan) - set(runtime) == set(without)


def test_unreadable_collision_mesh_is_a_finding(tmp_path):
    import shutil

    from tests.conftest import FIXTURES

    description = shutil.copytree(FIXTURES / "marm", tmp_path / "marm_description")
    (description / "meshes" / "link6.stl").write_text("garbage")
    pkg = generate_marm(tmp_path, "ros1")
    urdf = description / "urdf" / "marm.urdf.xacro"
    found = validate_package(pkg, urdf=urdf, plan=False)
    assert [(f.rule, f.element) for f in found] == [
        ("urdf.collision-geometry", "link[link6]/collision[0]/mesh")
    ]
    assert "cannot read mesh" in found[0].message

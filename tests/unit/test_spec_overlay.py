"""What a SPEC replaces takes along what was inferred for it (inference/spec_overlay.py): a SPEC group
`manipulator` covering the inferred `arm` drops `arm` and everything inferred for it, in every
list, also in a list the SPEC gives; an inferred controller on a joint a SPEC controller commands
goes; what the SPEC leaves alone stays."""

from __future__ import annotations

from marm_setup.inference.assemble import apply_patch
from marm_setup.inference.infer import fit_to_spec, infer_setup
from marm_setup.inference.spec_overlay import patch_items, spec_items, without_replaced
from marm_setup.robot.load import load_robot
from marm_setup.setup.checks import check_setup
from marm_setup.setup.model import RobotSource
from marm_setup.setup.yaml_io import patch_from_dict
from tests.helpers import ARM, FINGERS, build_file_tree, fixed_link, urdf

ROBOT = ARM + fixed_link("l3", "hand", True) + fixed_link("hand", "hand_tcp") + FINGERS


def _overlay(tmp_path, spec: dict):
    """(inferred, result) of `spec` over the inferred setup, as init assembles it."""
    build_file_tree(tmp_path, {"r.urdf": urdf(ROBOT)})
    robot = load_robot(tmp_path / "r.urdf")
    inferred = infer_setup(robot, package_name="p", source=RobotSource("r.urdf")).model
    patch = patch_from_dict(spec)
    assert patch_items(patch) == spec_items(spec)
    merged = apply_patch(inferred, patch)
    model = fit_to_spec(without_replaced(inferred, merged, robot, patch_items(patch)), robot, patch.keys)
    check_setup(model, robot, "spec.yaml")
    return inferred, model


MANIPULATOR = {"name": "manipulator", "chain": {"base": "base", "tip": "hand_tcp"}}
CONTROLLERS = [
    {
        "name": "joint_trajectory_controller",
        "type": "FollowJointTrajectory",
        "action_ns": "follow_joint_trajectory",
        "joints": ["j1", "j2", "j3"],
        "group": "manipulator",
    },
    {
        "name": "gripper_action_controller",
        "type": "GripperCommand",
        "action_ns": "gripper_cmd",
        "joints": ["finger_joint_l"],
        "group": "hand",
    },
]


def test_the_inferred_arm_goes_with_its_controller_kinematics_poses_and_end_effector(tmp_path):
    spec = {
        "groups": [MANIPULATOR],
        "controllers": CONTROLLERS,
        "kinematics": [{"group": "manipulator", "timeout": 0.005}],
    }
    inferred, model = _overlay(tmp_path, spec)
    assert [g.name for g in inferred.groups] == ["arm", "hand"]
    assert [c.name for c in inferred.controllers] == ["arm_controller", "hand_controller"]
    assert [g.name for g in model.groups] == ["hand", "manipulator"]
    # the SPEC lists every controller: the inferred ones on its joints go, arm_controller with `arm`
    assert [c.name for c in model.controllers] == ["joint_trajectory_controller", "gripper_action_controller"]
    assert [(k.group, k.timeout) for k in model.kinematics] == [("manipulator", 0.005)]
    assert {s.group for s in model.group_states} == {"hand"}  # arm's home went, hand's stays
    assert [e.parent_group for e in model.end_effectors] == []  # the one on arm went
    assert [p.group for p in model.planners] == ["hand", "manipulator"]  # derived again


def test_a_group_redefined_under_its_own_name_loses_its_inferred_settings(tmp_path):
    shorter = {"name": "arm", "chain": {"base": "base", "tip": "l2"}}
    spec = {"groups": [shorter], "kinematics": [{"group": "hand", "solver": "pick_ik/PickIkPlugin"}]}
    inferred, model = _overlay(tmp_path, spec)
    assert [k.group for k in inferred.kinematics] == ["arm"]
    # the arm kinematics inferred for the chain to hand_tcp went; the SPEC's list is kept as given
    assert [k.group for k in model.kinematics] == ["hand"]
    # controllers were not given: derived again for the new arm (j1, j2)
    assert [(c.name, c.joints) for c in model.controllers] == [
        ("arm_controller", ("j1", "j2")),
        ("hand_controller", ("finger_joint_l",)),
    ]


def test_what_the_spec_leaves_alone_stays(tmp_path):
    spec = {"controllers": [{**CONTROLLERS[1], "name": "fingers"}]}
    inferred, model = _overlay(tmp_path, spec)
    assert model.groups == inferred.groups
    # the SPEC's gripper controller replaces the inferred one on the same joint, arm's stays
    assert [c.name for c in model.controllers] == ["arm_controller", "fingers"]
    assert model.kinematics == inferred.kinematics
    assert model.end_effectors == inferred.end_effectors


def test_spec_items_are_the_keys_of_the_lists_a_spec_gives():
    spec = {"groups": [MANIPULATOR], "controllers": CONTROLLERS, "kinematics": [{"group": "manipulator"}]}
    assert spec_items({**spec, "author": {"name": "me"}, "passive_joints": ["x"]}) == {
        "groups": frozenset({"manipulator"}),
        "controllers": frozenset({"joint_trajectory_controller", "gripper_action_controller"}),
        "kinematics": frozenset({"manipulator"}),
        "passive_joints": frozenset(),
    }

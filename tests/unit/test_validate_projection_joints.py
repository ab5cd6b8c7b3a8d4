"""`projection_evaluator: joints(...)` as MoveIt reads it (model_based_planning_context.cpp
getProjectionEvaluator, moveit2 l.166-231; noetic the same): a joint the group has
(JointModelGroup::hasJointModel: every joint of the group, mimic and fixed ones included) with
variables is projected on; a fixed one (0 DOF) is skipped with a warning; only a joint outside
the group is logged as an error. motoman_sda10f_moveit_config projects its torso group on
`joints(torso_joint_b1,torso_joint_b2)`, torso_joint_b2 a mimic of torso_joint_b1."""

from __future__ import annotations

from tests.validate_helpers import copy_package, panda, replace_text, run

OMPL = "config/ompl_planning.yaml"


def projection_findings(tmp_path, joints: str) -> list[tuple[str, str]]:
    good = panda("ros1")
    pkg = copy_package(good, tmp_path)
    replace_text(
        pkg,
        OMPL,
        "hand:\n  planner_configs:",
        f"hand:\n  projection_evaluator: joints({joints})\n  planner_configs:",
    )
    return [
        (str(f.severity), f.message)
        for f in run(pkg, good, matrix_trials=0)
        if f.rule == "ompl.projection-invalid"
    ]


def test_a_mimic_joint_of_the_group_is_projected_on(tmp_path):
    assert projection_findings(tmp_path, "panda_finger_joint1,panda_finger_joint2") == []


def test_a_fixed_joint_of_the_group_is_skipped(tmp_path):
    [(severity, message)] = projection_findings(tmp_path, "panda_finger_joint1,panda_hand_joint")
    assert severity == "warning" and "'panda_hand_joint' (a fixed joint, 0 DOF)" in message


def test_a_joint_outside_the_group_is_still_reported(tmp_path):
    [(severity, message)] = projection_findings(tmp_path, "panda_finger_joint1,panda_joint1")
    assert severity == "warning" and "'panda_joint1' (not a joint of the group)" in message

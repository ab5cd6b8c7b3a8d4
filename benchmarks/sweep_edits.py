"""Realistic one-line edits of a generated ROS 2 package, each of which crashes or silently
disables move_group, the controller manager (or one of its controllers) or Servo: does
`validate` (no ROS installed) catch each one (exit 1)? Prints one line per edit and the count missed.

Run: .venv/bin/python benchmarks/sweep_edits.py
(Run it from an older checkout's folder to measure that version: the CLI is `python -m
marm_setup.cli.app` in the current folder.)
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARM = ROOT / "fixtures" / "marm" / "urdf" / "marm.urdf.xacro"
CLI = [sys.executable, "-m", "marm_setup.cli.app"]
MOVEIT, SERVO, DEMO = "config/moveit.yaml", "config/arm_servo.yaml", "launch/demo.launch.xml"
CONTROLLERS = "config/ros2_controllers.yaml"
GRIPPER = "action_ns: gripper_cmd\n"

# (distro, file, old, new, what MoveIt does)
EDITS = (
    ("jazzy", MOVEIT, "allowed_execution_duration_scaling: 1.2", "allowed_execution_duration_scaling: 2",
     "move_group dies at start-up (an integer for a declared double)"),
    ("humble", MOVEIT, "allowed_goal_duration_margin: 0.5", "allowed_goal_duration_margin: 1",
     "move_group dies at start-up (an integer for a double)"),
    ("jazzy", MOVEIT, GRIPPER, GRIPPER + "        max_effort: 10\n",
     "the simple controller manager drops the gripper controller"),
    ("humble", SERVO, "publish_period: 0.034", "publish_period: 1", "servo_node dies at start-up"),
    ("humble", SERVO, "incoming_command_timeout: 0.1", "incoming_command_timeout: 1", "servo_node dies at start-up"),
    ("jazzy", MOVEIT, "kinematics_solver_timeout: 0.05", "kinematics_solver_timeout: 1",
     "move_group dies at start-up (kinematics_parameters)"),
    ("jazzy", MOVEIT, "ompl_interface/OMPLPlanner", "ompl_interface/OMPLPlaner", "the OMPL pipeline fails to load"),
    ("humble", MOVEIT, "ompl_interface/OMPLPlanner", "ompl_interface/OMPLPlaner", "the OMPL pipeline fails to load"),
    ("jazzy", MOVEIT, "ValidateWorkspaceBounds", "ValidateWorkspaceBound", "the pipeline's adapter fails to load"),
    ("jazzy", MOVEIT, "kdl_kinematics_plugin/KDLKinematicsPlugin", "kdl_kinematics_plugin/KDLKinematicPlugin",
     "the arm has no IK solver"),
    ("jazzy", MOVEIT, "MoveItSimpleControllerManager", "MoveItSimpleControlerManager",
     "move_group cannot execute anything"),
    ("jazzy", DEMO, "config/moveit.yaml", "config/moveit_config.yaml",
     "move_group starts without pipelines, kinematics or controllers"),
    ("humble", MOVEIT, "allowed_start_tolerance: 0.01", "allowed_start_tolerance: 0",
     "move_group dies at start-up (an integer for a double)"),
    ("jazzy", MOVEIT, "publish_robot_description_semantic: true", "publish_robot_description_semantic: 1",
     "move_group dies at start-up (declared a bool)"),
    ("jazzy", MOVEIT, "      - pilz_industrial_motion_planner\n", "      - pilz_industrial_motion_planner\n      - chomp\n",
     "move_group dies at start-up ('Planning plugin name is empty')"),
    ("humble", CONTROLLERS, "update_rate: 100", "update_rate: 100.0", "ros2_control_node dies at start-up"),
    ("jazzy", CONTROLLERS, "allow_nonzero_velocity_at_trajectory_end: true",
     "allow_nonzero_velocity_at_trajectory_end: 1", "the arm controller does not load: nothing executes"),
    ("jazzy", CONTROLLERS, "    command_interfaces:\n      - position", "    command_interfaces:\n      - effort",
     "the arm controller never activates (mock hardware offers position only)"),
    ("humble", MOVEIT, "          max_velocity: 1.0\n", "          max_velocity: 1\n",
     "move_group drops the joint's limits (an integer where robot_model_loader reads a double)"),
)  # fmt: skip


def generate(out: Path, distro: str) -> Path:
    pkg = out / distro / "marm_moveit_config"
    args = [*CLI, "init", str(MARM), "--out", str(pkg), "--target", "ros2", "--ros-distro", distro]
    subprocess.run([*args, "--trials", "200"], check=True, capture_output=True)
    return pkg


def caught(fresh: Path, scratch: Path, rel: str, old: str, new: str) -> tuple[int, str]:
    shutil.rmtree(scratch, ignore_errors=True)
    shutil.copytree(fresh, scratch)
    text = (scratch / rel).read_text(encoding="utf-8")
    if old not in text:
        return -1, f"'{old}' not in {rel}"
    (scratch / rel).write_text(text.replace(old, new, 1), encoding="utf-8")
    done = subprocess.run(
        [*CLI, "validate", str(scratch), "--no-plan"], capture_output=True, text=True, check=False
    )
    rules = sorted({w.strip("[]") for w in done.stdout.split() if w.startswith("[") and "." in w})
    return done.returncode, ", ".join(rules)


def main() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        fresh = {d: generate(out, d) for d in sorted({e[0] for e in EDITS})}
        missed = 0
        for distro, rel, old, new, effect in EDITS:
            code, rules = caught(fresh[distro], out / "edit" / "marm_moveit_config", rel, old, new)
            missed += code != 1
            mark = "caught" if code == 1 else "MISSED"
            print(
                f"{mark:6} {distro:6} {rel:22} {old.strip()[:34]:34} -> {new.strip()[-30:]:30} exit {code} [{rules}]"
            )
            print(f"       ({effect})")
        print(f"{len(EDITS)} edits, {len(EDITS) - missed} caught, {missed} missed")


if __name__ == "__main__":
    main()

"""Rendering a config package: the per-template context, the whole package in memory, and the
atomic writer with its edit-guarding manifest.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "context": "build_context ros2_control_joints",
    "package": "description_package render_package robot_reference SETUP_FILE",
    "writer": (
        "apply_writes check_output_dir conflicts FileChange format_change plan_writes stale_files "
        "STATUS_WORDS write_text_atomic"
    ),
    "hardware": "description_hardware hardware_lines",
    "commit_record": "COMMIT read_commit",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.render.commit_record import COMMIT as COMMIT
    from marm_setup.render.commit_record import read_commit as read_commit
    from marm_setup.render.context import build_context as build_context
    from marm_setup.render.context import ros2_control_joints as ros2_control_joints
    from marm_setup.render.hardware import description_hardware as description_hardware
    from marm_setup.render.hardware import hardware_lines as hardware_lines
    from marm_setup.render.package import SETUP_FILE as SETUP_FILE
    from marm_setup.render.package import description_package as description_package
    from marm_setup.render.package import render_package as render_package
    from marm_setup.render.package import robot_reference as robot_reference
    from marm_setup.render.writer import STATUS_WORDS as STATUS_WORDS
    from marm_setup.render.writer import FileChange as FileChange
    from marm_setup.render.writer import apply_writes as apply_writes
    from marm_setup.render.writer import check_output_dir as check_output_dir
    from marm_setup.render.writer import conflicts as conflicts
    from marm_setup.render.writer import format_change as format_change
    from marm_setup.render.writer import plan_writes as plan_writes
    from marm_setup.render.writer import stale_files as stale_files
    from marm_setup.render.writer import write_text_atomic as write_text_atomic

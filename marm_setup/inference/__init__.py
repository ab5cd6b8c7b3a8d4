"""Inference from a robot: a setup for `init` from any kinematic tree (its limbs, where each
ends, groups, controllers, end effectors), collision-free named poses, and a SPEC laid over what
was inferred (`assemble`).

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "assemble": "apply_patch checked COMMAND_LINE_KEYS with_spec",
    "infer": (
        "derive_group_settings describe_setup fill_group_settings fit_to_spec home_poses infer_setup "
        "Inference REFERENCE"
    ),
    "poses": "choose_start_poses infer_poses",
    "spec_overlay": "patch_items spec_items without_replaced",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.inference.assemble import COMMAND_LINE_KEYS as COMMAND_LINE_KEYS
    from marm_setup.inference.assemble import apply_patch as apply_patch
    from marm_setup.inference.assemble import checked as checked
    from marm_setup.inference.assemble import with_spec as with_spec
    from marm_setup.inference.infer import REFERENCE as REFERENCE
    from marm_setup.inference.infer import Inference as Inference
    from marm_setup.inference.infer import derive_group_settings as derive_group_settings
    from marm_setup.inference.infer import describe_setup as describe_setup
    from marm_setup.inference.infer import fill_group_settings as fill_group_settings
    from marm_setup.inference.infer import fit_to_spec as fit_to_spec
    from marm_setup.inference.infer import home_poses as home_poses
    from marm_setup.inference.infer import infer_setup as infer_setup
    from marm_setup.inference.poses import choose_start_poses as choose_start_poses
    from marm_setup.inference.poses import infer_poses as infer_poses
    from marm_setup.inference.spec_overlay import patch_items as patch_items
    from marm_setup.inference.spec_overlay import spec_items as spec_items
    from marm_setup.inference.spec_overlay import without_replaced as without_replaced

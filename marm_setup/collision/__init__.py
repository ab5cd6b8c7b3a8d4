"""Self-collision: link pairs and their reasons, the coal collision scene, MoveIt's collision
matrix, SRDF updates, the matrix's summary and heat map.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "pairs": "DisabledPair DisabledReason link_pair PROVE_MODES UnprovedPair",
    "results": "CollisionMatrix PairProof ROUND",
    "cached_proof": "CachedProof",
    "proof_cache": "cache_dir known_proofs remember_proofs",
    "cached_matrix": "compute_cached_matrix",
    "proof_keys": "pair_keys run_context",
    "proof_summary": "proof_key unproved_notes unproved_pairs",
    "scene": "CollisionScene",
    "matrix": "compute_collision_matrix Progress trial_samples",
    "srdf_update": "load_srdf_text read_srdf_entries render_minimal_srdf update_srdf",
    "matrix_summary": "describe_matrix format_summary",
    "matrix_heat_map": "render_matrix_html render_matrix_svg",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.collision.cached_matrix import compute_cached_matrix as compute_cached_matrix
    from marm_setup.collision.cached_proof import CachedProof as CachedProof
    from marm_setup.collision.matrix import Progress as Progress
    from marm_setup.collision.matrix import compute_collision_matrix as compute_collision_matrix
    from marm_setup.collision.matrix import trial_samples as trial_samples
    from marm_setup.collision.matrix_heat_map import render_matrix_html as render_matrix_html
    from marm_setup.collision.matrix_heat_map import render_matrix_svg as render_matrix_svg
    from marm_setup.collision.matrix_summary import describe_matrix as describe_matrix
    from marm_setup.collision.matrix_summary import format_summary as format_summary
    from marm_setup.collision.pairs import PROVE_MODES as PROVE_MODES
    from marm_setup.collision.pairs import DisabledPair as DisabledPair
    from marm_setup.collision.pairs import DisabledReason as DisabledReason
    from marm_setup.collision.pairs import UnprovedPair as UnprovedPair
    from marm_setup.collision.pairs import link_pair as link_pair
    from marm_setup.collision.proof_cache import cache_dir as cache_dir
    from marm_setup.collision.proof_cache import known_proofs as known_proofs
    from marm_setup.collision.proof_cache import remember_proofs as remember_proofs
    from marm_setup.collision.proof_keys import pair_keys as pair_keys
    from marm_setup.collision.proof_keys import run_context as run_context
    from marm_setup.collision.proof_summary import proof_key as proof_key
    from marm_setup.collision.proof_summary import unproved_notes as unproved_notes
    from marm_setup.collision.proof_summary import unproved_pairs as unproved_pairs
    from marm_setup.collision.results import ROUND as ROUND
    from marm_setup.collision.results import CollisionMatrix as CollisionMatrix
    from marm_setup.collision.results import PairProof as PairProof
    from marm_setup.collision.scene import CollisionScene as CollisionScene
    from marm_setup.collision.srdf_update import load_srdf_text as load_srdf_text
    from marm_setup.collision.srdf_update import read_srdf_entries as read_srdf_entries
    from marm_setup.collision.srdf_update import render_minimal_srdf as render_minimal_srdf
    from marm_setup.collision.srdf_update import update_srdf as update_srdf

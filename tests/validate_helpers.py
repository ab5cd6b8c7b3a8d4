"""Good packages to break for validate tests: the shared panda packages and marm from `init`."""

from __future__ import annotations

import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import yaml

from marm_setup.findings import Finding
from marm_setup.validate.runner import validate
from tests.conftest import MARM_URDF, realworld


def validate_package(path: Path, **options) -> list[Finding]:
    """Every finding `validate` reports for the package at `path`, sorted by file then element."""
    return list(validate(path, **options).findings)


@dataclass(frozen=True)
class Good:
    """A package known to be good, and the package paths it needs."""

    path: Path
    package_paths: tuple[Path, ...] = ()


def panda(target: str) -> Good:
    return Good(realworld(target, "panda_moveit_config"), (realworld(target),))


def generate_marm(out_root: Path, target: str) -> Path:
    """`marm-setup init` the marm fixture into out_root/marm_<target> (ros1 with the ArbotiX driver):
    what that init leaves, the package and its proofs in the proof cache, without running it
    each time (_built_marm)."""
    out = out_root / f"marm_{target}"
    if not out.exists():
        spec = out_root / "driver.yaml"
        spec.write_text("driver: arbotix\n", encoding="utf-8")
        if len(out.parts) < 5 or _TMP not in out.parents:  # no folder like it to build in
            _init_marm(out, target, spec)
            return out
        built, cache = _built_marm(target, len(out.parts))
        shutil.copytree(built, out, symlinks=True)
        _add_proofs(cache)
    return out


# (target, depth of the package folder) -> (the package init wrote, the proof cache it filled),
# made once per process: init's output depends on neither the folder nor the cache it finds (its
# setup's relative package path on the folder's depth only, as the package is under /tmp and the
# fixtures are not).
_BUILT: dict[tuple[str, int], tuple[Path, Path]] = {}
_TMP = Path(tempfile.gettempdir())


def _built_marm(target: str, depth: int) -> tuple[Path, Path]:
    if (target, depth) not in _BUILT:
        import atexit

        import pytest

        root = Path(tempfile.mkdtemp(prefix="marm-built-"))
        atexit.register(shutil.rmtree, root, ignore_errors=True)
        out = root.joinpath(*["d"] * (depth - len(root.parts) - 1), f"marm_{target}")
        spec = root / "driver.yaml"
        spec.write_text("driver: arbotix\n", encoding="utf-8")
        with pytest.MonkeyPatch.context() as patch:
            patch.setenv("MARM_SETUP_CACHE", str(root / "proof-cache"))
            _init_marm(out, target, spec)
        assert len(out.parts) == depth
        _BUILT[target, depth] = out, root / "proof-cache"
    return _BUILT[target, depth]


def _init_marm(out: Path, target: str, spec: Path) -> None:
    from typer.testing import CliRunner

    from marm_setup.cli.app import app

    args = ["init", str(MARM_URDF), "--out", str(out), "--target", target, "--setup", str(spec)]
    result = CliRunner().invoke(app, args)
    assert result.exit_code == 0, result.output


def _add_proofs(cache: Path) -> None:
    """Put the proofs of the proof cache in `cache` into the one in use (as init would have)."""
    import sqlite3
    from contextlib import closing

    from marm_setup.collision.proof_cache import FILE, cache_dir

    folder = cache_dir()
    if folder is None or not (cache / FILE).is_file():
        return
    folder.mkdir(parents=True, exist_ok=True)
    if not (folder / FILE).exists():
        shutil.copyfile(cache / FILE, folder / FILE)
        return
    with closing(sqlite3.connect(folder / FILE, timeout=10.0)) as db, db:
        db.execute("ATTACH DATABASE ? AS built", (str(cache / FILE),))
        db.execute("INSERT OR REPLACE INTO proofs (key, value) SELECT key, value FROM built.proofs")


def copy_package(good: Good, dest_root: Path) -> Path:
    """A copy of the package at dest_root/<folder name> (same depth keeps relative URDF paths)."""
    dest = dest_root / good.path.name
    shutil.copytree(good.path, dest)
    return dest


def replace_text(pkg: Path, rel: str, old: str, new: str) -> None:
    """Replace the first `old` in pkg/rel (which must contain it)."""
    file = pkg / rel
    text = file.read_text(encoding="utf-8")
    assert old in text, f"{old!r} not in {rel}"
    file.write_text(text.replace(old, new, 1), encoding="utf-8")


def edit_yaml(pkg: Path, rel: str, edit) -> None:
    """Load pkg/rel, let `edit(data)` change it in place, write it back."""
    file = pkg / rel
    data = yaml.safe_load(file.read_text(encoding="utf-8"))
    edit(data)
    file.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")


def run(pkg: Path, good: Good, **kwargs) -> list[Finding]:
    return validate_package(pkg, package_paths=good.package_paths, plan=False, **kwargs)


def errors(findings: list[Finding]) -> set[tuple[str, str]]:
    """(rule, element) of every error."""
    return {(f.rule, f.element) for f in findings if f.is_error}


def rules(findings: list[Finding], severity: str | None = None) -> set[str]:
    return {f.rule for f in findings if severity is None or f.severity == severity}


def vouching_package(root: Path, marm) -> tuple[Path, tuple[str, str]]:
    """The marm package with its most often colliding enabled pair disabled as Never, and a
    marm_setup.yaml that vouches for it: listed as proved under a proof key recomputed with the
    public API, `trials: 0`, and another seed."""
    import numpy as np

    from marm_setup.collision import CollisionScene, proof_key, trial_samples
    from marm_setup.robot import robot_fingerprint
    from marm_setup.setup.srdf import allowed_pairs, read_srdf

    pkg = generate_marm(root, "ros1")
    srdf_file = pkg / "config" / "marm.srdf"
    scene = CollisionScene(marm)
    checked = scene.enabled_pairs(allowed_pairs(read_srdf(srdf_file), scene.candidate_pairs))
    q = trial_samples(marm, 0, 1000)
    counts = scene.collision_counts(scene.link_poses(q), scene.pair_ids(checked))
    assert counts.max() >= 50, "the pair collides often"
    a, b = checked[int(np.argmax(counts))]
    text = srdf_file.read_text(encoding="utf-8")
    srdf_file.write_text(
        text.replace("</robot>", f'  <disable_collisions link1="{a}" link2="{b}" reason="Never"/>\n</robot>'),
        encoding="utf-8",
    )
    setup_file = pkg / "marm_setup.yaml"
    data = yaml.safe_load(setup_file.read_text(encoding="utf-8"))
    collision = data["collision"]
    collision["disabled"].append({"link1": a, "link2": b, "reason": "Never"})
    collision.update(trials=0, seed=12345, unproved=[])
    never = [(d["link1"], d["link2"]) for d in collision["disabled"] if d["reason"] == "Never"]
    collision["proof_key"] = proof_key(robot_fingerprint(marm), collision["prove"], never, [])
    setup_file.write_text(yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    return pkg, (a, b)

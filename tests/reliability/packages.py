"""The setup edit that makes the next `render` of the marm package (the `pkg` fixture of
conftest.py) write."""

from __future__ import annotations

from pathlib import Path


def edit_setup(pkg: Path, value: str = "0.3") -> None:
    """Set marm_setup.yaml's default_velocity_scaling to `value` (the SPEC's is 0.1)."""
    setup = pkg / "marm_setup.yaml"
    text = setup.read_text()
    old = next(v for v in ("0.1", "0.3", "0.4") if f"default_velocity_scaling: {v}" in text)
    setup.write_text(text.replace(f"default_velocity_scaling: {old}", f"default_velocity_scaling: {value}"))

"""ompl_planning.yaml: groups exist, referenced planner configs exist, default planner config exists."""

from __future__ import annotations

from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error

if TYPE_CHECKING:
    from marm_setup.setup.srdf import Srdf
    from marm_setup.validate.discovery import ConfigSection

GLOBAL_KEYS = frozenset(
    {
        "planner_configs",
        "planning_plugin",
        "planning_plugins",
        "request_adapters",
        "response_adapters",
        "start_state_max_bounds_error",
        "jiggle_fraction",
        "max_sampling_attempts",
    }
)


def check_ompl(section: ConfigSection, srdf: Srdf) -> list[Finding]:
    """Every rule on an OMPL section (`{planner_configs: {...}, <group>: {...}}`)."""
    data = section.data
    if not isinstance(data, dict):
        return [error("ompl.malformed", section.file, section.element(), "expected a mapping")]
    configs = data.get("planner_configs") or {}
    if not isinstance(configs, dict):
        return [
            error("ompl.malformed", section.file, section.element("planner_configs"), "expected a mapping")
        ]
    groups = {g.name for g in srdf.groups}
    out: list[Finding] = []
    for key in sorted(k for k in data if k not in GLOBAL_KEYS and isinstance(data[k], dict)):
        where = section.element(key)
        if key not in groups:
            known = ", ".join(sorted(groups)) or "none"
            out.append(
                error("ompl.unknown-group", section.file, where, f"unknown group '{key}' (groups: {known})")
            )
            continue
        out += _check_group(section, where, data[key], configs)
    return out


def _check_group(section: ConfigSection, where: str, entry: dict, configs: dict) -> list[Finding]:
    out: list[Finding] = []
    listed = entry.get("planner_configs") or []
    if not isinstance(listed, list):
        listed = []
        out.append(error("ompl.malformed", section.file, f"{where}.planner_configs", "expected a list"))
    for name in map(str, listed):
        if name not in configs:
            msg = f"planner config '{name}' is not defined under planner_configs"
            out.append(error("ompl.unknown-planner-config", section.file, f"{where}.planner_configs", msg))
    default = entry.get("default_planner_config")
    if default is not None and str(default) not in configs:
        msg = f"default_planner_config '{default}' is not defined under planner_configs"
        hint = "known: " + ", ".join(sorted(map(str, configs))[:8]) if configs else ""
        out.append(
            error("ompl.unknown-default-planner", section.file, f"{where}.default_planner_config", msg, hint)
        )
    return out

"""pluginlib description files as plugin rows: each `<class>`'s lookup name (its `name`, else
its `type`, as pluginlib's ClassLoader reads it), kind by base class, and line."""

from __future__ import annotations

import re

from lxml import etree

# base_class_type -> the kind a parameter names (Humble's adapters derive from
# planning_request_adapter::PlanningRequestAdapter, Jazzy's from planning_interface::)
KINDS = {
    "planning_interface::PlannerManager": "planner",
    "planning_request_adapter::PlanningRequestAdapter": "request_adapter",
    "planning_interface::PlanningRequestAdapter": "request_adapter",
    "planning_interface::PlanningResponseAdapter": "response_adapter",
    "kinematics::KinematicsBase": "kinematics",
    "moveit_controller_manager::MoveItControllerManager": "controller_manager",
    "occupancy_map_monitor::OccupancyMapUpdater": "octomap_updater",
    "move_group::MoveGroupCapability": "capability",
    "online_signal_smoothing::SmoothingBaseClass": "smoothing_filter",
}


def plugin_rows(text: str, path: str) -> list[tuple[str, dict]]:
    """(kind, {class, source}) of every class of a kind the tables know."""
    body = re.sub(r"<\?xml[^>]*\?>", "", text)  # the wrapper below allows several <library> roots
    root = etree.fromstring(f"<root>{body}</root>".encode(), etree.XMLParser(recover=True))
    out = []
    for element in root.iter("class"):
        kind = KINDS.get(str(element.get("base_class_type", "")).strip())
        name = element.get("name") or element.get("type")
        if kind and name:
            out.append((kind, {"class": name.strip(), "source": f"{path}:{element.sourceline}"}))
    return out
